r"""``chaplygin mutate-derivations`` (``make mutate-derivations``): the arguments, the checks made
before anything runs, then each target in turn (:mod:`.derivations` plans its mutants,
:mod:`.runloop` decides them, :mod:`.record` keeps them).

Mutants run in ``--jobs`` forked workers, cheapest first; ``--out`` is rewritten every 30 s
(``"complete": false``) so an interrupted run keeps what it decided, and ``--resume`` goes on from
there (records of mutants the code no longer has, or decided on another source of their function,
are dropped with one line each and decided again: :func:`.record.current`). ``--check`` says how
the record stands against the code, and runs nothing. ``--sample N`` draws ``N`` mutants per
target with a fixed seed. Writes ``mutation-derivations.json`` (or ``--out``) atomically; each
target's summary line gives its wall and CPU seconds; exit 1 on a survivor or an error. Before
the first mutant each phase (listing the mutants, the unmutated rows, the instrumented tests)
prints what it does, and the long ones their progress every 30 s (:mod:`ledger.phase`).
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time

from chaplygin_nd.ledger.catalog import is_checkout
from chaplygin_nd.ledger.mutation import record, runloop
from chaplygin_nd.ledger.mutation import runtime as mr
from chaplygin_nd.ledger.mutation.checks import init_worker
from chaplygin_nd.ledger.mutation.derivations import OUT_PATH, SEED, functions, plan, sample
from chaplygin_nd.ledger.mutation.options import foreign_out, unknown_functions, unwritable_out
from chaplygin_nd.ledger.mutation.record import plural
from chaplygin_nd.ledger.phase import Phase

from chaplygin_nd.console import OneLineParser, fail, path_argument, say

TARGETS = ("derivations", "runtime")


def _parser() -> OneLineParser:
    parser = OneLineParser(prog="chaplygin mutate-derivations", description=(
        "mutants of derivations and runtime (make mutate-derivations)"))
    parser.add_argument("--target", choices=TARGETS, action="append",
                        help="what to mutate (default: both)")
    parser.add_argument("--sample", type=int, default=None,
                        help="draw this many mutants per target (seeded); default: all")
    parser.add_argument("--seed", type=int, default=SEED,
                        help=f"the seed of --sample's draw (default {SEED})")
    parser.add_argument("--function", action="append", default=[],
                        help="only these functions (e.g. reduction.reduced_n4.horizontal_blocks; --list "
                             "lists them)")
    parser.add_argument("--list", action="store_true",
                        help="list the functions of the targets (the names --function takes) and exit")
    parser.add_argument("--rerun", type=path_argument, default=None,
                        help="re-run only the survivors and errors recorded in this JSON file")
    parser.add_argument("--resume", action="store_true",
                        help="keep the mutants already decided in --out (an interrupted run) and "
                             "run only the others")
    parser.add_argument("--check", action="store_true",
                        help="say how --out stands against the code (records of mutants it no "
                             "longer has, stale or twice; mutants undecided) and exit: 0 when "
                             "consistent, 1 otherwise")
    parser.add_argument("--again", default="survived,error", type=lambda v: tuple(v.split(",")),
                        help="with --rerun: the outcomes run again (default survived,error; add "
                             "equivalent after adding a test that may tell such mutants apart)")
    parser.add_argument("--jobs", "-j", type=int, default=2, help="worker processes (default 2)")
    parser.add_argument("--out", type=path_argument, default=None,
                        help="where to write (default mutation-derivations.json in the checkout)")
    return parser


def _refusal(args: argparse.Namespace, prog: str, known: list[str]) -> str | None:
    """The one-line error that stops the command before anything runs, or None."""
    lister = " ".join([prog, *(f"--target {t}" for t in args.target or []), "--list"])
    problem = unknown_functions(args.function, known, lister)
    if problem:
        return problem
    if args.rerun is not None:  # read before the run: a wrong file never costs a whole run
        earlier = record.compared_outcomes(args.rerun)
        if isinstance(earlier, str):
            return earlier.replace("--compare", "--rerun", 1)
    if args.out is None and not is_checkout():
        return f"{prog}: give --out FILE (an installed package is never written into)"
    partial = [o for o, given in (("--function", args.function), ("--sample", args.sample),
                                  ("--target", args.target), ("--rerun", args.rerun)) if given]
    if args.out is None and partial and not (args.resume or args.check):  # the checked-in record
        return (f"{prog}: with {' '.join(partial)} give --out FILE: a partial run would "  # is a
                f"replace the record of the full run, {OUT_PATH.name}")                  # whole run
    return foreign_out(args.out, "a mutation JSON") or unwritable_out(args.out or OUT_PATH)


def check(path, targets=TARGETS) -> int:
    """``--check``: one line per kind of inconsistency of the record at ``path`` (its functions),
    then one verdict line; 0 when the record decides every mutant of ``targets`` as the code is
    now and holds nothing else, else 1."""
    records = record.read(path)[0]
    found = record.consistency(records, targets)
    for kind, items in found.items():
        if not items:
            continue
        names = sorted({r[1] if isinstance(r, tuple) else r["function"] for r in items})
        print(f"{kind}: {plural(len(items), 'mutant' if kind == 'undecided' else 'record')} "
              f"({', '.join(names[:12])}{', ...' if len(names) > 12 else ''})")
    bad = [k for k in ("gone", "stale", "twice", "moved", "undecided") if found[k]]
    print(f"{path}: {plural(len(records), 'record')}; "
          + ("consistent with the code" if not bad else
             f"not consistent ({', '.join(bad)}): `chaplygin mutate-derivations --out {path} "
             "--resume` decides what is missing"))
    return 1 if bad else 0


def _kept(args: argparse.Namespace, targets: list[str]) -> tuple[list[dict], list[dict]]:
    """The records and runs kept from ``--resume`` (``--out``) or ``--rerun``, as they stand for
    the code now (:func:`.record.current`)."""
    records: list[dict] = []
    runs: list[dict] = []
    if args.resume:  # keep what an earlier (interrupted) run into --out decided
        records, runs = record.read(args.out)
        records = [r for r in records if r["outcome"] != "error"]
    if args.rerun:  # keep what the earlier run decided, except what is run again
        records, runs = record.read(args.rerun)
        records = [r for r in records if r["target"] not in targets or r["outcome"] not in args.again]
    return record.current(records), runs


def _selection(args: argparse.Namespace, target: str, done: set) -> list:
    """The mutants of ``target`` this run decides (drawn, named, or re-run; none already done)."""
    named = frozenset(args.function) & set(functions(target)) if args.function else None
    Phase(f"{target}: listing the mutants of "
          f"{plural(len(functions(target)) if named is None else len(named), 'function')}").start()
    selection = sample(target, None if args.function else args.sample, args.seed, only=named)
    if args.rerun:
        again = {(r["function"], r["mutation"]) for r in record.read(args.rerun)[0]
                 if r["outcome"] in args.again and r["target"] == target}
        selection = [m for m in sample(target, None, args.seed)
                     if (m.function, f"{m.operator}: {m.description}") in again]
    return [m for m in selection if (target, m.function, f"{m.operator}: {m.description}") not in done]


def _run_target(args, argv, target: str, records: list[dict], runs: list[dict]) -> str | None:
    """Plan and decide ``target``'s mutants into ``records`` (its run appended to ``runs``);
    the one-line error when planning fails, else None."""
    done = {(r["target"], r["function"], r["mutation"]) for r in records}
    selection = _selection(args, target, done)
    t0, c0 = time.perf_counter(), record.cpu_seconds()
    run = {"argv": sys.argv[1:] if argv is None else list(argv), "target": target,
           "complete": False, "load average at start": list(os.getloadavg())}
    runs.append(run)
    with tempfile.TemporaryDirectory(prefix="chaplygin-mutate-") as work:
        os.environ[mr.WORK_ENV] = work  # the workers' cache folders (mutation.runtime)
        try:
            try:
                tasks = plan(target, selection, args.jobs,
                             {m.function for m in selection} if args.rerun else ())
            except RuntimeError as err:  # e.g. a test file that does not collect, an unmutated
                return str(err)  # row that raises: nothing to compare
            print(f"{target}: {len(tasks)} mutants to run", flush=True)
            mine = runloop.run_tasks(tasks, args.jobs, records, runs, args, run, t0, c0)
        finally:
            os.environ.pop(mr.WORK_ENV, None)
    record.progress(run, len(mine), len(tasks), t0, c0)
    run["complete"] = True
    print(record.summary([r for r in records if r["target"] == target], target,
                         time.perf_counter() - t0, record.cpu_seconds() - c0, len(mine)), flush=True)
    return None


def main(argv: list[str] | None = None) -> int:
    parser = _parser()
    args = parser.parse_args(argv)
    targets = args.target or list(TARGETS)
    known = [name for target in targets for name in functions(target)]
    if args.list:
        say("\n".join(known))
        return 0
    problem = _refusal(args, parser.prog, known)
    if problem:
        return fail(problem)
    args.out = args.out or OUT_PATH
    if args.check:
        return check(args.out, targets)
    init_worker()
    records, runs = _kept(args, targets)
    for target in targets:
        problem = _run_target(args, argv, target, records, runs)
        if problem:
            return fail(f"{parser.prog}: {problem}")
    record.write(records, runs, args)
    print(f"wrote {args.out}")
    bad = [r for r in records if r["outcome"] in ("survived", "error")]
    for r in bad:
        print(f"PROBLEM: {r['function']} {r['mutation']}: {r['outcome']}", file=sys.stderr)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
