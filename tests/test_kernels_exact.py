r"""Every generated kernel against the derived expression it was emitted from.

1. *Three-way exact check* at rational points (dyadic, so that the float inputs are exact): the
   exact SymPy value of the derived expression = its mpmath evaluation at 50 digits (to 1e-45
   relative) = the NumPy kernel (to the float bound below).
2. *Fidelity on seeded samples*: NumPy kernel vs the 50-digit mpmath evaluation of the derived
   expression with exact constants (:mod:`symbolic.exact.mpmath_eval`), error bounded by
   ``FIDELITY_ULPS`` machine epsilons times the formula's condition scale
   $\lvert f\rvert_{\mathrm{abs}}$ (absolute-value evaluation; Higham §3.1).

The kernel list is read from :data:`symbolic.codegen.kernels.MODULES`, so a new kernel is covered here
without a new test. Independent references (linear solves, the definitions) and the hard cases
live in test_kernels_axisym.py, test_kernels_fourd.py and test_kernels_sphere3d.py.
"""

from __future__ import annotations

import importlib

import mpmath
import numpy as np
import pytest
import sympy as sp
from chaplygin_nd.symbolic.codegen import kernels as codegen
from chaplygin_nd.symbolic.codegen.kernels import MODULES, kernels_of
from chaplygin_nd.symbolic.exact.mpmath_eval import mp_abs_eval, mp_eval

EPS = np.finfo(float).eps
#: Straight-line float evaluation of a formula of depth k has error <= gamma_k |f|_abs with
#: gamma_k ~ k u; our kernels have depth < 40, so 64 eps (= 128 u) is the documented bound.
FIDELITY_ULPS = 64


def _all_kernels(config):
    """Every kernel, derived once per run: by the first pytest-xdist worker that collects this
    module, unpickled by the other (conftest.derived_once), and left in codegen.KERNELS
    (kernels_of's memo) so that test_codegen's regeneration in either worker reuses them
    instead of deriving them again."""
    from conftest import derived_once

    derived = derived_once(config, "codegen-kernels",
                           lambda: {producer: kernels_of(producer) for _, producer in MODULES})
    codegen.KERNELS.update(derived)
    return [(stem, k) for stem, producer in MODULES for k in kernels_of(producer)]


def pytest_generate_tests(metafunc):
    """Parametrize the kernel tests at collection, from the derived kernels (see _all_kernels)."""
    if "kernel" not in metafunc.fixturenames:
        return
    kernels = _all_kernels(metafunc.config)
    if metafunc.function is test_three_way_exact:
        kernels = [(stem, k) for stem, k in kernels if _is_rational(k)]
    metafunc.parametrize("stem,kernel", [pytest.param(stem, k, id=f"{stem}.{k.name}")
                                         for stem, k in kernels])


def _sample(argument, rng, exact: bool):
    """Values for one argument inside the kernels' domain (exact dyadic rationals on request)."""
    name, m = argument.name, len(argument.symbols)

    def draw(lo, hi, size):
        v = rng.uniform(lo, hi, size)
        return np.round(v * 64) / 64 if exact else v

    if name in ("gamma", "gamma0"):
        if exact:  # dyadic points need not lie on the sphere: the formulas are rational functions
            return draw(-1, 1, m)
        v = rng.standard_normal(m)
        return v / np.linalg.norm(v)
    if name == "x" or name == "x0":
        return draw(-1, 1, 1)
    if name == "a":
        return draw(-1, 1, 1)
    if name in ("b", "t"):
        return draw(0.125, 3, 1)
    if name == "inertia":
        return draw(0.5, 2, m)
    if name in ("H", "h"):
        return draw(0, 1, 1)
    if name == "F2":
        return draw(2.5, 4, 1)  # F2 - 2bH > 0 for b <= 3, H <= 1/2 ... see the horizontal test
    if name == "r":
        v = draw(-1, 1, m)
        v[0], v[1] = abs(v[0]), abs(v[1])
        return v
    return draw(-1, 1, m)


def _point(kernel, rng, exact):
    args, values = [], {}
    for arg in kernel.arguments:
        v = _sample(arg, rng, exact)
        if arg.name == "F2":
            v = v * 0 + 2 * 3 * 1 + float(rng.uniform(0, 1))  # F2 >= 2 b H for b <= 3, H <= 1
        args.append(float(v[0]) if arg.scalar else v)
        for s, c in zip(arg.symbols, np.atleast_1d(v)):
            values[s] = float(c)
    return args, values


def _is_rational(kernel) -> bool:
    return all(not e.has(sp.sin, sp.cos, sp.sinc, sp.exp) and not any(
        p.exp.is_Rational and not p.exp.is_Integer for p in e.atoms(sp.Pow)) for e in kernel.outputs)


def test_fidelity_against_mpmath(stem, kernel):
    """NumPy kernel = 50-digit evaluation of the derived expression, within FIDELITY_ULPS eps |f|_abs."""
    fn = getattr(importlib.import_module(f"chaplygin_nd.generated.{stem}"), kernel.name)
    rng = np.random.default_rng([5, len(kernel.name), sum(map(ord, kernel.name))])
    mpmath.mp.dps = 50
    worst = 0.0
    for _ in range(12):
        args, values = _point(kernel, rng, exact=False)
        got = np.ravel(fn(*args))
        ref = mp_eval(list(kernel.outputs), values)
        scale = mp_abs_eval(list(kernel.outputs), values)
        assert got.shape == (len(ref),)
        for g_, r_, s_ in zip(got, ref, scale):
            err = abs(mpmath.mpf(float(g_)) - r_)
            bound = FIDELITY_ULPS * EPS * (s_ + mpmath.mpf(2) ** -1070)
            worst = max(worst, float(err / bound))
            assert err <= bound, (kernel.name, float(err), float(s_))
    assert worst <= 1.0


def test_three_way_exact(stem, kernel):
    """Exact SymPy value = mpmath (50 digits) = NumPy kernel, at dyadic rational points."""
    fn = getattr(importlib.import_module(f"chaplygin_nd.generated.{stem}"), kernel.name)
    rng = np.random.default_rng([7, sum(map(ord, kernel.name))])
    mpmath.mp.dps = 50
    for _ in range(2):
        args, values = _point(kernel, rng, exact=True)
        exact_subs = {s: sp.Rational(v) for s, v in values.items()}  # floats here are dyadic: exact
        exact = [sp.nsimplify(e.xreplace(exact_subs)) if e.has(sp.Abs) else e.xreplace(exact_subs)
                 for e in kernel.outputs]
        assert all(v.is_Rational for v in exact), kernel.name
        ref = mp_eval(list(kernel.outputs), values)
        scale = mp_abs_eval(list(kernel.outputs), values)
        got = np.ravel(fn(*args))
        for e, r_, g_, s_ in zip(exact, ref, got, scale):
            e_mp = mpmath.mpf(int(e.p)) / int(e.q)
            assert abs(r_ - e_mp) <= mpmath.mpf(10) ** -45 * (s_ + 1)
            assert abs(mpmath.mpf(float(g_)) - e_mp) <= FIDELITY_ULPS * EPS * (s_ + mpmath.mpf(2) ** -1070)


def test_kernels_broadcast_and_chunk():
    """A batch over several chunks, parameters as batch arrays, and constant outputs all broadcast:
    the chunked result, the one-call result (a batch of at most CHUNK points, evaluated on column
    views) and the point-by-point result agree exactly (same operations, same order)."""
    from chaplygin_nd.generated import axisym
    from chaplygin_nd.generated._batching import CHUNK

    rng = np.random.default_rng(11)
    count = 3 * CHUNK + 5
    g = rng.standard_normal((count, 4))
    g /= np.linalg.norm(g, axis=-1, keepdims=True)
    M = rng.standard_normal((count, 6))
    a = rng.uniform(-1, 1, count)
    out = axisym.angular_velocity_axisym_4d(M, g, a, 2.0)
    assert out.shape == (count, 6)
    for i in (0, CHUNK - 1, CHUNK, count - 1):
        assert np.array_equal(out[i], axisym.angular_velocity_axisym_4d(M[i], g[i], a[i], 2.0))
    for small in (1, 7, CHUNK):
        assert np.array_equal(out[:small], axisym.angular_velocity_axisym_4d(M[:small], g[:small],
                                                                             a[:small], 2.0))
    p = axisym.p_coefficients_4d(M[:7].reshape(7, 1, 6), g[:2])  # constant entries broadcast
    assert p.shape == (7, 2, 5, 2) and np.all(p[..., 4, 0] == 1) and np.all(p[..., 4, 1] == 0)
    assert axisym.Delta(0.5, 0.2, 1.0).shape == (1,)
    with pytest.raises(ValueError, match="gamma must have shape"):
        axisym.angular_velocity_axisym_4d(M[:3], g[:3, :3], 0.1, 1.0)
