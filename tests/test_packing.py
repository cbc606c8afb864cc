"""Packing orbits into heyoka's batches by a pilot's measured cost (simulate/analysis/packing.py):
sorted blocks are the cheapest packing for a known cost, the pilot's order is its decreasing steps,
and the order changes no orbit of the deviation-vector runs (bit for bit; the drawn evidence's
runs: tests/test_naff_projections.py)."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from chaplygin_nd.simulate.analysis import packing


def _cost(steps, index, width):
    """Lane-steps of the batches filled in the order ``index``: width x the slowest lane."""
    return sum(width * max(steps[k] for k in index[i:i + width]) for i in range(0, len(index), width))


@pytest.mark.parametrize("width", [2, 3])
def test_sorted_blocks_are_the_cheapest_packing(width):
    """Every order of 7 orbits (a short last batch included) costs at least the decreasing one."""
    rng = np.random.default_rng(width)
    steps = rng.integers(100, 1000, 7)
    best = min(_cost(steps, p, width) for p in itertools.permutations(range(7)))
    packed = list(np.argsort(-steps, kind="stable"))
    assert _cost(steps, packed, width) == best
    assert packing.efficiency(steps, packed, width) == pytest.approx(steps.sum() / best, rel=1e-15)


def test_batches_pad_with_the_last_orbit():
    out = [(list(lanes), used) for lanes, used in packing.batches(np.array([4, 2, 0, 1, 3]), 2)]
    assert out == [([4, 2], 2), ([0, 1], 2), ([3, 3], 1)]


def _pendula(count=11):
    from chaplygin_nd.simulate.analysis import gali_study

    y0, pars = gali_study._pendula_orbits(2, count, 11)
    return gali_study.pendula(2), y0, pars


def test_the_pilot_orders_by_decreasing_steps():
    pytest.importorskip("heyoka")
    from chaplygin_nd.simulate.analysis import gali_runs
    from chaplygin_nd.simulate.integrators.heyoka_taylor import compiled_integrator

    system, y0, pars = _pendula()
    ta, _, _ = compiled_integrator(system, "double", gali_runs.TOL, compact=True,
                                   batch=gali_runs.BATCH, opt_level=gali_runs.OPT_LEVEL)
    horizons = np.full(len(y0), 256.0)
    order = packing.order(ta, y0, pars, horizons)
    assert sorted(order) == list(range(len(y0)))
    steps = packing.pilot_steps(ta, y0, pars, packing.PILOT * horizons)
    assert np.all(np.diff(steps[order]) <= 0) and len(set(steps)) > 1
    few = packing.order(ta, y0[:3], pars[:, :3], horizons[:3], first=np.array([2, 0, 1]))
    assert list(few) == [2, 0, 1]                          # one batch: nothing to pack, no pilot
    with pytest.raises(ValueError, match="pilot fraction"):
        packing.order(ta, y0, pars, horizons, pilot=0.0)


def test_packing_changes_no_deviation_orbit(monkeypatch):
    pytest.importorskip("heyoka")
    from chaplygin_nd.simulate.analysis import gali_runs

    system, y0, pars = _pendula()
    f = np.linspace(0.5, 2.0, len(y0))                     # unequal horizons: a real reordering
    orders = []

    def recorded(*args, **kw):
        orders.append(packing_order(*args, **kw))
        return orders[-1]

    packing_order = packing.order
    monkeypatch.setattr(packing, "order", recorded)

    def sig(Y, idx):
        return np.moveaxis(Y[..., :1] + 1j * Y[..., 2:3], (0, 1, 2), (2, 0, 1))

    def both():
        run = gali_runs.integrate(system, y0, pars, K=2, T=96.0, dt=0.5, seed=1, signals=sig,
                                  stride=4, time_factor=f)
        more, end = gali_runs.extend(system, run["final"], pars, t0=96.0, t1=160.0, dt=0.5,
                                     signals=sig, time_factor=f)
        return run, more, end

    run, more, end = both()
    assert all(not np.array_equal(o, np.arange(len(y0))) for o in orders) and len(orders) == 2
    monkeypatch.setattr(packing, "order", lambda ta, states, *a, **k: np.arange(len(states)))
    run0, more0, end0 = both()
    for key in ("series", "signals", "final"):
        assert np.array_equal(run[key], run0[key]), key
    assert np.array_equal(more, more0) and np.array_equal(end, end0)
