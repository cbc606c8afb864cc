r"""A high-precision reference: a Taylor-series method in fixed-point integer arithmetic.

For eq:motion-general with eq:M-O (eq:Inertia, eq:axisymm), the Taylor coefficients of
$M, \gamma, \Omega$ (and of the reconstruction $g, c$) obey, with $w := \Omega\gamma$,

.. math::
    (k+1)M_{k+1} = \sum_{j\le k}[M_j, \Omega_{k-j}], \quad (k+1)\gamma_{k+1} = -\sum_{j\le k}\Omega_j\gamma_{k-j},
    \\
    L_{\gamma_0}(\Omega_{k+1}) = M_{k+1} - b\Big(\sum_{m\le k} w_m\wedge\gamma_{k+1-m} + w'_{k+1}\wedge\gamma_0\Big),
    \quad w'_{k+1} = \sum_{i\le k}\Omega_i\gamma_{k+1-i},
    \\
    (k+1)g_{k+1} = \sum_{j\le k} g_j\Omega_{k-j}, \quad (k+1)c_{k+1} = r\sum_{j\le k} g_j w_{k-j}.

$L_{\gamma_0}$ is built from its *definition* $\mathbb{J}\Omega + \Omega\mathbb{J} + b(\Omega\gamma_0)\wedge\gamma_0$,
$\mathbb{J} = \mathrm{Id} + aE_nE_n^T$, and inverted by an mpmath linear solve once per step — an
independent route to $L_\gamma^{-1}$ (it does not use the derived inverse of :mod:`generated`).
Numbers are Python integers scaled by $2^{P}$ ($P$ = the requested digits plus guard bits), so
every product is one big-integer multiplication; the step follows Jorba–Zou (Exp. Math. 14 (2005)):
$h = 0.9\min_{k\in\{p-1,p\}}(\varepsilon/\max(\|X_k\|, 2^{30-P}))^{1/k}$, clipped to land on every sample time.
"""

from __future__ import annotations

import math
import time
from typing import Any

import mpmath
import numpy as np
from chaplygin_nd.simulate.dynamics import so
from chaplygin_nd.simulate.integrators import settings
from chaplygin_nd.simulate.integrators.base import Solution
from chaplygin_nd.simulate.integrators.registry import Integrator, register
from chaplygin_nd.simulate.integrators.settings import Digits

__all__ = ["integrate", "default_order", "L_matrix_mp"]


def default_order(dps: int) -> int:
    """Series order used for ``dps`` digits (about the cost-optimal $1.15\\cdot$dps)."""
    return max(12, round(1.15 * dps))


class _Fixed:
    def __init__(self, bits: int):
        self.P = bits
        self.one = 1 << bits

    def of(self, x) -> int:
        return int(mpmath.nint(mpmath.ldexp(mpmath.mpf(x), self.P)))

    def array(self, a) -> np.ndarray:
        a = np.asarray(a, dtype=object)
        return np.vectorize(self.of, otypes=[object])(a) if a.size else a

    def to_mpf(self, a) -> np.ndarray:
        return np.vectorize(lambda v: mpmath.ldexp(mpmath.mpf(v), -self.P), otypes=[object])(a)


def _skew(S):
    return S - S.T


def L_matrix_mp(gamma, a, b, n: int):
    r"""The matrix of $L_\gamma(\Omega) = \mathbb{J}\Omega + \Omega\mathbb{J} + b(\Omega\gamma)\wedge\gamma$,
    $\mathbb{J} = \mathrm{Id} + aE_nE_n^T$ (eq:M-O-axi-symm), on vec-coordinates (upper triangle, row
    major), in mpmath at the working precision, assembled from the definition; any $\gamma$.

    Column $c$ is $L_\gamma(B)$ for the basis element $B = E_iE_j^T - E_jE_i^T$ ($i < j$), entry by
    entry: $(\mathbb{J}B + B\mathbb{J})_{pq} = \mathbb{J}_{pp}B_{pq} + B_{pq}\mathbb{J}_{qq}$ ($\mathbb{J}$ is
    diagonal) plus $b((B\gamma)_p\gamma_q - \gamma_p(B\gamma)_q)$, with the roundings of the matrix
    products of the definition (each entry of those products has one non-zero term), ten times
    cheaper than forming the $n\times n$ products."""
    mpf = mpmath.mpf
    J = [mpf(1)] * n
    J[n - 1] = J[n - 1] + a
    g = [mpf(v) for v in gamma]
    bm, zero = mpf(b), mpf(0)
    rows, cols = np.triu_indices(n, 1)
    pairs = list(zip(rows.tolist(), cols.tolist(), strict=True))
    L = mpmath.matrix(len(pairs), len(pairs))
    for c, (i, j) in enumerate(pairs):
        Bg = [zero] * n
        Bg[i], Bg[j] = g[j], -g[i]
        for r, (p, q) in enumerate(pairs):
            Bpq = 1 if (p, q) == (i, j) else 0  # p < q: the upper triangle of B is one 1
            L[r, c] = (J[p] * Bpq + Bpq * J[q]) + bm * (Bg[p] * g[q] - g[p] * Bg[q])
    return L


def _L_inverse(fx, gamma, a, b, n):
    r"""The matrix of $L_{\gamma_0}^{-1}$ on vec-coordinates, fixed point, from the definition."""
    g = [mpmath.ldexp(mpmath.mpf(int(v)), -fx.P) for v in gamma]
    Linv = mpmath.inverse(L_matrix_mp(g, a, b, n))
    size = Linv.rows
    return np.array([[fx.of(Linv[r, c]) for c in range(size)] for r in range(size)], dtype=object)


def _series(fx, M, gamma, g, c, a, b, r, n, p):
    P = fx.P
    rows, cols = np.triu_indices(n, 1)
    Linv = _L_inverse(fx, gamma, a, b, n)
    bf, rf = fx.of(b), fx.of(r)

    def solve(rhs):
        v = (Linv @ rhs[rows, cols]) >> P
        out = np.zeros((n, n), dtype=object)
        out[rows, cols] = v
        out[cols, rows] = -v
        return out

    Ms, gs, Os, ws = [M], [gamma], [], []
    Gs, Cs = [g], [c]
    Os.append(solve(M))
    ws.append((Os[0] @ gamma) >> P)
    for k in range(p):
        q = k + 1
        Pk = sum(Ms[j] @ Os[k - j] for j in range(q)) >> P
        Ms.append(_div(_skew(Pk), q))
        gs.append(_div(-(sum(Os[j] @ gs[k - j] for j in range(q)) >> P), q))
        wp = sum(Os[i] @ gs[q - i] for i in range(q)) >> P
        S = sum(np.outer(ws[m], gs[q - m]) for m in range(q)) + np.outer(wp, gamma)
        S = _skew(S >> P)
        Os.append(solve(Ms[q] - ((bf * S) >> P)))
        ws.append(wp + ((Os[q] @ gamma) >> P))
        if g is not None:
            Gs.append(_div(sum(Gs[j] @ Os[k - j] for j in range(q)) >> P, q))
            Cs.append(_div((rf * (sum(Gs[j] @ ws[k - j] for j in range(q)) >> P)) >> P, q))
    coeffs = [Ms, gs] + ([Gs, Cs] if g is not None else [])
    return coeffs


def _div(x, q):
    """Fixed-point ``x / q`` rounded to nearest (elementwise on integer object arrays)."""
    return (x + q // 2) // q


def _horner(fx, series, H):
    acc = series[-1]
    for X in reversed(series[:-1]):
        acc = X + ((acc * H) >> fx.P)
    return acc


def integrate(field, y0: np.ndarray, t: np.ndarray, dps: int = 30, order: int | None = None,
              progress=None) -> Solution:
    r"""Integrate eq:motion-general (``field``: a :class:`simulate.dynamics.field.FullField`, whose $n, a, b$,
    radius and reconstruction flag are used; its kernels are *not* used) at ``dps`` digits.
    Returns float64 samples in ``y`` and mpmath samples in ``y_high``. Forward in time only."""
    n, a, b, r = field.n, field.a, field.b, field.radius
    p = order or default_order(dps)
    fx = _Fixed(math.ceil(dps * math.log2(10)) + 40)
    eps = 10.0 ** (-dps - 2)
    floor = 2.0 ** (30 - fx.P)
    y0 = np.asarray(y0, dtype=float)
    start = time.perf_counter()
    out = np.empty((len(t),) + y0.shape, dtype=object)
    steps = 0
    members, span = y0.shape[0], (float(t[-1]) - float(t[0])) or 1.0
    for e in range(members):
        parts = field.unpack(y0[e])
        state: list[Any] = [fx.array(v) for v in parts] + ([] if field.reconstruct else [None, None])
        T = fx.of(t[0])
        out[0, e] = fx.to_mpf(fx.array(y0[e]))
        with mpmath.workdps(dps + 15):
            for i in range(1, len(t)):
                T_next = fx.of(t[i])
                while T < T_next:
                    M_, gamma_, g_, c_ = state
                    coeffs = _series(fx, M_, gamma_, g_, c_, a, b, r, n, p)
                    size = [max(abs(int(v)) for v in np.ravel(cs[k]))
                            for cs in coeffs for k in (p - 1, p)]
                    scale = max(1.0, max(abs(int(v)) for s in state if s is not None
                                         for v in np.ravel(s)) / fx.one)
                    # a coefficient below the working precision is bounded by it, not taken as 0
                    hs = [(eps * scale / max(m / fx.one, floor)) ** (1.0 / k)
                          for m, k in zip(size, (p - 1, p) * len(coeffs), strict=True)]
                    H = min(fx.of(0.9 * min(hs)), T_next - T)
                    new = [_horner(fx, cs, H) for cs in coeffs]
                    state = new + ([] if field.reconstruct else [None, None])
                    T += H
                    steps += 1
                    if progress is not None:  # the whole work: member e of the ensemble
                        progress(t[0] + (e + (T / fx.one - t[0]) / span) / members * span)
                flat = [so_vec_obj(state[0], n), state[1]]
                if field.reconstruct:
                    flat += [state[2].ravel(), state[3]]
                out[i, e] = fx.to_mpf(np.concatenate(flat))
    seconds = time.perf_counter() - start
    y = np.vectorize(float, otypes=[float])(out)
    return Solution(t=np.asarray(t), y=y, method=f"Taylor order {p}, {dps} digits",
                    steps=steps, calls=steps * p, seconds=seconds, y_high=out)


def so_vec_obj(M, n):
    """vec-coordinates of an object (fixed-point) skew matrix, in the basis order of :mod:`simulate.dynamics.so`."""
    i, j = so.pairs(n)
    return M[i, j]


def _run(f, y0, t, s: Digits, *, checked, progress=None, compact=None) -> Solution:
    return integrate(f, y0, t, dps=s.dps, progress=progress)


REFERENCE = register(Integrator(
    "reference", Digits, _run,
    calibrate=lambda target, span, step=0.01, dps=30, precision="double":
        settings.digits("reference", target, dps, span),
    error=settings.digits_error,
    describe=lambda s: f"mpmath Taylor, {s.dps} digits",
    reduced=False, auto=2, reference=2))  # acts on (M, gamma) only
