"""The integrators: order, structure preservation, high-precision agreement, vectorised ensembles."""

from __future__ import annotations

import numpy as np
from chaplygin_nd.simulate.dynamics import families
from chaplygin_nd.simulate.dynamics.field import FullField
from chaplygin_nd.simulate.integrators import dop853, lie, taylor
from chaplygin_nd.simulate.scene.outputs import p_coefficients

N, A, B = 4, 0.5, 1.0


def _start(count=1, seed=7):
    M0, g0 = families.draw("generic", N, A, B, seed, count)
    f = FullField(N, A, B)
    return f, f.pack(M0, g0)


def test_rkmk4_has_order_four():
    """Halving the step divides the error by about 2^4 = 16."""
    f, y0 = _start()
    t = np.array([0.0, 2.0])
    ref = dop853.integrate(f, y0, t, rtol=1e-14, atol=1e-14).y[-1]
    errs = [np.max(np.abs(lie.integrate(f, y0, t, h=h).y[-1] - ref)) for h in (0.2, 0.1)]
    assert 11 < errs[0] / errs[1] < 22, errs


def test_rkmk4_keeps_sphere_and_spectrum_to_rounding():
    """|gamma| = 1 and the coefficients of p(lambda, sigma) (eq:iso-spectral) at a coarse step."""
    f, y0 = _start()
    t = np.linspace(0.0, 40.0, 5)
    sol = lie.integrate(f, y0, t, h=0.2)
    M, gamma = f.unpack(sol.y)
    assert np.max(np.abs(np.linalg.norm(gamma, axis=-1) - 1)) < 1e-14
    p = p_coefficients(M, gamma)
    assert np.max(np.abs(p - p[:1])) < 1e-13
    # while DOP853 at a loose tolerance drifts visibly: the property is the method's, not the flow's
    loose = dop853.integrate(f, y0, t, rtol=1e-5, atol=1e-5).y
    assert np.max(np.abs(np.linalg.norm(f.unpack(loose)[1], axis=-1) - 1)) > 1e-10


def test_taylor_reference_converges_in_precision():
    """30- and 40-digit runs agree to 1e-28; DOP853 at rtol 1e-13 agrees to 1e-11."""
    f, y0 = _start()
    t = np.array([0.0, 2.5, 5.0])
    r30 = taylor.integrate(f, y0, t, dps=30)
    r40 = taylor.integrate(f, y0, t, dps=40)
    diff = max(abs(x - y) for x, y in zip(r30.y_high.ravel(), r40.y_high.ravel(), strict=True))
    assert diff < 1e-28
    d = dop853.integrate(f, y0, t, rtol=1e-13, atol=1e-13)
    assert np.max(np.abs(d.y - r30.y)) < 1e-11


def test_taylor_reconstruction_matches_dop853():
    M0, g0 = families.draw("generic", N, A, B, 3)
    f = FullField(N, A, B, reconstruct=True, radius=0.7)
    from chaplygin_nd.simulate.dynamics.so import rotation_to
    y0 = f.pack(M0, g0, rotation_to(g0[0])[None], np.zeros((1, N)))
    t = np.array([0.0, 3.0])
    r = taylor.integrate(f, y0, t, dps=20)
    d = dop853.integrate(f, y0, t, rtol=1e-13, atol=1e-13)
    assert np.max(np.abs(r.y - d.y)) < 1e-11


def test_ensemble_is_vectorised_and_equals_single_runs():
    """One stacked DOP853 run of 5 initial conditions equals 5 separate runs (tolerance-level),
    with one right-hand-side call per stage for the whole ensemble."""
    f, y0 = _start(count=5, seed=9)
    t = np.array([0.0, 1.0, 3.0])
    sol = dop853.integrate(f, y0, t, rtol=1e-12, atol=1e-12)
    assert sol.y.shape == (3, 5, f.dim)
    for e in range(5):
        one = dop853.integrate(f, y0[e:e + 1], t, rtol=1e-12, atol=1e-12)
        assert np.max(np.abs(one.y[:, 0] - sol.y[:, e])) < 1e-10
    lie_sol = lie.integrate(f, y0, t, h=0.05)
    assert np.max(np.abs(lie_sol.y - sol.y)) < 1e-7
