"""The heyoka back end: builders equal the NumPy kernels; heyoka.real and our mpmath Taylor method
agree to 28 digits; heyoka double agrees with DOP853; batch equals single runs; a corrupt or stale
cache entry is rebuilt, never trusted.

JIT work is kept small: compact mode, short horizons, and one cache folder per test session
(tests/conftest.py: each system compiles once per run, never into the user's cache).
"""

from __future__ import annotations

import math
import pickle

import mpmath
import numpy as np
import pytest
from chaplygin_nd.generated import expression_builders as eb
from chaplygin_nd.generated import reduced as gred
from chaplygin_nd.generated import sphere3d as g3
from chaplygin_nd.runtime import axisym
from chaplygin_nd.runtime import expressions as rx
from chaplygin_nd.runtime import jit_cache as heyoka_cache
from chaplygin_nd.simulate.dynamics import families, so
from chaplygin_nd.simulate.dynamics.field import FullField, ReducedField
from chaplygin_nd.simulate.integrators import dop853, heyoka_systems, heyoka_taylor, taylor

heyoka_only = pytest.mark.skipif(not heyoka_taylor.available(),
                                 reason="heyoka is not installed (extra 'fast'); the SciPy path is tested elsewhere")


class FloatOps:
    """The builders' ``ops`` in float64."""

    rational = staticmethod(lambda p, q: p / q)
    sqrt = staticmethod(math.sqrt)


@pytest.mark.parametrize("n", [3, 4, 5, 7])
def test_any_n_assembly_equals_runtime_numpy(n):
    """chaplygin_nd.runtime.expressions (the assembly heyoka compiles) on floats = runtime.axisym on arrays."""
    M0, g0 = families.draw("generic", n, -0.3, 0.8, seed=11 + n, count=3)
    for M, g in zip(M0, g0):
        got = np.array(rx.vector_field(list(so.vec(M)), list(g), -0.3, 0.8, FloatOps), float)
        dM, dg = axisym.vector_field(M, g, -0.3, 0.8, method="matrix")
        want = np.concatenate([so.vec(dM), dg])
        assert np.max(np.abs(got - want)) <= 1e-14 * max(1.0, np.max(np.abs(want)))


def test_builders_equal_numpy_kernels():
    """Each emitted builder, evaluated on floats, equals the NumPy kernel emitted from the same
    derived expression (reduced 7D field, 3D general inertia, the n = 4 component field)."""
    rng = np.random.default_rng(3)
    r = rng.uniform(-1, 1, 7)
    assert np.allclose(eb.reduced_field(list(r), 0.3, 0.9, FloatOps), gred.reduced_field(r, 0.3, 0.9),
                       rtol=1e-13, atol=1e-15)
    M, gam, inertia = rng.normal(size=3), rng.normal(size=3), np.array([1.0, 1.7, 2.2])
    gam /= np.linalg.norm(gam)
    assert np.allclose(eb.vector_field_3d(list(M), list(gam), list(inertia), 0.4, FloatOps),
                       g3.vector_field_3d(M, gam, inertia, 0.4), rtol=1e-13, atol=1e-15)
    M4, g4 = families.draw("generic", 4, 0.5, 1.0, seed=2)
    comp = eb.vector_field_axisym_4d(list(so.vec(M4[0])), list(g4[0]), 0.5, 1.0, FloatOps)
    full = rx.vector_field(list(so.vec(M4[0])), list(g4[0]), 0.5, 1.0, FloatOps)
    assert np.allclose(comp, full, rtol=1e-13, atol=1e-15)


def test_builders_are_exact_in_mpmath():
    """The builders carry exact rationals: evaluated in mpmath at 50 digits they agree with the
    float kernels to double rounding only (no float constant hides in them)."""
    ops = type("MpOps", (), {"rational": staticmethod(lambda p, q: mpmath.mpf(p) / q),
                             "sqrt": staticmethod(mpmath.sqrt)})
    with mpmath.workdps(50):
        c = eb.inverse_coefficients(mpmath.mpf(1) / 3, mpmath.mpf("0.5"), mpmath.mpf(1), ops)
        assert all(isinstance(v, mpmath.mpf) for v in c)
    c64 = eb.inverse_coefficients(1 / 3, 0.5, 1.0, FloatOps)
    assert max(abs(float(u) - v) / abs(v) for u, v in zip(c, c64) if v) < 1e-15


def _exact_point(seed=7):
    """A generic n = 4 point with gamma0 = (1/2, 1/2, 1/2, 1/2) exactly on S^3 in binary floats:
    the two 30-digit methods then integrate the same ODE (the derived L_gamma^{-1} formula of
    heyoka holds on the sphere only; our mpmath Taylor solves L_gamma at the actual gamma)."""
    M0, _ = families.draw("generic", 4, 0.5, 1.0, seed=seed)
    return M0, np.full((1, 4), 0.5)


@heyoka_only
def test_heyoka_real_and_mpmath_taylor_agree_to_28_digits():
    """Two independent 30-digit references (heyoka.real, 108 bits, on the derived inverse formula;
    our fixed-point mpmath Taylor method, on a linear solve of L_gamma) agree to >= 28 digits over
    T = 20 on generic n = 4."""
    M0, g0 = _exact_point()
    f = FullField(4, 0.5, 1.0)
    y0 = f.pack(M0, g0)
    t = np.linspace(0.0, 20.0, 5)
    hy = heyoka_taylor.integrate(f, y0, t, precision=heyoka_taylor.bits_for_digits(30), tol=1e-32)
    mp = taylor.integrate(f, y0, t, dps=30)
    with mpmath.workdps(40):
        diff = max(abs(u - v) for u, v in zip(hy.y_high.ravel(), mp.y_high.ravel()))
        scale = max(abs(v) for v in mp.y_high.ravel())
    assert diff <= mpmath.mpf(10) ** -28 * max(1, scale), mpmath.nstr(diff, 5)
    assert "real 108 bits" in hy.method and hy.compile_seconds > 0


@heyoka_only
def test_heyoka_double_agrees_with_dop853_on_generic4d():
    """heyoka (tol 1e-13) and DOP853 (rtol = atol = 1e-13) agree to the accuracy target 1e-12 of
    scenes/generic4d.toml (to T = 20)."""
    M0, g0 = families.draw("generic", 4, 0.5, 1.0, seed=7)
    f = FullField(4, 0.5, 1.0)
    y0 = f.pack(M0, g0)
    t = np.linspace(0.0, 20.0, 201)
    hy = heyoka_taylor.integrate(f, y0, t, tol=1e-13, compact=True)
    dp = dop853.integrate(f, y0, t, rtol=1e-13, atol=1e-13)
    assert np.max(np.abs(hy.y - dp.y)) <= 1e-12
    assert hy.method.startswith(f"heyoka Taylor, order {heyoka_taylor.order_for(1e-13)}, tol 1e-13")


@heyoka_only
def test_batch_mode_equals_single_runs():
    """An ensemble in batch (SIMD) mode, including a padded last chunk, equals one run per member."""
    M0, g0 = families.draw("generic", 4, 0.5, 1.0, seed=3, count=11)
    f = FullField(4, 0.5, 1.0)
    y0 = f.pack(M0, g0)
    t = np.linspace(0.0, 5.0, 6)
    batched = heyoka_taylor.integrate(f, y0, t, tol=1e-13, compact=True, batch=4)
    single = heyoka_taylor.integrate(f, y0, t, tol=1e-13, compact=True, batch=False)
    assert "batch 4" in batched.note
    assert np.max(np.abs(batched.y - single.y)) <= 1e-13


@heyoka_only
def test_reduced_field_with_heyoka_matches_dop853():
    from chaplygin_nd.simulate.dynamics.so import reduced_invariants

    M0, g0 = families.draw("generic", 4, -0.4, 0.7, seed=21)
    r0 = reduced_invariants(M0, g0)
    f = ReducedField(-0.4, 0.7)
    t = np.linspace(0.0, 5.0, 11)
    hy = heyoka_taylor.integrate(f, r0, t, tol=1e-14, compact=True)
    dp = dop853.integrate(f, r0, t, rtol=1e-13)
    assert np.max(np.abs(hy.y - dp.y)) <= 1e-11


@heyoka_only
def test_corrupt_or_stale_cache_entry_is_rebuilt():
    """Truncating a cache file or changing its stored key makes the next run rebuild with a
    warning, and the result is still right."""
    system = heyoka_systems.sphere3d()
    y0 = np.array([[0.3, -0.2, 0.5, 0.6, 0.0, 0.8]])
    t = np.linspace(0.0, 2.0, 5)
    pars = [1.0, 1.5, 2.0, 0.3]
    first = heyoka_taylor.integrate(system, y0, t, tol=1e-13, compact=True, pars=pars)
    assert "cold compile" in first.note
    files = sorted(heyoka_cache.cache_dir().glob("*.pkl"))
    entry = next(p for p in files if pickle.loads(p.read_bytes())["key"].get("system") == system.name)
    heyoka_cache.forget_memory()
    warm = heyoka_taylor.integrate(system, y0, t, tol=1e-13, compact=True, pars=pars)
    assert "warm load" in warm.note and np.array_equal(warm.y, first.y)
    data = entry.read_bytes()
    entry.write_bytes(data[: len(data) // 2])  # truncated
    heyoka_cache.forget_memory()
    with pytest.warns(heyoka_cache.CacheWarning, match="corrupt"):
        again = heyoka_taylor.integrate(system, y0, t, tol=1e-13, compact=True, pars=pars)
    assert "cold compile" in again.note and np.array_equal(again.y, first.y)
    stored = pickle.loads(entry.read_bytes())
    stored["key"] = dict(stored["key"], code="0" * 16)  # an entry of other code
    entry.write_bytes(pickle.dumps(stored))
    heyoka_cache.forget_memory()
    with pytest.warns(heyoka_cache.CacheWarning, match="stale"):
        third = heyoka_taylor.integrate(system, y0, t, tol=1e-13, compact=True, pars=pars)
    assert np.array_equal(third.y, first.y)
    ref = dop853.integrate(lambda s, y: g3.vector_field_3d(y[..., :3], y[..., 3:], np.array(pars[:3]),
                                                           pars[3]), y0, t, rtol=1e-13)
    assert np.max(np.abs(first.y - ref.y)) <= 1e-11


def test_order_and_precision_helpers():
    assert heyoka_taylor.order_for(1e-13) == 16 and heyoka_taylor.order_for(2.0 ** -52) == 20
    assert heyoka_taylor.bits_for_digits(30) == 108
    with pytest.raises(ValueError, match="precision"):
        heyoka_taylor.default_tol("single")


@heyoka_only
@pytest.mark.parametrize("n", [3, 4, 6])
def test_compiled_angular_velocity_matches_numpy_runtime(n):
    """chaplygin_nd.runtime.compiled (heyoka cfunc on the derived L_gamma^{-1}) equals runtime.axisym (the NumPy
    coefficient kernel + einsum) to 16 ulps of max |Omega| over a batch with broadcast a, b."""
    from chaplygin_nd.runtime import compiled

    M, g = families.draw("generic", n, 0.5, 1.0, seed=1, count=40)
    a = np.linspace(-1.0, 1.0, 40)
    want = axisym.angular_velocity(M, g, a, 2.0, method="matrix")
    got = compiled.angular_velocity(M, g, a, 2.0)
    eps = np.finfo(float).eps
    assert got.shape == want.shape
    assert np.max(np.abs(got - want)) <= 16 * eps * np.max(np.abs(want))
