r"""The run loop of ``chaplygin mutate-derivations``: tasks grouped by function (:func:`groups`),
decided in forked workers (:func:`run_tasks`), each record sent to the parent as soon as it is
decided, ``--out`` rewritten every :data:`WRITE_SECONDS` and on an interrupt, and one progress
line at each write."""

from __future__ import annotations

import math
import multiprocessing as mp
import time
from typing import Any

from chaplygin_nd.ledger.mutation import derivations, record
from chaplygin_nd.ledger.mutation.checks import init_worker
from chaplygin_nd.ledger.mutation.derivations import Task
from chaplygin_nd.ledger.phase import line

from chaplygin_nd import processes

#: Mutants of one function decided by one worker in a row (its recordings are made once for
#: them: each group of a function records and parks its rows again from empty caches, the largest
#: part of a group's CPU); a function with more is split. An interrupted run keeps every mutant
#: decided (each is sent as it is decided), so this bounds only the set-up repeated, not the loss:
#: at 160 no function of the derivations (147 mutants at most) is split in a full run.
GROUP = 160


def groups(tasks: list[Task], jobs: int = 1) -> list[list[Task]]:
    """``tasks`` grouped by function, the most expensive group first (cheapest check times
    mutants: the long groups start early and the workers end together). A group is decided in one
    worker and reported when it ends; its calls are recorded once. Chunks of at most
    :data:`GROUP`, and of at most a quarter of each worker's share: a run of one function's 21
    mutants was one group, so one core worked, nothing was reported for 6 minutes and a Ctrl-C kept
    nothing)."""
    size = max(1, min(GROUP, math.ceil(len(tasks) / (4 * max(1, jobs)))))
    by: dict[tuple[str, str], list[Task]] = {}
    for t in tasks:
        by.setdefault((t.target, t.mutant.function), []).append(t)
    out = [ts[i:i + size] for ts in by.values() for i in range(0, len(ts), size)]
    return sorted(out, key=lambda g: -sum(max(_cost(t), 0.1) for t in g))


def _cost(task: Task) -> float:
    """Expected seconds of a task (its cheapest check)."""
    return task.rows[0][2] if task.rows and task.target == "derivations" else 0.0


#: In a worker: where each record goes as soon as it is decided (a queue made by the parent
#: before it forks its workers), so that the parent counts and keeps a group's mutants before
#: the group ends. A group of the costliest function took 16 min and more, and a run printed no
#: progress and kept nothing until one ended.
_DECIDED: Any = None

#: How often a run writes ``--out`` and prints its progress line (s).
WRITE_SECONDS = 30


def evaluate_group(tasks: list[Task]) -> list[dict]:
    """Decide the mutants of one group in this worker, in order; each record is also sent to the
    parent as soon as it is decided (:data:`_DECIDED`)."""
    out = []
    try:
        for t in tasks:
            out.append(derivations.evaluate(t))
            if _DECIDED is not None:
                _DECIDED.put(out[-1])
    finally:
        derivations.end_group()
    return out


def run_tasks(tasks: list[Task], jobs: int, records: list[dict], runs, args, run, t0, c0) -> list[dict]:
    """Evaluate ``tasks`` in ``jobs`` forked workers, a group of one function's mutants at a time
    (:func:`groups`). ``records`` grows as mutants are decided (each worker sends each record when
    it is decided, :data:`_DECIDED`) and is written to ``--out`` every :data:`WRITE_SECONDS`
    (``"complete": false``) and on an interrupt, so an interrupted run keeps what it decided and
    ``--resume`` goes on from there. A progress line (mutants decided, the time left at the rate
    so far) at each write."""
    global _DECIDED
    mine: list[dict] = []
    seen: set[tuple] = set()
    last = time.perf_counter()
    context = mp.get_context("fork")

    def take(rec: dict) -> None:  # a record, once (from the queue, or from its group's result)
        key = (rec["target"], rec["function"], rec["index"])
        if key in seen:
            return
        seen.add(key)
        records.append(rec)
        mine.append(rec)
        if rec["outcome"] != "killed":
            print(f"  {rec['outcome']:<10} {rec['function']:<40} {rec['mutation']}  "
                  f"[{rec['row']}] {rec['reason'][:160]}", flush=True)

    def keep() -> None:
        record.progress(run, len(mine), len(tasks), t0, c0)
        record.write(records, runs, args)

    def on_wake() -> None:
        nonlocal last
        while not queue.empty():
            take(queue.get())
        if time.perf_counter() - last > WRITE_SECONDS:
            keep()
            last = time.perf_counter()
            print(progress_line(len(mine), len(tasks), last - t0), flush=True)

    _DECIDED = queue = context.SimpleQueue()  # before the pool forks its workers: they inherit it
    try:
        with processes.pool(jobs, context, init_worker) as pool:
            futures = [pool.submit(evaluate_group, g) for g in groups(tasks, jobs)]
            for fut in processes.as_completed(futures, on_wake=on_wake):
                for rec in fut.result():
                    take(rec)
    except BaseException:  # an interrupt: keep what was decided (written whole or not at all)
        keep()
        raise
    finally:
        queue.close()
        _DECIDED = None
    return mine


def progress_line(done: int, total: int, seconds: float) -> str:
    """``N of M mutants decided in S s, about T min left`` (at the rate so far;
    :func:`ledger.phase.line`, as the planning phases before it)."""
    return line(done, total, seconds, "mutants decided")

