r"""What each integrator would cost for a scene, predicted before the run: the planner's method choice.

For each candidate the scene may use — heyoka compact, heyoka unrolled (Taylor + LLVM), DOP853 —
the predicted total is *start-up* (compile, or load from the compile cache, and heyoka's import;
the cache state is known: in memory / on disk / cold, :func:`simulate.integrators.heyoka_taylor.cache_state`) plus
*run* (the integration). The outputs cost the same for every candidate (they are computed from
the samples), so they do not enter the choice. The cheapest candidate wins; the plan line prints
every prediction.

How the run is predicted (no constant is a guess; each was measured, see
``bench/bench_scaling.py``, on 2 shared cores): a **DOP853 pilot**
(:func:`simulate.integrators.dop853.pilot`) — the scene's own field and initial conditions (the
whole ensemble, as DOP853 integrates it), a few steps — gives DOP853's steps per unit time and
seconds per step (:class:`simulate.integrators.base.Pilot`); each integrator registered
``costed`` turns that into its candidates (its entry's ``cost``: DOP853's run in
:func:`simulate.integrators.dop853.predict_cost`, heyoka's Taylor steps, step cost, compile and
load in :func:`simulate.integrators.heyoka_taylor.predict_cost`).
"""

from __future__ import annotations

import math

import numpy as np
from chaplygin_nd.simulate.integrators import dop853, registry
from chaplygin_nd.simulate.integrators.base import Candidate, Pilot

__all__ = ["Candidate", "predict", "choose", "describe", "for_scene"]

def predict(field, y0: np.ndarray, t: np.ndarray, system, n: int, tolerances: dict[str, float],
            pilot_rtol: float) -> list[Candidate]:
    """The candidates of the methods in ``tolerances`` (name -> the tolerance it would run with)
    with their predicted costs (see the module docstring); ``system``: the
    :class:`heyoka_systems.System` of ``field``; ``y0`` ``(count, dim)``; the pilot runs at
    ``pilot_rtol`` (DOP853's tolerance for the scene)."""
    span = float(t[-1] - t[0])
    rate, per_step = dop853.pilot(field, y0, float(t[0]), float(t[-1]), pilot_rtol)
    pilot = Pilot(rate, per_step, pilot_rtol, span, len(t), y0, system, n)
    out: list[Candidate] = []
    for method, tol in tolerances.items():
        out += registry.get(method).cost(pilot, tol)  # type: ignore[misc]
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


def for_scene(scene, model: str, reconstruct: bool, tolerances: dict[str, float],
              pilot_rtol: float) -> tuple[Candidate, str] | None:
    """The planner's entry: ``(chosen candidate, plan-line sentence)`` for the ``full`` or
    ``reduced-7D`` model of ``scene`` among the methods of ``tolerances`` (name -> the tolerance it
    would run with; those that honour the target); the DOP853 pilot runs at ``pilot_rtol``. None
    when the pilot cannot run (a non-finite field: the run itself then stops with the reason)."""
    from chaplygin_nd.simulate.dynamics import so
    from chaplygin_nd.simulate.dynamics.field import FullField, ReducedField
    from chaplygin_nd.simulate.dynamics.so import reduced_invariants
    from chaplygin_nd.simulate.integrators import heyoka_systems

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
    try:
        with np.errstate(over="ignore", invalid="ignore", divide="ignore", under="ignore"):
            candidates = predict(field, y0, scene.t, system, scene.n, tolerances, pilot_rtol)
    except (FloatingPointError, ValueError, OverflowError, ZeroDivisionError):
        return None
    if not candidates or not all(math.isfinite(c.total) for c in candidates):
        return None
    chosen = choose(candidates)
    return chosen, describe(candidates, chosen)
