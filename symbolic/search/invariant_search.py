r"""The first-integral search in the invariant ring (row S6:first-integrals): a strategy of
symbolic/search/box_search.py whose unknowns are polynomials in the generators of the
$SO(n-1)$-invariants (symbolic/search/invariant_rings.py) instead of weight-zero monomials.

**The box.** $S^G(d, d_\gamma, k)$: the $G$-invariant $P$ of $M$-degree $d$ and $\gamma$-degree
$\le d_\gamma$ on the sphere, over $D^k$ ($D = \Delta$ for the axisymmetric sphere, $\det L_\gamma$
otherwise; symbolic/search/sampled_field.py). On $S^{n-1}$ every polynomial has exactly one form
$f_0(K, u, q) + x f_1(K, u, q)$ (standard monomials: $x^2 = 1 - \lVert q\rVert^2$), and the
$\gamma$-degree is $\max(\deg_q f_0, 1 + \deg_q f_1)$; $G$ fixes $x$ and acts linearly on $q$, so the
Reynolds operator maps the weight-zero box onto
$S^G = \{f_0 + xf_1 : f_0 \in I_{d,\le d_\gamma},\ f_1 \in I_{d,\le d_\gamma - 1}\}$, $I_{d,l}$ the
invariants of $M$-degree $d$ and $q$-degree $l$. **Unknowns:** for each $(d, l)$ a basis of $I_{d,l}$
chosen among the generator products (pivot columns of their values at random points mod $p$),
with a **proof that it is one**: its size equals $\dim I_{d,l}$ from characters (rank$_p \le$
rank$_\mathbb{Q} \le \dim$, so equality gives independence over $\mathbb{Q}$ and spanning); a
deficit raises. Every $G$-invariant integral of the box is then a combination of the unknowns:
**nothing of the invariance class is lost**; the class is smaller than the weight-zero one (a
$T$-invariant integral that is not $G$-invariant is not searched), and it is exactly the class of
integrals of the reduced system on $P/G$.

**Blocks.** Each generator and $x$ is even or odd under the reflections of the ring (they commute
with $X$ and normalise $G$); a product is an eigenvector, so the unknowns split by character
without mixing, and the known products are projected ($\sum_g \chi(g) f(g\cdot z)$).

**Conditions and exactness.** Rows: $X(P)(z) - kP(z)X(D)(z)/D(z) = 0$ at seeded points of $P$ mod
$p$ (symbolic/search/conditions.py, with $\dot g_i = dg_i(X)$ from the exact interpolation of
$t \mapsto g_i(z + t\dot z)$ at $\max_i \deg g_i + 1$ nodes). The unknowns have integer
coefficients, so the saturated-lattice argument of symbolic/search/integral_search.py gives
nullity$_p \ge \dim_\mathbb{Q} V^G$; the known integrals are $G$-invariant and lie in the box, so
rank$_p$(known) $\le \dim K \le \dim V^G$. Equal ends: $V^G = K$ exactly.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from math import comb

import numpy as np
from chaplygin_nd.symbolic.search import (
    backend,
    conditions,
    invariant_rings,
    known_integrals,
    sampled_field,
)
from chaplygin_nd.symbolic.search.box_search import MARGIN, BoxSearch

__all__ = ["InvariantRingSearch", "basis", "derivative_nodes"]



def derivative_nodes(degree: int) -> list[tuple[int, Fraction]]:
    r"""Nodes $t = 0..D$ and weights with $h'(0) = \sum_t w_t h(t)$ for every polynomial $h$ of
    degree $\le D$ (Lagrange: $w_0 = -\sum_{t=1}^D 1/t$, $w_t = (-1)^{t+1}\binom{D}{t}/t$)."""
    return [(0, -sum((Fraction(1, t) for t in range(1, degree + 1)), Fraction(0)))] + \
        [(t, Fraction((-1) ** (t + 1) * comb(degree, t), t)) for t in range(1, degree + 1)]


def _parities(ring, p: int = backend.PRIMES[1]) -> np.ndarray:
    """(generators + 1, reflections): 1 where odd. The last row is x = gamma_n."""
    z = np.random.default_rng([11, ring.n]).integers(1, p, size=(1, ring.n * (ring.n + 1) // 2))
    v = ring.values(z, p)[0]
    out = np.zeros((len(ring.names) + 1, len(ring.reflections)), dtype=np.int64)
    for c, k in enumerate(ring.reflections):
        w = ring.values(invariant_rings.reflect(z, ring.n, 1 << k, p), p)[0]
        for i in range(len(v)):
            if w[i] == (-v[i]) % p and v[i]:
                out[i, c] = 1
            elif w[i] != v[i]:
                raise ArithmeticError(f"generator {ring.names[i]} is neither even nor odd under g_{k + 1}")
        out[-1, c] = 1 if k == ring.n - 1 else 0
    return out


@cache
def basis(n: int, kind: str, d: int, l: int) -> dict:
    r"""Character -> exponent vectors (over the ring's generators) of a basis of $I_{d,l}$
    chosen among the generator products (module docstring); ArithmeticError when the products do
    not reach $\dim I_{d,l}$ (characters)."""
    ring = invariant_rings.ring_for(n, kind)
    prods = invariant_rings.products(ring, d, l)
    want = ring.dimension(d, l)
    if not prods:
        if want:
            raise ArithmeticError(f"{ring.group}: no generator product of bidegree ({d}, {l}), dim {want}")
        return {}
    par = _parities(ring)
    E = np.array(prods, dtype=np.int64)
    chars = (E @ par[:-1]) % 2 @ (1 << np.arange(par.shape[1]))
    p = backend.PRIMES[0]
    rng = np.random.default_rng([5, n, d, l])
    z = rng.integers(0, p, size=(len(prods) + 8, n * (n + 1) // 2))
    V = conditions.monomial_values(E, ring.values(z, p), p)
    la = backend.get()
    out, total = {}, 0
    for c in sorted(set(chars.tolist())):
        idx = np.flatnonzero(chars == c)
        R = la.rref(V[:, idx], p)
        piv = [int(np.flatnonzero(row)[0]) for row in R]
        out[int(c)] = [prods[idx[j]] for j in piv]
        total += len(piv)
    if total != want:
        raise ArithmeticError(f"{ring.group} generators span {total} of the {want} invariants of "
                              f"M-degree {d}, q-degree {l}")
    return out


@dataclass
class _Box:
    box: tuple
    p: int
    ring: object
    blocks: dict            # character -> unknowns
    E: dict                 # character -> exponent rows over (x, generators)
    prods: list
    zq: np.ndarray
    known: dict             # character -> known values (points, products)


class InvariantRingSearch(BoxSearch):
    """Integrals $P/D^k$ with $P$ in the invariant ring (module docstring)."""

    @property
    def ring(self):
        """The invariant ring of the model (symbolic/search/invariant_rings.py)."""
        return invariant_rings.ring_for(self.model.n, self.model.kind)

    @property
    def invariance(self) -> str:
        """The class searched: the ring's group's invariants."""
        return f"{self.ring.group}-invariant (the integrals of the reduced system on P/{self.ring.group})"

    def columns(self, box) -> dict:
        """Character -> exponent rows over (x, generators) of the unknowns of ``box``."""
        d, d_gamma, _k = box
        ring = self.ring
        xpar = _parities(ring)[-1] @ (1 << np.arange(len(ring.reflections)))
        out: dict[int, list] = {}
        for e in (0, 1):
            for l in range(d_gamma - e + 1):
                for c, exps in basis(self.model.n, self.model.kind, d, l).items():
                    key = int(c ^ (xpar if e else 0))
                    out.setdefault(key, []).extend((e,) + tuple(x) for x in exps)
        return {c: np.array(v, dtype=np.int64) for c, v in sorted(out.items())}

    def unknown_counts(self, box):
        return [len(v) for v in self.columns(box).values()]

    def _values(self, z, p):
        """(x, generators) mod p at the points z."""
        return np.concatenate([z[:, -1:] % p, self.ring.values(z, p)], axis=1)

    def _derivatives(self, z, zdot, p):
        acc = np.zeros((len(z), len(self.ring.names) + 1), dtype=np.int64)
        top = max(m + q for m, q in zip(self.ring.m_degree, self.ring.q_degree))
        for t, frac in derivative_nodes(max(1, top)):
            w = frac.numerator % p * pow(frac.denominator, p - 2, p) % p
            acc = (acc + w * self._values((z + t * zdot) % p, p)) % p
        return acc

    def prepare(self, box, p):
        d, d_gamma, k = box
        model, ring = self.model, self.ring
        E = self.columns(box)
        prods = known_integrals.products(model, d, d_gamma, k, self.include_new)
        zq = sampled_field.sample(model, len(prods) + MARGIN, p,
                                  np.random.default_rng([self.seed, 7, d, k]))["z"]
        known: dict = {}
        if prods:
            Dk = np.ones(len(zq), dtype=np.int64)
            for _ in range(k):
                Dk = Dk * sampled_field.field_at(model, zq, p)["D"] % p
            masks = range(1 << len(ring.reflections))
            flipped = []
            for mask in masks:
                full = sum(1 << ring.reflections[i] for i in range(len(ring.reflections)) if mask >> i & 1)
                gv = known_integrals.values(model, invariant_rings.reflect(zq, model.n, full, p), p,
                                            self.include_new)
                F = np.ones((len(zq), len(prods)), dtype=np.int64)
                for c, pr in enumerate(prods):
                    for i in pr:
                        F[:, c] = F[:, c] * gv[:, i] % p
                flipped.append(F)
            for c in E:
                acc = np.zeros((len(zq), len(prods)), dtype=np.int64)
                for mask, F in zip(masks, flipped):
                    chi = -1 if bin(c & mask).count("1") % 2 else 1
                    acc = (acc + chi * F) % p
                known[c] = acc * Dk[:, None] % p
        return _Box(box, p, ring, {c: len(v) for c, v in E.items()}, E, prods, zq, known)

    def condition_matrices(self, ctx):
        d, d_gamma, k = ctx.box
        p = ctx.p
        rng = np.random.default_rng([self.seed, self.model.n, d, d_gamma, k, self.prime_index, 31])
        rows = max(ctx.blocks.values()) + MARGIN
        s = sampled_field.sample(self.model, rows + rows // 8 + 8, p, rng)
        cv = self._values(s["z"], p)
        cd = self._derivatives(s["z"], s["zdot"], p)
        cv, cd, dlog = conditions.admissible(cv, cd, s["dlogD"], rows)
        return {c: conditions.condition_values(E, cv[:ctx.blocks[c] + MARGIN], cd[:ctx.blocks[c] + MARGIN],
                                               dlog[:ctx.blocks[c] + MARGIN], k, p)
                for c, E in ctx.E.items()}

    def known_values(self, ctx, label):
        return ctx.known.get(label, np.zeros((len(ctx.zq), 0), np.int64))

    def known_count(self, ctx):
        return len(ctx.prods)

    def basis_values(self, ctx, label):
        return conditions.monomial_values(ctx.E[label], self._values(ctx.zq, ctx.p), ctx.p)
