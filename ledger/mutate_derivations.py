r"""``chaplygin mutate-derivations`` (``make mutate-derivations``) — mutants of derivations and runtime.

:mod:`ledger.mutate` mutates the printed transcriptions. This module applies the same one-token AST
mutants (:func:`ledger.mutate.all_mutants`: sign, const, swap, exponent, factor) to two other
targets:

* ``derivations`` — the public functions of ``symbolic/`` that derive
  (:func:`ledger.reach.derivation_functions`). A mutant's checks are the ledger rows that reach the
  function (the ``derived`` map of ``ledger/reach.json``, cheapest first) and, for a derivation
  emitted into ``generated/``, the regeneration of the kernels. Each check is first **replayed**
  (:mod:`ledger.mutate_replay`: the function's calls in that check, recorded once per worker, are
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
  is run against the tests that call its function (:mod:`ledger.mutate_runtime`: recorded once
  per run, fastest first, ``pytest -x``); ``killed`` when a test fails; ``equivalent`` when every
  one passes and the mutant's outputs are bit-for-bit the original's at every call they make
  (e.g. the operands of an IEEE multiplication swapped); else ``survived``.

A survivor whose equivalence needs an argument beyond bit-for-bit equality (a branch that picks one
of two documented implementations of the same formula) is listed in :data:`ARGUED`, with the
argument, and reported ``equivalent`` with "argued:" in its reason.

Every function cached with ``functools`` anywhere in the package is cleared before and after each
mutant (a cached unmutated value would hide the mutant; a cached mutated one would leak into the
next). Mutants run in ``--jobs`` forked workers, cheapest first; ``--out`` is rewritten every 30 s
(``"complete": false``) so an interrupted run keeps what it decided, and ``--resume`` goes on from
there. ``--sample N`` draws ``N`` mutants per target with a fixed seed. Writes
``mutation-derivations.json`` (or ``--out``) atomically; each target's summary line gives its wall
and CPU seconds; exit 1 on a survivor or an error. Before the first mutant each phase (listing
the mutants, the unmutated rows, the instrumented tests) prints what it does, and the long ones
their progress every 30 s (:mod:`ledger.phase`).
"""

from __future__ import annotations

import math
import multiprocessing as mp
import os
import random
import sys
import tempfile
import time
import traceback
from dataclasses import dataclass
from types import FunctionType
from typing import Any

from chaplygin_nd.ledger import mutate as mu
from chaplygin_nd.ledger import mutate_runtime as mr
from chaplygin_nd.ledger.catalog import ROOT, is_checkout
from chaplygin_nd.ledger.mutate_replay import Recording, mutated_position, replay
from chaplygin_nd.ledger.mutate_replay import record as record_calls
from chaplygin_nd.ledger.mutate_runtime import runtime_functions, runtime_tests  # noqa: F401 - API
from chaplygin_nd.ledger.phase import Phase, line
from chaplygin_nd.ledger.reach import (
    clear_caches,
    derivation_functions,
    load,
    load_derived,
    write_json_atomic,
)

from chaplygin_nd import processes
from chaplygin_nd.console import OneLineParser, fail, path_argument, say
from chaplygin_nd.writing import probe_problem

OUT_PATH = ROOT / "mutation-derivations.json"
SEED = 20261123


def functions(target: str) -> dict[str, FunctionType]:
    """The functions mutated for ``target`` (``derivations`` or ``runtime``)."""
    return derivation_functions() if target == "derivations" else runtime_functions()


@dataclass(frozen=True)
class Task:
    target: str
    mutant: mu.Mutant
    rows: tuple  # derivations: ((row, signature, seconds), ...); runtime: (test id, ...)
    emitted: frozenset = frozenset()  # the emitted derivations (their kernels are compared too)
    tests: tuple = ()  # derivations: the tests that reach the function (mutate_runtime.test_map)


#: Mutants no check can tell apart although their outputs differ in the last bits, with the
#: argument that they are equivalent: ``(function, mutation) -> reason``. Applied only to a mutant
#: that survived every row and test reaching it (the outcome becomes ``equivalent``, the reason
#: says "argued"). The mutation text names the line: a change of the function renews the review.
ARGUED: dict[tuple[str, str], str] = {
    ("runtime.axisym.angular_velocity", "const: line 88 col 34: 3 -> 4"):
        "n = 3 then takes the documented method='matrix' path (inverse_coefficients + the six "
        "terms, valid for any n >= 3) instead of the n = 3 component kernel: both evaluate the "
        "same derived L_gamma^{-1}(M) (P:inversion), in a different order of floating-point "
        "operations; the branch is a speed choice",
    ("runtime.axisym.p_coefficients", "const: line 172 col 13: 3 -> 4"):
        "n = 3 then takes the documented any-n path (batched eigenvalues, p affine in sigma) "
        "instead of the n = 3 expanded-determinant kernel: both compute the coefficients of "
        "det(M + sigma gamma gamma^T - lambda Id) (eq:pol-first-integrals), rounded differently; "
        "the branch is a speed choice",
    ("runtime.compiled.angular_velocity_function", "const: line 43 col 52: 53 -> 54"):
        "HeyokaArithmetic reads its bits only for kind 'real'; for 'double' (here) they are unused",
    **{("runtime.compiled.angular_velocity_function", mutation):
       "renames the cfunc's variables (M<i>_<j>, gamma<i>) by another one-to-one map: the names "
       "stay pairwise distinct and a cfunc takes its inputs by position in the list of variables "
       "it is given (m + gamma), so the compiled function is the same map"
       for mutation in ("sign: line 45 col 35: i + 1 -> i - 1", "sign: line 45 col 43: j + 1 -> j - 1",
                        "sign: line 46 col 43: i + 1 -> i - 1", "const: line 45 col 39: 1 -> 2",
                        "const: line 45 col 47: 1 -> 2", "const: line 46 col 47: 1 -> 2")},
    **{("runtime.expressions.angular_velocity", mutation):
       "the two factors of one product of heyoka expressions exchanged: the expression text differs "
       "(the bit-for-bit comparison compares text), but IEEE multiplication is commutative, so the "
       "compiled code returns the same bits"
       for mutation in ("swap: line 98 col 21: _mul(u[i], v[j]) -> _mul(v[j], u[i])",
                        "swap: line 98 col 44: _mul(v[i], u[j]) -> _mul(u[j], v[i])",
                        "swap: line 102 col 39: _mul(c[1], wedge(Mg, gamma, i, j)) -> "
                        "_mul(wedge(Mg, gamma, i, j), c[1])",
                        "swap: line 103 col 18: _mul(c[2], wedge(Me, e, i, j)) -> "
                        "_mul(wedge(Me, e, i, j), c[2])",
                        "swap: line 103 col 50: _mul(c[3], wedge(Mg, e, i, j)) -> "
                        "_mul(wedge(Mg, e, i, j), c[3])",
                        "swap: line 104 col 18: _mul(c[4], wedge(Me, gamma, i, j)) -> "
                        "_mul(wedge(Me, gamma, i, j), c[4])")},
    ("runtime.expressions.structured_field", "swap: line 139 col 18: _mul(ui, Vi[k]) -> "
                                             "_mul(Vi[k], ui)"):
        "the two factors of one product of heyoka expressions exchanged: the expression text "
        "differs, but IEEE multiplication is commutative, so the compiled code returns the same bits",
    **{("search.reconstruction.real_columns", mutation):
       "scales one element of the real basis by 2: the mod-p matrix (_real_matrix) and the "
       "expression (to_expression) both read the coefficient, so the kernel vector's entry halves "
       "and the reconstructed integral is the same polynomial; the basis stays real, non-zero and "
       "independent (tests/test_first_integrals.py::test_real_columns_are_a_real_basis_of_each_block)"
       for mutation in ("const: line 80 col 24: 1 -> 2", "const: line 80 col 51: 1 -> 2")},
    ("search.reconstruction.real_columns", "const: line 80 col 54: 1 -> 2"):
        "the power of i is read only as a truth value (_real_matrix: i_p if ipow else 1; "
        "to_expression: u[0] if not ipow else -u[1]), so 2 acts as 1",
    **{("search.sampled_field.sample", mutation):
       "another seeded draw of the same points: the mutant changes how many candidates a round "
       "draws (line 232) or draws t and M from 1..p-1 instead of 0..p-1 (lines 233, 238); it "
       "still returns `count` points of P mod p with gamma on the sphere, D, 1 + |t|^2 and the "
       "pivots non-zero, and the field there (its contract; fi_field's docstring). The search "
       "concludes nothing from which points: nullity_p >= dim V and rank_p(known) <= dim K hold at "
       "every admissible choice (first_integrals' docstring), so when the ends meet the result is "
       "the same exact statement for any draw"
       for mutation in ("const: line 232 col 16: 64 -> 65",
                        "sign: line 232 col 20: int(1.2 * (count - have)) + 16 -> "
                        "int(1.2 * (count - have)) - 16",
                        "const: line 232 col 48: 16 -> 17",
                        "factor: line 232 col 24: 1.2 * (count - have) -> 1.2",
                        "factor: line 232 col 24: 1.2 * (count - have) -> count - have",
                        "const: line 233 col 25: 0 -> 1", "const: line 238 col 41: 0 -> 1")},
    ("search.integral_search.search_degree", "const: line 219 col 95: 0 -> 1"):
        "a box without known products gets K with one zero column instead of none, and reads it "
        "nowhere: known is 0 by the same 'if prods' (line 220) and the recovery check builds "
        "[F, K] only when there are products (line 224); tests/test_first_integrals.py's box "
        "(5, (3, 5, 1)) runs it and gives the same result",
    ("search.found_integral.varies_in_M", "const: line 227 col 69: 0 -> 1"):
        "another seeded exact point (stream 1 of the same seed and label instead of 0): the part "
        "needs one point where the exact slope dP/d eps is non-zero, a witness wherever it lies; "
        "the part's verdict is the same, its text names the other point",
    ("search.found_integral.varies_in_M", "sign: line 231 col 24: M + eps * N -> M - eps * N"):
        "the derivative along -N: d/d eps P(M - eps N)|_0 = -d/d eps P(M + eps N)|_0, non-zero "
        "exactly when the original is; the part's verdict is the same, its text shows -slope",
    ("reduction.invariants_n5.relations", "const: line 344 col 36: 1 -> 2"):
        "every relation doubled (each monomial starts from INV_RING(2)): 2r spans the same null "
        "space as r (the docstring's 'a basis of the exact null space') and 2r = 0 is the same "
        "relation; its users test vanishing (relation_part), count them, compare them with A_+-R1 "
        "(relations_on_P: all doubled alike) and take the zero set R1 = R2 = 0",
    ("family.sixth_integral.Delta_ring", "factor: line 67 col 11: (2 + a) * (2 + b) -> (2 + b) * (2 + a)"):
        "the same element of the commutative ring RING (== holds); only the insertion order of "
        "the terms in the PolyElement dict differs, which the replay's comparison reads and the "
        "rows do not (ring arithmetic, evaluation at a point, as_expr())",
    **{("axisym_inverse.inverse_denominator", mutation):
       "D times a non-zero constant (-1, 1/2, 3/2): _numerator_coefficients builds every D c_k "
       "from inverse_denominator() itself, so numerator and denominator scale together; D is "
       "only ever used with them (L(N) = D M in P:inversion, Omega = N / D, the cleared "
       "identity D' DN' - N' DD' of wedge_n6, homogeneous in the scale), and a constant multiple "
       "of a common denominator is one"
       for mutation in ("sign: line 90 col 11: 2 * Delta(x_, a_, b_) * (2 + a_ + b_) -> "
                        "-(2 * Delta(x_, a_, b_) * (2 + a_ + b_))",
                        "factor: line 90 col 11: 2 * Delta(x_, a_, b_) -> Delta(x_, a_, b_)",
                        "const: line 90 col 11: 2 -> 3")},
    ("search.found_integral.pfaffian", "sign: line 33 col 15: sp.Integer(0) -> -sp.Integer(0)"):
        "-Integer(0) is Integer(0), SymPy's zero singleton (S.Zero): the same object is returned; "
        "the odd-size branch it sits in is run by tests/test_fi_survivors.py",
    ("search.reconstruction.to_expression", "factor: line 184 col 17: int(co.re[r, j]) * X[j] -> X[j]"):
        "the real parts of the coordinate forms are 0 or 1 (fi_basis.coordinates: zeta_j = "
        "E_2j-1 + i E_2j, its conjugate, e_k = E_k; tested against that definition in "
        "tests/test_fi_survivors.py), and the zeros are skipped by the comprehension's 'if', so "
        "int(re) * X_j is X_j wherever it is formed",
    ("family.wedge_n6.h2_residual", "sign: line 55 col 15: R(expr.subs({a: A, b: B}, simultaneous=True)) -> "
                             "-R(expr.subs({a: A, b: B}, simultaneous=True))"):
        "every numerator coefficient of L_gamma^{-1} negated (the scaled c_k' and D' are built "
        "with R directly, not put): DO, so M-dot and gamma-dot, change sign, the field reversed in "
        "time, and the residual is exactly minus the original's, for any (a, b) and any model: "
        "zero modulo the sphere iff the original is, the function's one documented use",
    ("family.wedge_n6.h2_residual", "sign: line 112 col 15: tot -> -tot"):
        "the derivative along the field negated (DX returns -X(f)): the field reversed in time, "
        "and the residual Dp DX(NH) - NH DX(Dp), linear in DX, is exactly minus the original's "
        "for any model: zero modulo the sphere iff the original is, its one documented use",
    **{("fourd.inverse_apply", mutation):
       "the two summands of a component-wise sum, or the two factors of a product, of ring "
       "elements exchanged: the same elements "
       "of the commutative ring (== holds); only the insertion order of the terms in the "
       "PolyElement dicts differs, which the replay's comparison reads and the rows do not, as "
       "for sixth_integral.Delta_ring"
       for mutation in ("factor: line 191 col 44: c[1] * dot(q_, v) -> dot(q_, v) * c[1]",
                        "swap: line 192 col 12: _add(ap(C[0][0], kv), ap(C[0][1], uv)) -> "
                        "_add(ap(C[0][1], uv), ap(C[0][0], kv))",
                        "swap: line 193 col 11: _add(ap(C[1][0], kv), ap(C[1][1], uv)) -> "
                        "_add(ap(C[1][1], uv), ap(C[1][0], kv))")},
    **{("fourd.dot", mutation):
       "the two factors of one product of ring elements exchanged: the same element of the "
       "commutative ring (== holds); only the insertion order of the terms in the PolyElement "
       "dict differs, which the replay's comparison reads and the rows do not, as for "
       "family.sixth_integral.Delta_ring"
       for mutation in ("factor: line 71 col 11: p[0] * r[0] -> r[0] * p[0]",
                        "factor: line 71 col 25: p[1] * r[1] -> r[1] * p[1]",
                        "factor: line 71 col 39: p[2] * r[2] -> r[2] * p[2]")},
    ("family.wedge_n6.h2_residual", "sign: line 113 col 11: Dp * DX(NH) - NH * DX(Dp) -> "
                             "-(Dp * DX(NH) - NH * DX(Dp))"):
        "the residual negated: zero modulo the sphere iff the original is, its one documented use "
        "(the sign of a residual is a convention)",
}


def _argued(record: dict) -> dict:
    why = ARGUED.get((record["function"], record["mutation"]))
    if record["outcome"] == "survived" and why:
        record.update(outcome="equivalent", reason=f"argued: {why} ({record['reason']})")
    return record


def sample(target: str, size: int | None, seed: int = SEED,
           only: frozenset[str] | None = None) -> list[mu.Mutant]:
    """Every mutant of every function of ``target`` (source order; of the functions named in
    ``only`` if given), or ``size`` of them drawn with ``seed``."""
    every = [m for key, fn in functions(target).items() if only is None or key in only
             for m, _ in mu.all_mutants(key, fn)]
    if size is None or size >= len(every):
        return every
    return sorted(random.Random(f"{seed}:{target}").sample(every, size),
                  key=lambda m: (m.function, m.index))


def evaluate(task: Task) -> dict:
    """Decide one mutant in this process: apply it, run its rows (or tests), restore; a survivor
    whose equivalence is argued in :data:`ARGUED` is ``equivalent``."""
    return _argued(_evaluate(task))


def _evaluate(task: Task) -> dict:
    fn = functions(task.target)[task.mutant.function]
    original = fn.__code__
    m = task.mutant
    record: dict[str, Any] = {"target": task.target, "function": m.function, "index": m.index,
                              "mutation": f"{m.operator}: {m.description}", "row": None,
                              "outcome": "", "reason": ""}
    start = time.perf_counter()
    try:
        code = mu.compile_mutant(fn, m)
    except Exception as err:  # noqa: BLE001 - a mutant that does not compile is not a test
        record.update(outcome="killed", reason=f"does not compile: {type(err).__name__}")
        return record
    try:
        clear_caches()
        if task.target == "runtime":
            record = mr.evaluate(fn, code, m.function, task.rows, record)
        elif not task.rows:
            record = mr.evaluate(fn, code, m.function, task.tests, record)
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
        clear_caches()
        record["seconds"] = round(time.perf_counter() - start, 2)


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
    outcome: dict = {}
    if check == GENERATED_CHECK:
        from chaplygin_nd.symbolic.codegen.kernels import stale_report

        def run():
            outcome["same"] = not stale_report()
    else:
        def run():
            got, _note = mu.run_row(check, max(mu.MIN_BUDGET, mu.BUDGET_FACTOR * seconds))
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
    once per worker by one instrumented run (:func:`mutate_runtime.test_map`), only for a mutant
    its rows did not kill."""
    if key not in _TESTS:
        files = mr.mentioning([key])
        reach = mr.test_map({key: fn}, files) if files else {}
        _TESTS[key] = tuple(t for t, _ in reach.get(key, ()))
    return _TESTS[key]


def _run_check(fn, code, original, check: str, base, seconds: float) -> tuple[bool, str]:
    """Run one check with the mutant ``code`` in place of ``original``: (changed, why)."""
    fn.__code__ = code
    try:
        if check == GENERATED_CHECK:
            from chaplygin_nd.symbolic.codegen.kernels import stale_report

            budget = max(mu.MIN_BUDGET, mu.BUDGET_FACTOR * seconds)
            try:
                with mu.time_budget(budget):
                    stale = stale_report()
            except mu.BudgetExceeded:
                return True, f"the regeneration of the kernels ran past its budget of {budget:.0f} s"
            return (True, "no row changed, but the regenerated kernels differ: make verify's "
                          "stale check of generated/ fails") if stale else (False, "")
        got, note = mu.run_row(check, max(mu.MIN_BUDGET, mu.BUDGET_FACTOR * seconds), base)
        return got != base, note or (mu._difference(base, got) if got != base else "")
    finally:
        fn.__code__ = original
        clear_caches()


def _decide_by_rows(task: Task, fn, code, record: dict) -> dict:
    """A derivation's mutant against its rows (cheapest first) and, if emitted, the regenerated
    kernels. Each check is first *replayed* (:mod:`ledger.mutate_replay`): when the mutant returns
    exactly the recorded value at every call the check makes, the check cannot change and is not
    run; otherwise it is run with the mutant, and a change kills. ``equivalent`` needs every
    check replayed equal and the mutated line executed; a check that cannot be replayed falls
    back to running it and comparing values on the cheapest such row (:func:`ledger.mutate.settle`)."""
    m = task.mutant
    original = fn.__code__
    line = mutated_position(m.description)
    checks = [(row, base, seconds) for row, base, seconds in task.rows]
    if m.function in task.emitted:
        checks.append((GENERATED_CHECK, None, 0.0))
    replayed: list[str] = []
    differing: list[str] = []
    unreplayed: list[tuple[str, object, float]] = []
    calls, ran = 0, False
    for check, base, seconds in checks:  # cheapest first: replay, and run only what may change
        rec = _recording(m.function, fn, check, base, seconds)
        if rec.problem:
            unreplayed.append((check, base, seconds))
            record.setdefault("not replayed", {})[check] = rec.problem
        else:
            budget = max(mu.MIN_BUDGET, mu.BUDGET_FACTOR * max(seconds, rec.seconds))
            try:  # a replay has the check's budget too: a mutant may never return (round 25:
                with mu.time_budget(budget):  # a recursion that never ended held a worker)
                    same, line_ran = replay(fn, code, rec, line)
            except mu.BudgetExceeded:  # undecided by the replay: the check itself is run
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
        changed, why = _run_check(fn, code, original, check, base, max(seconds, rec.seconds))
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
        mu.settle(record, fn, code, rows, to_run, line=line, ran=ran)
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
        failed = mr.kill(fn, code, m.function, tests) if tests else None
        if failed is not None:
            record.update(outcome="killed", row="tests", reason=f"no row changed; {failed}")
    return record


def plan(target: str, selection: list[mu.Mutant], jobs: int, tests_for=()) -> list[Task]:
    """Tasks for ``selection``: for derivations, the reaching rows (cheapest first) with their
    unmutated signatures (one baseline run of just those rows), and for a derivation no row
    reaches or one in ``tests_for`` (the survivors re-run), the tests that reach it
    (:func:`mutate_runtime.test_map` over the test files that name it)."""
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
    base = mu.baseline(needed, jobs=jobs, phase=Phase(
        f"planning: running the {len(needed)} rows that reach the mutants, unmutated "
        f"({mu.plural(jobs, 'job')})",
        what="rows done").start()) if needed else {}
    every = functions(target)
    tested = {f: every[f] for f in chosen if not chosen[f] or f in tests_for}
    files = mr.mentioning(tested) if tested else ()
    reach = mr.test_map(tested, files, phase=Phase(
        f"planning: running {len(files)} test files unmutated, to find the tests that reach the "
        f"{len(tested)} functions no row reaches{' or re-run' if tests_for else ''}",
        what="tests done").start()) if tested else {}
    return [Task(target, m, tuple((r, base[r][0], base[r][1]) for r in chosen[m.function]),
                 frozenset(emitted), tuple(t for t, _ in reach.get(m.function, ())))
            for m in selection]


def _init_worker():
    from chaplygin_nd.ledger.catalog import discover

    discover()


def summary(records: list[dict], target: str, seconds: float | None = None, cpu: float = 0.0,
            ran: int | None = None) -> str:
    """One line per target: the outcomes of all its ``records``, and (``seconds`` given) the time
    of this run, which ran ``ran`` of them (the others were kept from the file resumed or re-run)."""
    count = {k: sum(r["outcome"] == k for r in records)
             for k in ("killed", "equivalent", "survived", "error")}
    functions = len({(r["target"], r["function"]) for r in records})
    line = (f"{target}: {mu.plural(len(records), 'mutant')} of {mu.plural(functions, 'function')}: "
            f"{count['killed']} killed, {count['equivalent']} equivalent, "
            f"{count['survived']} survived, {mu.plural(count['error'], 'error')}")
    if seconds is None:
        return line
    ran = len(records) if ran is None else ran
    return f"{line}; this run: {ran} mutants in {seconds:.0f} s wall, {cpu:.0f} s CPU"


def _current(records: list[dict]) -> list[dict]:
    """The records kept from an earlier run (``--resume``, ``--rerun``) whose mutant the code still
    has; the others (a line moved, the code changed) are dropped with one line, and the mutants
    the code has now in their place are run as not yet decided. A record of a mutant that no
    longer exists would otherwise stand in the table for code that is not there."""
    if not records:
        return records
    current = {(t, m.function, f"{m.operator}: {m.description}")
               for t in sorted({r["target"] for r in records}) for m in sample(t, None)}
    kept = [r for r in records if (r["target"], r["function"], r["mutation"]) in current]
    if len(kept) < len(records):
        gone = sorted({r["function"] for r in records if r not in kept})
        print(f"dropped {mu.plural(len(records) - len(kept), 'record')} of mutants the code no "
              f"longer has ({', '.join(gone)}): their functions changed since that run", flush=True)
    return kept


def main(argv: list[str] | None = None) -> int:
    parser = OneLineParser(prog="chaplygin mutate-derivations",
                           description=__doc__.splitlines()[0].replace("``", ""))
    parser.add_argument("--target", choices=("derivations", "runtime"), action="append",
                        help="what to mutate (default: both)")
    parser.add_argument("--sample", type=int, default=None,
                        help="draw this many mutants per target (seeded); default: all")
    parser.add_argument("--seed", type=int, default=SEED,
                        help=f"the seed of --sample's draw (default {SEED})")
    parser.add_argument("--function", action="append", default=[],
                        help="only these functions (e.g. reduced.horizontal_blocks; --list lists them)")
    parser.add_argument("--list", action="store_true",
                        help="list the functions of the targets (the names --function takes) and exit")
    parser.add_argument("--rerun", type=path_argument, default=None,
                        help="re-run only the survivors and errors recorded in this JSON file")
    parser.add_argument("--resume", action="store_true",
                        help="keep the mutants already decided in --out (an interrupted run) and "
                             "run only the others")
    parser.add_argument("--again", default="survived,error", type=lambda v: tuple(v.split(",")),
                        help="with --rerun: the outcomes run again (default survived,error; add "
                             "equivalent after adding a test that may tell such mutants apart)")
    parser.add_argument("--jobs", "-j", type=int, default=2, help="worker processes (default 2)")
    parser.add_argument("--out", type=path_argument, default=None,
                        help="where to write (default mutation-derivations.json in the checkout)")
    args = parser.parse_args(argv)
    known = [name for target in args.target or ["derivations", "runtime"]
             for name in functions(target)]
    if args.list:
        say("\n".join(known))
        return 0
    lister = " ".join([parser.prog, *(f"--target {t}" for t in args.target or []), "--list"])
    problem = mu.unknown_functions(args.function, known, lister)
    if problem:
        return fail(problem)
    if args.rerun is not None:  # read before the run: a wrong file never costs a whole run
        earlier = mu.compared_outcomes(args.rerun)
        if isinstance(earlier, str):
            return fail(earlier.replace("--compare", "--rerun", 1))
    if args.out is None and not is_checkout():
        return fail(f"{parser.prog}: give --out FILE (an installed package is never written into)")
    partial = [o for o, given in (("--function", args.function), ("--sample", args.sample),
                                  ("--target", args.target), ("--rerun", args.rerun)) if given]
    if args.out is None and partial and not args.resume:  # the checked-in record is a whole run
        return fail(f"{parser.prog}: with {' '.join(partial)} give --out FILE: a partial run would "
                    f"replace the record of the full run, {OUT_PATH.name}")
    if args.out is not None and (args.out.exists() or args.out.is_symlink()) and (
            args.out.is_symlink() or isinstance(mu.compared_outcomes(args.out), str)):
        return fail(f"--out {args.out}: exists and is not a mutation JSON this program wrote; give "
                    "a new file name (nothing else is replaced)")
    args.out = args.out or OUT_PATH
    folder = args.out.parent
    where = probe_problem(folder) if folder.is_dir() else "no such folder"
    if where:  # before the run, not after it (checked by creating a file there, as root too)
        return fail(f"--out {args.out}: cannot write in {folder} ({where}); give a file in a "
                    "folder you can write")
    _init_worker()
    records: list[dict] = []
    runs: list[dict] = []
    targets = args.target or ["derivations", "runtime"]
    if args.resume:  # keep what an earlier (interrupted) run into --out decided
        records, runs = _read(args.out)
        records = [r for r in records if r["outcome"] != "error"]
    if args.rerun:  # keep what the earlier run decided, except what is run again
        records, runs = _read(args.rerun)
        records = [r for r in records if r["target"] not in targets or r["outcome"] not in args.again]
    records = _current(records)
    done = {(r["target"], r["function"], r["mutation"]) for r in records}
    for target in targets:
        named = frozenset(args.function) & set(functions(target)) if args.function else None
        Phase(f"{target}: listing the mutants of "
              f"{mu.plural(len(functions(target)) if named is None else len(named), 'function')}"
              ).start()
        selection = sample(target, None if args.function else args.sample, args.seed, only=named)
        if args.rerun:
            again = {(r["function"], r["mutation"]) for r in _read(args.rerun)[0]
                     if r["outcome"] in args.again and r["target"] == target}
            selection = [m for m in sample(target, None, args.seed)
                         if (m.function, f"{m.operator}: {m.description}") in again]
        selection = [m for m in selection
                     if (target, m.function, f"{m.operator}: {m.description}") not in done]
        t0, c0 = time.perf_counter(), _cpu_seconds()
        run = {"argv": sys.argv[1:] if argv is None else list(argv), "target": target,
               "complete": False, "load average at start": list(os.getloadavg())}
        runs.append(run)
        with tempfile.TemporaryDirectory(prefix="chaplygin-mutate-") as work:
            os.environ[mr.WORK_ENV] = work  # the workers' cache folders (mutate_runtime)
            try:
                try:
                    tasks = plan(target, selection, args.jobs,
                                 {m.function for m in selection} if args.rerun else ())
                except RuntimeError as err:  # e.g. a test file that does not collect, an unmutated
                    return fail(f"{parser.prog}: {err}")  # row that raises: nothing to compare
                print(f"{target}: {len(tasks)} mutants to run", flush=True)
                mine = _run(tasks, args.jobs, records, runs, args, run, t0, c0)
            finally:
                os.environ.pop(mr.WORK_ENV, None)
        _progress(run, len(mine), len(tasks), t0, c0)
        run["complete"] = True
        print(summary([r for r in records if r["target"] == target], target,
                      time.perf_counter() - t0, _cpu_seconds() - c0, len(mine)), flush=True)
    _write(records, runs, args)
    print(f"wrote {args.out}")
    bad = [r for r in records if r["outcome"] in ("survived", "error")]
    for r in bad:
        print(f"PROBLEM: {r['function']} {r['mutation']}: {r['outcome']}", file=sys.stderr)
    return 1 if bad else 0


def _cpu_seconds() -> float:
    """CPU seconds of this process and its finished children (the workers, once joined; not the
    baseline's forkserver workers, grandchildren of this process)."""
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


def _read(path) -> tuple[list[dict], list[dict]]:
    """The records and runs of an earlier run written to ``path`` (none if there is no file)."""
    import json

    if not path.is_file():
        return [], []
    data = json.loads(path.read_text(encoding="utf-8"))
    return data["mutants"], data.get("runs", [])


def _progress(run: dict, ran: int, tasks: int, t0: float, c0: float) -> None:
    run.update({"mutants run": ran, "of": tasks, "wall seconds": round(time.perf_counter() - t0),
                "cpu seconds (this process and joined workers)": round(_cpu_seconds() - c0)})


def _write(records, runs, args) -> None:
    """``--out``: one summary line per target over all its records, the runs that made them
    (command, mutants run, wall and CPU seconds, load), ``complete`` when every run finished."""
    order = {"derivations": 0, "runtime": 1}
    targets = sorted({r["target"] for r in records}, key=lambda t: order.get(t, 2))
    lines = [summary([r for r in records if r["target"] == t], t) for t in targets]
    if len(targets) > 1:
        lines.append(summary(records, "total"))
    write_json_atomic({"summary": lines, "seed": args.seed, "sample": args.sample, "runs": runs,
                       "complete": all(r.get("complete") for r in runs),
                       "mutants": sorted(records, key=lambda r: (order.get(r["target"], 2),
                                                                 r["function"], r["index"]))},
                      args.out)


#: Mutants of one function decided by one worker in a row (its recordings are made once for
#: them); a function with more is split, so an interrupted run loses at most one such group.
GROUP = 40


def groups(tasks: list[Task], jobs: int = 1) -> list[list[Task]]:
    """``tasks`` grouped by function, the most expensive group first (cheapest check times
    mutants: the long groups start early and the workers end together). A group is decided in one
    worker and reported when it ends; its calls are recorded once. Chunks of at most
    :data:`GROUP`, and of at most a quarter of each worker's share: a run of one function's 21
    mutants was one group, so one core worked, nothing was reported for 6 minutes and a Ctrl-C kept
    nothing (round-24 trial)."""
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
#: progress and kept nothing until one ended (round 24).
_DECIDED: Any = None

#: How often a run writes ``--out`` and prints its progress line (s).
WRITE_SECONDS = 30


def evaluate_group(tasks: list[Task]) -> list[dict]:
    """Decide the mutants of one group in this worker, in order; each record is also sent to the
    parent as soon as it is decided (:data:`_DECIDED`)."""
    out = []
    for t in tasks:
        out.append(evaluate(t))
        if _DECIDED is not None:
            _DECIDED.put(out[-1])
    return out


def _run(tasks: list[Task], jobs: int, records: list[dict], runs, args, run, t0, c0) -> list[dict]:
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
        _progress(run, len(mine), len(tasks), t0, c0)
        _write(records, runs, args)

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
        with processes.pool(jobs, context, _init_worker) as pool:
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


if __name__ == "__main__":
    sys.exit(main())
