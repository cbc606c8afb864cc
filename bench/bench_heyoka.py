r"""heyoka against our integrators: cold compile, warm load and run time, at measured error.

Every function returns rows (dicts) for ``bench/out/work_precision.json`` — keys ``scene, T, method,
setting, error, seconds, compile_seconds`` (``compile_seconds``: the cold JIT compile, or the warm
load from the disk cache, never part of ``seconds``; ``seconds`` is the minimum of several runs) —
or, for :func:`throughput_rows`, ``kernel, backend, points, bytes, seconds``. Cold compiles use a
fresh cache folder; warm loads the same folder with the in-process copies dropped.

* :func:`generic4d_rows` — generic $n = 4$ to $T = 100$: heyoka double across tolerances, DOP853 at
  rtol = atol = 1e-13, and a hand-written heyoka script (``heyoka.from_sympy`` on our derived SymPy
  component field, no builders, no cache); errors against heyoka ``real128`` at tol 1e-30;
* :func:`reduced_rows` — invariant-only output (reduced4d scene): heyoka on the reduced 7D field vs on
  the full field, same tolerance, errors of the invariants;
* :func:`reference_rows` — 30 digits to $T = 20$: ``heyoka.real`` (108 bits) vs our mpmath Taylor;
* :func:`ensemble_rows` — 256 generic $n = 4$ to $T = 10$: batch (SIMD) mode vs stacked DOP853;
* :func:`throughput_rows` — compiled $L_\gamma^{-1}$ (``runtime.compiled``) vs the NumPy kernel vs a
  contiguous copy of exactly the bytes the compiled kernel reads and writes.

Run: ``chaplygin bench heyoka`` (writes ``heyoka.json`` and ``heyoka.md`` into bench/out/).
"""

from __future__ import annotations

import contextlib
import json
import os
import tempfile
import time
from pathlib import Path

import mpmath
import numpy as np
from chaplygin_nd.bench.report import write_atomic
from chaplygin_nd.runtime import jit_cache
from chaplygin_nd.simulate.dynamics import families
from chaplygin_nd.simulate.dynamics.field import FullField, ReducedField
from chaplygin_nd.simulate.dynamics.so import reduced_invariants
from chaplygin_nd.simulate.integrators import dop853, heyoka_taylor, taylor

REPEATS = 5


@contextlib.contextmanager
def _cache(folder):
    old = os.environ.get(jit_cache.ENV)
    os.environ[jit_cache.ENV] = str(folder)
    jit_cache.forget_memory()
    try:
        yield
    finally:
        jit_cache.forget_memory()
        if old is None:
            os.environ.pop(jit_cache.ENV, None)
        else:
            os.environ[jit_cache.ENV] = old


@contextlib.contextmanager
def no_heyoka_diskcache():
    """heyoka >= 7 keeps its own cache of compiled code (``~/.cache/heyoka``); a cold compile is
    measured with it switched off."""
    import heyoka as hy

    before = hy.llvm_state.get_diskcache_enabled()
    hy.llvm_state.set_diskcache_enabled(False)
    hy.llvm_state.clear_memcache()
    try:
        yield
    finally:
        hy.llvm_state.set_diskcache_enabled(before)


def _cold_warm(run):
    """(cold solution, warm solution, best-of-REPEATS seconds) of ``run()`` in a fresh cache:
    cold = compiled from scratch (no cache of ours, none of heyoka's), warm = loaded from ours."""
    with tempfile.TemporaryDirectory() as tmp, _cache(tmp):
        with no_heyoka_diskcache():
            cold = run()
        jit_cache.forget_memory()
        warm = run()
        best = min([warm.seconds] + [run().seconds for _ in range(REPEATS - 1)])
    return cold, warm, best


def _row(scene, T, method, setting, error, seconds, compile_seconds=0.0, **extra):
    return dict(scene=scene, T=T, method=method, setting=setting, error=float(error),
                seconds=float(seconds), compile_seconds=float(compile_seconds), **extra)


def _generic4d(T, samples):
    M0, g0 = families.draw("generic", 4, 0.5, 1.0, 7)
    f = FullField(4, 0.5, 1.0)
    return f, f.pack(M0, g0), np.linspace(0.0, T, samples)


def generic4d_rows(T: float = 100.0, tols=(1e-8, 1e-10, 1e-11, 1e-13, 1e-15)) -> list[dict]:
    """Generic n = 4 (a = 0.5, b = 1, seed 7) to T: heyoka across tolerances (cold, warm), DOP853 and
    the hand-written heyoka script; errors against heyoka real128 (tol 1e-30)."""
    f, y0, t = _generic4d(T, int(10 * T) + 1)
    with tempfile.TemporaryDirectory() as tmp, _cache(tmp):
        ref = heyoka_taylor.integrate(f, y0, t, precision="real128", tol=1e-30)
    rows = [_row("generic4d", T, "heyoka real128", "tol 1e-30 (reference)", 0.0, ref.seconds,
                 ref.compile_seconds)]
    for tol in tols:
        cold, warm, best = _cold_warm(lambda tol=tol: heyoka_taylor.integrate(f, y0, t, tol=tol))
        err = np.max(np.abs(warm.y - ref.y))
        rows.append(_row("generic4d", T, "heyoka", f"tol {tol:g} (cold)", err, cold.seconds,
                         cold.compile_seconds, order=heyoka_taylor.order_for(tol)))
        rows.append(_row("generic4d", T, "heyoka", f"tol {tol:g} (warm)", err, best,
                         warm.compile_seconds, order=heyoka_taylor.order_for(tol)))
    cold, warm, best = _cold_warm(lambda: heyoka_taylor.integrate(f, y0, t, tol=1e-11, compact=True))
    err = np.max(np.abs(warm.y - ref.y))
    rows.append(_row("generic4d", T, "heyoka compact mode", "tol 1e-11 (cold)", err, cold.seconds,
                     cold.compile_seconds))
    rows.append(_row("generic4d", T, "heyoka compact mode", "tol 1e-11 (warm)", err, best,
                     warm.compile_seconds))
    for rtol in (1e-13,):
        sols = [dop853.integrate(f, y0, t, rtol=rtol, atol=rtol) for _ in range(3)]
        rows.append(_row("generic4d", T, "dop853", f"rtol = atol = {rtol:g}",
                         np.max(np.abs(sols[0].y - ref.y)), min(s.seconds for s in sols)))
    for tol in (1e-10, 1e-11):
        script = hand_written_script(tol)
        err, best, compile_seconds = script(y0[0], t, ref.y[:, 0])
        rows.append(_row("generic4d", T, "heyoka hand-written script", f"tol {tol:g}", err, best,
                         compile_seconds))
    return rows


def hand_written_script(tol: float):
    """What a user would write: ``heyoka.from_sympy`` of our derived SymPy n = 4 field (the component
    field of symbolic.codegen.emit.axisym), one ``taylor_adaptive``, ``propagate_grid``; no builders, no cache."""
    import heyoka as hy
    from chaplygin_nd.symbolic.codegen.emit.axisym import component_kernels

    kernel = next(k for k in component_kernels(4) if k.name == "vector_field_axisym_4d")
    symbols = [s for arg in kernel.arguments[:2] for s in arg.symbols]
    a, b = kernel.arguments[2].symbols[0], kernel.arguments[3].symbols[0]
    hv = [hy.expression(s.name) for s in symbols]
    smap = dict(zip(symbols, hv)) | {a: hy.par[0], b: hy.par[1]}
    rhs = [hy.from_sympy(e, smap) for e in kernel.outputs]
    start = time.perf_counter()
    with no_heyoka_diskcache():
        ta = hy.taylor_adaptive(list(zip(hv, rhs)), np.zeros(len(hv)), pars=[0.5, 1.0], tol=tol)
    compile_seconds = time.perf_counter() - start

    def run(y0, t, ref):
        times, err = [], 0.0
        for _ in range(REPEATS):
            ta.state[:] = y0
            ta.time = t[0]
            start = time.perf_counter()
            _, _, _, _, _, states = ta.propagate_grid(t)
            times.append(time.perf_counter() - start)
            err = float(np.max(np.abs(states - ref)))
        return err, min(times), compile_seconds
    return run


def reduced_rows(T: float = 50.0, tol: float = 1e-13) -> list[dict]:
    """reduced4d (a = -0.4, b = 0.7, seed 21), invariants only: heyoka on eq:red-system vs heyoka on
    the full field (invariants computed from its M, gamma), same tol; errors vs real128 full."""
    M0, g0 = families.draw("generic", 4, -0.4, 0.7, 21)
    t = np.linspace(0.0, T, int(10 * T) + 1)
    full, red = FullField(4, -0.4, 0.7), ReducedField(-0.4, 0.7)
    y0, r0 = full.pack(M0, g0), reduced_invariants(M0, g0)
    with tempfile.TemporaryDirectory() as tmp, _cache(tmp):
        ref = heyoka_taylor.integrate(full, y0, t, precision="real128", tol=1e-30)
    r_ref = reduced_invariants(*full.unpack(ref.y))
    rows = []
    for name, field, start, to_r in (("heyoka full 10D", full, y0, lambda y: reduced_invariants(*full.unpack(y))),
                                     ("heyoka reduced 7D", red, r0, lambda y: y)):
        cold, warm, best = _cold_warm(lambda f=field, s=start: heyoka_taylor.integrate(f, s, t, tol=tol))
        err = np.max(np.abs(to_r(warm.y) - r_ref))
        rows.append(_row("reduced4d", T, name, f"tol {tol:g} (cold)", err, cold.seconds,
                         cold.compile_seconds))
        rows.append(_row("reduced4d", T, name, f"tol {tol:g} (warm)", err, best, warm.compile_seconds))
    return rows


def reference_rows(T: float = 20.0, digits: int = 30) -> list[dict]:
    """30-digit references to T = 20 (generic n = 4, gamma0 = (1/2, 1/2, 1/2, 1/2) exactly on S^3):
    heyoka.real vs our mpmath Taylor; the error column is their largest difference."""
    M0, _ = families.draw("generic", 4, 0.5, 1.0, 7)
    f = FullField(4, 0.5, 1.0)
    y0 = f.pack(M0, np.full((1, 4), 0.5))
    t = np.linspace(0.0, T, 21)
    bits = heyoka_taylor.bits_for_digits(digits)
    cold, warm, best = _cold_warm(lambda: heyoka_taylor.integrate(f, y0, t, precision=bits,
                                                                   tol=10.0 ** -(digits + 2)))
    mp = [taylor.integrate(f, y0, t, dps=digits) for _ in range(2)]
    with mpmath.workdps(digits + 10):
        diff = max(abs(u - v) for u, v in zip(warm.y_high.ravel(), mp[0].y_high.ravel()))
    return [_row("reference4d", T, "heyoka real", f"{bits} bits (cold)", diff, cold.seconds,
                 cold.compile_seconds),
            _row("reference4d", T, "heyoka real", f"{bits} bits (warm)", diff, best,
                 warm.compile_seconds),
            _row("reference4d", T, "mpmath Taylor", f"{digits} digits", diff,
                 min(s.seconds for s in mp))]


def ensemble_rows(count: int = 256, T: float = 10.0) -> list[dict]:
    """256 generic n = 4 to T = 10: heyoka batch mode vs one stacked DOP853 system; errors against
    heyoka batch at tol 2^-52 (double; its own error is ~1e-15 here)."""
    M0, g0 = families.draw("generic", 4, 0.5, 1.0, 5, count)
    f = FullField(4, 0.5, 1.0)
    y0 = f.pack(M0, g0)
    t = np.linspace(0.0, T, 11)
    with tempfile.TemporaryDirectory() as tmp, _cache(tmp):
        ref = heyoka_taylor.integrate(f, y0, t, tol=2.0 ** -52)
    rows = []
    for tol in (1e-10, 1e-12):
        cold, warm, best = _cold_warm(lambda tol=tol: heyoka_taylor.integrate(f, y0, t, tol=tol))
        err = np.max(np.abs(warm.y - ref.y))
        rows.append(_row("ensemble256", T, "heyoka batch", f"tol {tol:g}, {warm.note.split(';')[1].strip()} (warm)",
                         err, best, warm.compile_seconds))
        rows.append(_row("ensemble256", T, "heyoka batch", f"tol {tol:g} (cold)", err, cold.seconds,
                         cold.compile_seconds))
    for rtol in (1e-10, 1e-12):
        sols = [dop853.integrate(f, y0, t, rtol=rtol, atol=rtol) for _ in range(2)]
        rows.append(_row("ensemble256", T, "dop853 stacked", f"rtol = atol = {rtol:g}",
                         np.max(np.abs(sols[0].y - ref.y)), min(s.seconds for s in sols)))
    return rows


def _min_time(reps, fn, *args, **kwargs) -> float:
    times = []
    for _ in range(reps):
        start = time.perf_counter()
        fn(*args, **kwargs)
        times.append(time.perf_counter() - start)
    return min(times)


def throughput_rows(points=(10**3, 10**4, 10**5, 10**6), n: int = 4) -> list[dict]:
    """L_gamma^{-1} at N points: the compiled kernel (component-major, a, b per point: it reads
    (d + n + 2) N and writes d N doubles), a contiguous copy of exactly those bytes, and the NumPy
    component kernel of generated/ (same points)."""
    from chaplygin_nd.generated import axisym as ga
    from chaplygin_nd.runtime import compiled

    d = n * (n - 1) // 2
    rows = []
    M, g = families.draw("generic", n, 0.5, 1.0, 1, 1000)
    base = np.concatenate([M[:, *np.triu_indices(n, 1)], g], -1)
    with tempfile.TemporaryDirectory() as tmp, _cache(tmp):
        with no_heyoka_diskcache():
            _, compile_seconds, _ = compiled.angular_velocity_function(n)
        for N in points:
            cols = np.ascontiguousarray(np.resize(base, (N, d + n)).T)
            out, pars = np.empty((d, N)), np.empty((2, N))
            nbytes = 8 * N * (d + n + 2 + d)
            src, dst = np.ones(nbytes // 8), np.empty(nbytes // 8)
            reps = max(3, min(200, 10**6 // N))
            tk = _min_time(reps, compiled.angular_velocity_columns, cols, 0.5, 1.0, out=out, pars=pars)
            tc = _min_time(reps, np.copyto, dst, src)
            vm, gg = np.ascontiguousarray(cols[:d].T), np.ascontiguousarray(cols[d:].T)
            tn = _min_time(reps, ga.angular_velocity_axisym_4d, vm, gg, 0.5, 1.0)
            rows += [dict(kernel=f"angular_velocity n={n}", backend="heyoka cfunc", points=N,
                          bytes=nbytes, seconds=tk, compile_seconds=compile_seconds),
                     dict(kernel=f"angular_velocity n={n}", backend="contiguous copy", points=N,
                          bytes=nbytes, seconds=tc),
                     dict(kernel=f"angular_velocity n={n}", backend="numpy generated", points=N,
                          bytes=8 * N * (d + n + d), seconds=tn)]
    return rows


def targets(wp: list[dict], tp: list[dict]) -> list[str]:
    """The targets, each with its measured ratio and MET / NOT MET."""
    def pick(scene, method, setting_has):
        return [r for r in wp if r["scene"] == scene and r["method"] == method
                and setting_has in r["setting"]]

    lines = []
    ok = [r for r in pick("generic4d", "heyoka", "(warm)") if r["error"] <= 1e-12]
    fastest = min(ok, key=lambda r: r["seconds"]) if ok else None
    dops = pick("generic4d", "dop853", "1e-13")
    dop = dops[0] if dops else None
    if fastest and dop:
        ratio = dop["seconds"] / fastest["seconds"]
        lines.append(f"generic4d T=100, error <= 1e-12: heyoka {fastest['setting']} "
                     f"{fastest['seconds'] * 1e3:.2f} ms (error {fastest['error']:.1e}) vs DOP853 "
                     f"{dop['seconds'] * 1e3:.1f} ms (error {dop['error']:.1e}): {ratio:.0f}x "
                     f"(target >= 50x): {'MET' if ratio >= 50 else 'NOT MET'}")
        tol = fastest["setting"].split()[1]
        same = [r for r in pick("generic4d", "heyoka hand-written script", "")
                if r["setting"] == f"tol {tol}"]
        if same:
            q = fastest["seconds"] / same[0]["seconds"]
            lines.append(f"  vs hand-written heyoka script ({same[0]['setting']}): {q:.2f}x its time "
                         f"(target <= 1.5x): {'MET' if q <= 1.5 else 'NOT MET'}")
    red = pick("reduced4d", "heyoka reduced 7D", "(warm)")
    full = pick("reduced4d", "heyoka full 10D", "(warm)")
    if red and full:
        q = full[0]["seconds"] / red[0]["seconds"]
        lines.append(f"reduced4d invariants: reduced 7D {red[0]['seconds'] * 1e3:.2f} ms vs full "
                     f"{full[0]['seconds'] * 1e3:.2f} ms ({q:.2f}x; the planner picks reduced): "
                     f"{'MET' if q > 1 else 'NOT MET'}")
    hr = pick("reference4d", "heyoka real", "(warm)")
    mp = pick("reference4d", "mpmath Taylor", "")
    if hr and mp:
        q = mp[0]["seconds"] / hr[0]["seconds"]
        digits = -np.log10(max(hr[0]["error"], 1e-300))
        lines.append(f"30-digit reference T=20: heyoka.real {hr[0]['seconds']:.3f} s vs mpmath Taylor "
                     f"{mp[0]['seconds']:.3f} s ({q:.1f}x), agreement {digits:.1f} digits: "
                     f"{'MET' if q > 1 and digits >= 28 else 'NOT MET'}")
    for tol in ("1e-10", "1e-12"):
        hb = pick("ensemble256", "heyoka batch", f"tol {tol}, ")
        ds = pick("ensemble256", "dop853 stacked", tol)
        if hb and ds:
            q = ds[0]["seconds"] / hb[0]["seconds"]
            lines.append(f"ensemble 256 at {tol}: batch {hb[0]['seconds'] * 1e3:.1f} ms (error "
                         f"{hb[0]['error']:.1e}) vs stacked DOP853 {ds[0]['seconds'] * 1e3:.1f} ms "
                         f"(error {ds[0]['error']:.1e}): {q:.0f}x (target >= 10x at equal or better "
                         f"error): {'MET' if q >= 10 and hb[0]['error'] <= ds[0]['error'] else 'NOT MET'}")
    big = [r for r in tp if r["points"] == 10**6]
    if big:
        k = next(r for r in big if r["backend"] == "heyoka cfunc")
        c = next(r for r in big if r["backend"] == "contiguous copy")
        q = k["seconds"] / c["seconds"]
        lines.append(f"compiled L_gamma^-1 at 10^6 points: {k['seconds'] * 1e3:.1f} ms vs copy of the "
                     f"same {k['bytes'] / 1e6:.0f} MB {c['seconds'] * 1e3:.1f} ms: {q:.2f}x (target <= 3x): "
                     f"{'MET' if q <= 3 else 'NOT MET'}")
    return lines


def main(outdir) -> int:
    """Run every measurement; write heyoka.json (rows) and heyoka.md (targets, rows)."""
    if not heyoka_taylor.available():
        print("heyoka is not installed (pip install '.[fast]'): nothing to measure")
        return 0
    outdir = Path(outdir)
    wp = []
    for fn in (generic4d_rows, reduced_rows, reference_rows, ensemble_rows):
        start = time.perf_counter()
        wp += fn()
        print(f"  {fn.__name__}: {time.perf_counter() - start:.1f} s", flush=True)
    tp = throughput_rows()
    lines = targets(wp, tp)
    print("\n".join(lines))
    write_atomic(outdir / "heyoka.json", json.dumps({"work_precision": wp, "throughput": tp}, indent=1))
    md = ["# heyoka against our integrators (bench/bench_heyoka.py)", "", *[f"- {li}" for li in lines],
          "", "| scene | T | method | setting | error | seconds | compile/load s |", "|---|---|---|---|---|---|---|"]
    md += [f"| {r['scene']} | {r['T']:g} | {r['method']} | {r['setting']} | {r['error']:.2e} | "
           f"{r['seconds']:.5f} | {r['compile_seconds']:.3f} |" for r in wp]
    md += ["", "| kernel | backend | points | bytes | seconds |", "|---|---|---|---|---|"]
    md += [f"| {r['kernel']} | {r['backend']} | {r['points']} | {r['bytes']} | {r['seconds']:.6f} |"
           for r in tp]
    write_atomic(outdir / "heyoka.md", "\n".join(md) + "\n")
    return 0


if __name__ == "__main__":
    import sys

    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent / "out"
    out.mkdir(parents=True, exist_ok=True)
    sys.exit(main(out))
