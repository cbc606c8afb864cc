r"""The $SO(m)$-invariants of $(K, u, q) \in \mathfrak{so}(m)\oplus\mathbb{R}^m\oplus\mathbb{R}^m$ for any
$m$: their dimensions from the Weyl character formula, and generators found among natural
candidates (for the invariant-ring search at $n = m + 1 \ge 6$, symbolic/search/invariant_rings.py).

**Dimensions.** The multiplicity of the trivial representation in a representation with weight
multiplicities $c(\mu)$ is $\sum_{w \in W} \det(w)\, c(\rho - w\rho)$ (Weyl's character formula
evaluated at the trivial weight; Fulton–Harris, Proposition 25.8 / Brauer–Klimyk). For $SO(m)$,
$r = \lfloor m/2\rfloor$: the weights of $\mathbb{R}^m$ are $\pm e_i$ (and $0$ for odd $m$), those
of $\mathfrak{so}(m) = \Lambda^2\mathbb{R}^m$ are $\pm e_i \pm e_j$ ($i<j$), $\pm e_i$ (odd $m$) and
$0$ ($r$ times); $W$ is the signed permutations (type $B_r$, $m$ odd) or those with an even number of
sign changes ($D_r$, $m$ even); $\rho_i = r - i - \tfrac12$ ($B_r$) or $r - i$ ($D_r$), $i = 1..r$.
Weights are doubled here so that they are integers. :func:`dimension` sums the multiplicity over
$S^i(\mathfrak{so}(m))\otimes S^{d-i}(\mathbb{R}^m)\otimes S^l(\mathbb{R}^m)$, $i = 0..d$: the
invariants of $M$-degree $d$ ($K$ and $u$ together) and $q$-degree $l$. (For $m = 4$ it agrees with
the $SU(2)\times SU(2)$ count of symbolic/reduction/invariants_n5.py, for $m = 3$ with the $SU(2)$
count: tests/test_invariant_search.py.)

**Candidates.** The $O(m)$-invariants $\operatorname{tr}K^{2i}$, $u^TK^{2j}u$, $q^TK^{2j}q$, $u^TK^jq$
(the first fundamental theorem for $O(m)$ with one skew matrix and two vectors: traces of words
and forms $v^T(\text{word})w$; Cayley–Hamilton bounds the powers by $m - 1$) and the contractions
with the volume form $\varepsilon(K^{\wedge c}\wedge w_1\wedge\cdots\wedge w_{m-2c})$,
$w_t \in \{K^ju, K^jq\}$ distinct (the $SO(m)$-invariants odd under $O(m)\setminus SO(m)$). A
candidate is kept when it raises the rank mod $p$ of the products of those kept before it in its
bidegree. **No completeness is assumed**: the search's basis (symbolic/search/invariant_search.py)
compares the rank of the products with :func:`dimension` in every bidegree it uses and refuses
a deficit.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from functools import cache

import numpy as np
from chaplygin_nd.symbolic.search.weights import symmetric_power, tensor_product

__all__ = ["dimension", "Candidate", "generators", "products_of"]


@cache
def _root_data(m: int):
    r = m // 2

    def e(i, s):
        return tuple(2 * s if t == i else 0 for t in range(r))

    vec = [e(i, s) for i in range(r) for s in (1, -1)] + ([(0,) * r] if m % 2 else [])
    so = [tuple(2 * s if k == i else 2 * t if k == j else 0 for k in range(r))
          for i in range(r) for j in range(i + 1, r) for s in (1, -1) for t in (1, -1)]
    if m % 2:
        so += [e(i, s) for i in range(r) for s in (1, -1)]
    so += [(0,) * r] * r
    rho = [m - 2 - 2 * i for i in range(r)]          # doubled rho of B_r and D_r alike
    weyl = []
    for perm in itertools.permutations(range(r)):
        inv = sum(1 for a in range(r) for b in range(a + 1, r) if perm[a] > perm[b])
        for signs in itertools.product((1, -1), repeat=r):
            neg = signs.count(-1)
            if m % 2 == 0 and neg % 2:
                continue
            shift = tuple(rho[k] - signs[k] * rho[perm[k]] for k in range(r))
            weyl.append(((-1) ** (inv + neg), shift))
    return vec, so, weyl


@cache
def dimension(m: int, d: int, l: int) -> int:
    r"""$\dim$ of the $SO(m)$-invariant polynomials of $M$-degree $d$ in $(K, u)$ and degree $l$ in
    $q$ (module docstring), $m \ge 2$."""
    vec, so, weyl = _root_data(m)
    out = 0
    for i in range(d + 1):
        ch = tensor_product(tensor_product(symmetric_power(so, i), symmetric_power(vec, d - i)), symmetric_power(vec, l))
        out += sum(sign * ch[shift] for sign, shift in weyl)
    return out


@dataclass(frozen=True)
class Candidate:
    """One invariant: kind ``tr`` (tr K^j), ``form`` (a^T K^j b, a, b in 'u', 'q') or ``eps``
    (c copies of K and the vectors ``vecs`` = ((letter, power), ...)), its name and degrees."""

    name: str
    kind: str
    data: tuple
    m_degree: int
    q_degree: int


def _vectors(m):
    return [("u", j) for j in range(m)] + [("q", j) for j in range(m)]


def _vdeg(v):
    return (v[1] + 1, 0) if v[0] == "u" else (v[1], 1)


def candidates(m: int, dmax: int, lmax: int) -> list[Candidate]:
    """The candidates of the module docstring with M-degree <= dmax and q-degree <= lmax, lowest
    total degree first."""
    out = [Candidate(f"tr K^{2 * i}", "tr", (2 * i,), 2 * i, 0) for i in range(1, m // 2 + 1)]
    for j in range(m):
        if j % 2 == 0:
            out.append(Candidate(f"u.K^{j}u", "form", ("u", j, "u"), j + 2, 0))
            out.append(Candidate(f"q.K^{j}q", "form", ("q", j, "q"), j, 2))
        out.append(Candidate(f"u.K^{j}q", "form", ("u", j, "q"), j + 1, 1))
    for c in range(m // 2 + 1):
        for vecs in itertools.combinations(_vectors(m), m - 2 * c):
            dm = c + sum(_vdeg(v)[0] for v in vecs)
            dq = sum(_vdeg(v)[1] for v in vecs)
            name = "eps(" + ",".join(["K"] * c + [f"K^{j}{a}" for a, j in vecs]) + ")"
            out.append(Candidate(name, "eps", (c, vecs), dm, dq))
    out = [c for c in out if c.m_degree <= dmax and c.q_degree <= lmax and c.m_degree + c.q_degree > 0]
    return sorted(out, key=lambda c: (c.m_degree + c.q_degree, c.m_degree, c.name))


@cache
def _permutations(m: int):
    out = []
    for perm in itertools.permutations(range(m)):
        inv = sum(1 for a in range(m) for b in range(a + 1, m) if perm[a] > perm[b])
        out.append((perm, -1 if inv % 2 else 1))
    return out


def evaluate(cands: list[Candidate], K: np.ndarray, u: np.ndarray, q: np.ndarray, p: int) -> np.ndarray:
    """Values (points, candidates) mod p at K (points, m, m), u, q (points, m), entries in [0, p)."""
    m = K.shape[1]
    powers = [np.broadcast_to(np.eye(m, dtype=np.int64), K.shape).copy()]
    for _ in range(1, m):
        powers.append(np.einsum("rij,rjk->rik", powers[-1], K) % p)
    vec = {"u": [np.einsum("rij,rj->ri", P_, u) % p for P_ in powers],
           "q": [np.einsum("rij,rj->ri", P_, q) % p for P_ in powers]}
    base = {"u": u, "q": q}
    cols = []
    for c in cands:
        if c.kind == "tr":
            j = c.data[0]
            Pj = powers[j] if j < m else np.einsum("rij,rjk->rik", powers[j - m + 1], powers[m - 1]) % p
            cols.append(np.einsum("rii->r", Pj) % p)
        elif c.kind == "form":
            a, j, b = c.data
            cols.append(np.einsum("ri,ri->r", base[a], vec[b][j]) % p)
        else:
            k, vecs = c.data
            ws = [vec[a][j] for a, j in vecs]
            acc = np.zeros(K.shape[0], dtype=np.int64)
            for perm, sign in _permutations(m):
                t = np.ones(K.shape[0], dtype=np.int64)
                for s in range(k):
                    t = t * K[:, perm[2 * s], perm[2 * s + 1]] % p
                for s, w in enumerate(ws):
                    t = t * w[:, perm[2 * k + s]] % p
                acc = (acc + sign * t) % p
            cols.append(acc)
    return np.stack(cols, axis=1) if cols else np.zeros((K.shape[0], 0), np.int64)


def products_of(m_degree, q_degree, d: int, l: int) -> list[tuple[int, ...]]:
    """Exponent vectors of the products of generators with the given degrees that have M-degree d
    and q-degree l (generators of degree (0, 0) excluded)."""
    out = []
    r = len(m_degree)

    def rec(i, dm, dq, acc):
        if i == r:
            if dm == d and dq == l:
                out.append(tuple(acc))
            return
        e = 0
        while dm + e * m_degree[i] <= d and dq + e * q_degree[i] <= l:
            rec(i + 1, dm + e * m_degree[i], dq + e * q_degree[i], acc + [e])
            if m_degree[i] == 0 and q_degree[i] == 0:
                break
            e += 1

    rec(0, 0, 0, [])
    return out


def _random_KUQ(m, count, p, seed):
    rng = np.random.default_rng([seed, m, count])
    K = np.zeros((count, m, m), dtype=np.int64)
    for i in range(m):
        for j in range(i + 1, m):
            v = rng.integers(0, p, size=count)
            K[:, i, j], K[:, j, i] = v, (-v) % p
    return K, rng.integers(0, p, size=(count, m)), rng.integers(0, p, size=(count, m))


@cache
def generators(m: int, dmax: int, lmax: int, p: int) -> tuple[Candidate, ...]:
    """Candidates kept by the rank test of the module docstring (seeded points mod p)."""
    from chaplygin_nd.symbolic.search import backend, conditions

    la = backend.get()
    kept: list[Candidate] = []
    vals_kept = np.zeros((0, 0), np.int64)
    cands = candidates(m, dmax, lmax)
    pts = 64
    K, u, q = _random_KUQ(m, pts, p, 1)
    for c in cands:
        v = evaluate([c], K, u, q, p)
        if not v.any():
            continue
        if not kept:
            kept.append(c)
            vals_kept = v
            continue
        prods = products_of([k.m_degree for k in kept], [k.q_degree for k in kept], c.m_degree, c.q_degree)
        if len(prods) + 8 > pts:
            pts = 2 * (len(prods) + 8)
            K, u, q = _random_KUQ(m, pts, p, 1)
            vals_kept = evaluate(kept, K, u, q, p)
            v = evaluate([c], K, u, q, p)
        if prods:
            P_ = conditions.monomial_values(np.array(prods, dtype=np.int64), vals_kept, p)
            before = la.rank(P_, p)
            after = la.rank(np.concatenate([P_, v], axis=1), p)
        else:
            before, after = 0, 1
        if after > before:
            kept.append(c)
            vals_kept = np.concatenate([vals_kept, v], axis=1)
    return tuple(kept)
