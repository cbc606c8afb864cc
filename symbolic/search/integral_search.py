r"""Exact search for first integrals of the $n$-dimensional Chaplygin sphere (row
S6:first-integrals, beyond the paper; issue 23).

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

import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field

import flint
import numpy as np
from chaplygin_nd.symbolic.search import candidate_basis, known_integrals, sampled_field
from chaplygin_nd.symbolic.search.sampled_field import Model

__all__ = ["BlockResult", "DegreeResult", "search_degree", "search", "MARGIN", "RECOVERY_MAX"]

#: rows beyond the number of unknowns of a block (more rows never add integrals, only conditions)
MARGIN = 24
#: blocks up to this size also get an explicit F_p kernel and the recovery check
RECOVERY_MAX = 1200
CHUNK_ENTRIES = 4_000_000  #: entries of one chunk of the conditions (memory only: same matrix)


@dataclass
class BlockResult:
    character: int
    unknowns: int
    nullity: int
    known_rank: int
    recovered: bool | None      # None: not checked (block too large)


@dataclass
class DegreeResult:
    n: int
    kind: str
    d: int
    d_gamma: int
    k: int
    prime: int
    unknowns: int
    found: int                  # sum of nullities: >= dim of the integrals (equal when settled)
    known: int                  # sum of known ranks: <= dim of the span of the known products
    products: int
    settled: bool               # found == known: no integral beyond the known algebra
    recovered: bool | None
    seconds: float = field(compare=False)  # a time taken: no part of the result's value
    blocks: list[BlockResult] = field(default_factory=list)

    def as_dict(self) -> dict:
        return asdict(self)


def _coordinate_values(co: candidate_basis.Coordinates, z: np.ndarray, p: int, i_p: int) -> np.ndarray:
    return (z % p) @ ((co.re + i_p * co.im) % p).T % p


def _sqrt_minus_one(p: int) -> int:
    for c in range(2, 200):
        r = pow(c, (p - 1) // 4, p)
        if r * r % p == p - 1:
            return r
    raise ArithmeticError(f"no square root of -1 mod {p}")


def _monomial_values(E: np.ndarray, cv: np.ndarray, p: int) -> np.ndarray:
    """Values (points x monomials) of the monomials with exponent rows E at coordinate values cv."""
    out = np.ones((cv.shape[0], E.shape[0]), dtype=np.int64)
    for j in range(E.shape[1]):
        top = int(E[:, j].max())
        if top == 0:
            continue
        pw = np.ones((cv.shape[0], top + 1), dtype=np.int64)
        for e in range(1, top + 1):
            pw[:, e] = pw[:, e - 1] * cv[:, j] % p
        out = out * pw[:, E[:, j]] % p
    return out


def _block_apply(Y: np.ndarray, blk: candidate_basis.Block, p: int) -> np.ndarray:
    """Columns of a block from monomial columns: sum of sign * Y[:, monomial] per column."""
    order = np.argsort(blk.column, kind="stable")
    cols = blk.column[order]
    starts = np.flatnonzero(np.r_[True, cols[1:] != cols[:-1]])
    signed = Y[:, blk.monomial[order]] * blk.sign[order][None, :] % p
    return np.add.reduceat(signed, starts, axis=1) % p


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


def known_ranks(model: Model, d: int, d_gamma: int, k: int, include_new: bool, *,
                prime_index: int = 0, seed: int = 0) -> dict[int, int]:
    """Per character: the rank mod p of the known products in the box (a lower bound of the
    dimension of their span over Q), without the search matrix."""
    p = sampled_field.PRIMES[prime_index]
    B = candidate_basis.basis(model.n, d, d_gamma, model.planes)
    prods = known_integrals.products(model, d, d_gamma, k, include_new)
    if not prods:
        return {b.character: 0 for b in B.blocks}
    zq = sampled_field.sample(model, len(prods) + MARGIN, p, np.random.default_rng([seed, 7, d, k]))["z"]
    flipped = _flipped_values(model, zq, p, include_new)
    Dk = np.ones(len(zq), dtype=np.int64)
    for _ in range(k):
        Dk = Dk * sampled_field.field_at(model, zq, p)["D"] % p
    return {b.character: _nmod(_known_matrix(prods, b.character, flipped, Dk, p), p).rank()
            for b in B.blocks}


def _nmod(A: np.ndarray, p: int) -> flint.nmod_mat:
    return flint.nmod_mat(A.shape[0], A.shape[1], A.ravel().tolist(), p)


def search_degree(model: Model, d: int, d_gamma: int, k: int = 0, *, prime_index: int = 0,
                  seed: int = 0, include_new: bool = True,
                  progress: Callable[[str], None] | None = None) -> DegreeResult:
    r"""The integrals $P/D^k$ in the box $S(d, d_\gamma)$ of ``model`` (module docstring), one
    prime (``sampled_field.PRIMES[prime_index]``). $d \ge 1$, $d_\gamma \ge 0$, $k \ge 0$.
    ``include_new``: count the integral found by the search (search.found_integral) among the known ones;
    ``False`` counts only the paper's (the search then reports it as the excess)."""
    if d < 1 or d_gamma < 0 or k < 0:
        raise ValueError("need d >= 1, d_gamma >= 0, k >= 0")
    t0 = time.perf_counter()
    p = sampled_field.PRIMES[prime_index]
    i_p = _sqrt_minus_one(p)
    B = candidate_basis.basis(model.n, d, d_gamma, model.planes)
    co = B.coords
    rng = np.random.default_rng([seed, model.n, d, d_gamma, k, prime_index])
    rows = max(b.columns for b in B.blocks) + MARGIN
    s = sampled_field.sample(model, rows + rows // 8 + 8, p, rng)
    cv = _coordinate_values(co, s["z"], p, i_p)
    cd = _coordinate_values(co, s["zdot"], p, i_p)
    good = (cv != 0).all(axis=1)            # the log-derivative needs non-zero coordinates
    cv, cd, dlog = cv[good][:rows], cd[good][:rows], s["dlogD"][good][:rows]
    if len(cv) < rows:
        raise ArithmeticError("too few admissible points")
    ratio = cd * sampled_field.inv_mod(cv, p) % p
    blocks_A: dict[int, list] = {b.character: [] for b in B.blocks}
    chunk = max(1, CHUNK_ENTRIES // max(1, B.size))
    for r0 in range(0, rows, chunk):
        mv = _monomial_values(B.exponents, cv[r0:r0 + chunk], p)
        lin = (ratio[r0:r0 + chunk] @ B.exponents.T - k * dlog[r0:r0 + chunk, None]) % p
        Y = mv * lin % p
        for b in B.blocks:
            need = b.columns + MARGIN
            if r0 < need:
                blocks_A[b.character].append(_block_apply(Y[: need - r0], b, p))
    prods = known_integrals.products(model, d, d_gamma, k, include_new)
    zq = sampled_field.sample(model, len(prods) + MARGIN, p, np.random.default_rng([seed, 7, d, k]))["z"]
    flipped = _flipped_values(model, zq, p, include_new) if prods else []
    Dk = np.ones(len(zq), dtype=np.int64)
    for _ in range(k):
        Dk = Dk * sampled_field.field_at(model, zq, p)["D"] % p
    results = []
    for b in B.blocks:
        A = np.concatenate(blocks_A.pop(b.character), axis=0)
        Ap = _nmod(A, p)
        del A
        K = _known_matrix(prods, b.character, flipped, Dk, p) if prods else np.zeros((len(zq), 0), np.int64)
        known = _nmod(K, p).rank() if prods else 0
        recovered = None
        if b.columns <= RECOVERY_MAX:
            X, nullity = Ap.nullspace()
            if nullity and prods:
                cvq = _coordinate_values(co, zq, p, i_p)
                Vq = _block_apply(_monomial_values(B.exponents, cvq, p), b, p)
                Xk = _nmod(np.array(X.tolist(), dtype=np.int64)[:, :nullity], p)
                F = _nmod(Vq, p) * Xk
                both = np.concatenate([np.array(F.tolist(), dtype=np.int64), K], axis=1)
                recovered = _nmod(both, p).rank() == nullity
            else:
                recovered = known == 0
        else:
            nullity = b.columns - Ap.rank()
        results.append(BlockResult(b.character, b.columns, nullity, known, recovered))
        if progress:
            progress(f"n={model.n} d={d} d_gamma={d_gamma} k={k}: block chi={b.character:#x} "
                     f"{b.columns} unknowns, nullity {nullity}, known rank {known}")
    found = sum(r.nullity for r in results)
    kn = sum(r.known_rank for r in results)
    checked = [r.recovered for r in results if r.recovered is not None]
    return DegreeResult(model.n, model.kind, d, d_gamma, k, p, B.size, found, kn, len(prods),
                        found == kn, all(checked) if checked else None,
                        round(time.perf_counter() - t0, 3), results)


def search(model: Model, boxes, **kw) -> list[DegreeResult]:
    """:func:`search_degree` over ``boxes`` = iterable of (d, d_gamma, k)."""
    return [search_degree(model, d, dg, k, **kw) for d, dg, k in boxes]
