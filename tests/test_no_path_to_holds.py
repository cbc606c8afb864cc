"""No path to ``holds`` without a proof: empty conjunctions raise, a non-zero normal form refutes
(or is an error), controls decide their row, and argued steps are marked as argued."""

from __future__ import annotations

import pytest
from chaplygin_nd.ledger.catalog import discover
from chaplygin_nd.ledger.registry import Verdict, registry
from chaplygin_nd.proofs.s4_common import combine
from chaplygin_nd.proofs.s5_common import phase_point, reduced_check
from chaplygin_nd.symbolic.exact.identity import Check
from chaplygin_nd.symbolic.reduction import invariants_n4 as ri


def test_empty_conjunctions_raise():
    with pytest.raises(ValueError):
        combine([])
    with pytest.raises(ValueError):
        Verdict.all_of([])


def test_nonzero_normal_form_is_refuted_with_a_counterexample():
    chk = reduced_check(ri.F1 - ri.A, "test refute")
    assert not chk.ok and chk.counterexample is not None


def test_nonzero_normal_form_without_a_witness_is_an_error_not_holds():
    def orthogonal_point(rng):          # k perpendicular to u: F1 = <k, u> = 0 at every sample
        pt = phase_point(rng)
        k, u = pt["k"], pt["u"]
        pt["u"] = u - (k.T * u)[0, 0] / (k.T * k)[0, 0] * k
        return pt
    with pytest.raises(ArithmeticError):
        reduced_check(ri.F1, "test no witness", point=orthogonal_point, count=3)


def test_measure4d_controls_decide_the_row(monkeypatch):
    discover()
    import chaplygin_nd.proofs.s5_measure_4d as m

    # A test that cannot tell densities apart (everything "invariant") must not give holds.
    monkeypatch.setattr(m, "ring_on_P", lambda *a, **k: Check(True, "always"))
    assert registry()["S5:measure4D"].run().verdict == "fails"


def test_argued_steps_are_marked():
    discover()
    v = registry()["Th:Re-tori"].run()  # (ii), the measure facts, is argued
    argued = [p for p in v.parts if p.argued]
    assert argued and all(p.method.startswith("argued, not machine-checked") for p in argued)
    assert v.verdict == "corrected"
    assert Verdict.by_argument("a fact").as_part("x").argued
    with pytest.raises(ValueError):
        Verdict.by_argument(" ")


def test_vertical_horizontal_literal_reading_is_a_decided_part():
    discover()
    v = registry()["eq:VHgeneraln"].run()
    part = next(p for p in v.parts if p.name.startswith("literal reading"))
    assert part.verdict == "corrected" and part.counterexample
