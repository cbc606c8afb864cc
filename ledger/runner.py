"""Run ledger rows (in parallel processes, the longest first), one result per row, returned in ledger order."""

from __future__ import annotations

import multiprocessing as mp
import os
import signal
import time
import traceback
from collections.abc import Callable, Sequence
from concurrent.futures import Future
from dataclasses import dataclass, replace

from chaplygin_nd.ledger.catalog import Row, all_rows, discover
from chaplygin_nd.ledger.reach import Recorder
from chaplygin_nd.ledger.registry import Verdict, registry
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.exact.identity import (
    engine_note,
    engine_tally,
    point_timings,
    reset_engine_tally,
)

from chaplygin_nd import processes


@dataclass(frozen=True)
class Result:
    """One ledger line: the row, its verdict, the seconds it took, where it was proved."""

    row: Row
    verdict: Verdict
    seconds: float
    module: str = ""
    uses: tuple[str, ...] = ()
    error: str = ""
    #: the public functions of symbolic/printed/ this row called (ledger.reach.Recorder)
    printed: tuple[str, ...] = ()
    #: the derivations of symbolic/ this row called (ledger.reach.derivation_functions)
    derived: tuple[str, ...] = ()

    @property
    def status(self) -> str:
        return "error" if self.error else self.verdict.verdict

    def __repr__(self) -> str:
        """``<Result P:inversion: holds, 4.1 s, n = 3..12, 16, 20, 24>``; the verdict's fields
        (method, parts, counterexample) are in ``verdict`` and :meth:`to_dict`."""
        kind = f" ({self.verdict.kind})" if self.verdict.kind else ""
        ns = f", n = {points.n_text(self.verdict.n_values)}" if self.verdict.n_values else ""
        return f"<Result {self.row.id}: {self.status}{kind}, {self.seconds:.2g} s{ns}>"

    def to_dict(self) -> dict:
        d = {"id": self.row.id, "section": self.row.section, "claim": self.row.claim,
             "seconds": round(self.seconds, 3), "proof_module": self.module,
             "uses": list(self.uses), "error": self.error or None,
             "printed": list(self.printed), "derived": list(self.derived)}
        d.update(self.verdict.to_dict())
        d["verdict"] = self.status
        return d


def _run_one(claim_id: str, seed: int = points.DEFAULT_SEED, fresh: bool = False
             ) -> tuple[Verdict, float, str, tuple[str, ...], tuple[str, ...]]:
    """Decide one row with ``seed`` as the seed of its seeded checks (in this process);
    also the printed functions and the derivations it called (:mod:`ledger.reach`). ``fresh``
    empties the derivation caches first, so the record of derivations does not depend on what
    earlier rows (or the worker's preloading) computed: the reach map is written this way."""
    if fresh:
        from chaplygin_nd.ledger.reach import clear_derivation_caches

        clear_derivation_caches()
    spec = registry()[claim_id]
    previous = points.set_ledger_seed(seed)
    start = time.perf_counter()
    recorder = Recorder()
    reset_engine_tally()
    point_timings(clear=True)
    try:
        with recorder:
            verdict = spec.run()
        if not isinstance(verdict, Verdict):
            raise TypeError(f"proof of {claim_id} returned {type(verdict).__name__}, not Verdict")
        checked = {size for kind, _label, size, _engine, _s in point_timings(clear=True)
                   if kind == "points" and size is not None}
        if checked - set(verdict.n_values):
            # the [n] column: the n the proof names, and every n its seeded points were checked at
            verdict = replace(verdict, n_values=tuple(sorted(set(verdict.n_values) | checked)))
        tally = engine_tally()
        if tally or verdict.verdict in ("holds", "corrected", "fails"):
            # which engines decided the row's zero tests (symbolic.exact.identity): said in its method
            verdict = replace(verdict, method=f"{verdict.method}; {engine_note(tally)}")
        return verdict, time.perf_counter() - start, "", recorder.printed(), recorder.derived()
    except Exception:  # a proof that raises is an error row, never a silent pass
        return (Verdict("fails", "raised an exception", notes="see error"),
                time.perf_counter() - start, traceback.format_exc(limit=8),
                recorder.printed(), recorder.derived())
    finally:
        points.set_ledger_seed(previous)


#: How worker processes start: never ``fork`` (a forked child of a notebook kernel, of a process
#: with threads, or on macOS can deadlock); ``forkserver`` where the platform has it, else
#: ``spawn``. The fork server imports the proof modules once, before any worker starts (its
#: preload list), so a worker forked from it starts with them loaded, as ``fork`` did.
START_METHOD = "forkserver" if "forkserver" in mp.get_all_start_methods() else "spawn"


def _context():
    context = mp.get_context(START_METHOD)
    if START_METHOD == "forkserver":
        context.set_forkserver_preload(
            ["chaplygin_nd.ledger.runner"]
            + [f"chaplygin_nd.proofs.{name}" for name in discover()])
    return context


def _init_worker():
    signal.signal(signal.SIGTERM, signal.SIG_DFL)  # Ctrl-C is the parent's (processes.worker_start)
    discover()


def select(ids: Sequence[str] = ()) -> list[Row]:
    """The ledger rows to run: all, or those named (unknown names raise ``KeyError``)."""
    discover()
    rows = all_rows()
    if not ids:
        return rows
    by_id = {r.id: r for r in rows}
    unknown = [i for i in ids if i not in by_id]
    if unknown:
        from chaplygin_nd.console import shortlist

        raise KeyError(f"unknown ledger id(s): {shortlist(unknown)}")
    return [by_id[i] for i in ids]


def unknown_registrations() -> list[str]:
    """Registered proofs whose id is not a ledger row (a typo in a proof module)."""
    known = {r.id for r in all_rows()}
    return sorted(set(registry()) - known)


#: The seconds assumed for a row the stored timings do not name (:func:`longest_first`).
UNTIMED_SECONDS = 1.0
#: The name of :func:`run`'s ``also`` in the order the workers take their tasks (no row id
#: starts with a space).
ALSO_TASK = " also"


def stored_seconds() -> dict[str, float]:
    """Each row's seconds as the last ``python -m chaplygin_nd.ledger.remap`` measured them
    (``ledger/reach.json``); empty when the map is missing or unreadable (then the rows run in
    ledger order)."""
    from chaplygin_nd.ledger import reach

    try:
        _rows, seconds = reach.load()
    except (OSError, ValueError, KeyError, TypeError):
        return {}
    if not isinstance(seconds, dict):
        return {}
    return {k: float(v) for k, v in seconds.items()
            if isinstance(k, str) and isinstance(v, (int, float)) and not isinstance(v, bool)}


def longest_first(ids: Sequence[str], seconds: dict[str, float]) -> list[str]:
    """``ids`` in the order the workers take them: longest expected row first (``seconds``;
    :data:`UNTIMED_SECONDS` for a row it does not name), ties in ledger order. With rows of
    very unequal length (the evidence rows take 20-40 s, most rows 1-3 s) the ledger order left
    the longest rows, which come last in it, to run alone at the end; longest-first (LPT) ends
    within the longest row of the lower bound total / jobs. The order changes no verdict: each
    row is decided in its own call with the seed passed to it."""
    rank = {claim_id: k for k, claim_id in enumerate(ids)}
    return sorted(ids, key=lambda i: (-seconds.get(i, UNTIMED_SECONDS), rank[i]))


def hand_out_order(ids: Sequence[str], seconds: dict[str, float], also: bool) -> list[str]:
    """The order in which the workers take their tasks: with ``also``, :data:`ALSO_TASK` first,
    then the rows ``ids`` longest first (:func:`longest_first`). ``verify --check-generated``'s
    ``also`` empties the derivation caches of the worker that takes it, to record the calls of
    the regeneration (:func:`ledger.reach.regenerated_and_emitted`): first, it finds them empty and
    leaves them filled for the rows after it; handed out after the rows, it ran alone after the
    last one."""
    return ([ALSO_TASK] if also else []) + longest_first(ids, seconds)


def run(rows: Sequence[Row], *, jobs: int | None = None, seed: int = points.DEFAULT_SEED,
        on_result: Callable[[Result], None] = lambda r: None, fresh: bool = False,
        also: Callable[[], object] | None = None,
        on_also: Callable[[object], None] = lambda value: None,
        on_wake: Callable[[], None] | None = None) -> list[Result]:
    """Decide ``rows``; registered ones run in ``jobs`` processes (started longest first,
    :func:`longest_first`), the rest are ``open``. ``on_result`` is called for each row as it is
    decided (in one process: in ledger order; in several: as the rows finish); the results are
    returned in ledger order. ``seed`` is the seed of every seeded check (passed to each worker
    with each row); ``fresh``: see :func:`_run_one`. ``also``: a picklable call without
    arguments (``verify --check-generated``: the regeneration of generated/) handed out before
    the rows (:func:`hand_out_order`), or run after them in one process; its value goes to
    ``on_also`` (an exception it raises is raised here). ``on_wake``: called while waiting for the workers, every few seconds
    (:func:`chaplygin_nd.processes.as_completed`)."""
    discover()
    specs = registry()
    todo = list(dict.fromkeys(r.id for r in rows if r.id in specs))
    jobs = max(1, min(jobs or os.cpu_count() or 1, len(todo) or 1))
    pool = None
    decided: dict[str, Result] = {}

    def result_of(claim_id: str, outcome) -> Result:
        verdict, seconds, error, printed, derived = outcome
        spec = specs[claim_id]
        return Result(by_id[claim_id], verdict, seconds, spec.module, spec.uses, error, printed,
                      derived)

    by_id = {r.id: r for r in rows}
    try:
        for row in rows:
            if row.id in decided:
                continue
            if row.id not in specs:
                # No proof registered: an open row WITHOUT a reason (fails the run).
                decided[row.id] = Result(row, Verdict("open", "not yet checked"), 0.0)
            elif jobs == 1:
                decided[row.id] = result_of(row.id, _run_one(row.id, seed, fresh))
            else:
                continue
            on_result(decided[row.id])
        if jobs > 1:  # started whole before a Ctrl-C is taken (chaplygin_nd.processes.Pool)
            pool = processes.pool(jobs, _context(), _init_worker)
            futures: dict[Future, str] = {}
            extra: Future | None = None
            for task in hand_out_order(todo, stored_seconds(), also is not None):
                if task == ALSO_TASK and also is not None:
                    extra = pool.submit(also)
                else:
                    futures[pool.submit(_run_one, task, seed, fresh)] = task
            for future in processes.as_completed(futures, on_wake=on_wake):
                claim_id = futures[future]
                decided[claim_id] = result_of(claim_id, future.result())
                on_result(decided[claim_id])
            if extra is not None:
                on_also(extra.result())
        elif also is not None:
            on_also(also())
    except BaseException:  # Ctrl-C, SIGTERM or an error: do not wait for the rows in progress
        if pool is not None:
            pool.stop()
        raise
    if pool is not None:
        pool.shutdown()
    return [decided[row.id] for row in rows]
