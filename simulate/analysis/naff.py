r"""Frequency analysis of sampled orbits: NAFF spectral lines, the number of independent
frequencies (an integer-relation search), and Laskar's frequency diffusion.

Numerical Analysis of Fundamental Frequencies (Laskar, Icarus 88 (1990); Physica D 67 (1993)):
a quasi-periodic signal $z(t) = \sum_k c_k e^{i\langle k, \omega\rangle t}$ is decomposed line by line
(Hann window of order 2, each frequency refined by maximising $|\langle z, e^{i\nu t}\rangle|$ and
subtracted by Gram–Schmidt). On a torus of dimension $d$ every line lies on the lattice
$\{\langle k, \omega\rangle : k \in \mathbb{Z}^d\}$; the number of independent frequencies is the rank of
the lines over $\mathbb{Z}$, found here by an exhaustive bounded integer search.

Library: ``PyNAFF`` (PyPI ``PyNAFF``), chosen over ``nafflib`` after measuring both on
$z_n = e^{2\pi i f_1 n} + \tfrac12 e^{2\pi i f_2 n} + \tfrac15 e^{2\pi i (f_1 + f_2) n} + \tfrac1{20}
e^{4\pi i f_2 n}$ (4 lines, 2 independent): the worst frequency error was $2.7\cdot10^{-14}$ vs
$1.4\cdot10^{-14}$ at $N = 2048$ samples and $7\cdot10^{-17}$ vs $3\cdot10^{-17}$ at $N = 8192$
(both at rounding level); time per call 0.05 s vs 0.02 s at $N = 8192$ (10 lines: 0.018 s vs
0.028 s). ``nafflib`` needs numba and pandas, costs 0.6 s to import and 2.9 s for its first
(JIT-compiling) call in every fresh process — more than all our analyses together in
``make verify``'s worker processes — and returns the conjugate frequencies (accelerator
convention $x - ip_x$). ``PyNAFF`` is pure NumPy. It warns when it stops because the residual
peak lies within one FFT bin of a found line; that is its documented stopping rule, so we
silence that one warning and report how many lines it returned.
"""

from __future__ import annotations

import functools
import itertools
import warnings
from dataclasses import dataclass

import numpy as np
from chaplygin_nd.simulate.analysis.naff_lines import _hann2, spectral_lines_batch

__all__ = ["spectral_lines", "independent_frequencies", "frequency_diffusion", "Spectrum",
           "analyse", "fundamental_frequencies"]


def spectral_lines(z: np.ndarray, dt: float, terms: int = 12, constant: float = 1e-6,
                   floor: float = 1e-9) -> tuple[np.ndarray, np.ndarray]:
    r"""NAFF lines of a uniformly sampled signal $z(t_0 + j\,dt)$: angular frequencies (rad per unit
    of time, signed, $|\omega| < \pi/dt$) and amplitudes, strongest first. The mean is removed
    first. A signal whose variation $\max|z - \bar z|$ is at most ``constant`` times $\max|z|$ is
    constant (an equilibrium up to the integration error) and has no line; otherwise lines with
    amplitude below ``floor`` times that variation are dropped. Domain: $\ge 7$ samples."""
    z = np.asarray(z, dtype=complex)
    size = float(np.max(np.abs(z))) if z.size else 0.0
    z = z - z.mean()
    scale = float(np.max(np.abs(z))) if z.size else 0.0
    if scale <= constant * size or scale == 0.0:
        return np.zeros(0), np.zeros(0)
    import PyNAFF

    turns = len(z) - 1
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message="PyNAFF stopped", category=UserWarning)
        out = PyNAFF.naff(z, turns=turns, nterms=terms, getFullSpectrum=True, window=2,
                          warnings=False)
    out = np.asarray(out, dtype=float).reshape(-1, 5)
    omega, amp = 2 * np.pi * out[:, 1] / dt, out[:, 2]
    keep = amp > floor * scale
    return omega[keep], amp[keep]


@functools.lru_cache(maxsize=32)
def _coefficient_grid(K: int, k: int) -> np.ndarray:
    """Every integer vector in $[-K, K]^k$ (rows, as floats, read-only), in ``itertools.product``
    order; built once per ``(K, k)`` (it was rebuilt on every call, 3 s of a cold evidence row)."""
    grid = np.array(list(itertools.product(range(-K, K + 1), repeat=k)), dtype=float)
    grid.flags.writeable = False
    return grid


def _relation(f: float, basis: list[float], tol: float, K: int) -> tuple[int, ...] | None:
    """Integers (c0, c1..ck), 1 <= c0 <= K, |ci| <= K, with |c0 f - sum ci bi| <= tol·c0, or None."""
    if not basis:
        return None
    grid = _coefficient_grid(K, len(basis))
    combos = grid @ np.asarray(basis)
    for c0 in range(1, K + 1):
        err = np.abs(c0 * f - combos)
        i = int(np.argmin(err))
        if err[i] <= tol * c0:
            return (c0,) + tuple(int(c) for c in grid[i])
    return None


def independent_frequencies(freqs, tol: float, K: int = 8, limit: int = 5) -> list[float]:
    r"""A maximal $\mathbb{Z}$-independent subset of ``freqs`` (taken in the given order, strongest
    first): a frequency $f$ joins the basis $b_1..b_k$ unless integers $1 \le c_0 \le K$, $|c_i| \le K$
    give $|c_0 f - \sum_i c_i b_i| \le c_0\,$``tol`` (exhaustive search, not PSLQ, so "no relation" means
    none exists within the bound). Zero frequencies ($|f| \le$ ``tol``) are dependent. The length
    of the result is the number of independent frequencies; the search stops at ``limit`` (the
    count then means "at least ``limit``"). Domain: finite floats, ``tol`` > 0."""
    basis: list[float] = []
    for f in freqs:
        if len(basis) >= limit:
            break
        f = float(f)
        if abs(f) <= tol or _relation(f, basis, tol, K) is not None:
            continue
        basis.append(f)
    return basis


def frequency_diffusion(signals, dt: float, lines: int = 3, terms: int = 8,
                        rel_amp: float = 0.05) -> float:
    r"""Laskar's regularity indicator: the NAFF lines of the first and of the second half of each
    signal, and for the ``lines`` strongest lines of the first half (ignoring $|\omega| <
    10^{-3}\max|\omega|$ and lines weaker than ``rel_amp`` times the strongest: those are rounding) the relative change $|\omega^{(2)} - \omega^{(1)}|/|\omega^{(1)}|$ to the nearest line
    of the second half; the maximum over signals and lines. On a torus it decreases like a
    power of the orbit length (the NAFF error); on a chaotic orbit the frequencies drift.
    Domain: signals of equal length $\ge 14$ samples; returns inf if a half has no line."""
    halves = [len(z) // 2 for z in signals]
    first = [spectral_lines(z[:h], dt, terms) for z, h in zip(signals, halves)]
    second = [spectral_lines(z[h:2 * h], dt, terms) for z, h in zip(signals, halves)]
    return diffusion_from_lines(first, second, lines, rel_amp)


@dataclass
class Spectrum:
    """The frequency analysis of one orbit: its pooled lines, the independent frequencies,
    their count and the frequency diffusion."""

    lines: list[tuple[float, float]]
    frequencies: list[float]
    diffusion: float
    tolerance: float = float("nan")  # relative tolerance of the integer-relation search

    @property
    def count(self) -> int:
        return len(self.frequencies)

    def to_dict(self) -> dict:
        return {"frequencies": self.frequencies, "count": self.count,
                "diffusion": self.diffusion, "tolerance": self.tolerance, "lines": self.lines}


def analyse(signals, dt: float, *, terms: int = 10, rel_amp: float = 0.05, tol: float = 1e-7,
            K: int = 4, precision_factor: float = 10.0) -> Spectrum:
    r"""NAFF on each signal of one orbit; the lines whose amplitude is at least ``rel_amp`` times the
    strongest line of their signal are pooled (strongest first) and reduced to independent
    frequencies with :func:`independent_frequencies`, coefficients $\le$ ``K``, relative tolerance
    $\max(\text{tol}, \text{precision\_factor}\cdot D)$ times the largest pooled $|\omega|$, where $D$ is
    the orbit's :func:`frequency_diffusion` (the measured precision of its strong lines). The
    chance that a random frequency falls within that tolerance of one of the $(2K+1)^k K$
    combinations of a $k$-frequency basis is about $2\,\text{tol}\,(2K+1)^kK/k$ (for $K = 4$, $k = 3$,
    $\text{tol} = 10^{-6}$: $2\cdot10^{-3}$ per line). Frequencies are reported as $|\omega|$."""
    return _spectrum([spectral_lines(z, dt, terms) for z in signals],
                     frequency_diffusion(signals, dt), rel_amp, tol, K, precision_factor)


def _spectrum(lines, diffusion: float, rel_amp: float, tol: float, K: int,
              precision_factor: float) -> Spectrum:
    """Pool the strong ``lines`` (pairs ``(omega, amplitude)``, one per signal) and count the
    independent frequencies at the tolerance the ``diffusion`` allows (see :func:`analyse`)."""
    pooled: list[tuple[float, float]] = []
    for w, amp in lines:
        if len(w) == 0:
            continue
        strong = amp >= rel_amp * amp.max()
        pooled += [(float(x), float(y / amp.max())) for x, y in zip(w[strong], amp[strong])]
    pooled.sort(key=lambda p: -p[1])
    scale = max((abs(w) for w, _ in pooled), default=1.0)
    rel = max(tol, precision_factor * diffusion) if np.isfinite(diffusion) else 1.0
    basis = independent_frequencies([w for w, _ in pooled], rel * scale, K)
    return Spectrum(pooled, sorted(abs(f) for f in basis), diffusion, rel)


def diffusion_from_lines(first, second, lines: int = 3, rel_amp: float = 0.05) -> float:
    r""":func:`frequency_diffusion` from the lines already found in the two halves of each signal
    (``first``, ``second``: lists of ``(omega, amplitude)`` per signal, from
    :func:`spectral_lines_batch`); the same rule: the relative change of the ``lines`` strongest
    lines of the first half (ignoring $|\omega| < 10^{-3}\max|\omega|$ and lines weaker than
    ``rel_amp`` times the strongest) to the nearest line of the second half; inf if one half has
    lines and the other none."""
    worst = 0.0
    for (w1, a1), (w2, _) in zip(first, second):
        if len(w1) == 0 and len(w2) == 0:
            continue
        if len(w1) == 0 or len(w2) == 0:
            return float("inf")
        big = (np.abs(w1) >= 1e-3 * np.max(np.abs(w1))) & (a1 >= rel_amp * a1.max())
        for w in w1[big][:lines]:
            worst = max(worst, float(np.min(np.abs(w2 - w)) / abs(w)))
    return worst


def lines_batch(signals: np.ndarray, dt: float, *, terms: int = 8, half_terms: int = 4):
    """The NAFF lines of every signal (``terms``) and of both halves (``half_terms``) of an ensemble
    ``(orbits, signals, samples)``: three lists indexed ``[orbit][signal]`` for
    :func:`spectrum_from_lines`."""
    Z = np.asarray(signals, dtype=complex)
    n_orb, n_sig, N = Z.shape
    flat = Z.reshape(n_orb * n_sig, N)
    half = N // 2
    parts = (spectral_lines_batch(flat, dt, terms),
             spectral_lines_batch(flat[:, :half], dt, half_terms),
             spectral_lines_batch(flat[:, half:2 * half], dt, half_terms))
    return tuple([p[o * n_sig:(o + 1) * n_sig] for o in range(n_orb)] for p in parts)


def spectrum_from_lines(whole, first, second, *, rel_amp: float = 0.05, tol: float = 1e-7,
                        K: int = 4, precision_factor: float = 10.0) -> Spectrum:
    """The :class:`Spectrum` of one orbit from the lines of its signals (any subset of them) —
    pooling, diffusion and the integer-relation count exactly as :func:`analyse`."""
    return _spectrum(whole, diffusion_from_lines(first, second), rel_amp, tol, K, precision_factor)


def analyse_batch(signals: np.ndarray, dt: float, *, terms: int = 8, half_terms: int = 4,
                  **count) -> list[Spectrum]:
    r""":func:`analyse` for an ensemble at once: ``signals`` of shape ``(orbits, signals, samples)``
    (complex). The lines of every signal and of both halves come from one call each of
    :func:`spectral_lines_batch` (:func:`lines_batch`); the pooling, the diffusion rule and the
    integer-relation count are those of :func:`analyse` (``terms`` lines per whole signal,
    ``half_terms`` per half: the diffusion uses only the 3 strongest). Domain: ``samples`` $\ge 14$."""
    whole, first, second = lines_batch(signals, dt, terms=terms, half_terms=half_terms)
    return [spectrum_from_lines(w, f, s, **count) for w, f, s in zip(whole, first, second)]


def fundamental_frequencies(z: np.ndarray, dt: float, iterations: int = 12) -> np.ndarray:
    r"""The strongest NAFF line of each row of ``z`` ``(orbits, samples)`` (uniform samples, step
    ``dt``): the angular frequency $\nu$ (signed, $|\nu| < \pi/dt$) maximising
    $|\langle z - \bar z, e^{i\nu t}\rangle_{\chi_2}|$ (Laskar's first NAFF step, Hann window of
    order 2), vectorised over orbits. The FFT peak of the windowed signal, refined by parabolic
    interpolation, starts Newton's method on the derivative of $|\langle\cdot\rangle|^2$, each
    step clamped to half an FFT bin. A row that is constant gives 0. Domain: ``samples`` $\ge 8$."""
    z = np.atleast_2d(np.asarray(z, dtype=complex))
    rows, size = z.shape
    w = _hann2(size)
    x = (z - z.mean(axis=1, keepdims=True)) * w
    spectrum = np.abs(np.fft.fft(x, axis=1))
    k = np.argmax(spectrum, axis=1)
    left, mid, right = (spectrum[np.arange(rows), (k + d) % size] for d in (-1, 0, 1))
    denom = left - 2 * mid + right
    shift = np.where(denom < 0, 0.5 * (left - right) / np.where(denom < 0, denom, 1.0), 0.0)
    bin_ = 2 * np.pi / (size * dt)
    nu = (np.fft.fftfreq(size, d=dt)[k] * 2 * np.pi) + np.clip(shift, -0.5, 0.5) * bin_
    tc = (np.arange(size) - (size - 1) / 2) * dt
    for _ in range(iterations):
        e = x * np.exp(-1j * nu[:, None] * tc)
        A0 = e.sum(axis=1)
        A1 = (e * (-1j * tc)).sum(axis=1)
        A2 = (e * (-tc * tc)).sum(axis=1)
        d1 = 2 * np.real(A1 * np.conj(A0))
        d2 = 2 * (np.abs(A1) ** 2 + np.real(A2 * np.conj(A0)))
        step = np.where(d2 < 0, -d1 / np.where(d2 < 0, d2, -1.0), np.sign(d1) * 0.25 * bin_)
        step = np.clip(step, -0.5 * bin_, 0.5 * bin_)
        nu = nu + step
        if np.all(np.abs(step) <= 1e-15 * np.maximum(np.abs(nu), bin_)):
            break
    return np.where(spectrum[np.arange(rows), k] > 0, nu, 0.0)
