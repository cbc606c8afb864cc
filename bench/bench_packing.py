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


#: pilot fractions compared by :func:`pilot_sweep`
FRACTIONS = (1 / 64, 1 / 32, 1 / 16)


def pilot_sweep(label: str, count: int | None = None) -> dict:
    """Per pilot fraction: the correlation of the pilot's steps with the run's, the useful
    fraction packed by them, and the lane-steps saved against the parameter order minus the
    pilot's (fractions of the parameter order's lane-steps): what chose ``packing.PILOT``."""
    from chaplygin_nd.bench.bench_megno_scaling import _case
    from chaplygin_nd.simulate.analysis import chaos, packing
    from chaplygin_nd.simulate.analysis import drawn_evidence as de
    from chaplygin_nd.simulate.integrators.heyoka_taylor import compiled_integrator

    s, ens, y0 = _case(label)
    if count is not None:
        ens, y0 = de.subset(ens, np.arange(count)), y0[:count]
    _, _, _, extra = de._integrate(s, ens, y0, SEED)
    steps, width = extra["steps"], de.BATCH
    ta, _, _ = compiled_integrator(de._system(s), "double", s.tol, compact=True, batch=width,
                                   opt_level=de.OPT_LEVEL)
    u0 = chaos.initial_tangents(len(y0), y0.shape[1], SEED)
    if s.tangent == "V":
        u0 = de.v_tangents(u0, y0, s.n)
    full = np.concatenate([y0, u0, np.zeros((len(y0), 2))], axis=1)
    b = ens.b if s.b_override is None else np.full(len(y0), float(s.b_override))
    pars, first = np.stack([ens.a, b]), de.schedule(ens)

    def lane_steps(index, cost):
        return sum(width * cost[lanes[:used]].max() for lanes, used in packing.batches(index, width))

    base = lane_steps(first, steps)
    out = {}
    for frac in FRACTIONS:
        pilot = packing.pilot_steps(ta, full, pars, frac * s.T * ens.time_factor, first)
        packed = first[np.argsort(-pilot[first], kind="stable")]
        out[f"1/{round(1 / frac)}"] = {
            "correlation": round(float(np.corrcoef(pilot, steps)[0, 1]), 3),
            "efficiency": round(packing.efficiency(steps, packed, width), 4),
            "saved": round((base - lane_steps(packed, steps) - lane_steps(first, pilot)) / base, 4)}
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
    """Measure every case (``quick``: 24 orbits of two, no other width) and the pilot fractions
    on the first two, and write ``packing.md`` / ``.json`` into ``out``."""
    load0 = os.getloadavg()[0]
    result = {label: measure(label, 24, ()) if quick else measure(label)
              for label, _ in (CASES[:2] if quick else CASES)}
    sweep = {label: pilot_sweep(label, 24 if quick else None) for label, _ in CASES[:2]}
    load = [round(load0, 2), round(os.getloadavg()[0], 2)]
    (out / "packing.json").write_text(json.dumps({"cases": result, "pilot": sweep, "load": load},
                                                 indent=1), encoding="utf-8")
    lines = ["| system | pilot | correlation | useful fraction | lane-steps saved net |",
             "|---|---|---|---|---|"]
    lines += [f"| {label} | {frac} | {v['correlation']:.3f} | {v['efficiency']:.3f} | "
              f"{100 * v['saved']:.1f} % |" for label, rows in sweep.items() for frac, v in rows.items()]
    text = (f"# Batch packing of the evidence rows' orbits (load {load[0]} -> {load[1]} on "
            f"{os.cpu_count()} cores; CPU seconds of the integration, compile excluded)\n\n"
            + table(result) + "\n\n## The pilot's fraction\n\n" + "\n".join(lines) + "\n")
    (out / "packing.md").write_text(text, encoding="utf-8")
    print(text)
    return 0
