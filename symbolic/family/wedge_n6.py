r"""$H_2$ of row S6:wedge-integrals for $n = 6$ as a symbolic identity in $a, b$ (a slow check beside the row).

On $\Lambda^4\mathbb{R}^6 \cong \Lambda^2$ (Hodge star) the derivation of $B$ becomes
$\star D_B\star^{-1} = \operatorname{tr}B - D_B$, so with $V = \star(M\wedge M) \in \mathfrak{so}(6)$ and
$c = 2 + a + b$ ($\lVert\gamma\rVert = 1$),

.. math::
    H_2 \propto \langle V, (c - D_B)^{-1}V\rangle_\kappa, \qquad c - D_B = \tfrac c2\,(2 + D_{B'}),\quad
    B' = -\tfrac{2}{c}B,

i.e. $(c - D_B)^{-1} = \tfrac 2c L_\gamma^{-1}$ at $(a', b') = (-2a/c, -2b/c)$: the derived inverse of
P:inversion (:func:`symbolic.axisym_inverse.inverse_numerator` coefficients) at other parameters, its
denominators cleared by $c^3$. With $N_H = \langle V, \sum_k (D'c_k')\,T_k(V)\rangle$ and $D'$ the
scaled denominator (a polynomial in $a, b, x$), $\dot H_2 = 0$ iff
$D'\,D\dot N_H - N_H\,D\dot D' = 0$ on $P$ ($D\dot{}$ along the derived field, $D = 2(2+a+b)\Delta$).
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.symbolic.axisym_inverse import _numerator_coefficients, inverse_denominator
from chaplygin_nd.symbolic.axisymmetric import a, b, x
from sympy import QQ
from sympy.polys.rings import ring

__all__ = ["N", "GENS", "SPHERE", "h2_residual"]

N = 6
_PAIRS = [(i, j) for i in range(N) for j in range(i + 1, N)]
_M = [sp.Symbol(f"M_{i + 1}{j + 1}", real=True) for i, j in _PAIRS]
_Q = sp.symbols(f"q1:{N}", real=True)
GENS = (a, b, x, *_M, *_Q)
SPHERE = (*_Q, x)


def _parity(p) -> int:
    p, s = list(p), 1
    for i in range(len(p)):
        while p[i] != i:
            j = p[i]
            p[i], p[j] = p[j], p[i]
            s = -s
    return s


def h2_residual(at: tuple[sp.Rational, sp.Rational] | None = None):
    r"""$D'\,D\dot N_H - N_H\,D\dot D'$ (module docstring) as a sparse polynomial over $\mathbb{Q}$ in
    :data:`GENS`; zero modulo $\lVert\gamma\rVert^2 = 1$ iff $H_2$ is conserved ($n = 6$, symbolic $a, b$).
    ``at``: rational $(a, b)$ with $2 + a + b \ne 0$ to put in before the ring arithmetic (the same
    identity on one point of the parameter plane, in seconds; $a, b$ then do not occur)."""
    R, *G = ring(list(GENS), QQ)
    A, B = at if at else (a, b)   # the parameters: symbols, or the given rationals

    def put(expr):   # a SymPy coefficient in a, b, x as a ring element, at (A, B)
        return R(expr.subs({a: A, b: B}, simultaneous=True))
    X = G[2]
    M = [[R(0)] * N for _ in range(N)]
    for k, (i, j) in enumerate(_PAIRS):
        M[i][j], M[j][i] = G[3 + k], -G[3 + k]
    gam = [G[3 + len(_PAIRS) + i] for i in range(N - 1)] + [X]
    e = [R(0)] * (N - 1) + [R(1)]

    def wedge(u, v):
        return [[u[i] * v[j] - v[i] * u[j] for j in range(N)] for i in range(N)]

    def apply(V, cs):   # sum_k cs[k] T_k(V), the terms of symbolic.axisym_inverse.ansatz_terms
        Vg = [sum((V[i][t] * gam[t] for t in range(N)), R(0)) for i in range(N)]
        Ve = [V[i][N - 1] for i in range(N)]
        T = [V, wedge(Vg, gam), wedge(Ve, e), wedge(Vg, e), wedge(Ve, gam),
             [[Vg[N - 1] * w for w in row] for row in wedge(gam, e)]]
        return [[sum((cs[k] * T[k][i][j] for k in range(6)), R(0)) for j in range(N)] for i in range(N)]

    coeffs = [sp.expand(c) for c in _numerator_coefficients()]
    DO = apply(M, [put(c) for c in coeffs])
    Mdot = {(i, j): sum((M[i][t] * DO[t][j] - DO[i][t] * M[t][j] for t in range(N)), R(0))
            for i, j in _PAIRS}
    gdot = [-sum((DO[i][t] * gam[t] for t in range(N)), R(0)) for i in range(N)]

    def pf4(I):
        p, q, r, s = I
        return M[p][q] * M[r][s] - M[p][r] * M[q][s] + M[p][s] * M[q][r]
    V = [[R(0)] * N for _ in range(N)]
    for i, j in _PAIRS:
        comp = [t for t in range(N) if t not in (i, j)]
        V[i][j] = _parity([i, j] + comp) * pf4(comp)
        V[j][i] = -V[i][j]
    ap, bp = sp.symbols("ap bp")
    exprs = coeffs + [sp.expand(inverse_denominator())]
    deg = max(sp.Poly(c, a, b).total_degree() for c in exprs)

    def scaled(expr):   # expr(a', b', x) * c^deg at (A, B), a polynomial in (a, b,) x
        e_ = expr.subs({a: ap, b: bp}, simultaneous=True)
        e_ = e_.subs({ap: -2 * A / (2 + A + B), bp: -2 * B / (2 + A + B)}, simultaneous=True)
        return R(sp.cancel(sp.expand(e_ * (2 + A + B) ** deg)))
    *cp, Dp = [scaled(c) for c in exprs]
    Y = apply(V, cp)
    NH = sum((V[i][j] * Y[i][j] for i, j in _PAIRS), R(0))

    def DX(f):
        tot = R(0)
        for k, pr in enumerate(_PAIRS):
            d = f.diff(G[3 + k])
            if d:
                tot += d * Mdot[pr]
        for t in range(N - 1):
            d = f.diff(G[3 + len(_PAIRS) + t])
            if d:
                tot += d * gdot[t]
        d = f.diff(X)
        if d:
            tot += d * gdot[N - 1]
        return tot
    return Dp * DX(NH) - NH * DX(Dp)
