"""First integrals beyond the paper: the family $H_k$, the sixth integral of $n = 5$, and what they give.

``wedge_integrals``: $H_k = \\langle M^{\\wedge k}, (2 + D_B)^{-1} M^{\\wedge k}\\rangle$ (row
S6:wedge-integrals) at exact points; ``wedge_proof``: the identities of its proof for every $n$;
``independence``, ``independence_all_n``, ``exceptional_b``: the rank of the known integrals and the $H_k$
at a point, its argument for every $n$, and the exceptional $b$ of that argument (row S6:wedge-independence); ``wedge_n6``: $H_2$ for $n = 6$ as a
symbolic identity in $a, b$; ``sixth_integral``: the integral $F$ of $n = 5$ (row S6:sixth-integral-n5);
``euler_jacobi_n5``: the hypotheses of Euler–Jacobi on the $n = 5$ quotient (row S6:euler-jacobi-n5).
"""
