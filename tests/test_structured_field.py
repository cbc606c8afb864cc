"""The O(n^2) structured full field (row S4:structured-field) on floats and in mpmath.

Reference: eq:motion-general with Omega from an mpmath linear solve of L_gamma at 40 digits (the
matrix of L_gamma assembled from its definition, eq:M-O with J = Id + a E_n E_n^T), a route that
uses neither the derived coefficients nor the structured weights. Checked: the heyoka assembly
(runtime.expressions, evaluated on mpmath numbers and on floats) and the NumPy runtime
(runtime.axisym.vector_field) for n = 3..12, and the old matrix form on floats.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
from chaplygin_nd.runtime import axisym
from chaplygin_nd.runtime import expressions as rx
from chaplygin_nd.simulate.dynamics import families, so

DPS = 40


class MpOps:
    """The builders' ``ops`` in mpmath."""

    rational = staticmethod(lambda p, q: mpmath.mpf(p) / q)
    sqrt = staticmethod(mpmath.sqrt)


class FloatOps:
    """The builders' ``ops`` in float64."""

    rational = staticmethod(lambda p, q: p / q)
    sqrt = staticmethod(math.sqrt)


def _field_by_solve(M, gamma, a, b):
    """(vec dM, dgamma) with Omega = L_gamma^{-1} M from an mpmath solve (eq:M-O, eq:motion-general)."""
    n = len(gamma)
    pairs = rx.pairs(n)
    M = mpmath.matrix([[mpmath.mpf(v) for v in row] for row in M])
    g = mpmath.matrix([mpmath.mpf(v) for v in gamma])
    e = mpmath.matrix([0] * (n - 1) + [1])

    def wedge(u, v):
        return u * v.T - v * u.T

    def L(Om):  # J Om + Om J + b (Om g) ^ g = 2 Om + a (Om e) ^ e + b (Om g) ^ g
        return 2 * Om + a * wedge(Om * e, e) + b * wedge(Om * g, g)

    cols = []
    for i, j in pairs:
        B = mpmath.zeros(n, n)
        B[i, j], B[j, i] = 1, -1
        LB = L(B)
        cols.append([LB[p, q] for p, q in pairs])
    A = mpmath.matrix(cols).T
    w = mpmath.lu_solve(A, mpmath.matrix([M[i, j] for i, j in pairs]))
    Om = mpmath.zeros(n, n)
    for k, (i, j) in enumerate(pairs):
        Om[i, j], Om[j, i] = w[k], -w[k]
    Md = M * Om - Om * M
    gd = -(Om * g)
    return [Md[i, j] for i, j in pairs] + [gd[i] for i in range(n)]


@pytest.mark.parametrize("n", range(3, 13))
def test_structured_field_matches_mpmath_solve(n):
    """The assembly heyoka compiles, at 40 digits, equals the solve route to ~1e-35 (it is exact
    algebra: no cancellation hides an error); on floats and through NumPy within a few ulp of |field|."""
    a, b = mpmath.mpf(-3) / 10, mpmath.mpf(4) / 5
    M0, g0 = families.draw("generic", n, float(a), float(b), seed=40 + n, count=1)
    M, g = M0[0], g0[0]
    with mpmath.workdps(DPS):
        gm = [mpmath.mpf(v) for v in g]
        norm = mpmath.sqrt(sum(v * v for v in gm))
        gm = [v / norm for v in gm]  # on the sphere to 40 digits (L_gamma^{-1} is derived there)
        want = _field_by_solve(M, gm, a, b)
        got = rx.vector_field([mpmath.mpf(v) for v in so.vec(M)], gm, a, b, MpOps)
        scale = max(abs(v) for v in want)
        assert max(abs(x - y) for x, y in zip(got, want)) <= mpmath.mpf(10) ** (5 - DPS) * scale
    want = np.array([float(v) for v in want])
    scale = float(scale)
    eps = np.finfo(float).eps
    on_floats = np.array(rx.vector_field(list(so.vec(M)), list(g), float(a), float(b), FloatOps))
    dM, dg = axisym.vector_field(M, g, float(a), float(b))
    numpy_form = np.concatenate([so.vec(dM), dg])
    oM, og = axisym.vector_field(M, g, float(a), float(b), method="matrix")
    matrix_form = np.concatenate([so.vec(oM), og])
    for got in (on_floats, numpy_form, matrix_form):
        assert np.max(np.abs(got - want)) <= 16 * n * eps * scale


def test_numpy_structured_field_broadcasts():
    """A batch of states with per-member a equals the members one by one."""
    M0, g0 = families.draw("generic", 5, 0.2, 1.0, seed=3, count=4)
    a = np.array([-1.0, 0.0, 0.5, 1.0])
    dM, dg = axisym.vector_field(M0, g0, a, 1.0)
    for k in range(4):
        one = axisym.vector_field(M0[k], g0[k], a[k], 1.0)
        assert np.array_equal(one[0], dM[k]) and np.array_equal(one[1], dg[k])
