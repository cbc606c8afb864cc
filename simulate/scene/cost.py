r"""What each integrator would cost for a scene, predicted before the run: the planner's method choice.

For each candidate the scene may use — heyoka compact, heyoka unrolled (Taylor + LLVM), DOP853 —
the predicted total is *start-up* (compile, or load from the compile cache, and heyoka's import;
the cache state is known: in memory / on disk / cold, :func:`simulate.integrators.heyoka_taylor.cache_state`) plus
*run* (the integration). The outputs cost the same for every candidate (they are computed from
the samples), so they do not enter the choice. The cheapest candidate wins; the plan line prints
every prediction.

How the run is predicted (no constant here is a guess; each was measured, see
``bench/bench_scaling.py``, on 2 shared cores):

* a **DOP853 pilot** — the scene's own field and initial conditions (the whole ensemble, as DOP853
  integrates it), :data:`PILOT_STEPS` steps or :data:`PILOT_SECONDS` — gives DOP853's steps per
  unit time and seconds per step, so its run is ``steps x (seconds/step + the loop and dense
  output of solve_ivp)`` (:data:`SOLVE_IVP_STEP`);
* heyoka's steps follow from DOP853's: Taylor steps of order $p$ barely depend on the tolerance
  while DOP853's scale as $\mathrm{rtol}^{1/8}$; measured over $n = 3..12$, tol $10^{-8}..10^{-14}$:
  $N_\mathrm{Taylor} \approx N_\mathrm{DOP853}\,\mathrm{rtol}^{1/8}/0.082$ (spread 0.070–0.101);
* a Taylor step costs $\kappa\,D\,p^2$ for a decomposition of $D$ elementary operations
  (:func:`decomposition_size`): $\kappa$ = 0.25 ns compact, about half unrolled; an ensemble runs
  in batches of the SIMD width (a batch step ≈ 1.3 single steps);
* compile: compact $0.6 + 1.3\cdot10^{-4} D$ s, unrolled $0.3 + 0.025 D$ s (n = 3..32); a load from
  disk 0.03 s; importing heyoka 1.0 s when it is not yet imported.
"""

from __future__ import annotations

import importlib.util
import math
import sys
import time
from dataclasses import dataclass

import numpy as np

__all__ = ["Candidate", "predict", "choose", "describe", "decomposition_size"]

PILOT_STEPS = 8
PILOT_SECONDS = 0.05
#: N_Taylor = N_DOP853 * rtol^(1/8) / STEP_RATIO (measured, see the module docstring).
STEP_RATIO = 0.082
#: Seconds per decomposition operation and order^2 of one Taylor step (compact, unrolled).
KAPPA = {True: 0.25e-9, False: 0.13e-9}
BATCH_STEP = 1.3
HEYOKA_IMPORT = 1.0
DISK_LOAD = 0.03
#: Seconds of SciPy's dense output per sample and state component.
DENSE_OUTPUT = 2e-8
#: Seconds per DOP853 step that ``solve_ivp`` adds to the bare stepper of the pilot (its loop and
#: the dense output for the sample times: 3 more stages; measured 160-400 us on 2 loaded cores).
SOLVE_IVP_STEP = 2.5e-4


@dataclass
class Candidate:
    """One way to run the scene, and its predicted cost in seconds."""

    method: str  # "heyoka" or "dop853"
    compact: bool | None
    startup: float
    run: float
    state: str = ""  # compile-cache state: "in memory", "on disk", "cold" ("" for DOP853)

    @property
    def total(self) -> float:
        """Start-up plus run."""
        return self.startup + self.run

    @property
    def label(self) -> str:
        """``heyoka compact`` / ``heyoka unrolled`` / ``DOP853``."""
        if self.method == "dop853":
            return "DOP853"
        return f"heyoka {'compact' if self.compact else 'unrolled'}"

    def describe(self) -> str:
        """``heyoka compact ~1.2 s (cold compile 0.9 s + run 0.3 s)``."""
        if self.method == "dop853":
            return f"DOP853 ~{_s(self.run)}"
        start = {"in memory": "in memory", "on disk": "load", "cold": "compile"}[self.state]
        return f"{self.label} ~{_s(self.total)} ({start} {_s(self.startup)} + run {_s(self.run)})"


def _s(x: float) -> str:
    return f"{x:.2g} s" if x >= 0.01 else f"{x * 1e3:.2g} ms"


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


def _dop853_pilot(field, y0: np.ndarray, t0: float, t_end: float, rtol: float):
    """(steps per unit time, seconds per step) of DOP853 on the scene's own field and states."""
    from scipy.integrate import DOP853

    shape = y0.shape

    def finite_field(s, y):
        dy = field(s, y.reshape(shape)).ravel()
        if not np.isfinite(dy).all():  # SciPy's step-size loop never ends on a nan error norm
            raise FloatingPointError("the field is not finite in the DOP853 pilot")
        return dy

    if not np.isfinite(y0).all():
        raise FloatingPointError("the initial state is not finite")
    solver = DOP853(finite_field, t0, y0.ravel(), t_end,
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


def _startup(system_name: str, n: int, compact: bool, state: str) -> float:
    imported = 0.0 if "heyoka" in sys.modules else HEYOKA_IMPORT
    D = decomposition_size(system_name, n)
    if state == "in memory":
        return 0.0
    if state == "on disk":
        return imported + DISK_LOAD
    return imported + (0.6 + 1.3e-4 * D if compact else 0.3 + 0.025 * D)


def predict(field, y0: np.ndarray, t: np.ndarray, system, n: int, heyoka_tol: float,
            dop_rtol: float, methods=("heyoka", "dop853"), simd: int = 4) -> list[Candidate]:
    """The candidates of ``methods`` with their predicted costs (see the module docstring);
    ``system``: the :class:`heyoka_systems.System` of ``field``; ``y0`` ``(count, dim)``."""
    from chaplygin_nd.simulate.integrators import heyoka_taylor as ht

    span = float(t[-1] - t[0])
    rate, per_step = _dop853_pilot(field, y0, float(t[0]), float(t[-1]), dop_rtol)
    dop_steps = rate * span
    out: list[Candidate] = []
    if "dop853" in methods:
        out.append(Candidate("dop853", None, 0.0, dop_steps * (per_step + SOLVE_IVP_STEP)
                             + DENSE_OUTPUT * len(t) * y0.size))
    if "heyoka" in methods and importlib.util.find_spec("heyoka") is not None:
        count = y0.shape[0]
        width = max(1, min(simd, count)) if count > 1 else 1
        batches = math.ceil(count / width)
        taylor_steps = max(1.0, dop_steps * max(dop_rtol, 2.2e-14) ** 0.125 / STEP_RATIO)
        order = ht.order_for(heyoka_tol)
        D = decomposition_size(system.name, n)
        for compact in (True, False):
            state = ht.cache_state(system, "double", heyoka_tol, compact, width)
            step = KAPPA[compact] * D * order**2 * (BATCH_STEP if width > 1 else 1.0)
            out.append(Candidate("heyoka", compact, _startup(system.name, n, compact, state),
                                 batches * taylor_steps * step, state))
    return out


def choose(candidates: list[Candidate]) -> Candidate:
    """The candidate of least predicted total (start-up + run)."""
    return min(candidates, key=lambda c: c.total)


def describe(candidates: list[Candidate], chosen: Candidate) -> str:
    """The plan line's cost sentence: every prediction, the chosen one first."""
    rest = [c for c in candidates if c is not chosen]
    text = f"predicted {chosen.describe()}"
    if rest:
        text += "; other candidates: " + ", ".join(c.describe() for c in rest)
    return text + " (outputs cost the same for every candidate)"


def for_scene(scene, model: str, reconstruct: bool, method: str, heyoka_tol: float,
              dop_rtol: float) -> tuple[Candidate, str] | None:
    """The planner's entry: ``(chosen candidate, plan-line sentence)`` for the ``full`` or
    ``reduced-7D`` model of ``scene``; ``method``: ``"auto"`` (heyoka if importable, and DOP853),
    ``"heyoka"`` (compact or unrolled) or ``"dop853"``. None when the pilot cannot run (a
    non-finite field: the run itself then stops with the reason)."""
    from chaplygin_nd.simulate.dynamics import so
    from chaplygin_nd.simulate.dynamics.field import FullField, ReducedField
    from chaplygin_nd.simulate.dynamics.so import reduced_invariants
    from chaplygin_nd.simulate.integrators import heyoka_systems, registry

    field: ReducedField | FullField
    if model == "reduced-7D":
        field = ReducedField(scene.a, scene.b)
        y0 = reduced_invariants(scene.M0, scene.gamma0)
    else:
        field = FullField(scene.n, scene.a, scene.b, reconstruct, scene.radius)
        if reconstruct:
            g0 = np.array([so.rotation_to(g) for g in scene.gamma0])
            y0 = field.pack(scene.M0, scene.gamma0, g0, np.zeros_like(scene.gamma0))
        else:
            y0 = field.pack(scene.M0, scene.gamma0)
    system, _ = heyoka_systems.for_field(field)
    methods = tuple(m for m in registry.names("auto") if registry.get(m).costed) \
        if method == "auto" else (method,)
    try:
        with np.errstate(over="ignore", invalid="ignore", divide="ignore", under="ignore"):
            candidates = predict(field, y0, scene.t, system, scene.n, heyoka_tol, dop_rtol, methods)
    except (FloatingPointError, ValueError, OverflowError, ZeroDivisionError):
        return None
    if not candidates or not all(math.isfinite(c.total) for c in candidates):
        return None
    chosen = choose(candidates)
    return chosen, describe(candidates, chosen)
