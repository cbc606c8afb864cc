r"""Independence of the invariant integrals of the axisymmetric sphere at an exact point (row S6:wedge-independence).

The functions: the $n - 1$ non-constant coefficients of $p(\lambda, \sigma) = \det(M + \sigma\gamma\gamma^T - \lambda)$
(eq:pol-first-integrals: $\lambda^{n-2j}$ and $\sigma\lambda^{n-1-2j}$, $j \ge 1$; the others vanish for skew $M$ or
are constant on $P$), $H_1 = 2H$ (the energy) and $H_2, \dots, H_{\lceil n/2\rceil - 1}$ of
:mod:`symbolic.family.wedge_integrals`: $2n - 2 - \lfloor n/2\rfloor$ functions. Their differentials in the
coordinates $((M_{ij})_{i<j}, \gamma)$ are computed exactly, restricted to $TP$ by
$\operatorname{diag}(1, 1 - \gamma\gamma^T)$, and ranked over $\mathbb{Q}$ (SymPy ``DomainMatrix`` and FLINT
``fmpq_mat``). Beside the rank, every differential is evaluated on the field (eq:motion-general at
the same point: it must vanish, so the rank is that of *conserved* functions, not of functions that
merely look like them) and on the generators of $SO(n-1)$ (it must vanish: invariance, eq:action).

The coefficient gradients: $\partial_\theta p = \operatorname{tr}(\operatorname{adj}(A)\,\partial_\theta A)$, $A = M + \sigma\gamma\gamma^T - \lambda$
(Jacobi's formula), evaluated at $n + 1$ rational $\lambda$ and three $\sigma$ with $\operatorname{adj}A = \det A\cdot A^{-1}$
exactly, and interpolated (a polynomial of degree $\le n$ in $\lambda$, $\le 2$ in $\sigma$).
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.symbolic.family import wedge_integrals as wi

__all__ = ["coefficient_gradients", "integral_gradients", "rank_record"]


def _inverse(A, n, engine):
    if engine == "flint":
        import flint
        X = flint.fmpq_mat(n, n, [v for row in A for v in row])
        return X.det(), [[v for v in row] for row in X.inv().tolist()]
    from sympy.polys.matrices import DomainMatrix
    dm = DomainMatrix([list(row) for row in A], (n, n), sp.QQ)
    return dm.det(), dm.inv().to_list()


def coefficient_gradients(M, gamma, engine: str = "sympy") -> tuple[list[tuple[int, int]], list[list]]:
    r"""The monomials $(i, j)$ of $\lambda^i\sigma^j$ (the $n - 1$ non-constant coefficients of $p$,
    eq:pol-first-integrals) and their exact gradients in $((M_{ij})_{i<j}, \gamma)$ (module docstring)."""
    num, zero, one = wi.numbers(engine)
    n = M.rows
    Mq = [[num(M[i, j]) for j in range(n)] for i in range(n)]
    g = [num(v) for v in gamma]
    pairs = wi.subsets(n, 2)
    lams = [num(sp.Rational(2 * t + 1, 3)) for t in range(n + 1)]   # real, never an eigenvalue of skew M
    sigs = [zero, one, 2 * one]
    values = {}   # (sigma index, lambda index) -> list over directions
    for si, s in enumerate(sigs):
        for li, lam in enumerate(lams):
            A = [[Mq[i][j] + s * g[i] * g[j] - (lam if i == j else zero) for j in range(n)] for i in range(n)]
            d, inv = _inverse(A, n, engine)
            if d == 0:
                raise ZeroDivisionError(f"det(M + sigma gamma gamma^T - lambda) = 0 at lambda = {lam}, sigma = {s}")
            adj = [[d * inv[i][j] for j in range(n)] for i in range(n)]
            row = [adj[j][i] - adj[i][j] for i, j in pairs]
            ag = [sum((adj[i][t] * g[t] for t in range(n)), zero) for i in range(n)]
            atg = [sum((adj[t][i] * g[t] for t in range(n)), zero) for i in range(n)]
            row += [s * (ag[m] + atg[m]) for m in range(n)]
            values[(si, li)] = row
    # interpolation: V c = values, V the Vandermonde matrices in lambda (n+1) and sigma (3)
    _, Vl = _inverse([[lam**e for e in range(n + 1)] for lam in lams], n + 1, engine)
    _, Vs = _inverse([[s**e for e in range(3)] for s in sigs], 3, engine)
    monomials = [(n - 2 * j, 0) for j in range(1, n // 2 + 1)] + [(n - 1 - 2 * j, 1) for j in range(1, (n + 1) // 2)]
    width = len(pairs) + n
    # first in sigma (3 nodes), then in lambda: sum_li Vl[i][li] sum_si Vs[j][si] values[si, li]
    in_sigma = {(j, li): [sum((Vs[j][si] * values[(si, li)][col] for si in range(3)), zero)
                          for col in range(width)]
                for j in {j for _, j in monomials} for li in range(n + 1)}
    grads = []
    for i, j in monomials:
        grads.append([sum((Vl[i][li] * in_sigma[(j, li)][col] for li in range(n + 1)), zero)
                      for col in range(width)])
    return monomials, grads


def integral_gradients(M, gamma, a, b, engine: str = "sympy") -> tuple[list[str], list[list]]:
    r"""Names and exact gradients of the $2n - 2 - \lfloor n/2\rfloor$ functions of the module docstring."""
    n = M.rows
    monomials, grads = coefficient_gradients(M, gamma, engine)
    names = [f"coefficient of lambda^{i} sigma^{j} of p" for i, j in monomials]
    for k in range(1, (n + 1) // 2):
        names.append("H_1 = 2H" if k == 1 else f"H_{k}")
        grads.append(wi.gradient(M, gamma, a, b, k, engine))
    return names, grads


def _rank(rows, engine):
    if not rows:
        return 0
    if engine == "flint":
        import flint
        return flint.fmpq_mat(len(rows), len(rows[0]), [v for r in rows for v in r]).rank()
    from sympy.polys.matrices import DomainMatrix
    return DomainMatrix([list(r) for r in rows], (len(rows), len(rows[0])), sp.QQ).rank()


def rank_record(M, gamma, a, b, engine: str = "sympy") -> dict:
    r"""At one exact point: the rank on $TP$ of the differentials, the names of those that are not
    conserved there (their differential is non-zero on the field) or not $SO(n-1)$-invariant. ``engine``
    does every step in its own numbers."""
    num, zero, one = wi.numbers(engine)
    n = M.rows
    names, grads = integral_gradients(M, gamma, a, b, engine)
    g = [num(v) for v in gamma]
    N = n * (n - 1) // 2
    tangent = [row[:N] + [row[N + i] - g[i] * sum((row[N + t] * g[t] for t in range(n)), zero)
                          for i in range(n)] for row in grads]
    X = wi.field(M, gamma, a, b, engine)
    not_conserved = [nm for nm, row in zip(names, grads, strict=True)
                     if wi.rate_of_gradient(row, X, engine) != 0]
    Mq = [[num(M[i, j]) for j in range(n)] for i in range(n)]
    pairs = wi.subsets(n, 2)
    gens = []
    for i, j in wi.subsets(n - 1, 2):   # X = e_i ^ e_j fixes E_n: velocity ([X, M], X gamma)
        X = [[zero] * n for _ in range(n)]
        X[i][j], X[j][i] = one, -one
        XM = [[sum((X[r][t] * Mq[t][c] - Mq[r][t] * X[t][c] for t in range(n)), zero) for c in range(n)]
              for r in range(n)]
        gens.append([XM[r][c] for r, c in pairs] + [sum((X[r][t] * g[t] for t in range(n)), zero) for r in range(n)])
    not_invariant = [nm for nm, row in zip(names, grads, strict=True)
                     if any(sum((x * y for x, y in zip(row, v, strict=True)), zero) != 0 for v in gens)]
    return {"n": n, "functions": len(names), "rank": _rank(tangent, engine), "names": names,
            "not_conserved": not_conserved, "not_invariant": not_invariant,
            "expected": 2 * n - 2 - n // 2}
