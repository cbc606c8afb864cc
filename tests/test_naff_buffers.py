"""The NAFF line loop with kept buffers (in-place FFT, conjugated outer product, no residual after
the last line) returns the very bits of the earlier loop (the reference kept in bench/bench_naff.py)
on seeded signals of the evidence rows' kinds of length; also when calls of other shapes come in between
and when two threads run it at once."""

from __future__ import annotations

import threading

import numpy as np
import pytest
from chaplygin_nd.bench.bench_naff import earlier_find_lines
from chaplygin_nd.simulate.analysis import naff, naff_lines


def _reference_lines(Z, dt, terms=12, constant=1e-6, floor=1e-9, newton=4):
    """The earlier ``naff.spectral_lines_batch`` (on the reference loop)."""
    from scipy.fft import next_fast_len

    Z = np.asarray(Z, dtype=complex)
    K, N = Z.shape
    size = np.max(np.abs(Z), axis=1)
    R = Z - Z.mean(axis=1, keepdims=True)
    scale = np.max(np.abs(R), axis=1)
    live = (scale > constant * size) & (scale > 0)
    w = naff_lines._hann2(N)
    P, L = naff_lines._blocks(N)
    pad = next_fast_len(N)
    found_w, found_a = np.zeros((K, terms)), np.zeros((K, terms))
    with naff_lines._one_blas_thread():
        earlier_find_lines(R, w, dt, pad, P, L, terms, newton, found_w, found_a)
    out = []
    for k in range(K):
        if not live[k]:
            out.append((np.zeros(0), np.zeros(0)))
            continue
        order = np.argsort(-found_a[k], kind="stable")
        wk, ak = found_w[k][order], found_a[k][order]
        keep = ak > floor * scale[k]
        out.append((wk[keep], ak[keep]))
    return out


def _signals(rows: int, N: int, dt: float, seed: int) -> np.ndarray:
    """Seeded quasi-periodic signals (6 lines on a 3-frequency lattice, 1e-9 noise), one of them
    constant (no line) and one real (a spectrum symmetric in frequency: tied peaks)."""
    rng = np.random.default_rng(seed)
    t = np.arange(N) * dt
    Z = np.zeros((rows, N), complex)
    for k in range(rows):
        f = rng.uniform(0.05, 2.0, 3)
        for _ in range(6):
            c = rng.integers(-2, 3, 3)
            Z[k] += rng.uniform(0.05, 1.0) * np.exp(1j * (c @ f) * t + 1j * rng.uniform(0, 2 * np.pi))
    Z += 1e-9 * (rng.standard_normal(Z.shape) + 1j * rng.standard_normal(Z.shape))
    Z[0] = 0.3 + 0.1j
    Z[1] = np.cos(0.7 * t) + 0.25 * np.cos(1.9 * t)
    return Z


def _bits(lines) -> list[bytes]:
    return [x.tobytes() for pair in lines for x in pair]


@pytest.mark.parametrize("N, dt, terms", [(2049, 0.5, 8), (1024, 0.5, 4), (1500, 1.25, 6),
                                          (961, 1.0, 3)])
def test_kept_buffers_give_the_bits_of_the_earlier_loop(N, dt, terms):
    Z = _signals(12, N, dt, seed=N)
    ref = _reference_lines(Z, dt, terms)
    assert sum(len(w) for w, _ in ref) >= 10 * terms        # lines were found, not nothing
    assert _bits(naff.spectral_lines_batch(Z, dt, terms)) == _bits(ref)


def test_kept_buffers_survive_calls_of_other_shapes():
    """A large call, a small one, a wider one: each equals the reference (a buffer grown or
    reused keeps no stale padding)."""
    for rows, N, dt in [(10, 2049, 0.5), (4, 300, 0.3), (16, 1200, 0.7), (10, 2049, 0.5)]:
        Z = _signals(rows, N, dt, seed=rows * N)
        assert _bits(naff.spectral_lines_batch(Z, dt, 5)) == _bits(_reference_lines(Z, dt, 5))


def test_lines_batch_halves_equal_the_reference():
    """``lines_batch`` (whole signal and both halves) on an ensemble ``(orbits, signals, N)``."""
    Z = _signals(12, 1601, 0.5, seed=7).reshape(3, 4, 1601)
    whole, first, second = naff.lines_batch(Z, 0.5)
    flat = Z.reshape(12, 1601)
    parts = (_reference_lines(flat, 0.5, 8), _reference_lines(flat[:, :800], 0.5, 4),
             _reference_lines(flat[:, 800:1600], 0.5, 4))
    for got, ref in zip((whole, first, second), parts):
        assert _bits([x for orbit in got for x in orbit]) == _bits(ref)


def test_two_threads_do_not_share_buffers():
    Za, Zb = _signals(8, 1800, 0.5, seed=1), _signals(8, 1800, 0.5, seed=2)
    ref = {"a": _bits(_reference_lines(Za, 0.5, 6)), "b": _bits(_reference_lines(Zb, 0.5, 6))}
    got: dict = {}

    def work(key, Z):
        got[key] = [_bits(naff.spectral_lines_batch(Z, 0.5, 6)) for _ in range(3)]

    threads = [threading.Thread(target=work, args=a) for a in (("a", Za), ("b", Zb))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert got["a"] == [ref["a"]] * 3 and got["b"] == [ref["b"]] * 3


def test_frozen_rows_are_not_recomputed_and_keep_their_bits(monkeypatch):
    """Newton's rows whose frequency no longer moves keep their projections; the rows still
    moving are recomputed one by one (the path is taken here) and the lines keep their bits."""
    Z = _signals(16, 2049, 0.5, seed=3)
    ref = _reference_lines(Z, 0.5, 6)
    sizes: list[int] = []
    original = naff_lines._projections

    def counted(X, *args):
        sizes.append(len(X))
        return original(X, *args)

    monkeypatch.setattr(naff_lines, "_projections", counted)
    assert _bits(naff.spectral_lines_batch(Z, 0.5, 6)) == _bits(ref)
    assert 1 in sizes and sum(sizes) < 16 * 6 * 5      # fewer rows than 5 products per line
