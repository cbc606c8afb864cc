r"""The mutants of ``chaplygin mutate-derivations``: what each target mutates and how one mutant is decided.

:mod:`.printed` mutates the printed transcriptions. This module applies the same one-token AST
mutants (:func:`.operators.all_mutants`: sign, const, swap, exponent, factor) to two other
targets:

* ``derivations`` — the public functions of ``symbolic/`` that derive
  (:func:`ledger.reach.derivation_functions`). A mutant's checks are the ledger rows that reach the
  function (the ``derived`` map of ``ledger/reach.json``, cheapest first) and, for a derivation
  emitted into ``generated/``, the regeneration of the kernels. Each check is first **replayed**
  (:mod:`.replay`: the function's calls in that check, recorded once per worker, are
  made again with the mutant): a check at whose every call the mutant returns exactly the recorded
  value cannot change, and is not run. Any other check is run with the mutant, and stops at the
  first part the row announces final that differs (``registry.decided``). ``killed`` when a check
  changes (a row's verdict, counterexample or parts, a raise, its budget exceeded; stale kernels);
  ``equivalent`` when every check replayed equal and the mutated line ran (a check that cannot be
  replayed is run, then the values compared on the cheapest such row); otherwise the tests that
  reach the function (found by one instrumented run of the test files naming its module) are
  run, and a failure kills; else ``survived``. A derivation no row reaches is run against those
  tests alone (as the runtime is).
* ``runtime`` — the public functions of ``runtime/``. Their checks are tests, not rows: a mutant
  is run against the tests that call its function (:mod:`.runtime`: recorded once
  per run, fastest first, ``pytest -x``); ``killed`` when a test fails; ``equivalent`` when every
  one passes and the mutant's outputs are bit-for-bit the original's at every call they make
  (e.g. the operands of an IEEE multiplication swapped); else ``survived``.

A survivor whose equivalence needs an argument beyond bit-for-bit equality (a branch that picks one
of two documented implementations of the same formula) is listed in :data:`.argued.ARGUED`, with the
argument, and reported ``equivalent`` with "argued:" in its reason.

Every function cached with ``functools`` that a mutant can reach is cleared before and after
each mutant (a cached unmutated value would hide the mutant; a cached mutated one would leak into
the next): :mod:`.cache_scope` says which. The command, its run loop and its record file are
:mod:`.command`, :mod:`.runloop` and :mod:`.record`.
"""

from __future__ import annotations

import random
import time
import traceback
from dataclasses import dataclass
from types import FunctionType
from typing import Any

from chaplygin_nd.ledger.catalog import ROOT
from chaplygin_nd.ledger.mutation import cache_scope, checks, forkpoint, planned
from chaplygin_nd.ledger.mutation import runtime as mr
from chaplygin_nd.ledger.mutation.argued import argued
from chaplygin_nd.ledger.mutation.equivalence import settle
from chaplygin_nd.ledger.mutation.operators import (
    Mutant,
    all_mutants,
    compile_mutant,
    source_digest,
)
from chaplygin_nd.ledger.mutation.record import plural
from chaplygin_nd.ledger.mutation.replay import Recording, mutated_position, replay
from chaplygin_nd.ledger.mutation.replay import record as record_calls
from chaplygin_nd.ledger.mutation.runtime import runtime_functions
from chaplygin_nd.ledger.phase import Phase
from chaplygin_nd.ledger.reach import derivation_functions, load, load_derived

OUT_PATH = ROOT / "mutation-derivations.json"
SEED = 20261123


def functions(target: str) -> dict[str, FunctionType]:
    """The functions mutated for ``target`` (``derivations`` or ``runtime``)."""
    return derivation_functions() if target == "derivations" else runtime_functions()


@dataclass(frozen=True)
class Task:
    target: str
    mutant: Mutant
    rows: tuple  # derivations: ((row, signature, seconds), ...); runtime: (test id, ...)
    emitted: frozenset = frozenset()  # the emitted derivations (their kernels are compared too)
    tests: tuple = ()  # derivations: the tests that reach the function (runtime.test_map)


def sample(target: str, size: int | None, seed: int = SEED,
           only: frozenset[str] | None = None) -> list[Mutant]:
    """Every mutant of every function of ``target`` (source order; of the functions named in
    ``only`` if given), or ``size`` of them drawn with ``seed``."""
    every = [m for key, fn in functions(target).items() if only is None or key in only
             for m, _ in all_mutants(key, fn)]
    if size is None or size >= len(every):
        return every
    return sorted(random.Random(f"{seed}:{target}").sample(every, size),
                  key=lambda m: (m.function, m.index))


def evaluate(task: Task) -> dict:
    """Decide one mutant in this process: apply it, run its rows (or tests), restore; a survivor
    whose equivalence is argued in :data:`ARGUED` is ``equivalent``."""
    return argued(_evaluate(task))


def _evaluate(task: Task) -> dict:
    fn = functions(task.target)[task.mutant.function]
    original = fn.__code__
    m = task.mutant
    record: dict[str, Any] = {"target": task.target, "function": m.function, "index": m.index,
                              "mutation": f"{m.operator}: {m.description}", "row": None,
                              "outcome": "", "reason": "", "source": _digest(m.function, fn)}
    start, cpu = time.perf_counter(), time.process_time()
    try:
        code = compile_mutant(fn, m)
    except Exception as err:  # noqa: BLE001 - a mutant that does not compile is not a test
        record.update(outcome="killed", reason=f"does not compile: {type(err).__name__}")
        return record
    try:
        if task.target == "derivations":  # the caches fn cannot reach stay warm (cache_scope)
            cache_scope.begin(m.function, fn)
        else:
            cache_scope.end()
        cache_scope.clear()
        if task.target == "runtime":
            record = mr.evaluate(fn, code, m.function, task.rows, record)
        elif not task.rows:
            record = mr.evaluate(fn, code, m.function, task.tests, record, FORK)
        else:
            record = _decide_by_rows(task, fn, code, record)
        if record["outcome"] == "survived":  # the last resort: the slow tests of its module
            failed = mr.kill_slow(fn, code, m.function)
            if failed is not None:
                record.update(outcome="killed", row="slow tests",
                              reason=f"{record['reason'][:200]}; then a slow test failed: {failed}")
        return record
    except Exception:  # noqa: BLE001
        record.update(outcome="error", reason=traceback.format_exc(limit=3))
        return record
    finally:
        fn.__code__ = original
        cache_scope.clear()
        record["seconds"] = round(time.perf_counter() - start, 2)
        record["cpu seconds"] = round(time.process_time() - cpu, 2)


_DIGESTS: dict[tuple, str] = {}


def _digest(key: str, fn) -> str:
    """:func:`.operators.source_digest` of ``fn``, once per process and code object."""
    memo = (key, fn.__code__)
    if memo not in _DIGESTS:
        _DIGESTS[memo] = source_digest(fn)
    return _DIGESTS[memo]


#: This worker's recordings of one function's calls in each check ((function, check) -> Recording);
#: tasks come grouped by function, so only the current function's are kept.
_RECORDINGS: dict[tuple[str, str], Recording] = {}
GENERATED_CHECK = "generated/"


def _recording(key: str, fn, check: str, base, seconds: float) -> Recording:
    """The calls of ``fn`` in one check (a row, or :data:`GENERATED_CHECK`: the regeneration of
    the kernels), recorded once per worker; a run whose outcome is not the baseline's is not
    replayed (the recorder itself must not change what it watches)."""
    if (key, check) in _RECORDINGS:
        return _RECORDINGS[(key, check)]
    if any(k != key for k, _ in _RECORDINGS):
        _RECORDINGS.clear()
    made = planned.take(key, check) if PLANNED else None  # this row's run for every function
    if made is not None and made.problem != planned.NOT_BASELINE:
        _RECORDINGS[(key, check)] = planned.guard(fn, made)
        return _RECORDINGS[(key, check)]
    outcome: dict = {}
    if check == GENERATED_CHECK:
        from chaplygin_nd.symbolic.codegen.kernels import stale_report

        def run():
            outcome["same"] = not stale_report()
    else:
        def run():
            got, _note = checks.run_row(check, max(checks.MIN_BUDGET, checks.BUDGET_FACTOR * seconds))
            outcome["same"] = got == base
    start = time.perf_counter()
    rec = record_calls(fn, run)
    rec.seconds = time.perf_counter() - start
    if not rec.problem and not outcome.get("same"):
        rec.problem, rec.calls = "the recorded run did not reproduce the baseline", []
    _RECORDINGS[(key, check)] = rec
    return rec


_TESTS: dict[str, tuple[str, ...]] = {}


def _tests_reaching(key: str, fn) -> tuple[str, ...]:
    """The tests (fastest first) that call ``fn``, among the test files naming its module: found
    once per worker by one instrumented run (:func:`.runtime.test_map`), only for a mutant
    its rows did not kill."""
    if key not in _TESTS:
        files = mr.mentioning([key])
        reach = mr.test_map({key: fn}, files) if files else {}
        _TESTS[key] = tuple(t for t, _ in reach.get(key, ()))
    return _TESTS[key]


#: Whether a row (or, for a derivation no row reaches, its tests) is run with a mutant from a
#: process parked at the function's first call (:mod:`.forkpoint`); ``False``: in the worker
#: itself, from the start (the same answer, slower: ``chaplygin bench mutation`` runs both side
#: by side).
FORK = True
#: Whether a mutant that changed no row is run against its tests from the test session parked at
#: the function's first call (:func:`.runtime.kill` with ``fork``, as a derivation no row reaches
#: is); ``False``: a whole ``pytest`` session in the worker per mutant (the same answer, slower:
#: ``python -m bench.bench_mutation_profile --fast`` runs both side by side).
TESTS_FORK = True
#: Whether the planning records every planned function's calls in ONE run of each row
#: (:mod:`.planned`) for the workers to take, instead of each worker running a row once per
#: function to record it (the same answer, slower: ``python -m bench.bench_mutation_profile
#: --fast`` runs both side by side).
PLANNED = True
#: This worker's parked processes ((function, row) -> :class:`.forkpoint.Parked`), of the current
#: function only (tasks come grouped by function; :func:`end_group` ends them).
_PARKED: dict[tuple[str, str], forkpoint.Parked] = {}


def end_group() -> None:
    """End this worker's parked processes, rows' and tests' (after a group of one function's
    mutants)."""
    for parked in _PARKED.values():
        parked.close()
    _PARKED.clear()
    mr.end_parked()


def _row_from_fork(key: str, fn, code, check: str, base, budget: float) -> tuple | None:
    """``checks.run_row(check, budget, base)`` with ``code`` in ``fn``, run from the process parked
    at ``fn``'s first call in that row (:mod:`.forkpoint`), or None (then run in the worker)."""
    if not FORK or check == GENERATED_CHECK:
        return None
    if any(k != key for k, _ in _PARKED):
        end_group()
    if (key, check) not in _PARKED:
        cache_scope.clear()  # the parked process starts from the state a run here would
        _PARKED[(key, check)] = forkpoint.Parked(fn, lambda: checks.run_row(check, budget, base))
    answer = _PARKED[(key, check)].run(code)
    return answer if isinstance(answer, tuple) and len(answer) == 2 else None


def _run_check(fn, code, original, check: str, base, seconds: float, key: str = ""
               ) -> tuple[bool, str]:
    """Run one check with the mutant ``code`` in place of ``original``: (changed, why)."""
    budget = max(checks.MIN_BUDGET, checks.BUDGET_FACTOR * seconds)
    answer = _row_from_fork(key, fn, code, check, base, budget) if key else None
    if answer is not None:
        got, note = answer
        return got != base, note or (checks.difference(base, got) if got != base else "")
    fn.__code__ = code
    try:
        if check == GENERATED_CHECK:
            from chaplygin_nd.symbolic.codegen.kernels import stale_report

            budget = max(checks.MIN_BUDGET, checks.BUDGET_FACTOR * seconds)
            try:
                with checks.time_budget(budget):
                    stale = stale_report()
            except checks.BudgetExceeded:
                return True, f"the regeneration of the kernels ran past its budget of {budget:.0f} s"
            return (True, "no row changed, but the regenerated kernels differ: make verify's "
                          "stale check of generated/ fails") if stale else (False, "")
        got, note = checks.run_row(check, max(checks.MIN_BUDGET, checks.BUDGET_FACTOR * seconds), base)
        return got != base, note or (checks.difference(base, got) if got != base else "")
    finally:
        fn.__code__ = original
        cache_scope.clear()


def _decide_by_rows(task: Task, fn, code, record: dict) -> dict:
    """A derivation's mutant against its rows (cheapest first) and, if emitted, the regenerated
    kernels. Each check is first *replayed* (:mod:`.replay`): when the mutant returns
    exactly the recorded value at every call the check makes, the check cannot change and is not
    run; otherwise it is run with the mutant, and a change kills. ``equivalent`` needs every
    check replayed equal and the mutated line executed; a check that cannot be replayed falls
    back to running it and comparing values on the cheapest such row (:func:`.equivalence.settle`)."""
    m = task.mutant
    original = fn.__code__
    line = mutated_position(m.description)
    order = [(row, base, seconds) for row, base, seconds in task.rows]
    if m.function in task.emitted:
        order.append((GENERATED_CHECK, None, 0.0))
    replayed: list[str] = []
    differing: list[str] = []
    unreplayed: list[tuple[str, object, float]] = []
    calls, ran = 0, False
    for check, base, seconds in order:  # cheapest first: replay, and run only what may change
        rec = _recording(m.function, fn, check, base, seconds)
        if rec.problem:
            unreplayed.append((check, base, seconds))
            record.setdefault("not replayed", {})[check] = rec.problem
        else:
            budget = max(checks.MIN_BUDGET, checks.BUDGET_FACTOR * max(seconds, rec.seconds))
            try:  # a replay has the check's budget too: a mutant may never return (once
                with checks.time_budget(budget):  # a recursion that never ended held a worker)
                    same, line_ran = replay(fn, code, rec, line)
            except checks.BudgetExceeded:  # undecided by the replay: the check itself is run
                record.setdefault("not replayed", {})[check] = f"replay past {budget:.0f} s"
                unreplayed.append((check, base, seconds))
                same = line_ran = False
            ran = ran or line_ran
            if same:
                replayed.append(check)
                calls += len(rec.calls)
                continue
            if check not in record.get("not replayed", {}):
                differing.append(check)
        changed, why = _run_check(fn, code, original, check, base, max(seconds, rec.seconds),
                                  key=m.function)
        if changed:
            record.update(outcome="killed", row=check, reason=why)
            return record
    to_run = [*differing, *(r[0] for r in unreplayed)]
    rows = [r for r in unreplayed if r[0] != GENERATED_CHECK]
    if differing:
        record.update(outcome="survived", row=", ".join(differing), reason=(
            f"the mutant's value differs at a call of {', '.join(differing)}, but no check "
            "changed"))
    elif rows:
        settle(record, fn, code, rows, to_run, line=line, ran=ran)
    elif not ran:
        record.update(outcome="survived", row=", ".join(replayed), reason=(
            f"equal values at all {calls} calls of {', '.join(replayed)}, but the mutated line "
            "never ran there (a branch no check takes)"))
    else:
        record.update(outcome="equivalent", row=", ".join(replayed), reason=(
            f"replayed: the mutant returns exactly the recorded value (and leaves its arguments "
            f"as the original does) at all {calls} calls made by {', '.join(replayed)}, the "
            "mutated line executed; so no check can change"))
    if record["outcome"] == "survived":  # no check changed: the tests that reach it may tell
        tests = task.tests or _tests_reaching(m.function, fn)
        failed = mr.kill(fn, code, m.function, tests, TESTS_FORK) if tests else None
        if failed is not None:
            record.update(outcome="killed", row="tests", reason=f"no row changed; {failed}")
    return record


def plan(target: str, selection: list[Mutant], jobs: int, tests_for=()) -> list[Task]:
    """Tasks for ``selection``: for derivations, the reaching rows (cheapest first) with their
    unmutated signatures (one baseline run of just those rows), and for a derivation no row
    reaches or one in ``tests_for`` (the survivors re-run), the tests that reach it
    (:func:`.runtime.test_map` over the test files that name it)."""
    if target == "runtime":
        reach = mr.test_map(phase=Phase(
            "planning: running the runtime's tests unmutated, to find the tests that reach each of "
            "its functions",
            what="tests done").start()) if selection else {}
        return [Task(target, m, tuple(t for t, _ in reach.get(m.function, ()))) for m in selection]
    derived, emitted = load_derived()
    _, seconds = load()
    by_function: dict[str, list[str]] = {}
    for row, fs in derived.items():
        for f in fs:
            by_function.setdefault(f, []).append(row)
    chosen: dict[str, list[str]] = {}
    for m in selection:
        chosen[m.function] = sorted(by_function.get(m.function, []),
                                    key=lambda r: (seconds.get(r, 99), r))
    needed = sorted({r for rows in chosen.values() for r in rows})
    base = checks.baseline(needed, jobs=jobs, phase=Phase(
        f"planning: running the {len(needed)} rows that reach the mutants, unmutated "
        f"({plural(jobs, 'job')})",
        what="rows done").start()) if needed else {}
    every = functions(target)
    tested = {f: every[f] for f in chosen if not chosen[f] or f in tests_for}
    files = mr.mentioning(tested) if tested else ()
    reach = mr.test_map(tested, files, phase=Phase(
        f"planning: running {len(files)} test files unmutated, to find the tests that reach the "
        f"{len(tested)} functions no row reaches{' or re-run' if tests_for else ''}",
        what="tests done").start()) if tested else {}
    tasks = [Task(target, m, tuple((r, base[r][0], base[r][1]) for r in chosen[m.function]),
                  frozenset(emitted), tuple(t for t, _ in reach.get(m.function, ())))
             for m in selection]
    if PLANNED and needed:
        planned.record_tasks(tasks, jobs, phase=Phase(
            f"planning: recording the calls of every mutated function in one run of each of the "
            f"{len(needed)} rows ({plural(jobs, 'job')})", what="rows done").start())
    return tasks


