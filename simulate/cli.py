"""``python -m simulate SCENE [--out DIR] [--cross-check]``: plan, run, write, summarise."""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from simulate.dispatch import KernelMissing
from simulate.outputs import collect, max_drift, write
from simulate.planner import plan
from simulate.run import execute
from simulate.scene import SceneError, load

__all__ = ["main", "summary"]


def summary(scene, p, traj, arrays, seconds, diffs=None, out=None) -> str:
    """The one-screen summary: scene, model and why, cost, integral drift, cross-check."""
    lines = [f"scene   {scene.title}  (n = {scene.n}, a = {scene.a:g}, b = {scene.b:g}, "
             f"{scene.count} initial condition{'s' if scene.count > 1 else ''}, "
             f"t in [{scene.t[0]:g}, {scene.t[-1]:g}], {len(scene.t)} samples)",
             p.describe(),
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
    if diffs is not None:
        lines.append("cross-check against the full system (DOP853 rtol 1e-13), max |difference|:")
        lines += [f"        {k:<24} {v:.2e}" for k, v in diffs.items()]
    if out is not None:
        lines.append(f"written {out}")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    """Entry point; returns the exit status (2 for a bad scene, 3 for a missing kernel)."""
    ap = argparse.ArgumentParser(prog="python -m simulate", description=__doc__)
    ap.add_argument("scene", help="a scene file (TOML), e.g. scenes/generic4d.toml")
    ap.add_argument("--out", help="output folder (default: out/<scene name>)")
    ap.add_argument("--cross-check", action="store_true",
                    help="also run the full system and report the largest difference per output")
    ap.add_argument("--no-plots", action="store_true", help="skip the PNG plots")
    args = ap.parse_args(argv)
    start = time.perf_counter()
    try:
        scene = load(args.scene)
        p = plan(scene)
        print(p.describe(), flush=True)
        traj = execute(scene, p)
        arrays = collect(scene, traj)
        diffs = None
        if args.cross_check:
            from simulate.crosscheck import cross_check
            diffs = cross_check(scene, arrays)
    except SceneError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except KernelMissing as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 3
    out = Path(args.out) if args.out else Path("out") / Path(args.scene).stem
    text = summary(scene, p, traj, arrays, time.perf_counter() - start, diffs, out)
    write(out, arrays, text, plots=not args.no_plots)
    print(text)
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
