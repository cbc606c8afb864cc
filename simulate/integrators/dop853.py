r"""Explicit Runge–Kutta of order 8(5,3) (Dormand–Prince, DOP853) through SciPy.

Hairer, Nørsett, Wanner, *Solving ODEs I*, §II.10. Any field of the interface in
:mod:`simulate.integrators.base`; an ensemble is integrated as one stacked system, so error
control is over the whole ensemble. SciPy clamps ``rtol`` at $100\,\varepsilon \approx 2.2\times
10^{-14}$; ``atol`` is not clamped.
"""

from __future__ import annotations

import math
import time
from functools import partial

import numpy as np
from chaplygin_nd.simulate.integrators import settings
from chaplygin_nd.simulate.integrators.base import Candidate, Pilot, Solution
from chaplygin_nd.simulate.integrators.registry import Integrator, register
from chaplygin_nd.simulate.integrators.settings import Calibration, Tolerance
from chaplygin_nd.simulate.integrators.stops import RunStopped
from scipy.integrate import solve_ivp

__all__ = ["integrate", "pilot", "predict_cost"]

#: The pilot: at most this many steps, or (after two) this many seconds.
PILOT_STEPS = 8
PILOT_SECONDS = 0.05
#: Seconds of SciPy's dense output per sample and state component.
DENSE_OUTPUT = 2e-8
#: Seconds per DOP853 step that ``solve_ivp`` adds to the bare stepper of the pilot (its loop and
#: the dense output for the sample times: 3 more stages; measured 160-400 us on 2 loaded cores).
SOLVE_IVP_STEP = 2.5e-4


def integrate(field, y0: np.ndarray, t: np.ndarray, rtol: float = 1e-10,
              atol: float | None = None, progress=None, scheme: str = "DOP853") -> Solution:
    r"""Integrate $\dot y = f(t, y)$ with DOP853 from ``t[0]``, sampling at ``t`` (dense output is
    not used: SciPy steps onto every sample). Domain: any smooth field; ``rtol`` $\ge 2.2\cdot10^{-14}$.
    ``scheme = "RK45"`` uses SciPy's Dormand–Prince 5(4) instead (the independent run of
    ``--cross-check``, :mod:`simulate.scene.crosscheck`)."""
    y0 = np.asarray(y0, dtype=float)
    shape = y0.shape
    atol = rtol if atol is None else atol

    calls = [0]

    def flat(s, y):
        calls[0] += 1
        if progress is not None and calls[0] != 2:  # call 2: SciPy's probe for the first step
            progress(s)
        return field(s, y.reshape(shape)).ravel()

    start = time.perf_counter()
    sol = solve_ivp(flat, (t[0], t[-1]), y0.ravel(), method=scheme, t_eval=t,
                    rtol=max(rtol, 100 * np.finfo(float).eps), atol=atol)
    seconds = time.perf_counter() - start
    if sol.status != 0:
        raise RunStopped(f"{scheme} failed before t = {t[-1]:g}: {sol.message}")
    y = sol.y.T.reshape((len(t),) + shape)
    steps = (sol.nfev - 1) // (12 if scheme == "DOP853" else 6)
    return Solution(t=np.asarray(t), y=y, method=f"{scheme} rtol={rtol:g} atol={atol:g}",
                    steps=steps, calls=sol.nfev, seconds=seconds)


def pilot(field, y0: np.ndarray, t0: float, t_end: float, rtol: float) -> tuple[float, float]:
    """(steps per unit time, seconds per step) of DOP853 on ``field`` from the states ``y0``:
    :data:`PILOT_STEPS` steps or :data:`PILOT_SECONDS` (the cost model's measurement,
    :mod:`simulate.scene.cost`). ``FloatingPointError`` when the field is not finite or the
    pilot makes no progress."""
    from scipy.integrate import DOP853 as Stepper

    shape = y0.shape

    def finite_field(s, y):
        dy = field(s, y.reshape(shape)).ravel()
        if not np.isfinite(dy).all():  # SciPy's step-size loop never ends on a nan error norm
            raise FloatingPointError("the field is not finite in the DOP853 pilot")
        return dy

    if not np.isfinite(y0).all():
        raise FloatingPointError("the initial state is not finite")
    solver = Stepper(finite_field, t0, y0.ravel(), t_end,
                     rtol=max(rtol, 100 * np.finfo(float).eps), atol=rtol)
    start = time.perf_counter()
    steps = 0
    while solver.status == "running" and steps < PILOT_STEPS:
        solver.step()
        steps += 1
        if time.perf_counter() - start > PILOT_SECONDS and steps >= 2:
            break
    seconds = time.perf_counter() - start
    reached = solver.t - t0
    if not reached > 0 or not math.isfinite(reached) or not np.isfinite(solver.y).all():
        raise FloatingPointError("the DOP853 pilot made no progress")
    return steps / reached, seconds / steps


def predict_cost(p: Pilot, tol: float) -> list[Candidate]:
    """DOP853's run: the pilot's steps over the span, each its measured seconds plus
    :data:`SOLVE_IVP_STEP`, and the dense output (:data:`DENSE_OUTPUT` per sample and component)."""
    steps = p.rate * p.span
    return [Candidate("dop853", None, 0.0, steps * (p.per_step + SOLVE_IVP_STEP)
                      + DENSE_OUTPUT * p.samples * p.y0.size)]


def _run(f, y0, t, s: Tolerance, *, checked, progress=None, compact=None, scheme="DOP853"):
    return integrate(checked, y0, t, rtol=s.tol, atol=s.tol, progress=progress, scheme=scheme)


def _entry(name: str, scheme: str, **ranks) -> Integrator:
    return register(Integrator(
        name, Tolerance, partial(_run, scheme=scheme),
        calibrate=lambda target, span, step=0.01, dps=30, precision="double":
            settings.tolerance(name, target, precision, span),
        error=settings.tolerance_error,
        describe=lambda s: f"{scheme}, rtol = atol = {s.tol:.3g}",
        calibration=((name, CALIBRATION),), **ranks))


#: Measured by ``chaplygin bench calibration`` against heyoka in real128 (rounded up); the floor is
#: SciPy's clamp of rtol. RK45 shares DOP853's (the same error control, a lower order).
CALIBRATION = Calibration(measured=650.0, rounding=3.5e-12, floor=100 * float(np.finfo(float).eps))
DOP853 = _entry("dop853", "DOP853", auto=1, reference=0, costed=True, cost=predict_cost)
#: SciPy's Dormand–Prince 5(4): not chosen by the planner; a second route for tests and benches.
RK45 = _entry("rk45", "RK45", reduced=False, scene=False)
