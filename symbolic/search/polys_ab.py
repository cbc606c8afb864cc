r"""Exact algebra over $\mathbb{Q}[a, b]$ for carrying search results to generic $(a, b)$
(symbolic/search/jacobi_generic.py): fraction-free elimination, rank profiles at a point,
factors, text SymPy can parse, and a test that a factor has no zero on the parameter domain
$a \ge -1$, $b \ge 0$. Polynomials are FLINT ``fmpq_mpoly`` in ``AB``."""

from __future__ import annotations

from typing import Any

import flint
import sympy as sp

__all__ = ["AB", "ab_ctx", "poly_text", "factored", "point_rank_profile", "ff_gauss_jordan", "primitive",
           "det_L", "factor_set", "no_zero_in_domain"]

AB = ("a", "b")


def ab_ctx():
    """The ring Q[a, b] (FLINT, lex)."""
    return flint.fmpq_mpoly_ctx.get(AB, "lex")


def poly_text(p) -> str:
    """An ``fmpq_mpoly`` as text SymPy can parse (``**`` for powers)."""
    return str(p).replace("^", "**")


def factored(p) -> tuple[str, str]:
    """(p factored as text SymPy can parse, a short form naming each long factor by its degrees)."""
    c, fac = p.factor()
    parts, short = [], []
    for f, m in fac:
        t = f"({poly_text(f)})" + (f"**{m}" if m > 1 else "")
        parts.append(t)
        da, db = f.degrees()
        short.append(t if len(t) <= 60 else f"[an irreducible factor of degree {da} in a, {db} in b]"
                     + (f"**{m}" if m > 1 else ""))
    return " * ".join([str(c)] + parts), " * ".join(["c"] + short)


def point_rank_profile(rows: list, at: tuple) -> tuple[list, list]:
    """Pivot columns and rows of a nonzero maximal minor of ``rows`` (fmpq_mpoly) at ``at``."""
    from chaplygin_nd.symbolic.search.generic_extension import _pivots

    m, k = len(rows), len(rows[0])
    vals = [[p(*at) for p in r] for r in rows]
    R, r = flint.fmpq_mat(m, k, [v for row in vals for v in row]).rref()
    C = _pivots(R, r, k)
    Rt, _ = flint.fmpq_mat(r, m, [vals[i][j] for j in C for i in range(m)]).rref()
    return C, _pivots(Rt, r, m)


def ff_gauss_jordan(Mx: list, pivots: list) -> tuple[list, list, Any]:
    """Fraction-free Gauss-Jordan elimination of the rows ``Mx`` (fmpq_mpoly) on the columns
    ``pivots`` (as many as rows, their minor nonzero): each step takes the nonzero entry of least
    degree left (the constant rows first, so the degrees grow late). Returns the rows, the column
    each row is solved for, and the final pivot mu, the minor: row i then reads
    mu * x_{cols[i]} + (the columns not in ``pivots``) (exact divisions, checked by FLINT)."""
    Mx = [list(r) for r in Mx]
    prev = None
    left_rows, left_cols = set(range(len(Mx))), set(pivots)
    solved: dict = {}
    for _ in pivots:
        k, c = min(((i, j) for i in left_rows for j in left_cols if not Mx[i][j].is_zero()),
                   key=lambda ij: (Mx[ij[0]][ij[1]].total_degree(), len(Mx[ij[0]][ij[1]]), ij))
        left_rows.discard(k)
        left_cols.discard(c)
        solved[k] = c
        piv = Mx[k][c]
        for i in range(len(Mx)):
            if i == k:
                continue
            f = Mx[i][c]
            row = []
            for j, v in enumerate(Mx[i]):
                w = piv * v - f * Mx[k][j] if not f.is_zero() else piv * v
                row.append(w / prev if prev is not None else w)
            Mx[i] = row
        prev = piv
    return Mx, [solved[i] for i in range(len(Mx))], prev


def primitive(v: list) -> list:
    """A vector of polynomials divided by the gcd of its entries (unchanged if all are zero)."""
    g = None
    for p in v:
        if not p.is_zero():
            g = p if g is None else g.gcd(p)
    return v if g is None else [p / g for p in v]


def det_L(n: int, g) -> Any:
    r"""$\det L_\gamma$ (eq:M-O) at the point ``g`` as a polynomial in $(a, b)$ (fraction-free)."""
    from chaplygin_nd.symbolic.mass_operator import L_entries

    ctx = ab_ctx()
    a, b = ctx.gens()
    zero, one = ctx.from_dict({}), ctx.from_dict({(0, 0): 1})
    gq = [one * flint.fmpq(int(sp.Rational(v).p), int(sp.Rational(v).q)) for v in g]
    L = L_entries(gq, [one] * (n - 1) + [one + a], b, zero, one)
    return ff_gauss_jordan(L, list(range(len(L))))[2]


def factor_set(polys: list) -> list:
    """The distinct irreducible factors (up to sign) of the product of ``polys``."""
    out: list = []
    for p in polys:
        for f, _ in p.factor()[1]:
            if not any(f == g or f == -g for g in out):
                out.append(f)
    return out


def no_zero_in_domain(f) -> bool:
    """True when f(a, b) has no zero on a >= -1, b >= 0: f(u - 1, v) has coefficients of one sign
    and a nonzero constant term (then |f| >= |constant| > 0 for u, v >= 0)."""
    ctx = ab_ctx()
    u, v = ctx.gens()
    h = f.compose(u - 1, v, ctx=ctx)
    cs = h.coeffs()
    return any(m == (0, 0) for m in h.monoms()) and (all(c > 0 for c in cs) or all(c < 0 for c in cs))
