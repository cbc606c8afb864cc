"""``make mutate-derivations``: the mutants of the derivations and the runtime are drawn
deterministically, and a mutant of an emitted derivation is killed by a row that checks it.

The seeded sample (150 derivation and 40 runtime mutants) and its outcomes are in docs/design-notes/i17b.md;
here: the selection, and the mutant the issue describes (the frequency of the horizontal closed
form changed) killed by S5:H-linear.
"""

from __future__ import annotations

import pytest
from chaplygin_nd.ledger import mutate
from chaplygin_nd.ledger import mutate_derivations as md
from chaplygin_nd.ledger.catalog import discover


@pytest.mark.slow  # ~30 s: each draw enumerates every mutant of symbolic/ (ledger/mutate.all_mutants)
def test_the_sample_is_deterministic_and_covers_both_targets():
    for target in ("derivations", "runtime"):
        first = md.sample(target, 30)
        assert first == md.sample(target, 30) and len(first) == 30
        assert len({m.function for m in first}) > 5
    assert "runtime.axisym.vertical_solution" in md.functions("runtime")
    assert "reduced.horizontal_frequency_squared" in md.functions("derivations")
    assert not any(k.split(".")[-1].startswith("_") for k in md.functions("runtime"))


def test_a_mutant_of_the_emitted_frequency_is_killed_by_its_row():
    discover()
    key = "reduced.horizontal_frequency_squared"
    fn = md.functions("derivations")[key]
    m = next(m for m, _ in mutate.all_mutants(key, fn) if "2 * b * h" in m.description
             and m.operator == "sign")
    original = fn.__code__
    base = mutate.baseline(["S5:H-linear"], jobs=1)
    task = md.Task("derivations", m, (("S5:H-linear", base["S5:H-linear"][0],
                                       base["S5:H-linear"][1]),))
    record = md.evaluate(task)
    assert record["outcome"] == "killed", record
    assert record["row"] == "S5:H-linear"
    assert fn.__code__ is original  # restored
