"""Reductions by the symmetry $SO(n-1)$: invariant polynomials and the reduced fields.

``invariants_n4`` and ``reduced_n4``: $n = 4$, the $SO(3)$ invariants $A, B, E, G, F_1, \\delta$
and the 7-dimensional reduced field of Section 5. ``invariants_n5`` and ``reduced_n5``: $n = 5$,
the ten $SO(4)$ invariants with their two relations and the 8-dimensional reduced field (row
S6:reduced-n5, beyond the paper). A further $n$ adds its own pair of modules.
"""
