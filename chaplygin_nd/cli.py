"""``chaplygin`` (``python -m chaplygin_nd``): one command for the whole toolkit.

``chaplygin verify``            decide every ledger row, write the reports (``make verify``)
``chaplygin prove ID [ID ...]`` decide single rows
``chaplygin simulate SCENE``    plan and run a scene (``python -m chaplygin_nd.simulate``)
``chaplygin bench [NAME ...]``  the benchmarks (``make bench``)
``chaplygin generate``          rewrite ``generated/`` from the proved formulas (``make generate``)
``chaplygin mutate``            mutation testing of the printed formulas (``make mutate``)
``chaplygin mutate-derivations`` the same for the derivations and the runtime
                                (``make mutate-derivations``)
``chaplygin docs [REPORT]``     build the reading site into docs/_build/html (``make docs-html``;
                                in a source checkout, with the ``docs`` extra installed)
``chaplygin --version``         the version and, in a source checkout, the commit

Each subcommand takes the options of the module it runs (``chaplygin simulate -h``). Subcommands
import their module only when chosen, so ``chaplygin --version`` imports neither SymPy nor NumPy.
"""

from __future__ import annotations

import errno
import importlib
import sys

from chaplygin_nd import __version__

#: Errors of the storage (full disk, quota, read-only, permissions, I/O) that a subcommand did not
#: turn into its own one-line message: :func:`main` says them in one line too, never a traceback.
STORAGE_ERRORS = frozenset({errno.ENOSPC, errno.EDQUOT, errno.EROFS, errno.EFBIG, errno.EIO,
                            errno.EACCES, errno.EPERM})

#: subcommand -> (module, its function ``f(argv) -> exit status`` that runs it, one-line help)
COMMANDS = {
    "verify": ("chaplygin_nd.ledger.__main__", "main", "decide every ledger row and write the reports"),
    "prove": ("chaplygin_nd.ledger.__main__", "prove", "decide the ledger rows named"),
    "simulate": ("chaplygin_nd.simulate.scene.cli", "main", "plan and run a scene"),
    "bench": ("chaplygin_nd.bench.__main__", "main", "run the benchmarks"),
    "generate": ("chaplygin_nd.symbolic.codegen.kernels", "main", "rewrite generated/ from the proofs"),
    "mutate": ("chaplygin_nd.ledger.mutation.printed", "main", "mutation testing of the printed formulas"),
    "mutate-derivations": ("chaplygin_nd.ledger.mutation.command", "main",
                           "mutation testing of the derivations and the runtime"),
    "first-integrals": ("chaplygin_nd.symbolic.search.command", "main",
                        "exact search for first integrals, degree by degree"),
    "poisson": ("chaplygin_nd.symbolic.search.poisson_command", "main",
                "exact search for a Hamiltonisation on P, box by box"),
    "symmetry-fields": ("chaplygin_nd.symbolic.search.fields_command", "main",
                        "exact search for commuting symmetry fields, box by box"),
    "docs": ("chaplygin_nd.cli", "docs", "build the reading site (a source checkout)"),
}


def docs(argv: list[str]) -> int:
    """``chaplygin docs [REPORT]``: the steps of ``make docs-html`` — pages from ``REPORT``
    (default ``verification.json``, written by ``chaplygin verify``), Sphinx with warnings as
    errors, the internal link check. Only in a source checkout (the site's sources are not
    installed)."""
    import importlib.util
    import subprocess
    from pathlib import Path

    from chaplygin_nd.console import OneLineParser, fail, path_argument

    parser = OneLineParser(prog="chaplygin docs", description="Build the reading site into "
                           "docs/_build/html (make docs-html) from a verification.json.")
    parser.add_argument("report", nargs="?", metavar="REPORT", type=path_argument,
                        help="the verification.json to build from (default: the checkout's, "
                             "written by `chaplygin verify`)")
    args = parser.parse_args(argv)
    root = Path(__file__).resolve().parent.parent
    if not (root / "docs" / "build_pages.py").is_file():
        return fail("chaplygin docs: the reading site is built from a source checkout (make docs); "
                    "this installation has no docs/ folder")
    report = args.report or root / "verification.json"
    if not report.is_file():
        return fail(f"chaplygin docs: no report {report}: run `chaplygin verify` first "
                    "(or give the path of a verification.json)")
    if importlib.util.find_spec("sphinx") is None:
        return fail("chaplygin docs: Sphinx is not installed: pip install -e '.[docs]' (or make docs)")
    steps = [[sys.executable, str(root / "docs" / "build_pages.py"), "--report", str(report)],
             [sys.executable, "-m", "sphinx", "-b", "html", "-W", "--keep-going", "-q", "-c",
              str(root / "docs"), str(root / "docs/_build/src"), str(root / "docs/_build/html")],
             [sys.executable, str(root / "docs" / "check_links.py"), str(root / "docs/_build/html")]]
    for step in steps:
        code = subprocess.run(step, cwd=root).returncode
        if code:
            return code
    print(f"wrote {root / 'docs/_build/html/index.html'}")
    return 0


def commit() -> str | None:
    """The checkout's commit (short hash, ``+dirty`` when the tree has changes), or ``None`` when
    this is not a git checkout (an installed wheel)."""
    import subprocess
    from pathlib import Path

    root = Path(__file__).resolve().parent.parent
    if not (root / ".git").exists() or not (root / "pyproject.toml").is_file():
        return None
    try:
        head = subprocess.run(["git", "-C", str(root), "rev-parse", "--short", "HEAD"],
                              capture_output=True, text=True, timeout=10, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(root), "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, timeout=10).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return None
    return head + ("+dirty" if dirty else "")


def version_line() -> str:
    """``chaplygin-nd VERSION`` and, in a checkout, ``(commit HASH)``."""
    c = commit()
    return f"chaplygin-nd {__version__}" + (f" (commit {c})" if c else "")


def _usage() -> str:
    width = max(map(len, COMMANDS))
    lines = [f"  {name:<{width}}  {help_}" for name, (_, _, help_) in COMMANDS.items()]
    return ("usage: chaplygin [--version] COMMAND [ARGS ...]\n\ncommands:\n" + "\n".join(lines)
            + "\n\n`chaplygin COMMAND -h` shows the options of COMMAND.")


def main(argv: list[str] | None = None, *, program: bool = False) -> int:
    """Run the ``chaplygin`` command; the exit status of the subcommand (2 on a usage error,
    130 when interrupted by Ctrl-C, 143 by SIGTERM). Ctrl-C or SIGTERM at any moment of the
    command — while a module is imported (the signal then waits for the import to end:
    :mod:`chaplygin_nd.console`), while the subcommand runs or while it prints its last line —
    ends it with one line, ``interrupted``; a signal received before the subcommand returned is
    never lost, even if something on the way swallowed it (the run then says ``interrupted``).
    As the program (``program``, from :func:`entry`): once the subcommand has returned, its files
    are whole and a late signal no longer changes the exit status (the process ignores both
    signals until it exits). Called in-process (a test, a mutant's test run) it leaves the
    signals as it found them: ignoring them there lost a SIGTERM sent to the caller later."""
    import signal

    from chaplygin_nd import console, signals

    try:
        status = _main(argv)
    except KeyboardInterrupt:
        status = console.fail("interrupted", 130)
    except BaseException:  # noqa: BLE001 - after a signal, whatever a library made of it
        if signals.received() is None or isinstance(sys.exc_info()[1], SystemExit):
            raise
        status = console.fail("interrupted", 130)
    finally:
        if program:
            for sig in (signal.SIGINT, signal.SIGTERM):
                signal.signal(sig, signal.SIG_IGN)
    first = signals.received()
    if first is not None:
        if status != 130:
            console.fail("interrupted", 130)
        status = 128 + first
    return status


def entry() -> None:
    """The ``chaplygin`` program (console script and ``python -m chaplygin_nd``): :func:`main`,
    then exit with its status. An interrupted run (130) flushes stdout and stderr and ends with
    ``os._exit``: its files are whole or absent by then (every ``finally`` has run), and the
    interpreter's own shutdown after Ctrl-C inside gmpy2 arithmetic (the mpmath Taylor pilot)
    crashed with SIGSEGV in 4 of 40 seeded trials, turning exit 130 into -11."""
    import os

    from chaplygin_nd.signals import take_signals

    take_signals()  # first, before any heavy import: an interrupt is one line from here on
    from chaplygin_nd.cache import place_matplotlib_cache

    place_matplotlib_cache()  # every subcommand that draws (verify's claim graph too) uses it
    try:
        status = main(program=True)
    except BrokenPipeError:
        # the reader of stdout went away (`chaplygin --help | head -1`): what it did not read is
        # not wanted, and there is no one to tell; the shell's status of a SIGPIPE death, 128 + 13.
        # stdout goes to /dev/null so that the interpreter's flush at exit does not raise again.
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        sys.exit(141)
    if status in (130, 143):
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except (OSError, ValueError, AttributeError):
                pass
        os._exit(status)
    sys.exit(status)


def _main(argv: list[str] | None) -> int:
    args = list(sys.argv[1:] if argv is None else argv)
    if not args or args[0] in ("-h", "--help"):
        print(_usage(), file=sys.stdout if args else sys.stderr)
        return 0 if args else 2
    if args[0] in ("-V", "--version"):
        print(version_line())
        return 0
    from chaplygin_nd.console import fail

    name, rest = args[0], args[1:]
    if name not in COMMANDS:
        print(f"chaplygin: unknown command {name!r}\n\n{_usage()}", file=sys.stderr)
        return 2
    if name == "prove" and not [a for a in rest if not a.startswith("-")] \
            and not {"--list", "-h", "--help"} & set(rest):
        return fail("chaplygin prove: name at least one ledger id (`chaplygin prove --list` lists "
                    "them; `chaplygin verify` runs them all)")
    if name == "verify" and [a for a in rest if not a.startswith("-") and not _is_option_value(rest, a)]:
        return fail("chaplygin verify: takes no ids (use `chaplygin prove ID ...`)")
    module, function, _ = COMMANDS[name]
    run = getattr(importlib.import_module(module), function)  # Ctrl-C here: one line too (see main)
    try:
        return int(run(rest) or 0)
    except OSError as exc:
        if exc.errno not in STORAGE_ERRORS:
            raise
        # every writer writes whole files or none (chaplygin_nd.writing): only the line is missing
        where = f"{exc.filename}: " if exc.filename else ""
        return fail(f"chaplygin {name}: {where}{exc.strerror or exc} (nothing was half-written)")


def _is_option_value(args: list[str], value: str) -> bool:
    """True when ``value`` follows an option that takes a value (``--seed 3``, ``-j 2``)."""
    i = args.index(value)
    return i > 0 and args[i - 1] in ("--seed", "--jobs", "-j", "--report-dir")
