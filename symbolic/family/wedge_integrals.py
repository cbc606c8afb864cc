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
(checked in the tests). The proof that every $H_k$ is a first integral for every $n$ is in
proofs/s6_wedge_integrals.py (its identities: :mod:`symbolic.family.wedge_proof`).

Everything here is exact at a rational point, in the number type of the caller: SymPy's ``QQ``
(GMP rationals; linear solves by ``DomainMatrix`` over QQ) or FLINT ``fmpq`` (``fmpq_mat``), so the two engines
decide independently. Forms on $\Lambda^m$ are dicts $I \mapsto$ coefficient ($I$ a sorted tuple);
$2 + D_B$ is kept sparse and solved block by block (the connected components of its non-zero
pattern: one block for a generic $\gamma$, blocks of size $\le 2$ when $\gamma \in \operatorname{span}\{E_{n-1}, E_n\}$).
Two routes to the rate:

* :func:`rate`: $\dot H_k = 2\langle \dot W, Y\rangle - \langle Y, D_{\dot B} Y\rangle$, $Y = (2 + D_B)^{-1}W$, with $\dot W$ by
  dual numbers through the Pfaffians and $D_{\dot B}$ as a matrix ($\dot M = [M, \Omega]$, $\dot\gamma = -\Omega\gamma$,
  $\Omega$ an exact solve of $L_\gamma$, eq:M-O, the definition, not a derived inverse);
* :func:`gradient` dotted with the field (:func:`rate_of_gradient`): the differential the rank check
  uses, evaluated on the field, so the rank check tests the conservation of the very function it
  differentiates.
"""

from __future__ import annotations

import bisect
import functools
import itertools

import flint
import sympy as sp
from sympy.polys.matrices import DomainMatrix

__all__ = ["subsets", "pfaffian", "wedge_power", "derivation_matrix", "shifted", "solve", "interior",
           "inner", "rate", "value", "gradient", "rate_of_gradient", "field", "point_fields", "numbers"]

#: the constant of the resolvent: $L_\gamma = 2 + D_B$ on $\Lambda^2$ (eq:M-O-axi-symm), and $H_k$ uses the same
SHIFT = 2


def subsets(n: int, m: int) -> list[tuple[int, ...]]:
    """The sorted ``m``-subsets of ``range(n)``: the basis $e_I$ of $\\Lambda^m\\mathbb{R}^n$."""
    return list(itertools.combinations(range(n), m))


def pfaffian(M, idx, zero, one, memo: dict | None = None):
    r"""$\operatorname{Pf}(M_{II})$ by expansion along the first row (``idx`` sorted, of even length); ``M`` a
    list of lists of any ring elements (duals allowed); ``memo`` shares the minors between calls.
    S6:wedge-integrals."""
    if not idx:
        return one
    if memo is not None and idx in memo:
        return memo[idx]
    i0, rest = idx[0], tuple(idx[1:])
    tot = zero
    for t, j in enumerate(rest):
        sub = rest[:t] + rest[t + 1:]   # rest without j = rest[t]
        term = M[i0][j] * pfaffian(M, sub, zero, one, memo)
        tot = tot + term if t % 2 == 0 else tot - term
    if memo is not None:
        memo[idx] = tot
    return tot


def wedge_power(M, n: int, k: int, zero, one) -> list:
    r"""$(M^{\wedge k})_I = \operatorname{Pf}(M_{II})$ for the $2k$-subsets $I$, in the order of :func:`subsets`
    (S6:wedge-integrals)."""
    memo: dict = {}
    return [pfaffian(M, I, zero, one, memo) for I in subsets(n, 2 * k)]


def derivation_matrix(B, n: int, m: int, zero) -> dict[int, dict[int, object]]:
    r"""The matrix of $D_B$ on $\Lambda^m\mathbb{R}^n$ in the basis $e_I$ of :func:`subsets`, sparse: ``D[row][col]``
    (column $I$ = $D_B e_I$); ``B`` a list of lists. $D_B e_I = \sum_s\sum_j B_{j,i_s}\,e_{i_1}\wedge\dots\wedge e_j\wedge\dots$
    (S6:wedge-integrals)."""
    D: dict[int, dict[int, object]] = {}
    for c, i, j, r, positive in _derivation_pattern(n, m):
        if B[j][i] == 0:
            continue
        row = D.setdefault(r, {})
        row[c] = row.get(c, zero) + (B[j][i] if positive else -B[j][i])
    return D


@functools.lru_cache(maxsize=64)
def _derivation_pattern(n: int, m: int) -> tuple:
    r"""The entries of :func:`derivation_matrix` that do not depend on $B$, in its order: $(c, i, j, r, +)$ for
    $e_I$ ($I$ the ``c``-th subset) with $i_s = i$ replaced by $j \notin I \setminus \{i\}$, $e_J$ the ``r``-th subset
    and ``+`` the sign of the sorting permutation. Computed once per $(n, m)$ in a worker."""
    basis = subsets(n, m)
    index = {I: r for r, I in enumerate(basis)}
    out = []
    for c, I in enumerate(basis):
        for s, i in enumerate(I):
            rest = I[:s] + I[s + 1:]
            for j in range(n):
                if j != i and j in I:
                    continue
                # sorting I with i_s -> j moves j from position s to its place p in J: a cycle of
                # length |s - p| + 1, sign (-1)^(s - p)
                p = bisect.bisect_left(rest, j)
                out.append((c, i, j, index[rest[:p] + (j,) + rest[p:]], (s - p) % 2 == 0))
    return tuple(out)


def shifted(B, n: int, m: int, zero, shift=SHIFT) -> dict[int, dict[int, object]]:
    r"""$\mathrm{shift} + D_B$ on $\Lambda^m$ (sparse, as :func:`derivation_matrix`); $2 + D_B$ by default, which is
    $L_\gamma$ for $m = 2$ (eq:M-O-axi-symm)."""
    A = derivation_matrix(B, n, m, zero)
    for i in range(len(subsets(n, m))):
        row = A.setdefault(i, {})
        row[i] = row.get(i, zero) + shift
    return A


def _components(A, size: int) -> list[list[int]]:
    parent = list(range(size))

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i
    for r, row in A.items():
        for c, v in row.items():
            if v != 0:
                parent[root(r)] = root(c)
    blocks: dict[int, list[int]] = {}
    for i in range(size):
        blocks.setdefault(root(i), []).append(i)
    return list(blocks.values())


def _dense_solve(A, y, engine: str):
    n = len(y)
    if engine == "flint":
        X = flint.fmpq_mat(n, n, [v for row in A for v in row]).solve(flint.fmpq_mat(n, 1, list(y)))
        return [X[i, 0] for i in range(n)]
    dm = DomainMatrix([list(row) for row in A], (n, n), sp.QQ)
    rhs = DomainMatrix([[v] for v in y], (n, 1), sp.QQ)
    return [row[0] for row in dm.lu_solve(rhs).to_list()]


def solve(A, y: list, engine: str, zero) -> list:
    r"""$x$ with $Ax = y$ exactly, ``A`` sparse (dict of rows), block by block over the connected
    components of its pattern (a permutation to block-diagonal form; each block an exact dense solve
    by the engine). Raises ``ZeroDivisionError``/``ValueError`` from the engine if a block is singular."""
    x = [zero] * len(y)
    for block in _components(A, len(y)):
        pos = {c: t for t, c in enumerate(block)}
        dense = [[zero] * len(block) for _ in block]
        for r in block:
            for c, v in A.get(r, {}).items():
                dense[pos[r]][pos[c]] = v
        for r, v in zip(block, _dense_solve(dense, [y[r] for r in block], engine), strict=True):
            x[r] = v
    return x


def interior(v, Y: dict, zero) -> dict:
    r"""$\iota_v Y$ for a vector ``v`` (list) and a form ``Y`` (dict $I \mapsto$ coefficient):
    $\iota_{e_i} e_I = (-1)^{s} e_{I\setminus i}$, $s$ the position of $i$ in $I$ (0-based)."""
    out: dict = {}
    for I, y in Y.items():
        for s, i in enumerate(I):
            if v[i] == 0:
                continue
            J = I[:s] + I[s + 1:]
            term = v[i] * y
            out[J] = out.get(J, zero) + (term if s % 2 == 0 else -term)
    return out


def inner(X: dict, Y: dict, zero):
    r"""$\langle X, Y\rangle$ in the orthonormal basis $e_I$."""
    return sum((v * Y[I] for I, v in X.items() if I in Y), zero)


def numbers(engine: str):
    """(convert, zero, one) for the engine's rationals: the elements of SymPy's domain ``QQ`` (GMP's
    ``mpq`` under the project's ground types, never FLINT's: chaplygin_nd sets ``SYMPY_GROUND_TYPES``)
    or FLINT ``fmpq``."""
    if engine == "flint":
        return (lambda v: flint.fmpq(int(sp.Rational(v).p), int(sp.Rational(v).q))), flint.fmpq(0), flint.fmpq(1)
    if engine != "sympy":
        raise ValueError(f"unknown engine {engine!r} (sympy or flint)")
    return (lambda v: sp.QQ.convert(sp.Rational(v))), sp.QQ.zero, sp.QQ.one


def _B(gamma, a, b, n):
    return [[(a if i == j == n - 1 else 0) + b * gamma[i] * gamma[j] for j in range(n)] for i in range(n)]


def point_fields(M, gamma, a, b, engine: str = "sympy", Omega=None):
    r"""$(M, \gamma, \dot M, \dot\gamma, B, \dot B)$ at a rational point in the engine's numbers: $\Omega$ by
    an exact solve of $L_\gamma = 2 + D_B$ on $\Lambda^2$ (eq:M-O-axi-symm), $\dot M = [M,\Omega]$,
    $\dot\gamma = -\Omega\gamma$ (eq:motion-general). ``M``: SymPy skew matrix, ``gamma``: on $S^{n-1}$.
    ``Omega``: a SymPy skew matrix to use instead of $L_\gamma^{-1}M$ (the proof's identity that holds
    for every rotation rate, :mod:`symbolic.family.wedge_proof`)."""
    num, zero, one = numbers(engine)
    n = M.rows
    Mq = [[num(M[i, j]) for j in range(n)] for i in range(n)]
    g = [num(v) for v in gamma]
    a_, b_ = num(a), num(b)
    B = _B(g, a_, b_, n)
    pairs = subsets(n, 2)
    if Omega is None:
        om = solve(shifted(B, n, 2, zero), [Mq[i][j] for i, j in pairs], engine, zero)
    else:
        om = [num(Omega[i, j]) for i, j in pairs]
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
    return [sum((v * y[c] for c, v in A.get(r, {}).items()), zero) for r in range(len(y))]


def value(M, gamma, a, b, k: int, engine: str = "sympy"):
    """$H_k$ at a rational point (S6:wedge-integrals)."""
    Mq, g, Md, gd, B, Bd, (zero, one) = point_fields(M, gamma, a, b, engine)
    n = M.rows
    W = wedge_power(Mq, n, k, zero, one)
    Y = solve(shifted(B, n, 2 * k, zero), W, engine, zero)
    return sum((w * y for w, y in zip(W, Y, strict=True)), zero)


def rate(M, gamma, a, b, k: int, engine: str = "sympy", Omega=None):
    r"""$\dot H_k$ along eq:motion-general at a rational point, exactly (module docstring, first route);
    zero iff $H_k$ is conserved there. ``Omega``: as in :func:`point_fields`. S6:wedge-integrals."""
    Mq, g, Md, gd, B, Bd, (zero, one) = point_fields(M, gamma, a, b, engine, Omega)
    n = M.rows
    W, Wd = _wedge_and_rate(Mq, Md, n, k, zero, one)
    Y = solve(shifted(B, n, 2 * k, zero), W, engine, zero)
    DBd = derivation_matrix(Bd, n, 2 * k, zero)
    first = sum((wd * y for wd, y in zip(Wd, Y, strict=True)), zero)
    second = sum((y * z for y, z in zip(Y, _apply(DBd, Y, zero), strict=True)), zero)
    return 2 * first - second


def gradient(M, gamma, a, b, k: int, engine: str = "sympy", shift=SHIFT) -> list:
    r"""$\partial H_k$ in the coordinates $(M_{ij})_{i<j}, \gamma$ at a rational point, exactly, with
    $W = M^{\wedge k}$, $Y = (\mathrm{shift} + D_B)^{-1}W$:
    $\partial_{M_{ij}}H_k = 2\sum_{I\ni i,j}(-1)^{s+t+1}\operatorname{Pf}(M_{I\setminus\{i,j\}})\,Y_I$ ($s < t$ the
    positions of $i, j$ in $I$: the derivative of a Pfaffian) and
    $\partial_{\gamma_m}H_k = -\langle Y, D_{\partial B}Y\rangle = -2b\langle\iota_{e_m}Y, \iota_\gamma Y\rangle$
    ($\partial B = b(e_m\gamma^T + \gamma e_m^T)$, $D_{xy^T + yx^T} = \varepsilon_x\iota_y + \varepsilon_y\iota_x$).
    ``shift`` other than 2 gives the differential of a function that is not an integral (the
    tests' controls). S6:wedge-integrals."""
    num, zero, one = numbers(engine)
    n = M.rows
    Mq = [[num(M[i, j]) for j in range(n)] for i in range(n)]
    g = [num(v) for v in gamma]
    B = _B(g, num(a), num(b), n)
    basis = subsets(n, 2 * k)
    memo: dict = {}
    W = [pfaffian(Mq, I, zero, one, memo) for I in basis]
    Yv = solve(shifted(B, n, 2 * k, zero, shift), W, engine, zero)
    Y = dict(zip(basis, Yv, strict=True))
    dM = {p: zero for p in subsets(n, 2)}
    for I, y in Y.items():
        if y == 0:
            continue
        for s, t in itertools.combinations(range(2 * k), 2):
            minor = pfaffian(Mq, I[:s] + I[s + 1:t] + I[t + 1:], zero, one, memo)
            term = minor * y
            dM[(I[s], I[t])] += term if (s + t) % 2 == 1 else -term
    out = [2 * dM[p] for p in subsets(n, 2)]
    Z = interior(g, Y, zero)
    for m in range(n):
        e = [one if i == m else zero for i in range(n)]
        out.append(-2 * num(b) * inner(interior(e, Y, zero), Z, zero))
    return out


def field(M, gamma, a, b, engine: str = "sympy") -> list:
    r"""$X = ((\dot M_{ij})_{i<j}, \dot\gamma)$ of eq:motion-general at the point, in the coordinates of
    :func:`gradient` and the engine's numbers ($\Omega$ by the exact solve of :func:`point_fields`)."""
    _, _, Md, gd, _, _, _ = point_fields(M, gamma, a, b, engine)
    return [Md[i][j] for i, j in subsets(M.rows, 2)] + list(gd)


def rate_of_gradient(grad: list, X: list, engine: str = "sympy"):
    r"""$dF(X) = \sum_{i<j}\partial_{M_{ij}}F\,\dot M_{ij} + \sum_m\partial_{\gamma_m}F\,\dot\gamma_m$: the rate along
    the field ``X`` (:func:`field`) of the function whose differential ``grad`` is (coordinates of
    :func:`gradient`); ``grad`` and ``X`` in the engine's numbers."""
    _, zero, _ = numbers(engine)
    return sum((d * f for d, f in zip(grad, X, strict=True)), zero)
