r"""Execute a plan: produce the trajectory of a scene with the model the planner chose.

The result is a :class:`Trajectory`: sample times and, as the model provides them,
$M, \Omega$ ``(S, count, n, n)``, $\gamma$ ``(S, count, n)``, $g$, $c$ (reconstruction),
the reduced invariants $r = (A, B, E, G, F_1, x, \delta)$ ``(S, count, 7)`` and $\zeta$ ``(count, n, n)``;
plus the cost (steps, right-hand-side calls, seconds of the run, and apart from them the seconds
of a JIT compile or a compiled-cache load).
"""

from __future__ import annotations

import sys
import time
from dataclasses import dataclass, field

import numpy as np

from simulate import so
from simulate.closed_forms import horizontal, relative_equilibrium
from simulate.dispatch import active
from simulate.field import FullField, ReducedField
from simulate.integrators import dop853, heyoka_taylor, lie, taylor
from simulate.planner import Plan, heyoka_tolerance
from simulate.scene import Scene

__all__ = ["Trajectory", "execute", "reduced_invariants", "Progress"]


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


class Progress:
    """Progress on stderr for runs longer than ``after`` seconds (at most one line a second)."""

    def __init__(self, t_end: float, label: str, after: float = 2.0, stream=sys.stderr):
        self.t_end, self.label, self.after, self.stream = t_end, label, after, stream
        self.start = time.perf_counter()
        self.last = self.start
        self.shown = False

    def __call__(self, t: float) -> None:
        """Report that the integration reached time ``t``."""
        now = time.perf_counter()
        if now - self.start >= self.after and now - self.last >= 1.0:
            frac = t / self.t_end if self.t_end else 1.0
            self.stream.write(f"\r{self.label}: t = {t:.4g} / {self.t_end:.4g} "
                              f"({100 * frac:5.1f}%, {now - self.start:.0f} s)")
            self.stream.flush()
            self.last, self.shown = now, True

    def done(self) -> None:
        """End the progress line."""
        if self.shown:
            self.stream.write("\n")


def reduced_invariants(M: np.ndarray, gamma: np.ndarray) -> np.ndarray:
    r"""$r = (A, B, E, G, F_1, x, \delta)$ with $A = \|k\|^2$, $B = \|u\|^2$, $F_1 = \langle k, u\rangle$,
    $E = \langle k, q\rangle$, $G = \langle u, q\rangle$, $\delta = \langle q, k\times u\rangle$ — the
    definitions of Section 5 (Reduction by SO(3)); $n = 4$, $M$ ``(..., 4, 4)``, $\gamma = (q, x)$."""
    k, u = so.split4(M)
    q, x = gamma[..., :3], gamma[..., 3]
    dot = lambda p, s: np.einsum("...i,...i->...", p, s)  # noqa: E731
    return np.stack([dot(k, k), dot(u, u), dot(k, q), dot(u, q), dot(k, u), x,
                     dot(q, np.cross(k, u))], axis=-1)


def execute(scene: Scene, plan: Plan, progress: bool = True) -> Trajectory:
    """Run ``plan`` on ``scene`` (see the module docstring)."""
    t = scene.t
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
        parts = [relative_equilibrium(X[e], scene.M0[e], scene.gamma0[e], plan.Omega0[e], t,
                                      g0[e] if plan.reconstruct else None, scene.radius)
                 for e in range(scene.count)]
        for key in parts[0]:
            traj.data[key] = np.stack([p[key] for p in parts], axis=1)
        traj.calls = 1
    elif plan.model == "horizontal-4D":
        traj.data["reduced"] = horizontal(reduced_invariants(scene.M0, scene.gamma0),
                                          scene.a, scene.b, t)
        traj.calls = 3
    elif plan.model == "reduced-7D":
        f = ReducedField(scene.a, scene.b)
        r0 = reduced_invariants(scene.M0, scene.gamma0)
        sol = _integrate(f, r0, t, plan, scene)
        traj.data["reduced"] = sol.y
        traj.steps, traj.calls = sol.steps, sol.calls
        traj.method, traj.compile_seconds = sol.method, sol.compile_seconds
    else:
        f = FullField(scene.n, scene.a, scene.b, plan.reconstruct, scene.radius)
        y0 = f.pack(scene.M0, scene.gamma0, g0, np.zeros_like(scene.gamma0)) \
            if plan.reconstruct else f.pack(scene.M0, scene.gamma0)
        sol = _integrate(f, y0, t, plan, scene, progress)
        parts = f.unpack(sol.y)
        traj.data["M"], traj.data["gamma"] = parts[0], parts[1]
        if plan.reconstruct:
            traj.data["g"], traj.data["c"] = parts[2], parts[3]
        traj.steps, traj.calls = sol.steps, sol.calls
        traj.method, traj.compile_seconds = sol.method, sol.compile_seconds
    # integrators: their own run time (no imports, no JIT compile or load); closed forms: wall time
    traj.seconds = sol.seconds if sol is not None else time.perf_counter() - start
    return traj


def _integrate(f, y0, t, plan, scene, progress=True):
    bar = Progress(t[-1], f"{plan.model} {plan.method}") if progress else None
    try:
        if plan.method == "heyoka":
            return heyoka_taylor.integrate(f, y0, t, tol=heyoka_tolerance(scene.target),
                                           progress=bar)
        if plan.method == "dop853":
            rtol = max(scene.target / 100, 2.3e-14)  # global error ~ 10-100 x rtol (bench)
            return dop853.integrate(f, y0, t, rtol=rtol, atol=rtol, progress=bar)
        if plan.method == "lie":
            return lie.integrate(f, y0, t, h=scene.step, progress=bar)
        return taylor.integrate(f, y0, t, dps=scene.dps, progress=bar)
    finally:
        if bar:
            bar.done()
