r"""From one rational $(a, b)$ to generic $(a, b)$: the argument that carries an exclusion of the
Hamiltonisation and symmetry-field searches (symbolic/search/poisson.py,
symbolic/search/symmetry_fields.py) from the point $(a_0, b_0)$ where it was computed to every
$(a, b)$ off a proper algebraic subset, checked exactly at $(a_0, b_0)$.

The sample points of $P$ are chosen independently of $(a, b)$, and every entry of the sampled
conditions ($dH$, $X$, $\Delta^e$, the Jacobian of $X$, the gradients of the integrals) is a
rational function of $(a, b)$, regular at $(a_0, b_0)$.

* **Lower semicontinuity of the nullity.** A minor $\mu$ of size $r$ of the sampled conditions,
  nonzero at $(a_0, b_0)$, is a nonzero element of $\mathbb{Q}(a, b)$: off its zero set (and the
  poles) the rank is $\ge r$ and the nullity $\le$ ``cols`` $- r$ (:func:`nullity_certificate`
  exhibits $\mu(a_0, b_0)$ exactly). This carries a homogeneous system whose solutions at
  $(a_0, b_0)$ are all known ones (the symmetry-field search: the trivial fields are solutions for
  every $(a, b)$) to generic $(a, b)$.
* **An inconsistent linear stage** ($Ac = h$ of the Hamiltonisation search, $h = \Delta^e X$) needs
  more: $\mathrm{rank}[A \mid h] \ge r + 1$ generically (a minor, as above) *and*
  $\mathrm{rank}\,A \le r$ over $\mathbb{Q}(a, b)$, an upper bound that no single point gives.
  Sampled at $(M, \gamma) = (L_\gamma\Omega, \gamma)$ for seeded $(\Omega, \gamma)$, $A$ is affine,
  $A_0 + aA_1 + bA_2$, so each $(r+1)$-minor is a polynomial of degree $\le \mathrm{rank}\,A_1$ in
  $a$ and $\le \mathrm{rank}\,A_2$ in $b$; exact ranks $\le r$ on a grid of that size make every such
  minor zero (:func:`linear_generic`).
* **A box excluded by Jacobi** (a nonempty affine space of linear solutions, then a Gröbner basis
  $\{1\}$) is *not* carried: emptiness of a fibre is not an open condition, and the obvious
  properness argument (homogenise and close in $\mathbb{P}^{\kappa-1}\times\mathbb{P}^1$) fails
  here, because the kernel of $A$ holds bivectors $K$ with $\Delta^\sigma K$ Jacobi at the sample
  points (measured: the charts at infinity are not empty). Those boxes are carried by a
  certificate computed over $\mathbb{Q}(a, b)$ itself (symbolic/search/jacobi_generic.py).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import flint

__all__ = ["NullityCertificate", "nullity_certificate", "omega_rows", "grid_rank", "affine_grid",
           "linear_generic", "inconsistency_certificate", "fields_generic"]


@dataclass
class NullityCertificate:
    """Rank r of a matrix at (a0, b0), the rows and columns of an r x r minor and its exact value."""

    rank: int
    nullity: int
    rows: list
    cols: list
    minor: object          # an fmpq, nonzero

    def text(self) -> str:
        v = str(self.minor)
        v = v if len(v) <= 40 else f"{v[:18]}...{v[-18:]} ({len(v)} digits)"
        return f"a minor of size {self.rank} = {v} != 0"


def _mat(rows: list[list]) -> flint.fmpq_mat:
    return flint.fmpq_mat(len(rows), len(rows[0]), [v for r in rows for v in r])


def _pivots(R: Any, rank: int, cols: int) -> list[int]:
    """The pivot columns of the first ``rank`` rows of a row echelon form (any FLINT matrix)."""
    out, j = [], 0
    for i in range(rank):
        while R[i, j] == 0:
            j += 1
        out.append(j)
        j += 1
    return out


def nullity_certificate(rows: list[list], prime_index: int = 0) -> NullityCertificate:
    r"""Lower semicontinuity of the nullity, checked (module docstring): a minor of ``rows`` (fmpq,
    the conditions at $(a_0, b_0)$) of the largest size $r$ found, with its exact value. The rows
    are scaled to integers (one factor per row), pivot columns and rows are chosen modulo a prime
    (FLINT ``nmod_mat``), and the minor is then computed exactly over $\mathbb{Z}$ and divided by
    the row factors; a nonzero value proves rank $\ge r$ at $(a_0, b_0)$, hence over
    $\mathbb{Q}(a, b)$, so the nullity is $\le$ ``cols - r`` off the minor's zero set."""
    from chaplygin_nd.symbolic.search.backend import PRIMES

    m, ncols = len(rows), len(rows[0])
    dens = [_lcm_den(r) for r in rows]
    Z = [[int(v * d) for v in r] for r, d in zip(rows, dens, strict=True)]
    p = PRIMES[prime_index]
    R, rank = flint.nmod_mat(m, ncols, [v % p for r in Z for v in r], p).rref()
    if rank == 0:
        return NullityCertificate(0, ncols, [], [], flint.fmpq(1))
    C = _pivots(R, rank, ncols)
    Rt, rt = flint.nmod_mat(rank, m, [Z[i][j] % p for j in C for i in range(m)], p).rref()
    Rows = _pivots(Rt, rt, m)
    det = flint.fmpz_mat([[Z[i][j] for j in C] for i in Rows]).det()
    if det == 0 or rt != rank:
        if prime_index + 1 < len(PRIMES):
            return nullity_certificate(rows, prime_index + 1)
        raise ArithmeticError("no nonzero pivot minor found")
    scale = 1
    for i in Rows:
        scale *= dens[i]
    return NullityCertificate(rank, ncols - rank, Rows, C, flint.fmpq(int(det), scale))


# --------------------------------------------------------------- the linear stage at generic (a, b)
def omega_rows(n: int, a, b, e: int, fb: list, cols: list, points: list) -> tuple[list, list]:
    r"""The linear conditions $P\,dH = \Delta^e X$, $P\,d\|\gamma\|^2 = 0$ of
    symbolic/search/poisson.py sampled at the points $(M, \gamma) = (L_\gamma\Omega, \gamma)$ for
    seeded $(\Omega, \gamma)$ (``points``): then $dH = (\Omega, -\tfrac12\langle\Omega,
    \partial_{\gamma_k}L_\gamma\,\Omega\rangle)$, $X = ([M, \Omega], -\Omega\gamma)$ and the weight $-1$
    bivector are affine in $(a, b)$ ($\mathbb{I} = J\Omega + \Omega J$ with $J = 1 + aE_nE_n^T$,
    the rolling term linear in $b$), so the matrix $A$ is $A_0 + aA_1 + bA_2$ exactly. Returns
    (rows of $A$, the right-hand side $h$) over $\mathbb{Q}$ at $(a, b)$."""
    from chaplygin_nd.symbolic.algebra import vec
    from chaplygin_nd.symbolic.axisymmetric import Delta
    from chaplygin_nd.symbolic.mass_operator import L_entries
    from chaplygin_nd.symbolic.search.point_values import bivector_values as _values
    from chaplygin_nd.symbolic.search.point_values import dH_gamma
    from chaplygin_nd.symbolic.search.point_values import fq as _fq

    m = n * (n - 1) // 2
    N = m + n
    zero, one = flint.fmpq(0), flint.fmpq(1)
    fa, fb_ = _fq(a), _fq(b)
    pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]
    rows, rhs = [], []
    for Om, g in points:
        w = [_fq(v) for v in vec(Om)]
        gq = [_fq(v) for v in g]
        L = L_entries(gq, [one] * (n - 1) + [one + fa], fb_, zero, one)
        mv = [sum((L[r][c] * w[c] for c in range(m)), zero) for r in range(m)]
        Mq, Oq = _skew(mv, n, pairs), _skew(w, n, pairs)
        dH = w + dH_gamma(w, gq, fb_, n)
        MO = [[sum((Mq[i][k] * Oq[k][j] - Oq[i][k] * Mq[k][j] for k in range(n)), zero)
               for j in range(n)] for i in range(n)]
        X = [MO[i][j] for i, j in pairs] + [-sum((Oq[i][k] * gq[k] for k in range(n)), zero)
                                            for i in range(n)]
        De = _fq(Delta(g[n - 1], a, b) ** e)
        pt = mv + gq
        Vs = [_values(fb[u], pt, N) for u in cols]
        for i in range(N):
            rows.append([sum((V[i][j] * dH[j] for j in range(N)), zero) for V in Vs])
            rhs.append(De * X[i])
        gg = [2 * v for v in gq]
        for i in range(m):
            rows.append([sum((V[i][m + k] * gg[k] for k in range(n)), zero) for V in Vs])
            rhs.append(zero)
    return rows, rhs


def _skew(c: list, n: int, pairs: list) -> list[list]:
    A = [[flint.fmpq(0)] * n for _ in range(n)]
    for v, (i, j) in zip(c, pairs, strict=True):
        A[i][j], A[j][i] = v, -v
    return A


def _lcm_den(row: list) -> int:
    d = 1
    for v in row:
        q = int(v.q)
        d = d * q // math.gcd(d, q)
    return d


_GRIDS: dict = {}


def _modulo_constant_rows(A0: list, A1: list, A2: list) -> tuple[list, list, list, int]:
    r"""The rows of $A_0 + aA_1 + bA_2$ that vary, reduced modulo the span of the constant ones
    (exact RREF over $\mathbb{Z}$), on the columns that are not pivots of it: for every $(a, b)$,
    $\mathrm{rank}\,A = c + \mathrm{rank}(V_0 + aV_1 + bV_2)$ with $c$ the rank of the constant rows."""
    zero = flint.fmpq(0)
    const = [i for i in range(len(A0)) if all(v == zero for v in A1[i]) and all(v == zero for v in A2[i])]
    vary = [i for i in range(len(A0)) if i not in set(const)]
    cols = len(A0[0])
    if not const:
        return [A0[i] for i in vary], [A1[i] for i in vary], [A2[i] for i in vary], 0
    C = [A0[i] for i in const]
    R, den, c = flint.fmpz_mat([[int(v * d) for v in row] for row, d in ((r, _lcm_den(r)) for r in C)]).rref()
    piv = _pivots(R, c, cols)
    Rq = flint.fmpq_mat(c, cols, [flint.fmpq(int(R[i, j]), int(den)) for i in range(c) for j in range(cols)])
    keep = [j for j in range(cols) if j not in set(piv)]
    out = []
    for B in (A0, A1, A2):
        V = flint.fmpq_mat(len(vary), cols, [v for i in vary for v in B[i]])
        Vp = flint.fmpq_mat(len(vary), c, [V[r, j] for r in range(len(vary)) for j in piv])
        W = V - Vp * Rq
        out.append([[W[r, j] for j in keep] for r in range(len(vary))])
    return out[0], out[1], out[2], c


def grid_rank(A0: list, A1: list, A2: list) -> dict:
    r"""For $A = A_0 + aA_1 + bA_2$ (rows of ``fmpq``): the rank $c$ of its constant rows, the ranks
    $k_1, k_2$ of $V_1, V_2$ (the varying rows modulo the constant ones) and ``top`` = (the largest
    exact rank of $A$ on the grid $\{0..k_1\}\times\{0..k_2\}$, where): an upper bound of its rank
    over $\mathbb{Q}(a, b)$ (:func:`linear_generic`)."""
    V0, V1, V2, c = _modulo_constant_rows(A0, A1, A2)
    if not V0 or not V0[0]:
        return {"k": (0, 0), "top": (c, (0, 0)), "constant": c}
    # one common denominator per row over the three matrices keeps V0 + i V1 + j V2 integral
    dens = [_lcm_den(r0 + r1 + r2) for r0, r1, r2 in zip(V0, V1, V2, strict=True)]
    Z = [flint.fmpz_mat([[int(v * d) for v in row] for row, d in zip(B, dens, strict=True)])
         for B in (V0, V1, V2)]
    k1, k2 = Z[1].rank(), Z[2].rank()
    top = max((c + (Z[0] + i * Z[1] + j * Z[2]).rank(), (i, j))
              for i in range(k1 + 1) for j in range(k2 + 1))
    return {"k": (k1, k2), "top": top, "constant": c}


def affine_grid(n: int, fb: list, cols: list, points: list, key) -> dict:
    r"""$A = A_0 + aA_1 + bA_2$ and $X = X_0 + aX_1 + bX_2$ of :func:`omega_rows` (affinity checked
    exactly at $(a, b) = (2, 3)$), and the largest rank of $A$ on the grid
    $\{0..k_1\}\times\{0..k_2\}$ of :func:`grid_rank` (cached per ``key``: the grid does not
    depend on $(a_0, b_0)$ or $e$)."""
    if key in _GRIDS:
        return _GRIDS[key]
    (A00, X00), (A10, X10), (A01, X01) = (omega_rows(n, a, b, 0, fb, cols, points)
                                          for a, b in ((0, 0), (1, 0), (0, 1)))
    A1 = [[u - v for u, v in zip(r1, r0, strict=True)] for r1, r0 in zip(A10, A00, strict=True)]
    A2 = [[u - v for u, v in zip(r1, r0, strict=True)] for r1, r0 in zip(A01, A00, strict=True)]
    X1 = [u - v for u, v in zip(X10, X00, strict=True)]
    X2 = [u - v for u, v in zip(X01, X00, strict=True)]
    A23, X23 = omega_rows(n, 2, 3, 0, fb, cols, points)
    if (A23 != [[x + 2 * y + 3 * z for x, y, z in zip(r0, r1, r2, strict=True)]
                for r0, r1, r2 in zip(A00, A1, A2, strict=True)]
            or X23 != [x + 2 * y + 3 * z for x, y, z in zip(X00, X1, X2, strict=True)]):
        raise ArithmeticError("the sampled conditions are not affine in (a, b): the argument fails")
    out = {"A": (A00, A1, A2), "X": (X00, X1, X2), **grid_rank(A00, A1, A2)}
    _GRIDS[key] = out
    return out


def linear_generic(n: int, a0, b0, e: int, fb: list, cols: list, points: list, key=None) -> tuple[bool, str]:
    r"""Carry "the linear stage is inconsistent at $(a_0, b_0)$" to generic $(a, b)$, exactly
    (module docstring; :func:`omega_rows`). $\mathrm{rank}\,A = c + \mathrm{rank}\,V$ with $c$ the rank
    of the constant rows and $V = V_0 + aV_1 + bV_2$ the other rows reduced modulo them
    (:func:`_modulo_constant_rows`). Every minor of $V$ is a polynomial of degree
    $\le k_1 = \mathrm{rank}\,V_1$ in $a$ and $\le k_2 = \mathrm{rank}\,V_2$ in $b$ (multilinearity in
    the columns); with $r$ the largest exact rank of $A$ on the grid $\{0..k_1\}\times\{0..k_2\}$,
    each minor of $V$ of size $r - c + 1$ vanishes there, so it is zero: $\mathrm{rank}\,A \le r$
    over $\mathbb{Q}(a, b)$. An $(r+1)$-minor $\mu$ of $[A \mid h]$ nonzero at $(a_0, b_0)$ gives
    $\mathrm{rank}[A \mid h] \ge r + 1$ off $\{\mu = 0\}$: there $Ac = h$ is inconsistent (and off the
    poles of $\Delta^e$ and the zeros of $\det L_\gamma$ at the sample points). Returns (proved,
    statement)."""
    from chaplygin_nd.symbolic.axisymmetric import Delta
    from chaplygin_nd.symbolic.search.point_values import fq as _fq

    grid = affine_grid(n, fb, cols, points, key if key is not None else object())
    (A00, A1, A2), (X0, X1, X2) = grid["A"], grid["X"]
    fa, fbb = _fq(a0), _fq(b0)
    A = [[x + fa * y + fbb * z for x, y, z in zip(r0, r1, r2, strict=True)]
         for r0, r1, r2 in zip(A00, A1, A2, strict=True)]
    per_point = len(A) // len(points)
    De = [_fq(Delta(g[n - 1], a0, b0) ** e) for _, g in points]
    h = [De[i // per_point] * (x + fa * y + fbb * z)
         for i, (x, y, z) in enumerate(zip(X0, X1, X2, strict=True))]
    return inconsistency_certificate(A, h, grid, f"({a0}, {b0})")


def inconsistency_certificate(A: list, h: list, grid: dict, at: str) -> tuple[bool, str]:
    r"""$Ac = h$ inconsistent over $\mathbb{Q}(a, b)$ off a minor's zero set: $\mathrm{rank}\,A \le r$
    generically (``grid`` of :func:`grid_rank`) and a minor of $[A \mid h]$ of size $r + 1$ nonzero
    at the point ``at`` where ``A``, ``h`` are evaluated. Returns (proved, statement)."""
    (k1, k2), (r, where) = grid["k"], grid["top"]
    cert = nullity_certificate([row + [v] for row, v in zip(A, h, strict=True)])
    if cert.rank != r + 1:
        return False, (f"no minor of [A | h] of size {r + 1} = 1 + (the largest rank of A on the grid, "
                       f"at {where}) is nonzero at {at}")
    return True, (f"generic (a, b): A c = h is inconsistent off the zero set of one minor of [A | h] "
                  f"and the poles (at {at}: {cert.text()}; rank A <= {r} over Q(a, b): "
                  f"A = A0 + a A1 + b A2; modulo its constant rows (rank {grid['constant']}) rank A1 = "
                  f"{k1}, rank A2 = {k2}, and rank A <= {r} on the {(k1 + 1) * (k2 + 1)}-point grid)")


def fields_generic(rows: list, solutions: int, trivial: int, at: str, dx_syzygy: bool,
                   uses_dx: list, proved: list) -> str:
    r"""Over which $(a, b)$ a symmetry-field count "no field beyond the trivial ones" holds
    (symbolic/search/symmetry_fields.py): lower semicontinuity of the nullity (one minor of the
    sampled conditions ``rows``, nonzero at the point ``at``) bounds the solutions at generic
    $(a, b)$ by ``solutions``; the ``trivial`` ones are solutions for every $(a, b)$ (the orbit fields
    and $DX$ by equivariance and invariance; an orbit-direction field, with its column coefficients
    in ``proved``, by its proof, which does not involve $a, b$ when it avoids the $DX$ column,
    flagged by ``uses_dx``) and stay independent off a proper closed set."""
    if dx_syzygy:
        return f"only at {at} (a column syzygy proved there involves D X, which depends on a, b)"
    if any(coef[u] != 0 and uses_dx[u] for coef in proved for u in range(len(uses_dx))):
        return f"only at {at} (an orbit-direction field proved there involves D X, which depends on a, b)"
    cert = nullity_certificate(rows)
    if cert.nullity != solutions:   # the pivot prime divides the minor: no certificate here
        return f"only at {at} (no minor of size {len(rows[0]) - solutions} found nonzero mod p)"
    return (f"generic (a, b): off the zero set of one minor and the poles of the sampled conditions "
            f"(lower semicontinuity of the nullity; minor at {at}: {cert.text()}), the "
            f"{trivial} trivial fields being solutions for every (a, b)")
