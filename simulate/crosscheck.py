r"""``--cross-check``: judge a run against an independent one.

The independent run:

* for a closed form or the reduced 7D model: the full system eq:motion-general with DOP853;
* for the full system integrated by DOP853: the same equations with a *different* integrator,
  SciPy's RK45 (Dormand–Prince 5(4), Hairer–Nørsett–Wanner §II.5);
* for the full system integrated by heyoka, the Lie-group or the Taylor method: DOP853.

Each runs at a tighter tolerance than the scene asks: ``rtol = atol = min(target/1000, 1e-10)``
clamped at SciPy's floor $100\varepsilon$. Per output the difference is $\max|a - b|$ over all
samples, initial conditions and components; the bound is ``accuracy.target`` times the size
$\max|b|$ of the output (``target`` itself when the output is identically 0). The verdict is
``pass`` when every difference is within its bound. Outputs only one of the runs produces
(``zeta``) and the drifts $I(t) - I(0)$ are not compared.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
from chaplygin_nd.simulate.outputs import collect
from chaplygin_nd.simulate.planner import plan
from chaplygin_nd.simulate.run import execute
from chaplygin_nd.simulate.stops import fmt

__all__ = ["CrossCheck", "cross_check", "reference_rtol"]


def reference_rtol(target: float) -> float:
    """Tolerance of the independent run for a scene asking ``target``."""
    return max(min(target / 1000, 1e-10), 100 * np.finfo(float).eps)


@dataclass
class CrossCheck:
    """Differences, bounds and the verdict of a cross-check."""

    against: str
    rows: list[tuple[str, float, float]]  # (output, max |difference|, bound)

    @property
    def passed(self) -> bool:
        """Every difference within its bound (and at least one output compared)."""
        return bool(self.rows) and all(d <= bound for _, d, bound in self.rows)

    def describe(self) -> str:
        """The lines of the summary, ending with ``cross-check: pass`` or ``cross-check: FAIL``."""
        lines = [f"cross-check against {self.against}: max |difference| <= bound "
                 "(accuracy.target x max |output|)"]
        lines += [f"        {k:<24} {d:.2e} {'<=' if d <= bound else '>'} {bound:.2e}"
                  for k, d, bound in self.rows]
        if not self.rows:
            lines.append("        no output in common")
        lines.append(f"cross-check: {'pass' if self.passed else 'FAIL'}")
        return "\n".join(lines)


def cross_check(scene, main_plan, arrays: dict[str, np.ndarray], progress: bool = True,
                force: bool = False) -> CrossCheck:
    """Compare ``arrays`` (the outputs of ``main_plan`` on ``scene``) with an independent run."""
    rtol = reference_rtol(scene.target)
    if main_plan.model == "full" and main_plan.method == "dop853":
        method, name = "rk45", f"the full system with RK45 rtol {fmt(rtol)}"
    else:
        method, name = "dop853", f"the full system with DOP853 rtol {fmt(rtol)}"
    other_scene = dataclasses.replace(scene, method=method, target=100 * rtol)
    p = plan(other_scene, force_full=True)
    traj = execute(other_scene, p, progress=progress, force=force)
    other = collect(other_scene, traj)
    rows = []
    for key, v in arrays.items():
        if key == "t" or key not in other or key.startswith("drift."):
            continue
        ref = np.asarray(other[key])
        size = float(np.max(np.abs(ref))) if ref.size else 0.0
        bound = scene.target * size if size > 0 else scene.target
        rows.append((key, float(np.max(np.abs(np.asarray(v) - ref))), bound))
    return CrossCheck(name, rows)
