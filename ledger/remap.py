"""``python -m chaplygin_nd.ledger.remap``: run every ledger row and write the reach map
(:mod:`chaplygin_nd.ledger.reach`), ``ledger/reach.json``; exit 1 if a printed function is
reached by no row."""

from __future__ import annotations

import sys

from chaplygin_nd.ledger.reach import MAP_PATH, printed_functions, save, unreached
from chaplygin_nd.ledger.runner import run, select


def compute(jobs: int | None = 2) -> tuple[dict[str, list[str]], dict[str, float]]:
    """Run every registered ledger row: (row -> printed functions it reached, row -> seconds)."""
    results = run(select(), jobs=jobs)
    bad = [r.row.id for r in results if r.error]
    if bad:
        raise RuntimeError(f"rows raised while mapping reach: {', '.join(bad)}")
    done = [r for r in results if r.module]
    return {r.row.id: list(r.printed) for r in done}, {r.row.id: r.seconds for r in done}


def main(argv: list[str] | None = None) -> int:
    """``python -m chaplygin_nd.ledger.remap``: map every row, write ledger/reach.json, exit 1 if unreached."""
    reach, seconds = compute()
    save(reach, seconds)
    missing = unreached(reach)
    n_fn = len(printed_functions())
    print(f"{len(reach)} rows reach {n_fn - len(missing)} of {n_fn} printed functions; "
          f"wrote {MAP_PATH.relative_to(MAP_PATH.parent.parent)}")
    for f in missing:
        print(f"PROBLEM: printed function {f} is reached by no ledger row", file=sys.stderr)
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
