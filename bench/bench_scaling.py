"""Scaling in n and time to first result: ``chaplygin bench scaling``.

Writes ``bench/out/scaling.json`` (rows: n, method, setting, error, seconds = CPU seconds of the
integration, wall, compile_seconds, ops), ``scaling.png`` (log-log: CPU seconds, decomposition size
and compile seconds against n, with the fitted growth exponents), ``first_result.json`` and
``scaling.md`` with every target line MET or NOT MET.

* scaling — the full field, generic initial condition (seed 7), $a = 0.5$, $b = 1$, $T = 10$, for
  $n = 3 \\dots 32$ (and 64 unless ``--quick``): heyoka (compact, tol $10^{-12}$) and DOP853 at the
  loosest rtol of $10^{-10} \\dots 10^{-13}$ whose error is $\\le 10^{-10}$, the error against heyoka
  at tol $2^{-52}$; the fixed cost of a warm ``heyoka_taylor.integrate`` call (its wall time minus
  the raw ``propagate_grid`` of the same integrator); the compiled $L_\\gamma^{-1}$ wrapper against
  its raw cfunc at $10^3$ points;
* time to first result — three built-in scenes run by the command line in a fresh process with
  empty caches (an empty ``CHAPLYGIN_ND_CACHE`` and an empty ``XDG_CACHE_HOME`` for heyoka's own),
  then again warm: the planner's choice against forced DOP853 and forced heyoka, each twice in
  the order A B C A B C (the machine is shared: only ratios in one run count), and the printed run
  estimate against the measured integration time.
"""

from __future__ import annotations

import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from chaplygin_nd.bench.report import save_figure, target, write_atomic, write_rows

from chaplygin_nd import processes

ROOT = Path(__file__).resolve().parents[1]
T_END = 10.0
ERROR = 1e-10
A, B = 0.5, 1.0
SCENES = ("generic4d", "reduced4d", "explicit4d")


def _cpu(fn, repeat: int = 3) -> tuple[float, float, object]:
    """(best CPU seconds, best wall seconds, last result) of ``fn()``."""
    cpu, wall, out = math.inf, math.inf, None
    for _ in range(repeat):
        c0, w0 = time.process_time(), time.perf_counter()
        out = fn()
        cpu, wall = min(cpu, time.process_time() - c0), min(wall, time.perf_counter() - w0)
    return cpu, wall, out


def scaling_rows(ns) -> tuple[list[dict], list[dict]]:
    """(rows of scaling.json, rows of the fixed-cost measurement)."""
    from chaplygin_nd.simulate.dynamics import families
    from chaplygin_nd.simulate.dynamics.field import FullField
    from chaplygin_nd.simulate.integrators import dop853, heyoka_systems, heyoka_taylor

    rows, fixed = [], []
    for n in ns:
        f = FullField(n, A, B)
        M, g = families.draw("generic", n, A, B, seed=7)
        y0 = f.pack(M, g)
        t = np.linspace(0.0, T_END, 11)
        ref = heyoka_taylor.integrate(f, y0, t, tol=2.0**-52, compact=True)

        def err(sol, ref=ref):
            return float(np.max(np.abs(sol.y - ref.y)) / max(1.0, np.max(np.abs(ref.y))))

        first = heyoka_taylor.integrate(f, y0, t, tol=1e-12, compact=True)
        cpu, wall, sol = _cpu(lambda f=f, y0=y0, t=t: heyoka_taylor.integrate(f, y0, t, tol=1e-12,
                                                                               compact=True), 5)
        ta, _, _ = heyoka_taylor.compiled_integrator(heyoka_systems.full(n), "double", 1e-12, True, 1)
        rows.append({"n": n, "method": "heyoka compact", "setting": "tol 1e-12", "error": err(sol),
                     "seconds": cpu, "wall": wall, "compile_seconds": first.compile_seconds,
                     "ops": len(ta.decomposition), "steps": sol.steps})
        raw = math.inf
        for _ in range(20):
            ta.state[:] = y0[0]
            ta.time = 0.0
            w0 = time.perf_counter()
            ta.propagate_grid(t)
            raw = min(raw, time.perf_counter() - w0)
        whole = min(_cpu(lambda f=f, y0=y0, t=t: heyoka_taylor.integrate(
            f, y0, t, tol=1e-12, compact=True), 1)[1] for _ in range(20))
        fixed.append({"n": n, "wall_ms": whole * 1e3, "raw_ms": raw * 1e3,
                      "fixed_ms": (whole - raw) * 1e3})
        for rtol in (1e-10, 1e-11, 1e-12, 1e-13):
            cpu, wall, sol = _cpu(lambda f=f, y0=y0, t=t, rtol=rtol: dop853.integrate(
                f, y0, t, rtol=rtol, atol=rtol), 1 if n > 16 else 2)
            if err(sol) <= ERROR or rtol == 1e-13:
                break
        rows.append({"n": n, "method": "DOP853", "setting": f"rtol = atol = {rtol:g}",
                     "error": err(sol), "seconds": cpu, "wall": wall, "compile_seconds": 0.0,
                     "ops": None, "steps": sol.steps})
        print(f"  n = {n}: heyoka {rows[-2]['seconds']:.4f} s CPU (error {rows[-2]['error']:.1e}, "
              f"{rows[-2]['ops']} ops, compile {rows[-2]['compile_seconds']:.2f} s), DOP853 "
              f"{rows[-1]['seconds']:.4f} s (error {rows[-1]['error']:.1e}), fixed cost "
              f"{fixed[-1]['fixed_ms']:.3f} ms", flush=True)
    return rows, fixed


def cfunc_rows() -> list[dict]:
    """The compiled L_gamma^{-1} wrapper against its raw cfunc, 10^3 points, n = 4 and 12."""
    from chaplygin_nd.runtime import compiled

    out = []
    for n in (4, 12):
        fn, _, _ = compiled.angular_velocity_function(n)
        d, N = n * (n - 1) // 2, 1000
        inputs = np.ascontiguousarray(np.random.default_rng(n).normal(size=(d + n, N)))
        pars, res = np.empty((2, N)), np.empty((d, N))
        pars[0], pars[1] = A, B

        def raw(fn=fn, inputs=inputs, pars=pars, res=res):
            fn(inputs, pars=pars, outputs=res)

        def wrapper(inputs=inputs):
            compiled.angular_velocity_columns(inputs, A, B)

        best = {}
        for name, fun in (("raw", raw), ("wrapper", wrapper), ("raw", raw), ("wrapper", wrapper)):
            fun()
            t = min(_timed(fun) for _ in range(200))
            best[name] = min(best.get(name, math.inf), t)
        out.append({"n": n, "points": N, "raw_us": best["raw"] * 1e6,
                    "wrapper_us": best["wrapper"] * 1e6, "ratio": best["wrapper"] / best["raw"]})
    return out


def _timed(fn) -> float:
    start = time.perf_counter()
    fn()
    return time.perf_counter() - start


def _exponent(ns, values) -> float:
    """Least-squares slope of log(value) against log(n)."""
    x, y = np.log(np.asarray(ns, float)), np.log(np.asarray(values, float))
    return float(np.polyfit(x, y, 1)[0])


def _scene_variant(scene: str, method: str | None, folder: Path) -> Path:
    text = (ROOT / "scenes" / f"{scene}.toml").read_text()
    if method is not None:
        text = re.sub(r"(?m)^\s*method\s*=.*$", "", text)
        if "[accuracy]" not in text:
            text += "\n[accuracy]\n"
        text = text.replace("[accuracy]", f'[accuracy]\nmethod = "{method}"', 1)
    path = folder / f"{scene}-{method or 'auto'}.toml"
    path.write_text(text)
    return path


def _run_cli(scene_file: Path, env: dict, out: Path) -> dict:
    start = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "chaplygin_nd", "simulate", str(scene_file),
                           "--out", str(out), "--no-plots"], env=env, capture_output=True,
                          text=True, **processes.popen_kwargs())
    wall = time.perf_counter() - start
    text = proc.stdout + proc.stderr
    integ = re.search(r"([0-9.eE+-]+) s integrating", text)
    chosen = re.search(r"cost: predicted (.*?)(;| \(outputs)", text)
    predicted = None
    if chosen:
        run = re.search(r"run ([0-9.eE+-]+) (ms|s)\)", chosen.group(1)) or \
            re.search(r"DOP853 ~([0-9.eE+-]+) (ms|s)", chosen.group(1))
        if run:
            predicted = float(run.group(1)) * (1e-3 if run.group(2) == "ms" else 1.0)
    model = re.search(r"model: \S+ \((.*?)\)", text)
    return {"exit": proc.returncode, "wall": wall, "integration": float(integ.group(1)) if integ else None,
            "predicted_run": predicted, "method": model.group(1) if model else "",
            "error": text.strip().splitlines()[-1] if proc.returncode else ""}


def first_result_rows(scenes=SCENES) -> list[dict]:
    """Cold then warm command-line runs of each scene: auto, forced DOP853, forced heyoka."""
    rows = []
    with tempfile.TemporaryDirectory(prefix="chaplygin-ttfr-") as tmp:
        tmp = Path(tmp)
        for scene in scenes:
            variants = {"auto": None, "dop853": "dop853", "heyoka": "heyoka"}
            files = {k: _scene_variant(scene, m, tmp) for k, m in variants.items()}
            for state in ("cold", "warm"):
                best: dict[str, dict] = {}
                for rep in range(2):
                    for k, path in files.items():
                        cache = tmp / f"cache-{scene}-{k}-{rep}"
                        env = dict(os.environ, CHAPLYGIN_ND_CACHE=str(cache / "nd"),
                                   XDG_CACHE_HOME=str(cache / "xdg"))
                        if state == "cold":
                            for sub in ("nd", "xdg"):
                                folder = cache / sub
                                if folder.exists():
                                    import shutil

                                    shutil.rmtree(folder)
                        else:  # warm: the caches of this variant's cold run
                            env = dict(env, CHAPLYGIN_ND_CACHE=str(tmp / f"cache-{scene}-{k}-0" / "nd"),
                                       XDG_CACHE_HOME=str(tmp / f"cache-{scene}-{k}-0" / "xdg"))
                        r = _run_cli(path, env, tmp / f"out-{scene}-{k}-{state}-{rep}")
                        if k in best and best[k]["integration"] and r["integration"]:
                            # a ~1 ms integration is one scheduler quantum from 10 ms on a loaded
                            # machine: the best of the two is the estimate's reference
                            r["integration"] = min(r["integration"], best[k]["integration"])
                        if k not in best or r["wall"] < best[k]["wall"]:
                            best[k] = dict(r, integration=r["integration"] if k not in best else
                                           min(r["integration"] or math.inf,
                                               best[k]["integration"] or math.inf))
                for k, r in best.items():
                    rows.append({"scene": scene, "caches": state, "variant": k, **r})
                print(f"  {scene} {state}: " + ", ".join(
                    f"{k} {r['wall']:.2f} s ({r['method']})" for k, r in best.items()), flush=True)
    return rows


def _figure(rows, path: Path) -> dict:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11, 4.4), layout="constrained")
    fits = {}
    for method, color in (("heyoka compact", "C0"), ("DOP853", "C3")):
        sel = [r for r in rows if r["method"] == method]
        ns = [r["n"] for r in sel]
        secs = [r["seconds"] for r in sel]
        big = [(n, s) for n, s in zip(ns, secs) if n >= 8]
        fits[method] = _exponent(*zip(*big)) if len(big) >= 2 else float("nan")
        ax.loglog(ns, secs, "o-", color=color,
                  label=f"{method}: CPU s of the run (n >= 8: ~n^{fits[method]:.2f})")
        if method.startswith("heyoka"):
            comp = [r["compile_seconds"] for r in sel]
            ax.loglog(ns, comp, "s--", color=color, alpha=0.6, label="heyoka compact: compile s")
            ops = [r["ops"] for r in sel]
            big_ops = [(n, o) for n, o in zip(ns, ops) if n >= 8]
            fits["ops"] = _exponent(*zip(*big_ops)) if len(big_ops) >= 2 else float("nan")
            ax2.loglog(ns, ops, "o-", color=color,
                       label=f"decomposition of the O(n^2) field (~n^{fits['ops']:.2f})")
            ax2.loglog(ns, [30 * n * n for n in ns], "k:", label="target 30 n^2")
    ax2.loglog([12, 32], [4015, 69535], "x", color="C3", ms=8,
               label="old O(n^3) field (before: 4 015, 69 535)")
    ax.set_xlabel("n")
    ax.set_ylabel("seconds")
    ax.set_title(f"full field, T = {T_END:g}, error <= {ERROR:g} (both)")
    ax2.set_xlabel("n")
    ax2.set_ylabel("elementary operations")
    ax2.set_title("heyoka's decomposition of the full field")
    from matplotlib.ticker import FixedLocator, NullLocator, ScalarFormatter

    ticks = sorted({r["n"] for r in rows})
    for a in (ax, ax2):
        a.xaxis.set_major_locator(FixedLocator(ticks))
        a.xaxis.set_major_formatter(ScalarFormatter())
        a.xaxis.set_minor_locator(NullLocator())
        a.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=8, loc="center left", bbox_to_anchor=(0.0, 0.6))
    ax2.legend(fontsize=8, loc="upper left")
    save_figure(fig, path)
    plt.close(fig)
    return fits


def _targets(rows, fixed, cfuncs, first, fits) -> list[str]:
    lines = []
    ops = {r["n"]: r["ops"] for r in rows if r["method"] == "heyoka compact"}
    span = [n for n in ops if 8 <= n <= 32]
    worst = max((ops[n] / n**2 for n in span), default=float("nan"))
    lines.append(target("decomposition of the full field <= 30 n^2 for n = 8..32",
                        bool(span) and worst <= 30,
                        f"max ops/n^2 = {worst:.1f} over n = {span}; growth ~n^{fits.get('ops', float('nan')):.2f}"))
    by = {(r["n"], r["method"]): r for r in rows}
    for n, want in ((12, 20), (32, 3)):
        h, d = by.get((n, "heyoka compact")), by.get((n, "DOP853"))
        if h and d:
            ratio = d["seconds"] / h["seconds"]
            ok = ratio >= want and h["error"] <= ERROR and d["error"] <= ERROR
            detail = (f"DOP853/heyoka CPU = {ratio:.1f} (DOP853 {d['seconds']:.4f} s at error "
                      f"{d['error']:.1e}, heyoka {h['seconds']:.5f} s at error {h['error']:.1e})")
        else:
            ok, detail = False, "not measured (--quick)"
        lines.append(target(f"heyoka / DOP853 at equal error (<= 1e-10, T = 10) >= {want}x at n = {n}",
                            ok, detail))
    worst_fixed = max((r for r in fixed if r["n"] <= 32), key=lambda r: r["fixed_ms"])
    lines.append(target("fixed cost of a warm heyoka integrate call <= 0.1 ms at every n <= 32",
                        all(r["fixed_ms"] <= 0.1 for r in fixed if r["n"] <= 32),
                        f"worst {worst_fixed['fixed_ms']:.3f} ms at n = {worst_fixed['n']}"))
    worst_c = max(cfuncs, key=lambda r: r["ratio"])
    lines.append(target("compiled L_gamma^-1 wrapper at 10^3 points <= 2x its raw cfunc",
                        worst_c["ratio"] <= 2,
                        "; ".join(f"n = {r['n']}: {r['wrapper_us']:.1f} vs {r['raw_us']:.1f} us "
                                  f"({r['ratio']:.2f}x)" for r in cfuncs)))
    for state, rule in (("cold", "the cheaper of forced DOP853 and forced heyoka"),
                        ("warm", "forced heyoka")):
        details, ok = [], True
        for scene in sorted({r["scene"] for r in first}):
            sel = {r["variant"]: r for r in first if r["scene"] == scene and r["caches"] == state}
            if len(sel) < 3:
                continue
            ref = (min(sel["dop853"]["wall"], sel["heyoka"]["wall"]) if state == "cold"
                   else sel["heyoka"]["wall"])
            ratio = sel["auto"]["wall"] / ref
            ok &= ratio <= 1.1 and sel["auto"]["exit"] == 0
            details.append(f"{scene} {ratio:.2f} (auto {sel['auto']['wall']:.2f} s: "
                           f"{sel['auto']['method']}; DOP853 {sel['dop853']['wall']:.2f} s, heyoka "
                           f"{sel['heyoka']['wall']:.2f} s)")
        lines.append(target(f"{state} caches: every scene's wall <= 1.1x {rule}",
                            ok and bool(details), "; ".join(details) or "not measured"))
    est = [(r["predicted_run"] / r["integration"], r) for r in first
           if r["predicted_run"] and r["integration"]]
    worst_est = max(est, key=lambda x: max(x[0], 1 / x[0]), default=None)
    lines.append(target("every printed run estimate within 3x of the integration time",
                        worst_est is not None and all(1 / 3 <= q <= 3 for q, _ in est),
                        f"{len(est)} runs; worst predicted/actual = {worst_est[0]:.2f} "
                        f"({worst_est[1]['scene']} {worst_est[1]['variant']} {worst_est[1]['caches']})"
                        if worst_est else "no estimate parsed"))
    return lines


def main(outdir, quick: bool = False) -> int:
    """Run the sections; write scaling.json, scaling.png, first_result.json, scaling.md."""
    from chaplygin_nd.bench.report import heyoka_available, machine

    ok, why = heyoka_available()
    if not ok:
        print(why)
        return 0
    outdir = Path(outdir)
    ns = (3, 4, 8) if quick else (3, 4, 5, 6, 8, 10, 12, 16, 20, 24, 28, 32, 64)
    rows, fixed = scaling_rows(ns)
    write_rows(outdir / "scaling.json", rows)
    fits = _figure(rows, outdir / "scaling.png")
    cfuncs = cfunc_rows()
    first = first_result_rows(SCENES[:1] if quick else SCENES)
    write_rows(outdir / "first_result.json", first)
    lines = _targets(rows, fixed, cfuncs, first, fits)
    print("\n".join(lines))
    md = ["# Scaling in n and time to first result (bench/bench_scaling.py)", "", *machine(), "",
          "Ratios are measured side by side in one run (A B C A B C, best of two); the machine is "
          "shared, so absolute seconds are noisy.", "", *lines, "",
          f"Fitted growth (n >= 8): heyoka CPU ~n^{fits['heyoka compact']:.2f}, DOP853 CPU "
          f"~n^{fits['DOP853']:.2f}, decomposition ~n^{fits['ops']:.2f}.", "",
          "| n | method | setting | error | CPU s | wall s | compile s | ops |", "|---|---|---|---|---|---|---|---|"]
    md += [f"| {r['n']} | {r['method']} | {r['setting']} | {r['error']:.1e} | {r['seconds']:.5f} | "
           f"{r['wall']:.5f} | {r['compile_seconds']:.2f} | {r['ops'] if r['ops'] else ''} |" for r in rows]
    md += ["", "| n | warm integrate wall ms | raw propagate_grid ms | fixed ms |", "|---|---|---|---|"]
    md += [f"| {r['n']} | {r['wall_ms']:.3f} | {r['raw_ms']:.3f} | {r['fixed_ms']:.3f} |" for r in fixed]
    md += ["", "| scene | caches | variant | exit | wall s | integration s | predicted run s | method |",
           "|---|---|---|---|---|---|---|---|"]
    md += [f"| {r['scene']} | {r['caches']} | {r['variant']} | {r['exit']} | {r['wall']:.2f} | "
           f"{r['integration'] if r['integration'] is not None else ''} | "
           f"{r['predicted_run'] if r['predicted_run'] is not None else ''} | {r['method']} |"
           for r in first]
    write_atomic(outdir / "scaling.md", "\n".join(md) + "\n")
    write_atomic(outdir / "scaling_fixed.json",
                 json.dumps({"fixed_cost": fixed, "cfunc": cfuncs}, indent=1) + "\n")
    return 0
