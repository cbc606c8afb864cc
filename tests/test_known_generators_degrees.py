"""The search's known algebra records each integral found beyond the paper with the degrees of its
definition: the generator's (M-degree, gamma-degree, power of Delta) are read off the formula that
S6:sixth-integral and the n = 6 search prove conserved (``search.found_integral``; F's form of
gamma-degree 2 from ``family.sixth_integral``: F = N_F / Delta), with Delta the
determinant of the derived block (eq:Delta).  A generator recorded as numerator / Delta^2 instead of
/ Delta would put the integral into the wrong boxes, and the sandwich could still close there."""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.symbolic.algebra import skew_symbols, vector_symbols
from chaplygin_nd.symbolic.axisymmetric import Delta
from chaplygin_nd.symbolic.family import sixth_integral
from chaplygin_nd.symbolic.search import found_integral, known_integrals
from chaplygin_nd.symbolic.search.sampled_field import axisymmetric

A, B = sp.Rational(1, 3), sp.Rational(2, 5)


def _declared(n: int, name: str) -> known_integrals.Generator:
    found = [g for g in known_integrals.generators(axisymmetric(n, A, B), include_new=True)
             if g.name == name]
    assert len(found) == 1, name
    return found[0]


def _defined_degrees(n: int, formula) -> tuple[int, int, int]:
    """(M-degree, gamma-degree, Delta power) of numerator / denominator as the formula gives them."""
    M = skew_symbols("m", n)
    gam = sp.Matrix(list(vector_symbols("g", n)))
    num, den = formula(M, gam, A, B)
    m_vars = sorted(M.free_symbols, key=str)
    g_vars = list(gam)
    m_degree = sp.Poly(num, *m_vars).total_degree()
    assert sp.Poly(num, *m_vars).is_homogeneous
    g_degree = sp.Poly(num, *g_vars).total_degree()
    delta = Delta(gam[n - 1], A, B)
    power = 0
    rest = sp.expand(den)
    while sp.degree(rest, gam[n - 1]) > 0:
        quotient, remainder = sp.div(rest, sp.expand(delta), gam[n - 1])
        assert remainder == 0, "the denominator is a power of Delta"
        rest, power = quotient, power + 1
    assert rest.is_number and rest != 0
    return m_degree, g_degree, power


def test_F_is_recorded_with_the_degrees_of_its_definition():
    n = 5
    g = _declared(n, "F")
    assert (g.m_degree, g.g_degree, g.d_power) == _defined_degrees(n, found_integral.new_integral)


def test_G_is_recorded_with_the_degrees_of_its_definition():
    n = 6
    g = _declared(n, "G")
    assert (g.m_degree, g.g_degree, g.d_power) == _defined_degrees(n, found_integral.new_integral_6)


def test_F2_is_recorded_with_the_degrees_of_its_definition():
    n = 5
    g = _declared(n, "F2")

    def lowest_form(M, gam, a, b):
        return sixth_integral.numerator_expr(M, gam, a, b), Delta(gam[n - 1], a, b)

    assert (g.m_degree, g.g_degree, g.d_power) == _defined_degrees(n, lowest_form)
