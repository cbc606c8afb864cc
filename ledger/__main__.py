"""``chaplygin verify`` / ``chaplygin prove ID ...`` (``python -m chaplygin_nd.ledger``) — decide ledger rows and print one line per row.

With no ids it runs the whole ledger and writes ``VERIFICATION.md``, ``verification.json`` (at the
repository root) and the claim graph ``docs/claim-graph.svg`` (only in a source checkout: an installed
package does not write into site-packages). ``--seed N`` is the seed of every
seeded check (recorded in both reports). Exit status 1 when a row fails, a proof raises, an open row
gives no reason, a finding has no kind, a proof registers an id that is not a ledger row, or
(``--check-generated``) ``generated/`` is stale — then the report says STALE at its top.
"""

from __future__ import annotations

import argparse
import signal
import sys
import time

from chaplygin_nd.ledger import graph, report
from chaplygin_nd.ledger.catalog import ROOT, is_checkout
from chaplygin_nd.ledger.runner import run, select, unknown_registrations
from chaplygin_nd.symbolic.points import DEFAULT_SEED

from chaplygin_nd.cli import version_line


def _seed(text: str) -> int:
    value = int(text)
    if value < 0:
        raise argparse.ArgumentTypeError("the seed is a non-negative integer")
    return value


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="chaplygin verify", description=__doc__.splitlines()[0])
    parser.add_argument("ids", nargs="*", help="ledger ids to run (default: all)")
    parser.add_argument("--version", action="version", version=version_line())
    parser.add_argument("--jobs", "-j", type=int, default=None,
                        help="worker processes (default: one per core)")
    parser.add_argument("--check-generated", action="store_true",
                        help="also regenerate generated/ into a temporary folder and fail on a difference")
    parser.add_argument("--seed", type=_seed, default=DEFAULT_SEED,
                        help=f"seed of every seeded exact check (default {DEFAULT_SEED})")
    parser.add_argument("--list", action="store_true", help="list the ledger ids and exit")
    args = parser.parse_args(argv)
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # `chaplygin verify | head` exits quietly

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
    print(f"seed {args.seed}", flush=True)
    print(f"{'id':<24} {'verdict':<20} {'seconds':>8}  method [n]", flush=True)
    results = run(rows, jobs=args.jobs, seed=args.seed,
                  on_result=lambda r: print(report.line(r), flush=True))
    problems = []
    for r in results:
        if r.error:
            problems.append(f"{r.row.id}: the proof raised:\n{r.error}")
        elif r.status == "fails":
            problems.append(f"{r.row.id}: fails ({r.verdict.counterexample})")
        elif r.status == "open" and not r.verdict.notes.strip():
            problems.append(f"{r.row.id}: open without a reason")
    problems += [f"{i}: a finding without a kind (formula/proof/scope/reading): an error of the "
                 "ledger" for i in report.missing_kind(results)]
    if not args.ids:  # every printed formula must be checked by some row (DESIGN rule 1)
        from chaplygin_nd.ledger.reach import unreached, unreached_emitted

        missing = unreached({r.row.id: list(r.printed) for r in results})
        problems += [f"printed function {f} is reached by no ledger row" for f in missing]
        # every derivation emitted into generated/ must be checked by some row (issue 17)
        problems += [f"derivation {f} is emitted into generated/ but reached by no ledger row"
                     for f in unreached_emitted({r.row.id: list(r.derived) for r in results})]
    unknown = unknown_registrations()
    problems += [f"{i}: registered by a proof but not a ledger row" for i in unknown]
    generated = "not checked"
    if args.check_generated:
        from chaplygin_nd.symbolic.codegen import stale_report

        stale = stale_report()
        generated = "STALE" if stale else "up to date"
        if stale:
            problems.append(stale)
        else:
            print("generated/ is up to date with symbolic/ (regenerated and compared byte for byte)")
    print(report.summary(results) + f"; wall {time.perf_counter() - start:.1f} s")
    if not args.ids and not is_checkout():
        print("not a source checkout: VERIFICATION.md, verification.json and the graph not written")
    elif not args.ids:
        info = report.RunInfo(args.seed, generated, tuple(problems))
        report.write_markdown(results, ROOT / "VERIFICATION.md", info)
        report.write_json(results, ROOT / "verification.json", info)
        changed = graph.write(results, ROOT / report.GRAPH_PATH)
        print(f"wrote VERIFICATION.md, verification.json and {report.GRAPH_PATH}"
              + (f" ({report.GRAPH_PATH} changed: commit it)" if changed else ""))
    for p in problems:
        print(f"PROBLEM: {p}", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
