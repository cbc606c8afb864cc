"""symbolic/family/wedge_integrals.py (row S6:wedge-integrals) against its definitions, at exact points.

The row checks dH_k/dt = 0 and a Jacobian rank. Both are blind to some errors: each of the two
terms of the rate vanishes on its own at the points checked, so a wrong factor on either term
(or on B-dot) leaves the rate zero, and a rank is the same for almost any perturbed gradient
(a mutation run: such mutants survived the row). These tests compare the pieces with
independent computations: B and B-dot with SymPy's differentiation of the definition, M-dot and
gamma-dot with the exact angular velocity of symbolic.model, the M-gradient with the exact
derivative of the value (a polynomial of degree 2k in M along a line, so 2k + 1 values give it
exactly by interpolation).
"""

from __future__ import annotations

import definitions
import pytest
import sympy as sp
from chaplygin_nd.symbolic import model
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.family import wedge_integrals as wi


def _point(n: int, seed: int = 7):
    rng = points.generator(seed, "tests/test_wedge_integrals", n)
    M, gamma = points.skew_matrix(rng, n), points.sphere_point(rng, n)
    return M, gamma, sp.Rational(-2, 7), sp.Rational(5, 3)


@pytest.mark.parametrize("engine", ["sympy", "flint"])
def test_point_fields_are_the_definitions(engine):
    n = 5
    M, gamma, a, b = _point(n)
    Mq, g, Md, gd, B, Bd, _ = wi.point_fields(M, gamma, a, b, engine)
    rat = (lambda v: sp.Rational(int(v.p), int(v.q))) if engine == "flint" else sp.Rational
    as_matrix = lambda rows: sp.Matrix([[rat(v) for v in row] for row in rows])  # noqa: E731
    J = sp.diag(*([1] * (n - 1) + [1 + a]))
    Omega = model.angular_velocity(M, gamma, J, b)             # eq:M-O solved, not wedge_integrals
    assert as_matrix(Mq) == M and sp.Matrix([rat(v) for v in g]) == gamma
    assert as_matrix(Md) == M * Omega - Omega * M                 # M-dot = [M, Omega]
    assert sp.Matrix([rat(v) for v in gd]) == -Omega * gamma      # gamma-dot = -Omega gamma
    eps = sp.Symbol("eps")
    E = sp.zeros(n, 1)
    E[n - 1] = 1
    B_of = lambda g_: a * E * E.T + b * g_ * g_.T  # noqa: E731 - B of the module docstring
    assert as_matrix(B) == B_of(gamma)
    moved = gamma + eps * sp.Matrix([rat(v) for v in gd])
    assert as_matrix(Bd) == sp.diff(B_of(moved), eps).subs(eps, 0)


@pytest.mark.parametrize("n, k", [(4, 2), (5, 2), (6, 2)])
def test_gradient_in_M_is_the_derivative_of_the_value(n, k):
    M, gamma, a, b = _point(n, seed=11)
    grad = wi.gradient(M, gamma, a, b, k)
    hs = list(range(2 * k + 1))
    for col, (i, j) in enumerate(wi.subsets(n, 2)):
        E = sp.zeros(n, n)
        E[i, j], E[j, i] = 1, -1
        values = [wi.value(M + h * E, gamma, a, b, k) for h in hs]
        h = sp.Symbol("h")
        slope = sp.diff(sp.interpolate(list(zip(hs, values)), h), h).subs(h, 0)
        assert grad[col] == slope, (i, j)


def test_value_is_the_energy_for_k_1():
    """H_1 = 2H = <M, Omega> with Omega = L_gamma^{-1} M (the module docstring), exactly."""
    n = 5
    M, gamma, a, b = _point(n, seed=3)
    Omega = model.angular_velocity(M, gamma, sp.diag(*([1] * (n - 1) + [1 + a])), b)
    pairing = sum(M[i, j] * Omega[i, j] for i in range(n) for j in range(i + 1, n))
    assert wi.value(M, gamma, a, b, 1) == pairing


@pytest.mark.parametrize("size", [2, 4, 6])
def test_pfaffian_is_the_definition(size):
    """wedge_integrals.pfaffian against the permutation sum, its sign included: H_k is quadratic
    in the wedge power, so S6:wedge-integrals cannot see a Pfaffian's sign (a mutation
    run: every term's sign flipped survived the row). On a principal submatrix too."""
    rng = points.generator(size, "tests/test_wedge_integrals pfaffian")
    A = points.skew_matrix(rng, size + 1)
    rows = A.tolist()
    assert wi.pfaffian(rows, tuple(range(size)), 0, 1) == definitions.pfaffian(A[:size, :size])
    idx = tuple(range(1, size + 1))
    assert wi.pfaffian(rows, idx, 0, 1) == definitions.pfaffian(A.extract(list(idx), list(idx)))
    assert wi.pfaffian(rows, (), 0, 1) == 1


@pytest.mark.parametrize("engine", ["sympy", "flint"])
def test_gamma_gradient_is_the_derivation_route(engine):
    """The gamma part of wedge_integrals.gradient (interior products) against -<Y, D_dB Y> with the
    matrix of the derivation of dB = b(e_m gamma^T + gamma e_m^T) (derivation_matrix), n = 6, k = 2."""
    n, k = 6, 2
    M, gamma, a, b = _point(n, seed=5)
    num, zero, one = wi.numbers(engine)
    grad = wi.gradient(M, gamma, a, b, k, engine)
    g = [num(v) for v in gamma]
    B = [[(num(a) if i == j == n - 1 else zero) + num(b) * g[i] * g[j] for j in range(n)] for i in range(n)]
    W = wi.wedge_power([[num(M[i, j]) for j in range(n)] for i in range(n)], n, k, zero, one)
    Y = wi.solve(wi.shifted(B, n, 2 * k, zero), W, engine, zero)
    for m in range(n):
        dB = [[num(b) * ((one if i == m else zero) * g[j] + g[i] * (one if j == m else zero))
               for j in range(n)] for i in range(n)]
        D = wi.derivation_matrix(dB, n, 2 * k, zero)
        DY = [sum((v * Y[c] for c, v in D.get(r, {}).items()), zero) for r in range(len(Y))]
        assert grad[n * (n - 1) // 2 + m] == -sum((y * z for y, z in zip(Y, DY, strict=True)), zero)


def test_the_rank_part_fails_for_a_function_that_is_not_an_integral(monkeypatch):
    """The rank part of S6:wedge-independence evaluates the conservation of the functions it
    differentiates: with (1 + D_B)^{-1} in place of (2 + D_B)^{-1} in the differential (a function
    that is not an integral, whose rank would still be full) the part fails, in both engines."""
    import functools

    from chaplygin_nd.proofs import s6_wedge_independence as row
    from chaplygin_nd.symbolic.family import independence as ind

    assert row.independence(6)[0].verdict == "holds"
    M, g, a, b = row.point(6, "rank", adapted=True)
    monkeypatch.setattr(wi, "gradient", functools.partial(wi.gradient, shift=1))
    for engine in ("sympy", "flint"):
        rec = ind.rank_record(M, g, a, b, engine)
        assert rec["rank"] == rec["expected"]          # the rank alone would not notice
        assert rec["not_conserved"] == ["H_1 = 2H", "H_2"]
    part, _ = row.independence(6)
    assert part.verdict == "fails" and "not conserved" in part.counterexample


def test_the_collapse_and_vanishing_parts_can_fail(monkeypatch):
    """Controls of the proof's checks: a wrong constant in the resolvent (3 + D_B) breaks the
    vanishing step's closed form of Y; the two sides of the collapse are non-zero."""
    from chaplygin_nd.proofs import s6_wedge_integrals as row
    from chaplygin_nd.symbolic.family import wedge_proof as wp

    assert row.vanishing(6).verdict == "holds" and row.collapse(6).verdict == "holds"
    M, g, a, b = row.point(6, "collapse", adapted=False)
    Om = points.skew_matrix(points.generator(1, "Omega"), 6)
    # both sides of the collapse are non-zero for a generic Omega: the identity is not 0 = 0
    assert all(wp.collapse_residual(M, g, a, b, k, Om, "flint") == 0 for k in (1, 2, 3))
    assert any(wi.rate(M, g, a, b, k, "flint", Om) != 0 for k in (1, 2))
    original = wi.shifted
    monkeypatch.setattr(wi, "shifted", lambda B, n, m, zero, shift=2: original(B, n, m, zero, 3 if m == 4 else shift))
    assert row.vanishing(6).verdict == "fails"
