r"""Exact search for first integrals of the $n$-dimensional Chaplygin sphere (row
S6:first-integrals, beyond the paper): the weight-zero strategy of symbolic/search/box_search.py.

**The question.** Which $F = P/D^k$, $P$ polynomial in $(M, \gamma)$, are first integrals of the
field $X$ of eq:motion-general on $P = \mathfrak{so}(n)\times S^{n-1}$? Here $D$ is the denominator
of $\Omega = L_\gamma^{-1}(M)$ (symbolic/search/sampled_field.py: $\Delta$ of eq:Delta for the axisymmetric
sphere, $\det L_\gamma$ otherwise). $X(P/D^k) = (D\,X(P) - kP\,X(D))/D^{k+1}$, and $D\,X(P)$ is a
polynomial, so $F$ is an integral iff $D\,X(P) - kP\,X(D) \equiv 0$ modulo $\|\gamma\|^2 - 1$.

**Reductions (nothing is lost for the question asked).**
(i) $X$ raises the $M$-degree by exactly one ($\Omega$ is linear in $M$, $D$ depends on $\gamma$
only), so every $M$-homogeneous part of an integral is an integral: the search is per $M$-degree
$d$. (ii) The box $S(d, d_\gamma, k)$: $P$ of $M$-degree $d$ and $\gamma$-degree $\le d_\gamma$ on the
sphere, in the standard-monomial basis (symbolic/search/candidate_basis.py). (iii) For the axisymmetric
sphere $X$ is $SO(n-1)$-equivariant (eq:action); a torus $T$ acts on integrals, and the
projection onto weight zero (the $T$-average) of an integral is an integral. We search **weight
zero** only: we find every $T$-invariant integral, in particular every $SO(n-1)$-invariant one —
exactly the integrals of the reduced system on $P/SO(n-1)$. Integrals of non-zero weight are not
searched (none is a function on $P/SO(n-1)$). (iv) The coordinate reflections $g_k$ commute with
$X$ for diagonal $\mathbb{J}$; the projections onto the isotypic parts $S_\chi$ of an integral are
integrals, and we search every $\chi$: no loss.

**Exactness (the argument written into the row).** Let $V_\chi \subset S_\chi$ be the
$\mathbb{Q}(i)$-space of integrals (the torus coordinates have Gaussian coefficients; $V_\chi$ is
the complexification of the real space, same dimension). Rows of the matrix $A_p$ are the
conditions $X(P)(z) - kP(z)\,X(D)(z)/D(z) = 0$ at points $z$ of the sphere mod $p$, $p \equiv 1
\bmod 4$ (so $i \in \mathbb{F}_p$), with $D(z) \ne 0$. Take a basis of the saturated lattice
$V_\chi \cap \mathbb{Z}[i]^N$ ($\mathbb{Z}[i]$ is a PID, a saturated submodule is a direct summand):
its reduction modulo a prime over $p$ stays linearly independent, and satisfies every row
(the identity $D\,X(P) - kP\,X(D) = (\|\gamma\|^2 - 1)Q$ has $p$-integral coefficients, as
$\|\gamma\|^2 - 1$ is monic in $\gamma_n$). Hence **nullity$_p(A_p) \ge \dim V_\chi$**, for any
number of rows. On the other side, the known integrals whose products lie in the box
(symbolic/search/known_integrals.py) span $K_\chi \subset V_\chi$, and the rank mod $p$ of their values at points
is **$\le \dim K_\chi$**. So $\mathrm{rank}_p(\text{known}) \le \dim K_\chi \le \dim V_\chi \le
\mathrm{nullity}_p(A_p)$; when the two ends agree, **$V_\chi = K_\chi$ exactly**: no integral in the
box beyond the algebra of the known ones. If they do not agree, the excess is a *candidate*, never
an integral until reconstructed over $\mathbb{Q}$ and proved by an exact identity with both
engines. The recovery check evaluates an $\mathbb{F}_p$ basis of the kernel at fresh points and
tests that the known integrals lie in its span (a search that misses a known integral fails).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from chaplygin_nd.symbolic.search import (
    backend,
    candidate_basis,
    conditions,
    known_integrals,
    sampled_field,
)
from chaplygin_nd.symbolic.search.box_search import (
    MARGIN,
    RECOVERY_MAX,
    BlockResult,
    BoxSearch,
    DegreeResult,
    box_for,
)
from chaplygin_nd.symbolic.search.sampled_field import Model

__all__ = ["WeightZeroSearch", "BlockResult", "DegreeResult", "search_degree", "search",
           "known_ranks", "box_for", "MARGIN", "RECOVERY_MAX"]

CHUNK_ENTRIES = 4_000_000  #: entries of one chunk of the conditions (memory only: same matrix)


def _flipped_values(model: Model, zq: np.ndarray, p: int, include_new: bool) -> list[np.ndarray]:
    """Generator values at g.zq for every reflection g (bitmask order)."""
    n = model.n
    out = []
    for mask in range(1 << n):
        s = np.array([-1 if mask >> i & 1 else 1 for i in range(n)])
        real = np.array([s[i] * s[j] for i in range(n) for j in range(i + 1, n)] + list(s))
        out.append(known_integrals.values(model, zq * real[None, :] % p, p, include_new))
    return out


def _known_matrix(prods, character: int, flipped, Dk: np.ndarray, p: int) -> np.ndarray:
    """Values of the chi-projections of the known products at the points, times D^k (D is
    invariant under the reflections): the numerators P of the products as elements of the box."""
    acc = np.zeros((len(Dk), len(prods)), dtype=np.int64)
    for mask, gv in enumerate(flipped):
        chi = -1 if bin(character & mask).count("1") % 2 else 1
        for c, pr in enumerate(prods):
            v = np.ones(len(Dk), dtype=np.int64)
            for i in pr:
                v = v * gv[:, i] % p
            acc[:, c] = (acc[:, c] + chi * v) % p
    return acc * Dk[:, None] % p


@dataclass
class _Box:
    """The context of one box: the basis, its blocks and the points of the known products."""

    box: tuple
    p: int
    i_p: int
    basis: candidate_basis.Basis
    blocks: dict
    prods: list
    zq: np.ndarray
    flipped: list
    Dk: np.ndarray


class WeightZeroSearch(BoxSearch):
    """Integrals $P/D^k$ in the weight-zero part of a maximal torus of $SO(n-1)$, split by the
    characters of the coordinate reflections (module docstring); any diagonal mass tensor
    (``planes = 0``: no torus)."""

    @property
    def invariance(self) -> str:
        """The class searched: weight zero for the torus (larger than the invariants)."""
        return "weight zero of a maximal torus of SO(n-1) (contains every SO(n-1)-invariant integral)"

    def unknown_counts(self, box):
        d, d_gamma, _k = box
        return [b.columns for b in candidate_basis.basis(self.model.n, d, d_gamma, self.model.planes).blocks]

    def prepare(self, box, p):
        d, d_gamma, k = box
        model, seed = self.model, self.seed
        B = candidate_basis.basis(model.n, d, d_gamma, model.planes)
        prods = known_integrals.products(model, d, d_gamma, k, self.include_new)
        zq = sampled_field.sample(model, len(prods) + MARGIN, p,
                                  np.random.default_rng([seed, 7, d, k]))["z"]
        flipped = _flipped_values(model, zq, p, self.include_new) if prods else []
        Dk = np.ones(len(zq), dtype=np.int64)
        for _ in range(k):
            Dk = Dk * sampled_field.field_at(model, zq, p)["D"] % p
        return _Box(box, p, backend.sqrt_minus_one(p), B, {b.character: b.columns for b in B.blocks},
                    prods, zq, flipped, Dk)

    def condition_matrices(self, ctx):
        d, d_gamma, k = ctx.box
        p, B = ctx.p, ctx.basis
        co = B.coords
        rng = np.random.default_rng([self.seed, self.model.n, d, d_gamma, k, self.prime_index])
        rows = max(b.columns for b in B.blocks) + MARGIN
        s = sampled_field.sample(self.model, rows + rows // 8 + 8, p, rng)
        cv = conditions.coordinate_values(co, s["z"], p, ctx.i_p)
        cd = conditions.coordinate_values(co, s["zdot"], p, ctx.i_p)
        cv, cd, dlog = conditions.admissible(cv, cd, s["dlogD"], rows)
        blocks_A: dict[int, list] = {b.character: [] for b in B.blocks}
        chunk = max(1, CHUNK_ENTRIES // max(1, B.size))
        for r0 in range(0, rows, chunk):
            sl = slice(r0, r0 + chunk)
            Y = conditions.condition_values(B.exponents, cv[sl], cd[sl], dlog[sl], k, p)
            for b in B.blocks:
                need = b.columns + MARGIN
                if r0 < need:
                    blocks_A[b.character].append(conditions.block_apply(Y[: need - r0], b, p))
        return _Lazy({c: v for c, v in blocks_A.items()})

    def known_values(self, ctx, label):
        if not ctx.prods:
            return np.zeros((len(ctx.zq), 0), np.int64)
        return _known_matrix(ctx.prods, label, ctx.flipped, ctx.Dk, ctx.p)

    def known_count(self, ctx):
        return len(ctx.prods)

    def basis_values(self, ctx, label):
        B = ctx.basis
        blk = next(b for b in B.blocks if b.character == label)
        cvq = conditions.coordinate_values(B.coords, ctx.zq, ctx.p, ctx.i_p)
        return conditions.block_apply(conditions.monomial_values(B.exponents, cvq, ctx.p), blk, ctx.p)


class _Lazy(dict):
    """Block label -> its condition rows, concatenated when the base pops them."""

    def pop(self, key, *default):
        parts = super().pop(key, *default)
        return np.concatenate(parts, axis=0)


def search_degree(model: Model, d: int, d_gamma: int, k: int = 0, *, prime_index: int = 0,
                  seed: int = 0, include_new: bool = True, backend: str = "flint",
                  progress: Callable[[str], None] | None = None) -> DegreeResult:
    r"""The integrals $P/D^k$ in the box $S(d, d_\gamma)$ of ``model`` (module docstring), one
    prime (``backend.PRIMES[prime_index]``). $d \ge 1$, $d_\gamma \ge 0$, $k \ge 0$.
    ``include_new``: count the integral found by the search (search.found_integral) among the known ones;
    ``False`` counts only the paper's (the search then reports it as the excess)."""
    if d < 1 or d_gamma < 0 or k < 0:
        raise ValueError("need d >= 1, d_gamma >= 0, k >= 0")
    return WeightZeroSearch(model, backend=backend, prime_index=prime_index, seed=seed,
                            include_new=include_new).run_box((d, d_gamma, k), progress)


def known_ranks(model: Model, d: int, d_gamma: int, k: int, include_new: bool, *,
                prime_index: int = 0, seed: int = 0) -> dict[int, int]:
    """Per character: the rank mod p of the known products in the box (a lower bound of the
    dimension of their span over Q), without the search matrix."""
    return WeightZeroSearch(model, prime_index=prime_index, seed=seed,
                            include_new=include_new).known_ranks((d, d_gamma, k))


def search(model: Model, boxes, **kw) -> list[DegreeResult]:
    """:func:`search_degree` over ``boxes`` = iterable of (d, d_gamma, k)."""
    return [search_degree(model, d, dg, k, **kw) for d, dg, k in boxes]
