"""One run of a row records every planned function's calls (ledger/mutation/planned.py): each
function's recording is, call by call, the one the one-function recorder (replay.record) makes
from the same empty caches; it survives the pickle; the guard accepts it and refuses a recording
whose value the original does not give; a run that is not the baseline keeps no call."""

from __future__ import annotations

import pickle

import pytest
from chaplygin_nd.ledger.mutation import cache_scope, checks, planned, replay
from chaplygin_nd.ledger.mutation.derivations import functions

ROW = "eq:axisymm"  # a row of a few hundredths of a second reached by several derivations
KEYS = ("algebra.hat", "axisymmetric.E_n", "axisymmetric.mass_tensor", "model.inertia_operator")


@pytest.fixture(scope="module")
def together():
    checks.init_worker()
    cache_scope.end()
    base, _ = checks.run_row(ROW)
    got = planned.record_row(ROW, KEYS, base, 1.0)
    return base, {key: pickle.loads(data) for key, data in got.items()}


def _same_calls(a: replay.Recording, b: replay.Recording) -> bool:
    return len(a.calls) == len(b.calls) and all(
        replay.identical(x, y) for ca, cb in zip(a.calls, b.calls) for x, y in zip(ca, cb))


@pytest.mark.parametrize("key", KEYS)
def test_one_run_records_what_one_function_at_a_time_records(together, key):
    _, recs = together
    fn = functions("derivations")[key]
    alone = replay.record(fn, lambda: checks.run_row(ROW))
    assert key in recs
    assert recs[key].problem == alone.problem == ""
    assert recs[key].calls  # the row calls it
    assert _same_calls(recs[key], alone)


def test_the_guard_accepts_the_recording_and_refuses_a_changed_value(together):
    _, recs = together
    key = "axisymmetric.E_n"
    fn = functions("derivations")[key]
    good = planned.guard(fn, pickle.loads(pickle.dumps(recs[key])))
    assert good.problem == "" and len(good.calls) == len(recs[key].calls)
    args, kwargs, value, after, kwafter = recs[key].calls[0]
    changed = replay.Recording(calls=[(args, kwargs, 2 * value, after, kwafter)])
    assert not replay.identical(value, changed.calls[0][2])
    bad = planned.guard(fn, changed)
    assert "gives other values" in bad.problem and bad.calls == []


def test_a_run_that_is_not_the_baseline_keeps_no_call():
    checks.init_worker()
    cache_scope.end()
    got = planned.record_row(ROW, KEYS[:1], ("not", "the", "baseline"), 1.0)
    rec = pickle.loads(got[KEYS[0]])
    assert rec.problem == planned.NOT_BASELINE and rec.calls == []


def test_take_answers_only_for_what_was_recorded():
    assert planned.take("algebra.hat", "no such row") is None
