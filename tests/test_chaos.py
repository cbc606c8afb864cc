"""The chaos indicator (simulate/analysis/chaos.py), the general-J heyoka control, the drawn initial
conditions and the vectorised NAFF.

MEGNO is checked where it is known in closed form (a shear flow: <Y> -> 2; a saddle:
<Y> ~ lambda T / 2, Lyapunov exponent lambda), then on the sphere: an orbit of the integrable
axisymmetric n = 4 sphere stays near 2 and a control orbit grows past the chaos threshold."""

from __future__ import annotations

import numpy as np
import pytest
from chaplygin_nd.simulate.analysis import chaos, draws, naff
from chaplygin_nd.simulate.analysis.control import (
    CHAOTIC_J,
    general_inertia_kernels,
    general_system,
)
from chaplygin_nd.simulate.analysis.drawn_evidence import Setting, classify, measure
from chaplygin_nd.simulate.dynamics import so
from chaplygin_nd.simulate.integrators.heyoka_systems import System

hy = pytest.importorskip("heyoka")


def _megno_of(system, y0, pars, T, dt=0.05, tol=1e-13):
    """(<Y>(T), l(T)/T, the initial tangent) of one orbit of ``system`` (double, no cache)."""
    from chaplygin_nd.runtime.expressions import HeyokaArithmetic

    tsys = chaos.tangent_system(system)
    ops = HeyokaArithmetic(hy, "double", 53)
    u0 = chaos.initial_tangents(1, system.dim, 1)[0]
    ta = hy.taylor_adaptive(tsys.equations(hy, ops), np.concatenate([y0, u0, [0.0, 0.0]]),
                            pars=list(pars), tol=tol, compact_mode=True)
    t = np.arange(int(round(T / dt)) + 1) * dt
    _, _, _, _, _, states = ta.propagate_grid(t)
    ell, m = chaos.unscaled(states)
    return chaos.megno_from_samples(t, m), ell[-1] / T, u0


def test_megno_of_a_shear_flow_tends_to_two():
    """theta' = I, I' = 0: tangent vectors grow linearly, <Y> -> 2 (within 0.03 at T = 2000)."""
    shear = System("shear", ("theta", "I"), (), lambda v, p, ops: [v[1], 0])
    y, lam, _ = _megno_of(shear, np.array([0.1, 0.7]), [], 2000.0, dt=0.5)
    assert abs(y - 2.0) < 0.03
    assert abs(lam) < 0.01


def test_the_tangent_system_keeps_the_stated_tolerance_on_the_state():
    r"""A twist $\dot z = i(1 + |z|^2)z$ (a torus whose frequency depends on the amplitude, so phase
    errors accumulate; exact solution $z_0e^{i(1+|z_0|^2)t}$) carried with the MEGNO tangent at
    tolerance $10^{-10}$ to $T = 512$: the state stays within $5\cdot10^{-8}$ of the closed form. With
    $m$ carried unscaled ($m \approx t$, so heyoka's error control turns relative to it) the same run
    was $7.6\cdot10^{-7}$ off; scaled, $4.8\cdot10^{-9}$. The carried moment and log stay far below 1."""
    from chaplygin_nd.runtime.expressions import HeyokaArithmetic

    def field(v, p, ops):
        w = 1 + v[0] * v[0] + v[1] * v[1]
        return [-w * v[1], w * v[0]]

    tsys = chaos.tangent_system(System("twist", ("x", "y"), (), field))
    ops = HeyokaArithmetic(hy, "double", 53)
    u0 = chaos.initial_tangents(1, 2, 1)[0]
    ta = hy.taylor_adaptive(tsys.equations(hy, ops), np.concatenate([[0.6, 0.0], u0, [0.0, 0.0]]),
                            tol=1e-10, compact_mode=True)
    t = np.arange(1025) * 0.5
    states = ta.propagate_grid(t)[-1]
    w = 1 + 0.6 ** 2
    exact = np.stack([0.6 * np.cos(w * t), 0.6 * np.sin(w * t)], axis=1)
    assert np.abs(states[:, :2] - exact).max() < 5e-8
    assert np.abs(states[:, -2:]).max() < 1e-3
    ell, m = chaos.unscaled(states)
    assert np.array_equal(ell * chaos.LOG_SCALE, states[:, -2])      # powers of two: exact
    assert 1.5 < chaos.megno_from_samples(t, m) < 2.0                 # a torus: <Y> rises to 2


def test_megno_of_a_saddle_matches_its_closed_form():
    r"""x' = lam x, y' = -lam y: $\|\delta(t)\|^2 = u_x^2e^{2\lambda t} + u_y^2e^{-2\lambda t}$, so
    $\ell(T)$ and $\sigma(t) = \frac{d}{dt}\ln\|\delta\|$ are known; <Y> from that sigma by quadrature
    on the same grid. For large T, <Y> ~ lam T / 2 (chaotic by the rule)."""
    import scipy.integrate

    lam, T, dt = 0.5, 40.0, 0.05
    saddle = System("saddle", ("x", "y"), ("lam",), lambda v, p, ops: [p[0] * v[0], -p[0] * v[1]])
    y, lyap, u = _megno_of(saddle, np.array([1e-3, 1e-3]), [lam], T, dt=dt)
    ux2, uy2 = u[0] ** 2, u[1] ** 2
    ell = 0.5 * np.log(ux2 * np.exp(2 * lam * T) + uy2 * np.exp(-2 * lam * T))
    assert abs(lyap * T - ell) < 1e-8
    sigma = lambda s: lam * (ux2 * np.exp(2 * lam * s) - uy2 * np.exp(-2 * lam * s)) / (  # noqa: E731
        ux2 * np.exp(2 * lam * s) + uy2 * np.exp(-2 * lam * s))
    t = np.arange(int(round(T / dt)) + 1) * dt
    m = np.concatenate([[0.0], np.cumsum([scipy.integrate.quad(lambda s: s * sigma(s), a, b,
                                                               epsabs=1e-13)[0]
                                          for a, b in zip(t[:-1], t[1:])])])
    assert abs(y - chaos.megno_from_samples(t, m)) < 1e-8
    assert abs(y - lam * T / 2) < 0.15 * lam * T / 2
    assert chaos.megno_class(y) == "chaotic"


def test_megno_rule_classes():
    assert chaos.megno_class(1.98) == "regular"
    assert chaos.megno_class(0.0) == "regular"       # isochronous periodic orbit
    assert chaos.megno_class(3.0) == "undecided"
    assert chaos.megno_class(12.0) == "chaotic"
    assert chaos.megno_class(float("nan")) == "undecided"


@pytest.mark.parametrize("n", [4, 5])
def test_general_J_system_matches_the_linear_solve(n):
    """control.general_system (the n x n solve for v = Omega gamma, LDL^T as heyoka expressions)
    against DOP853 on the NumPy solve of the whole matrix of L_gamma."""
    from chaplygin_nd.simulate.dynamics.field import FullField
    from chaplygin_nd.simulate.integrators import dop853, heyoka_taylor

    J, a, b = CHAOTIC_J[n], -0.5, 2.0
    ens = draws.draw("test-control", "generic", n, 2, seed=5)
    f = FullField(n, a, b, kernels=general_inertia_kernels(J, b))
    y0 = f.pack(ens.M0, ens.gamma0)
    t = np.linspace(0.0, 5.0, 11)
    sol = heyoka_taylor.integrate(general_system(J), y0, t, tol=1e-13, pars=[a, b], compact=True,
                                  cache=False)
    ref = dop853.integrate(f, y0, t, rtol=1e-12, atol=1e-12)
    assert np.max(np.abs(sol.y - ref.y)) < 1e-9


def test_megno_separates_the_sphere_from_its_control(tmp_path, monkeypatch):
    """One drawn orbit each: the axisymmetric n = 4 sphere (integrable) stays MEGNO-regular at
    T = 2048; the control J = CHAOTIC_J[4] at b = 2 (where 7 of 8 pilot orbits were chaotic) is
    MEGNO-chaotic at T = 4096."""
    monkeypatch.setenv("CHAPLYGIN_ND_CACHE", str(tmp_path))
    ens = draws.draw("test-megno", "generic", 4, 1, seed=11, a_values=(-0.5,), b_values=(2.0,),
                     scales=(1.0,))
    y0 = np.concatenate([so.vec(ens.M0), ens.gamma0], axis=-1)
    sym = measure(Setting("t-sym", "full", 4, 2048.0, 0.5, observables="four", expected=3), ens,
                  y0, 1, use_cache=False)[0]
    ctl = measure(Setting("t-ctl", "control", 4, 4096.0, 0.5, observables="four",
                          J=CHAOTIC_J[4]), ens, y0, 1, use_cache=False)[0]
    assert sym.megno_cls == "regular", sym
    assert abs(sym.megno - 2.0) < 0.5
    assert ctl.megno_cls == "chaotic", ctl
    assert ctl.lyapunov > 5 * sym.lyapunov


def test_draws_are_reproducible_and_cover_the_grid():
    e1 = draws.draw("x", "generic", 4, 24, seed=3)
    e2 = draws.draw("x", "generic", 4, 24, seed=3)
    e3 = draws.draw("x", "generic", 4, 24, seed=4)
    assert np.array_equal(e1.M0, e2.M0) and not np.array_equal(e1.M0, e3.M0)
    assert set(e1.a) == set(draws.A_VALUES) and set(e1.b) == set(draws.B_VALUES)
    assert set(e1.scale) == set(draws.SCALES)
    norms = np.sqrt(so.killing(e1.M0, e1.M0))
    assert np.allclose(norms, e1.scale)
    v = draws.draw("v", "vertical", 5, 4, seed=3)
    assert np.max(np.abs(np.einsum("kij,kj->ki", v.M0, v.gamma0))) < 1e-12


def test_vectorised_naff_agrees_with_pynaff():
    dt = 0.5
    t = np.arange(4097) * dt
    w1, w2 = 0.7310412, 0.1892347
    rng = np.random.default_rng(0)
    Z = []
    for _ in range(6):
        c = rng.standard_normal(3) + 1j * rng.standard_normal(3)
        Z.append(c[0] * np.exp(1j * w1 * t) + c[1] * np.exp(-1j * w2 * t)
                 + 0.3 * c[2] * np.exp(1j * (w1 + 2 * w2) * t))
    Z = np.array(Z)
    for (w, amp), z in zip(naff.spectral_lines_batch(Z, dt, terms=4), Z):
        w0, amp0 = naff.spectral_lines(z, dt, terms=4)
        for f in (w1, -w2, w1 + 2 * w2):
            assert np.min(np.abs(w - f)) < 1e-10
            assert np.min(np.abs(w0 - f)) < 1e-10
        assert np.allclose(np.sort(amp)[-3:], np.sort(amp0)[-3:], rtol=1e-6)
    specs = naff.analyse_batch(Z[:, None, :], dt)
    assert [s.count for s in specs] == [2] * 6
    assert max(s.diffusion for s in specs) < 1e-9
    assert naff.spectral_lines_batch(np.full((1, 101), 0.3 + 0j), dt)[0][0].size == 0


def test_classes_follow_the_rule():
    reg = naff.Spectrum([], [0.1, 0.3], 1e-8, 1e-7)
    assert classify(reg, 2) == "predicted"
    assert classify(reg, 3) == "resonant"
    assert classify(reg, 1) == "excess"
    assert classify(naff.Spectrum([], [0.1, 0.3], 1e-3, 1e-2), 2) == "unresolved"
    assert classify(reg, None) == "regular"


# -- the horizon ladder, the tangent growth, the controls ----------------------------------------------

def _ladder_of(system, y0, pars, T, dt=0.5):
    """<Y> at T/8, T/4, T/2, T of one orbit (heyoka, the module's tangent system)."""
    import heyoka as hy
    from chaplygin_nd.runtime.expressions import HeyokaArithmetic

    tsys = chaos.tangent_system(system)
    ops = HeyokaArithmetic(hy, "double", 53)
    u0 = chaos.initial_tangents(1, system.dim, 1)[0]
    ta = hy.taylor_adaptive(tsys.equations(hy, ops), np.concatenate([y0, u0, [0.0, 0.0]]),
                            pars=list(pars), tol=1e-12, compact_mode=True)
    t = np.arange(int(round(T / dt)) + 1) * dt
    _, _, _, _, _, states = ta.propagate_grid(t)
    return chaos.megno_ladder(t, chaos.unscaled(states)[1])


def test_power_law_tangent_growth_is_bounded_not_chaos():
    """x' = y, y' = z, z' = 0: tangent vectors grow like t^2, <Y> -> 2p = 4 — the value the old
    single threshold (>= 4) called chaotic and that the V orbits show in the whole space. The ladder
    sees it settle: regular."""
    chain = System("chain", ("x", "y", "z"), (), lambda v, p, ops: [v[1], v[2], 0])
    ladder = _ladder_of(chain, np.array([0.0, 0.3, 0.2]), [], 4000.0)
    # <Y> = 4 - O(log t / t): from below, slowly, and settled over the last doubling
    assert 3.9 < ladder[-1] < 4.0 and np.all(np.diff(ladder) > 0)
    assert chaos.ladder_class(ladder) == "regular"
    shear = System("shear", ("theta", "I"), (), lambda v, p, ops: [v[1], 0])
    assert chaos.ladder_class(_ladder_of(shear, np.array([0.1, 0.7]), [], 2000.0)) == "regular"


def test_exponential_growth_is_chaos_on_the_ladder():
    saddle = System("saddle", ("x", "y"), ("lam",), lambda v, p, ops: [p[0] * v[0], -p[0] * v[1]])
    ladder = _ladder_of(saddle, np.array([1e-3, 1e-3]), [0.05], 400.0, dt=0.1)
    # <Y> ~ lam t / 2: doubles with the horizon
    assert abs(ladder[-1] - ladder[-2] - 0.05 * 400 / 4) < 1.0
    assert chaos.ladder_class(ladder) == "chaotic"
    assert chaos.ladder_class([1.0, 1.5, 2.5, 3.9]) == "undecided"   # grew, not yet beyond 4
    assert chaos.ladder_class([1.9, 2.0, 2.0, float("nan")]) == "undecided"


def test_the_standard_map_ties_the_scale_to_its_lyapunov_exponent():
    """Chirikov's standard map at K = 10: lambda = ln(K/2) + O(K^-2); 2 x the slope of <Y> over the
    last doubling must give it (within 3 %); the twist map K = 0 is regular by the ladder."""
    from chaplygin_nd.bench.bench_evidence import standard_map

    chaotic = standard_map(10.0, 32, 2048)
    slopes = [2 * (y[3] - y[2]) / 1024 for y in chaotic["ladder"]]
    assert abs(np.mean(slopes) - np.log(5.0)) < 0.03 * np.log(5.0)
    assert all(chaos.ladder_class(y) == "chaotic" for y in chaotic["ladder"])
    twist = standard_map(0.0, 32, 2048)
    assert all(chaos.ladder_class(y) == "regular" for y in twist["ladder"])


def test_tangents_of_V_satisfy_the_linearised_constraints():
    from chaplygin_nd.simulate.analysis.drawn_evidence import v_tangents

    ens = draws.draw("v-tangent", "vertical", 6, 5, seed=3)
    y0 = np.concatenate([so.vec(ens.M0), ens.gamma0], axis=-1)
    u = v_tangents(chaos.initial_tangents(5, y0.shape[1], 2), y0, 6)
    N = so.so_dim(6)
    dM, dg = so.unvec(u[:, :N], 6), u[:, N:]
    lin = np.einsum("kij,kj->ki", dM, ens.gamma0) + np.einsum("kij,kj->ki", ens.M0, dg)
    assert np.max(np.abs(lin)) < 1e-12
    assert np.max(np.abs(np.einsum("ki,ki->k", dg, ens.gamma0))) < 1e-12
    assert np.allclose(np.linalg.norm(u, axis=1), 1.0)


def test_large_combinations_are_explained_with_their_false_match_chance():
    from chaplygin_nd.simulate.analysis import combinations as cb

    w = [0.1234567, 0.3141593, 0.0271828]
    f = abs(7 * w[0] - 11 * w[1] + 5 * w[2])
    assert cb.explain(f, w, 1e-9) in ((7, -11, 5), (-7, 11, -5))     # |f| = |c . w|: up to sign
    assert cb.explain(f + 1e-4, w, 1e-9) is None
    p = cb.false_match(w, 1e-9, 1.0)
    assert 0 < p < 2 * 1e-9 * 25 ** 3                        # below the counting bound
    lines = [(w[0], 1.0), (-w[1], 0.8), (w[2], 0.5), (f, 0.2)]
    basis, info = cb.recount(lines, 1e-9, 6)
    assert sorted(basis) == sorted(w) and info["large"] == 1 and not info["ambiguous"]
    # the same line at a coarse tolerance: a match is likely by chance, so it is not credible
    basis, info = cb.recount(lines, 1e-4, 6)
    assert info["p_false"] > cb.CREDIBLE and info["ambiguous"] == 1 and len(basis) == 3
