r"""Mutants argued equivalent: no check can tell them apart although a value differs, with the
reason they are equivalent anyway (:data:`ARGUED`; applied by :func:`argued` to a survivor only)."""

from __future__ import annotations

#: Mutants no check can tell apart although their outputs differ in the last bits, with the
#: argument that they are equivalent: ``(function, mutation) -> reason``. Applied only to a mutant
#: that survived every row and test reaching it (the outcome becomes ``equivalent``, the reason
#: says "argued"). The mutation text names the line: a change of the function renews the review.
ARGUED: dict[tuple[str, str], str] = {
    ("search.invariant_rings.ring_for", "const: line 160 col 96: 0 -> 1"):
        "the SO(3) ring (n = 4) then splits by the reflections g_2 and g_4 instead of g_1 and g_4: "
        "g_1 g_2 = diag(-1, -1, 1, 1) lies in the group SO(3) acting on the first three "
        "coordinates, so g_2 acts on every SO(3)-invariant (the generators, x and the known "
        "integrals) exactly as g_1 does; the characters, the blocks, the projected known products "
        "and every rank are the same",
    ("search.invariant_rings.ring_for", "const: line 165 col 37: 0 -> 1"):
        "the SO(4) ring (n = 5) then splits by the reflections g_2 and g_5 instead of g_1 and g_5: "
        "g_1 g_2 = diag(-1, -1, 1, 1, 1) lies in the group SO(4) acting on the first four "
        "coordinates, so g_2 acts on every SO(4)-invariant exactly as g_1 does; the characters, "
        "the blocks, the projected known products and every rank are the same",
    ("runtime.axisym.angular_velocity", "const: line 88 col 34: 3 -> 4"):
        "n = 3 then takes the documented method='matrix' path (inverse_coefficients + the six "
        "terms, valid for any n >= 3) instead of the n = 3 component kernel: both evaluate the "
        "same derived L_gamma^{-1}(M) (P:inversion), in a different order of floating-point "
        "operations; the branch is a speed choice",
    ("runtime.axisym.p_coefficients", "const: line 172 col 13: 3 -> 4"):
        "n = 3 then takes the documented any-n path (batched eigenvalues, p affine in sigma) "
        "instead of the n = 3 expanded-determinant kernel: both compute the coefficients of "
        "det(M + sigma gamma gamma^T - lambda Id) (eq:pol-first-integrals), rounded differently; "
        "the branch is a speed choice",
    ("runtime.compiled.angular_velocity_function", "const: line 43 col 52: 53 -> 54"):
        "HeyokaArithmetic reads its bits only for kind 'real'; for 'double' (here) they are unused",
    **{("runtime.compiled.angular_velocity_function", mutation):
       "renames the cfunc's variables (M<i>_<j>, gamma<i>) by another one-to-one map: the names "
       "stay pairwise distinct and a cfunc takes its inputs by position in the list of variables "
       "it is given (m + gamma), so the compiled function is the same map"
       for mutation in ("sign: line 45 col 35: i + 1 -> i - 1", "sign: line 45 col 43: j + 1 -> j - 1",
                        "sign: line 46 col 43: i + 1 -> i - 1", "const: line 45 col 39: 1 -> 2",
                        "const: line 45 col 47: 1 -> 2", "const: line 46 col 47: 1 -> 2")},
    **{("runtime.expressions.angular_velocity", mutation):
       "the two factors of one product of heyoka expressions exchanged: the expression text differs "
       "(the bit-for-bit comparison compares text), but IEEE multiplication is commutative, so the "
       "compiled code returns the same bits"
       for mutation in ("swap: line 98 col 21: _mul(u[i], v[j]) -> _mul(v[j], u[i])",
                        "swap: line 98 col 44: _mul(v[i], u[j]) -> _mul(u[j], v[i])",
                        "swap: line 102 col 39: _mul(c[1], wedge(Mg, gamma, i, j)) -> "
                        "_mul(wedge(Mg, gamma, i, j), c[1])",
                        "swap: line 103 col 18: _mul(c[2], wedge(Me, e, i, j)) -> "
                        "_mul(wedge(Me, e, i, j), c[2])",
                        "swap: line 103 col 50: _mul(c[3], wedge(Mg, e, i, j)) -> "
                        "_mul(wedge(Mg, e, i, j), c[3])",
                        "swap: line 104 col 18: _mul(c[4], wedge(Me, gamma, i, j)) -> "
                        "_mul(wedge(Me, gamma, i, j), c[4])")},
    ("runtime.expressions.structured_field", "swap: line 139 col 18: _mul(ui, Vi[k]) -> "
                                             "_mul(Vi[k], ui)"):
        "the two factors of one product of heyoka expressions exchanged: the expression text "
        "differs, but IEEE multiplication is commutative, so the compiled code returns the same bits",
    **{("search.reconstruction.real_columns", mutation):
       "scales one element of the real basis by 2: the mod-p matrix (_real_matrix) and the "
       "expression (to_expression) both read the coefficient, so the kernel vector's entry halves "
       "and the reconstructed integral is the same polynomial; the basis stays real, non-zero and "
       "independent (tests/test_first_integrals.py::test_real_columns_are_a_real_basis_of_each_block)"
       for mutation in ("const: line 80 col 24: 1 -> 2", "const: line 80 col 51: 1 -> 2")},
    ("search.reconstruction.real_columns", "const: line 80 col 54: 1 -> 2"):
        "the power of i is read only as a truth value (_real_matrix: i_p if ipow else 1; "
        "to_expression: u[0] if not ipow else -u[1]), so 2 acts as 1",
    **{("search.sampled_field.sample", mutation):
       "another seeded draw of the same points: the mutant changes how many candidates a round "
       "draws (line 232) or draws t and M from 1..p-1 instead of 0..p-1 (lines 233, 238); it "
       "still returns `count` points of P mod p with gamma on the sphere, D, 1 + |t|^2 and the "
       "pivots non-zero, and the field there (its contract; fi_field's docstring). The search "
       "concludes nothing from which points: nullity_p >= dim V and rank_p(known) <= dim K hold at "
       "every admissible choice (first_integrals' docstring), so when the ends meet the result is "
       "the same exact statement for any draw"
       for mutation in ("const: line 232 col 16: 64 -> 65",
                        "sign: line 232 col 20: int(1.2 * (count - have)) + 16 -> "
                        "int(1.2 * (count - have)) - 16",
                        "const: line 232 col 48: 16 -> 17",
                        "factor: line 232 col 24: 1.2 * (count - have) -> 1.2",
                        "factor: line 232 col 24: 1.2 * (count - have) -> count - have",
                        "const: line 233 col 25: 0 -> 1", "const: line 238 col 41: 0 -> 1")},
    ("search.integral_search.search_degree", "const: line 219 col 95: 0 -> 1"):
        "a box without known products gets K with one zero column instead of none, and reads it "
        "nowhere: known is 0 by the same 'if prods' (line 220) and the recovery check builds "
        "[F, K] only when there are products (line 224); tests/test_first_integrals.py's box "
        "(5, (3, 5, 1)) runs it and gives the same result",
    ("search.found_integral.varies_in_M", "const: line 248 col 69: 0 -> 1"):
        "another seeded exact point (stream 1 of the same seed and label instead of 0): the part "
        "needs one point where the exact slope dP/d eps is non-zero, a witness wherever it lies; "
        "the part's verdict is the same, its text names the other point",
    ("search.found_integral.varies_in_M", "sign: line 252 col 24: M + eps * N -> M - eps * N"):
        "the derivative along -N: d/d eps P(M - eps N)|_0 = -d/d eps P(M + eps N)|_0, non-zero "
        "exactly when the original is; the part's verdict is the same, its text shows -slope",
    ("reduction.invariants_n5.relations", "const: line 344 col 36: 1 -> 2"):
        "every relation doubled (each monomial starts from INV_RING(2)): 2r spans the same null "
        "space as r (the docstring's 'a basis of the exact null space') and 2r = 0 is the same "
        "relation; its users test vanishing (relation_part), count them, compare them with A_+-R1 "
        "(relations_on_P: all doubled alike) and take the zero set R1 = R2 = 0",
    ("family.sixth_integral.Delta_ring", "factor: line 67 col 11: (2 + a) * (2 + b) -> (2 + b) * (2 + a)"):
        "the same element of the commutative ring RING (== holds); only the insertion order of "
        "the terms in the PolyElement dict differs, which the replay's comparison reads and the "
        "rows do not (ring arithmetic, evaluation at a point, as_expr())",
    **{("axisym_inverse.inverse_denominator", mutation):
       "D times a non-zero constant (-1, 1/2, 3/2): _numerator_coefficients builds every D c_k "
       "from inverse_denominator() itself, so numerator and denominator scale together; D is "
       "only ever used with them (L(N) = D M in P:inversion, Omega = N / D, the cleared "
       "identity D' DN' - N' DD' of wedge_n6, homogeneous in the scale), and a constant multiple "
       "of a common denominator is one"
       for mutation in ("sign: line 90 col 11: 2 * Delta(x_, a_, b_) * (2 + a_ + b_) -> "
                        "-(2 * Delta(x_, a_, b_) * (2 + a_ + b_))",
                        "factor: line 90 col 11: 2 * Delta(x_, a_, b_) -> Delta(x_, a_, b_)",
                        "const: line 90 col 11: 2 -> 3")},
    ("search.found_integral.pfaffian", "sign: line 33 col 15: sp.Integer(0) -> -sp.Integer(0)"):
        "-Integer(0) is Integer(0), SymPy's zero singleton (S.Zero): the same object is returned; "
        "the odd-size branch it sits in is run by tests/test_fi_survivors.py",
    ("search.reconstruction.to_expression", "factor: line 184 col 17: int(co.re[r, j]) * X[j] -> X[j]"):
        "the real parts of the coordinate forms are 0 or 1 (fi_basis.coordinates: zeta_j = "
        "E_2j-1 + i E_2j, its conjugate, e_k = E_k; tested against that definition in "
        "tests/test_fi_survivors.py), and the zeros are skipped by the comprehension's 'if', so "
        "int(re) * X_j is X_j wherever it is formed",
    ("family.wedge_n6.h2_residual", "sign: line 55 col 15: R(expr.subs({a: A, b: B}, simultaneous=True)) -> "
                             "-R(expr.subs({a: A, b: B}, simultaneous=True))"):
        "every numerator coefficient of L_gamma^{-1} negated (the scaled c_k' and D' are built "
        "with R directly, not put): DO, so M-dot and gamma-dot, change sign, the field reversed in "
        "time, and the residual is exactly minus the original's, for any (a, b) and any model: "
        "zero modulo the sphere iff the original is, the function's one documented use",
    ("family.wedge_n6.h2_residual", "sign: line 112 col 15: tot -> -tot"):
        "the derivative along the field negated (DX returns -X(f)): the field reversed in time, "
        "and the residual Dp DX(NH) - NH DX(Dp), linear in DX, is exactly minus the original's "
        "for any model: zero modulo the sphere iff the original is, its one documented use",
    **{("fourd.inverse_apply", mutation):
       "the two summands of a component-wise sum, or the two factors of a product, of ring "
       "elements exchanged: the same elements "
       "of the commutative ring (== holds); only the insertion order of the terms in the "
       "PolyElement dicts differs, which the replay's comparison reads and the rows do not, as "
       "for sixth_integral.Delta_ring"
       for mutation in ("factor: line 191 col 44: c[1] * dot(q_, v) -> dot(q_, v) * c[1]",
                        "swap: line 192 col 12: _add(ap(C[0][0], kv), ap(C[0][1], uv)) -> "
                        "_add(ap(C[0][1], uv), ap(C[0][0], kv))",
                        "swap: line 193 col 11: _add(ap(C[1][0], kv), ap(C[1][1], uv)) -> "
                        "_add(ap(C[1][1], uv), ap(C[1][0], kv))")},
    **{("fourd.dot", mutation):
       "the two factors of one product of ring elements exchanged: the same element of the "
       "commutative ring (== holds); only the insertion order of the terms in the PolyElement "
       "dict differs, which the replay's comparison reads and the rows do not, as for "
       "family.sixth_integral.Delta_ring"
       for mutation in ("factor: line 71 col 11: p[0] * r[0] -> r[0] * p[0]",
                        "factor: line 71 col 25: p[1] * r[1] -> r[1] * p[1]",
                        "factor: line 71 col 39: p[2] * r[2] -> r[2] * p[2]")},
    **{("reduction.reduced_n5.raw_derivatives", mutation):
       "the two factors of one product of ring elements (d f / d z times D z-dot) exchanged: the "
       "same element of the commutative ring RING (== holds); only the insertion order of the "
       "terms in the PolyElement dicts differs, which the replay's comparison reads and the rows "
       "do not: field_numerators passes each D f-dot to invariants_n5.in_generators, which groups "
       "its terms by tridegree and sorts the monomials and parameters before the exact rref, so "
       "its result does not depend on the order (as for family.sixth_integral.Delta_ring); the "
       "value is tested against the chain rule along the field of eq:M-O in "
       "tests/test_reduced5_field_definition.py"
       for mutation in ("factor: line 71 col 23: d * Mdot[pair] -> Mdot[pair] * d",
                        "factor: line 75 col 23: d * gdot[k] -> gdot[k] * d")},
    ("family.wedge_n6.h2_residual", "exponent: line 94 col 42: (2 + A + B) ** deg -> "
                                    "(2 + A + B) ** (deg + 1)"):
        "every scaled coefficient c_k' and D' multiplied by one more factor c = 2 + a + b, which "
        "holds no M, gamma or x: NH is linear in the c_k', so NH and D' both become c times "
        "themselves and the residual D' DX(NH) - NH DX(D') becomes c^2 times the original's; c is "
        "not zero (symbolic, in the domain Q[a, b, x, M, gamma]/(|gamma|^2 - 1); at a rational "
        "(a, b) by the documented 2 + a + b != 0), so it is zero modulo the sphere iff the "
        "original is, the function's one documented use",
    ("family.wedge_n6.h2_residual", "sign: line 77 col 12: -sum((DO[i][t] * gam[t] for t in "
                                    "range(N)), R(0)) -> sum((DO[i][t] * gam[t] for t in "
                                    "range(N)), R(0))"):
        "gamma-dot alone negated: the residual becomes D' (X_M - X_gamma)(NH) - NH (X_M - "
        "X_gamma)(D'), and tests/test_wedge_n6.py's symbolic test, run on this mutant, finds it "
        "zero modulo |gamma|^2 = 1 for symbolic a, b (exact FLINT reduction), as it finds the "
        "original: the M-part and the gamma-part of the H_2 rate vanish on P each by itself, so "
        "the function's one documented use (zero modulo the sphere or not) gives the same answer. "
        "The H_2 check cannot see the sign of gamma-dot (a fact about H_2, not a gap this "
        "function can close)",
    ("family.wedge_n6.h2_residual", "sign: line 113 col 11: Dp * DX(NH) - NH * DX(Dp) -> "
                             "-(Dp * DX(NH) - NH * DX(Dp))"):
        "the residual negated: zero modulo the sphere iff the original is, its one documented use "
        "(the sign of a residual is a convention)",
}


def argued(record: dict) -> dict:
    """``record`` with a survivor whose equivalence is argued in :data:`ARGUED` made ``equivalent``
    (its reason starts with "argued:")."""
    why = ARGUED.get((record["function"], record["mutation"]))
    if record["outcome"] == "survived" and why:
        record.update(outcome="equivalent", reason=f"argued: {why} ({record['reason']})")
    return record

