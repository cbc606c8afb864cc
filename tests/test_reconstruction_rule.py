"""The re-examination rule of the reconstruction row (simulate/analysis/reconstruction.py) on
lines of known lattices: a 3-torus whose strongest lines span only a sublattice, one whose lines
need coefficients beyond 12, a 4-torus, and signals sampled from a known quasi-periodic motion."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from chaplygin_nd.simulate.analysis import combinations
from chaplygin_nd.simulate.analysis import reconstruction as rc5

W = (0.0506563354, 0.2187443238, 0.1068470217)   # a 3-torus of the n = 4 row (orbit 35 of seed 20261121)


def _lines(coeffs, basis, amps):
    return rc5.distinct([(abs(float(np.dot(c, basis))), a) for c, a in zip(coeffs, amps)], 1e-12)


def test_p_false_is_the_exact_union_of_combinations():
    basis = (0.31, 0.077)
    s = rc5.candidates_sorted(basis, 6)
    for tau in (1e-6, 1e-4, 3e-3):
        assert rc5.p_false(s, tau, 0.9) == pytest.approx(combinations.false_match(basis, tau, 0.9, 6),
                                                         rel=1e-9)


def test_a_sublattice_basis_chosen_by_amplitude_is_still_rank_3():
    # the three strongest lines (w2, w2 + w3, w3 - 2 w1) span an index-2 sublattice: the row's
    # count made w1 a fourth frequency; every line is a small combination of (w1, w2, w3)
    coeffs = [(0, 1, 0), (0, 1, 1), (-2, 0, 1), (0, 0, 1), (1, 0, 0), (-1, 1, -1), (1, 1, 1)]
    lines = _lines(coeffs, W, [1.0, 0.9, 0.8, 0.7, 0.6, 0.5, 0.3])
    fit = rc5.lattice_fit(lines, 1e-9, [1e-12] * len(lines))
    assert fit["basis"] is not None and fit["max_c"] <= 3


def test_large_coefficients_count_only_at_a_credible_precision():
    slow = (0.0045099187, 0.1239907872, 0.4041286209)
    coeffs = [(0, 0, 1), (1, 0, 0), (0, 1, 0), (20, 1, 0), (22, 1, 1), (-2, 1, 0)]
    lines = _lines(coeffs, slow, [1.0, 0.9, 0.8, 0.7, 0.6, 0.5])
    precise = rc5.lattice_fit(lines, 1e-7, [1e-11] * len(lines))
    assert precise["basis"] is not None and precise["max_c"] == 22
    # the same lines known only to 1e-6: a match among ~10^5 combinations is no evidence, so the
    # lattice is not established (the orbit is not counted as the predicted count)
    vague = rc5.lattice_fit(lines, 1e-6, [1e-6] * len(lines))
    assert vague["basis"] is None and vague["unexplained"]
    # known only to 1e-4, no search up to |c| <= 12 is credible: the lines are not testable either
    blurred = rc5.lattice_fit(lines, 1e-4, [1e-4] * len(lines))
    assert blurred["basis"] is None and blurred["untestable"] == blurred["unexplained"]


def test_a_fourth_frequency_is_unexplained_testable_and_persists():
    w4 = 0.0731234567
    basis = W + (w4,)
    coeffs = [c + (0,) for c in itertools.product((-1, 0, 1), repeat=3) if any(c)][:10]
    coeffs += [(0, 0, 1, 1)]
    amps = [1.0 - 0.05 * k for k in range(10)] + [0.2]
    lines = _lines(coeffs, basis, amps)
    looks = [rc5.Look(h, 1e-9, [list(x) for x in lines], 1e-9) for h in (1.0, 2.0, 4.0, 8.0)]
    out = rc5.decide(looks, 4096.0)
    assert out.cls == "fourth frequency"
    assert any(t["persists"] for t in out.track)


def test_a_line_that_moves_with_the_horizon_is_transient_not_a_frequency():
    coeffs = [(0, 1, 0), (0, 0, 1), (1, 0, 0), (1, 1, 0)]
    lines = _lines(coeffs, W, [1.0, 0.9, 0.8, 0.7])
    stray_8, stray_4 = 0.0371234567, 0.0371234567 + 2 * (2 * np.pi / (8 * 4096.0))
    looks = [rc5.Look(h, 1e-9, [list(x) for x in lines] + [[stray_4 if h < 8 else stray_8, 0.3]], 1e-9)
             for h in (1.0, 2.0, 4.0, 8.0)]
    out = rc5.decide(looks, 4096.0)
    assert out.cls == "transient"
    assert looks[-1].fit["basis"] is None


def test_signals_of_a_known_3_torus_read_rank_3():
    T, dt = 512.0, 0.5
    t = np.arange(int(8 * T / dt) + 1) * dt
    w1, w2, w3 = 0.31, 0.0731234567 * 3, 0.11 * np.sqrt(2)
    e = [np.exp(1j * w * t) for w in (w1, w2, w3)]
    z = np.array([[e[0] + 0.3 * e[1], e[1] * (1 + 0.3 * e[0]),
                   e[2] * (1 + 0.4 * e[0]) * (1 + 0.3 * np.conj(e[1])), np.conj(e[2]) + 0.2 * e[0] * e[2]]])
    out = rc5.examine_signals(z, dt, T)[0]
    assert out.cls == "rank 3"
    assert sorted(out.looks[-1].fit["basis"]) != []
