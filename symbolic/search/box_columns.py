r"""The columns of a bivector box of the Hamiltonisation search (symbolic/search/poisson.py) and the
exact tools the searches on P share: the box's basis bivectors as FLINT polynomials, seeded rational
points of P, exact solution sets over QQ, and the columns independent as functions on P (every
sampled dependency proved an identity modulo the sphere before its column is dropped). Used by the
Poisson search, its generic-(a, b) certificates (symbolic/search/jacobi_generic.py) and the
symmetry-field search."""

from __future__ import annotations

import flint
import sympy as sp
from chaplygin_nd.symbolic.algebra import vec
from chaplygin_nd.symbolic.exact.points import generator, skew_matrix, sphere_point
from chaplygin_nd.symbolic.search import bivector_ansatz as ba
from chaplygin_nd.symbolic.search.point_values import fq as _fq

__all__ = ["mpoly_context", "jacobi_values", "flint_bivectors", "sample_points", "rref_solve", "independent_columns",
           "sphere_reduce"]


def mpoly_context(coords):
    """The FLINT context of exact polynomials over QQ in ``coords`` (lex order)."""
    return flint.fmpq_mpoly_ctx.get(tuple(str(c) for c in coords), "lex")


_FLINT_BIVECTORS: dict = {}


def flint_bivectors(ans: ba.Ansatz) -> list[dict]:
    """Each basis bivector of the box as {(row, col): fmpq_mpoly} over its upper-triangle entries
    (kept per (n, degree): the box does not depend on anything else)."""
    key = (ans.n, ans.degree)
    if key not in _FLINT_BIVECTORS:
        _FLINT_BIVECTORS[key] = _flint_bivectors(ans)
    return _FLINT_BIVECTORS[key]


#: per coordinate tuple: entry expression -> its fmpq_mpoly (a box of degree d repeats every
#: entry of the box of degree d - 1)
_FLINT_ENTRIES: dict = {}


def _flint_bivectors(ans: ba.Ansatz) -> list[dict]:
    ctx = mpoly_context(ans.coords)
    memo = _FLINT_ENTRIES.setdefault(tuple(ans.coords), {})
    out = []
    for B in ans.bivectors:
        entries = {}
        for i in range(B.rows):
            for j in range(i + 1, B.cols):
                e = B[i, j]
                if e != 0:
                    if e not in memo:
                        poly = sp.Poly(e, *ans.coords)
                        memo[e] = ctx.from_dict({m: _fq(c) for m, c in poly.as_dict().items()})
                    entries[(i, j)] = memo[e]
        out.append(entries)
    return out


def sample_points(n: int, count: int, seed: int, label: str):
    """``count`` seeded rational points (M, gamma) of P (gamma on the sphere), drawn under ``label``."""
    rng = generator(seed, "poisson", label, n)
    return [(skew_matrix(rng, n), sphere_point(rng, n)) for _ in range(count)]


def rref_solve(rows: list[list], rhs: list) -> tuple[list | None, list[list]]:
    """Exact solution set of rows * c = rhs over QQ: (particular solution or None, kernel basis)."""
    m = len(rows[0])
    A = flint.fmpq_mat(len(rows), m + 1, [v for r, h in zip(rows, rhs) for v in (*r, h)])
    R, rank = A.rref()
    pivots = []
    for i in range(rank):
        j = next(j for j in range(m + 1) if R[i, j] != 0)
        if j == m:
            return None, []
        pivots.append(j)
    free = [j for j in range(m) if j not in pivots]
    part = [flint.fmpq(0)] * m
    for i, j in enumerate(pivots):
        part[j] = R[i, m]
    kernel = []
    for f in free:
        v = [flint.fmpq(0)] * m
        v[f] = flint.fmpq(1)
        for i, j in enumerate(pivots):
            v[j] = -R[i, f]
        kernel.append(v)
    return part, kernel


def independent_columns(ans: ba.Ansatz, fb: list[dict], seed: int) -> tuple[list[int], int]:
    """Columns of the box that are independent as functions on P; every dependency the sampled
    points suggest is proved as an exact identity modulo the sphere before its column is dropped."""
    n = ans.n
    N = len(ans.coords)
    keys = sorted({k for e in fb for k in e})
    cols = len(fb)
    pts = sample_points(n, max(4, cols // max(1, len(keys)) + 4), seed, "columns")
    rows = []
    for M, g in pts:
        pt = [_fq(v) for v in list(vec(M)) + list(g)]
        vals = [{k: f(*pt) for k, f in e.items()} for e in fb]
        for k in keys:
            rows.append([vals[u].get(k, flint.fmpq(0)) for u in range(cols)])
    _, kernel = rref_solve(rows, [flint.fmpq(0)] * len(rows))
    gam = list(ans.coords[N - n:])
    for v in kernel:  # prove each syzygy exactly: sum v_u B_u = 0 modulo |gamma|^2 = 1
        comb = sp.zeros(N, N)
        for u, c in enumerate(v):
            if c != 0:
                comb += sp.Rational(int(c.p), int(c.q)) * ans.bivectors[u]
        for entry in comb:
            if entry != 0 and sphere_reduce(sp.expand(entry), gam) != 0:
                raise ArithmeticError("a sampled syzygy of the box is not an identity; more points")
    dropped = set()
    for v in kernel:  # the free column of each kernel vector (rref: one per vector)
        dropped.add(max(u for u, c in enumerate(v) if c != 0))
    return [u for u in range(cols) if u not in dropped], len(kernel)


def sphere_reduce(expr: sp.Expr, gamma: list) -> sp.Expr:
    """Normal form of a polynomial modulo $\\|\\gamma\\|^2 - 1$ (powers of $\\gamma_n^2$ replaced)."""
    g = gamma[-1]
    rest = 1 - sum(v**2 for v in gamma[:-1])
    return sp.expand(sp.rem(sp.Poly(expr, g), sp.Poly(g**2 - rest, g)).as_expr())


def jacobi_values(V, dV, D, dD, s, zero):
    r"""The Jacobi identity of $\Pi = \Delta^{s}P$ at one point, cleared of $\Delta^{2s-1}$: for
    every $i < j < k$ the value $\Delta\sum_{\mathrm{cyc}}\sum_l P_{pl}\,\partial_l P_{qr}
    + s\sum_{\mathrm{cyc}} P_{qr}P_{p,N}\,\partial_x\Delta$ (cyclic over $(p, q, r)$ in $(i, j, k)$;
    the last coordinate is $x = \gamma_n$, the only one $\Delta$ depends on). ``V``: the values
    $P_{pl}$, ``dV[l]``: those of $\partial_l P$, ``D``, ``dD``: $\Delta$, $\partial_x\Delta$ (elements of
    one ring, e.g. FLINT ``fmpq_mpoly`` in the unknowns, or their coefficients); ``s`` the exponent
    (of that ring), ``zero`` its zero.
    Yields ``((i, j, k), value)`` for the non-zero values (the Hamiltonisation search and its
    generic Jacobi stage)."""
    N = len(V)
    PdD = [V[i][N - 1] * dD for i in range(N)]
    for i in range(N):
        for j in range(i + 1, N):
            for k in range(j + 1, N):
                jac = zero
                for (p, q, r) in ((i, j, k), (j, k, i), (k, i, j)):
                    for l in range(N):
                        if V[p][l] != 0 and dV[l][q][r] != 0:
                            jac += V[p][l] * dV[l][q][r]
                extra = V[j][k] * PdD[i] + V[k][i] * PdD[j] + V[i][j] * PdD[k]
                val = D * jac + s * extra
                if val != 0:
                    yield (i, j, k), val

