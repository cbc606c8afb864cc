"""What a scene run says about itself: the heading (the scene and the plan, printed before the
run) and the one-screen summary after it (cost, the drift of the integrals, the cross-check).
``chaplygin simulate`` prints them and writes them into ``summary.txt``; the notebook's
:meth:`chaplygin_nd.api.Simulation.summary` returns the same text (so it need not import the
command line)."""

from __future__ import annotations

from chaplygin_nd.simulate.scene.outputs import max_drift

__all__ = ["heading", "summary"]


def heading(scene, p, report: bool = False) -> str:
    """The summary's first lines, the scene and the plan (model and why), which ``chaplygin
    simulate`` prints before the run; with ``report`` (summary.txt) also the scene's remarks
    (``body:`` lines, e.g. that no ball of matter has its (a, b): see ``spec._body``)."""
    return "\n".join([f"scene   {scene.title}  (n = {scene.n}, a = {scene.a:g}, b = {scene.b:g}, "
                      f"{scene.count} initial condition{'s' if scene.count > 1 else ''}, "
                      f"t in [{scene.t[0]:g}, {scene.t[-1]:g}], {len(scene.t)} samples)",
                      p.describe(),
                      *([f"  body: {r}" for r in scene.remarks] if report else [])])


def summary(scene, p, traj, arrays, seconds, check=None, out=None, *, with_heading=True) -> str:
    """The one-screen summary: scene, model and why (:func:`heading`; left out when
    ``with_heading`` is false), cost, integral drift, cross-check."""
    lines = ([heading(scene, p)] if with_heading else []) + [
             (f"cost    closed form: {traj.calls} kernel evaluation(s) and matrix exponentials "
              f"at {len(scene.t)} samples, {traj.seconds:.3f} s; {seconds:.3f} s in all"
              if traj.method == "closed form" else
              f"cost    {traj.steps} steps, {traj.calls} right-hand-side calls, "
              f"{traj.seconds:.3g} s integrating"
              + (f" + {traj.compile_seconds:.3g} s compiling or loading the compiled integrator"
                 if traj.compile_seconds else "") + f", {seconds:.3f} s in all"),
             f"outputs {', '.join(scene.outputs)}"]
    drift = max_drift(arrays)
    if drift:
        lines.append("drift   " + ", ".join(f"{k} {v:.2e}" for k, v in drift.items()))
    if getattr(p, "bound", None) is not None:  # a closed form keeps its integrals exactly
        lines.append(f"bound   {p.bound.describe()}; a drift cannot show a phase error")
    if check is not None:
        lines.append(check.describe())
    if out is not None:
        lines.append(f"written {out}")
    return "\n".join(lines)
