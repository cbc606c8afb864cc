r"""Writing an $SO(3)$-invariant polynomial in the invariants $A, B, E, G, F_1, \delta$ (Section 5).

$SO(3)$ acts on $(k, u, q, x)$ by $h\cdot(k,u,q,x) = (hk, hu, hq, x)$ (S5:SO3-action). By the first
fundamental theorem of invariant theory for $SO(3)$ acting on three vectors, every invariant
polynomial is a polynomial in the Gram entries and the triple product

.. math::
    A = \lVert k\rVert^2,\ B = \lVert u\rVert^2,\ F_1 = \langle k,u\rangle,\ E = \langle k,q\rangle,\
    G = \langle u,q\rangle,\ s = \lVert q\rVert^2,\ \delta = \langle q, k\times u\rangle,

and by the second fundamental theorem the only relation is $\delta^2 = \det\Lambda$ ($\Lambda$ the Gram
matrix of $k, u, q$). Hence every invariant has exactly one *normal form* linear in $\delta$:
$P_0 + \delta P_1$ with $P_0, P_1 \in \mathbb{Q}[a,b,x][A,B,F_1,E,G,s]$. (Uniqueness: the six Gram
entries are algebraically independent; if $P_0 + \delta P_1 = 0$, the orientation reversal
$(k,u,q) \mapsto -(k,u,q)$ fixes the Gram entries and flips $\delta$, so $P_0 = P_1 = 0$.) On
$S^3$ we then substitute $s = 1 - x^2$; the result is unique as a function on the reduced space
because $(A, B, F_1, E, G, x)$ remain independent there.

**Method (an ansatz solved by exact linear algebra).** An invariant $N$ is split into its
bihomogeneous parts (degree $d$ in $(k, u)$, degree $e$ in $q$); each part is matched against all
monomials $A^iB^jF_1^lE^mG^ps^t\delta^r$ ($r \le 1$) of the same bidegree, the coefficients (in
$\mathbb{Q}[a, b, x]$) are found by an exact reduced row echelon form over $\mathbb{Q}$, and
consistency of the system is checked (an inconsistent system raises: $N$ is not invariant).
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.symbolic import fourd
from sympy import QQ
from sympy.polys.matrices import DomainMatrix
from sympy.polys.rings import ring

__all__ = ["A", "B", "E", "G", "F1", "delta", "INV_RING", "INV_GENS", "invariant_polys",
           "in_invariants", "to_phase_space", "det_Lambda", "reduce_delta"]

A, B, E, G, F1, delta = sp.symbols("A B E G F1 delta", real=True)
INV_GENS = (fourd.a, fourd.b, fourd.x, A, B, E, G, F1, delta)
INV_RING, *_IG = ring(list(INV_GENS), QQ)
_ia, _ib, _ix, _A, _B, _E, _G, _F1, _delta = _IG

_k, _u, _q = fourd._k, fourd._u, fourd._q
_KU = range(3, 9)    # generator positions of k1..u3 in fourd.RING
_QI = range(9, 12)   # q1..q3
_ORDER = ("A", "B", "F1", "E", "G", "s", "delta")


def invariant_polys():
    """The generators of the invariant ring of S5:SO3-action ($A, B, F_1, E, G, s = \\lVert q\\rVert^2,
    \\delta$) as elements of :data:`symbolic.fourd.RING` (polynomials in k, u, q; any point)."""
    dot, cross = fourd.dot, fourd.cross
    return {"A": dot(_k, _k), "B": dot(_u, _u), "F1": dot(_k, _u), "E": dot(_k, _q),
            "G": dot(_u, _q), "s": dot(_q, _q), "delta": dot(_q, cross(_k, _u))}


def det_Lambda():
    r"""$\det\Lambda$, $\Lambda = \begin{pmatrix} A & F_1 & E\\ F_1 & B & G\\ E & G & 1-x^2\end{pmatrix}$
    (eq:PrincMinors), element of :data:`INV_RING`."""
    s = 1 - _ix**2
    return _A * (_B * s - _G**2) - _F1 * (_F1 * s - _G * _E) + _E * (_F1 * _G - _B * _E)


def _monomials(d: int, e: int):
    out = []
    for iA in range(d // 2 + 1):
        for iB in range(d // 2 + 1):
            for iF in range(d // 2 + 1):
                for iD in (0, 1):
                    rest = d - 2 * (iA + iB + iF + iD)
                    if rest < 0:
                        continue
                    for iE in range(rest + 1):
                        iG = rest - iE
                        eq = e - iE - iG - iD
                        if eq >= 0 and eq % 2 == 0:
                            out.append((iA, iB, iF, iE, iG, eq // 2, iD))
    return out


def _expand(mon, inv):
    p = fourd.RING(1)
    for name, ex in zip(_ORDER, mon, strict=False):
        if ex:
            p *= inv[name] ** ex
    return p


def in_invariants(N):
    r"""The normal form (linear in $\delta$, $s \to 1 - x^2$) of an $SO(3)$-invariant polynomial ``N``
    (the step that derives eq:red-system and S5:red-integrals from the 4D field)
    in :data:`symbolic.fourd.RING` (generators $a, b, x, k, u, q$; no $\eta, \xi$), as an element of
    :data:`INV_RING`. Raises ``ValueError`` if ``N`` is not invariant."""
    inv = invariant_polys()
    pieces = {}
    for mon, c in N.terms():
        if any(mon[12:]):
            raise ValueError("N must not contain eta or xi")
        key = (sum(mon[i] for i in _KU), sum(mon[i] for i in _QI))
        pieces.setdefault(key, []).append((mon, c))
    total = INV_RING(0)
    for (d, e), terms in sorted(pieces.items()):
        mons = _monomials(d, e)
        cols = [_expand(m, inv) for m in mons]
        rhs = {}
        for mon, c in terms:
            rhs.setdefault(mon[:3], {})[(0, 0, 0) + mon[3:]] = c
        keys = sorted({m for col in cols for m in col.keys()} | {m for r in rhs.values() for m in r})
        index = {m: i for i, m in enumerate(keys)}
        params = sorted(rhs)
        width = len(cols) + len(params)
        rows = [[QQ(0)] * width for _ in keys]
        for j, col in enumerate(cols):
            for m, c in col.terms():
                rows[index[m]][j] = QQ(c)
        for j, al in enumerate(params):
            for m, c in rhs[al].items():
                rows[index[m]][len(cols) + j] = QQ(c)
        rref, pivots = DomainMatrix(rows, (len(keys), width), QQ).rref()
        if any(p >= len(cols) for p in pivots):
            raise ValueError(f"not SO(3)-invariant (bidegree {(d, e)})")
        if len(pivots) != len(cols):
            raise ArithmeticError("invariant monomials found dependent: impossible")
        rr = rref.to_list()
        for i, pc in enumerate(pivots):
            iA, iB, iF, iE, iG, iS, iD = mons[pc]
            mono = (_A**iA * _B**iB * _F1**iF * _E**iE * _G**iG * (1 - _ix**2)**iS * _delta**iD)
            for j, al in enumerate(params):
                c = rr[i][len(cols) + j]
                if c:
                    total += c * _ia**al[0] * _ib**al[1] * _ix**al[2] * mono
    return total


def to_phase_space(P):
    r"""Substitute the invariants of $(k, u, q)$ into ``P`` $\in$ :data:`INV_RING`: the composition
    $P\circ\pi$ as an element of :data:`symbolic.fourd.RING` (the quotient map $\pi$ of S5:SO3-action)."""
    inv = invariant_polys()
    images = [fourd._a, fourd._b, fourd._x, inv["A"], inv["B"], inv["E"], inv["G"], inv["F1"],
              inv["delta"]]
    out = fourd.RING(0)
    for mon, c in P.terms():
        t = fourd.RING(c)
        for img, ex in zip(images, mon, strict=False):
            if ex:
                t *= img**ex
        out += t
    return out


def reduce_delta(P):
    r"""Replace $\delta^2$ by $\det\Lambda$ (eq:PrincMinors) in ``P`` $\in$ :data:`INV_RING`: the normal
    form linear in $\delta$, unique on the reduced space $\mathcal{R}$."""
    dL = det_Lambda()
    out = INV_RING(0)
    for mon, c in P.terms():
        e = mon[8]
        t = INV_RING(c) * dL**(e // 2) * _delta**(e % 2)
        for g, ex in zip(_IG[:8], mon[:8], strict=False):
            if ex:
                t *= g**ex
        out += t
    return out
