"""Every printed formula is reached by a ledger row, and the reach tracer sees every route.

The full map is written by ``python -m proofs.reach`` / ``make mutate`` into proofs/reach.json;
here it only chooses a small set of rows, which are re-run *live* under the tracer: the assertion
that every public function of symbolic/printed/ is reached rests on that live run, so a stale map
makes the test fail, never pass. ``make verify`` repeats the check over all rows at no extra cost.
"""

from __future__ import annotations

import pytest
import sympy as sp

from proofs import reach
from proofs.catalog import discover
from proofs.ledger import registry
from symbolic.printed import section4


def test_recorder_sees_every_route_and_restores_the_code():
    from symbolic.printed.section4 import Omega_inverse  # a name bound at import time

    M = sp.Matrix([[0, 1, 0], [-1, 0, 2], [0, -2, 0]])
    g = sp.Matrix([0, 0, 1])
    codes = {k: f.__code__ for k, f in reach.printed_functions().items()}
    before = section4.Omega_inverse(M, g, 1, 1)
    with reach.Recorder() as rec:
        inside = Omega_inverse(M, g, 1, 1)           # from-import route
    assert {"section4.Omega_inverse", "section4.K", "section4.Delta"} <= rec.calls  # nested calls
    assert inside == before
    with reach.Recorder() as rec2:
        section4.Delta(sp.Rational(1, 2), 1, 1)        # module-attribute route
    assert rec2.calls == {"section4.Delta"}
    assert {k: f.__code__ for k, f in reach.printed_functions().items()} == codes


def test_unreached_flags_a_function_no_row_calls():
    fns = list(reach.printed_functions())
    fake = {"row": fns[1:]}
    assert reach.unreached(fake) == [fns[0]]


@pytest.mark.slow
def test_every_printed_function_is_reached_by_a_ledger_row():
    discover()
    stored, seconds = reach.load()
    rows = reach.cover({r: fs for r, fs in stored.items() if r in registry()}, seconds)
    seen = set()
    for claim_id in rows:
        with reach.Recorder() as rec:
            registry()[claim_id].run()
        seen |= rec.calls
    missing = sorted(set(reach.printed_functions()) - seen)
    assert missing == [], (f"printed functions reached by none of the rows {rows}: {missing} "
                           "(a new transcription needs a row that calls it; if a row does, "
                           "refresh proofs/reach.json with `python -m proofs.reach`)")
