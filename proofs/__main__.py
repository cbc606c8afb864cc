"""``python -m proofs [ID ...]`` — decide ledger rows and print one line per row.

With no ids it runs the whole ledger and writes ``VERIFICATION.md`` and ``verification.json`` at
the repository root. Exit status 1 when a row fails, a proof raises, an open row gives no reason,
a proof registers an id that is not a ledger row, or (``--check-generated``) ``generated/`` is stale.
"""

from __future__ import annotations

import argparse
import signal
import sys
import time

from proofs import report
from proofs.catalog import ROOT
from proofs.runner import run, select, unknown_registrations


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m proofs", description=__doc__.splitlines()[0])
    parser.add_argument("ids", nargs="*", help="ledger ids to run (default: all)")
    parser.add_argument("--jobs", "-j", type=int, default=None,
                        help="worker processes (default: one per core)")
    parser.add_argument("--check-generated", action="store_true",
                        help="also regenerate generated/ into a temporary folder and fail on a difference")
    parser.add_argument("--list", action="store_true", help="list the ledger ids and exit")
    args = parser.parse_args(argv)
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # `python -m proofs | head` exits quietly

    try:
        rows = select(args.ids)
    except KeyError as err:
        print(f"error: {err.args[0]}", file=sys.stderr)
        return 2
    if args.list:
        for row in rows:
            print(f"{row.id:<24} {row.section}")
        return 0

    start = time.perf_counter()
    print(f"{'id':<24} {'verdict':<10} {'seconds':>8}  method [n]", flush=True)
    results = run(rows, jobs=args.jobs, on_result=lambda r: print(report.line(r), flush=True))
    problems = []
    for r in results:
        if r.error:
            problems.append(f"{r.row.id}: the proof raised:\n{r.error}")
        elif r.status == "fails":
            problems.append(f"{r.row.id}: fails ({r.verdict.counterexample})")
        elif r.status == "open" and not r.verdict.notes.strip():
            problems.append(f"{r.row.id}: open without a reason")
    if not args.ids:  # every printed formula must be checked by some row (DESIGN rule 1)
        from proofs.reach import unreached

        missing = unreached({r.row.id: list(r.printed) for r in results})
        problems += [f"printed function {f} is reached by no ledger row" for f in missing]
    unknown = unknown_registrations()
    problems += [f"{i}: registered by a proof but not a ledger row" for i in unknown]
    if args.check_generated:
        from symbolic.codegen import stale_report

        stale = stale_report()
        if stale:
            problems.append(stale)
        else:
            print("generated/ is up to date with symbolic/ (regenerated and compared byte for byte)")
    print(report.summary(results) + f"; wall {time.perf_counter() - start:.1f} s")
    if not args.ids:
        report.write_markdown(results, ROOT / "VERIFICATION.md")
        report.write_json(results, ROOT / "verification.json")
        print("wrote VERIFICATION.md and verification.json")
    for p in problems:
        print(f"PROBLEM: {p}", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
