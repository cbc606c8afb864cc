r"""``chaplygin mutate`` (``make mutate``) — mutation testing of every printed formula.

A transcription in :mod:`symbolic.printed` is only useful if a ledger row notices when it is
wrong. For every public function there (:func:`ledger.reach.printed_functions`) this tool makes
one-symbol mutants from the function's AST (:func:`.operators.mutants`: sign, const, swap,
exponent, factor; at most four per function, one of each kind first).

Each mutant is applied in a worker process by replacing the function's ``__code__`` (every caller
sees it; source files are never written), the rows that reach the function (the reach map of
:mod:`ledger.reach`, cheapest first) are run, and each row's verdict, counterexample and parts
are compared with the unmutated run. Outcomes:

* ``killed``     — a row's verdict or counterexample changed (or the row raised, or it ran past
  its time budget: that is said in the reason);
* ``equivalent`` — no row changed *and* the mutant returns exactly the original value (exact
  SymPy comparison) at every call the cheapest reaching row makes, e.g. a swap inside a
  symmetric term; the reason says so and how many calls were compared;
* ``survived``   — no row changed although the mutant's value differs: the transcription is not
  really checked. The run exits 1.

Writes ``mutation.json`` (``{"mutants": [{"function", "row", "mutation", "outcome", "reason"},
...]}``) atomically at the repository root and prints one summary line.

``--engines flint`` makes SymPy abstain from every exact zero test (FLINT alone decides them,
:mod:`symbolic.exact.flint_engine`) and writes ``mutation-flint.json``; ``--compare mutation.json``
lists the mutants whose outcome differs from the two-engine run; ``--sample K`` runs a seeded
sample of K mutants.
"""

from __future__ import annotations

import argparse
import multiprocessing as mp
import os
import random
import sys
import time
import traceback
from typing import Any

from chaplygin_nd.ledger.catalog import ROOT, is_checkout
from chaplygin_nd.ledger.mutation.checks import (
    BUDGET_FACTOR,
    MIN_BUDGET,
    baseline,
    difference,
    init_worker,
    run_row,
)
from chaplygin_nd.ledger.mutation.equivalence import settle
from chaplygin_nd.ledger.mutation.operators import PER_FUNCTION, Mutant, compile_mutant, mutants
from chaplygin_nd.ledger.mutation.options import foreign_out, unknown_functions, unwritable_out
from chaplygin_nd.ledger.mutation.record import compared_outcomes, plural
from chaplygin_nd.ledger.mutation.replay import mutated_position
from chaplygin_nd.ledger.phase import Phase
from chaplygin_nd.ledger.reach import (
    kept_seconds,
    printed_functions,
    rows_by_function,
    unreached,
    write_json_atomic,
)
from chaplygin_nd.ledger.reach import load as load_reach
from chaplygin_nd.ledger.reach import save as save_reach
from chaplygin_nd.symbolic.exact.flint_engine import ENGINES_ENV, active_engines, engine_label

from chaplygin_nd import processes
from chaplygin_nd.console import OneLineParser, fail, path_argument, positive_int, say

OUT_PATH = ROOT / "mutation.json"
#: Rows tried per mutant: cheapest first, until the summed unmutated time passes this (s).
ROW_TIME_CAP = 90.0
#: ``--sample``: draw among mutants whose reaching rows took less than this in the saved reach map
SAMPLE_ROW_SECONDS = 8.0


def evaluate(task: tuple[Mutant, list[tuple[str, tuple, float]]]) -> dict:
    """Decide one mutant (in a worker): apply it, run its rows, compare, restore."""
    mutant, rows = task
    fn = printed_functions()[mutant.function]
    original = fn.__code__
    record: dict[str, Any] = {"function": mutant.function, "mutation": f"{mutant.operator}: {mutant.description}",
              "row": None, "outcome": "", "reason": ""}
    try:
        code = compile_mutant(fn, mutant)
    except Exception as err:  # noqa: BLE001 - e.g. a swap producing an undefined name
        record.update(outcome="killed", row=rows[0][0] if rows else None,
                      reason=f"the mutant does not compile/define: {type(err).__name__}: {err}")
        return record
    tried = []
    start = time.perf_counter()
    try:
        for claim_id, base, seconds in rows:
            budget = max(MIN_BUDGET, BUDGET_FACTOR * seconds)
            fn.__code__ = code
            try:
                got, note = run_row(claim_id, budget, base)
            finally:
                fn.__code__ = original
            tried.append(claim_id)
            if got != base:
                why = note or difference(base, got)
                record.update(outcome="killed", row=claim_id, reason=why)
                return record
        return settle(record, fn, code, rows, tried, mutant.function,
                      mutated_position(mutant.description))
    except Exception:  # noqa: BLE001
        record.update(outcome="error", reason=traceback.format_exc(limit=3))
        return record
    finally:
        fn.__code__ = original
        record["seconds"] = round(time.perf_counter() - start, 2)


def plan(base: dict, selection: list[Mutant]) -> list[tuple[Mutant, list]]:
    """Each mutant with the rows reaching its function, cheapest first, capped by ROW_TIME_CAP."""
    reach = rows_by_function({row: info[2] for row, info in base.items()})
    tasks = []
    for m in selection:
        rows = sorted(reach.get(m.function, []), key=lambda r: base[r][1])
        chosen: list = []
        total = 0.0
        for r in rows:
            if chosen and total + base[r][1] > ROW_TIME_CAP:
                break
            chosen.append((r, base[r][0], base[r][1]))
            total += base[r][1]
        if chosen:
            tasks.append((m, chosen))
    return tasks


def run_mutants(tasks, jobs: int = 2, on_record=lambda r: None) -> list[dict]:
    """Evaluate ``tasks`` in ``jobs`` forked worker processes (ordered output)."""
    if jobs <= 1:
        out = []
        for t in tasks:
            out.append(evaluate(t))
            on_record(out[-1])
        return out
    ctx = mp.get_context("fork")
    with processes.pool(jobs, ctx, init_worker) as pool:
        out = []
        for rec in pool.map(evaluate, tasks):
            out.append(rec)
            on_record(rec)
        return out


def select_all(per_function: int = PER_FUNCTION) -> list[Mutant]:
    """At most ``per_function`` mutants of every printed function (:func:`.operators.mutants`)."""
    return [m for key, fn in printed_functions().items() for m in mutants(key, fn, per_function)]


def summary(records: list[dict], functions: int, seconds: float) -> str:
    """The one summary line of a ``chaplygin mutate`` run (outcomes, score, seconds)."""
    count = {k: sum(r["outcome"] == k for r in records)
             for k in ("killed", "equivalent", "survived", "error")}
    raised = sum(r["outcome"] == "killed" and r["reason"].startswith(("raised", "row error",
                                                                         "the mutant does not"))
                 for r in records)
    covered = len({r["function"] for r in records})
    return (f"{len(records)} mutants of {covered}/{functions} printed functions: "
            f"{count['killed']} killed ({raised} of them because a row raised or timed out), "
            f"{count['equivalent']} equivalent, {count['survived']} "
            f"survived, {count['error']} errors; score {count['killed']}/"
            f"{len(records) - count['equivalent']} non-equivalent killed; {seconds:.0f} s")


def _compare(records: list[dict], theirs: dict[tuple[str, str], str]) -> list[str]:
    """Mutants run in both ``records`` and ``theirs`` (:func:`compared_outcomes`) whose outcome
    differs."""
    return [f"{r['function']} {r['mutation']}: {theirs[(r['function'], r['mutation'])]} there, "
            f"{r['outcome']} here" for r in records
            if (r["function"], r["mutation"]) in theirs
            and theirs[(r["function"], r["mutation"])] != r["outcome"]]


def _parser() -> OneLineParser:
    parser = OneLineParser(prog="chaplygin mutate", description=(
        "Mutation testing of every printed formula: one-symbol mutants, each run against the "
        "ledger rows that reach it; writes mutation.json (make mutate)."))
    parser.add_argument("--jobs", "-j", type=positive_int, default=2)
    parser.add_argument("--per-function", type=positive_int, default=PER_FUNCTION)
    parser.add_argument("--function", action="append", default=[],
                        help="only these printed functions (e.g. section4.K; --list lists them)")
    parser.add_argument("--list", action="store_true",
                        help="list the printed functions (the names --function takes) and exit")
    parser.add_argument("--out", type=path_argument, default=None,
                        help="where to write (default mutation.json; mutation-flint.json with "
                             "--engines flint)")
    parser.add_argument("--engines", choices=("both", "flint"), default="both",
                        help="who decides the exact zero tests: SymPy and FLINT (default), or "
                             "FLINT alone (SymPy abstains: CHAPLYGIN_ND_ENGINES=flint)")
    parser.add_argument("--sample", type=int, default=0,
                        help="run a seeded sample of this many mutants among those whose rows "
                             f"are cheap (< {SAMPLE_ROW_SECONDS:.0f} s in ledger/reach.json), "
                             "with a baseline of those rows only (0: all)")
    parser.add_argument("--compare", type=path_argument, default=None,
                        help="a mutation.json of another run: report mutants whose outcome differs")
    return parser


def _refusal(args: argparse.Namespace) -> str | None:
    """The one-line error that stops ``chaplygin mutate`` before anything runs, or None."""
    problem = unknown_functions(args.function, printed_functions(), "chaplygin mutate --list")
    if args.sample < 0:
        problem = f"--sample: {args.sample} is negative; give a number of mutants (0: all)"
    if problem:
        return problem
    if args.compare and isinstance(theirs := compared_outcomes(args.compare), str):
        return theirs
    if args.out is None and not is_checkout():
        return "chaplygin mutate: give --out FILE (an installed package is never written into)"
    partial = [o for o, given in (("--function", args.function), ("--sample", args.sample)) if given]
    if args.out is None and partial:  # the checked-in record is a whole run
        return (f"chaplygin mutate: with {' '.join(partial)} give --out FILE: a partial run "
                "would replace the record of the full run, mutation.json")
    return foreign_out(args.out, "a mutation.json") or unwritable_out(
        args.out or (OUT_PATH if args.engines == "both" else ROOT / "mutation-flint.json"))


def _sample(args: argparse.Namespace) -> tuple[list[Mutant], list[str]]:
    """``--sample``: a seeded draw among the mutants whose rows (in the saved reach map) are
    cheap, and the rows that reach them."""
    saved_rows, saved_seconds = load_reach()
    by_function = rows_by_function(saved_rows)
    cheap = [m for m in select_all(args.per_function)
             if (not args.function or m.function in args.function) and by_function.get(m.function)
             and sum(saved_seconds.get(r, 99.0) for r in by_function[m.function]) < SAMPLE_ROW_SECONDS]
    chosen = random.Random(20261123).sample(cheap, min(args.sample, len(cheap)))
    return chosen, sorted({r for m in chosen for r in by_function[m.function]})


def _show(rec: dict) -> None:
    if rec["outcome"] != "killed":
        print(f"  {rec['outcome']:<10} {rec['function']:<32} {rec['mutation']}  "
              f"[{rec['row']}] {rec['reason'][:160]}", flush=True)


def _problems(args: argparse.Namespace, records: list[dict], missing: list[str]) -> list[str]:
    """What makes the run fail: unreached printed functions, survivors and errors, and (a whole
    run) printed functions without a mutant."""
    problems = [f"printed function {f} is reached by no ledger row" for f in missing]
    problems += [f"{r['function']} {r['mutation']}: {r['outcome']}" for r in records
                 if r["outcome"] in ("survived", "error")]
    if not args.function and not args.sample:
        covered = {r["function"] for r in records}
        problems += [f"printed function {f} has no mutant" for f in printed_functions()
                     if f not in covered]
    return problems


def _write(args: argparse.Namespace, records: list[dict], selection: list, seconds: float) -> None:
    """Write ``--out`` and print the summary line (and, with ``--compare``, what differs)."""
    line = summary(records, len(printed_functions()), seconds)
    line = f"engines {engine_label(active_engines())}: {line}"
    if args.sample:
        line += f" (seeded sample of {len(selection)} mutants)"
    theirs = compared_outcomes(args.compare) if args.compare else {}
    differ = _compare(records, theirs) if isinstance(theirs, dict) else []
    write_json_atomic({"summary": line, "engines": args.engines, "mutants": records,
                       "differs_from_compared": differ}, args.out)
    print(line)
    if args.compare:
        print(f"compared with {args.compare}: {len(differ)} mutants with another outcome")
        for d in differ:
            print(f"  {d}")
    print(f"wrote {args.out}")


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    if args.list:
        say("\n".join(printed_functions()))
        return 0
    problem = _refusal(args)
    if problem:
        return fail(problem)
    os.environ[ENGINES_ENV] = args.engines
    if args.out is None:
        args.out = OUT_PATH if args.engines == "both" else ROOT / "mutation-flint.json"
    start = time.perf_counter()
    from chaplygin_nd.ledger.catalog import discover

    discover()
    listing = Phase(f"listing the mutants of {len(printed_functions())} printed functions")
    chosen: list[Mutant] = []
    sample_rows = None
    if args.sample:  # a seeded sample among mutants whose rows (saved reach map) are cheap
        listing.start()
        chosen, sample_rows = _sample(args)
    base = baseline(sample_rows, jobs=args.jobs, phase=Phase(
        f"baseline: running the {'rows of the sample' if sample_rows else 'ledger rows'} unmutated "
        f"({plural(args.jobs, 'job')}; it finds which rows reach each printed function)",
        what="rows done").start())
    reach = {row: info[2] for row, info in base.items()}
    missing = unreached(reach) if not args.sample else []
    if not args.function and args.engines == "both" and not args.sample and is_checkout():
        save_reach(reach, kept_seconds({row: info[1] for row, info in base.items()}))
    if args.sample:
        selection = chosen
    else:
        listing.start()
        selection = [m for m in select_all(args.per_function)
                     if not args.function or m.function in args.function]
    tasks = plan(base, selection)
    print(f"baseline: {len(base)} rows in {time.perf_counter() - start:.0f} s; "
          f"{len(tasks)} mutants to run", flush=True)
    records = run_mutants(tasks, jobs=args.jobs, on_record=_show)
    _write(args, records, selection, time.perf_counter() - start)
    problems = _problems(args, records, missing)
    for p in problems:
        print(f"PROBLEM: {p}", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
