r"""How the exact checks grow with $n$, per engine (SymPy, FLINT), and what each engine costs.

Runs the all-$n$ ledger rows in this process with the seeded point checks up to
``symbolic.exact.points.ALL_N_MAX`` ($n = 24$), SymPy deciding the points up to ``SYMPY_N`` (default 14:
beyond the ledger's 12, to show its growth) and FLINT every $n$, and reads the engine's own timing
record (:func:`symbolic.exact.identity.point_timings`): seconds per (row, $n$, engine) summed over the
row's points at that $n$ (value and zero test), and per identity check the seconds each engine
spent. The growth exponent of each (row, engine) is the least-squares slope of
$\log(\text{seconds})$ against $\log n$: SymPy over $n \ge 8$, FLINT over the $n$ where it
evaluates alone (above ``SYMPY_N``). ``EXACT_GROWTH_REPLOT=1`` re-renders the last JSON.

Writes ``exact_growth.json`` (``rows``: row, n, engine, seconds; ``fits``: row, engine,
exponent, n range; ``kinds``: SymPy vs FLINT seconds per kind of check), ``exact_growth.md`` and
``exact_growth.png`` (log-log, one panel per row). Timings depend on the machine's load: the
JSON records the load average at start and end.

Run: ``chaplygin bench exact_growth`` (``--quick``: up to n = 14, SymPy to 12).
"""

from __future__ import annotations

import json
import math
import os
import platform
import time
from collections import defaultdict
from pathlib import Path

from chaplygin_nd.writing import write_atomic

#: The rows with seeded point checks for every n (the [n] column reaches ALL_N_MAX).
ROWS = ("eq:M-O-axi-symm", "P:inversion", "eq:aux-inversion", "P:Measure", "eq:action",
        "eq:V-velocity", "Th:Re", "Th:Re-corollary", "eq:xiVnD", "eq:itildendim",
        "eq:solManakov", "eq:motion-velocitynD", "eq:iso-spectral", "eq:pol-first-integrals",
        "S2.2:energy", "eq:invmeasuredet", "eq:def-H-V", "S5:H-linear-nD")
SYMPY_N = 14


def measure(top: int, sympy_n: int, rows=ROWS) -> dict:
    """Run ``rows`` with points up to ``top`` (SymPy up to ``sympy_n``); the timing tables."""
    os.environ.setdefault("SYMPY_GROUND_TYPES", "gmpy")
    from chaplygin_nd.ledger.catalog import discover
    from chaplygin_nd.ledger.registry import registry
    from chaplygin_nd.symbolic.exact import identity, points

    old = points.ALL_N_MAX, identity.SYMPY_POINT_MAX_N, points.SPARSE_LARGE_N
    # every n up to ``top``, also for the rows the ledger samples sparsely above 12
    points.ALL_N_MAX, identity.SYMPY_POINT_MAX_N = top, sympy_n
    points.SPARSE_LARGE_N = tuple(range(13, top + 1))
    try:
        discover()
        specs = registry()
        per_n: dict = defaultdict(float)
        kinds: dict = defaultdict(float)
        verdicts = {}
        for row in rows:
            identity.point_timings(clear=True)
            start = time.perf_counter()
            verdicts[row] = specs[row].run().verdict
            wall = time.perf_counter() - start
            for kind, _label, size, engine, seconds in identity.point_timings(clear=True):
                if kind == "points" and size is not None:
                    per_n[(row, size, engine)] += seconds
                    band = "points n <= 12" if size <= 12 else "points n > 12"
                    kinds[(band, engine)] += seconds
                else:
                    kinds[("identity", engine)] += seconds
            print(f"  {row:24s} {verdicts[row]:8s} {wall:7.2f} s", flush=True)
    finally:
        points.ALL_N_MAX, identity.SYMPY_POINT_MAX_N, points.SPARSE_LARGE_N = old
    table = [{"row": r, "n": n, "engine": e, "seconds": round(s, 5)}
             for (r, n, e), s in sorted(per_n.items())]
    return {"rows": table, "fits": fits(table, flint_from=sympy_n + 1), "verdicts": verdicts,
            "kinds": [{"kind": k, "engine": e, "seconds": round(s, 3)}
                      for (k, e), s in sorted(kinds.items())]}


def fits(table: list[dict], n_min: int = 8, flint_from: int = 13) -> list[dict]:
    """Least-squares slope of log(seconds) on log(n) per (row, engine): SymPy over n >= ``n_min``,
    FLINT over n >= ``flint_from`` (where it evaluates alone; below, when the residual has no
    engine-dispatched step, FLINT only re-tests SymPy's value and its time is not a growth)."""
    series: dict = defaultdict(list)
    for r in table:
        low = flint_from if r["engine"] == "flint" else n_min
        if r["n"] >= low and r["seconds"] > 0:
            series[(r["row"], r["engine"])].append((math.log(r["n"]), math.log(r["seconds"])))
    out = []
    for (row, engine), xy in sorted(series.items()):
        if len(xy) < 3:
            continue
        mx = sum(x for x, _ in xy) / len(xy)
        my = sum(y for _, y in xy) / len(xy)
        slope = (sum((x - mx) * (y - my) for x, y in xy) / sum((x - mx) ** 2 for x, _ in xy))
        ns = [round(math.exp(x)) for x, _ in xy]
        out.append({"row": row, "engine": engine, "exponent": round(slope, 2),
                    "n_from": min(ns), "n_to": max(ns)})
    return out


def markdown(result: dict) -> str:
    """The tables: per-n seconds (FLINT and SymPy), the exponents, the kinds of check."""
    by = defaultdict(dict)
    ns = sorted({r["n"] for r in result["rows"]})
    for r in result["rows"]:
        by[(r["row"], r["engine"])][r["n"]] = r["seconds"]
    big = [n for n in ns if n >= 8]
    lines = ["# Exact checks: growth with n, per engine", "",
             f"Machine: {platform.machine()}, {os.cpu_count()} cores; load average "
             f"{result['load'][0]} at start, {result['load'][1]} at end (timings under that load).",
             f"SymPy ground types: {result['ground_types']}. Seconds per row and n, summed over "
             "the row's seeded points at that n (value and zero test).", "",
             "| row | engine | " + " | ".join(f"n={n}" for n in big) + " | exponent |",
             "|---|---|" + "---|" * (len(big) + 1)]
    exps = {(f["row"], f["engine"]): f["exponent"] for f in result["fits"]}
    for (row, engine), vals in sorted(by.items()):
        cells = " | ".join(f"{vals[n]:.3f}" if n in vals else "" for n in big)
        lines.append(f"| `{row}` | {engine} | {cells} | {exps.get((row, engine), '')} |")
    lines += ["", "## SymPy and FLINT per kind of check (seconds, all rows above)", "",
              "| kind | SymPy | FLINT | SymPy / FLINT |", "|---|---|---|---|"]
    kinds = defaultdict(dict)
    for k in result["kinds"]:
        kinds[k["kind"]][k["engine"]] = k["seconds"]
    for kind, d in sorted(kinds.items()):
        s, f = d.get("sympy"), d.get("flint")
        ratio = f"{s / f:.1f}" if s and f else ""
        lines.append(f"| {kind} | {s if s is not None else ''} | {f if f is not None else ''} | {ratio} |")
    lines += ["", "`points n > 12` with SymPy is measured only by this bench (the ledger decides "
              "those points with FLINT alone).", ""]
    return "\n".join(lines)


def figure(result: dict, path: Path) -> None:
    """Log-log seconds against n, one panel per row, FLINT solid and SymPy dashed."""
    import matplotlib
    import matplotlib.ticker
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = sorted({r["row"] for r in result["rows"]})
    cols = 4
    fig, axes = plt.subplots(math.ceil(len(rows) / cols), cols, figsize=(16, 3.2 * math.ceil(len(rows) / cols)),
                             squeeze=False)
    exps = {(f["row"], f["engine"]): f["exponent"] for f in result["fits"]}
    for ax, row in zip(axes.flat, rows):
        for engine, style in (("flint", "-o"), ("sympy", "--s")):
            pts = sorted((r["n"], r["seconds"]) for r in result["rows"]
                         if r["row"] == row and r["engine"] == engine and r["seconds"] > 0)
            if pts:
                label = f"{'FLINT' if engine == 'flint' else 'SymPy'}"
                if (row, engine) in exps:
                    label += f" (slope {exps[(row, engine)]})"
                ax.loglog([p[0] for p in pts], [p[1] for p in pts], style, ms=3, label=label)
        edge = result.get("sympy_up_to_n", SYMPY_N) + 0.5
        ax.axvline(edge, color="grey", lw=0.8, ls=":")
        ax.set_xticks([4, 8, 12, 16, 20, 24])
        ax.xaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.set_title(row, fontsize=9)
        ax.set_xlabel("n")
        ax.set_ylabel("seconds at n")
        ax.legend(fontsize=7)
        ax.grid(True, which="both", alpha=0.3)
    for ax in list(axes.flat)[len(rows):]:
        ax.axis("off")
    fig.suptitle("Seeded exact point checks: seconds per n (sum over the row's points), log-log. "
                 "Left of the dotted line both engines run; where a row has no engine-dispatched "
                 "step FLINT only re-tests SymPy's value there (tiny times); right of it FLINT "
                 "evaluates alone", fontsize=10, wrap=True)
    fig.tight_layout()
    try:
        write_atomic(path, lambda tmp: fig.savefig(tmp, dpi=90))
    finally:
        plt.close(fig)


def _write(path: Path, text: str) -> None:
    write_atomic(path, text)


def main(out: Path, quick: bool = False) -> int:
    """Measure, then write exact_growth.json / .md / .png into ``out``."""
    from chaplygin_nd.symbolic.exact.flint_engine import sympy_ground_types

    top, sympy_n = (14, 12) if quick else (24, SYMPY_N)
    load0 = os.getloadavg()[0]
    if os.environ.get("EXACT_GROWTH_REPLOT") == "1":  # re-render the last measurement
        result = json.loads((out / "exact_growth.json").read_text())
        result["fits"] = fits(result["rows"], flint_from=result["sympy_up_to_n"] + 1)
        load0 = result["load"][0]
    else:
        result = measure(top, sympy_n)
    if os.environ.get("EXACT_GROWTH_REPLOT") != "1":
        result.update({"top_n": top, "sympy_up_to_n": sympy_n,
                       "ground_types": sympy_ground_types(),
                       "load": [round(load0, 2), round(os.getloadavg()[0], 2)],
                       "cores": os.cpu_count()})
    out.mkdir(parents=True, exist_ok=True)
    _write(out / "exact_growth.json", json.dumps(result, indent=1) + "\n")
    _write(out / "exact_growth.md", markdown(result))
    figure(result, out / "exact_growth.png")
    print(markdown(result))
    return 0


if __name__ == "__main__":
    import sys
    sys.exit(main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).parent / "out"))
