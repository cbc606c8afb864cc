"""symbolic/exact/flint_matrix.py (printed matrix formulas in fmpq arithmetic) and the one-solve FLINT
divergence of symbolic/flint_model.py: equal, entry by entry, to SymPy's values."""

from __future__ import annotations

import flint
import pytest
import sympy as sp
from chaplygin_nd.proofs import s3_vertical_horizontal as s3
from chaplygin_nd.symbolic import flint_model
from chaplygin_nd.symbolic.algebra import wedge
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.exact.flint_engine import linear_algebra_calls, use_engine
from chaplygin_nd.symbolic.exact.flint_matrix import (
    FlintMatrix,
    entries,
    formula_matrix,
    from_columns,
)
from chaplygin_nd.symbolic.measure import chaplygin_divergence_at
from chaplygin_nd.symbolic.printed import section3 as printed


def _q(values):
    return [flint.fmpq(int(sp.Rational(v).p), int(sp.Rational(v).q)) for v in values]


def test_printed_formulas_give_sympy_values_in_fmpq():
    rng = points.generator(5, "flint-matrix")
    n = 6
    M, g = points.skew_matrix(rng, n), points.sphere_point(rng, n)
    with use_engine("flint"):
        Mf, gf = formula_matrix(M), formula_matrix(g)
    assert isinstance(Mf, FlintMatrix) and Mf.shape == (n, n) and gf.shape == (n, 1)
    for sympy_value, flint_value in ((printed.H_nd(M, g), printed.H_nd(Mf, gf)),
                                     (printed.V_nd(M, g), printed.V_nd(Mf, gf)),
                                     (wedge(M * g, g), wedge(Mf * gf, gf)),
                                     (sp.Rational(2, 3) * M - M.T, sp.Rational(2, 3) * Mf - Mf.T),
                                     (-M[:, 2], -Mf[:, 2])):
        assert isinstance(flint_value, FlintMatrix)
        assert entries(flint_value) == _q(entries(sympy_value))
    assert Mf[1, 2] == flint.fmpq(int(M[1, 2].p), int(M[1, 2].q)) and gf[3] == _q([g[3]])[0]


def test_formula_matrix_follows_the_engine_and_counts_as_a_dispatched_step():
    A = sp.Matrix([[1, sp.Rational(1, 2)], [0, -3]])
    before = linear_algebra_calls()
    with use_engine("sympy"):
        assert formula_matrix(A) is A
    with use_engine("flint"):
        assert formula_matrix(A).mat == flint.fmpq_mat(2, 2, [1, flint.fmpq(1, 2), 0, -3])
    assert linear_algebra_calls() == before + 2


def test_flint_matrix_refuses_inexact_or_symbolic_operands():
    with use_engine("flint"):
        A = formula_matrix(sp.eye(2))
    for bad in (0.5, sp.Float(0.5), sp.Symbol("x"), sp.sqrt(2)):
        with pytest.raises(TypeError):
            A * bad
    with pytest.raises(TypeError):
        A + 1
    with pytest.raises(ValueError):
        sp.Matrix([[sp.Symbol("x"), 0], [0, 1]]) * A


def test_sympy_matrices_of_rationals_mix_in_on_either_side():
    # a (mutated or printed) formula may use sp.eye(n) or basis_vector next to its arguments
    S = sp.Matrix([[1, sp.Rational(1, 3)], [-2, 5]])
    with use_engine("flint"):
        A = formula_matrix(sp.Matrix([[0, 1], [sp.Rational(-1, 2), 4]]))
    A_sympy = sp.Matrix([[0, 1], [sp.Rational(-1, 2), 4]])
    for got, want in ((S * A, S * A_sympy), (A * S, A_sympy * S), (S + A, S + A_sympy),
                      (S - A, S - A_sympy), (A - S, A_sympy - S), (A + S, A_sympy + S)):
        assert isinstance(got, FlintMatrix) and entries(got) == _q(entries(want))
    with pytest.raises(ValueError):
        with use_engine("flint"):
            formula_matrix(sp.Matrix([[sp.sqrt(2)]]))


def test_from_columns_builds_columns_in_either_type():
    cols = [[sp.Rational(1, 2), 3], [0, -1], [5, sp.Rational(-2, 7)]]
    A = from_columns(cols)
    assert A == sp.Matrix([[sp.Rational(1, 2), 0, 5], [3, -1, sp.Rational(-2, 7)]])
    F = from_columns([_q(c) for c in cols])
    assert isinstance(F, FlintMatrix) and entries(F) == _q(entries(A))
    with pytest.raises(ValueError):
        from_columns([[1, 2], [3]])
    with pytest.raises(ValueError):
        from_columns([])


@pytest.mark.parametrize("n, unit", [(5, False), (8, True)])
def test_one_solve_divergence_equals_the_full_inverse_route(n, unit):
    # the FLINT route (one solve, trace identities) against SymPy's (full inverse, every d_k L),
    # also off the sphere: the identities hold for any gamma
    rng = points.generator(13, "divergence", n)
    J = sp.diag(*[points.rational(rng, 1, 3, 4) for _ in range(n)])
    bb = points.rational(rng, 0, 3, 4, open_lo=True)
    M = points.skew_matrix(rng, n)
    gamma = points.sphere_point(rng, n) * (1 if unit else sp.Rational(3, 2))
    fast = flint_model.divergence_at_fmpq(M, gamma, J, bb)
    full = chaplygin_divergence_at(M, gamma, J, bb)
    for key in ("div", "gamma_dot", "Omega", "dlogdet"):
        assert fast[key] == full[key], key


def test_one_solve_divergence_refuses_a_non_symmetric_L(monkeypatch):
    rng = points.generator(17, "divergence-asym")
    n = 4
    J, bb = sp.diag(1, 2, 3, 4), sp.Rational(1, 2)
    M, gamma = points.skew_matrix(rng, n), points.sphere_point(rng, n)
    true_L = flint_model.L_matrix_fmpq

    def skewed(*args):
        L = true_L(*args)
        L[0, 1] += 1
        return L
    monkeypatch.setattr(flint_model, "L_matrix_fmpq", skewed)
    with pytest.raises(ArithmeticError):
        flint_model.divergence_at_fmpq(M, gamma, J, bb)


def test_dimension_count_of_eq_def_H_V_is_the_same_in_both_engines():
    rng = points.generator(19, "dims")
    for n in (4, 7):
        p = s3._nd_point(n)(rng)
        values = {}
        for engine in ("sympy", "flint"):
            with use_engine(engine):
                values[engine] = s3._dimension_residual(n, p)
        assert values["sympy"] == values["flint"] == [0, 0]
