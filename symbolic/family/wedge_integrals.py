r"""The wedge-power integrals $H_k = \langle M^{\wedge k}, (2 + D_B)^{-1} M^{\wedge k}\rangle$ (row S6:wedge-integrals).

For the axisymmetric sphere in any dimension $n$, with $B = aE_nE_n^T + b\gamma\gamma^T$ (so that
$L_\gamma(\Omega) = 2\Omega + B\Omega + \Omega B = (2 + D_B)\Omega$ on $\Lambda^2 = \mathfrak{so}(n)$, eq:M-O-axi-symm) and
$D_B$ the derivation extension of $B$ to $\Lambda^{2k}\mathbb{R}^n$
($D_B(v_1\wedge\dots\wedge v_{2k}) = \sum_s v_1\wedge\dots\wedge Bv_s\wedge\dots\wedge v_{2k}$),

.. math::
    H_k = \langle M^{\wedge k}, (2 + D_B)^{-1} M^{\wedge k}\rangle, \qquad 1 \le k \le \lfloor n/2\rfloor,

in the orthonormal basis $e_I$ of $\Lambda^{2k}$, $(M^{\wedge k})_I = \operatorname{Pf}(M_{II})$ (up to the factor $k!$).
$H_1 = 2H$ (the energy); for $n = 2k$, $D_B = \operatorname{tr}B$ on $\Lambda^n$ and $H_{n/2} = \operatorname{Pf}(M)^2/(2+a+b)$
(known). For $n = 5$, $H_2 = (\lVert w\rVert^2 + F)/(2+a+b)$ with the $F$ of S6:sixth-integral-n5
(checked in the tests). Conjecture: every $H_k$ is a first integral of eq:motion-general;
with the $n$ known integrals they give $2n - 2 - \lfloor n/2\rfloor$ independent invariant integrals.

Everything here is exact at a rational point, in the number type of the caller: SymPy ``Rational``
(linear solves by ``DomainMatrix`` over QQ) or FLINT ``fmpq`` (``fmpq_mat``), so the two engines
decide independently. The rate $\dot H_k$ uses $\dot M = [M, \Omega]$, $\dot\gamma = -\Omega\gamma$ with $\Omega$ an
exact solve of $L_\gamma$ (eq:M-O, the definition, not a derived inverse):
$\dot H_k = 2\langle \dot W, Y\rangle - \langle Y, D_{\dot B} Y\rangle$, $Y = (2 + D_B)^{-1}W$ ($D_B$ is symmetric).
"""

from __future__ import annotations

import itertools

import flint
import sympy as sp
from sympy.polys.matrices import DomainMatrix

__all__ = ["subsets", "pfaffian", "wedge_power", "derivation_matrix", "rate", "value", "gradient",
           "point_fields"]


def subsets(n: int, m: int) -> list[tuple[int, ...]]:
    """The sorted ``m``-subsets of ``range(n)``: the basis $e_I$ of $\\Lambda^m\\mathbb{R}^n$."""
    return list(itertools.combinations(range(n), m))


def pfaffian(M, idx, zero, one):
    r"""$\operatorname{Pf}(M_{II})$ by expansion along the first row (``idx`` of even length); ``M`` a
    list of lists of any ring elements (duals allowed). S6:wedge-integrals."""
    if not idx:
        return one
    i0, rest = idx[0], idx[1:]
    tot = zero
    for t, j in enumerate(rest):
        sub = tuple(r for r in rest if r != j)
        term = M[i0][j] * pfaffian(M, sub, zero, one)
        tot = tot + term if t % 2 == 0 else tot - term
    return tot


def wedge_power(M, n: int, k: int, zero, one) -> list:
    r"""$(M^{\wedge k})_I = \operatorname{Pf}(M_{II})$ for the $2k$-subsets $I$ (S6:wedge-integrals)."""
    return [pfaffian(M, I, zero, one) for I in subsets(n, 2 * k)]


def derivation_matrix(B, n: int, m: int, zero) -> list[list]:
    r"""The matrix of $D_B$ on $\Lambda^m\mathbb{R}^n$ in the basis $e_I$ (column $I$ = $D_B e_I$); ``B`` a list
    of lists. $D_B e_I = \sum_s\sum_j B_{j,i_s}\,e_{i_1}\wedge\dots\wedge e_j\wedge\dots$ (S6:wedge-integrals)."""
    basis = subsets(n, m)
    index = {I: r for r, I in enumerate(basis)}
    D = [[zero] * len(basis) for _ in basis]
    for c, I in enumerate(basis):
        for s, i in enumerate(I):
            for j in range(n):
                if B[j][i] == 0 or (j != i and j in I):
                    continue
                new = list(I)
                new[s] = j
                order = sorted(range(m), key=lambda t: new[t])
                sign = _parity(order)
                J = tuple(new[t] for t in order)
                D[index[J]][c] = D[index[J]][c] + (B[j][i] if sign > 0 else -B[j][i])
    return D


def _parity(perm) -> int:
    perm, sign = list(perm), 1
    for i in range(len(perm)):
        while perm[i] != i:
            j = perm[i]
            perm[i], perm[j] = perm[j], perm[i]
            sign = -sign
    return sign


def _solve(A, y, engine: str):
    if engine == "flint":
        X = flint.fmpq_mat(len(A), len(A), [v for row in A for v in row]).solve(
            flint.fmpq_mat(len(y), 1, list(y)))
        return [X[i, 0] for i in range(len(y))]
    dm = DomainMatrix([[sp.QQ(v.p, v.q) for v in row] for row in A], (len(A), len(A)), sp.QQ)
    rhs = DomainMatrix([[sp.QQ(v.p, v.q)] for v in y], (len(y), 1), sp.QQ)
    sol = dm.lu_solve(rhs).to_Matrix()
    return [sol[i, 0] for i in range(len(y))]


def _num(engine: str):
    if engine == "flint":
        return (lambda v: flint.fmpq(int(sp.Rational(v).p), int(sp.Rational(v).q))), flint.fmpq(0), flint.fmpq(1)
    return (lambda v: sp.Rational(v)), sp.Integer(0), sp.Integer(1)


def _B(gamma, a, b, n):
    return [[(a if i == j == n - 1 else 0) + b * gamma[i] * gamma[j] for j in range(n)] for i in range(n)]


def point_fields(M, gamma, a, b, engine: str = "sympy"):
    r"""$(M, \gamma, \dot M, \dot\gamma, B, \dot B)$ at a rational point in the engine's numbers: $\Omega$ by
    an exact solve of $L_\gamma = 2 + D_B$ on $\Lambda^2$ (eq:M-O-axi-symm), $\dot M = [M,\Omega]$,
    $\dot\gamma = -\Omega\gamma$ (eq:motion-general). ``M``: SymPy skew matrix, ``gamma``: on $S^{n-1}$."""
    num, zero, one = _num(engine)
    n = M.rows
    Mq = [[num(M[i, j]) for j in range(n)] for i in range(n)]
    g = [num(v) for v in gamma]
    a_, b_ = num(a), num(b)
    B = _B(g, a_, b_, n)
    L = derivation_matrix(B, n, 2, zero)
    for i in range(len(L)):
        L[i][i] = L[i][i] + 2
    pairs = subsets(n, 2)
    om = _solve(L, [Mq[i][j] for i, j in pairs], engine)
    Om = [[zero] * n for _ in range(n)]
    for (i, j), v in zip(pairs, om, strict=True):
        Om[i][j], Om[j][i] = v, -v
    Md = [[sum((Mq[i][t] * Om[t][j] - Om[i][t] * Mq[t][j] for t in range(n)), zero) for j in range(n)]
          for i in range(n)]
    gd = [-sum((Om[i][t] * g[t] for t in range(n)), zero) for i in range(n)]
    Bd = [[b_ * (gd[i] * g[j] + g[i] * gd[j]) for j in range(n)] for i in range(n)]
    return Mq, g, Md, gd, B, Bd, (zero, one)


class _Dual:
    __slots__ = ("v", "w")

    def __init__(self, v, w):
        self.v, self.w = v, w

    def __add__(self, o):
        return _Dual(self.v + o.v, self.w + o.w)

    def __sub__(self, o):
        return _Dual(self.v - o.v, self.w - o.w)

    def __mul__(self, o):
        return _Dual(self.v * o.v, self.v * o.w + self.w * o.v)


def _wedge_and_rate(Mq, Md, n, k, zero, one):
    D = [[_Dual(Mq[i][j], Md[i][j]) for j in range(n)] for i in range(n)]
    W = wedge_power(D, n, k, _Dual(zero, zero), _Dual(one, zero))
    return [d.v for d in W], [d.w for d in W]


def _apply(A, y, zero):
    return [sum((A[i][j] * y[j] for j in range(len(y))), zero) for i in range(len(A))]


def value(M, gamma, a, b, k: int, engine: str = "sympy"):
    """$H_k$ at a rational point (S6:wedge-integrals)."""
    Mq, g, Md, gd, B, Bd, (zero, one) = point_fields(M, gamma, a, b, engine)
    n = M.rows
    W, _ = _wedge_and_rate(Mq, Md, n, k, zero, one)
    L = derivation_matrix(B, n, 2 * k, zero)
    for i in range(len(L)):
        L[i][i] = L[i][i] + 2
    Y = _solve(L, W, engine)
    return sum((w * y for w, y in zip(W, Y, strict=True)), zero)


def rate(M, gamma, a, b, k: int, engine: str = "sympy"):
    r"""$\dot H_k$ along eq:motion-general at a rational point, exactly (module docstring); zero iff
    $H_k$ is conserved there. S6:wedge-integrals."""
    Mq, g, Md, gd, B, Bd, (zero, one) = point_fields(M, gamma, a, b, engine)
    n = M.rows
    W, Wd = _wedge_and_rate(Mq, Md, n, k, zero, one)
    L = derivation_matrix(B, n, 2 * k, zero)
    for i in range(len(L)):
        L[i][i] = L[i][i] + 2
    Y = _solve(L, W, engine)
    DBd = derivation_matrix(Bd, n, 2 * k, zero)
    first = sum((wd * y for wd, y in zip(Wd, Y, strict=True)), zero)
    second = sum((y * z for y, z in zip(Y, _apply(DBd, Y, zero), strict=True)), zero)
    return 2 * first - second


def gradient(M, gamma, a, b, k: int, engine: str = "sympy") -> list:
    r"""$\partial H_k$ in the coordinates $(M_{ij})_{i<j}, \gamma$ at a rational point, exactly:
    $\partial_{M_{ij}}H_k = 2\langle\partial W, Y\rangle$, $\partial_{\gamma_l}H_k = -\langle Y, D_{\partial B}Y\rangle$
    (S6:wedge-integrals)."""
    num, zero, one = _num(engine)
    n = M.rows
    Mq = [[num(M[i, j]) for j in range(n)] for i in range(n)]
    g = [num(v) for v in gamma]
    B = _B(g, num(a), num(b), n)
    L = derivation_matrix(B, n, 2 * k, zero)
    for i in range(len(L)):
        L[i][i] = L[i][i] + 2
    W = wedge_power(Mq, n, k, zero, one)
    Y = _solve(L, W, engine)
    out = []
    for i, j in subsets(n, 2):
        E = [[zero] * n for _ in range(n)]
        E[i][j], E[j][i] = one, -one
        _, dW = _wedge_and_rate(Mq, E, n, k, zero, one)
        out.append(2 * sum((d * y for d, y in zip(dW, Y, strict=True)), zero))
    for m in range(n):
        dB = [[num(b) * ((one if i == m else zero) * g[j] + g[i] * (one if j == m else zero))
               for j in range(n)] for i in range(n)]
        DdB = derivation_matrix(dB, n, 2 * k, zero)
        out.append(-sum((y * z for y, z in zip(Y, _apply(DdB, Y, zero), strict=True)), zero))
    return out
