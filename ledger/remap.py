"""``python -m chaplygin_nd.ledger.remap``: run every ledger row and write the reach map
(:mod:`chaplygin_nd.ledger.reach`), ``ledger/reach.json``: the printed functions and the derivations
each row calls, and the derivations emitted into ``generated/``; exit 1 if a printed function or an
emitted derivation is reached by no row."""

from __future__ import annotations

import os
import sys
import tempfile

from chaplygin_nd.ledger.reach import (
    MAP_PATH,
    derivation_functions,
    emitted_derivations,
    printed_functions,
    save,
    unreached,
    unreached_derivations,
    unreached_emitted,
)
from chaplygin_nd.ledger.runner import run, select

from chaplygin_nd import cache


def compute(jobs: int | None = 2
            ) -> tuple[dict[str, list[str]], dict[str, float], dict[str, list[str]]]:
    """Run every registered ledger row: (row -> printed functions it reached, row -> seconds,
    row -> derivations it reached). The rows run with an empty cache (a new temporary
    ``$CHAPLYGIN_ND_CACHE``, removed after): the seconds order the rows of a cold ``verify --jobs``
    (:func:`ledger.runner.longest_first`), and with the user's warm cache the evidence rows took
    0.2-0.8 s instead of 20-40 s, so a cold run started its longest rows last."""
    with tempfile.TemporaryDirectory(prefix="chaplygin-remap-") as cold:
        before = os.environ.get(cache.ENV)
        os.environ[cache.ENV] = cold   # read by the pool's workers, started in run()
        try:
            results = run(select(), jobs=jobs, fresh=True)
        finally:
            if before is None:
                os.environ.pop(cache.ENV, None)
            else:
                os.environ[cache.ENV] = before
    bad = [r.row.id for r in results if r.error]
    if bad:
        raise RuntimeError(f"rows raised while mapping reach: {', '.join(bad)}")
    done = [r for r in results if r.module]
    return ({r.row.id: list(r.printed) for r in done}, {r.row.id: r.seconds for r in done},
            {r.row.id: list(r.derived) for r in done})


def main(argv: list[str] | None = None) -> int:
    """``python -m chaplygin_nd.ledger.remap``: map every row, write ledger/reach.json, exit 1 if
    a printed function or an emitted derivation is unreached."""
    reach, seconds, derived = compute()
    emitted = emitted_derivations()
    save(reach, seconds, derived_by_row=derived, emitted=emitted)
    missing = unreached(reach)
    n_fn, n_der = len(printed_functions()), len(derivation_functions())
    not_derived = unreached_derivations(derived)
    not_emitted = unreached_emitted(derived, emitted)
    print(f"{len(reach)} rows reach {n_fn - len(missing)} of {n_fn} printed functions and "
          f"{n_der - len(not_derived)} of {n_der} derivations ({len(emitted) - len(not_emitted)} "
          f"of the {len(emitted)} emitted into generated/); "
          f"wrote {MAP_PATH.relative_to(MAP_PATH.parent.parent)}")
    for f in not_derived:
        print(f"  derivation {f} is reached by no ledger row"
              + (" (EMITTED)" if f in not_emitted else ""))
    for f in missing:
        print(f"PROBLEM: printed function {f} is reached by no ledger row", file=sys.stderr)
    for f in not_emitted:
        print(f"PROBLEM: emitted derivation {f} is reached by no ledger row", file=sys.stderr)
    return 1 if missing or not_emitted else 0


if __name__ == "__main__":
    sys.exit(main())
