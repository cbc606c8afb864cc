r"""The unknowns of the exact first-integral search (row S6:first-integrals): a basis of the
candidate space $S(d, d_\gamma)$ split by symmetry.

**Coordinates.** A maximal torus $T$ of $SO(n-1)$ (the stabiliser of $E_n$, eq:SOnminus1) rotates
the planes $(E_1, E_2), (E_3, E_4), \dots$; it is diagonal in the complex basis
$\zeta_j = E_{2j-1} + iE_{2j}$, $\bar\zeta_j$ (weights $\pm e_j$), and fixes $E_{n-1}$ when $n - 1$ is
odd and $E_n$. The coordinates are the linear functions $\gamma \mapsto u^T\gamma$ and
$M \mapsto u^T M v$ ($u$ before $v$) for $u, v$ in that basis: $\binom{n}{2} + n$ functions with
Gaussian-integer coefficients in the real coordinates $(M_{ij})_{i<j}, \gamma$, a basis of the
linear forms over $\mathbb{Q}(i)$. With ``planes = 0`` (no torus: a mass tensor without
symmetry) they are the real coordinates themselves.

**Monomials.** $S(d, d_\gamma)$ is spanned by the monomials of degree exactly $d$ in the $M$
coordinates times a monomial in the $\gamma$ coordinates of degree $\le d_\gamma$ whose exponent
of $\gamma_n$ is $\le 1$: modulo $\|\gamma\|^2 - 1$ (monic of degree 2 in $\gamma_n$, and
$\gamma_n$ is itself a coordinate) these are the standard monomials, a basis of the polynomials
of degree $\le d_\gamma$ on the sphere. Only **weight zero** monomials are kept.

**Discrete symmetries.** The coordinate reflections $g_k = \mathrm{diag}(1, .., -1_k, .., 1)$
act on $P$ by $(M, \gamma) \mapsto (g_k M g_k, g_k\gamma)$; each maps a coordinate to $\pm$ a
coordinate ($\zeta_j \leftrightarrow \bar\zeta_j$ inside a plane), hence permutes the weight-zero
monomials with signs. The group $G \cong \mathbb{Z}_2^n$ they generate is abelian; for each
character $\chi$ the projections $\sum_g \chi(g)\, g\cdot m$ of the orbit representatives that do
not vanish form a basis of the $\chi$-isotypic part $S_\chi$, and $S = \bigoplus_\chi S_\chi$.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field

import numpy as np

__all__ = ["Coordinates", "coordinates", "Block", "Basis", "basis"]


@dataclass(frozen=True)
class Coordinates:
    """The coordinate functions of P over Q(i): ``re``/``im`` rows give each coordinate as a
    Gaussian-integer combination of the real coordinates ``(M_ij)_{i<j}`` then ``gamma``."""

    n: int
    planes: int
    names: tuple[str, ...]
    re: np.ndarray            # (V, dim) integer
    im: np.ndarray
    is_gamma: np.ndarray      # (V,) bool
    weight: np.ndarray        # (V, planes) integer
    xn: int                   # index of the coordinate gamma_n
    action: tuple             # per reflection k: (permutation (V,), signs (V,))


def _pairs(n):
    return [(i, j) for i in range(n) for j in range(i + 1, n)]


def coordinates(n: int, planes: int) -> Coordinates:
    r"""The coordinates of the module docstring for $n \ge 3$ and ``planes`` torus planes
    ($0 \le$ ``planes`` $\le \lfloor (n-1)/2 \rfloor$)."""
    if not 0 <= planes <= (n - 1) // 2:
        raise ValueError(f"planes must lie in 0..{(n - 1) // 2}")
    vecs, wts, labels = [], [], []
    for j in range(planes):
        for s, lab in ((1, f"z{j + 1}"), (-1, f"zb{j + 1}")):
            v = np.zeros(n, dtype=complex)
            v[2 * j], v[2 * j + 1] = 1, 1j * s
            w = np.zeros(planes, dtype=np.int64)
            w[j] = s
            vecs.append(v)
            wts.append(w)
            labels.append(lab)
    for k in range(2 * planes, n):
        v = np.zeros(n, dtype=complex)
        v[k] = 1
        vecs.append(v)
        wts.append(np.zeros(planes, dtype=np.int64))
        labels.append(f"e{k + 1}")
    pairs = _pairs(n)
    rows, weights, names, is_g = [], [], [], []
    for a, b in _pairs(n):   # M coordinates u^T M v = sum_{k<l} (u_k v_l - u_l v_k) M_kl
        u, v = vecs[a], vecs[b]
        rows.append(np.concatenate([[u[k] * v[l] - u[l] * v[k] for k, l in pairs], np.zeros(n)]))
        weights.append(wts[a] + wts[b])
        names.append(f"M[{labels[a]},{labels[b]}]")
        is_g.append(False)
    for a in range(n):
        rows.append(np.concatenate([np.zeros(len(pairs)), vecs[a]]))
        weights.append(wts[a])
        names.append(f"g[{labels[a]}]")
        is_g.append(True)
    C = np.array(rows)
    re, im = np.rint(C.real).astype(np.int64), np.rint(C.imag).astype(np.int64)
    actions = []
    for k in range(n):   # reflection g_k on the real coordinates, then matched to +- a coordinate
        flip = np.ones(n, dtype=np.int64)
        flip[k] = -1
        real_sign = np.array([flip[i] * flip[j] for i, j in pairs] + list(flip))
        perm: list[int] = []
        sign: list[int] = []
        for r in range(len(rows)):
            image = C[r] * real_sign
            for t in range(len(rows)):
                if np.allclose(image, C[t]):
                    perm.append(t)
                    sign.append(1)
                    break
                if np.allclose(image, -C[t]):
                    perm.append(t)
                    sign.append(-1)
                    break
            else:
                raise ArithmeticError("a reflection does not permute the coordinates")
        actions.append((np.array(perm), np.array(sign)))
    return Coordinates(n, planes, tuple(names), re, im, np.array(is_g), np.array(weights),
                       len(rows) - 1, tuple(actions))


@dataclass
class Block:
    """The basis of one isotypic part S_chi: column c is sum_t sign[t] * monomial[t] over the
    entries t with ``column[t] == c``."""

    character: int            # bit k set: chi(g_k) = -1
    columns: int
    monomial: np.ndarray
    sign: np.ndarray
    column: np.ndarray


@dataclass
class Basis:
    """All weight-zero standard monomials of S(d, d_gamma) (``exponents``) and their split."""

    coords: Coordinates
    d: int
    d_gamma: int
    exponents: np.ndarray     # (N, V)
    blocks: list[Block] = field(default_factory=list)

    @property
    def size(self) -> int:
        return len(self.exponents)


def _monomials(count: int, degree: int):
    for combo in itertools.combinations_with_replacement(range(count), degree):
        e = [0] * count
        for c in combo:
            e[c] += 1
        yield tuple(e)


def basis(n: int, d: int, d_gamma: int, planes: int) -> Basis:
    r"""The basis of $S(d, d_\gamma)$ (module docstring) split into the isotypic parts of the
    reflection group; $n \ge 3$, $d \ge 1$, $d_\gamma \ge 0$."""
    co = coordinates(n, planes)
    mi = [i for i in range(len(co.names)) if not co.is_gamma[i]]
    gi = [i for i in range(len(co.names)) if co.is_gamma[i]]
    by_weight: dict[tuple, list] = {}
    for e in _monomials(len(mi), d):
        w = tuple(np.asarray(e) @ co.weight[mi]) if planes else ()
        by_weight.setdefault(w, []).append(e)
    gam: dict[tuple, list] = {}
    xn = gi.index(co.xn)
    for deg in range(d_gamma + 1):
        for e in _monomials(len(gi), deg):
            if e[xn] <= 1:
                w = tuple(np.asarray(e) @ co.weight[gi]) if planes else ()
                gam.setdefault(w, []).append(e)
    rows = []
    for w, ms in by_weight.items():
        neg = tuple(-x for x in w)
        for g in gam.get(neg, []):
            for m in ms:
                full = [0] * len(co.names)
                for i, x in zip(mi, m):
                    full[i] = x
                for i, x in zip(gi, g):
                    full[i] = x
                rows.append(tuple(full))
    rows.sort()
    out = Basis(co, d, d_gamma, np.array(rows, dtype=np.int64).reshape(len(rows), len(co.names)))
    out.blocks = _split(out)
    return out


def _act(co: Coordinates, k: int, e: tuple) -> tuple[tuple, int]:
    perm, sign = co.action[k]
    img = [0] * len(e)
    s = 1
    for i, x in enumerate(e):
        if x:
            img[perm[i]] = x
            if sign[i] < 0 and x % 2:
                s = -s
    return tuple(img), s


def _split(B: Basis) -> list[Block]:
    """Orbits of the reflections on the monomials (BFS with Schreier relations), then for every
    character the non-vanishing projections of the orbit representatives."""
    co, n = B.coords, B.coords.n
    index = {tuple(e): i for i, e in enumerate(B.exponents.tolist())}
    seen = np.full(B.size, -1)
    orbits: list[tuple[dict, list]] = []   # (members [(index, mask, sign)], stabiliser relations [(mask, sign)])
    for start in range(B.size):
        if seen[start] >= 0:
            continue
        members, rel = {start: (0, 1)}, []
        queue = [start]
        seen[start] = len(orbits)
        while queue:
            i = queue.pop()
            mask, s = members[i]
            e = tuple(B.exponents[i])
            for k in range(n):
                img, sk = _act(co, k, e)
                j = index[img]
                m2, s2 = mask ^ (1 << k), s * sk
                if j in members:
                    mj, sj = members[j]
                    if (m2, s2) != (mj, sj):
                        rel.append((m2 ^ mj, s2 * sj))
                else:
                    members[j] = (m2, s2)
                    seen[j] = len(orbits)
                    queue.append(j)
        orbits.append((members, rel))
    blocks = []
    for chi in range(1 << n):
        mono, sign, col = [], [], []
        c = 0
        for members, rel in orbits:
            if any((-1) ** bin(chi & m).count("1") * s != 1 for m, s in rel):
                continue   # the projection of this orbit vanishes for chi
            for j, (m, s) in members.items():
                mono.append(j)
                sign.append((-1) ** bin(chi & m).count("1") * s)
                col.append(c)
            c += 1
        if c:
            blocks.append(Block(chi, c, np.array(mono), np.array(sign), np.array(col)))
    return blocks
