r"""Execute a plan: produce the trajectory of a scene with the model the planner chose.

The result is a :class:`Trajectory`: sample times and, as the model provides them,
$M, \Omega$ ``(S, count, n, n)``, $\gamma$ ``(S, count, n)``, $g$, $c$ (reconstruction),
the reduced invariants $r = (A, B, E, G, F_1, x, \delta)$ ``(S, count, 7)``, the horizontal
invariants $(x, G, A, B)$ ``(S, count, 4)`` and $\zeta$ ``(count, n, n)``;
plus the cost (steps, right-hand-side calls, seconds of the run, and apart from them the seconds
of a JIT compile or a compiled-cache load).
"""

from __future__ import annotations

import math
import sys
import time
from dataclasses import dataclass, field

import numpy as np
from chaplygin_nd.simulate.dynamics import so
from chaplygin_nd.simulate.dynamics.closed_forms import (
    horizontal,
    horizontal_nd,
    relative_equilibrium,
)
from chaplygin_nd.simulate.dynamics.field import FullField, ReducedField
from chaplygin_nd.simulate.dynamics.so import reduced_invariants
from chaplygin_nd.simulate.integrators import registry
from chaplygin_nd.simulate.integrators.stops import NonFinite, check_finite, fmt
from chaplygin_nd.simulate.kernels import active
from chaplygin_nd.simulate.scene.budget import Projection, refuse_before
from chaplygin_nd.simulate.scene.planner import Plan, settings
from chaplygin_nd.simulate.scene.progress import Line
from chaplygin_nd.simulate.scene.spec import Scene

__all__ = ["Trajectory", "execute", "Progress"]


@dataclass
class Trajectory:
    """Samples of the scene's solution and what they cost."""

    t: np.ndarray
    model: str
    method: str
    data: dict[str, np.ndarray] = field(default_factory=dict)
    steps: int = 0
    calls: int = 0
    seconds: float = 0.0
    compile_seconds: float = 0.0  # JIT compile (cold) or cache load (warm), not in ``seconds``


class Progress(Line):
    """Progress on stderr for runs longer than ``after`` seconds (as :class:`Line` writes it), with
    an ETA; it also stops a run whose time became nan and, through ``projection``
    (:class:`simulate.scene.budget.Projection`), one projected to cost too much. The line is
    monotone: it shows the furthest time reported, so an integrator's probe or rejected step
    (a time it does not keep) never makes it go back."""

    def __init__(self, t_end: float, label: str, after: float = 2.0, stream=sys.stderr,
                 projection=None, t0: float = 0.0):
        super().__init__(label, after, stream)
        self.t0, self.t_end = t0, t_end
        self.projection = projection
        self.reached = t0

    def restart(self) -> None:
        """The integrator is ready (compiled or loaded): the run's clocks start now."""
        self.start = self.last = time.perf_counter()
        if self.projection is not None:
            self.projection.restart()

    def __call__(self, t: float) -> None:
        """Report that the integration reached time ``t``."""
        if not math.isfinite(t):
            raise NonFinite(f"the integration time is not finite ({t}) after t = {fmt(self.t0)}: "
                            "the solution left float64")
        if self.projection is not None:
            self.projection(t)
        self.reached = max(self.reached, min(t, self.t_end))
        span = self.t_end - self.t0
        self.show(f"{self.label}: t = {self.reached:.4g} / {self.t_end:.4g}",
                  (self.reached - self.t0) / span if span else 1.0)


def execute(scene: Scene, plan: Plan, progress: bool = True, force: bool = False) -> Trajectory:
    """Run ``plan`` on ``scene`` (see the module docstring). The initial condition is the state
    at ``t[0]`` for every model: closed forms are evaluated at ``t - t[0]``. Raises
    :class:`simulate.integrators.stops.NonFinite` when a field leaves float64 and
    :class:`simulate.integrators.stops.TooCostly` when the projected time is past the limit (unless ``force``)."""
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):  # checked below
        return _execute(scene, plan, progress, force)


def _execute(scene, plan, progress, force):
    t = scene.t
    elapsed = t - t[0]
    traj = Trajectory(t=t, model=plan.model, method=plan.method)
    g0 = np.array([so.rotation_to(g) for g in scene.gamma0])
    start = time.perf_counter()
    sol = None
    if plan.model in ("constant-Omega", "vertical"):
        if plan.model == "vertical":
            X = active().require("zeta")(scene.M0, scene.gamma0, scene.a, scene.b)
            traj.data["zeta"] = X
        else:
            X = -plan.Omega0
        parts = [relative_equilibrium(X[e], scene.M0[e], scene.gamma0[e], plan.Omega0[e], elapsed,
                                      g0[e] if plan.reconstruct else None, scene.radius)
                 for e in range(scene.count)]
        for key in parts[0]:
            traj.data[key] = np.stack([p[key] for p in parts], axis=1)
        traj.calls = 1
    elif plan.model == "horizontal-4D":
        traj.data["reduced"] = horizontal(reduced_invariants(scene.M0, scene.gamma0),
                                          scene.a, scene.b, elapsed)
        traj.calls = 3
    elif plan.model == "horizontal":
        traj.data["horizontal"] = horizontal_nd(scene.M0, scene.gamma0, plan.Omega0,
                                                scene.a, scene.b, elapsed)
        traj.calls = 2
    elif plan.model == "reduced-7D":
        f = ReducedField(scene.a, scene.b)
        r0 = reduced_invariants(scene.M0, scene.gamma0)
        sol = _integrate(f, r0, t, plan, scene, progress, force)
        traj.data["reduced"] = sol.y
        traj.steps, traj.calls = sol.steps, sol.calls
        traj.method, traj.compile_seconds = sol.method, sol.compile_seconds
    else:
        f = FullField(scene.n, scene.a, scene.b, plan.reconstruct, scene.radius)
        y0 = f.pack(scene.M0, scene.gamma0, g0, np.zeros_like(scene.gamma0)) \
            if plan.reconstruct else f.pack(scene.M0, scene.gamma0)
        sol = _integrate(f, y0, t, plan, scene, progress, force)
        parts = f.unpack(sol.y)
        traj.data["M"], traj.data["gamma"] = parts[0], parts[1]
        if plan.reconstruct:
            traj.data["g"], traj.data["c"] = parts[2], parts[3]
        traj.steps, traj.calls = sol.steps, sol.calls
        traj.method, traj.compile_seconds = sol.method, sol.compile_seconds
    for key, v in traj.data.items():
        if key != "zeta":
            check_finite(key, v, t)
    # integrators: their own run time (no imports, no JIT compile or load); closed forms: wall time
    traj.seconds = sol.seconds if sol is not None else time.perf_counter() - start
    return traj


def _checked(f):
    """``f`` that raises :class:`NonFinite` naming the field whose derivative is not finite."""
    names = getattr(f, "names", None) or ("M", "gamma", "g", "c")

    def field(s, y):
        dy = f(s, y)
        if not np.isfinite(dy).all():
            if hasattr(f, "unpack"):
                parts = [p for p in f.unpack(dy) if p is not None]
                bad = [nm for nm, p in zip(names, parts) if not np.isfinite(p).all()]
            else:
                bad = [nm for nm, col in zip(names, np.moveaxis(dy, -1, 0))
                       if not np.isfinite(col).all()]
            raise NonFinite(f"the time derivative of {', '.join(bad)} is not finite at t = {fmt(s)} "
                            "(the state left float64: are a, b or the scale too large?)")
        return dy
    return field


def _integrate(f, y0, t, plan, scene, progress=True, force=False):
    label = f"{plan.model} {plan.method}"
    refuse_before(plan, label, t, force)
    bar = Progress(t[-1], label, stream=sys.stderr if progress else _Null(),
                   projection=Projection(t[0], t[-1], label, force), t0=t[0])
    acc = plan.accuracy or settings(scene, plan.method, plan.model)  # simulate.scene.accuracy
    try:  # the integrator registered under the plan's method (simulate.integrators.registry)
        return registry.get(acc.method).run(f, y0, t, acc, checked=_checked(f), progress=bar,
                                            compact=getattr(plan, "compact", None))
    finally:
        bar.done()


class _Null:
    def write(self, text):
        pass

    def flush(self):
        pass
