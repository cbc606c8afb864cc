r"""Cost of the exact first-integral search (row S6:first-integrals) per (n, box, space): the
weight-zero monomials of a maximal torus (symbolic/search/integral_search.py) against the
invariant ring (symbolic/search/invariant_search.py), side by side in one run.

Each (box, space) runs in a fresh child process (its peak resident memory is then the box's own):
seconds, peak RSS, the unknowns and the largest block (FLINT ``nmod_mat``: the rank of a block of
$N$ unknowns costs $\sim N^3$), and the estimate printed before a run (symbolic/search/cost.py)
beside the measurement. A weight-zero box too heavy for the run is not run: its row gives the
exact unknowns and the estimate only. The growth exponent is the least-squares slope of
$\log(\text{seconds})$ on $\log(\text{unknowns})$ per space. Timings depend on the load: the JSON
records the load average at start and end, and both spaces of a box run one after the other.

Writes ``first_integrals.json`` and ``first_integrals.md``. Run: ``chaplygin bench
first_integrals`` (``--quick``: the small boxes only).
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

#: (n, box, run the weight-zero space too)
QUICK = ((3, (2, 4, 1), True), (3, (3, 4, 1), True), (4, (2, 4, 1), True), (4, (4, 6, 1), True),
         (5, (2, 4, 1), True), (5, (4, 4, 1), True), (6, (3, 5, 1), True))
FULL = QUICK + ((5, (4, 6, 1), True), (5, (5, 5, 0), True), (5, (6, 6, 2), True),
                (6, (4, 4, 1), True), (5, (7, 8, 1), False), (5, (8, 8, 0), False),
                (5, (8, 8, 1), False), (5, (8, 8, 2), False), (6, (6, 6, 1), False),
                (6, (6, 6, 2), False), (7, (4, 6, 1), False), (7, (6, 6, 1), False),
                (7, (6, 6, 2), False))


def _one(n: int, box: tuple, space: str) -> dict:
    import resource
    import time

    from chaplygin_nd.proofs.s6_first_integrals import model_for
    from chaplygin_nd.symbolic.search import cost
    from chaplygin_nd.symbolic.search.strategies import make_search

    search = make_search(model_for(n), space)
    est = cost.estimate(search, box)
    t0 = time.perf_counter()
    r = search.run_box(box)
    return {"n": n, "d": box[0], "d_gamma": box[1], "k": box[2], "space": space,
            "unknowns": r.unknowns, "largest_block": max(b.unknowns for b in r.blocks),
            "found": r.found, "known": r.known, "settled": r.settled, "engine": search.backend.name,
            "seconds": round(time.perf_counter() - t0, 3),
            "peak_mb": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, 1),
            "estimated_seconds": round(est.seconds, 2), "estimated_mb": round(est.bytes / 2**20)}


def _not_run(n: int, box: tuple) -> dict:
    from chaplygin_nd.proofs.s6_first_integrals import model_for
    from chaplygin_nd.symbolic.search import cost
    from chaplygin_nd.symbolic.search.strategies import make_search

    est = cost.estimate(make_search(model_for(n), "weight-zero"), box)
    return {"n": n, "d": box[0], "d_gamma": box[1], "k": box[2], "space": "weight-zero",
            "unknowns": est.unknowns, "largest_block": est.largest, "found": None, "known": None,
            "settled": None, "engine": "not run", "seconds": None, "peak_mb": None,
            "estimated_seconds": round(est.seconds, 2), "estimated_mb": round(est.bytes / 2**20)}


def fits(rows: list[dict]) -> list[dict]:
    out = []
    for space in ("weight-zero", "invariant"):
        xy = [(math.log(r["unknowns"]), math.log(r["seconds"])) for r in rows
              if r["space"] == space and r["seconds"] and r["unknowns"] > 100]
        if len(xy) < 3:
            continue
        mx, my = sum(x for x, _ in xy) / len(xy), sum(y for _, y in xy) / len(xy)
        slope = sum((x - mx) * (y - my) for x, y in xy) / sum((x - mx) ** 2 for x, _ in xy)
        out.append({"space": space, "exponent_in_unknowns": round(slope, 2), "boxes": len(xy)})
    return out


def markdown(result: dict) -> str:
    lines = ["# First-integral search: weight-zero monomials against the invariant ring", "",
             f"Machine: {platform.machine()}, {result['cores']} cores; load average "
             f"{result['load'][0]} at start, {result['load'][1]} at end (timings under that load; "
             "both spaces of a box run one after the other).", "",
             "| n | box (d, d_gamma, k) | space | unknowns | largest block | found | known | "
             "settled | s | peak MB | estimate s | estimate MB |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in result["rows"]:
        lines.append(f"| {r['n']} | ({r['d']}, {r['d_gamma']}, {r['k']}) | {r['space']} | "
                     f"{r['unknowns']} | {r['largest_block']} | {_cell(r['found'])} | "
                     f"{_cell(r['known'])} | {_cell(r['settled'])} | {_cell(r['seconds'])} | "
                     f"{_cell(r['peak_mb'])} | {r['estimated_seconds']} | {r['estimated_mb']} |")
    lines += ["", "Growth (slope of log seconds on log unknowns): "
              + (", ".join(f"{f['space']}: {f['exponent_in_unknowns']} ({f['boxes']} boxes)"
                           for f in result["fits"]) or "too few boxes"), ""]
    return "\n".join(lines)


def _cell(v) -> str:
    return "not run" if v is None else str(v)


def main(out: Path, quick: bool = False) -> int:
    """Measure every (box, space) of QUICK (or FULL), each in its own child process; write the tables."""
    load0 = os.getloadavg()[0]
    rows = []
    for n, box, old_too in (QUICK if quick else FULL):
        for space in ("weight-zero", "invariant"):
            if space == "weight-zero" and not old_too:
                r = _not_run(n, box)
            else:
                with processes.pool(1, get_context("spawn")) as pool:  # dies with this process
                    r = pool.submit(_one, n, box, space).result()
            print(f"  n={n} box={box} {space}: {r['unknowns']} unknowns, {r['seconds']} s, "
                  f"{r['peak_mb']} MB", flush=True)
            rows.append(r)
    result = {"rows": rows, "fits": fits(rows), "cores": os.cpu_count(),
              "load": [round(load0, 2), round(os.getloadavg()[0], 2)]}
    out.mkdir(parents=True, exist_ok=True)
    write_atomic(out / "first_integrals.json", json.dumps(result, indent=1) + "\n")
    write_atomic(out / "first_integrals.md", markdown(result))
    return 0
