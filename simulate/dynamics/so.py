r"""NumPy helpers on $\mathfrak{so}(n)$ and $SO(n)$, batched over leading axes (Section 2.2).

Definitions only (no derived formula lives here):

* wedge $u\wedge v = uv^T - vu^T$ (footnote to eq:M-O);
* commutator $[A, B] = AB - BA$ (eq:motion-general);
* Killing metric $\langle A, B\rangle_\kappa = -\tfrac12\operatorname{tr}(AB)$ (S2.2:energy);
* coordinates ``vec``/``unvec`` in the basis $E_i\wedge E_j$, $i<j$ (as :mod:`symbolic.algebra`);
* the 4D blocks $M = \begin{pmatrix}\hat k & u\\ -u^T & 0\end{pmatrix}$, $\gamma = (q, x)$
  (Section 5, before eq:motion-n4), with $\hat w v = w\times v$;
* the exponential of skew matrices, $e^{Xt}$ on a time grid and $\int_0^t e^{Ws}\,ds\,v$.
"""

from __future__ import annotations

import math
from functools import cache

import numpy as np

__all__ = [
    "so_dim", "pairs", "vec", "unvec", "wedge", "commutator", "killing", "expm_skew_t", "expm_integral",
    "skew_modes",
    "hat", "split4", "join4", "rotation_to", "expm_small", "reduced_invariants",
]


def so_dim(n: int) -> int:
    r"""$\dim\mathfrak{so}(n) = n(n-1)/2$."""
    return n * (n - 1) // 2


@cache
def pairs(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Row and column indices $(i, j)$, $i < j$, in lexicographic order (the basis order)."""
    return np.triu_indices(n, 1)


@cache
def _eye(n: int) -> np.ndarray:
    return np.eye(n)


def vec(M: np.ndarray) -> np.ndarray:
    r"""Coordinates of $M \in \mathfrak{so}(n)$ (shape ``(..., n, n)``): the entries $M_{ij}$, $i<j$."""
    M = np.asarray(M, dtype=float)
    i, j = pairs(M.shape[-1])
    return M[..., i, j]


def unvec(c: np.ndarray, n: int) -> np.ndarray:
    r"""The skew matrix with coordinates ``c`` (shape ``(..., n(n-1)/2)``) in the basis $E_i\wedge E_j$."""
    c = np.asarray(c, dtype=float)
    if c.shape[-1] != so_dim(n):
        raise ValueError(f"so({n}) has {so_dim(n)} coordinates, got shape {c.shape}")
    out = np.zeros(c.shape[:-1] + (n, n))
    i, j = pairs(n)
    out[..., i, j] = c
    out[..., j, i] = -c
    return out


def wedge(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    r"""$u\wedge v = uv^T - vu^T$ (footnote to eq:M-O), batched: ``(..., n) -> (..., n, n)``."""
    uv = u[..., :, None] * v[..., None, :]
    return uv - np.swapaxes(uv, -1, -2)


def commutator(A: np.ndarray, B: np.ndarray) -> np.ndarray:
    r"""$[A, B] = AB - BA$ (eq:motion-general)."""
    return A @ B - B @ A


def killing(A: np.ndarray, B: np.ndarray) -> np.ndarray:
    r"""$\langle A, B\rangle_\kappa = -\tfrac12\operatorname{tr}(AB)$ (S2.2:energy); for skew matrices
    $=\sum_{i<j}A_{ij}B_{ij}$."""
    return -0.5 * np.einsum("...ij,...ji->...", A, B)


def _spectral(X: np.ndarray):
    r"""$iX = V\Lambda V^*$ (Hermitian eigendecomposition) of one real skew matrix."""
    lam, V = np.linalg.eigh(1j * np.asarray(X, dtype=float))
    return lam, V


def skew_modes(X: np.ndarray):
    r"""The modes of one real skew ``X`` as $e^{Xt}$ uses them: ``(P0, lam, V)`` with
    $P_0$ the real projector on the eigenvalues of $iX$ at most ``4 eps max|lambda|`` in size
    (exactly 0 for a real skew matrix of odd size or deficient rank; rounding makes them
    $\pm\varepsilon\lVert X\rVert$), and the positive eigenvalues ``lam`` with their eigenvectors ``V``.
    The negative ones are taken as $-\lambda$ with $\bar v$, as they are for a real $X$; so

    .. math:: e^{Xt} = P_0 + 2\,\mathrm{Re}\sum_{\lambda > 0} e^{-i\lambda t}\,v v^*

    is real and orthogonal to rounding at every $t$ (a zero eigenvalue computed as $10^{-17}$
    would otherwise turn by $10^{-5}$ rad at $t = 10^{12}$ and break orthogonality)."""
    lam, V = _spectral(X)
    tol = 4 * np.finfo(float).eps * (float(np.max(np.abs(lam))) if lam.size else 0.0)
    zero = np.abs(lam) <= tol
    P0 = np.real(V[:, zero] @ V[:, zero].conj().T)
    pos = lam > tol
    return P0, lam[pos], V[:, pos]


def expm_skew_t(X: np.ndarray, t: np.ndarray) -> np.ndarray:
    r"""$e^{Xt}$ for one skew ``X`` (``(n, n)``) at every time of ``t``; shape ``(len(t), n, n)``.

    From one Hermitian eigendecomposition $iX = V\Lambda V^*$ paired as a real matrix needs
    (:func:`skew_modes`): orthogonal to rounding for every $t$ (no scaling and squaring, so no
    error growth with $\|Xt\|$ beyond the phase error $\varepsilon\,|\lambda| t$ inherent in $t$)."""
    P0, lam, V = skew_modes(X)
    phase = np.exp(-1j * np.outer(np.asarray(t, dtype=float), lam))
    return P0 + 2 * np.real(np.einsum("ik,tk,jk->tij", V, phase, V.conj()))


def expm_small(X: np.ndarray) -> np.ndarray:
    r"""$\exp X$ by scaling and squaring with a Taylor polynomial (Horner), batched.

    Meant for the small arguments of one integrator step: after scaling to $\|Y\|_1 \le 1/4$ the
    degree $d$ is the least with $\|Y\|^{d+1}/(d+1)! < 2^{-60}$ (at most 12), so for skew $X$ the
    result is orthogonal to rounding. Several times cheaper than SciPy's ``expm`` on tiny matrices."""
    X = np.asarray(X, dtype=float)
    norm = float(np.abs(X).sum(axis=-2).max()) if X.size else 0.0
    s = max(0, math.ceil(math.log2(norm / 0.25))) if norm > 0.25 else 0
    Y = X / (2.0 ** s) if s else X
    r = norm / 2.0 ** s
    d, term = 1, r
    while d < 12 and term * r / (d + 1) >= 2.0 ** -60:
        d += 1
        term *= r / d
    eye = _eye(X.shape[-1])
    E = eye + Y / d
    for k in range(d - 1, 0, -1):
        E = eye + (Y @ E) / k
    for _ in range(s):
        E = E @ E
    return E


def expm_integral(W: np.ndarray, v: np.ndarray, t: np.ndarray) -> np.ndarray:
    r"""$\int_0^{t} e^{Ws}\,ds\; v$ for one skew ``W`` (``(n, n)``), ``v`` (``(n,)``), at each time of
    ``t``; returns ``(len(t), n)``. With the modes of :func:`skew_modes`: $tP_0v$ plus, per
    $\lambda > 0$, $2\,\mathrm{Re}\,\int_0^te^{-i\lambda s}ds\,vv^*$, $\int_0^te^{-i\lambda s}ds =
    t\,e^{-i\lambda t/2}\operatorname{sinc}(\lambda t/2\pi)$ (no $0/0$ at small $\lambda$)."""
    P0, lam, V = skew_modes(W)
    t = np.asarray(t, dtype=float)
    lt = np.outer(t, lam)
    weight = t[:, None] * np.exp(-0.5j * lt) * np.sinc(lt / (2 * np.pi))
    return t[:, None] * (P0 @ v) + 2 * np.real(np.einsum("ik,tk,jk,j->ti", V, weight, V.conj(), v))


def hat(w: np.ndarray) -> np.ndarray:
    r"""Hat map $\mathbb{R}^3\to\mathfrak{so}(3)$, $\hat w v = w\times v$ (eq:xiV3D), batched."""
    w = np.asarray(w, dtype=float)
    out = np.zeros(w.shape[:-1] + (3, 3))
    out[..., 0, 1], out[..., 0, 2], out[..., 1, 2] = -w[..., 2], w[..., 1], -w[..., 0]
    out[..., 1, 0], out[..., 2, 0], out[..., 2, 1] = w[..., 2], -w[..., 1], w[..., 0]
    return out


def split4(M: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    r"""$(k, u)$ from $M = \begin{pmatrix}\hat k & u\\ -u^T & 0\end{pmatrix}\in\mathfrak{so}(4)$
    (Section 5; also $(\eta, \xi)$ from $\Omega$)."""
    k = np.stack([M[..., 2, 1], M[..., 0, 2], M[..., 1, 0]], axis=-1)
    return k, M[..., :3, 3]


def join4(k: np.ndarray, u: np.ndarray) -> np.ndarray:
    r"""The inverse of :func:`split4`: $\begin{pmatrix}\hat k & u\\ -u^T & 0\end{pmatrix}$."""
    out = np.zeros(np.broadcast_shapes(k.shape, u.shape)[:-1] + (4, 4))
    out[..., :3, :3] = hat(k)
    out[..., :3, 3] = u
    out[..., 3, :3] = -u
    return out


def rotation_to(gamma: np.ndarray) -> np.ndarray:
    r"""A rotation $g_0\in SO(n)$ with $g_0^T E_n = \gamma$ (last row $=\gamma^T$), $\gamma\in S^{n-1}$:
    the Householder reflection exchanging $E_n$ and $\gamma$, composed with a reflection in $E_1$
    (which fixes $E_n$) to make $\det g_0 = +1$; $g_0 = \mathrm{Id}$ when $\gamma = E_n$."""
    gamma = np.asarray(gamma, dtype=float)
    n = gamma.shape[-1]
    e = np.zeros(n)
    e[-1] = 1.0
    w = e - gamma
    nw = np.linalg.norm(w)
    if nw < 1e-300:
        return np.eye(n)
    w = w / nw
    H = np.eye(n) - 2.0 * np.outer(w, w)  # H e = gamma, H gamma = e, H symmetric
    D = np.eye(n)
    D[0, 0] = -1.0
    return D @ H  # (D H)^T E_n = H D E_n = H E_n = gamma, det = +1


def reduced_invariants(M: np.ndarray, gamma: np.ndarray) -> np.ndarray:
    r"""$r = (A, B, E, G, F_1, x, \delta)$ with $A = \|k\|^2$, $B = \|u\|^2$, $F_1 = \langle k, u\rangle$,
    $E = \langle k, q\rangle$, $G = \langle u, q\rangle$, $\delta = \langle q, k\times u\rangle$ — the
    definitions of Section 5 (Reduction by SO(3)); $n = 4$, $M$ ``(..., 4, 4)``, $\gamma = (q, x)$."""
    k, u = split4(M)
    q, x = gamma[..., :3], gamma[..., 3]
    dot = lambda p, s: np.einsum("...i,...i->...", p, s)  # noqa: E731
    return np.stack([dot(k, k), dot(u, u), dot(k, q), dot(u, q), dot(k, u), x,
                     dot(q, np.cross(k, u))], axis=-1)
