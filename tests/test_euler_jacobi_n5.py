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
