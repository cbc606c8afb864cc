"""symbolic/family/independence_all_n.py (row S6:wedge-independence): the finite identities of the argument
that the invariant integrals are independent for every n, and controls that show each check can fail."""

from __future__ import annotations

import pytest
import sympy as sp
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.family import independence_all_n as ia
from chaplygin_nd.symbolic.family import wedge_integrals as wi


@pytest.mark.parametrize("n", [5, 6, 7, 8])
def test_closed_form_and_ranks(n):
    M, g, f, theta = ia.frame_point(points.generator(5, "all-n test", n), n)
    a = sp.Rational(-1, 3)
    K = (n + 1) // 2 - 1
    for eng in ("sympy", "flint"):
        assert all(ia.closed_form_residual(M, g, f, theta, a, k, eng) == 0 for k in range(1, n // 2 + 1))
        assert ia.phi_rank(f, theta, eng) == K
        assert ia.c_rank(M, g, eng) == n - 1


def test_controls_the_checks_can_fail():
    n = 7
    M, g, f, theta = ia.frame_point(points.generator(5, "all-n control"), n)
    # equal eigenvalues: the determinant of e_(k-1)(t_(!=j)) vanishes and the rank falls
    assert ia.phi_rank(f, [theta[0]] * len(theta), "flint") < (n + 1) // 2 - 1
    # gamma along a frame vector: its weights on the other planes vanish and rank dc falls
    assert ia.c_rank(M, f[:, 0], "flint") < n - 1
    # the closed form is that of b = 0: at b != 0 the value differs
    a = sp.Rational(-1, 3)
    assert wi.value(M, g, a, 1, 2, "flint") != wi.value(M, g, a, 0, 2, "flint")
    assert ia.closed_form_residual(M, g, f, theta, a, 2, "flint") == 0


@pytest.mark.parametrize("n", [4, 5, 6])
def test_c_tangent_rows_are_the_gradients_restricted_to_tp(n):
    """Each restricted row vanishes on the normal (0, gamma) of P and agrees with the full gradient on
    tangent vectors (dM, v) with <v, gamma> = 0: the rows are the differentials on TP."""
    from chaplygin_nd.symbolic.family import independence as ind

    rng = points.generator(5, "c rows on TP", n)
    M, g = points.skew_matrix(rng, n), points.sphere_point(rng, n)
    N = n * (n - 1) // 2
    rows = ia.c_tangent_rows(M, g, "sympy")
    _, grads = ind.coefficient_gradients(M, g, "sympy")
    assert len(rows) == len(grads) == n - 1 and all(len(r) == N + n for r in rows)
    normal = [0] * N + list(g)
    v = [sp.Rational(k + 1, 7) for k in range(n)]
    v = [vi - sum(vj * gj for vj, gj in zip(v, g, strict=True)) * gi for vi, gi in zip(v, g, strict=True)]
    tangent = [sp.Rational((-1) ** k * (k + 2), 5) for k in range(N)] + v
    for row, grad in zip(rows, grads, strict=True):
        assert sp.simplify(sum(r * c for r, c in zip(row, normal, strict=True))) == 0
        assert sp.simplify(sum((r - q) * c for r, q, c in zip(row, grad, tangent, strict=True))) == 0
