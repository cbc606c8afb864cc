"""Every printed formula is reached by a ledger row, and the reach tracer sees every route.

Most printed functions are reached by their own row only, so a live run covering all of them is
nearly the whole ledger (~90 s): that complete live check is done by ``make verify`` (the runner
records every row's printed calls at no extra cost and the run fails on an unreached function) and
by ``make mutate``, which also writes the map ledger/reach.json. Here: the tracer sees every
route; the stored map reaches every *current* public printed function (a new transcription no row
calls fails at once); and the stored map is what the tracer records, live, for a deterministic
sample of cheap rows (so the map is not a hand-written list).
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.ledger import reach
from chaplygin_nd.ledger.catalog import discover
from chaplygin_nd.ledger.registry import registry
from chaplygin_nd.symbolic.printed import section4


def test_recorder_sees_every_route_and_restores_the_code():
    from chaplygin_nd.symbolic.printed.section4 import Omega_inverse  # a name bound at import time

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


def test_every_printed_function_is_reached_by_a_ledger_row():
    stored, _ = reach.load()
    missing = reach.unreached(stored)
    assert missing == [], (f"printed functions reached by no row: {missing} (a new transcription "
                           "needs a row that calls it; if a row does, refresh the map with "
                           "`python -m chaplygin_nd.ledger.remap`)")


def test_the_stored_map_is_what_the_tracer_records():
    discover()
    stored, seconds = reach.load()
    cheap = sorted((r for r in stored if r in registry() and seconds.get(r, 99) < 0.5),
                   key=lambda r: (seconds[r], r))[:8]
    assert cheap
    for claim_id in cheap:
        with reach.Recorder() as rec:
            registry()[claim_id].run()
        assert sorted(rec.calls) == sorted(stored[claim_id]), claim_id
