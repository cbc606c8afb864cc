r"""The $SO(4)$-invariant polynomials of the axisymmetric $n = 5$ sphere (row S6:reduced-n5, beyond the paper).

Block notation as in Section 5 one dimension up: $M = \begin{pmatrix} K & u\\ -u^T & 0\end{pmatrix}$,
$K \in \mathfrak{so}(4)$, $u \in \mathbb{R}^4$, $\gamma = (q, x)$, $q \in \mathbb{R}^4$. $SO(4) = \{h : hE_5 = E_5\}$
(eq:SOnminus1) acts by $h\cdot(K, u, q, x) = (hKh^{-1}, hu, hq, x)$ (eq:action). With the Hodge star
($(\star K)_{ij} = \tfrac12\varepsilon_{ijkl}K_{kl}$), $K_\pm = K \pm \star K$ are the self-dual and
anti-self-dual parts (times 2); they commute, $K_\pm^2 = -A_\pm I$, and $S = K_+K_- = K^2 - (\star K)^2$
is symmetric and traceless. The generators (integer coefficients):

.. math::
    A_\pm = \lVert k_\pm\rVert^2 = -\tfrac14\operatorname{tr}K_\pm^2,\quad B = \lVert u\rVert^2,\quad
    G = \langle u, q\rangle,\quad s = \lVert q\rVert^2 = 1 - x^2,\quad E_\pm = u^TK_\pm q,\quad
    S_{uu} = u^TSu,\ S_{uq} = u^TSq,\ S_{qq} = q^TSq,

with $k_+ = (K_{12}+K_{34}, K_{13}-K_{24}, K_{14}+K_{23})$, $k_- = (K_{12}-K_{34}, K_{13}+K_{24}, K_{14}-K_{23})$;
so $\lVert K\rVert^2 = (A_++A_-)/2$ and $\operatorname{Pf}K = (A_+-A_-)/4$ (the determinant-type
invariants, odd under $O(4)\setminus SO(4)$, are $A_+-A_-$ and $E_+-E_-$).

**Why these generate (up to the degrees the reduced field needs).** $SO(4)$ preserves the tridegree
$(i, j, l)$ in $(K, u, q)$. The dimension of the invariants of each tridegree is the multiplicity of
the trivial representation in $S^i(\Lambda^2_+\oplus\Lambda^2_-)\otimes S^j(\mathbb{R}^4)\otimes S^l(\mathbb{R}^4)$,
computed exactly from the characters of $SU(2)\times SU(2)$ (weights $(\pm2,0),(0,0)$ on $\Lambda^2_+$,
$(0,\pm2),(0,0)$ on $\Lambda^2_-$, $(\pm1,\pm1)$ on $\mathbb{R}^4$; Weyl: $c_{00}-c_{20}-c_{02}+c_{22}$).
The products of the generators of that tridegree are evaluated at random points modulo a prime; the
rank modulo $p$ bounds the rank over $\mathbb{Q}$ from below and the character bounds it from above,
so equality proves that the products *span* the invariants of that tridegree
(:func:`generation_check`, FLINT ``nmod_mat`` and SymPy ``DomainMatrix`` over GF(p)).

**Relations.** 10 generators (with $s$) on the 8-dimensional quotient of $(K, u, q)$: the first two
relations sit in tridegrees $(2,2,2)$ and $(4,2,2)$ (one each, :func:`relations`, exact null space
over $\mathbb{Q}$ of the products' coefficient vectors); on $P$, $s = 1 - x^2$.
"""

from __future__ import annotations

import random
from collections import Counter
from functools import cache

import flint
import sympy as sp
from chaplygin_nd.symbolic.axisymmetric import a, b, x
from sympy import QQ
from sympy.polys.matrices import DomainMatrix
from sympy.polys.rings import ring

__all__ = ["NAMES", "TRIDEGREE", "SYMBOLS", "M", "gamma", "q", "RING", "PHASE_GENS", "K_matrix",
           "generator_polys", "invariant_dimension", "products", "generation_check", "relations",
           "in_generators", "to_phase_space", "INV_RING", "point_values"]

#: Generator names, in the order of the reduced coordinates (``s`` is replaced by $1 - x^2$ on $P$).
NAMES = ("Ap", "Am", "B", "G", "Ep", "Em", "Suu", "Suq", "Sqq", "s")
#: Tridegree in $(K, u, q)$ of each generator.
TRIDEGREE = {"Ap": (2, 0, 0), "Am": (2, 0, 0), "B": (0, 2, 0), "G": (0, 1, 1), "Ep": (1, 1, 1),
             "Em": (1, 1, 1), "Suu": (2, 2, 0), "Suq": (2, 1, 1), "Sqq": (2, 0, 2), "s": (0, 0, 2)}
SYMBOLS = {n: sp.Symbol(n, real=True) for n in NAMES}

#: $M \in \mathfrak{so}(5)$ with symbols ``M_ij`` ($i < j$) and $\gamma = (q_1..q_4, x)$.
_PAIRS = [(i, j) for i in range(5) for j in range(i + 1, 5)]
_M_SYMS = [sp.Symbol(f"M_{i + 1}{j + 1}", real=True) for i, j in _PAIRS]
M = sp.zeros(5, 5)
for (_i, _j), _s in zip(_PAIRS, _M_SYMS, strict=True):
    M[_i, _j], M[_j, _i] = _s, -_s
q = sp.Matrix(sp.symbols("q1:5", real=True))
gamma = sp.Matrix([*q, x])

#: $\mathbb{Q}[a, b, x, M_{ij}, q]$; the $K$ entries are $M_{ij}$, $i<j\le4$, and $u_i = M_{i5}$.
PHASE_GENS = (a, b, x, *_M_SYMS, *q)
RING, *_RG = ring(list(PHASE_GENS), QQ)
_PAR = 3
_K_IDX = [3 + k for k, (i, j) in enumerate(_PAIRS) if j < 4]
_U_IDX = [3 + k for k, (i, j) in enumerate(_PAIRS) if j == 4]
_Q_IDX = list(range(13, 17))
#: The reduced coordinates' ring $\mathbb{Q}[a, b, x, A_\pm, B, G, E_\pm, S_{uu}, S_{uq}, S_{qq}, s]$.
INV_RING, *_IV = ring([a, b, x, *SYMBOLS.values()], QQ)


def K_matrix(Mm):
    """The upper-left $4\\times4$ block $K$ of $M$ (list of lists), its $u = (M_{i5})$ (S6:reduced-n5)."""
    K = [[Mm[i][j] for j in range(4)] for i in range(4)]
    return K, [Mm[i][4] for i in range(4)]


def _hodge(K):
    r"""$(\star K)_{ij} = \tfrac12\varepsilon_{ijkl}K_{kl}$ on $\mathfrak{so}(4)$, orientation $e_{1234}$."""
    z = K[0][0] * 0
    S = [[z] * 4 for _ in range(4)]
    for (i, j, k, l, sign) in ((0, 1, 2, 3, 1), (0, 2, 1, 3, -1), (0, 3, 1, 2, 1), (1, 2, 0, 3, 1),
                               (1, 3, 0, 2, -1), (2, 3, 0, 1, 1)):
        S[i][j] = sign * K[k][l]
        S[j][i] = -S[i][j]
    return S


def _mv(A, v):
    return [sum((A[i][k] * v[k] for k in range(4)), v[0] * 0) for i in range(4)]


def _dot(v, w):
    return sum((vi * wi for vi, wi in zip(v, w, strict=True)), v[0] * 0)


def generators_from(Mm, qv) -> dict:
    r"""The generators (module docstring) of $M$ (5x5, any ring or numbers) and $q$ (length 4):
    dict name -> value. S6:reduced-n5."""
    K, u = K_matrix(Mm)
    S_ = _hodge(K)
    Kp = [[K[i][j] + S_[i][j] for j in range(4)] for i in range(4)]
    Km = [[K[i][j] - S_[i][j] for j in range(4)] for i in range(4)]
    kp = (K[0][1] + K[2][3], K[0][2] - K[1][3], K[0][3] + K[1][2])
    km = (K[0][1] - K[2][3], K[0][2] + K[1][3], K[0][3] - K[1][2])
    Su, Sq = _mv(Kp, _mv(Km, u)), _mv(Kp, _mv(Km, qv))
    return {"Ap": _dot(kp, kp), "Am": _dot(km, km), "B": _dot(u, u), "G": _dot(u, qv),
            "Ep": _dot(u, _mv(Kp, qv)), "Em": _dot(u, _mv(Km, qv)), "Suu": _dot(u, Su),
            "Suq": _dot(u, Sq), "Sqq": _dot(qv, Sq), "s": _dot(qv, qv)}


@cache
def generator_polys() -> dict:
    """The generators as elements of :data:`RING` (S6:reduced-n5)."""
    Mm = [[RING(0)] * 5 for _ in range(5)]
    for k, (i, j) in enumerate(_PAIRS):
        Mm[i][j], Mm[j][i] = _RG[3 + k], -_RG[3 + k]
    return generators_from(Mm, [_RG[i] for i in _Q_IDX])


# ------------------------------------------------------------------ characters and generation
def _sym_power(weights, d: int) -> Counter:
    dp: list[Counter] = [Counter() for _ in range(d + 1)]
    dp[0][(0, 0)] = 1
    for w in weights:
        new: list[Counter] = [Counter() for _ in range(d + 1)]
        for k in range(d + 1):
            for key, c in dp[k].items():
                for m in range(d - k + 1):
                    new[k + m][(key[0] + m * w[0], key[1] + m * w[1])] += c
        dp = new
    return dp[d]


def _times(c1: Counter, c2: Counter) -> Counter:
    out: Counter = Counter()
    for k1, v1 in c1.items():
        for k2, v2 in c2.items():
            out[(k1[0] + k2[0], k1[1] + k2[1])] += v1 * v2
    return out


_R4 = ((1, 1), (1, -1), (-1, 1), (-1, -1))
_SO4 = ((2, 0), (0, 0), (-2, 0), (0, 2), (0, 0), (0, -2))


@cache
def invariant_dimension(i: int, j: int, l: int) -> int:
    r"""$\dim$ of the $SO(4)$-invariant polynomials of tridegree $(i, j, l)$ in $(K, u, q)$: the
    multiplicity of the trivial representation, from $SU(2)\times SU(2)$ characters (module
    docstring; exact integer arithmetic). S6:reduced-n5."""
    ch = _times(_times(_sym_power(_SO4, i), _sym_power(_R4, j)), _sym_power(_R4, l))
    return ch[(0, 0)] - ch[(2, 0)] - ch[(0, 2)] + ch[(2, 2)]


def products(deg: tuple[int, int, int], names=NAMES) -> list[tuple[int, ...]]:
    """Exponent vectors (over ``names``) of the generator products of tridegree ``deg``, each once, in
    decreasing lexicographic order (the later generators' exponents vary fastest). S6:reduced-n5."""
    out = []

    def rec(k, cur, exps):
        if k == len(names):
            if cur == tuple(deg):
                out.append(tuple(exps))
            return
        d = TRIDEGREE[names[k]]
        e = 0
        while all(cur[t] + e * d[t] <= deg[t] for t in range(3)):
            rec(k + 1, tuple(cur[t] + e * d[t] for t in range(3)), exps + [e])
            e += 1
    rec(0, (0, 0, 0), [])
    return out[::-1]


def point_values(rng: random.Random, p: int) -> dict:
    """The generators at a random point of $(K, u, q)$ with entries in $[0, p)$, reduced mod ``p``."""
    Mm = [[0] * 5 for _ in range(5)]
    for i, j in _PAIRS:
        v = rng.randrange(p)
        Mm[i][j], Mm[j][i] = v, -v
    vals = generators_from(Mm, [rng.randrange(p) for _ in range(4)])
    return {k: v % p for k, v in vals.items()}


def _evaluation_rows(deg, rng, p, count):
    prods = products(deg)
    rows = []
    for _ in range(count):
        v = point_values(rng, p)
        rows.append([_mono_mod(v, e, p) for e in prods])
    return prods, rows


def _mono_mod(v, e, p):
    out = 1
    for name, k in zip(NAMES, e, strict=True):
        if k:
            out = out * pow(v[name], k, p) % p
    return out


def generation_check(degrees, seed: int, p: int = 2**61 - 1) -> list[dict]:
    r"""For each tridegree in ``degrees``: the invariant dimension (characters), the number of
    generator products, and their rank modulo ``p`` at ``len(products) + 4`` random points, by FLINT
    ``nmod_mat`` and by SymPy ``DomainMatrix`` over GF(p) (must agree). ``spans`` is rank == dimension
    (a proof that the products span the invariants of that tridegree). S6:reduced-n5."""
    from sympy.polys.domains import GF

    rng = random.Random(seed)
    out = []
    for deg in degrees:
        dim = invariant_dimension(*deg)
        prods, rows = _evaluation_rows(deg, rng, p, len(products(deg)) + 4)
        if not prods:
            out.append({"deg": tuple(deg), "dim": dim, "products": 0, "rank": 0, "spans": dim == 0})
            continue
        r_flint = int(flint.nmod_mat(rows, p).rank())
        F = GF(p)
        r_sympy = DomainMatrix([[F(c) for c in row] for row in rows], (len(rows), len(prods)), F).rank()
        if r_flint != r_sympy:
            raise ArithmeticError(f"rank mod p at {deg}: FLINT {r_flint}, SymPy {r_sympy}")
        out.append({"deg": tuple(deg), "dim": dim, "products": len(prods), "rank": r_flint,
                    "spans": r_flint == dim})
    return out


# ------------------------------------------------------------------ exact expression in generators
def _tridegree(mon) -> tuple[int, int, int]:
    return (sum(mon[i] for i in _K_IDX), sum(mon[i] for i in _U_IDX), sum(mon[i] for i in _Q_IDX))


@cache
def _product_polys(deg):
    g = generator_polys()
    out = []
    for e in products(deg):
        t = RING(1)
        for name, k in zip(NAMES, e, strict=True):
            if k:
                t *= g[name] ** k
        out.append(t)
    return out


@cache
def _basis(deg):
    """The monomials (sorted), their row index and the generator products of tridegree ``deg``."""
    polys = _product_polys(deg)
    keys = sorted({m for p_ in polys for m in p_.keys()})
    index = {m: r for r, m in enumerate(keys)}
    return keys, index, polys


def in_generators(N, *, strict: bool = True):
    r"""Write an $SO(4)$-invariant ``N`` $\in$ :data:`RING` as a polynomial in the generators with
    coefficients in $\mathbb{Q}[a, b, x]$ (element of :data:`INV_RING`; $s$ kept). Per tridegree,
    an ansatz over all generator products solved by exact rref over $\mathbb{Q}$ (the earliest
    independent products are used, so the form is canonical); raises ``ValueError`` when the system
    is inconsistent (``N`` not in the span: not invariant, or a missing generator). S6:reduced-n5."""
    pieces: dict = {}
    for mon, c in N.terms():
        pieces.setdefault(_tridegree(mon), []).append((mon, c))
    total = INV_RING(0)
    for deg, terms in sorted(pieces.items()):
        keys, index, polys = _basis(deg)
        rhs: dict = {}
        for mon, c in terms:
            par = mon[:_PAR]
            rhs.setdefault(par, {})[(0, 0, 0) + mon[_PAR:]] = c
        params = sorted(rhs)
        extra = sorted({m for r in rhs.values() for m in r} - set(index))
        if extra:
            raise ValueError(f"not in the span of the generator products (tridegree {deg})")
        width = len(polys) + len(params)
        rows = [[QQ(0)] * width for _ in keys]
        for j, pj in enumerate(polys):
            for m, c in pj.terms():
                rows[index[m]][j] = QQ(c)
        for j, al in enumerate(params):
            for m, c in rhs[al].items():
                rows[index[m]][len(polys) + j] = QQ(c)
        rref, pivots = DomainMatrix(rows, (len(keys), width), QQ).rref()
        if any(pc >= len(polys) for pc in pivots):
            raise ValueError(f"not in the span of the generator products (tridegree {deg})")
        rr = rref.to_list()
        prods = products(deg)
        for i, pc in enumerate(pivots):
            mono = INV_RING(1)
            for g_, k in zip(_IV[3:], prods[pc], strict=True):
                if k:
                    mono *= g_**k
            for j, al in enumerate(params):
                c = rr[i][len(polys) + j]
                if c:
                    total += c * _IV[0]**al[0] * _IV[1]**al[1] * _IV[2]**al[2] * mono
    return total


def to_phase_space(P):
    r"""$P\circ\pi$: substitute the generators (as polynomials of $(K, u, q)$) into ``P`` $\in$
    :data:`INV_RING`, an element of :data:`RING` (the quotient map of S6:reduced-n5)."""
    g = generator_polys()
    images = [_RG[0], _RG[1], _RG[2]] + [g[n] for n in NAMES]
    out = RING(0)
    for mon, c in P.terms():
        t = RING(c)
        for img, k in zip(images, mon, strict=True):
            if k:
                t *= img**k
        out += t
    return out


def on_sphere(P):
    r"""``P`` $\in$ :data:`INV_RING` with $s = \lVert q\rVert^2$ replaced by $1 - x^2$ (on $P$). S6:reduced-n5."""
    return P.compose(_IV[-1], 1 - _IV[2]**2)


def relations() -> dict:
    r"""The relations among the generators in tridegrees $(2,2,2)$ and $(4,2,2)$ (S6:reduced-n5):
    tridegree -> list of elements of :data:`INV_RING` (a basis of the exact null space over
    $\mathbb{Q}$ of the products' coefficient vectors; at $(4,2,2)$ modulo the multiples
    $A_\pm R_{222}$ of the first)."""
    out = {}
    for deg in ((2, 2, 2), (4, 2, 2)):
        keys, index, polys = _basis(deg)
        A = [[QQ(0)] * len(polys) for _ in keys]
        for j, pj in enumerate(polys):
            for m, c in pj.terms():
                A[index[m]][j] = QQ(c)
        null = DomainMatrix(A, (len(keys), len(polys)), QQ).nullspace().to_list()
        prods = products(deg)
        rels = []
        for vec in null:
            r = INV_RING(0)
            for c, e in zip(vec, prods, strict=True):
                if c:
                    mono = INV_RING(1)
                    for g_, k in zip(_IV[3:], e, strict=True):
                        if k:
                            mono *= g_**k
                    r += c * mono
            rels.append(r)
        out[deg] = rels
    return out


__all__ += ["generators_from", "on_sphere"]
