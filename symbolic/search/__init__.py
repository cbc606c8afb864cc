"""Exact searches: the linear space of solutions of a linear condition on the field $X$, box by box.

The first-integral search (``integral_search``, row S6:first-integrals): unknowns from
``candidate_basis``, the field at seeded points modulo primes from ``sampled_field``, the algebra
of known integrals from ``known_integrals``, an exact sandwich rank$_p$(known) $\\le \\dim_\\mathbb{Q}
\\le$ nullity$_p$, rational reconstruction and proof over $\\mathbb{Q}$ in ``reconstruction``, the
integral it found in ``found_integral``, and the command line ``chaplygin first-integrals`` in
``command``.
"""
