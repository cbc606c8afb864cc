r"""Throughput of $\mathrm{vec}\,\Omega = \mathrm{vec}(L_\gamma^{-1}M)$ (P:inversion), $n = 4$, from 1 to
$10^7$ points.

Backends, all on the same points (seeded), checked against each other before timing:

* ``generated`` — the emitted NumPy kernel ``generated.axisym.angular_velocity_axisym_4d`` (CSE;
  one call up to ``CHUNK`` points, chunks of ``CHUNK`` beyond);
* ``lambdify`` — a plain ``sympy.lambdify`` of the same derived expressions without CSE, evaluated
  on whole arrays (its build time is its ``compile_seconds``);
* ``solve`` — batched ``numpy.linalg.solve`` of the $6\times6$ matrix of $L_\gamma$, assembly by the
  generated ``L_matrix_axisym_4d`` included;
* ``compiled`` — the compiled heyoka backend (``runtime.compiled.angular_velocity_columns``) when
  heyoka imports, on its native component-major layout prepared once (the transposes a caller
  with point-major data would pay are not included); cold compile or warm load in
  ``compile_seconds``;
* ``copy`` — the floor: one contiguous ``numpy.copyto`` with the kernel's memory traffic. The kernel
  reads 80 B and writes 48 B per point (``bytes`` = 128 B per point); a copy of 64 B per point reads
  64 B and writes 64 B, the same 128 B, into a preallocated buffer;
* ``generated CHUNK=k`` — the generated kernel with other chunk lengths (the measurement behind
  ``CHUNK``).

Writes ``throughput.json`` (rows: ``kernel``, ``backend``, ``points``, ``bytes``, ``seconds``,
``compile_seconds``, ...), ``throughput.md`` (tables, target lines MET / NOT MET) and
``throughput.png``. Times are the minimum over repeats (a few at large sizes). Skipped for memory:
``solve`` at $10^7$ points (its $L$ alone is 2.9 GB, doubled inside ``solve``).

Reproduce: ``chaplygin bench throughput`` (``--quick``: up to $10^5$ points).
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
from chaplygin_nd.bench.report import (
    best_time,
    machine,
    save_figure,
    target,
    write_atomic,
    write_rows,
)

KERNEL = "angular_velocity_axisym_4d"
A, B = 0.3, 1.7
READ, WRITTEN = 10 * 8, 6 * 8  # bytes per point: M (6) and gamma (4) read, vec Omega (6) written
SIZES = tuple(10 ** k for k in range(8))
QUICK_SIZES = tuple(10 ** k for k in range(6))
SOLVE_MAX = 10 ** 6
LAMBDIFY_MAX = 10 ** 6  # at 1e7 one run took 37 s under load (80 MB whole-array temporaries)
CHECK_MAX = 10 ** 5  # slow baselines are checked against the kernel up to here (same code beyond)
CHUNKS = (1024, 4096, 16384)


def points(count: int, seed: int = 2026) -> tuple[np.ndarray, np.ndarray]:
    """``count`` seeded points: ``M`` (count, 6) standard normal, ``gamma`` (count, 4) on S^3."""
    rng = np.random.default_rng(seed)
    gamma = rng.standard_normal((count, 4))
    gamma /= np.linalg.norm(gamma, axis=-1, keepdims=True)
    return rng.standard_normal((count, 6)), gamma


def _lambdified():
    """The plain (no CSE) lambdify of the derived expressions, and its build seconds."""
    import sympy as sp
    from chaplygin_nd.symbolic.codegen.emit.axisym import component_kernels

    start = time.perf_counter()
    kernel = next(k for k in component_kernels(4) if k.name == KERNEL)
    syms = [s for arg in kernel.arguments for s in arg.symbols]
    plain = sp.lambdify(syms, list(kernel.outputs), modules="numpy", cse=False)
    return plain, time.perf_counter() - start


def _compiled():
    """``(runtime.compiled, compile seconds, how)``, or ``(None, 0, reason)`` without heyoka."""
    try:
        import heyoka  # noqa: F401
        from chaplygin_nd.runtime import compiled
    except ImportError as exc:
        return None, 0.0, f"not available ({exc})"
    _, seconds, how = compiled.angular_velocity_function(4)
    return compiled, seconds, how


def _backends(count: int, plain, compiled) -> dict:
    """The timed callables on ``count`` seeded points (the copy: its own buffers)."""
    from chaplygin_nd.generated import axisym

    M, gamma = points(count)
    src = np.ones(count * (READ + WRITTEN) // 16)
    dst = np.empty_like(src)

    def lambdified():
        cols = plain(*M.T, *gamma.T, A, B)
        return np.stack([np.broadcast_to(c, (count,)) for c in cols], axis=-1)

    def solve():
        L = axisym.L_matrix_axisym_4d(gamma, A, B)
        return np.linalg.solve(L, M[..., None])[..., 0]

    fns = {"generated": lambda: axisym.angular_velocity_axisym_4d(M, gamma, A, B)}
    if count <= LAMBDIFY_MAX:
        fns["lambdify"] = lambdified
    if count <= SOLVE_MAX:
        fns["solve"] = solve
    if compiled is not None:  # its native layout: component-major columns, prepared once
        cols = np.ascontiguousarray(np.concatenate([M, gamma], axis=-1).T)
        out, pars = np.empty((6, count)), np.empty((2, count))
        fns["compiled"] = lambda: compiled.angular_velocity_columns(cols, A, B, out=out, pars=pars).T
        raw, _, _ = compiled.angular_velocity_function(4)
        pars_ab = np.empty((2, count))
        pars_ab[0], pars_ab[1] = A, B
        fns["compiled raw cfunc"] = lambda: (raw(cols, pars=pars_ab, outputs=out), out.T)[1]
    fns["copy"] = lambda: np.copyto(dst, src)
    return fns


def measure(sizes=SIZES) -> list[dict]:
    """One row per (backend, size); every backend is checked against ``generated`` first."""
    from chaplygin_nd.generated import _batching

    plain, lambdify_seconds = _lambdified()
    compiled, compiled_seconds, compiled_how = _compiled()
    rows = []

    def row(backend, count, seconds, compile_seconds=0.0, note=""):
        rows.append({"kernel": KERNEL, "backend": backend, "points": count,
                     "bytes": count * (READ + WRITTEN), "seconds": seconds,
                     "compile_seconds": compile_seconds,
                     "ns_per_point": None if seconds is None else seconds / count * 1e9,
                     "note": note})

    for count in sizes:
        repeat = 1 if count >= 10 ** 7 else 3 if count >= 10 ** 6 else 5
        budget = 1.0 if count >= 10 ** 6 else 0.3
        fns = _backends(count, plain, compiled)
        ref = fns["generated"]()
        scale = 1.0 + np.abs(ref)
        for name, fn in fns.items():
            if name in ("generated", "copy") or (name in ("lambdify", "solve") and count > CHECK_MAX):
                continue
            err = float(np.max(np.abs(fn() - ref) / scale))
            if not err < 1e-11:
                raise SystemExit(f"throughput: {name} disagrees with the generated kernel at "
                                 f"{count} points (max relative difference {err:.1e})")
        del ref, scale
        row("generated", count, best_time(fns["generated"], repeat, budget),
            note=f"CHUNK={_batching.CHUNK}")
        slow = 2 if count >= 10 ** 6 else repeat  # the slow baselines: fewer repeats
        if "lambdify" in fns:
            row("lambdify", count, best_time(fns["lambdify"], slow, budget), lambdify_seconds,
                "sympy.lambdify, cse=False, whole arrays; compile = build")
        else:
            row("lambdify", count, None, lambdify_seconds,
                "skipped: one run took 37 s at 1e7 points under load (80 MB temporaries)")
        if "solve" in fns:
            row("solve", count, best_time(fns["solve"], slow, budget),
                note="assembly + numpy.linalg.solve")
        else:
            row("solve", count, None, note="skipped: L alone needs 2.9 GB, doubled inside solve")
        if compiled is not None:
            row("compiled", count, best_time(fns["compiled"], repeat, budget),
                compiled_seconds, "chaplygin_nd.runtime.compiled.angular_velocity_columns (heyoka cfunc) on "
                "component-major columns prepared once (+16 B/pt of a, b); compile: "
                f"{compiled_how}")
            row("compiled raw cfunc", count, best_time(fns["compiled raw cfunc"], repeat, budget),
                note="the heyoka cfunc itself, a and b filled once (what angular_velocity_columns "
                     "costs beyond it is Python: it rebuilds and hashes the expression graph to find "
                     "the cached function on every call)")
        row("copy", count, best_time(fns["copy"], repeat, budget),
            note="contiguous copy, 64 B read + 64 B written per point (= the kernel's traffic)")
        if 10 ** 4 <= count <= 10 ** 6:
            saved = _batching.CHUNK
            try:
                for chunk in CHUNKS:
                    _batching.CHUNK = chunk
                    row(f"generated CHUNK={chunk}", count, best_time(fns["generated"], repeat, budget))
            finally:
                _batching.CHUNK = saved
        del fns
        print(f"  {count:>10,} points: " + ", ".join(
            f"{r['backend']} {r['ns_per_point']:.0f} ns/pt" for r in rows
            if r["points"] == count and r["seconds"] is not None and "CHUNK" not in r["backend"]),
            flush=True)
    if compiled is None:
        print(f"  compiled backend: {compiled_how}", flush=True)
    return rows


def _seconds(rows, backend, count):
    for r in rows:
        if r["backend"] == backend and r["points"] == count and r["seconds"] is not None:
            return r["seconds"]
    return None


def targets(rows: list[dict]) -> list[str]:
    """The target lines (issues 5 and 9), each MET or NOT MET."""
    big = max(r["points"] for r in rows)
    n6 = 10 ** 6 if any(r["points"] == 10 ** 6 for r in rows) else big
    g, s, lam, c = (_seconds(rows, b, n6) for b in ("generated", "solve", "lambdify", "copy"))
    out = [target(f"generated >= 50x batched solve at {n6:,} points", s / g >= 50,
                  f"{s / g:.1f}x ({s:.3f} s vs {g:.3f} s)"),
           target(f"generated >= 2x plain lambdify at {n6:,} points", lam / g >= 2,
                  f"{lam / g:.1f}x ({lam:.3f} s vs {g:.3f} s)"),
           target(f"generated within 10x of the copy floor at {n6:,} points", g / c <= 10,
                  f"{g / c:.1f}x the copy ({g:.4f} s vs {c:.4f} s)")]
    sizes = sorted({r["points"] for r in rows})
    ratios = [(n, _seconds(rows, "lambdify", n) / _seconds(rows, "generated", n)) for n in sizes
              if _seconds(rows, "lambdify", n) is not None]
    worst = min(ratios, key=lambda x: x[1])
    out.append(target("generated never loses to plain lambdify (every size measured)",
                      worst[1] >= 1.0, "lambdify / generated = " + ", ".join(
                          f"{r:.1f}x at {n:,}" for n, r in ratios)))
    cc = _seconds(rows, "compiled", n6)
    out.append(target(f"compiled L_gamma^-1 within 3x of the copy floor at {n6:,} points",
                      cc is not None and cc / c <= 3,
                      f"{cc / c:.1f}x the copy ({cc:.4f} s vs {c:.4f} s); compiled vs generated "
                      f"{g / cc:.1f}x" if cc is not None else
                      "not measured: no compiled backend (runtime/compiled.py with heyoka)"))
    return out


def _figure(path: Path, rows: list[dict]) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7.5, 5))
    for backend in dict.fromkeys(r["backend"] for r in rows):
        rs = [r for r in rows if r["backend"] == backend and r["seconds"] is not None]
        style = ":" if "CHUNK" in backend else ("--" if backend == "copy" else "o-")
        ax.loglog([r["points"] for r in rs], [r["ns_per_point"] for r in rs], style, label=backend,
                  lw=1 if "CHUNK" in backend else 1.5, ms=4)
    ax.set_xlabel("points per call")
    ax.set_ylabel("wall time per point [ns] (min of repeats)")
    ax.set_title(f"{KERNEL}: vec Omega = L_gamma^-1 M, n = 4 (lower is faster)", fontsize=9)
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    save_figure(fig, path)
    plt.close(fig)


def markdown(rows: list[dict], lines_of_targets: list[str]) -> str:
    """The Markdown report: machine, targets, and a table of ns per point by backend and size."""
    sizes = sorted({r["points"] for r in rows})
    backends = list(dict.fromkeys(r["backend"] for r in rows))
    head = ["# Throughput: vec Omega = L_gamma^-1 M (P:inversion), n = 4", "", *machine(), "",
            "Reproduce: `chaplygin bench throughput` (from the repository root).", "",
            "## Targets", "", *lines_of_targets, "",
            "## Nanoseconds per point (minimum over repeats)", "",
            "| backend | " + " | ".join(f"{n:,}" for n in sizes) + " | compile s |",
            "|---|" + "---|" * (len(sizes) + 1)]
    for b in backends:
        cells = []
        for n in sizes:
            s = _seconds(rows, b, n)
            cells.append("" if s is None else f"{s / n * 1e9:.1f}")
        comp = max((r["compile_seconds"] for r in rows if r["backend"] == b), default=0.0)
        head.append(f"| {b} | " + " | ".join(cells) + f" | {comp:.2f} |")
    notes: dict[str, dict] = {}
    for r in rows:
        if r["note"]:
            notes.setdefault(r["backend"], {})[r["note"]] = None
    notes = {b: "; ".join(n) for b, n in notes.items()}
    head += ["", "Backends: " + "; ".join(f"`{b}`: {n}" for b, n in notes.items()),
             "", f"bytes per point: {READ} read + {WRITTEN} written. Rows: throughput.json.", ""]
    return "\n".join(head)


def main(outdir: Path, quick: bool = False) -> int:
    """Measure, then write ``throughput.json``, ``throughput.md`` and ``throughput.png``."""
    outdir = Path(outdir)
    rows = measure(QUICK_SIZES if quick else SIZES)
    lines = targets(rows)
    write_rows(outdir / "throughput.json", rows)
    write_atomic(outdir / "throughput.md", markdown(rows, lines))
    _figure(outdir / "throughput.png", rows)
    print("\n".join(["throughput targets:", *lines]), flush=True)
    return 0
