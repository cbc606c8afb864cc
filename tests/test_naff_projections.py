"""Issue 20: the faster vectorised NAFF (BLAS products, one windowed buffer) equals the earlier
``einsum`` formulation, and the batch packing and width of the drawn evidence change no orbit."""

from __future__ import annotations

import numpy as np
import pytest
from chaplygin_nd.simulate.analysis import naff, naff_lines


def _einsum_projections(X, nu, dt, L, derivatives):
    """The earlier formulation of ``naff_lines._projections``, kept as the reference."""
    K, P, _ = X.shape
    p = np.arange(P) * (L * dt)
    l_ = np.arange(L) * dt
    alpha = np.exp(-1j * nu[:, None] * p[None])
    beta = np.exp(-1j * nu[:, None] * l_[None])
    if not derivatives:
        phi = np.einsum("kp,kp->k", alpha, np.einsum("kpl,kl->kp", X, beta))
        return phi, alpha, beta
    B = np.stack([beta, beta * l_[None], beta * (l_ ** 2)[None]], axis=-1)
    XB = np.einsum("kpl,klj->kpj", X, B)
    Xb, Xbl, Xbll = XB[..., 0], XB[..., 1], XB[..., 2]
    phi = np.einsum("kp,kp->k", alpha, Xb)
    d1 = np.einsum("kp,kp->k", alpha, p[None] * Xb + Xbl)
    d2 = np.einsum("kp,kp->k", alpha, (p ** 2)[None] * Xb + 2 * p[None] * Xbl + Xbll)
    return phi, -1j * d1, -d2


def _einsum_lines(Z, dt, terms, newton=4):
    """The earlier loop of ``naff.spectral_lines_batch`` on the einsum projections:
    ``(omega, amplitude)`` of every row, in the order found (no sorting, no floor)."""
    Z = np.asarray(Z, dtype=complex)
    K, N = Z.shape
    R = Z - Z.mean(axis=1, keepdims=True)
    w = naff_lines._hann2(N)
    P, L = naff_lines._blocks(N)
    from scipy.fft import next_fast_len

    pad = next_fast_len(N)
    omega_grid = 2 * np.pi * np.fft.fftfreq(pad, d=dt)
    found_w, found_a = np.zeros((K, terms)), np.zeros((K, terms))
    idx = np.arange(K)
    for m in range(terms):
        spec = np.abs(np.fft.fft(R * w[None], n=pad, axis=1))
        i = np.argmax(spec, axis=1)
        y0, y1, y2 = (np.log(spec[idx, (i + s) % pad] + 1e-300) for s in (-1, 0, 1))
        den = y0 - 2 * y1 + y2
        shift = np.where(np.abs(den) > 0, 0.5 * (y0 - y2) / np.where(den == 0, 1, den), 0.0)
        nu = omega_grid[i] + shift * (2 * np.pi / (pad * dt))
        X = np.zeros((K, P * L), dtype=complex)
        X[:, :N] = R * w[None]
        X = X.reshape(K, P, L)
        for _ in range(newton):
            phi, d1, d2 = _einsum_projections(X, nu, dt, L, True)
            g = 2 * np.real(np.conj(phi) * d1)
            h = 2 * np.real(np.abs(d1) ** 2 + np.conj(phi) * d2)
            step = np.where(h < 0, g / np.where(h == 0, 1, h), 0.0)
            nu = nu - np.clip(step, -np.pi / (N * dt), np.pi / (N * dt))
        phi, alpha, beta = _einsum_projections(X, nu, dt, L, False)
        found_w[:, m], found_a[:, m] = nu, np.abs(phi)
        line = np.conj(alpha[:, :, None] * beta[:, None, :]).reshape(K, P * L)[:, :N]
        R -= phi[:, None] * line
    return found_w, found_a


def _signals(rows: int, N: int, dt: float, seed: int) -> np.ndarray:
    """Random quasi-periodic signals: 5 lines on a 3-frequency lattice, random amplitudes and
    phases, plus 1e-9 noise."""
    rng = np.random.default_rng(seed)
    t = np.arange(N) * dt
    Z = np.zeros((rows, N), complex)
    for k in range(rows):
        f = rng.uniform(0.05, 2.0, 3)
        for _ in range(5):
            c = rng.integers(-2, 3, 3)
            Z[k] += rng.uniform(0.05, 1.0) * np.exp(1j * (c @ f) * t + 1j * rng.uniform(0, 2 * np.pi))
    return Z + 1e-9 * (rng.standard_normal(Z.shape) + 1j * rng.standard_normal(Z.shape))


@pytest.mark.parametrize("derivatives", [True, False])
def test_blas_projections_equal_the_einsum_formulation(derivatives):
    rng = np.random.default_rng(20)
    K, P, L = 9, 37, 41
    X = rng.standard_normal((K, P, L)) + 1j * rng.standard_normal((K, P, L))
    nu = rng.uniform(-3, 3, K)
    new, old = naff_lines._projections(X, nu, 0.5, L, derivatives), _einsum_projections(X, nu, 0.5, L, derivatives)
    for a, b in zip(new, old):
        assert np.max(np.abs(a - b)) <= 1e-12 * np.max(np.abs(b))


@pytest.mark.parametrize("N, dt", [(2049, 0.5), (1500, 1.25)])
def test_lines_equal_the_einsum_formulation_on_random_signals(N, dt):
    Z = _signals(24, N, dt, seed=N)
    terms = 8
    ref_w, ref_a = _einsum_lines(Z, dt, terms)
    new = naff.spectral_lines_batch(Z, dt, terms, floor=0.0)
    compared = 0
    for k, (w, a) in enumerate(new):
        order = np.argsort(-ref_a[k], kind="stable")
        rw, ra = ref_w[k][order], ref_a[k][order]
        strong = ra >= 1e-3 * ra[0]                 # the signal's lines, not fits of the noise
        assert len(w) == terms
        np.testing.assert_allclose(w[strong], rw[strong], rtol=0, atol=1e-12 * np.max(np.abs(rw)))
        np.testing.assert_allclose(a[strong], ra[strong], rtol=1e-12)
        compared += int(strong.sum())
    assert compared >= 24 * 5                        # every planted line was compared


def test_the_batch_packing_and_width_change_no_orbit(tmp_path, monkeypatch):
    pytest.importorskip("heyoka")
    from chaplygin_nd.simulate.analysis import drawn_evidence as de
    from chaplygin_nd.simulate.analysis import draws, packing
    from chaplygin_nd.simulate.dynamics import so

    monkeypatch.setenv("CHAPLYGIN_ND_CACHE", str(tmp_path))
    ens = draws.draw("schedule test", "generic", 4, 11, 5)  # 11 orbits: padded last batches
    y0 = np.concatenate([so.vec(ens.M0), ens.gamma0], axis=-1)
    s = de.Setting("schedule", "full", 4, 48.0, 0.5, observables="four", expected=3)
    order = de.schedule(ens)
    assert sorted(order) == list(range(11)) and not np.array_equal(order, np.arange(11))
    packed = []
    pack = packing.order
    monkeypatch.setattr(packing, "order", lambda *a, **k: packed.append(pack(*a, **k)) or packed[-1])
    Z, megno, lyap, extra = de._integrate(s, ens, y0, 5)   # packed by the pilot's steps
    (used,) = packed
    assert sorted(used) == list(range(11))
    assert not np.array_equal(used, order) and not np.array_equal(used, np.arange(11))
    monkeypatch.setattr(packing, "order", lambda ta, states, *a, **k: np.arange(len(states)))
    monkeypatch.setattr(de, "BATCH", 4)            # draw order, and another SIMD width
    Z0, megno0, lyap0, extra0 = de._integrate(s, ens, y0, 5)
    assert np.array_equal(Z, Z0) and np.array_equal(megno, megno0) and np.array_equal(lyap, lyap0)
    for key in ("ladder", "power", "drift", "steps", "final"):   # the ladder and the integrals too
        assert np.array_equal(extra[key], extra0[key]), key


@pytest.mark.parametrize("N", [8193, 4096, 2049])
def test_scipy_fft_is_numpy_fft_bit_for_bit(N):
    """NAFF's peak search takes scipy.fft (faster on a batch) for numpy.fft: the same pocketfft,
    the same bits, at the sample counts of the evidence rows (T, its halves, the ladder's)."""
    from scipy.fft import fft, next_fast_len

    rng = np.random.default_rng(N)
    X = rng.standard_normal((7, N)) + 1j * rng.standard_normal((7, N))
    pad = next_fast_len(N)
    assert np.array_equal(fft(X, n=pad, axis=1), np.fft.fft(X, n=pad, axis=1))
