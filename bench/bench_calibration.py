r"""Calibration of ``accuracy.target`` -> integrator settings (:mod:`simulate.scene.accuracy`).

For every method the planner may run (DOP853, RK45, heyoka in double, RKMK4) and a few settings
each, on every built-in scene that integrates (long ones cut to a shorter horizon, said in the
rows) and on a seeded set of generic initial conditions (n = 3, 4, 5; a = -0.9, 0.5, 3; b = 1, 2.5;
|M0| = 1, 5; T = 50), the relative error of every output

.. math:: e = \max_\text{outputs} \max|y - y_\text{ref}| / \max|y_\text{ref}|

is measured against heyoka in ``real128`` at tolerance $10^{-28}$ (or, without heyoka, the
mpmath Taylor method at 32 digits), and the ratio $e/\text{setting}$ (for RKMK4 $e/(h^4\,T)$)
recorded. ``worst`` per method is what :data:`simulate.scene.accuracy.MEASURED` must be at least; the
run uses ``setting = target / (worst x SAFETY)``. Writes ``calibration.json`` (rows) and
``calibration.md`` (the table, and MET / NOT MET: the constants in the code are >= the measured
worst). Reproduce: ``chaplygin bench calibration`` (``--quick``: fewer cases).
"""

from __future__ import annotations

import dataclasses
import time
from pathlib import Path

import numpy as np
from chaplygin_nd.bench.report import machine, write_atomic, write_rows
from chaplygin_nd.simulate.scene import accuracy
from chaplygin_nd.simulate.scene.outputs import collect
from chaplygin_nd.simulate.scene.planner import plan
from chaplygin_nd.simulate.scene.run import execute
from chaplygin_nd.simulate.scene.spec import find, loads

SETTINGS = {"dop853": (1e-7, 1e-10, 1e-12, accuracy.FLOORS["dop853"]),
            "rk45": (1e-7, 1e-9),
            "heyoka": (1e-8, 1e-12, accuracy.FLOORS["heyoka"]),
            "lie": (0.05, 0.02)}
BUILTIN = {"generic4d": None, "explicit4d": None, "prolate_ball3d": None, "reduced4d": None,
           "ensemble3d": None, "reference4d": None, "tori4d": 128.0, "long4d": 100.0}


def seeded_cases(quick: bool):
    """Generic initial conditions across n, a, b and scale (seeded), T = 50."""
    cases = []
    grid = [(n, a, b, scale) for n in (3, 4, 5) for a in (-0.9, 0.5, 3.0) for b in (1.0, 2.5)
            for scale in (1.0, 5.0)]
    rng = np.random.default_rng(2026)
    picks = rng.choice(len(grid), size=4 if quick else 12, replace=False)
    for i, k in enumerate(sorted(picks)):
        n, a, b, scale = grid[k]
        text = (f'title = "seeded {i}"\nn = {n}\na = {a}\nb = {b}\n[initial]\nfamily = "generic"\n'
                f'seed = {100 + i}\nscale = {scale}\n[times]\nt_end = 50.0\nsamples = 201\n'
                '[outputs]\nwant = ["M", "gamma", "x", "integrals"]\n')
        scene = loads(text, source=f"seeded {i}")
        scene.name = f"seeded{i}:n={n},a={a},b={b},|M|={scale}"
        cases.append(scene)
    return cases


def builtin_cases(quick: bool):
    out = []
    for name, horizon in BUILTIN.items():
        scene = find(name)
        if horizon is not None or quick:
            horizon = min(horizon or scene.t[-1], 20.0 if quick else scene.t[-1])
            scene = dataclasses.replace(scene, t=scene.t[scene.t <= horizon])
        if set(scene.outputs) <= {"frequencies", "poincare"}:  # not comparable arrays: the state
            scene = dataclasses.replace(scene, outputs=("M", "gamma", "x"))
            scene.name = f"{name} (to T = {horizon:g})"
        else:
            scene.name = name
        out.append(scene)
    return out


def _run(scene, method, settings):
    auto = dataclasses.replace(scene, method="auto" if method != "lie" else "lie")
    p = plan(auto)
    if p.model not in ("full", "reduced-7D") or scene.method == "lie":  # RKMK4: the full system
        p = plan(auto, force_full=True)
    p = dataclasses.replace(p, method=settings.method, accuracy=settings)
    start = time.perf_counter()
    traj = execute(scene, p, progress=False, force=True)
    return collect(scene, traj), time.perf_counter() - start, p.model


def relative_error(arrays, ref) -> float:
    """Largest max|a - b|/max|b| over the outputs both have (``t`` and drifts left out)."""
    worst = 0.0
    for key, v in arrays.items():
        if key == "t" or key.startswith("drift.") or key not in ref:
            continue
        size = float(np.max(np.abs(ref[key]))) if np.size(ref[key]) else 0.0
        if size > 0:
            worst = max(worst, float(np.max(np.abs(np.asarray(v) - ref[key]))) / size)
    return worst


def _settings(method: str, value: float) -> accuracy.Settings:
    """The registered settings class of ``method`` holding ``value`` (tol, h or dps)."""
    from chaplygin_nd.simulate.integrators import registry

    kind = registry.get(method).settings
    field = {accuracy.Tolerance: "tol", accuracy.Step: "h", accuracy.Digits: "dps"}[kind]
    return kind(method, 0.0, True, **{field: value})


def reference_settings() -> accuracy.Settings:
    if accuracy.heyoka_usable():
        return accuracy.Tolerance("heyoka", 1e-26, True, "real128", tol=1e-28)
    return accuracy.Digits("reference", 1e-28, True, dps=32)


def main(out: Path, quick: bool = False) -> int:
    rows = []
    ref_settings = reference_settings()
    methods = [m for m in SETTINGS if m != "heyoka" or accuracy.heyoka_usable()]
    for scene in builtin_cases(quick) + seeded_cases(quick):
        lie_only = scene.method == "lie"
        try:
            ref, ref_seconds, model = _run(scene, ref_settings.method, ref_settings)
        except Exception as exc:  # a reference that cannot run (e.g. Taylor on reduced): said
            print(f"  {scene.name}: no reference ({exc})", flush=True)
            continue
        span = float(scene.t[-1] - scene.t[0])
        for method in methods:
            if (method == "lie") != lie_only and not (method == "lie" and model == "full"):
                continue
            if model == "reduced-7D" and method in ("lie", "rk45"):
                continue
            for value in SETTINGS[method][:1 if quick else None]:
                s = _settings(method, value)
                arrays, seconds, model = _run(scene, method, s)
                err = relative_error(arrays, ref)
                ratio = err / (value ** 4 * span if method == "lie" else value)
                rows.append({"case": scene.name, "model": model, "method": method,
                             "setting": value, "error": err, "ratio": ratio, "seconds": seconds,
                             "reference": ref_settings.describe()})
                print(f"  {scene.name:<40} {method:<7} {value:<9.3g} error {err:.2e} "
                      f"ratio {ratio:.3g} ({seconds:.1f} s)", flush=True)
    out.mkdir(parents=True, exist_ok=True)
    write_rows(out / "calibration.json", rows)
    lines = ["# Calibration: accuracy.target -> settings", "",
             f"Reference: {ref_settings.describe()}. Ratio = error/setting (RKMK4: error/(h^4 T)). "
             f"A run uses setting = (target/{accuracy.SAFETY:g} - E)/K (RKMK4: h = "
             f"(target/({accuracy.SAFETY:g} C T))^(1/4)), K and E from simulate/scene/accuracy.py.", "",
             "| method | cases | worst K (above the floor) | K in accuracy.py | worst E (at the floor) "
             "| E in accuracy.py | |", "|---|---|---|---|---|---|---|"]
    ok_all = True
    for method in methods:
        mine = [r for r in rows if r["method"] == method]
        if not mine:
            continue
        floor = accuracy.FLOORS.get(method, 0.0)
        above = [r["ratio"] for r in mine if r["setting"] > 10 * floor]
        at = [r["error"] for r in mine if floor and r["setting"] <= floor]
        worst_k, worst_e = max(above, default=0.0), max(at, default=0.0)
        ok = accuracy.MEASURED[method] >= worst_k and accuracy.ROUNDING[method] >= worst_e
        ok_all &= ok
        lines.append(f"| {method} | {len({r['case'] for r in mine})} | {worst_k:.3g} | "
                     f"{accuracy.MEASURED[method]:g} | {worst_e:.3g} | "
                     f"{accuracy.ROUNDING[method]:g} | {'MET' if ok else 'NOT MET'} |")
    lines += ["", "| case | model | method | setting | error | ratio | seconds |",
              "|---|---|---|---|---|---|---|"]
    lines += [f"| {r['case']} | {r['model']} | {r['method']} | {r['setting']:.3g} | "
              f"{r['error']:.2e} | {r['ratio']:.3g} | {r['seconds']:.2f} |" for r in rows]
    lines += ["", "Machine:", *machine()]
    write_atomic(out / "calibration.md", "\n".join(lines) + "\n")
    print(f"  calibration: {'every constant >= its measured worst' if ok_all else 'NOT MET'}")
    return 0
