"""The frequency evidence of Section 5: NAFF wrapper, integer-relation counter,
control kernel, level-set points, control separation on short orbits, the `evidence` verdict."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from chaplygin_nd.ledger.registry import Verdict
from chaplygin_nd.simulate.analysis import frequencies as fq
from chaplygin_nd.simulate.analysis import naff
from chaplygin_nd.simulate.analysis.control import L_gamma_general, general_inertia_kernels
from chaplygin_nd.simulate.analysis.evidence import (
    _reduced_constraints,
    level_set_points,
    orbits,
    signals,
)
from chaplygin_nd.simulate.dynamics import families
from chaplygin_nd.simulate.kernels import active

W1, W2 = 0.7310412, 0.1892347   # rad per unit time, rationally independent (to the tolerance)


def _torus_signal(t):
    return (np.exp(1j * W1 * t) + 0.5 * np.exp(-1j * W2 * t)
            + 0.2 * np.exp(1j * (W1 + W2) * t) + 0.08 * np.exp(1j * (W1 - 2 * W2) * t))


def test_naff_recovers_known_lines():
    dt = 0.5
    t = np.arange(4097) * dt
    w, amp = naff.spectral_lines(_torus_signal(t), dt, terms=6)
    for f, a in ((W1, 1.0), (-W2, 0.5), (W1 + W2, 0.2), (W1 - 2 * W2, 0.08)):
        i = int(np.argmin(np.abs(w - f)))
        assert abs(w[i] - f) < 1e-10 and abs(amp[i] - a) < 1e-8


def test_analyse_counts_two_frequencies_on_a_two_torus():
    dt = 0.5
    t = np.arange(4097) * dt
    z = _torus_signal(t)
    spec = naff.analyse([z], dt)
    assert spec.count == 2
    assert spec.diffusion < 1e-9
    lattice = (W1, W2, W1 + W2, abs(W1 - 2 * W2))
    assert all(min(abs(f - g) for g in lattice) < 1e-9 for f in spec.frequencies)


def test_constant_signal_has_no_line():
    z = np.full(1001, 0.3 + 0.1j) + 1e-12 * np.sin(np.arange(1001))
    w, _ = naff.spectral_lines(z, 0.5)
    assert len(w) == 0


def test_integer_relation_counter():
    s2, s3 = math.sqrt(2), math.sqrt(3)
    assert len(naff.independent_frequencies([1.0, s2, 1 + s2, 2 - 3 * s2, 0.0], 1e-9)) == 2
    assert len(naff.independent_frequencies([1.0, s2, s3, s2 + s3], 1e-9)) == 3
    # a half-frequency is dependent (2 f = basis) with c0 = 2
    assert len(naff.independent_frequencies([1.0, 0.5], 1e-9)) == 1
    # off by 100 x tol: independent; within tol: dependent
    assert len(naff.independent_frequencies([1.0, s2, 1 + s2 + 1e-7], 1e-9)) == 3
    assert len(naff.independent_frequencies([1.0, s2, 1 + s2 + 1e-10], 1e-9)) == 2
    # coefficients beyond K are not searched
    assert len(naff.independent_frequencies([1.0, s2, 5 * s2 + 1], 1e-9, K=4)) == 3


def test_control_kernel_solves_the_definition_and_matches_the_axisymmetric_one():
    a, b = -0.5, 0.5
    M, g = families.draw("generic", 4, a, b, seed=5, count=3)
    axi = general_inertia_kernels([1, 1, 1, 1 + a], b).angular_velocity(M, g, a, b)
    assert np.max(np.abs(axi - active().angular_velocity(M, g, a, b))) < 1e-13
    J = fq.CONTROL_J
    Om = general_inertia_kernels(J, b).angular_velocity(M, g, a, b)
    assert np.max(np.abs(L_gamma_general(Om, g, J, b) - M)) < 1e-13


def test_level_set_points_share_the_integrals():
    M, g = families.draw("generic", 4, fq.A, fq.B, seed=fq.SEED, count=4)
    from chaplygin_nd.simulate.dynamics.so import reduced_invariants

    r0 = reduced_invariants(M, g)[3]
    pts = level_set_points(r0, (0.05, 0.1), fq.A, fq.B)
    ref = _reduced_constraints(r0, fq.A, fq.B)
    for p in pts:
        assert np.max(np.abs(_reduced_constraints(p, fq.A, fq.B) - ref)) < 1e-12
        assert np.linalg.norm(p - r0) > 0.04


def test_control_separates_on_short_orbits(tmp_path, monkeypatch):
    """Threshold fixed beforehand (simulate/analysis/frequencies.py): control D >= 100 x regular D."""
    monkeypatch.setenv("CHAPLYGIN_ND_CACHE", str(tmp_path))
    reg = replace(fq.reduced_experiment(t_end=1024.0, rtol=1e-9), members=(3,), level_shifts=())
    ctl = replace(fq.control_experiment(t_end=1024.0, rtol=1e-9), members=(3,))
    d_reg = [s.diffusion for s in fq.spectra(reg)]
    d_ctl = [s.diffusion for s in fq.spectra(ctl)]
    assert max(d_reg) < fq.REGULAR
    assert fq.separates(d_reg, d_ctl), (d_reg, d_ctl)
    # the cache returns the same orbits
    again = orbits(reg)
    assert again.cached and np.array_equal(again.y, orbits(reg).y)
    assert len(signals(again, 0)) == 2


def test_evidence_verdict_needs_its_fields_and_a_separating_control():
    kw = dict(measured="m", initial_conditions=3, tolerance="t", contradiction="c", control="k",
              method="numerical")
    assert Verdict.numerical(True, control_separates=True, **kw).verdict == "evidence"
    assert Verdict.numerical(True, control_separates=False, **kw).verdict == "open"
    assert Verdict.numerical(False, control_separates=True, **kw).verdict == "open"
    with pytest.raises(ValueError):
        Verdict("evidence", "numerical")


def test_tori_scene_plans_the_full_system_for_frequencies_only():
    from chaplygin_nd.simulate.scene.planner import plan
    from chaplygin_nd.simulate.scene.spec import SceneError, load, loads

    scene = load(Path(__file__).resolve().parent.parent / "scenes" / "tori4d.toml")
    assert scene.count == 4
    p = plan(scene)
    assert p.model == "full" and "frequencies on P" in p.reason
    text = ('n = 4\na = -0.5\nb = 0.5\n[initial]\nfamily = "generic"\nseed = 3\n'
            'members = [3, 1]\n[times]\nt_end = 10.0\nsamples = 64\n[outputs]\nwant = ["poincare"]\n')
    s2 = loads(text)
    assert plan(s2).model == "reduced-7D"
    M, g = families.draw("generic", 4, -0.5, 0.5, 3, count=4)
    assert np.array_equal(s2.M0, M[[3, 1]]) and np.array_equal(s2.gamma0, g[[3, 1]])
    with pytest.raises(SceneError):
        loads(text.replace("members = [3, 1]", "members = [-1]"))
    with pytest.raises(SceneError):
        loads(text.replace("n = 4", "n = 5"))
