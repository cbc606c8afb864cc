r"""3D kernels with a general diagonal inertia (Section 2.1) against a 50-digit mpmath solve of
eq:mom3D, $M = \mathbb{I}\Omega + b\,\gamma\times(\Omega\times\gamma)$, hard cases included.

Bound: ``BOUND_ULPS`` eps times the condition scale $\lVert L_\gamma^{-1}\rVert_2\lVert M\rVert$ for
$\Omega$ and $\dot\gamma$, times $\lVert M\rVert$ more for $\dot M$ and $H$.
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
from chaplygin_nd.generated import sphere3d as g

EPS = np.finfo(float).eps
BOUND_ULPS = 8
CASES = [("generic", 1.0, 1.0), ("b=1e6", 1e6, 1.0), ("b=1e-12", 1e-12, 1.0),
         ("|M|=1e-150", 1.0, 1e-150), ("|M|=1e150", 1.0, 1e150), ("pole", 1.0, 1.0)]


@pytest.mark.parametrize("name,b,scale", CASES, ids=[c[0] for c in CASES])
def test_sphere3d_against_solve(name, b, scale):
    mpmath.mp.dps = 50
    rng = np.random.default_rng([3, CASES.index((name, b, scale))])
    for _ in range(4):
        inertia = rng.uniform(0.5, 3.0, 3)
        gm = [mpmath.mpf(0), mpmath.mpf(0), mpmath.mpf(1)] if name == "pole" else \
            [mpmath.mpf(float(c)) for c in rng.standard_normal(3)]
        nrm = mpmath.sqrt(sum(c * c for c in gm))
        gm = [c / nrm for c in gm]
        gf = np.array([float(c) for c in gm])
        M = rng.standard_normal(3) * scale
        G = mpmath.matrix(gm)
        L = mpmath.diag([mpmath.mpf(float(c)) for c in inertia]) + mpmath.mpf(b) * (
            (G.T * G)[0] * mpmath.eye(3) - G * G.T)
        Om = mpmath.lu_solve(L, mpmath.matrix([mpmath.mpf(float(c)) for c in M]))
        Mm = mpmath.matrix([mpmath.mpf(float(c)) for c in M])
        cross = lambda p, r: [p[1] * r[2] - p[2] * r[1], p[2] * r[0] - p[0] * r[2], p[0] * r[1] - p[1] * r[0]]  # noqa: E731
        ref_field = cross(Mm, Om) + cross(G, Om)
        ell = 1 / np.linalg.eigvalsh(np.array(L.tolist(), dtype=float)).min()
        m = float(np.linalg.norm(M))
        H = mpmath.fsum(Mm[i] * Om[i] for i in range(3)) / 2

        def ulps(got, ref, s):
            return max(float(abs(mpmath.mpf(float(x)) - r)) for x, r in zip(np.ravel(got), ref)) / (EPS * s)

        assert ulps(g.angular_velocity_3d(M, gf, inertia, b), [Om[i] for i in range(3)], ell * m) <= BOUND_ULPS
        f = g.vector_field_3d(M, gf, inertia, b)
        assert ulps(f[:3], ref_field[:3], ell * m * m) <= BOUND_ULPS
        assert ulps(f[3:], ref_field[3:], ell * m) <= BOUND_ULPS
        I3 = g.integrals_3d(M, gf, inertia, b)
        assert ulps(I3[2:], [H], ell * m * m) <= BOUND_ULPS
        assert ulps(I3[:1], [mpmath.fsum(Mm[i] * G[i] for i in range(3))], m) <= BOUND_ULPS
