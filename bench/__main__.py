"""``python -m bench [NAME ...]``: run every module ``bench/bench_*.py`` that defines ``main(outdir)``
(or only those named), writing into ``bench/out/`` (git-ignored)."""

from __future__ import annotations

import importlib
import pkgutil
import sys
import time
from pathlib import Path

OUT = Path(__file__).resolve().parent / "out"


def modules() -> list[str]:
    """The benchmark modules, sorted by name."""
    import bench

    return sorted(m.name for m in pkgutil.iter_modules(bench.__path__) if m.name.startswith("bench_"))


def main(argv: list[str] | None = None) -> int:
    names = (argv if argv is not None else sys.argv[1:]) or modules()
    OUT.mkdir(parents=True, exist_ok=True)
    status = 0
    for name in names:
        mod = importlib.import_module(f"bench.{name}")
        run = getattr(mod, "main", None)
        if run is None:
            continue
        start = time.perf_counter()
        print(f"== {name}", flush=True)
        status |= int(bool(run(OUT)))
        print(f"== {name}: {time.perf_counter() - start:.1f} s", flush=True)
    return status


if __name__ == "__main__":
    sys.exit(main())
