"""``chaplygin bench [-h] [--quick] [--list] [NAME ...]`` from the repository root: run the
benchmarks (every ``bench/bench_*.py`` that defines ``main``, or only those named), writing figures,
Markdown and JSON rows into ``bench/out/``. Exit status 0 when every benchmark ran (a target that
is NOT MET is reported in its output, not an error), 2 on a usage error, 130 when interrupted."""

from __future__ import annotations

import argparse
import importlib
import inspect
import os
import pkgutil
import shutil
import sys
import time
from pathlib import Path

from chaplygin_nd.cli import version_line
from chaplygin_nd.console import fail, interruptible, path_argument
from chaplygin_nd.writing import folder_problem

OUT = Path(__file__).resolve().parent / "out"
#: Written into every ``--out`` folder the bench uses: a non-empty folder without it holds files
#: this program did not write, and is refused (the bench replaces its files and, with ``--cold``,
#: empties its cache folders).
MARKER = ".chaplygin-bench"
#: Run when no name is given (``make bench``). ``heyoka`` (bench_heyoka.py) repeats the heyoka
#: measurements with fresh caches per tolerance and real128 references: run it by name.
DEFAULT = ("throughput", "work_precision")


def modules() -> list[str]:
    """The benchmark names (``bench_<name>.py`` without the prefix), sorted."""
    here = Path(__file__).resolve().parent
    return sorted(m.name.removeprefix("bench_") for m in pkgutil.iter_modules([str(here)])
                  if m.name.startswith("bench_"))


def _parser() -> argparse.ArgumentParser:
    names = ", ".join(modules())
    p = argparse.ArgumentParser(
        prog="chaplygin bench",
        description="Accuracy-versus-time and throughput benchmarks of chaplygin-nd (never part of "
                    "the tests). Run from the repository root; writes into bench/out/.",
        epilog=f"benchmarks: {names} (default: {', '.join(DEFAULT)}). "
               "Example: chaplygin bench throughput --quick")
    p.add_argument("names", nargs="*", metavar="NAME",
                   help="benchmarks to run (default: see below); 'bench_' prefix optional, '-' "
                        "for '_' (verify-cold)")
    p.add_argument("--quick", action="store_true",
                   help="smoke run: short horizons, few sizes and tolerances (numbers not meaningful)")
    p.add_argument("--cold", action="store_true",
                   help="empty the bench's caches first (bench/out/cache: references, compiled heyoka "
                        "objects, heyoka's own LLVM disk cache): the cold timings; without it the "
                        "caches of the last run are used (warm)")
    p.add_argument("--list", action="store_true", help="list the benchmarks and exit")
    p.add_argument("--version", action="version", version=version_line())
    p.add_argument("--out", type=path_argument, default=None,
                   help="output folder (default: bench/out/ of the source checkout; required "
                        "when installed, so nothing is written inside the installed package)")
    return p


def main(argv: list[str] | None = None) -> int:
    """Run the benchmarks; Ctrl-C or SIGTERM ends with one line ``interrupted``, exit 130 (every
    file a benchmark wrote is whole: bench.report.write_atomic)."""
    with interruptible():
        try:
            return _main(argv)
        except KeyboardInterrupt:
            return fail("interrupted", 130)


def _main(argv: list[str] | None) -> int:
    parser = _parser()
    args = parser.parse_args(argv)
    known = modules()
    if args.list:
        print("\n".join(known))
        return 0
    names = [n.removeprefix("bench_").replace("-", "_") for n in args.names] or \
        [n for n in DEFAULT if n in known]
    unknown = [n for n in names if n not in known]
    if unknown:
        parser.print_usage(sys.stderr)
        print(f"chaplygin bench: unknown benchmark {', '.join(unknown)}; known: {', '.join(known)}",
              file=sys.stderr)
        return 2
    if args.out is None:
        if not (OUT.parent.parent / "pyproject.toml").is_file():
            return fail("chaplygin bench: give --out DIR (an installed package is never written "
                        "into)")
        args.out = OUT
    if problem := _unusable_out(args.out):
        return fail(f"chaplygin bench: --out {args.out}: {problem}")
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / MARKER).write_text("written by chaplygin bench\n", encoding="utf-8")
    _own_caches(args.out / "cache", args.cold)
    return _run(names, args)


def _unusable_out(out: Path) -> str:
    """Why ``out`` cannot take the bench's files (``""`` when it can): it must be a new folder, an
    empty one, one with :data:`MARKER`, or the checkout's default ``bench/out``, and one this
    program can create and write into (:func:`chaplygin_nd.writing.folder_problem`)."""
    if out.exists() and not out.is_dir():
        return "exists and is not a folder; give a new or empty folder"
    if (out.is_dir() and out.resolve() != OUT.resolve() and not (out / MARKER).is_file()
            and any(out.iterdir())):
        return ("the folder holds files this program did not write; give a new or empty folder, "
                "or one an earlier `chaplygin bench --out` wrote")
    return folder_problem(out)  # really created and removed: os.access says yes to root on /proc


CACHES = ("references", "jit", "heyoka-llvm")


def _own_caches(root: Path, cold: bool) -> None:
    """Every cache the bench uses lives in its own folder ``root`` (never the user's): our cached
    references, the compiled heyoka objects ($CHAPLYGIN_ND_CACHE) and heyoka's own LLVM disk cache.
    ``cold`` empties those three subfolders first (they hold only what the bench wrote)."""
    for name in CACHES:
        folder = root / name
        if cold and folder.exists():
            shutil.rmtree(folder)
        folder.mkdir(parents=True, exist_ok=True)
    os.environ["CHAPLYGIN_ND_CACHE"] = str(root / "jit")
    os.environ["BENCH_CACHE"] = str(root / "references")
    try:
        import heyoka

        heyoka.llvm_state.set_diskcache_path(str(root / "heyoka-llvm"))
        heyoka.llvm_state.clear_memcache()
    except ImportError:
        pass
    if cold:
        print(f"== cold: emptied {', '.join(CACHES)} under {root}", flush=True)


def _run(names: list[str], args) -> int:
    status = 0
    total = time.perf_counter()
    for name in names:
        mod = importlib.import_module(f"chaplygin_nd.bench.bench_{name}")
        run = getattr(mod, "main", None)
        if run is None:
            continue
        start = time.perf_counter()
        print(f"== {name}", flush=True)
        params = inspect.signature(run).parameters
        kwargs = {k: v for k, v in (("quick", args.quick), ("cold", args.cold)) if k in params}
        status |= int(bool(run(args.out, **kwargs)))
        print(f"== {name}: {time.perf_counter() - start:.1f} s", flush=True)
    print(f"== all: {time.perf_counter() - total:.1f} s", flush=True)
    return status


if __name__ == "__main__":
    sys.exit(main())
