r"""``python -m chaplygin_nd.ledger.mutate_derivations`` (``make mutate-derivations``) — mutants of derivations and runtime.

:mod:`ledger.mutate` mutates the printed transcriptions. This module applies the same one-token AST
mutants (:func:`ledger.mutate.all_mutants`: sign, const, swap, exponent, factor) to two other
targets:

* ``derivations`` — the public functions of ``symbolic/`` that derive
  (:func:`ledger.reach.derivation_functions`). A mutant is run against the ledger rows that reach
  the function (the ``derived`` map of ``ledger/reach.json``, cheapest first, all of them until
  one changes), as ``make mutate`` does for printed functions: ``killed`` when a row's verdict,
  counterexample or parts change (or it raises or runs past its budget); for a derivation emitted
  into ``generated/``, also when the regenerated kernels differ (``make verify``'s stale check
  fails); ``equivalent`` when nothing changed and the mutant returns exactly the original value at
  every call of the cheapest row, else ``survived``.
* ``runtime`` — the public functions of ``runtime/``. Their checks are tests, not rows: a mutant
  is run against the test files that import the runtime (:func:`runtime_tests`) with
  ``pytest -x``; ``killed`` when a test fails; ``equivalent`` when every test passes and the
  mutant's outputs are bit-for-bit the original's at every call the tests make (e.g. the operands
  of an IEEE multiplication swapped); else ``survived``.

Every function cached with ``functools`` anywhere in the package is cleared before and after each
mutant (a cached unmutated value would hide the mutant; a cached mutated one would leak into the
next). The full set of mutants is large; ``--sample N`` draws ``N`` of them with a fixed seed
(deterministic, recorded). Writes ``mutation-derivations.json`` (or ``--out``) atomically; exit 1
on a survivor or an error.
"""

from __future__ import annotations

import importlib
import multiprocessing as mp
import pkgutil
import random
import re
import sys
import time
import traceback
from dataclasses import dataclass
from types import FunctionType
from typing import Any

from chaplygin_nd.ledger import mutate as mu
from chaplygin_nd.ledger.catalog import ROOT, is_checkout
from chaplygin_nd.ledger.reach import derivation_functions, load_derived, write_json_atomic

from chaplygin_nd import processes
from chaplygin_nd.console import OneLineParser, fail, path_argument, say

OUT_PATH = ROOT / "mutation-derivations.json"
_IMPORTS_RUNTIME = re.compile(r"^\s*(from chaplygin_nd\.runtime\b|import chaplygin_nd\.runtime\b|"
                              r"from chaplygin_nd import runtime\b)", re.MULTILINE)


def runtime_tests() -> tuple[str, ...]:
    """The tests that check the runtime: every test file that imports it (found, not listed: a
    hand-kept list had missed tests/test_p_coefficients.py, so p_coefficients' mutants looked
    untested), run with ``pytest -x``."""
    return tuple(sorted(str(p.relative_to(ROOT)) for p in (ROOT / "tests").glob("test_*.py")
                        if _IMPORTS_RUNTIME.search(p.read_text(encoding="utf-8"))))


SEED = 20261123


def runtime_functions() -> dict[str, FunctionType]:
    """``{"runtime.axisym.zeta": function}`` for every public function of ``runtime/``."""
    import chaplygin_nd.runtime as runtime

    out: dict[str, FunctionType] = {}
    for info in sorted(pkgutil.iter_modules(runtime.__path__), key=lambda i: i.name):
        mod = importlib.import_module(f"chaplygin_nd.runtime.{info.name}")
        for attr, obj in sorted(vars(mod).items()):
            if (not attr.startswith("_") and isinstance(obj, FunctionType)
                    and obj.__module__ == mod.__name__ and not obj.__code__.co_freevars):
                out[f"runtime.{info.name}.{attr}"] = obj
    return out


def functions(target: str) -> dict[str, FunctionType]:
    """The functions mutated for ``target`` (``derivations`` or ``runtime``)."""
    return derivation_functions() if target == "derivations" else runtime_functions()


@dataclass(frozen=True)
class Task:
    target: str
    mutant: mu.Mutant
    rows: tuple  # derivations: ((row, signature, seconds), ...); runtime: ()
    emitted: frozenset = frozenset()  # the emitted derivations (their kernels are compared too)


def sample(target: str, size: int | None, seed: int = SEED) -> list[mu.Mutant]:
    """Every mutant of every function of ``target`` (source order), or ``size`` of them drawn with
    ``seed``."""
    every = [m for key, fn in functions(target).items() for m, _ in mu.all_mutants(key, fn)]
    if size is None or size >= len(every):
        return every
    return sorted(random.Random(f"{seed}:{target}").sample(every, size),
                  key=lambda m: (m.function, m.index))


def clear_caches() -> None:
    """``cache_clear()`` every ``functools`` cache of the package's loaded modules."""
    for name, mod in list(sys.modules.items()):
        if name.startswith("chaplygin_nd.") and mod is not None:
            for obj in list(vars(mod).values()):
                if callable(getattr(obj, "cache_clear", None)) and hasattr(obj, "cache_info"):
                    obj.cache_clear()


def _run_tests(files) -> tuple[bool, str]:
    """Run ``files`` with ``pytest -x`` in this process, with empty caches: the compiled heyoka
    objects and evidence live in memory and on disk keyed by the source files' hashes, which an
    in-memory mutant does not change, so a warm cache would hand the tests the original's
    objects (a mutant of ``runtime.expressions`` then looked untested)."""
    import contextlib
    import io
    import os
    import tempfile

    import pytest
    from chaplygin_nd.runtime import jit_cache

    from chaplygin_nd.cache import ENV

    buffer = io.StringIO()
    saved = os.environ.get(ENV)
    with tempfile.TemporaryDirectory(prefix="chaplygin-mutant-") as empty:
        os.environ[ENV] = empty
        jit_cache.forget_memory()
        try:
            with contextlib.redirect_stdout(buffer), contextlib.redirect_stderr(buffer):
                code = pytest.main(["-q", "-x", "-p", "no:cacheprovider", "--no-header", *files])
        finally:
            jit_cache.forget_memory()
            if saved is None:
                os.environ.pop(ENV, None)
            else:
                os.environ[ENV] = saved
    lines = [ln for ln in buffer.getvalue().splitlines() if ln.startswith(("FAILED", "ERROR"))]
    return code == 0, (lines[0] if lines else f"pytest exit {code}")[:200]


def _bitwise_equal(x, y) -> bool:
    import numpy as np

    if isinstance(x, (tuple, list)) and isinstance(y, (tuple, list)):
        return len(x) == len(y) and all(_bitwise_equal(u, v) for u, v in zip(x, y))
    try:
        xa, ya = np.asarray(x), np.asarray(y)
    except Exception:  # noqa: BLE001 - not array-like: compare as objects
        return x is y or x == y
    if xa.dtype == object or ya.dtype == object:
        return str(x) == str(y)  # e.g. heyoka expressions: the same expression text
    return xa.shape == ya.shape and xa.dtype == ya.dtype and np.array_equal(xa, ya, equal_nan=True)


def _runtime_equivalence(fn, mutant_code) -> tuple[bool, int]:
    """Run the runtime tests once with both versions computed at every call of ``fn``: (all
    outputs bit-for-bit equal, number of calls). The original's output is what the tests see."""
    orig = FunctionType(fn.__code__, fn.__globals__, fn.__name__, fn.__defaults__)
    orig.__kwdefaults__ = fn.__kwdefaults__
    mut = FunctionType(mutant_code, fn.__globals__, fn.__name__, fn.__defaults__)
    mut.__kwdefaults__ = fn.__kwdefaults__
    state: dict[str, Any] = {"calls": 0, "same": True}

    def hook(*args, **kwargs):
        want = orig(*args, **kwargs)
        state["calls"] += 1
        try:
            got = mut(*args, **kwargs)
            state["same"] = state["same"] and _bitwise_equal(want, got)
        except Exception:  # noqa: BLE001 - raises where the original does not
            state["same"] = False
        return want

    name = "__mutate_runtime_hook__"
    src = f"def {fn.__name__}(*args, **kwargs):\n    return {name}(*args, **kwargs)\n"
    ns: dict = {}
    exec(compile(src, "<runtime compare>", "exec"), ns)  # noqa: S102 - fixed template
    original = fn.__code__
    fn.__globals__[name] = hook
    fn.__code__ = ns[fn.__name__].__code__
    try:
        _run_tests(runtime_tests())
    finally:
        fn.__code__ = original
        fn.__globals__.pop(name, None)
    return bool(state["same"]) and state["calls"] > 0, state["calls"]


def evaluate(task: Task) -> dict:
    """Decide one mutant in this process: apply it, run its rows (or tests), restore."""
    fn = functions(task.target)[task.mutant.function]
    original = fn.__code__
    m = task.mutant
    record = {"target": task.target, "function": m.function, "index": m.index,
              "mutation": f"{m.operator}: {m.description}", "row": None, "outcome": "",
              "reason": ""}
    start = time.perf_counter()
    try:
        code = mu.compile_mutant(fn, m)
    except Exception as err:  # noqa: BLE001 - a mutant that does not compile is not a test
        record.update(outcome="killed", reason=f"does not compile: {type(err).__name__}")
        return record
    try:
        clear_caches()
        if task.target == "runtime":
            fn.__code__ = code
            try:
                passed, note = _run_tests(runtime_tests())
            finally:
                fn.__code__ = original
            if not passed:
                record.update(outcome="killed", row="tests", reason=note)
                return record
            same, calls = _runtime_equivalence(fn, code)
            record.update(row="tests", **(
                {"outcome": "equivalent", "reason": f"every runtime test passed and the mutant's "
                 f"outputs are bit-for-bit the original's at all {calls} calls the tests make"}
                if same else {"outcome": "survived", "reason": f"every runtime test passed; "
                              f"outputs differ or no call was made ({calls} calls)"}))
            return record
        if not task.rows:
            record.update(outcome="survived", reason="no ledger row reaches this derivation")
            return record
        tried = []
        for claim_id, base, seconds in task.rows:
            fn.__code__ = code
            try:
                got, note = mu.run_row(claim_id, max(mu.MIN_BUDGET, mu.BUDGET_FACTOR * seconds))
            finally:
                fn.__code__ = original
                clear_caches()
            tried.append(claim_id)
            if got != base:
                record.update(outcome="killed", row=claim_id,
                              reason=note or mu._difference(base, got))
                return record
        if task.mutant.function in task.emitted:
            fn.__code__ = code
            try:
                from chaplygin_nd.symbolic.codegen import stale_report

                stale = stale_report()
            finally:
                fn.__code__ = original
                clear_caches()
            if stale:
                record.update(outcome="killed", row="generated/",
                              reason="no row changed, but the regenerated kernels differ: make "
                                     "verify's stale check of generated/ fails")
                return record
        return mu.settle(record, fn, code, task.rows, tried)
    except Exception:  # noqa: BLE001
        record.update(outcome="error", reason=traceback.format_exc(limit=3))
        return record
    finally:
        fn.__code__ = original
        clear_caches()
        record["seconds"] = round(time.perf_counter() - start, 2)


def plan(target: str, selection: list[mu.Mutant], jobs: int) -> list[Task]:
    """Tasks for ``selection``: for derivations, the reaching rows (cheapest first, capped) with
    their unmutated signatures (one baseline run of just those rows)."""
    if target == "runtime":
        return [Task(target, m, ()) for m in selection]
    derived, emitted = load_derived()
    _, seconds = mu_load_seconds()
    by_function: dict[str, list[str]] = {}
    for row, fs in derived.items():
        for f in fs:
            by_function.setdefault(f, []).append(row)
    chosen: dict[str, list[str]] = {}
    for m in selection:
        chosen[m.function] = sorted(by_function.get(m.function, []),
                                    key=lambda r: (seconds.get(r, 99), r))
    needed = sorted({r for rows in chosen.values() for r in rows})
    base = mu.baseline(needed, jobs=jobs) if needed else {}
    return [Task(target, m, tuple((r, base[r][0], base[r][1]) for r in chosen[m.function]),
                 frozenset(emitted)) for m in selection]


def mu_load_seconds():
    from chaplygin_nd.ledger.reach import load

    return load()


def _init_worker():
    from chaplygin_nd.ledger.catalog import discover

    discover()


def summary(records: list[dict], target: str, seconds: float) -> str:
    count = {k: sum(r["outcome"] == k for r in records)
             for k in ("killed", "equivalent", "survived", "error")}
    return (f"{target}: {len(records)} mutants of {len({r['function'] for r in records})} functions: "
            f"{count['killed']} killed, {count['equivalent']} equivalent, {count['survived']} "
            f"survived, {count['error']} errors; {seconds:.0f} s")


def main(argv: list[str] | None = None) -> int:
    parser = OneLineParser(prog="python -m chaplygin_nd.ledger.mutate_derivations",
                           description=__doc__.splitlines()[0])
    parser.add_argument("--target", choices=("derivations", "runtime"), action="append",
                        help="what to mutate (default: both)")
    parser.add_argument("--sample", type=int, default=None,
                        help="draw this many mutants per target (seeded); default: all")
    parser.add_argument("--seed", type=int, default=SEED)
    parser.add_argument("--function", action="append", default=[],
                        help="only these functions (e.g. reduced.horizontal_blocks; --list lists them)")
    parser.add_argument("--list", action="store_true",
                        help="list the functions of the targets (the names --function takes) and exit")
    parser.add_argument("--rerun", type=path_argument, default=None,
                        help="re-run only the survivors and errors recorded in this JSON file")
    parser.add_argument("--jobs", "-j", type=int, default=2)
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
    if args.out is not None and (args.out.exists() or args.out.is_symlink()) and (
            args.out.is_symlink() or isinstance(mu.compared_outcomes(args.out), str)):
        return fail(f"--out {args.out}: exists and is not a mutation JSON this program wrote; give "
                    "a new file name (nothing else is replaced)")
    args.out = args.out or OUT_PATH
    start = time.perf_counter()
    _init_worker()
    records, lines = [], []
    for target in args.target or ["derivations", "runtime"]:
        selection = [m for m in sample(target, None if args.function else args.sample, args.seed)
                     if not args.function or m.function in args.function]
        if args.rerun:
            import json

            again = {(r["function"], r["mutation"]) for r in json.loads(args.rerun.read_text())[
                "mutants"] if r["outcome"] in ("survived", "error") and r["target"] == target}
            selection = [m for m in sample(target, None, args.seed)
                         if (m.function, f"{m.operator}: {m.description}") in again]
        tasks = plan(target, selection, args.jobs)
        print(f"{target}: {len(tasks)} mutants to run", flush=True)
        t0 = time.perf_counter()
        with processes.pool(args.jobs, mp.get_context("fork"), _init_worker) as pool:
            for rec in pool.map(evaluate, tasks):
                records.append(rec)
                if rec["outcome"] != "killed":
                    print(f"  {rec['outcome']:<10} {rec['function']:<40} {rec['mutation']}  "
                          f"[{rec['row']}] {rec['reason'][:160]}", flush=True)
        lines.append(summary([r for r in records if r["target"] == target], target,
                             time.perf_counter() - t0))
        print(lines[-1], flush=True)
    write_json_atomic({"summary": lines, "seed": args.seed, "sample": args.sample,
                       "seconds": round(time.perf_counter() - start), "mutants": records}, args.out)
    print(f"wrote {args.out}")
    bad = [r for r in records if r["outcome"] in ("survived", "error")]
    for r in bad:
        print(f"PROBLEM: {r['function']} {r['mutation']}: {r['outcome']}", file=sys.stderr)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
