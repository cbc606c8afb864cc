"""p(lambda, sigma) = det(M + sigma gamma gamma^T - lambda Id) (eq:pol-first-integrals) on batches:
runtime.axisym.p_coefficients (generated closed form for n = 3, 4; batched eigenvalues otherwise),
against mpmath at 40 digits (determinants at n + 1 points in lambda, interpolated exactly)."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
from chaplygin_nd.runtime.axisym import p_coefficients
from chaplygin_nd.simulate.dynamics import families
from chaplygin_nd.simulate.scene.outputs import p_coefficients as output_p


def _reference(M, g):
    n = len(g)
    with mpmath.workdps(40):
        Mm = mpmath.matrix(M.tolist())
        G = mpmath.matrix(g.tolist())
        lams = [mpmath.mpf(k) for k in range(n + 1)]
        V = mpmath.matrix([[lam**i for i in range(n + 1)] for lam in lams])
        out = np.empty((n + 1, 2))
        dets = []
        for sigma in (0, 1):
            vals = [mpmath.det(Mm + sigma * G * G.T - lam * mpmath.eye(n)) for lam in lams]
            dets.append(mpmath.lu_solve(V, mpmath.matrix(vals)))
        for i in range(n + 1):
            out[i, 0] = float(dets[0][i])
            out[i, 1] = float(dets[1][i] - dets[0][i])
    return out


@pytest.mark.parametrize("n", [3, 4, 5, 6, 7])
def test_p_coefficients_against_mpmath(n):
    M0, g0 = families.draw("generic", n, 0.3, 1.0, seed=5 + n, count=3)
    got = p_coefficients(M0, g0)
    assert got.shape == (3, n + 1, 2)
    assert np.array_equal(output_p(M0, g0), got)
    for k in range(3):
        want = _reference(M0[k], g0[k])
        scale = (1 + np.linalg.norm(M0[k], 2)) ** n
        assert np.max(np.abs(got[k] - want)) <= 64 * n * np.finfo(float).eps * scale


def test_p_coefficients_broadcast_over_samples_and_members():
    M0, g0 = families.draw("generic", 5, 0.3, 1.0, seed=2, count=4)
    M, g = np.stack([M0, 2 * M0]), np.stack([g0, g0])
    got = p_coefficients(M, g)
    assert got.shape == (2, 4, 6, 2)
    for s in range(2):
        for e in range(4):
            assert np.allclose(got[s, e], p_coefficients(M[s, e], g[s, e]), rtol=0, atol=1e-12)
