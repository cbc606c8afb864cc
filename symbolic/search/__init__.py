"""Exact searches: the linear space of solutions of a linear condition on the field $X$, box by box.

One shape for every search (``box_search``): a base class ``BoxSearch`` owns the loop over boxes,
the exact sandwich rank$_p$(known) $\\le \\dim_\\mathbb{Q} \\le$ nullity$_p$ and the lifting of a kernel
to $\\mathbb{Q}$; a strategy overrides the ansatz, the linear conditions and the known solutions.
The linear algebra mod $p$ goes through one back end (``backend``: FLINT ``nmod_mat`` by default;
a second back end is one file, e.g. ``backend_numpy``). Row builders shared by the strategies and
reconstruction: ``conditions``. What a box costs before it runs: ``cost``; several primes per box,
mapped over processes or Dask: ``multimodular``; from one $(a, b)$ to generic ones: ``genericity``.

The first-integral search (row S6:first-integrals) has two strategies (``strategies`` picks one):
the SO(n-1)-invariant ring (``invariant_search``; the rings in ``invariant_rings``, those of
$n \\ge 6$ from ``orthogonal_invariants``) and the weight-zero monomials of a maximal torus
(``integral_search``, unknowns from ``candidate_basis``). Shared: the field at seeded points
modulo primes (``sampled_field``), the algebra of known integrals (``known_integrals``), rational
reconstruction and proof over $\\mathbb{Q}$ (``reconstruction``), the integral it found
(``found_integral``) and the command line ``chaplygin first-integrals`` (``command``).
"""
