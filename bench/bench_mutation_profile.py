"""``python -m bench.bench_mutation_profile``: where a derivation mutant's CPU seconds go in
``chaplygin mutate-derivations``, on a seeded sample of the mutants the record does not decide.

The sample: ``--size`` mutants drawn with the command's seed (``derivations.SEED``) from those
``mutation-derivations.json`` leaves undecided (:func:`.record.consistency`). They are planned once
(the unmutated rows that reach them, the tests of the functions no row reaches), then decided in a
fresh fork of that planned process, grouped by function as a run groups them, with each stage of
:mod:`chaplygin_nd.ledger.mutation.derivations` timed *exclusively* (a stage's CPU excludes the
stages called inside it): recording a function's calls per check (a set-up per function), the
replays, the rows re-run with a mutant, the tests, the test map (a set-up), the slow tests, the
equivalence runs, the cache clearing, compiling the mutant. The parked processes (rows and test
sessions stopped at the function's first call, :mod:`.forkpoint`) and their copies are children:
their CPU is counted when each is ended, under "children". ``--fast`` runs with the stage-level
changes of the current code switched off and on (:data:`FLAGS`) side by side,
the same sample, one after the other, and lists every verdict that differs (none may).
Writes ``bench/out/mutation_profile.md`` and ``.json``.
"""

from __future__ import annotations

import argparse
import json
import os
import pickle
import random
import resource
import tempfile
import time
from pathlib import Path

#: The switches of :mod:`.derivations` that ``--fast`` turns off ("before") and on ("after").
#: ``PLANNED``: every function's calls recorded in one run per row (:mod:`.planned`), made inside
#: the timed run (its CPU is the mutants'), not in the shared planning.
FLAGS = ("PLANNED",)


def _cpu() -> float:
    own, kids = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + kids.ru_utime + kids.ru_stime


def _children() -> float:
    kids = resource.getrusage(resource.RUSAGE_CHILDREN)
    return kids.ru_utime + kids.ru_stime


class _Stages:
    """Exclusive CPU (own process) and children's CPU per stage, by wrapping module attributes."""

    def __init__(self):
        self.own: dict[str, float] = {}
        self.kids: dict[str, float] = {}
        self.count: dict[str, int] = {}
        self._stack: list[list] = []
        self.prefix = 0.0  # CPU of the parked processes up to the first call (in "end parked")
        self.parkings = 0

    def wrap(self, owner, attr: str, stage: str) -> None:
        inner = getattr(owner, attr)

        def timed(*args, **kwargs):
            frame = [time.process_time(), _children(), 0.0, 0.0]
            self._stack.append(frame)
            try:
                return inner(*args, **kwargs)
            finally:
                self._stack.pop()
                own = time.process_time() - frame[0]
                kids = _children() - frame[1]
                self.own[stage] = self.own.get(stage, 0.0) + own - frame[2]
                self.kids[stage] = self.kids.get(stage, 0.0) + kids - frame[3]
                self.count[stage] = self.count.get(stage, 0) + 1
                if self._stack:
                    self._stack[-1][2] += own
                    self._stack[-1][3] += kids

        setattr(owner, attr, timed)


def _instrument() -> _Stages:
    from chaplygin_nd.ledger.mutation import (
        cache_scope,
        derivations,
        equivalence,
        forkpoint,
        planned,
    )
    from chaplygin_nd.ledger.mutation import runtime as mr

    s = _Stages()
    s.wrap(derivations, "evaluate", "other (the mutant's bookkeeping)")
    s.wrap(derivations, "_recording", "set-up: record a function's calls per check")
    s.wrap(derivations, "replay", "replay the recorded calls")
    s.wrap(derivations, "_run_check", "rows re-run with the mutant (worker)")
    s.wrap(forkpoint.Parked, "__init__", "set-up: park a row or test session")
    parked_init = forkpoint.Parked.__init__

    def noting_prefix(self, *args, **kwargs):  # the parked process's CPU up to the first call
        parked_init(self, *args, **kwargs)
        s.prefix += self.first_call or 0.0
        s.parkings += 1

    forkpoint.Parked.__init__ = noting_prefix
    s.wrap(forkpoint.Parked, "run", "rows/tests from the parked process")
    s.wrap(forkpoint.Parked, "close", "end parked processes (their CPU: children)")
    s.wrap(planned, "record_tasks", "set-up: record every function in one run per row")
    s.wrap(planned, "guard", "set-up: check a planned recording (guard)")
    s.wrap(derivations, "_tests_reaching", "set-up: test map (instrumented run)")
    s.wrap(mr, "kill", "tests run with the mutant")
    s.wrap(mr, "kill_slow", "slow tests (last resort)")
    s.wrap(mr, "equivalence", "tests run twice (equivalence)")
    s.wrap(derivations, "settle", "row run twice (equivalence)")
    s.wrap(equivalence, "compare_on_row", "row run twice (equivalence)")
    s.wrap(cache_scope, "clear", "cache clearing")
    s.wrap(cache_scope, "begin", "cache clearing")
    s.wrap(derivations, "compile_mutant", "compile the mutant")
    return s


def _decide(tasks, fast: bool | None) -> dict:
    """Decide ``tasks`` in a fresh fork with the stages timed; ``fast``: ``derivations.FAST``."""
    from chaplygin_nd.bench.bench_mutation import in_fork

    def work():
        os.nice(0)
        from chaplygin_nd.ledger.mutation import derivations, planned, runloop

        if fast is not None:
            for flag in FLAGS:
                setattr(derivations, flag, fast)
        stages = _instrument()
        c0 = _cpu()
        if derivations.PLANNED:  # the planning's one run per row, timed with the mutants
            planned.record_tasks(tasks, 1)
        out = [r for g in runloop.groups(tasks, 1) for r in runloop.evaluate_group(g)]
        return (out, _cpu() - c0, stages.own, stages.kids, stages.count,
                (stages.parkings, stages.prefix))

    (records, cpu, own, kids, count, (parkings, prefix)), wall = in_fork(work)
    return {"records": records, "cpu": cpu, "wall": wall, "own": own, "kids": kids, "count": count,
            "parkings": parkings, "prefix cpu": prefix}


def draw(size: int, seed: int) -> list:
    """``size`` undecided derivation mutants drawn with ``seed`` (source order)."""
    from chaplygin_nd.ledger.catalog import ROOT
    from chaplygin_nd.ledger.mutation import derivations, record

    undecided = record.consistency(record.read(ROOT / "mutation-derivations.json")[0],
                                   ("derivations",))["undecided"]
    chosen = {(k[1], k[2]) for k in random.Random(f"{seed}:undecided").sample(
        undecided, min(size, len(undecided)))}
    return [m for m in derivations.sample("derivations", None, seed,
                                          only=frozenset(f for f, _ in chosen))
            if (m.function, f"{m.operator}: {m.description}") in chosen]


def main(out: Path, size: int, seed: int, fast: bool, planned: Path | None = None) -> int:
    from chaplygin_nd.ledger.mutation import derivations
    from chaplygin_nd.ledger.mutation import runtime as mr
    from chaplygin_nd.ledger.mutation.checks import init_worker

    init_worker()
    selection = draw(size, seed)
    result: dict = {"size": len(selection), "seed": seed,
                    "functions": len({m.function for m in selection})}
    with tempfile.TemporaryDirectory(prefix="chaplygin-mutate-") as work:
        os.environ[mr.WORK_ENV] = work
        try:
            c0 = _cpu()
            if planned is not None and planned.is_file():  # this bench's own earlier planning
                tasks, result["planning cpu"] = pickle.loads(planned.read_bytes())
            else:  # the recordings of one run per row are made in each timed run (_decide)
                kept, derivations.PLANNED = derivations.PLANNED, False
                tasks = derivations.plan("derivations", selection, 1)
                derivations.PLANNED = kept
                result["planning cpu"] = round(_cpu() - c0, 1)
                if planned is not None:
                    planned.write_bytes(pickle.dumps((tasks, result["planning cpu"])))
            for name, switch in ((("before", False), ("after", True)) if fast
                                 else (("now", None),)):
                load = os.getloadavg()[0]
                got = _decide(tasks, switch)
                got["load"] = round(load, 2)
                got["verdicts"] = {f"{r['function']} {r['mutation']}": r["outcome"]
                                   for r in got.pop("records")}
                result[name] = got
        finally:
            os.environ.pop(mr.WORK_ENV, None)
    runs = [k for k in ("before", "after", "now") if k in result]
    lines = ["# Where a derivation mutant's CPU goes", "",
             f"{result['size']} undecided mutants of {result['functions']} functions, drawn with "
             f"seed {seed}; planning (unmutated rows and test maps, once) {result['planning cpu']} "
             "CPU s.", "", "| stage | " + " | ".join(f"{k}: own CPU s | {k}: children CPU s"
                                                     for k in runs) + " |",
             "|---|" + "---|---|" * len(runs)]
    stages = sorted({s for k in runs for s in result[k]["own"]},
                    key=lambda s: -sum(result[k]["own"].get(s, 0) + result[k]["kids"].get(s, 0)
                                       for k in runs))
    for s in stages:
        lines.append(f"| {s} | " + " | ".join(
            f"{result[k]['own'].get(s, 0):.1f} | {result[k]['kids'].get(s, 0):.1f}" for k in runs)
            + " |")
    for k in runs:
        r = result[k]
        lines.append(f"\n{k}: {r['parkings']} parked processes, {r['prefix cpu']:.1f} CPU s up to "
                     "their first calls (counted in 'end parked processes')")
        lines.append(f"{k}: {r['cpu']:.1f} CPU s ({r['cpu'] / max(1, result['size']):.2f} per "
                     f"mutant), {r['wall']:.1f} s wall, load {r['load']} at start")
    if fast:
        differ = sorted(v for v in result["before"]["verdicts"]
                        if result["before"]["verdicts"][v] != result["after"]["verdicts"].get(v))
        result["verdicts differ"] = differ
        lines.append(f"\nverdicts that differ: {len(differ)}" + "".join(f"\n- {v}" for v in differ))
    out.mkdir(parents=True, exist_ok=True)
    (out / "mutation_profile.md").write_text("\n".join(lines) + "\n", encoding="utf-8")
    (out / "mutation_profile.json").write_text(json.dumps(result, indent=1) + "\n",
                                               encoding="utf-8")
    print("\n".join(lines))
    return 1 if result.get("verdicts differ") else 0


if __name__ == "__main__":
    from chaplygin_nd.ledger.mutation.derivations import SEED

    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--size", type=int, default=30)
    p.add_argument("--seed", type=int, default=SEED)
    p.add_argument("--fast", action="store_true", help="before/after the stage-level changes")
    p.add_argument("--out", type=Path, default=Path("bench/out"))
    p.add_argument("--plan", type=Path, default=None,
                   help="keep the planned tasks in this file, and reuse them when it exists "
                        "(the same code and sample only)")
    a = p.parse_args()
    raise SystemExit(main(a.out, a.size, a.seed, a.fast, a.plan))
