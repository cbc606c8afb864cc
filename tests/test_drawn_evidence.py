"""The verdict rule of the drawn evidence rows (simulate/analysis/rules.py, proofs/drawn_common.py) on synthetic orbits, and
the exact part of S6:open-reduced-n5 (quotient dimension and independent invariant integrals)."""

from __future__ import annotations

import pytest
from chaplygin_nd.proofs import drawn_common as dc
from chaplygin_nd.simulate.analysis.drawn_evidence import OrbitResult


def _orbits(spec: dict, drift: float = 1e-10) -> list[OrbitResult]:
    """``{(cls, megno_cls, diffusion, megno): how many}`` -> synthetic results (integrals kept
    to ``drift``)."""
    out = []
    for (cls, mcls, d, y), k in spec.items():
        out += [OrbitResult(0.5, 0.5, 1.0, 2, [0.1, 0.3], d, y, 0.0, cls, mcls, drift=drift)] * k
    return out


def test_rule_supports_tori_and_rejects_chaos():
    good = _orbits({("predicted", "regular", 1e-9, 1.9): 150, ("unresolved", "regular", 1e-4, 2.0): 50})
    assert dc.supported(good)
    chaotic = _orbits({("predicted", "regular", 1e-9, 1.9): 190, ("unresolved", "chaotic", 0.1, 9.0): 10})
    assert not dc.supported(chaotic)                       # 5 % contradict
    excess = _orbits({("predicted", "regular", 1e-9, 1.9): 195, ("excess", "regular", 1e-8, 2.0): 5})
    assert not dc.supported(excess)                        # 2.5 % > 2 %
    few = _orbits({("predicted", "regular", 1e-9, 1.9): 30, ("unresolved", "regular", 1e-3, 2.0): 170})
    assert not dc.supported(few)                           # the prediction is hardly observed
    undecided = _orbits({("predicted", "regular", 1e-9, 1.9): 170, ("predicted", "undecided", 1e-9, 3.3): 30})
    assert not dc.supported(undecided)                     # MEGNO certifies < 90 %


def test_rule_rejects_a_field_that_breaks_the_integrals_and_names_the_part():
    good = {("predicted", "regular", 1e-9, 1.9): 150, ("unresolved", "regular", 1e-4, 2.0): 50}
    assert dc.parts(_orbits(good)) == {"integrals": True, "chaos": True, "frequencies": True}
    broken = _orbits(good, drift=1e-3)                     # tori, no chaos, integrals not kept
    assert not dc.supported(broken)
    assert dc.parts(broken) == {"integrals": False, "chaos": True, "frequencies": True}
    assert dc.unmet(broken)[0].startswith("integrals: 0 of 200 orbits keep")


def test_control_must_separate_on_both_indicators():
    row = _orbits({("predicted", "regular", 1e-8, 1.9): 100})
    chaotic = _orbits({("unresolved", "chaotic", 1.0, 15.0): 92, ("unresolved", "regular", 1e-2, 2.0): 8})
    assert dc.separates(row, chaotic) == (True, True)
    mixed = _orbits({("unresolved", "chaotic", 1.0, 15.0): 80, ("unresolved", "regular", 1e-2, 2.0): 20})
    assert dc.separates(row, mixed) == (False, True)                     # < 90 % chaotic
    quiet = _orbits({("unresolved", "regular", 1e-2, 2.0): 100})          # diffuses, no chaos
    assert dc.separates(row, quiet) == (False, True)
    sharp = _orbits({("predicted", "chaotic", 1e-8, 15.0): 100})          # chaos, no diffusion
    assert dc.separates(row, sharp) == (True, False)


@pytest.mark.slow
def test_n5_quotient_and_integrals_at_another_seed():
    from chaplygin_nd.proofs import s6_open_reduced_n5 as s6
    from chaplygin_nd.symbolic.exact import points

    saved = points.ledger_seed()
    try:
        points.set_ledger_seed(7)
        exact = s6.reduced_dimension_check()
    finally:
        points.set_ledger_seed(saved)
    assert exact["orbit_rank"] == (6, 6)
    assert exact["integral_rank"] == (5, 5)
    assert exact["invariant"] and exact["integrals"] == 5
