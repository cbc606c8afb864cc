r"""Cost of the exact first-integral search (row S6:first-integrals) per (n, degree box, engine).

Each box $(d, d_\gamma, k)$ runs in a fresh child process (its peak resident memory is then the
box's own): seconds, peak RSS, the number of unknowns and of the largest block (FLINT
``nmod_mat``: the rank of a block of $N$ unknowns costs $\sim N^3$). The growth exponent is the
least-squares slope of $\log(\text{seconds})$ on $\log(\text{largest block})$ per $n$. Timings depend
on the machine's load: the JSON records the load average at start and end.

Writes ``first_integrals.json`` and ``first_integrals.md``. Run: ``chaplygin bench
first_integrals`` (``--quick``: the ``make verify`` boxes only).
"""

from __future__ import annotations

import json
import math
import os
import platform
from multiprocessing import get_context
from pathlib import Path

from chaplygin_nd import processes
from chaplygin_nd.writing import write_atomic

QUICK = {3: ((1, 2, 0), (2, 4, 1), (3, 4, 1)), 4: ((2, 4, 1), (3, 5, 1), (4, 6, 1)),
         5: ((2, 4, 1), (3, 5, 1), (4, 4, 1))}
FULL = {**QUICK, 5: QUICK[5] + ((4, 6, 1), (5, 5, 0), (6, 4, 0)), 6: ((2, 4, 1), (3, 5, 1), (4, 4, 1))}


def _one(n: int, box: tuple) -> dict:
    import resource
    import time

    from chaplygin_nd.proofs.s6_first_integrals import model_for
    from chaplygin_nd.symbolic.search import integral_search as fi

    t0 = time.perf_counter()
    r = fi.search_degree(model_for(n), *box)
    return {"n": n, "d": box[0], "d_gamma": box[1], "k": box[2], "unknowns": r.unknowns,
            "largest_block": max(b.unknowns for b in r.blocks), "found": r.found,
            "known": r.known, "settled": r.settled, "engine": "FLINT nmod_mat",
            "seconds": round(time.perf_counter() - t0, 3),
            "peak_mb": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, 1)}


def fits(rows: list[dict]) -> list[dict]:
    out = []
    for n in sorted({r["n"] for r in rows}):
        xy = [(math.log(r["largest_block"]), math.log(r["seconds"])) for r in rows
              if r["n"] == n and r["largest_block"] > 50 and r["seconds"] > 0]
        if len(xy) < 3:
            continue
        mx, my = sum(x for x, _ in xy) / len(xy), sum(y for _, y in xy) / len(xy)
        slope = sum((x - mx) * (y - my) for x, y in xy) / sum((x - mx) ** 2 for x, _ in xy)
        out.append({"n": n, "exponent_in_largest_block": round(slope, 2), "boxes": len(xy)})
    return out


def markdown(result: dict) -> str:
    lines = ["# First-integral search: cost per box", "",
             f"Machine: {platform.machine()}, {result['cores']} cores; load average "
             f"{result['load'][0]} at start, {result['load'][1]} at end (timings under that load).", "",
             "| n | d | d_gamma | k | unknowns | largest block | found | known | settled | s | peak MB |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in result["rows"]:
        lines.append(f"| {r['n']} | {r['d']} | {r['d_gamma']} | {r['k']} | {r['unknowns']} | "
                     f"{r['largest_block']} | {r['found']} | {r['known']} | {r['settled']} | "
                     f"{r['seconds']} | {r['peak_mb']} |")
    lines += ["", "Growth (slope of log seconds on log largest block): "
              + (", ".join(f"n = {f['n']}: {f['exponent_in_largest_block']}" for f in result["fits"])
                 or "too few boxes"), ""]
    return "\n".join(lines)


def _write(path: Path, text: str) -> None:
    write_atomic(path, text)


def main(out: Path, quick: bool = False) -> int:
    """Measure every box of QUICK (or FULL), each in its own child process; write the tables."""
    load0 = os.getloadavg()[0]
    rows = []
    for n, boxes in (QUICK if quick else FULL).items():
        for box in boxes:
            with processes.pool(1, get_context("spawn")) as pool:  # dies with this process
                r = pool.submit(_one, n, box).result()
            print(f"  n={n} box={box}: {r['unknowns']} unknowns, {r['seconds']} s, "
                  f"{r['peak_mb']} MB", flush=True)
            rows.append(r)
    result = {"rows": rows, "fits": fits(rows), "cores": os.cpu_count(),
              "load": [round(load0, 2), round(os.getloadavg()[0], 2)]}
    out.mkdir(parents=True, exist_ok=True)
    _write(out / "first_integrals.json", json.dumps(result, indent=1) + "\n")
    _write(out / "first_integrals.md", markdown(result))
    return 0
