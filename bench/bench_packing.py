r"""Packing the evidence rows' orbits into heyoka's batches (:mod:`simulate.analysis.packing`):
``chaplygin bench packing`` writes ``packing.md`` and ``packing.json``.

Per row system (the drawn ensembles of the evidence rows at $T$, the row's seed, tangents and
horizon; ``--quick``: the first 24 orbits of two of them), the ensemble is integrated by
:func:`simulate.analysis.drawn_evidence._integrate` in the parameter order of
:func:`simulate.analysis.drawn_evidence.schedule` (no pilot) and packed by the pilot's steps, side by
side in one process after one warm-up compile: the CPU seconds of each (the packed one including its
pilot, measured apart), the useful fraction of the batches' lane-steps
(:func:`simulate.analysis.packing.efficiency`, from each orbit's Taylor steps: identical in both
runs), the oracle's fraction (packed by the real steps), and whether the orbits are bit-identical.
``WIDTHS`` repeats the packed run at other SIMD widths (``BATCH``; a width is a compiled integrator
of its own).
"""

from __future__ import annotations

import json
import os
import time
from pathlib import Path

import numpy as np
from chaplygin_nd.bench.bench_megno_scaling import SEED

#: (label of bench.bench_megno_scaling._case, row)
CASES = (("full4", "S5:reconstruction"), ("control5", "S6:open-reduced-n5 control"),
         ("reduced", "S5:EJ-tori"), ("open5", "S6:open-reduced-n5"),
         ("vertical4", "Th:Re-tori:frequencies n = 4"), ("vertical7", "Th:Re-tori:frequencies n = 7"),
         ("open6", "S6:open-reduced-n6"))
WIDTHS = (4, 16)


def _run(s, ens, y0, packed: bool, width: int) -> dict:
    from chaplygin_nd.simulate.analysis import drawn_evidence as de
    from chaplygin_nd.simulate.analysis import packing
    from chaplygin_nd.simulate.integrators.heyoka_taylor import compiled_integrator

    compiled_integrator(de._system(s), "double", s.tol, compact=True, batch=width,
                        opt_level=de.OPT_LEVEL)                      # compiled before the clock
    order_of, pilot_of = packing.order, packing.pilot_steps
    used, pilot = [], [0.0]

    def order(ta, states, pars, horizons, first=None, **kw):
        out = order_of(ta, states, pars, horizons, first, **kw) if packed else np.asarray(first)
        used.append(out)
        return out

    def pilot_steps(*a, **kw):
        start = time.process_time()
        out = pilot_of(*a, **kw)
        pilot[0] += time.process_time() - start
        return out

    batch = de.BATCH
    packing.order, packing.pilot_steps, de.BATCH = order, pilot_steps, width
    try:
        start = time.process_time()
        Z, megno, _, extra = de._integrate(s, ens, y0, SEED)
        cpu = time.process_time() - start
    finally:
        packing.order, packing.pilot_steps, de.BATCH = order_of, pilot_of, batch
    steps = extra["steps"]
    return {"cpu": round(cpu, 3), "pilot_cpu": round(pilot[0], 3), "steps": int(steps.sum()),
            "efficiency": round(packing.efficiency(steps, used[0], width), 4),
            "oracle": round(packing.efficiency(steps, np.argsort(-steps, kind="stable"), width), 4),
            "Z": Z, "megno": megno}


def measure(label: str, count: int | None = None, widths=WIDTHS) -> dict:
    """The comparison of the module docstring for one row system (its first ``count`` orbits)."""
    from chaplygin_nd.bench.bench_megno_scaling import _case
    from chaplygin_nd.simulate.analysis import drawn_evidence as de

    s, ens, y0 = _case(label)
    if count is not None:
        ens, y0 = de.subset(ens, np.arange(count)), y0[:count]
    before = _run(s, ens, y0, False, de.BATCH)
    after = _run(s, ens, y0, True, de.BATCH)
    same = bool(np.array_equal(before.pop("Z"), after.pop("Z")) and
                np.array_equal(before.pop("megno"), after.pop("megno"), equal_nan=True))
    out = {"orbits": len(y0), "parameter order": before, "packed": after, "identical": same}
    for w in widths:
        r = _run(s, ens, y0, True, w)
        r.pop("Z"), r.pop("megno")
        out[f"packed, width {w}"] = r
    return out


def table(result: dict) -> str:
    """Markdown: one line per row system and run."""
    lines = ["| system (row) | orbits | run | CPU s (pilot) | useful fraction | oracle | bit-identical |",
             "|---|---|---|---|---|---|---|"]
    for label, row in CASES:
        r = result.get(label)
        if r is None:
            continue
        for run, v in r.items():
            if isinstance(v, dict):
                lines.append(f"| {label} ({row}) | {r['orbits']} | {run} | {v['cpu']:.2f} "
                             f"({v['pilot_cpu']:.2f}) | {v['efficiency']:.3f} | {v['oracle']:.3f} | "
                             f"{r['identical'] if run == 'packed' else ''} |")
    return "\n".join(lines)



def main(out: Path, quick: bool = False) -> int:
    """Measure every case (``quick``: 24 orbits of two, no other width) and write
    ``packing.md`` / ``.json`` into ``out``."""
    load0 = os.getloadavg()[0]
    result = {label: measure(label, 24, ()) if quick else measure(label)
              for label, _ in (CASES[:2] if quick else CASES)}
    load = [round(load0, 2), round(os.getloadavg()[0], 2)]
    (out / "packing.json").write_text(json.dumps({"cases": result, "load": load}, indent=1),
                                      encoding="utf-8")
    text = (f"# Batch packing of the evidence rows' orbits (load {load[0]} -> {load[1]} on "
            f"{os.cpu_count()} cores; CPU seconds of the integration, compile excluded)\n\n"
            + table(result) + "\n")
    (out / "packing.md").write_text(text, encoding="utf-8")
    print(text)
    return 0
