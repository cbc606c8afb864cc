"""Carrying an exclusion from one rational (a, b) to generic (a, b): the minor certificate, the
grid bound on the rank over Q(a, b), and a refusal where inconsistency holds at the point only."""

import flint
import sympy as sp
from chaplygin_nd.symbolic.search import generic_extension as ge
from chaplygin_nd.symbolic.search import poisson as ps


def _q(rows):
    return [[flint.fmpq(sp.Rational(v).p, sp.Rational(v).q) for v in r] for r in rows]


def test_the_minor_certificate_is_an_exact_nonzero_minor_of_the_rank():
    rows = [[1, 2, 3, 4], [2, 4, 6, 8], [sp.Rational(1, 3), 0, 5, 1], [0, 1, 0, sp.Rational(-2, 7)]]
    cert = ge.nullity_certificate(_q(rows))
    M = sp.Matrix(rows)
    assert cert.rank == M.rank() == 3 and cert.nullity == 1
    sub = M.extract(cert.rows, cert.cols)
    assert sp.Rational(int(cert.minor.p), int(cert.minor.q)) == sub.det() != 0


def test_the_grid_refuses_an_inconsistency_that_holds_at_the_point_only():
    # A(a, b) c = h with A = [[a - 1/3]], h = [1]: inconsistent at a = 1/3, consistent elsewhere
    A0, A1, A2 = _q([[sp.Rational(-1, 3)]]), _q([[1]]), _q([[0]])
    grid = ge.grid_rank(A0, A1, A2)
    assert grid["top"][0] == 1
    ok, text = ge.inconsistency_certificate(_q([[0]]), _q([[1]])[0], grid, "(1/3, 0)")
    assert not ok and "nonzero" in text
    # A = [[0], [0]] for every (a, b), h = (1, b): inconsistent for every (a, b)
    grid = ge.grid_rank(_q([[0], [0]]), _q([[0], [0]]), _q([[0], [0]]))
    ok, text = ge.inconsistency_certificate(_q([[0], [0]]), _q([[1, 2]])[0], grid, "(0, 2)")
    assert ok and text.startswith("generic")


def test_a_linear_exclusion_of_n4_holds_for_generic_parameters():
    r = ps.search_box(4, 1, 0, sp.Rational(1, 3), sp.Rational(2, 5), seed=20261121)
    assert r.outcome == "excluded (linear)" and r.generic.startswith("generic (a, b)")
    r = ps.search_box(4, 2, 1, sp.Rational(1, 3), sp.Rational(2, 5), seed=20261121)
    assert r.outcome == "excluded (Jacobi)" and r.generic.startswith("only at")
