r"""The torus dimension of an orbit by the Generalized Alignment Index GALI$_k$ (Ch. Skokos,
T. C. Bountis, Ch. Antonopoulos, *Geometrical properties of local dynamics in Hamiltonian systems:
the Generalized Alignment Index (GALI) method*, Physica D 231 (2007) 30, arXiv:0704.3155), a second
indicator beside the NAFF frequency count.

**The index.** Carry $K$ deviation vectors $\delta_1, \dots, \delta_K$ along an orbit of
$\dot y = f(y)$ by the variational equation $\dot\delta = Df(y)\,\delta$; in the state we keep their
directions $u_i = \delta_i/\|\delta_i\|$, which obey $\dot u = Df(y)u - \langle u, Df(y)u\rangle u$
(as the MEGNO tangent of :mod:`simulate.analysis.chaos`; $Df(y)u$ by heyoka's symbolic
differentiation of the project's expression builders, no Jacobian matrix). GALI$_k(t)$ is the volume of
the parallelepiped of the unit vectors $\hat u_1, \dots, \hat u_k$: the product of the diagonal of
$R$ in the QR factorisation of $[\hat u_1 \cdots \hat u_K]$ (nested in $k$: one factorisation gives
every $k \le K$).

**Why it measures the torus dimension** (Skokos et al. §4 for Hamiltonian systems; the argument
holds for any flow on invariant tori, e.g. Euler–Jacobi). Near an $s$-torus with angles $\theta$
and $m$ transverse coordinates $c$ (the values of the integrals), the flow is
$\dot\theta = \omega(c)$, $\dot c = 0$, so a deviation is $\delta\theta(t) = \delta\theta(0) +
t\,\omega'(c)\,\delta c$, $\delta c(t) = \delta c(0)$: every deviation turns towards the $s$
directions of the torus and grows linearly there (when $\omega'$ has rank $s$: the frequencies change
with the level set). $k \le s$ unit vectors then span a $k$-dimensional part of the torus's tangent
space: GALI$_k$ stays bounded away from 0; for $k > s$ the $k - s$ excess vectors keep only their
bounded transverse parts against a growth $\propto t$: GALI$_k \propto t^{-(k-s)}$. Under chaos
the vectors align with the most unstable direction and GALI$_k$ falls exponentially,
$\propto e^{-[(\lambda_1 - \lambda_2) + \dots + (\lambda_1 - \lambda_k)]t}$.

**On a quotient.** The axisymmetric sphere has the symmetry $SO(n-1)$ (eq:action); the torus
statement is about $P/SO(n-1)$. We compute on $P$ and keep only what the quotient sees: at each
sampled time every vector is projected onto the orthogonal complement in $T_yP$ of the group
orbit's tangent space $\mathfrak{so}(n-1)\cdot y = \{([X, M], X\gamma)\}$ (Euclidean metric of the
coordinates $(\mathrm{vec}\,M, \gamma)$, which $SO(n-1)$ preserves). This is exact, not an
approximation: the flow is equivariant, so $D\varphi_t$ maps $\mathfrak{so}(n-1)\cdot y$ onto
$\mathfrak{so}(n-1)\cdot\varphi_t(y)$ and the class of $\delta(t)$ modulo the group directions is the
linearised reduced flow applied to the class of $\delta(0)$; the projection is a metric on those
classes (a bounded distortion, which changes no power law). The initial vectors are drawn in that
complement (and tangent to $P$: $\langle\gamma, \delta\gamma\rangle = 0$, which the flow keeps). A
system without symmetry (the general-$\mathbb J$ control) is projected onto $T_yP$ only.

**Rule (fixed before any run of a row, validated by :mod:`simulate.analysis.gali_study`).** From
the samples of $\log_{10}\mathrm{GALI}_k$: the medians over the windows $W_1 = [T/8, T/4]$ and
$W_2 = [T/2, T]$ and the log-log slope $p_k = (\mathrm{med}_{W_2} - \mathrm{med}_{W_1})/\log_{10}4$
(the windows' centres are a factor 4 apart). GALI$_k$ is **flat** iff $p_k >$ ``FLAT_SLOPE`` $= -0.5$
and $\mathrm{med}_{W_2} >$ ``FLOOR`` $= -12$ (a constant is $p = 0$, the first decay $t^{-1}$ is
$p = -1$). An orbit is

* ``chaotic`` iff $p_2 \le$ ``CHAOTIC_SLOPE`` $= -3$ or $\mathrm{med}_{W_2}\log_{10}\mathrm{GALI}_2
  \le$ ``FLOOR`` (faster than the power laws of regular motion at $k = 2$: $t^{-1}$ on a closed
  curve, $t^{-2}$ when the two vectors share a plane with one growing direction, as in the twist
  map of the study);
* otherwise its **dimension** is the largest $k \le K$ with GALI$_1 \dots$ GALI$_k$ all flat
  (GALI$_1 \equiv 1$), reported as ``>= K`` when GALI$_K$ is flat (the index cannot see further).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from chaplygin_nd.simulate.dynamics import so
from chaplygin_nd.simulate.integrators.heyoka_systems import System

__all__ = ["deviation_system", "initial_deviations", "group_directions", "project", "gali",
           "slopes", "verdict", "GaliResult", "FLAT_SLOPE", "CHAOTIC_SLOPE", "FLOOR", "WINDOWS"]

FLAT_SLOPE = -0.5
CHAOTIC_SLOPE = -3.0
#: log10 of a GALI that has collapsed (exponential decay that reached rounding before W_1 has no
#: slope left). -12, not -8: the validation study's twist map (K = 0) decays like t^-2 (two
#: vectors in a plane holding one growing direction) and reached 1e-8 on 2 of 64 orbits at t = 4096
FLOOR = -12.0
#: the two windows of the slope, as fractions of T
WINDOWS = ((0.125, 0.25), (0.5, 1.0))


def deviation_system(system: System, count: int) -> System:
    r"""``system`` with ``count`` unit deviation vectors $u_i$, $\dot u_i = Df(y)u_i - \langle u_i,
    Df(y)u_i\rangle u_i$ (module docstring); state $(y, u_1, \dots, u_K)$, the same parameters.
    Domain: as ``system``."""
    d = system.dim
    names = tuple(system.names) + tuple(f"dev{i}_{v}" for i in range(count) for v in system.names)

    def build(v, p, ops):
        hy = ops.hy
        y = v[:d]
        f = system.build(list(y), p, ops)
        f = [r if not isinstance(r, int) else hy.expression(float(r)) for r in f]
        eps = hy.expression("deviation_epsilon")
        out = list(f)
        for i in range(count):
            u = v[d * (i + 1):d * (i + 2)]
            shifted = hy.subs(f, {str(y[j]): y[j] + eps * u[j] for j in range(d)})
            Du = hy.subs([hy.diff(e, eps) for e in shifted],
                         {"deviation_epsilon": hy.expression(0.0)})
            sigma = hy.sum([u[j] * Du[j] for j in range(d)])
            out += [Du[j] - sigma * u[j] for j in range(d)]
        return out

    return System(f"{system.name} + {count} deviation vectors", names, system.parameters, build)


def group_directions(y: np.ndarray, n: int, symmetric: bool = True) -> np.ndarray:
    r"""Orthonormal columns spanning $\mathfrak{so}(n-1)\cdot y$ and the normal $(0, \gamma)$ of $P$ at
    the full states ``y`` ``(..., d)`` (layout :func:`simulate.dynamics.so.vec`, then $\gamma$): shape
    ``(..., d, r)``. ``symmetric`` False: the normal only (a system without the symmetry)."""
    Q, R = np.linalg.qr(_group_matrix(y, n, symmetric))
    return Q


def _group_matrix(y: np.ndarray, n: int, symmetric: bool = True) -> np.ndarray:
    r"""The columns that :func:`group_directions` orthonormalises: $([X, M], X\gamma)$ for $X = E_i
    \wedge E_j$, $i < j < n - 1$ (in that order), then $(0, \gamma)$. $X$ moves rows and columns:
    $(XM)_{i\cdot} = M_{j\cdot}$, $(XM)_{j\cdot} = -M_{i\cdot}$, $(MX)_{\cdot j} = M_{\cdot i}$,
    $(MX)_{\cdot i} = -M_{\cdot j}$, $(X\gamma)_i = \gamma_j$, $(X\gamma)_j = -\gamma_i$, so they are
    copied, not multiplied. The products with the matrix $X$ (``einsum``, as before) gave the same
    numbers with every zero $+0$ (a sum of products starts at $+0$); the copies are normalised
    the same way (``+ 0.0``), so the columns are the same bits (tests/test_gali.py compares)."""
    N = so.so_dim(n)
    y = np.asarray(y, float)
    M, g = so.unvec(y[..., :N], n), y[..., N:N + n]
    a, b = so.pairs(n)
    r = (n - 1) * (n - 2) // 2 + 1 if symmetric else 1
    A = np.zeros(y.shape[:-1] + (N + n, r))
    XM, MX, Xg = np.empty_like(M), np.empty_like(M), np.empty_like(g)
    col = 0
    for i in range(n - 1 if symmetric else 0):
        for j in range(i + 1, n - 1):
            XM.fill(0.0)
            MX.fill(0.0)
            Xg.fill(0.0)
            XM[..., i, :], XM[..., j, :] = M[..., j, :], -M[..., i, :]
            MX[..., :, j], MX[..., :, i] = M[..., :, i], -M[..., :, j]
            Xg[..., i], Xg[..., j] = g[..., j], -g[..., i]
            XM += 0.0
            MX += 0.0
            Xg += 0.0
            A[..., :N, col] = (XM - MX)[..., a, b]
            A[..., N:, col] = Xg
            col += 1
    A[..., N:, col] = g
    return A


def project(u: np.ndarray, y: np.ndarray, n: int, symmetric: bool = True) -> np.ndarray:
    r"""The vectors ``u`` ``(..., K, d)`` at the states ``y`` ``(..., d)`` with their components along
    :func:`group_directions` removed (module docstring, *On a quotient*)."""
    Q = group_directions(y, n, symmetric)
    c = np.einsum("...dr,...kd->...kr", Q, u)
    return u - np.einsum("...dr,...kr->...kd", Q, c)


def initial_deviations(y0: np.ndarray, count: int, seed: int, n: int | None = None,
                       symmetric: bool = True) -> np.ndarray:
    r"""``count`` unit deviation vectors per state ``y0`` ``(orbits, d)``: standard normal directions
    drawn from ``seed``, projected as :func:`project` when ``n`` is given (the sphere: tangent to $P$,
    transverse to the group orbits), then normalised. Shape ``(orbits, count, d)``."""
    rng = np.random.default_rng([int(seed), 0x6A11])
    u = rng.standard_normal((len(y0), count, y0.shape[1]))
    if n is not None:
        u = project(u, y0, n, symmetric)
    return u / np.linalg.norm(u, axis=-1, keepdims=True)


def gali(u: np.ndarray) -> np.ndarray:
    r"""GALI$_k$ for $k = 1..K$ of the vectors ``u`` ``(..., K, d)`` (normalised here): the products
    of the first $k$ diagonal entries of $R$ in $[\hat u_1\cdots\hat u_K] = QR$. Shape ``(..., K)``."""
    u = u / np.linalg.norm(u, axis=-1, keepdims=True)
    R = np.linalg.qr(np.swapaxes(u, -1, -2), mode="r")
    diag = np.abs(np.diagonal(R, axis1=-2, axis2=-1))
    return np.cumprod(diag, axis=-1)


def slopes(t: np.ndarray, g: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    r"""$(p_k, \mathrm{med}_{W_2}\log_{10}\mathrm{GALI}_k)$ of the module docstring from the samples
    ``g`` ``(samples, K)`` at the times ``t`` ``(samples,)`` (from 0 to $T$)."""
    t = np.asarray(t, float)
    T = t[-1]
    lg = np.log10(np.maximum(g, 1e-300))
    (a1, b1), (a2, b2) = WINDOWS
    w1 = (t >= a1 * T) & (t <= b1 * T)
    w2 = (t >= a2 * T) & (t <= b2 * T)
    m1, m2 = np.median(lg[w1], axis=0), np.median(lg[w2], axis=0)
    return (m2 - m1) / np.log10(4.0), m2


@dataclass
class GaliResult:
    """One orbit: ``slopes`` $p_k$, ``late`` medians of $\\log_{10}$GALI$_k$ over $W_2$ ($k = 1..K$),
    ``cls`` ``chaotic`` / ``regular``, ``dimension`` (the largest flat $k$; ``K`` means ``>= K``)."""

    slopes: list
    late: list
    cls: str
    dimension: int

    def to_dict(self) -> dict:
        return {"slopes": [float(v) for v in self.slopes], "late": [float(v) for v in self.late],
                "cls": self.cls, "dimension": int(self.dimension)}


def verdict(t: np.ndarray, g: np.ndarray) -> GaliResult:
    """The rule of the module docstring for one orbit (``g`` ``(samples, K)``, ``K >= 2``)."""
    p, late = slopes(t, g)
    K = g.shape[1]
    if K < 2:
        raise ValueError("GALI needs at least 2 deviation vectors")
    if p[1] <= CHAOTIC_SLOPE or late[1] <= FLOOR:
        return GaliResult(list(p), list(late), "chaotic", 0)
    dim = 1
    for k in range(1, K):
        if p[k] > FLAT_SLOPE and late[k] > FLOOR:
            dim = k + 1
        else:
            break
    return GaliResult(list(p), list(late), "regular", dim)
