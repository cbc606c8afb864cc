r"""NAFF's spectral lines of many signals at once (the orbits of an ensemble): Laskar's line search
vectorised over rows (:func:`spectral_lines_batch`), used through
:func:`simulate.analysis.naff.lines_batch`. Apart from :mod:`simulate.analysis.naff` (the count, the
diffusion, the scalar PyNAFF reference) because its cost is the cost of every evidence row's
frequency analysis: the projections as BLAS products, one BLAS thread, buffers kept between calls
and Newton steps only on the rows whose frequency still moves, each with the measurement that
motivated it, and each leaving the lines the same bits (tests/test_naff_buffers.py,
tests/test_naff_projections.py).
"""

from __future__ import annotations

import functools
import threading

import numpy as np

__all__ = ["spectral_lines_batch"]


def _hann2(N: int) -> np.ndarray:
    r"""Hann window of order 2, $w_j = (1 + \cos\pi\tau_j)^2$, $\tau_j \in [-1, 1]$ (the window of
    :func:`simulate.analysis.naff.spectral_lines`), normalised to $\sum_j w_j = 1$."""
    tau = np.linspace(-1.0, 1.0, N)
    w = (1.0 + np.cos(np.pi * tau)) ** 2
    return w / w.sum()


def _blocks(N: int) -> tuple[int, int]:
    """``(P, L)`` with ``P * L >= N``, ``L`` about $\\sqrt{N}$: sample $j = pL + l$."""
    L = max(1, int(np.ceil(np.sqrt(N))))
    return -(-N // L), L


def _projections(X: np.ndarray, nu: np.ndarray, dt: float, L: int, derivatives: bool):
    r"""$\phi(\nu) = \sum_j X_j e^{-i\nu t_j}$ and (``derivatives``) $\phi'$, $\phi''$ for every row of
    ``X`` (shape ``(K, P, L)``, zero-padded, C-contiguous complex128), $t_j = j\,dt$, $j = pL + l$: the
    exponential factorises, $e^{-i\nu t_j} = \alpha_p\beta_l$, so each sum is two small matrix
    products per row (no $K\times N$ exponentials). Without ``derivatives`` returns
    ``(phi, alpha, beta)``.

    The products are stacked ``@`` with three columns (one BLAS ``zgemm`` per row): the same sums
    as the earlier ``einsum`` formulation, which did not use BLAS and was half of the NAFF time
    (tests/test_naff_projections.py compares the two). Always three columns, also when only
    $\phi$ is needed: a one-column product is a matrix-vector product, which OpenBLAS runs
    multi-threaded and which was 10-100x slower on the shared 2-core machine (measured)."""
    K, P, _ = X.shape
    p = np.arange(P) * (L * dt)
    l_ = np.arange(L) * dt
    alpha = np.exp(-1j * nu[:, None] * p[None])     # (K, P)
    beta = np.exp(-1j * nu[:, None] * l_[None])     # (K, L)
    B = np.stack([beta, beta * l_[None], beta * (l_ ** 2)[None]], axis=-1)   # (K, L, 3)
    XB = X @ B                                                               # (K, P, 3)
    Xb, Xbl, Xbll = XB[..., 0], XB[..., 1], XB[..., 2]
    # t = p + l (in time units): sum t X e = sum_p alpha (p Xb + Xbl), and so on
    W = np.stack([Xb, p[None] * Xb + Xbl, (p ** 2)[None] * Xb + 2 * p[None] * Xbl + Xbll], axis=-1)
    S = (alpha[:, None, :] @ W)[:, 0, :]                                     # (K, 3)
    if not derivatives:
        return S[:, 0], alpha, beta
    return S[:, 0], -1j * S[:, 1], -S[:, 2]


def _one_blas_thread():
    """A context with one BLAS thread (threadpoolctl, a dependency; a venv installed before it was
    added only runs slower, the lines are the same). The controller that finds the loaded BLAS
    libraries is built once per process (:func:`_blas_controller`): building it scans every loaded
    library, 7 ms a call, which was paid three times per ensemble."""
    controller = _blas_controller()
    if controller is None:  # pragma: no cover - the dependency is declared
        import contextlib

        return contextlib.nullcontext()
    return controller.limit(limits=1, user_api="blas")


@functools.lru_cache(maxsize=1)
def _blas_controller():
    """The process's ``threadpoolctl.ThreadpoolController`` (None without threadpoolctl)."""
    try:
        from threadpoolctl import ThreadpoolController
    except ImportError:  # pragma: no cover - the dependency is declared
        return None
    return ThreadpoolController()


_WORK = threading.local()


def _scratch(name: str, shape: tuple[int, ...], dtype) -> np.ndarray:
    """A C-contiguous array of ``shape`` and ``dtype`` whose memory is kept between calls (one
    buffer per ``name`` and thread, grown to the largest request; contents undefined). NAFF on
    an ensemble needs a few arrays of tens of MB per call; allocated fresh, their first touch
    (page faults, zeroing by the kernel) cost a third of the time of a call on this machine
    (measured). Kept per thread, so that concurrent calls (a threaded Dask worker) never share
    one. A process keeps its largest request: 72 bytes per sample of the ensemble (about
    220 MB for the largest ensemble of the evidence rows, 32 orbits of 10 signals of 9601 samples)."""
    size = int(np.prod(shape))
    store = _WORK.__dict__
    buf = store.get(name)
    if buf is None or buf.dtype != np.dtype(dtype) or buf.size < size:
        store[name] = buf = np.empty(size, dtype=dtype)
    return buf[:size].reshape(shape)


def _update_projections(Xr, nu, dt, L, rows, phi, d1, d2) -> None:
    r"""Overwrite ``phi``, ``d1``, ``d2`` (:func:`_projections` with derivatives) at the rows
    ``rows`` by their values at ``nu``; the other rows are left as they are. The values of a row
    do not depend on the other rows (elementwise operations and one BLAS product per row: the
    stacked ``@`` calls ``zgemm`` row by row), so a row computed alone has the bits it has in the
    whole batch. The whole batch when more than a quarter of the rows are asked for (then one
    call is cheaper than many), else one call per row."""
    K = len(nu)
    if len(rows) == 0:
        return
    if 4 * len(rows) > K:
        phi[:], d1[:], d2[:] = _projections(Xr, nu, dt, L, True)
        return
    for k in rows:
        phi[k:k + 1], d1[k:k + 1], d2[k:k + 1] = _projections(Xr[k:k + 1], nu[k:k + 1], dt, L, True)


def _find_lines(R, w, dt, pad, P, L, terms, newton, found_w, found_a) -> None:
    r"""The loop of :func:`spectral_lines_batch`: ``terms`` lines of every row of the residual
    ``R`` (subtracted in place, but for the last line) into ``found_w``, ``found_a``. Runs with one BLAS thread (the caller
    limits it): the products are small, and on a busy machine (``make verify`` runs a worker per
    core) OpenBLAS's waiting threads made them and everything after them up to 3x slower
    (measured on the evidence rows).

    Every ``(K, N)``-sized array is a kept buffer (:func:`_scratch`), not a fresh allocation
    per line: the page faults of fresh arrays of tens of MB cost more than the arithmetic (the
    spectrum's ``abs`` 5x, the line's outer product 2x, measured). The arithmetic is unchanged
    operation for operation, so the lines are the same bits (tests/test_naff_buffers.py compares
    with the earlier loop): the window is multiplied in as the complex array NumPy cast it to,
    the FFT runs in place on a zero-padded copy as ``fft(x, n=pad)`` makes one, and
    $\overline{\alpha_p\beta_l} = \bar\alpha_p\bar\beta_l$ exactly (negation is exact)."""
    from scipy.fft import fft  # the same pocketfft as numpy.fft, bit for bit, 1.6x faster batched

    K, N = R.shape
    omega_grid = 2 * np.pi * np.fft.fftfreq(pad, d=dt)
    idx = np.arange(K)
    wc = w.astype(complex)[None]                 # what R * w casts w to, once
    X = _scratch("window", (K, P * L), complex)  # the windowed residual, zero-padded to P * L
    X[:, N:] = 0.0
    F = _scratch("fft", (K, pad), complex)       # its zero-padded copy, transformed in place
    spec = _scratch("abs", (K, pad), float)
    line = _scratch("line", (K, P, L), complex)
    flat = line.reshape(K, P * L)[:, :N]
    for m in range(terms):
        np.multiply(R, wc, out=X[:, :N])
        F[:, :N] = X[:, :N]                       # pad >= N
        F[:, N:] = 0.0
        np.abs(fft(F, axis=1, overwrite_x=True), out=spec)
        i = np.argmax(spec, axis=1)
        y0, y1, y2 = (np.log(spec[idx, (i + s) % pad] + 1e-300) for s in (-1, 0, 1))
        den = y0 - 2 * y1 + y2
        shift = np.where(np.abs(den) > 0, 0.5 * (y0 - y2) / np.where(den == 0, 1, den), 0.0)
        nu = omega_grid[i] + shift * (2 * np.pi / (pad * dt))
        Xr = X.reshape(K, P, L)
        phi, d1, d2 = _projections(Xr, nu, dt, L, True)
        for _ in range(newton):
            g = 2 * np.real(np.conj(phi) * d1)
            h = 2 * np.real(np.abs(d1) ** 2 + np.conj(phi) * d2)
            step = np.where(h < 0, g / np.where(h == 0, 1, h), 0.0)
            new = nu - np.clip(step, -np.pi / (N * dt), np.pi / (N * dt))
            moved = np.flatnonzero(new.view(np.int64) != nu.view(np.int64))
            nu = new
            # phi, d1, d2 at the new nu (after the last step phi alone is read): a row whose
            # nu did not move keeps the values it has, which are those bits (:func:`_update_projections`)
            _update_projections(Xr, nu, dt, L, moved, phi, d1, d2)
        alpha = np.exp(-1j * nu[:, None] * (np.arange(P) * (L * dt))[None])   # as _projections
        beta = np.exp(-1j * nu[:, None] * (np.arange(L) * dt)[None])
        found_w[:, m] = nu
        found_a[:, m] = np.abs(phi)
        if m == terms - 1:
            break                                 # the last residual is never read
        # subtract the line phi e^{i nu t}, e^{i nu t_j} = conj(alpha_p beta_l) (<e, e>_w = 1)
        np.multiply(np.conj(alpha)[:, :, None], np.conj(beta)[:, None, :], out=line)
        flat *= phi[:, None]
        R -= flat


def spectral_lines_batch(Z: np.ndarray, dt: float, terms: int = 12, constant: float = 1e-6,
                         floor: float = 1e-9, newton: int = 4) -> list[tuple[np.ndarray, np.ndarray]]:
    r"""NAFF lines of many signals at once (the orbits of an ensemble): ``Z`` of shape ``(K, N)``,
    each row sampled at $t_0 + j\,dt$. Same conventions as :func:`simulate.analysis.naff.spectral_lines` (mean removed,
    a constant signal has no line, lines weaker than ``floor`` times the signal's variation
    dropped, angular frequencies, strongest first); per row a pair ``(omega, amplitude)``.

    Method (Laskar's NAFF, vectorised): Hann window of order 2; each line starts at the peak of the
    zero-padded FFT of the windowed residual (parabolic interpolation of $\log|\hat z|$) and is
    refined by ``newton`` Newton steps on $|\phi(\nu)|^2$, $\phi(\nu) = \sum_j w_j r_j e^{-i\nu t_j}$;
    the line $\phi(\nu)e^{i\nu t}$ ($\sum_j w_j = 1$) is then subtracted from the residual. Unlike
    :func:`simulate.analysis.naff.spectral_lines` there is no Gram–Schmidt step: the order-2 Hann window vanishes to fourth
    order at both ends, so the windowed overlap of two lines $\Delta\nu$ apart falls like
    $(\Delta\nu T)^{-5}$ and only lines closer than a few $2\pi/T$ (unresolved ones) interact — those
    orbits are reported as unresolved by the frequency diffusion anyway. Every row advances
    together: no Python loop over signals. Domain: $N \ge 7$; ``terms`` $\ge 1$."""
    Z = np.asarray(Z, dtype=complex)
    K, N = Z.shape
    mag = _scratch("abs", (K, N), float)       # kept buffers (see _find_lines), same values
    size = np.max(np.abs(Z, out=mag), axis=1)
    R = np.subtract(Z, Z.mean(axis=1, keepdims=True), out=_scratch("residual", (K, N), complex))
    scale = np.max(np.abs(R, out=mag), axis=1)
    live = (scale > constant * size) & (scale > 0)
    w = _hann2(N)
    P, L = _blocks(N)
    from scipy.fft import next_fast_len

    pad = next_fast_len(N)
    found_w = np.zeros((K, terms))
    found_a = np.zeros((K, terms))
    with _one_blas_thread():
        _find_lines(R, w, dt, pad, P, L, terms, newton, found_w, found_a)
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
