"""symbolic/family/euler_jacobi_n5.py (row S6:euler-jacobi-n5): the hypotheses of Euler-Jacobi on the
n = 5 quotient, and controls that show each check can fail."""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.family import euler_jacobi_n5 as ej


def test_the_measure_exponent_is_derived_and_unique():
    """P0 + alpha P1 = 0 for the derived alpha only: the Lebesgue density (alpha = 0) and the
    n = 4 exponent (alpha = -2) are not invariant on the quotient."""
    P0, P1 = ej.measure_polynomials()
    alpha = ej.measure_exponent()
    assert alpha == sp.Rational(-3, 2)
    assert 2 * P0 - 3 * P1 == 0
    assert P0 != 0 and P0 - 2 * P1 != 0


def test_relations_are_invariant_but_not_first_integrals():
    """X(R_1) = C11 R_1 with C11 != 0: the relations cut out an invariant set, but are not conserved,
    so the residue needs the cofactors (the same trap as the n = 4 measure)."""
    C = ej.relation_cofactors()
    assert C["C11"] != 0 and C["C22"] != 0


def test_rank_drops_when_an_integral_is_replaced_by_a_function_of_the_others():
    """The independence check can fail: with F replaced by H the rank is 7, not 8."""
    rng = points.generator(4, "EJ5 test")
    M, g = points.skew_matrix(rng, 5), points.sphere_point(rng, 5)
    a, b = sp.Rational(-1, 3), sp.Rational(3, 2)
    J = ej.jacobian_at(ej.quotient_point(M, g), a, b)
    assert J.rank() == 8
    names = list(ej.integral_fractions())
    J2 = J.copy()
    J2[names.index("F"), :] = J[names.index("H"), :]
    assert J2.rank() == 7


def test_positivity_range_at_sample_parameters():
    """L_gamma (n = 5) has a non-positive eigenvalue just outside the stated range (a = -5/2) and none
    inside it (a = -1, b = 1/2), at gamma with x = 0 and x = 3/5: its exact eigenvalues 2, 2 + a + b and the roots of the quadratic."""
    from chaplygin_nd.symbolic import model

    for (a, b), positive in (((-1, sp.Rational(1, 2)), True), ((sp.Rational(-5, 2), 1), False)):
        for gamma in (sp.Matrix([0, 0, 0, 1, 0]), sp.Matrix([0, 0, 0, sp.Rational(4, 5), sp.Rational(3, 5)])):
            L = model.L_matrix(gamma, sp.diag(1, 1, 1, 1, 1 + a), b)
            assert all(ev > 0 for ev in L.eigenvals()) == positive


def test_the_chart_density_is_invariant_and_is_the_push_forward():
    from chaplygin_nd.symbolic.family import quotient_measure_n5 as qm

    _, _, rem = qm.chart_divergence()
    assert rem == 0
    ratios, without_J = set(), set()
    J, _ = qm.chart_jacobian()
    for t in range(2):
        rng = points.generator(11, "push-forward test", t)
        M, g = points.skew_matrix(rng, 5), points.sphere_point(rng, 5)
        r = qm.pushforward_ratio(M, g, "flint")
        assert str(r) == str(qm.pushforward_ratio(M, g, "sympy"))
        ratios.add(str(r))
        Jv = qm.ev_inv(J, ej.quotient_point(M, g), sp.Rational, sp.Integer(0), sp.Integer(1))
        without_J.add(sp.Rational(str(r)) / Jv**2)
    assert len(ratios) == 1 and len(without_J) == 2


def test_the_cell_certificate_tells_ranges_apart():
    for eng in ("sympy", "flint"):
        assert not ej.positivity_cells(eng)["differ"]
        # the physical range and a range missing a + b > -2 are not the positivity range
        assert ej.positivity_cells(eng, stated=lambda l1, l2, l3: l1 > 1 and l2 > 2)["differ"]
        assert ej.positivity_cells(eng, stated=lambda l1, l2, l3: l1 > 0 and l2 > 0)["differ"]
    assert ej.quadratic_reflection_residual() == 0


def test_equilibria_fixed_by_eta_are_equilibria_and_critical():
    from chaplygin_nd.symbolic.exact import flint_engine
    from chaplygin_nd.symbolic.family import equilibria_n5 as eqm

    a, b = sp.Rational(-1, 3), sp.Rational(3, 2)
    drawn = None
    for t in range(5):
        drawn = eqm.eta_point(points.generator(3, "eta test", t), a, b)
        if drawn:
            break
    M, g, eta = drawn
    assert eqm.fixed_by(M, g, eta) and not eqm.fixed_by(M, g, points.skew_matrix(points.generator(3, "x"), 5))
    pt = ej.quotient_point(M, g)
    field = ej.r5.field()
    at = {ej.r5.SYMBOLS[n]: v for n, v in pt.items()} | {ej.r5.a: a, ej.r5.b: b}
    assert all(sp.cancel(field[n].xreplace(at)) == 0 for n in ej.r5.COORDS)
    with flint_engine.use_engine("flint"):
        assert flint_engine.rank(ej.jacobian_at(pt, a, b)) < 8
    # a generic point is neither an equilibrium nor critical
    rng = points.generator(3, "generic")
    pt = ej.quotient_point(points.skew_matrix(rng, 5), points.sphere_point(rng, 5))
    at = {ej.r5.SYMBOLS[n]: v for n, v in pt.items()} | {ej.r5.a: a, ej.r5.b: b}
    assert any(sp.cancel(field[n].xreplace(at)) != 0 for n in ej.r5.COORDS)
    assert ej.jacobian_at(pt, a, b).rank() == 8


def test_points_fixed_by_eta_have_dependent_invariants_but_generic_points_do_not():
    from chaplygin_nd.symbolic.family import equilibria_n5 as eqm
    from chaplygin_nd.symbolic.family import independence_all_n as ia
    from sympy.polys.matrices import DomainMatrix

    G, syms = eqm.isotropy_family_matrix()
    assert DomainMatrix.from_Matrix(G).convert_to(sp.QQ.frac_field(*syms)).rank() == 3
    rng = points.generator(4, "generic c rank")
    assert ia.c_rank(points.skew_matrix(rng, 5), points.sphere_point(rng, 5), "sympy") == 4


def test_the_box_bounds_every_generator_and_needs_its_degree():
    """|g| <= C_g ||M||^d_g at points of P (both engines give the same C_g, d_g); with d_g - 1 the bound fails
    for some generator once M is scaled up, so the degrees are not slack."""
    bounds = ej.generator_bounds("sympy")
    assert bounds == ej.generator_bounds("flint")
    assert set(bounds) == set(ej.r5.COORDS) - {"x"}
    rng = points.generator(5, "EJ5 box test")
    M, g = points.skew_matrix(rng, 5), points.sphere_point(rng, 5)
    for scale, expect_sharp in ((1, False), (10**4, True)):
        vals = ej.quotient_point(M * scale, g)
        norm2 = sum((M[i, j] * scale) ** 2 for i in range(5) for j in range(i + 1, 5))
        assert all(vals[n] ** 2 <= sp.Rational(C) ** 2 * norm2**d for n, (d, C) in bounds.items())
        if expect_sharp:
            assert any(vals[n] ** 2 > sp.Rational(C) ** 2 * norm2 ** (d - 1) for n, (d, C) in bounds.items())


def test_z_has_real_points_outside_the_image_of_p():
    """A_+ = -1 with every other coordinate 0 satisfies R_1 = R_2 = 0, but A_+ = |k_+|^2 >= 0 on the image of P:
    the level sets are bounded in the image of P, not in all of Z."""
    R1, R2 = ej.relations()
    c = ej.coordinates()
    at = {str(v): 0 for v in c.values()} | {"Ap": -1, "x": sp.Rational(1, 2)}
    names = [str(s) for s in R1.ring.symbols]
    vals = [at.get(n, 0) for n in names]
    assert R1(*vals) == 0 and R2(*vals) == 0


def test_liouville_needs_the_s_polynomial_in_a_chart_solving_for_x():
    """In the chart solving for (x, B) a plain division by (R_1, R_2) leaves a remainder; with their reduced
    S-polynomial g_3 = u R_1 + v R_2 it leaves none, and the cofactors make an identity."""
    from chaplygin_nd.symbolic.family import quotient_measure_n5 as qm

    R1, R2 = ej.relations()
    g3, (u, v) = qm.relation_s_polynomial()
    assert g3 != 0 and g3 - u * R1 - v * R2 == 0
    T, (q1, q2), rem = qm.chart_divergence(("x", "B"))
    assert rem == 0 and T - q1 * R1 - q2 * R2 == 0
    assert T.div([R1, R2])[1] != 0
    assert len(qm.charts()) == 44 and ("Ap", "Am") not in qm.charts()


def test_the_equilibrium_set_on_z_is_cut_out_by_four_polynomials_free_of_a():
    eq = ej.equilibrium_equations()
    assert set(eq["vanishing"]) == set(ej.r5.COORDS) - {"G", "Suq"}
    assert eq["a_free"]
    PG, Puq = eq["P"]
    assert PG != 0 and Puq != 0


def test_every_equilibrium_is_critical_by_an_explicit_kernel_vector():
    """J d_G N lies in the ideal of (N, R1, R2, d_G R1, d_G R2) with explicit cofactors; the G and S_uq columns
    vanish at G = S_uq = 0 and (d_G N)_x = 2 Delta. Controls: the G column does not vanish off G = S_uq = 0, and
    dH . d_G N is not the zero polynomial (the membership has content: it vanishes only on the ideal's zeros)."""
    k = ej.equilibrium_kernel_residuals()
    assert all(r == 0 for r in k["residuals"].values())
    assert all(col == 0 for col in k["columns"]) and k["wx"] == 0
    kf = ej.equilibrium_kernel_residuals("flint")
    assert all(r == 0 for r in kf["residuals"].values()) and kf["wx"] == 0
    P, Q = ej.integral_fractions()["H"]
    G = ej.coordinates()["G"]
    assert Q * P.diff(G) - P * Q.diff(G) != 0
    c = ej.coordinates()
    row = sum(((Q * P.diff(c[n]) - P * Q.diff(c[n])) * k["w"][n] for n in ej.r5.COORDS), 0 * P)
    assert row != 0


def test_the_chart_densities_agree_on_every_overlap_and_the_check_can_fail():
    """|det dz'/dz| = |J_c'/J_c| for every pair of charts (946), so the 44 chart densities are one density;
    control: with J_c in place of J_c' (the density 1/|J| read as the same function in every chart) the
    identity fails for some pair."""
    import itertools

    from chaplygin_nd.symbolic.family import quotient_measure_n5 as qm

    residuals = qm.chart_transition_residuals()
    assert len(residuals) == 44 * 43 // 2 and all(r == 0 for r in residuals)
    R1, R2 = ej.relations()
    c = ej.coordinates()
    wrong = 0
    for one, other in itertools.islice(itertools.combinations(qm.charts(), 2), 40):
        J, m = qm.chart_jacobian(one)
        r = [one.index(y) for y in one if y not in other]
        s = [y for y in other if y not in one]
        if len(r) != 1:
            continue
        adj = [[m[1][1], -m[0][1]], [-m[1][0], m[0][0]]]
        scaled = -(adj[r[0]][0] * R1.diff(c[s[0]]) + adj[r[0]][1] * R2.diff(c[s[0]]))
        wrong += scaled - J != 0 and scaled + J != 0
    assert wrong > 0
