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
    derived, _ = reach.load_derived()
    cheap = sorted((r for r in stored if r in registry() and seconds.get(r, 99) < 0.5),
                   key=lambda r: (seconds[r], r))[:8]
    assert cheap
    for claim_id in cheap:
        reach.clear_derivation_caches()
        with reach.Recorder() as rec:
            registry()[claim_id].run()
        assert list(rec.printed()) == sorted(stored[claim_id]), claim_id
        assert list(rec.derived()) == sorted(derived[claim_id]), claim_id


def test_recorder_sees_derivations_and_cache_hits():
    from chaplygin_nd.symbolic import vertical
    from chaplygin_nd.symbolic.reduction.reduced_n4 import horizontal_blocks

    vertical.zeta_coefficient()                     # warm the lru cache: the next call is a hit
    with reach.Recorder() as rec:
        horizontal_blocks(sp.Rational(1, 2), 1, 3)  # from-import route
        vertical.zeta_coefficient()                 # a cache hit: no trampoline runs
    assert {"reduction.reduced_n4.horizontal_blocks", "vertical.zeta_coefficient"} <= set(rec.derived())
    assert not set(rec.printed())


def test_unreached_emitted_flags_an_emitted_derivation_no_row_calls():
    emitted = ["reduction.reduced_n4.horizontal_blocks", "reduction.reduced_n4.horizontal_frequency_squared"]
    rows = {"S5:H-linear-nD": ["reduction.reduced_n4.horizontal_blocks"]}
    assert reach.unreached_emitted(rows, emitted) == ["reduction.reduced_n4.horizontal_frequency_squared"]


def test_every_emitted_derivation_is_reached_by_a_ledger_row():
    """The derivations called while generated/ is built (live) are all reached in the stored map
    (``make verify`` checks the same on its live run)."""
    derived, stored_emitted = reach.load_derived()
    emitted = reach.emitted_derivations()
    assert "reduction.reduced_n4.horizontal_frequency_squared" in emitted and "reduction.reduced_n4.horizontal_blocks" in emitted
    assert emitted == stored_emitted, "refresh the map: python -m chaplygin_nd.ledger.remap"
    missing = reach.unreached_emitted(derived, emitted)
    assert missing == [], f"emitted derivations reached by no row: {missing}"


def test_a_warm_run_keeps_the_stored_cold_seconds(tmp_path):
    """make mutate maps reach with a warm cache; it writes back the stored (cold) seconds of the
    rows the map has, and its own only for a row the map lacks."""
    path = tmp_path / "reach.json"
    reach.save({"A": [], "B": []}, {"A": 90.0, "B": 2.0}, path=path, derived_by_row={}, emitted=[])
    assert reach.kept_seconds({"A": 0.3, "B": 2.5, "C": 4.0}, path) == {"A": 90.0, "B": 2.0, "C": 4.0}
    assert reach.kept_seconds({"A": 0.3}, tmp_path / "none.json") == {"A": 0.3}


def test_the_same_map_is_the_same_file_whatever_order_the_rows_came_in(tmp_path):
    """make mutate saves the map with the rows in the order its baseline ran them and the
    derivation map as read back from the file: the same sets in another order rewrote every list
    of ledger/reach.json. Every list is sorted on save."""
    derivation = next(iter(reach.derivation_functions()))
    first, second = tmp_path / "a.json", tmp_path / "b.json"
    reach.save({"B": ["section4.K", "section2.a"], "A": ["section2.a"]}, {"A": 1.0, "B": 2.0},
               path=first, derived_by_row={"B": [derivation], "A": [derivation]},
               emitted=[derivation])
    reach.save({"A": ["section2.a"], "B": ["section2.a", "section4.K"]}, {"B": 2.0, "A": 1.0},
               path=second, derived_by_row={"A": [derivation], "B": [derivation]},
               emitted=[derivation])
    assert first.read_bytes() == second.read_bytes()
    assert reach.load(first)[0]["B"] == ["section2.a", "section4.K"]
