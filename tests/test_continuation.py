"""The frequency ladder's longer runs continue the orbit from the state at the shorter horizon
(simulate/analysis/continuation.py): the stitched signals are those of the orbit integrated from 0,
and the records do not depend on what the result cache or the memory held."""

from __future__ import annotations

import json

import numpy as np
import pytest


@pytest.fixture()
def small(tmp_path, monkeypatch):
    pytest.importorskip("heyoka")
    from chaplygin_nd.simulate.analysis import drawn_evidence as de
    from chaplygin_nd.simulate.analysis import draws
    from chaplygin_nd.simulate.dynamics import so

    monkeypatch.setenv("CHAPLYGIN_ND_CACHE", str(tmp_path))
    ens = draws.draw("continuation test", "generic", 4, 6, 5)
    y0 = np.concatenate([so.vec(ens.M0), ens.gamma0], axis=-1)
    s = de.Setting("continuation", "full", 4, 64.0, 0.5, observables="four", expected=3)
    return s, ens, y0


def _measured(s, ens, y0):
    from chaplygin_nd.simulate.analysis import continuation
    from chaplygin_nd.simulate.analysis import drawn_evidence as de

    base = de.settings(s, ens, y0, 5)
    de.measure(s, ens, y0, 5, on_signals=lambda Z, final: continuation.remember(
        base, 1.0, range(len(y0)), Z, final))
    return base


def test_continued_signals_are_the_orbit_integrated_from_zero(small):
    from chaplygin_nd.simulate.analysis import continuation
    from chaplygin_nd.simulate.analysis import drawn_evidence as de

    s, ens, y0 = small
    base = _measured(s, ens, y0)
    try:
        for factor, index in ((2.0, [1, 3, 4]), (4.0, [1, 4])):
            longer, _, Z, _, _, extra = continuation._continue(s, ens, y0, 5, factor, index)
            Z0, _, _, extra0 = de._integrate(longer, de.subset(ens, index), y0[index], 5)
            assert Z.shape == Z0.shape == (len(index), 5, int(round(longer.T / longer.dt)) + 1)
            # one orbit, two step sequences (the first T also followed the tangent vector): equal
            # to the integrator's accuracy; a sample shifted at the seam would differ by ~0.1
            assert np.max(np.abs(Z - Z0)) < 1e-7, factor
            np.testing.assert_allclose(extra["final"], extra0["final"], atol=1e-7)
            assert np.all(extra["drift"] < 1e-8)
    finally:
        continuation.forget(base)


def test_the_records_do_not_depend_on_what_memory_and_cache_held(small):
    from chaplygin_nd.simulate.analysis import continuation

    s, ens, y0 = small
    base = _measured(s, ens, y0)
    try:
        index = [0, 2, 5]
        kept = continuation.extend(s, ens, y0, 5, 2.0, index)
        further = continuation.extend(s, ens, y0, 5, 4.0, index[:2])
        continuation.forget(base)               # as after a run at T read from the result cache
        again = continuation.extend(s, ens, y0, 5, 2.0, index, use_cache=False)
        continuation.forget(base)
        again4 = continuation.extend(s, ens, y0, 5, 4.0, index[:2], use_cache=False)
    finally:
        continuation.forget(base)

    def text(records):
        return json.dumps([r.to_dict() for r in records], sort_keys=True)

    assert text(kept) == text(again) and text(further) == text(again4)
    assert all(np.isnan(r.megno) for r in kept + further)   # frequency-only: no chaos indicator
