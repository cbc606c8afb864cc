"""The NAFF count over the horizon ladder (simulate/analysis/naff_ladder.py): an orbit resolved at T
stays there, one whose lines T cannot separate is continued and resolved at a longer horizon with
the right count, a chaotic one stays unresolved at every horizon; the continuation of the heyoka
runs (simulate/analysis/gali_runs.py) joins the first run without a gap; quick versions of the
validation study (simulate/analysis/naff_study.py)."""

from __future__ import annotations

import numpy as np
import pytest
from chaplygin_nd.simulate.analysis import naff_ladder, naff_study

DT = 0.5


def _torus(freqs, amps, t):
    """Two signals on a torus: the fundamentals and a few combinations (lattice lines)."""
    w1, w2 = freqs
    z1 = sum(a * np.exp(1j * w * t) for a, w in zip(amps, (w1, w2, w1 + w2)))
    z2 = 0.8 * np.exp(1j * w2 * t) + 0.3 * np.exp(1j * (2 * w1 - w2) * t) + 0.2 * np.exp(1j * w1 * t)
    return np.stack([z1, z2])


def _ensemble(freqs, T, factor=4):
    t = np.arange(int(round(factor * T / DT)) + 1) * DT
    full = np.stack([_torus(f, (1.0, 0.6, 0.3), t) for f in freqs])     # (orbits, 2, samples)
    n0 = int(round(T / DT))
    calls = []

    def extend(idx, t0, t1):
        calls.append((list(idx), t0, t1))
        a, b = int(round(t0 / DT)) + 1, int(round(t1 / DT)) + 1
        return full[idx, :, a:b]

    return full[:, :, :n0 + 1], extend, calls


def test_resolved_at_T_is_not_continued():
    T = 1024.0
    z, extend, calls = _ensemble([(0.31, 0.5 * np.sqrt(2) * 0.31 + 0.2)], T)
    (spec, extra), = naff_ladder.ladder(z, DT, T, 2, extend)
    assert naff_ladder.resolved(spec, extra) and extra["horizon"] == 1.0
    assert spec.count == 2 and calls == []


def test_close_lines_are_continued_to_a_longer_horizon():
    """Two fundamentals 1.5 Fourier bins of a half apart at T: unresolved there; the ladder asks
    for the next stretch and stops at the first horizon that resolves them."""
    T = 512.0
    bin_half = 2 * np.pi / (T / 2)
    z, extend, calls = _ensemble([(0.37, 0.37 + 1.5 * bin_half)], T)
    (spec, extra), = naff_ladder.ladder(z, DT, T, 2, extend)
    assert extra["diffusions"][0] >= 1e-5                     # not resolved at T
    assert extra["horizon"] > 1.0 and naff_ladder.resolved(spec, extra)
    assert calls[0] == ([0], T, 2 * T)
    assert len(extra["diffusions"]) == len(calls) + 1


def test_separated_lines_count_two():
    T = 512.0
    bin_half = 2 * np.pi / (T / 2)
    z, extend, calls = _ensemble([(0.37, 0.37 + 8 * bin_half)], T)
    (spec, extra), = naff_ladder.ladder(z, DT, T, 2, extend)
    assert naff_ladder.resolved(spec, extra) and spec.count == 2 and calls == []


def test_lines_three_bins_apart_pass_the_diffusion_but_overcount():
    """A limit of the rule (stated on the evidence page): D compares the two halves, and a line
    a few bins away biases both alike, so D < 1e-5 while the frequencies are off by more than the
    count's tolerance and combinations read as new frequencies. Here 3 bins of a half: D ~ 3e-8,
    count 4 on a 2-torus."""
    T = 512.0
    bin_half = 2 * np.pi / (T / 2)
    z, extend, _ = _ensemble([(0.37, 0.37 + 3 * bin_half)], T)
    (spec, extra), = naff_ladder.ladder(z, DT, T, 2, extend)
    assert spec.diffusion < 1e-6 and spec.count > 2


def test_chaotic_map_stays_unresolved_at_every_horizon():
    out = naff_study._map_case(10.0, 16, 5)
    assert not any(naff_ladder.resolved(s, e) for s, e in out)
    assert all(e["horizon"] == 4.0 for _, e in out)            # each was carried to 4T


def test_twist_map_counts_one():
    out = naff_study._map_case(0.0, 16, 5)
    assert all(naff_ladder.resolved(s, e) and s.count == 1 for s, e in out)


def test_continuation_joins_the_first_run():
    """gali_runs.continuation starts where gali_runs.integrate stopped: the continued signal at
    T + dt equals a run from the start sampled there (heyoka tolerance)."""
    pytest.importorskip("heyoka")
    from chaplygin_nd.simulate.analysis import gali_runs, gali_study

    y0, pars = gali_study._pendula_orbits(2, 3, 11)

    def sig(Y, idx):
        return np.moveaxis(Y[..., :1] + 1j * Y[..., 2:3], (0, 1, 2), (2, 0, 1))

    first = gali_runs.integrate(gali_study.pendula(2), y0, pars, K=2, T=64.0, dt=DT, seed=1,
                                signals=sig, stride=8)
    more = gali_runs.continuation(gali_study.pendula(2), first["final"], pars, dt=DT,
                                  signals=sig)(np.array([0, 2]), 64.0, 128.0)
    whole, _ = gali_runs.extend(gali_study.pendula(2), y0, pars, t0=0.0, t1=128.0, dt=DT,
                                signals=sig)
    assert more.shape == (2, 1, 128)
    np.testing.assert_allclose(more, whole[[0, 2], :, 128:], atol=1e-7)


@pytest.mark.parametrize("m", [2, 3])
def test_pendula_counts_on_the_ladder(m):
    """A quick run of the study's pendula: most orbits resolve, and the resolved ones count their
    torus dimension up to the study's false alarms (m = 2: 5 of 45 resolved read 3, a doubled
    line entering the basis before the fundamental; m = 3: 2 of 42), so at most 2 in 8 here."""
    pytest.importorskip("heyoka")
    out = naff_study._flow(naff_study._pendula_case(m, 8, 17))
    counts = [s.count for s, e in out if naff_ladder.resolved(s, e)]
    assert len(counts) >= 6
    assert sum(c == m for c in counts) >= len(counts) - 2
    assert all(c >= m for c in counts)
