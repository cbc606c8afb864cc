r"""Taylor's method compiled with LLVM (heyoka, Biscani & Izzo, MNRAS 504 (2021) 2614) on the derived fields.

heyoka integrates $\dot y = f(y)$ with an adaptive Taylor method of order $p = \lceil -\ln(\varepsilon)/2 + 1\rceil$
for tolerance $\varepsilon$ (its paper, eq. 31), choosing each step from the last two Taylor
coefficients so that the local error stays below $\varepsilon$ (relative for large states,
absolute for small). The systems are those of :mod:`simulate.integrators.heyoka_systems`, built from
``generated/expression_builders.py`` (derived expressions only).

Precision: ``"double"``, ``"real128"`` (quadruple, 113 bits) or an ``int`` number of bits for
heyoka's multiprecision ``real`` (:func:`bits_for_digits` converts digits). Ensembles in double
precision run in heyoka's batch (SIMD) mode, ``recommended_simd_size()`` trajectories per compiled
step; the threaded ensemble functions are not used (2–9× slower than batch mode on 2 cores).
Compiled integrators are cached on disk (:mod:`runtime.jit_cache`); the solution
reports the compile or load time in ``compile_seconds`` apart from the run time ``seconds``.

Compact mode (heyoka's loop-based code generation) compiles several times faster and runs slower;
``compact=None`` chooses it (:func:`default_compact`). Measured with the O(n^2) field (tol 1e-12,
2 shared cores): unrolled compiles in 2.1 / 3.6 / 5.8 / 9.6 / 18 s at n = 3 / 4 / 5 / 6 / 8 against
0.7–1.1 s compact, and steps about 2x faster; so unrolled pays only on long runs or when it is
already cached — a choice the planner's cost model makes (:mod:`simulate.scene.cost`) and passes here.
"""

from __future__ import annotations

import importlib.util
import math
import os
import sys
import time
from typing import Any

import numpy as np
from chaplygin_nd.runtime import jit_cache
from chaplygin_nd.runtime.expressions import HeyokaArithmetic
from chaplygin_nd.simulate.integrators import heyoka_systems, settings
from chaplygin_nd.simulate.integrators.base import Candidate, Pilot, Solution
from chaplygin_nd.simulate.integrators.registry import Integrator, register
from chaplygin_nd.simulate.integrators.settings import Calibration, Tolerance

__all__ = ["available", "integrate", "order_for", "bits_for_digits", "compiled_integrator",
           "default_tol", "default_compact", "cache_key"]


def available() -> bool:
    """True when heyoka can be imported (checked without importing it)."""
    return importlib.util.find_spec("heyoka") is not None


def order_for(tol: float) -> int:
    r"""heyoka's Taylor order for tolerance ``tol``: $p = \lceil -\ln(\mathrm{tol})/2 + 1\rceil$."""
    return int(math.ceil(-math.log(tol) / 2 + 1))


def bits_for_digits(digits: int) -> int:
    """Bits of a multiprecision ``real`` carrying ``digits`` decimal digits plus 8 guard bits."""
    return int(math.ceil(digits * math.log2(10))) + 8


def _kind(precision) -> tuple[str, int]:
    if precision in ("double", "float64"):
        return "double", 53
    if precision in ("real128", "quad"):
        return "real128", 113
    if isinstance(precision, int) and not isinstance(precision, bool) and precision >= 2:
        return "real", precision
    raise ValueError(f"precision {precision!r}: use 'double', 'real128' or a number of bits (int)")


def default_tol(precision) -> float:
    """Machine epsilon of the precision (heyoka's default tolerance)."""
    return 2.0 ** (1 - _kind(precision)[1])


class _Numbers:
    """Conversions between floats/strings and the integrator's floating-point type."""

    def __init__(self, hy, kind: str, bits: int):
        self.hy, self.kind, self.bits = hy, kind, bits

    def scalar(self, v):
        if self.kind == "double":
            return float(v)
        if self.kind == "real128":
            return self.hy.real128(str(v) if not isinstance(v, float) else v)
        return self.hy.real(v if isinstance(v, float) else str(v), self.bits)

    def array(self, values):
        values = np.asarray(values, dtype=object if self.kind != "double" else float)
        if self.kind == "double":
            return np.array(values, dtype=float)
        flat = [self.scalar(v) for v in values.ravel()]
        if self.kind == "real128":
            return np.array(flat, dtype=self.hy.real128).reshape(values.shape)
        return np.array(flat).reshape(values.shape)


def default_compact(system, kind: str) -> bool:
    """Compact mode unless told otherwise (see the module docstring); ``system`` and ``kind`` are
    accepted for a future rule."""
    return True


def cache_key(system, precision, tol: float, compact: bool, batch: int, opt_level: int = 3) -> dict:
    """What identifies a compiled integrator in :mod:`runtime.jit_cache` (known without importing
    heyoka or building the graph: the planner asks the cache state with it)."""
    from importlib.metadata import version

    kind, bits = _kind(precision)
    return {"object": "taylor_adaptive", "system": system.name, "parameters": list(system.parameters),
            "tol": repr(float(tol)), "precision": f"{kind}:{bits}", "compact": bool(compact),
            "batch": int(batch), "heyoka": version("heyoka")} | \
        ({} if opt_level == 3 else {"opt_level": int(opt_level)})


def cache_state(system, precision, tol: float, compact: bool, batch: int) -> str:
    """Where the compiled integrator of :func:`cache_key` is now: ``in memory``, ``on disk`` or
    ``cold`` (:func:`runtime.jit_cache.cache_state`; what the cost model charges for it)."""
    return jit_cache.cache_state(cache_key(system, precision, tol, compact, batch))


def compiled_integrator(system, precision="double", tol=None, compact=None, batch: int = 1,
                        cache: bool = True, opt_level: int = 3):
    r"""``(integrator, seconds, how)``: a heyoka Taylor integrator of ``system``
    (:class:`heyoka_systems.System`) at ``precision``, tolerance ``tol`` (default: epsilon),
    ``batch`` trajectories per step (double only), from the disk cache when possible
    (``how`` = "cold compile" / "warm load" / "in memory"; ``seconds`` of that). ``opt_level``:
    LLVM's optimisation level (heyoka's default 3). In compact mode level 1 compiled 1.1–2x faster
    and gave bit-identical orbits at the same speed (the evidence rows' tangent systems, n = 4..7,
    measured side by side); level 0 changed the bits and ran 2.5x slower."""
    kind, bits = _kind(precision)
    tol = default_tol(precision) if tol is None else float(tol)
    if compact is None:
        compact = default_compact(system, kind)
    if batch > 1 and kind != "double":
        raise ValueError("batch mode needs double precision")
    token = ("taylor_adaptive", system.name, system.parameters, kind, bits, tol, bool(compact),
             int(batch), bool(cache), int(opt_level))
    hit = jit_cache.memory_hit(token)
    if hit is not None:  # a warm call: one dictionary lookup, no graph, no hash
        return hit, 0.0, "in memory"
    import heyoka as hy

    key = cache_key(system, precision, tol, compact, batch, opt_level)
    ops = HeyokaArithmetic(hy, kind, bits)
    numbers = _Numbers(hy, kind, bits)

    def build():
        eqs = system.equations(hy, ops)
        npar = len(system.parameters)
        if batch > 1:
            return hy.taylor_adaptive_batch(eqs, np.zeros((system.dim, batch)),
                                            pars=np.zeros((npar, batch)), tol=tol,
                                            compact_mode=compact, opt_level=opt_level)
        state = numbers.array(np.zeros(system.dim))
        pars = numbers.array(np.zeros(npar))
        if kind == "double":
            return hy.taylor_adaptive(eqs, state, pars=pars, tol=tol, compact_mode=compact,
                                      opt_level=opt_level)
        if kind == "real128":
            return hy.taylor_adaptive(eqs, state, pars=pars, tol=hy.real128(tol),
                                      compact_mode=compact, fp_type=hy.real128, opt_level=opt_level)
        return hy.taylor_adaptive(eqs, state, pars=pars, tol=hy.real(tol, bits),
                                  compact_mode=compact, fp_type=hy.real, prec=bits,
                                  opt_level=opt_level)

    return jit_cache.load_or_build(key, build, use_disk=cache,
                                   source=lambda: system.fingerprint(hy, ops),
                                   expect=_integrator_types(hy), token=token)


def _integrator_types(hy) -> tuple[type, ...]:
    """The classes a cached integrator may have (a loaded object of another type is rebuilt)."""
    names = ("taylor_adaptive_dbl", "taylor_adaptive_f128", "taylor_adaptive_real",
             "taylor_adaptive_batch_dbl")
    return tuple(getattr(hy, k) for k in names if hasattr(hy, k))


def integrate(field, y0: np.ndarray, t: np.ndarray, tol: float | None = None,
              precision="double", compact: bool | None = None, batch: bool | int = True,
              cache: bool = True, pars=None, progress=None) -> Solution:
    r"""Integrate ``field`` (a :class:`simulate.dynamics.field.FullField`, :class:`simulate.dynamics.field.ReducedField`,
    or a :class:`heyoka_systems.System` with parameter values ``pars``) from ``y0`` ``(count, dim)``
    over the increasing times ``t``. ``batch``: True (SIMD width), an int, or False (one trajectory
    per integrator). Multiprecision runs return mpmath values in ``y_high``. Domain: as the field."""
    import heyoka as hy

    if isinstance(field, heyoka_systems.System):
        system, values = field, list(pars)
    else:
        system, values = heyoka_systems.for_field(field)
    kind, bits = _kind(precision)
    tol = default_tol(precision) if tol is None else float(tol)
    y0 = np.atleast_2d(np.asarray(y0, dtype=float))
    t = np.asarray(t, dtype=float)
    count = y0.shape[0]
    width = (hy.recommended_simd_size() if batch is True else int(batch or 1)) if kind == "double" else 1
    width = max(1, min(width, count)) if count > 1 else 1
    ta, compile_seconds, how = compiled_integrator(system, precision, tol, compact, width, cache)
    restart = getattr(progress, "restart", None)
    if restart is not None:
        restart()  # a run budget measures the integration, not the compile or load before it
    numbers = _Numbers(hy, kind, bits)
    out = np.empty((len(t), count, system.dim))
    high = np.empty((len(t), count, system.dim), dtype=object) if kind != "double" else None
    steps = 0
    passes = -(-count // width)  # the members run in this many passes, one after the other
    watch = _watch(progress, float(t[0]), float(t[-1]), passes) if progress is not None else None
    start = time.perf_counter()
    if width > 1:
        for s in range(0, count, width):
            if watch is not None:
                watch.done = s // width
            chunk = y0[s:s + width]
            used = chunk.shape[0]
            block = np.concatenate([chunk, np.repeat(chunk[-1:], width - used, 0)])  # pad
            ta.state[:] = block.T
            ta.pars[:] = np.repeat(np.asarray(values, float)[:, None], width, 1)
            ta.set_time(float(t[0]))
            _, states = ta.propagate_grid(np.repeat(t[:, None], width, 1), callback=watch)
            if watch is not None:
                watch.raise_error()
            for lane, (outcome, _, _, n) in enumerate(ta.propagate_res):
                _check(hy, outcome, system, ta.time[lane])
                steps = max(steps, n)
            out[:, s:s + used] = np.moveaxis(states, 2, 1)[:, :used]
            if progress is not None:  # the whole work done: this pass of ``passes``
                progress(float(t[0]) + (s // width + 1) / passes * (float(t[-1]) - float(t[0])))
    else:
        grid = numbers.array(t)
        for e in range(count):
            if watch is not None:
                watch.done = e
            ta.state[:] = numbers.array(y0[e])
            ta.pars[:] = numbers.array(values)
            ta.time = numbers.scalar(float(t[0]))
            outcome, _, _, n, _, states = ta.propagate_grid(grid, callback=watch)
            if watch is not None:
                watch.raise_error()
            _check(hy, outcome, system, ta.time)
            steps += n
            done = e + 1
            if kind == "double":
                out[:, e] = states
            else:
                import mpmath

                assert high is not None  # allocated for every precision but double
                with mpmath.workprec(bits):
                    high[:, e] = np.vectorize(lambda v: mpmath.mpf(str(v)), otypes=[object])(states)
                out[:, e] = np.vectorize(float, otypes=[float])(high[:, e])
            if progress is not None:  # the whole work done: this member of ``count``
                progress(float(t[0]) + done / count * (float(t[-1]) - float(t[0])))
    seconds = time.perf_counter() - start
    label = {"double": "double", "real128": "real128"}.get(kind, f"real {bits} bits")
    mode = ("compact" if ta.compact_mode else "unrolled") + (f", batch {width}" if width > 1 else "")
    return Solution(t=t, y=out, method=f"heyoka Taylor, order {ta.order}, tol {tol:.3g}, {label}",
                    steps=steps, calls=steps, seconds=seconds, y_high=high,
                    note=f"{system.name}; {mode}; {how} {compile_seconds:.3f} s",
                    compile_seconds=compile_seconds)


def _watch(progress, t0: float, t_end: float, passes: int):
    """A step callback for ``propagate_grid`` that reports the time reached to ``progress`` (which
    may stop a run: non-finite time, a projected cost past the limit). With the ensemble run in
    ``passes`` passes (``callback.done`` of them finished) the time reported is that of the whole
    work done, $t_0 + (\text{done} + (t - t_0)/(t_1 - t_0))(t_1 - t_0)/\text{passes}$, so a projection
    from it covers every pass. heyoka cannot carry a Python exception through its loop, so the
    callback stops the integration and :meth:`raise_error` re-raises the exception afterwards. A
    closure, not an object: heyoka may copy the callback."""
    error: list[BaseException] = []
    span = t_end - t0

    def callback(ta) -> bool:
        try:
            reached = float(np.min(np.asarray(ta.time, dtype=float)))
            if passes > 1 and span > 0 and math.isfinite(reached):
                reached = t0 + (watch.done + (reached - t0) / span) * span / passes
            progress(reached)
        except Exception as exc:  # noqa: BLE001 - re-raised by raise_error
            error.append(exc)
            return False
        return True

    def raise_error() -> None:
        if error:
            raise error[0]

    watch: Any = callback  # a function with two attributes: raise_error and done
    watch.raise_error = raise_error
    watch.done = 0
    return watch


def _check(hy, outcome, system, reached) -> None:
    """Raise unless the integration reached the last output time. A non-finite state is a
    :class:`simulate.integrators.stops.NonFinite` (exit 2 in the command line), naming the time reached."""
    if outcome == hy.taylor_outcome.time_limit:
        return
    from chaplygin_nd.simulate.integrators.stops import NonFinite, fmt

    if outcome == hy.taylor_outcome.err_nf_state:
        raise NonFinite(f"the state of {system.name} is not finite at t = {fmt(float(reached))} "
                        "(heyoka: non-finite state or step size; are a, b or the scale too large?)")
    raise RuntimeError(f"heyoka stopped early on {system.name} at t = {fmt(float(reached))}: {outcome}")


#: Environment variable that hides heyoka from the planner (the base install, for tests).
WITHOUT_HEYOKA = "CHAPLYGIN_ND_WITHOUT_HEYOKA"


def usable() -> bool:
    """heyoka is importable and not hidden by ``CHAPLYGIN_ND_WITHOUT_HEYOKA=1``."""
    return available() and os.environ.get(WITHOUT_HEYOKA, "") in ("", "0")


def _run(f, y0, t, s: Tolerance, *, checked, progress=None, compact=None) -> Solution:
    checked(t[0], y0)  # a non-finite start is named here (heyoka would only say nan)
    return integrate(f, y0, t, tol=s.tol, precision=s.precision, compact=compact,
                     progress=progress)


def _describe(s) -> str:
    return f"heyoka Taylor, tol {s.tol:.3g}" + ("" if s.precision == "double" else f", {s.precision}")


# -- what a run would cost (simulate.scene.cost; constants measured by bench/bench_scaling.py) --

#: N_Taylor = N_DOP853 * rtol^(1/8) / STEP_RATIO: Taylor steps of order p barely depend on the
#: tolerance while DOP853's scale as rtol^(1/8) (measured over n = 3..12, tol 1e-8..1e-14; spread
#: 0.070-0.101).
STEP_RATIO = 0.082
#: Seconds per decomposition operation and order^2 of one Taylor step (compact, unrolled).
KAPPA = {True: 0.25e-9, False: 0.13e-9}
#: A step of a batch of the SIMD width costs this many single steps.
BATCH_STEP = 1.3
HEYOKA_IMPORT = 1.0
DISK_LOAD = 0.03
SIMD = 4


def decomposition_size(system_name: str, n: int) -> int:
    """Elementary operations of heyoka's decomposition of a system (fitted to the measured sizes:
    full field 216 / 672 / 1416 / 9456 at n = 4 / 8 / 12 / 32; the reconstruction adds the
    $2n^3$ of $g\\Omega$; the reduced 7D field 135)."""
    if system_name.startswith("reduced"):
        return 135
    size = 9 * n * n + 12 * n + 20
    if "reconstruction" in system_name:
        size += 2 * n**3 + 3 * n * n
    return size


def _startup(system_name: str, n: int, compact: bool, state: str) -> float:
    """Compile (compact 0.6 + 1.3e-4 D s, unrolled 0.3 + 0.025 D s for D operations), or load from
    disk (:data:`DISK_LOAD`), plus importing heyoka when it is not yet imported."""
    imported = 0.0 if "heyoka" in sys.modules else HEYOKA_IMPORT
    D = decomposition_size(system_name, n)
    if state == "in memory":
        return 0.0
    if state == "on disk":
        return imported + DISK_LOAD
    return imported + (0.6 + 1.3e-4 * D if compact else 0.3 + 0.025 * D)


def predict_cost(p: Pilot, tol: float) -> list[Candidate]:
    """heyoka compact and unrolled: Taylor steps from the DOP853 pilot's (:data:`STEP_RATIO`), a
    step $\\kappa D p^2$ (:data:`KAPPA`), batches of the SIMD width, and the start-up of each
    compile-cache state. ``[]`` when heyoka is not installed."""
    if importlib.util.find_spec("heyoka") is None:
        return []
    count = p.y0.shape[0]
    width = max(1, min(SIMD, count)) if count > 1 else 1
    batches = math.ceil(count / width)
    taylor_steps = max(1.0, p.rate * p.span * max(p.rtol, 2.2e-14) ** 0.125 / STEP_RATIO)
    order = order_for(tol)
    D = decomposition_size(p.system.name, p.n)  # type: ignore[attr-defined]
    out = []
    for compact in (True, False):
        state = cache_state(p.system, "double", tol, compact, width)
        step = KAPPA[compact] * D * order**2 * (BATCH_STEP if width > 1 else 1.0)
        out.append(Candidate("heyoka", compact, _startup(p.system.name, p.n, compact, state),  # type: ignore[attr-defined]
                             batches * taylor_steps * step, state))
    return out


#: Measured by ``chaplygin bench calibration`` against heyoka in real128 (rounded up); in real128
#: the same ratio K, the rounding scaled by 2^-60, the floor that of quadruple precision.
CALIBRATION = (("heyoka", Calibration(measured=12.0, rounding=1.4e-13, floor=2.0 ** -52)),
               ("real128", Calibration(measured=12.0, rounding=1.4e-13 * 2.0 ** -60,
                                       floor=2.0 ** -112)))
HEYOKA = register(Integrator(
    "heyoka", Tolerance, _run,
    calibrate=lambda target, span, step=0.01, dps=30, precision="double":
        settings.tolerance("heyoka", target, precision, span),
    error=settings.tolerance_error, describe=_describe, available=usable,
    auto=0, reference=1, costed=True, cost=predict_cost, calibration=CALIBRATION))
