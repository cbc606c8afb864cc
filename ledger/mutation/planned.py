r"""Record every planned derivation's calls in a ledger row in ONE run of that row.

:mod:`.replay` needs, for each function ``f`` and each row that reaches it, the calls ``f``
makes in the unmutated row. Recorded one function at a time (:func:`.replay.record`), a row
reached by ``k`` functions is run ``k`` times, from empty caches each time, and that was most of
a mutant's CPU (``python -m bench.bench_mutation_profile``). :func:`record_tasks` runs each row
once, in a forked process with the caches emptied first, with every planned function of that row
hooked at once (:func:`.replay.recorder`, the hook of the one-function recorder; each function's
hook has its own name, :func:`.replay.calls_through`). A hook returns the original's value, so
the row runs as it does unmutated; a run whose signature is not the baseline's keeps nothing.

The recordings come back pickled (:data:`RECORDINGS`, in the planning process: the workers are
forked from it after planning, and inherit them). A worker deciding ``f``'s mutants takes
``f``'s recording of a row (:func:`take`) in place of recording it again, and first checks it
(:func:`guard`): the *original* code, called on the unpickled arguments, must give back every
recorded value and leave the arguments as recorded — the dynamic guard of :func:`.replay.record`,
here run from empty caches and on what came through the pickle. While it runs, the cache
scope of ``f`` (:mod:`.cache_scope`) watches it, so the caches that ``f``'s own computation fills
without calling ``f`` are clean and stay warm for the mutants, as a recording in the worker left
them. A recording that could not be pickled, or is larger than :data:`MAX_BYTES`, is not kept:
the worker records that row itself, as before. What a row's recording holds for a function is
what the one-function recorder gives from the same empty caches: the hooks of the other functions
change no value, and a cache a function never calls through cannot hide one of its calls.
"""

from __future__ import annotations

import contextlib
import multiprocessing as mp
import pickle
import time
from types import FunctionType

from chaplygin_nd.ledger.mutation import cache_scope, checks
from chaplygin_nd.ledger.mutation.replay import (
    Recording,
    _call,
    _clone,
    _globals_state,
    _snapshot,
    calls_through,
    identical,
    impure,
    mutable_globals,
    recorder,
)

#: ``(function, row) -> the pickled Recording`` made by :func:`record_tasks` in this process.
RECORDINGS: dict[tuple[str, str], bytes] = {}
#: A recording pickled larger than this is not kept (the worker records that row itself).
MAX_BYTES = 64 * 2**20
#: The reason a run that does not reproduce its baseline gives (as :mod:`.derivations` words it).
NOT_BASELINE = "the recorded run did not reproduce the baseline"


def record_row(row: str, keys: tuple[str, ...], base, seconds: float) -> dict[str, bytes]:
    """Run ``row`` once, unmutated, from empty caches, with every function of ``keys`` recorded
    (:func:`.replay.recorder`): ``{function: pickled Recording}`` (a function whose recording
    cannot be pickled, or is too large, is left out). ``base``: the row's unmutated signature."""
    from chaplygin_nd.ledger.mutation.derivations import functions

    every = functions("derivations")
    recs: dict[str, Recording] = {}
    hooks = []
    for key in keys:
        fn = every[key]
        recs[key] = Recording()
        why = impure(fn)
        if why:
            recs[key].problem = why
        else:
            hooks.append(calls_through(fn, recorder(fn, recs[key])))
    cache_scope.end()
    cache_scope.clear()
    start = time.perf_counter()
    try:
        with contextlib.ExitStack() as stack:
            for h in hooks:
                stack.enter_context(h)
            got, _note = checks.run_row(row, max(checks.MIN_BUDGET,
                                                 checks.BUDGET_FACTOR * seconds))
    finally:
        cache_scope.clear()
    took = time.perf_counter() - start
    out: dict[str, bytes] = {}
    for key, rec in recs.items():
        if not rec.problem and got != base:
            rec.problem = NOT_BASELINE
        if not rec.problem and not rec.calls:
            rec.problem = "not called"
        if rec.problem:
            rec.calls = []
        rec.seconds = took
        try:
            data = pickle.dumps(rec, protocol=pickle.HIGHEST_PROTOCOL)
        except Exception:  # noqa: BLE001 - e.g. a compiled object: the worker records it itself
            continue
        if len(data) <= MAX_BYTES:
            out[key] = data
    return out


def _record_row(args) -> tuple[str, dict[str, bytes]]:
    row, keys, base, seconds = args
    return row, record_row(row, keys, base, seconds)


def record_tasks(tasks, jobs: int = 1, phase=None) -> None:
    """Fill :data:`RECORDINGS` for the derivation ``tasks`` (their rows, signatures and seconds):
    each row reached by some task's function run once for all of them, in ``jobs`` forked
    processes (most expensive first). ``phase`` (:class:`ledger.phase.Phase`) counts the rows."""
    from chaplygin_nd.ledger.mutation.checks import init_worker

    from chaplygin_nd import processes

    rows: dict[str, list] = {}
    for t in tasks:
        if t.target != "derivations":
            continue
        for row, base, seconds in t.rows:
            entry = rows.setdefault(row, [base, seconds, []])
            if t.mutant.function not in entry[2]:
                entry[2].append(t.mutant.function)
    todo = sorted(((r, tuple(e[2]), e[0], e[1]) for r, e in rows.items()
                   if any((k, r) not in RECORDINGS for k in e[2])), key=lambda a: -a[3])
    if phase is not None:
        phase.total = len(todo)
    if not todo:
        return
    with processes.pool(max(1, min(jobs, len(todo))), mp.get_context("fork"), init_worker) as pool:
        futures = [pool.submit(_record_row, a) for a in todo]
        for fut in processes.as_completed(futures, on_wake=phase.tick if phase else None):
            row, got = fut.result()
            for key, data in got.items():
                RECORDINGS[(key, row)] = data
            if phase is not None:
                phase.add()


def take(key: str, row: str) -> Recording | None:
    """``key``'s recording of ``row`` made at planning (unpickled, not yet :func:`guard`-ed), or
    None when there is none (the worker then records the row itself)."""
    data = RECORDINGS.get((key, row))
    if data is None:
        return None
    try:
        return pickle.loads(data)
    except Exception:  # noqa: BLE001 - unpickling failed: recorded in the worker instead
        return None


def guard(fn: FunctionType, rec: Recording) -> Recording:
    """The dynamic guard of :func:`.replay.record` on a recording made elsewhere: the original
    code called on each recorded call (from the caches :func:`.cache_scope.clear` keeps, with the
    scope watching, so what it computes without calling ``fn`` stays warm) must return the
    recorded value and leave the arguments and the module-level containers as recorded; else the
    recording says so and holds no call. ``rec`` is changed and returned."""
    if rec.problem:
        rec.calls = []
        return rec
    orig = _clone(fn, fn.__code__)
    names = mutable_globals(fn)

    def hook(*args, **kwargs):  # a recursive call of fn: the caches open around it depend on fn
        cache_scope.called()
        return orig(*args, **kwargs)

    cache_scope.clear()
    same = True
    with calls_through(fn, hook), cache_scope.watching():
        for args, kwargs, value, args_after, kwargs_after in rec.calls:
            a, k = _snapshot(args), _snapshot(kwargs)
            state = _globals_state(fn, names)
            got = _call(orig, a, k)
            if not (identical(value, got) and identical(args_after, a)
                    and identical(kwargs_after, k) and identical(state, _globals_state(fn, names))):
                same = False
                break
    cache_scope.clear()
    if not same:
        rec.problem = "the original itself gives other values on replay (depends on state)"
        rec.calls = []
    return rec
