"""``chaplygin verify`` / ``chaplygin prove ID ...`` (``python -m chaplygin_nd.ledger``) — decide ledger rows and print one line per row.

With no ids it runs the whole ledger and writes ``VERIFICATION.md``, ``verification.json`` (at the
repository root) and the claim graph ``docs/claim-graph.svg`` — or, with ``--report-dir DIR``, all
three into ``DIR`` (for an installed package or a read-only checkout; an installed package writes
nothing without it). The two reports are one result (:func:`ledger.report.write_pair`) and name the
run (seed, commit, time, generation id). Ids are checked before any proof is imported (blanks
stripped, "did you mean" for near misses). Ctrl-C or SIGTERM: one line ``interrupted``, exit 130 (the
``chaplygin`` program exits 143 for SIGTERM); a
closed stdout (``| head -1``) does not stop the run. ``--seed N`` is the seed of every
seeded check (recorded in both reports). Exit status 1 when a row fails, a proof raises, an open row
gives no reason, a finding has no kind, a proof registers an id that is not a ledger row, or
(``--check-generated``) ``generated/`` is stale — then the report says STALE at its top; 2 on a
usage error or a report that cannot be written (one line naming the path). With ids named
(``chaplygin prove``) no report is written: ``--report-dir`` is then refused (a partial report must
never stand in for the whole ledger's).
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import time
import uuid
from collections.abc import Callable
from datetime import UTC, datetime
from pathlib import Path
from typing import cast

from chaplygin_nd.ledger import graph, report
from chaplygin_nd.ledger.catalog import ROOT, is_checkout, resolve
from chaplygin_nd.ledger.runner import run, select, unknown_registrations
from chaplygin_nd.symbolic.exact.points import DEFAULT_SEED

from chaplygin_nd.cli import commit, version_line
from chaplygin_nd.console import (
    OneLineParser,
    fail,
    interruptible,
    path_argument,
    positive_int,
    say,
)
from chaplygin_nd.writing import folder_problem

#: command -> its one-line description (``-h``).
_DESCRIPTIONS = {
    "verify": "Decide every ledger row, print one line per row and write VERIFICATION.md, "
              "verification.json and the claim graph.",
    "prove": "Decide the ledger rows named and print one line per row (no report is written: "
             "`chaplygin verify` writes the reports of the whole ledger).",
    "python -m chaplygin_nd.ledger": "Decide the ledger rows named, or every row and write the "
                                      "reports (`chaplygin prove` / `chaplygin verify`).",
}


def _seed(text: str) -> int:
    try:
        value = int(text.strip())
    except ValueError:
        value = -1
    if value < 0:
        raise argparse.ArgumentTypeError(f"not a non-negative integer: {text!r}")
    return value


def main(argv: list[str] | None = None) -> int:
    """Run ``chaplygin verify`` (and ``python -m chaplygin_nd.ledger [ID ...]``); the exit status
    (module docstring)."""
    return _entry(argv, "verify")


def prove(argv: list[str] | None = None) -> int:
    """Run ``chaplygin prove ID [ID ...]``; the exit status (module docstring)."""
    return _entry(argv, "prove")


def _entry(argv: list[str] | None, command: str) -> int:
    with interruptible():
        try:
            return _main(argv, command)
        except KeyboardInterrupt:
            return fail("interrupted", 130)


def _parser(command: str) -> OneLineParser:
    """The options of ``chaplygin verify`` / ``prove``."""
    prog = command if command.startswith("python") else f"chaplygin {command}"
    parser = OneLineParser(prog=prog, description=_DESCRIPTIONS[command])
    parser.add_argument("ids", nargs="*", metavar="ID", help={
        "prove": "ledger ids to decide (--list lists them)",
        "verify": argparse.SUPPRESS}.get(command, "ledger ids to run (default: all)"))
    parser.add_argument("--version", action="version", version=version_line())
    parser.add_argument("--jobs", "-j", type=positive_int, default=None,
                        help="worker processes (default: one per core)")
    parser.add_argument("--check-generated", action="store_true",
                        help="also regenerate generated/ into a temporary folder and fail on a difference")
    parser.add_argument("--seed", type=_seed, default=DEFAULT_SEED,
                        help=f"seed of every seeded exact check (default {DEFAULT_SEED})")
    parser.add_argument("--report-dir", metavar="DIR", type=path_argument,
                        help=argparse.SUPPRESS if command == "prove" else
                        "write VERIFICATION.md, verification.json and claim-graph.svg into DIR "
                        "(default: the checkout's root and docs/; an installed package writes "
                        "them only when DIR is given)")
    parser.add_argument("--list", action="store_true", help="list the ledger ids and exit")
    return parser


def _main(argv: list[str] | None, command: str) -> int:
    parser = _parser(command)
    args = parser.parse_args(argv)

    try:
        ids = resolve(args.ids) if args.ids else []  # before any proof is imported
        rows = select(ids)
    except KeyError as err:
        return fail(err.args[0])
    if args.list:
        for row in rows:
            say(f"{row.id:<24} {row.section}")
        return 0
    targets = _report_paths(args.report_dir, whole=not ids)
    if isinstance(targets, int):
        return targets

    start = time.perf_counter()
    info = report.RunInfo(args.seed, commit=commit(), generation=uuid.uuid4().hex[:12],
                          started=datetime.now(UTC).strftime("%Y-%m-%dT%H:%M:%SZ"))
    say(f"seed {args.seed}")
    say(f"{'id':<24} {'verdict':<20} {'seconds':>8}  method [n]")
    regenerated: list[tuple[str, list[str]]] = []
    also: Callable[..., object] | None = None
    if args.check_generated:
        from chaplygin_nd.ledger.reach import regenerated_and_emitted

        also = regenerated_and_emitted
    if targets:
        graph.import_beside()
    results = run(rows, jobs=args.jobs, seed=args.seed, on_result=lambda r: say(report.line(r)),
                  also=also, on_also=lambda value: regenerated.append(cast("tuple[str, list[str]]", value)))
    # regenerated beside the rows (runner.run's ``also``): the stale text and the derivations
    # the kernels of generated/ call
    problems = _problems(results, whole=not args.ids,
                         emitted=regenerated[0][1] if regenerated else None)
    generated = "not checked"
    if args.check_generated:
        stale = regenerated[0][0]
        generated = "STALE" if stale else "up to date"
        if stale:
            problems.append(stale)
        else:
            say("generated/ is up to date with symbolic/ (regenerated and compared byte for byte)")
    say(report.summary(results) + f"; wall {time.perf_counter() - start:.1f} s")
    if targets is None:
        say("not a source checkout: VERIFICATION.md, verification.json and the graph not written "
            "(give --report-dir DIR)")
    elif targets:
        md, js, svg = targets
        info = dataclasses.replace(info, generated=generated, problems=tuple(problems),
                                   graph=svg.relative_to(md.parent).as_posix())
        try:
            text = graph.render(results)
            changed = not svg.exists() or svg.read_text(encoding="utf-8") != text
            report.write_pair(results, md, js, info, {svg: text} if changed else None)
        except OSError as exc:
            return fail(f"writing the report {exc.filename}: {exc.strerror or exc} "
                        "(give --report-dir DIR for a writable folder)")
        say(f"wrote {md}, {js} and {svg} (run {info.names()})"
            + (f" ({svg.name} changed: commit it)" if changed and args.report_dir is None else ""))
    for p in problems:
        fail(f"PROBLEM: {p}", 1)
    return 1 if problems else 0


def _problems(results, whole: bool, emitted: list[str] | None = None) -> list[str]:
    """What makes the run fail: a proof that raised, a ``fails`` row, an ``open`` row without a
    reason, a finding without a kind, a proof registering an id that is no row; on a ``whole``
    run also a printed formula or an emitted derivation that no row reaches (DESIGN rule 1;
    ``emitted``: the emitted derivations when already recorded, else recorded here)."""
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
    if whole:  # every printed formula must be checked by some row (DESIGN rule 1)
        from chaplygin_nd.ledger.reach import unreached, unreached_emitted

        missing = unreached({r.row.id: list(r.printed) for r in results})
        problems += [f"printed function {f} is reached by no ledger row" for f in missing]
        # every derivation emitted into generated/ must be checked by some row
        problems += [f"derivation {f} is emitted into generated/ but reached by no ledger row"
                     for f in unreached_emitted({r.row.id: list(r.derived) for r in results},
                                                emitted)]
    unknown = unknown_registrations()
    problems += [f"{i}: registered by a proof but not a ledger row" for i in unknown]
    return problems


def _report_paths(report_dir: str | Path | None, whole: bool):
    """(VERIFICATION.md, verification.json, graph) paths; ``()`` when ids were named (no report),
    ``None`` outside a checkout without ``--report-dir``; an exit status when ``--report-dir``
    cannot be a folder or is given with ids (checked before any proof runs)."""
    if not whole:
        if report_dir is not None:
            return fail(f"--report-dir {report_dir}: the reports are written for the whole ledger "
                        "only, and ids were named; drop --report-dir (`chaplygin prove` writes no "
                        "report) or run `chaplygin verify --report-dir DIR`")
        return ()
    if report_dir is None:
        if not is_checkout():
            return None
        return ROOT / "VERIFICATION.md", ROOT / "verification.json", ROOT / report.GRAPH_PATH
    folder = Path(report_dir)
    # created only when the reports are written (an interrupted run leaves no empty folder); here
    # it is created with a file in it and removed again (os.access says yes to root on /proc)
    problem = folder_problem(folder)
    if problem:
        return fail(f"--report-dir {report_dir}: {problem}")
    targets = folder / "VERIFICATION.md", folder / "verification.json", folder / "claim-graph.svg"
    foreign = _foreign_reports(*targets)
    if foreign:
        return fail(f"--report-dir {report_dir}: {', '.join(foreign)} "
                    f"{'was' if len(foreign) == 1 else 'were'} not written by `chaplygin verify` "
                    "and would be replaced; give a new or empty folder, or one an earlier "
                    "`chaplygin verify --report-dir` wrote")
    return targets


def _foreign_reports(markdown: Path, json_path: Path, svg: Path) -> list[str]:
    """The names of the report files in a ``--report-dir`` folder that exist but were not written
    by ``chaplygin verify`` (so must not be replaced): VERIFICATION.md is ours when it starts with
    the report's heading, verification.json when it is a JSON object with the report's
    ``generation`` and ``rows``, the graph when it is a file beside our verification.json."""
    import json

    def read(path: Path) -> str | None:
        try:
            return path.read_text(encoding="utf-8") if path.is_file() else None
        except (OSError, UnicodeDecodeError):
            return None

    def ours_json() -> bool:
        try:
            data = json.loads(read(json_path) or "null")
        except ValueError:
            return False
        return isinstance(data, dict) and {"generation", "rows"} <= data.keys()

    ours = {markdown: lambda: (read(markdown) or "").startswith(report.HEADING),
            json_path: ours_json,
            svg: lambda: svg.is_file() and ours_json()}
    return [path.name for path, check in ours.items()
            if (path.exists() or path.is_symlink()) and (path.is_symlink() or not check())]


if __name__ == "__main__":
    sys.exit(_entry(None, "python -m chaplygin_nd.ledger"))
