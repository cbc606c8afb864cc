r"""The Taylor tolerance of the evidence rows' MEGNO runs: what a looser one costs in accuracy and
saves in work, per setting, side by side in one process.

For each setting of the rows (:mod:`simulate.analysis.evidence_rows`: the reduced $n = 4$ system,
$P$ at $n = 4$ and $5$, the general-$\mathbb{J}$ controls at $n = 4$ and $5$, $\mathcal V$ at $n = 6$
and $7$) the first ``ORBITS`` orbits of the row's own draw are integrated with the MEGNO tangent
(:func:`simulate.analysis.drawn_evidence._integrate`, the rows' machinery: batch mode, compact
mode, the rows' grid) at each tolerance of ``TOLS`` and at the reference ``REFERENCE`` = $10^{-13}$.
Per setting and tolerance: Taylor steps per orbit (heyoka's count, the largest lane of each
batch: a batch steps until its slowest lane is done), the Taylor order, CPU seconds per orbit of
``propagate_grid`` alone (compilation excluded), the largest relative error of the state at $T$
against the reference (regular orbits only: a chaotic orbit's state at $T$ is not reproducible
at any tolerance), the largest $|\Delta\langle Y\rangle(T)|$ against the reference, and the orbits
whose MEGNO ladder class or frequency class differs from the one at the reference.

Run: ``chaplygin bench tangent-tol`` (writes ``tangent-tol.md`` / ``.json``: the table, then the
interleaved CPU comparison of :func:`cost`; ``--quick``: 8 orbits of two settings) or
``python -m chaplygin_nd.bench.bench_tangent_tol [--orbits N] [--tols 1e-10,1e-9] [--only full5,...]
[--cost REPEAT]`` (prints). A measurement, not a test: whether a tolerance may be used is decided
by the validation study (bench/bench_evidence.py) at it.
"""

from __future__ import annotations

import argparse
import contextlib
import time
from dataclasses import replace

import numpy as np

TOLS = (1e-10, 3e-10, 1e-9)
REFERENCE = 1e-13
ORBITS = 16


def _cases(orbits: int):
    """``(name, setting, ensemble, y0)`` of each setting, first ``orbits`` of the row's draw."""
    from chaplygin_nd.simulate.analysis import draws
    from chaplygin_nd.simulate.analysis import evidence_rows as er
    from chaplygin_nd.simulate.analysis.control import CHAOTIC_J
    from chaplygin_nd.simulate.analysis.drawn_evidence import subset
    from chaplygin_nd.simulate.dynamics.so import reduced_invariants
    from chaplygin_nd.symbolic.exact import points

    seed = points.ledger_seed()

    def first(label, family, n, count, **kw):
        ens = draws.draw(label, family, n, count, seed, **kw)
        return subset(ens, range(min(orbits, count)))

    out = []
    ens = first("S5:EJ-tori", "generic", 4, er.LEVEL_SETS)
    out.append(("reduced", er.SETTINGS["reduced"], ens, reduced_invariants(ens.M0, ens.gamma0)))
    ens = first("S5:reconstruction", "generic", 4, 200)
    out.append(("full4", er.SETTINGS["full4"], ens, er._full_state(ens)))
    ens = first("control4", "generic", 4, er.CONTROL4_COUNT)
    out.append(("control4", er.SETTINGS["control4"], ens, er._full_state(ens)))
    ens = first("S6:open-reduced-n5", "generic", 5, er.N5_COUNT)
    out.append(("full5", er.open_setting(5), ens, er._full_state(ens)))
    ens = first("S6:open-reduced-n5 control", "generic", 5, er.N5_CONTROL)
    out.append(("control5", er.open_setting(5, CHAOTIC_J[5]), ens, er._full_state(ens)))
    for n in (6, 7):
        ens = first(f"Th:Re-tori:frequencies n={n}", "vertical", n, 50, a_values=er.VERTICAL_A)
        out.append((f"vertical{n}", er.vertical_setting(n), ens, er._full_state(ens)))
    return out, seed


class _Counting:
    """A heyoka batch integrator that records each ``propagate_grid``'s CPU time and steps."""

    def __init__(self, ta, log):
        object.__setattr__(self, "_ta", ta)
        object.__setattr__(self, "_log", log)

    def __getattr__(self, name):
        return getattr(self._ta, name)

    def __setattr__(self, name, value):
        setattr(self._ta, name, value)

    def propagate_grid(self, grid):
        t0 = time.process_time()
        out = self._ta.propagate_grid(grid)
        self._log["cpu"] += time.process_time() - t0
        self._log["steps"] += max(int(r[3]) for r in self._ta.propagate_res)
        self._log["order"] = int(self._ta.order)
        return out


@contextlib.contextmanager
def _counted():
    """Inside it, every integrator the rows compile counts its CPU and steps into the yielded log
    (``{"cpu", "steps", "order"}``)."""
    from chaplygin_nd.simulate.integrators import heyoka_taylor as ht

    log = {"cpu": 0.0, "steps": 0, "order": 0}
    original = ht.compiled_integrator

    def counting(*args, **kw):
        ta, sec, how = original(*args, **kw)
        return _Counting(ta, log), sec, how

    ht.compiled_integrator = counting
    try:
        yield log
    finally:
        ht.compiled_integrator = original


def run_one(s, ens, y0, seed, tol):
    """The rows' integration of ``ens`` at ``tol``: records, states at T, CPU and steps."""
    from chaplygin_nd.simulate.analysis import drawn_evidence as de

    s = replace(s, tol=tol)
    with _counted() as log:
        Z, megno, lyap, extra = de._integrate(s, ens, y0, seed)
    records = de.analyse(s, ens, Z, megno, lyap, extra)
    return records, extra["final"], log


def measure(orbits=ORBITS, tols=TOLS, only=None):
    """One row per (setting, tolerance) (module docstring)."""
    from chaplygin_nd.simulate.analysis.drawn_evidence import BATCH

    cases, seed = _cases(orbits)
    rows = []
    for name, s, ens, y0 in cases:
        if only and name not in only:
            continue
        ref, ref_final, ref_log = run_one(s, ens, y0, seed, REFERENCE)
        d = y0.shape[1]
        scale = np.linalg.norm(ref_final[:, :d], axis=1)
        batches = -(-len(y0) // BATCH)
        for tol in tols:
            rec, final, log = run_one(s, ens, y0, seed, tol)
            regular = [k for k, r in enumerate(ref) if r.megno_cls == "regular"]
            err = (np.linalg.norm(final[regular, :d] - ref_final[regular, :d], axis=1)
                   / scale[regular]) if regular else np.zeros(0)
            dy = max(abs(a.megno - b.megno) for a, b in zip(rec, ref))
            rows.append({
                "setting": name, "orbits": len(y0), "tol": tol, "order": log["order"],
                "steps": log["steps"] / batches,
                "cpu_per_orbit": log["cpu"] / len(y0),
                "state_error": float(err.max()) if len(err) else float("nan"),
                "dmegno": float(dy),
                "megno_changed": [k for k, (a, b) in enumerate(zip(rec, ref))
                                  if a.megno_cls != b.megno_cls],
                "cls_changed": [k for k, (a, b) in enumerate(zip(rec, ref)) if a.cls != b.cls],
                "megno_cls": {c: sum(r.megno_cls == c for r in rec) for c in
                              ("regular", "chaotic", "undecided")},
            })
        rows.append({"setting": name, "orbits": len(y0), "tol": REFERENCE,
                     "order": ref_log["order"], "steps": ref_log["steps"] / batches,
                     "cpu_per_orbit": ref_log["cpu"] / len(y0), "state_error": 0.0, "dmegno": 0.0,
                     "megno_changed": [], "cls_changed": [],
                     "megno_cls": {c: sum(r.megno_cls == c for r in ref) for c in
                                   ("regular", "chaotic", "undecided")}})
        print(table(rows[-len(tols) - 1:], header=not any(r["setting"] != name for r in rows)),
              flush=True)
    return rows


#: the rows' orbits per setting (MEGNO runs at T; the n = 4..7 V ensembles each 50): the weights of
#: the rows' integration CPU in :func:`cost`
ROW_ORBITS = {"reduced": 200, "full4": 200, "control4": 50, "full5": 100, "control5": 24,
              "vertical6": 50, "vertical7": 50}


def cost(orbits=ORBITS, tols=(1e-10, 1e-9), repeat=5, only=None):
    """CPU of ``propagate_grid`` per orbit at each of ``tols``, interleaved ``repeat`` times on the
    same orbits (the least of the repeats: the other jobs of a shared machine only add to it),
    and the rows' integration CPU weighted by :data:`ROW_ORBITS`."""
    cases, seed = _cases(orbits)
    best = {}
    for name, s, ens, y0 in cases:
        if only and name not in only:
            continue
        for tol in tols:
            run_one_integrate(s, ens, y0, seed, tol)          # compile (or load) first
        for _ in range(repeat):
            for tol in tols:
                log = run_one_integrate(s, ens, y0, seed, tol)
                key = (name, tol)
                best[key] = min(best.get(key, np.inf), log["cpu"] / len(y0))
    lines = ["| setting | " + " | ".join(f"CPU s/orbit at {t:.0e}" for t in tols)
             + " | ratio |", "|---|" + "---|" * (len(tols) + 1)]
    total = dict.fromkeys(tols, 0.0)
    for name in dict.fromkeys(k[0] for k in best):
        row = [best[(name, t)] for t in tols]
        for t, v in zip(tols, row):
            total[t] += v * ROW_ORBITS[name]
        lines.append(f"| {name} | " + " | ".join(f"{v:.4f}" for v in row)
                     + f" | {row[-1] / row[0]:.3f} |")
    lines.append("| weighted by the rows' orbits | " + " | ".join(f"{total[t]:.1f} s" for t in tols)
                 + f" | {total[tols[-1]] / total[tols[0]]:.3f} |")
    text = "\n".join(lines)
    print(text, flush=True)
    return best, text


def run_one_integrate(s, ens, y0, seed, tol):
    """Only the integration of :func:`run_one` (no frequency analysis): its CPU and steps."""
    from chaplygin_nd.simulate.analysis import drawn_evidence as de

    with _counted() as log:
        de._integrate(replace(s, tol=tol), ens, y0, seed)
    return log


def table(rows, header=True) -> str:
    """The rows as Markdown."""
    out = []
    if header:
        out += ["| setting | orbits | tol | order | steps/batch | CPU s/orbit | state err at T "
                "(regular) | max dMEGNO | MEGNO class changed | freq. class changed | MEGNO classes |",
                "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        out.append(f"| {r['setting']} | {r['orbits']} | {r['tol']:.0e} | {r['order']} | "
                   f"{r['steps']:.0f} | {r['cpu_per_orbit']:.3f} | {r['state_error']:.1e} | "
                   f"{r['dmegno']:.1e} | {r['megno_changed']} | {r['cls_changed']} | "
                   f"{r['megno_cls']} |")
    return "\n".join(out)


def main(out, quick: bool = False) -> int:
    """Measure (``quick``: 8 orbits of two settings) and write ``tangent-tol.md`` / ``.json`` into
    ``out``."""
    import json
    import os
    from pathlib import Path

    from chaplygin_nd.bench.report import write_atomic

    load0 = os.getloadavg()[0]
    orbits, only = (8, {"reduced", "full5"}) if quick else (ORBITS, None)
    rows = measure(orbits, TOLS, only)
    best, cost_text = cost(orbits, (TOLS[0], TOLS[-1]), 1 if quick else 5, only)
    load = [round(load0, 2), round(os.getloadavg()[0], 2)]
    out = Path(out)
    write_atomic(out / "tangent-tol.json", json.dumps(
        {"rows": rows, "cost": [{"setting": k[0], "tol": k[1], "cpu_per_orbit": v}
                                for k, v in best.items()], "load": load}, indent=1))
    text = (f"# The MEGNO runs' tolerance, per setting (load {load[0]} -> {load[1]} on "
            f"{os.cpu_count()} cores)\n\n{table(rows)}\n\n## CPU, interleaved\n\n{cost_text}\n")
    write_atomic(out / "tangent-tol.md", text)
    return 0


def cli(argv=None) -> int:
    """``python -m`` entry point (module docstring)."""
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--orbits", type=int, default=ORBITS)
    p.add_argument("--tols", default=",".join(f"{t:g}" for t in TOLS))
    p.add_argument("--only", default="")
    p.add_argument("--cost", type=int, default=0, metavar="REPEAT",
                   help="only the interleaved CPU comparison, REPEAT rounds")
    a = p.parse_args(argv)
    if a.cost:
        cost(a.orbits, tuple(float(t) for t in a.tols.split(",")), a.cost,
             set(a.only.split(",")) if a.only else None)
        return 0
    measure(a.orbits, tuple(float(t) for t in a.tols.split(",")),
            set(a.only.split(",")) if a.only else None)
    return 0


if __name__ == "__main__":
    raise SystemExit(cli())
