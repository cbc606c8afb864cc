r"""``--cross-check``: judge a run against a reference at least 100 times more accurate.

The run promises a relative error ``promised`` (:mod:`simulate.scene.accuracy`: ``accuracy.target``, or
what a method the scene named reaches when it cannot honour the target; for a closed form its
bound at the horizon, :mod:`simulate.scene.bounds`). The reference integrates the full system eq:motion-general with the first of

1. DOP853, 2. heyoka in double, 3. the mpmath Taylor method (:mod:`simulate.integrators.taylor`,
   an independent route to $L_\gamma^{-1}$, at the digits the target needs plus 6)

whose calibrated settings honour ``promised / 100`` (:data:`MARGIN`) and that differs from the run
in integrator or precision (the Taylor method judging a Taylor run uses 10 more digits). heyoka
counts only where it is usable (:func:`simulate.scene.accuracy.heyoka_usable`). heyoka in ``real128``
is not a candidate: on prolate_ball3d (reconstruction, T = 60) its reference was projected past the
600 s limit of simulate.scene.budget, where the mpmath Taylor reference takes about 30 s.

Per output: the difference $d = \max|a - b|$ over all samples, initial conditions and components,
the bound ``promised x max|b|`` (``promised`` when the output is identically 0) and the
reference's own estimated error $e_\text{ref}$ = its calibrated relative error times $\max|b|$.
The run's error lies in $[d - e_\text{ref}, d + e_\text{ref}]$, so with $e_\text{ref} \le$ bound/100
a FAIL ($d$ > bound) says that the *run* is off, and by how much. Outputs only one of the runs
produces (``zeta``) and the drifts $I(t) - I(0)$ are not compared.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
from chaplygin_nd.simulate.integrators import registry
from chaplygin_nd.simulate.scene import accuracy
from chaplygin_nd.simulate.scene.outputs import collect
from chaplygin_nd.simulate.scene.planner import plan
from chaplygin_nd.simulate.scene.run import execute

__all__ = ["CrossCheck", "cross_check", "reference_settings", "MARGIN"]

#: The reference is at least this many times more accurate than the run promises.
MARGIN = 100.0


def promised(scene, main_plan) -> float:
    """The relative error the run stands for (see the module docstring)."""
    if main_plan.accuracy is not None:
        return main_plan.accuracy.promised
    return main_plan.bound.value if main_plan.bound is not None else scene.target


def reference_settings(scene, main_plan) -> accuracy.Settings:
    """The reference's :class:`simulate.scene.accuracy.Settings` (rules in the module docstring)."""
    need = promised(scene, main_plan) / MARGIN
    span = float(scene.t[-1] - scene.t[0])
    run = main_plan.accuracy
    for method in registry.names("reference"):  # DOP853, heyoka (double), the Taylor method
        entry = registry.get(method)
        if not entry.available():
            continue
        if entry.settings is accuracy.Digits:  # multiprecision: honours every target
            s = accuracy.choose(method, need, span, dps=scene.dps)
            if isinstance(run, accuracy.Digits) and isinstance(s, accuracy.Digits) \
                    and run.method == method:
                s = dataclasses.replace(s, dps=max(s.dps, run.dps + 10))
            return s
        if run is not None and method == run.method and run.precision == "double":
            continue  # the same integrator in the same precision is no independent reference
        s = accuracy.choose(method, need, span)
        if s.honoured:
            return s
    raise AssertionError("unreachable: the Taylor method honours every target")  # pragma: no cover


@dataclass
class CrossCheck:
    """Differences, bounds, the reference's own error and the verdict of a cross-check."""

    against: str
    rows: list[tuple[str, float, float, float]]  # (output, max |difference|, bound, reference error)

    @property
    def passed(self) -> bool:
        """Every difference within its bound (and at least one output compared)."""
        return bool(self.rows) and all(d <= bound for _, d, bound, _ in self.rows)

    def describe(self) -> str:
        """The lines of the summary, ending with ``cross-check: pass`` or ``cross-check: FAIL ...``."""
        lines = [f"cross-check against {self.against}: max |difference| <= bound "
                 "(promised error x max |output|); the reference's estimated error beside it"]
        lines += [f"        {k:<24} {d:.2e} {'<=' if d <= bound else '>'} {bound:.2e}   "
                  f"(reference error <= {e:.1e})" for k, d, bound, e in self.rows]
        if not self.rows:
            lines.append("        no output in common")
        if self.passed:
            lines.append("cross-check: pass")
        elif not self.rows:
            lines.append("cross-check: FAIL (nothing to compare)")
        else:
            bad = [(k, d, bound, e) for k, d, bound, e in self.rows if d > bound]
            judged = all(e <= bound / 10 for _, _, bound, e in bad)
            worst = max(bad, key=lambda r: r[1] / r[2])
            lines.append("cross-check: FAIL — " + (
                f"the run is off: its error in {worst[0]} is {worst[1]:.2e} +- {worst[3]:.1e}, "
                f"past the bound {worst[2]:.2e}" if judged else
                "the reference is not accurate enough to say which side is off"))
        return "\n".join(lines)


def cross_check(scene, main_plan, arrays: dict[str, np.ndarray], progress: bool = True,
                force: bool = False, state: dict[str, np.ndarray] | None = None) -> CrossCheck:
    """Compare ``arrays`` (the outputs of ``main_plan`` on ``scene``) with the reference run;
    ``state`` (``M``, ``gamma`` of the run) is compared too when given — for the outputs
    ``frequencies``/``poincare``, which are not arrays of the trajectory."""
    ref = reference_settings(scene, main_plan)
    p = plan(dataclasses.replace(scene, method="dop853"), force_full=True)
    p = dataclasses.replace(p, method=ref.method, accuracy=ref, detail=ref.describe())
    traj = execute(scene, p, progress=progress, force=force)
    other = collect(scene, traj)
    if state is not None:  # frequencies/poincare: the trajectory they are computed from
        other.update({k: traj.data[k] for k in ("M", "gamma")})
        arrays = {**arrays, **state}
    bound_rel = promised(scene, main_plan)
    ref_rel = ref.promised
    rows = []
    for key, v in arrays.items():
        if key == "t" or key not in other or key.startswith("drift."):
            continue
        b = np.asarray(other[key])
        size = float(np.max(np.abs(b))) if b.size else 0.0
        bound = bound_rel * size if size > 0 else bound_rel
        rows.append((key, float(np.max(np.abs(np.asarray(v) - b))), bound,
                     ref_rel * size if size > 0 else ref_rel))
    return CrossCheck(f"the full system with {ref.describe()}", rows)
