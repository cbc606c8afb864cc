"""First integrals beyond the paper: the family $H_k$ and the sixth integral of $n = 5$.

``wedge_integrals``: $H_k = \\langle M^{\\wedge k}, (2 + D_B)^{-1} M^{\\wedge k}\\rangle$ (row
S6:wedge-integrals) at exact points; ``wedge_n6``: $H_2$ for $n = 6$ as a symbolic identity in
$a, b$; ``sixth_integral``: the integral $F$ of $n = 5$ (row S6:sixth-integral-n5).
"""
