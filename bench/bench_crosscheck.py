"""Every built-in scene's own ``--cross-check`` on both installs (with heyoka, and without it:
``CHAPLYGIN_ND_WITHOUT_HEYOKA=1``), including the longest ones the tests leave out (long4d, tori4d,
and on the base install the scenes whose reference is the mpmath Taylor method on an ensemble or
in n = 5, 6). Writes ``crosscheck.json`` (rows: scene, install, model and method, reference,
verdict, worst difference/bound, seconds) and ``crosscheck.md`` (MET when every row passes).
Reproduce: ``chaplygin bench crosscheck`` (``--quick``: the scenes the tests run, fast install only).
"""

from __future__ import annotations

import os
import time
from pathlib import Path

from chaplygin_nd.bench.report import machine, target, write_atomic, write_rows
from chaplygin_nd.simulate.integrators import heyoka_taylor
from chaplygin_nd.simulate.scene import accuracy
from chaplygin_nd.simulate.scene import tori as tori_scene
from chaplygin_nd.simulate.scene.crosscheck import cross_check
from chaplygin_nd.simulate.scene.outputs import collect
from chaplygin_nd.simulate.scene.planner import plan
from chaplygin_nd.simulate.scene.run import execute
from chaplygin_nd.simulate.scene.spec import builtin_scenes, find

LONGEST = ("long4d", "tori4d")


def one(name: str) -> dict:
    """Plan, run and cross-check the built-in scene ``name`` as ``chaplygin simulate`` does."""
    start = time.perf_counter()
    scene = find(name)
    p = plan(scene)
    traj = execute(scene, p, progress=False, force=True)
    arrays = collect(scene, traj)
    state = ({k: traj.data[k] for k in ("M", "gamma") if k in traj.data}
             if tori_scene.wants(scene) else None)
    check = cross_check(scene, p, arrays, progress=False, force=True, state=state)
    worst = max((d / b for _, d, b, _ in check.rows), default=float("inf"))
    return {"scene": name, "model": p.model, "run": p.detail, "reference": check.against,
            "passed": check.passed, "worst_difference_over_bound": worst,
            "seconds": time.perf_counter() - start}


def main(out: Path, quick: bool = False) -> int:
    installs = (["fast"] if heyoka_taylor.available() else []) + ([] if quick else ["base"])
    names = [n for n in builtin_scenes() if not (quick and n in LONGEST)]
    rows = []
    old = os.environ.get(accuracy.WITHOUT_HEYOKA)
    try:
        for install in installs:
            os.environ[accuracy.WITHOUT_HEYOKA] = "1" if install == "base" else "0"
            for name in names:
                row = {"install": install, **one(name)}
                rows.append(row)
                print(f"  {install:<5} {name:<16} {'pass' if row['passed'] else 'FAIL'} "
                      f"(worst difference/bound {row['worst_difference_over_bound']:.2g}, "
                      f"{row['seconds']:.0f} s)", flush=True)
    finally:
        if old is None:
            os.environ.pop(accuracy.WITHOUT_HEYOKA, None)
        else:
            os.environ[accuracy.WITHOUT_HEYOKA] = old
    out.mkdir(parents=True, exist_ok=True)
    write_rows(out / "crosscheck.json", rows)
    ok = bool(rows) and all(r["passed"] for r in rows)
    lines = ["# Every built-in scene's own cross-check, on both installs", "",
             target("every scene passes its cross-check on every install", ok,
                    f"{sum(r['passed'] for r in rows)} of {len(rows)} pass"), "",
             "| install | scene | model | run | reference | verdict | worst diff/bound | seconds |",
             "|---|---|---|---|---|---|---|---|"]
    lines += [f"| {r['install']} | {r['scene']} | {r['model']} | {r['run']} | {r['reference']} | "
              f"{'pass' if r['passed'] else 'FAIL'} | {r['worst_difference_over_bound']:.2g} | "
              f"{r['seconds']:.1f} |" for r in rows]
    lines += ["", "Machine:", *machine()]
    write_atomic(out / "crosscheck.md", "\n".join(lines) + "\n")
    return 0
