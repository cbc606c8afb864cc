r"""The known first integrals, for the exact first-integral search (row S6:first-integrals).

Generators (each an integral of eq:motion-general for every diagonal $\mathbb{J}$ unless said):

* the non-constant coefficients of $p(\lambda, \sigma) = \det(M + \sigma\gamma\gamma^T - \lambda)$
  (eq:pol-first-integrals), computed as those of $\det(\lambda - M - \sigma\gamma\gamma^T) = (-1)^n p$
  ($p = p_0 + \sigma p_1$: $\gamma\gamma^T$ has rank one); the $\lambda^k$ coefficient of $p_0$ has
  $M$-degree $n-k$ ($\gamma$-degree 0), that of $p_1$ $n-1-k$ ($\gamma$-degree 2); zero if that is odd;
* their square roots that are polynomials: $\mathrm{Pf}(M)$ for even $n$ ($\det M = \mathrm{Pf}(M)^2$),
  $\langle v, \gamma\rangle$ for odd $n$ with $v_i = (-1)^{i+1}\mathrm{Pf}(M_{\hat\imath\hat\imath})$
  ($\mathrm{adj}(M) = vv^T$, so $\gamma^T\mathrm{adj}(M)\gamma = \langle v, \gamma\rangle^2$): a continuous
  square root of an integral is an integral; for $n = 3$ this is $\langle M, \gamma\rangle$;
* the energy $H = \frac12\langle M, \Omega\rangle_\kappa$ (Section 2.2), $= P_H/D$ with $D$ the search's
  denominator (search.sampled_field);
* for the axisymmetric sphere and odd $n$, with ``include_new``: the integral found by the search,
  $F = \langle v, (2+a)E_n + bx\gamma\rangle^2/\Delta$ (symbolic/search/found_integral.py; proved there).

Each carries its $M$-degree, a bound of its numerator's $\gamma$-degree modulo $\|\gamma\|^2 = 1$
and its power of $D$, so that a product is placed in a candidate space only when it lies there.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import flint
import numpy as np
import sympy as sp
from chaplygin_nd.symbolic.search import backend, sampled_field
from chaplygin_nd.symbolic.search.sampled_field import Model

__all__ = ["Generator", "generators", "products", "values", "jacobian_rank"]


@dataclass(frozen=True)
class Generator:
    name: str
    m_degree: int
    g_degree: int      # bound of the numerator's gamma-degree modulo the sphere
    d_power: int       # the function is numerator / D^d_power


def _sphere_degree(expr, gam) -> int:
    """Total degree in gamma of expr reduced modulo gamma_n^2 = 1 - sum of the others."""
    rule = 1 - sum(g**2 for g in gam[:-1])
    poly = sp.Poly(sp.expand(expr), *gam)
    red = sp.Poly(0, *gam)
    for mon, c in poly.terms():
        q, r = divmod(mon[-1], 2)
        red += sp.Poly(c * sp.Mul(*[g**e for g, e in zip(gam[:-1], mon[:-1])]) * gam[-1]**r
                       * rule**q, *gam)
    return red.total_degree() if not red.is_zero else 0


@lru_cache(maxsize=16)
def _energy_degrees(model: Model) -> tuple[int, int]:
    """(gamma-degree of P_H, gamma-degree of D), both modulo the sphere."""
    from chaplygin_nd.symbolic.algebra import skew_symbols, vec, vector_symbols

    n = model.n
    gam = list(vector_symbols("g", n))
    M = skew_symbols("m", n)
    if model.kind == "axisymmetric":
        from chaplygin_nd.symbolic.axisym_inverse import ansatz_terms, inverse_coefficients
        from chaplygin_nd.symbolic.axisymmetric import Delta, a, b, x
        sub = {a: model.a, b: model.b}
        Dx = Delta(x, model.a, model.b)
        G = sp.Matrix(gam)
        num = sum((sp.cancel(c.subs(sub) * Dx).subs(x, gam[-1]) * T
                   for c, T in zip(inverse_coefficients(), ansatz_terms(M, G), strict=True)),
                  sp.zeros(n, n))
        PH = sp.Rational(1, 2) * sum(vec(M)[i] * vec(num)[i] for i in range(len(vec(M))))
        return _sphere_degree(PH, gam), 2
    from chaplygin_nd.symbolic.model import L_matrix
    L = L_matrix(sp.Matrix(gam), sp.diag(*model.J), model.b)
    m = vec(M)
    PH = sp.Rational(1, 2) * (m.T * L.adjugate() * m)[0, 0]
    return _sphere_degree(PH, gam), _sphere_degree(L.det(), gam)


def generators(model: Model, include_new: bool = False) -> list[Generator]:
    """The generators of the module docstring for this model, lowest M-degree first."""
    n = model.n
    out = [Generator(f"p0[lambda^{k}]", n - k, 0, 0) for k in range(n - 1) if (n - k) % 2 == 0]
    out += [Generator(f"p1[sigma lambda^{k}]", n - 1 - k, 2, 0) for k in range(n - 2)
            if (n - 1 - k) % 2 == 0]
    out.append(Generator("Pf(M)", n // 2, 0, 0) if n % 2 == 0 else
               Generator("<v, gamma>", (n - 1) // 2, 1, 0))
    out.append(Generator("H", 2, _energy_degrees(model)[0], 1))
    if include_new and model.kind == "axisymmetric" and n % 2:
        out.append(Generator("F", n - 1, 4, 1))
    if include_new and model.kind == "axisymmetric" and n >= 6:
        out.append(Generator("G", 4, 2, 1))
    return sorted(out, key=lambda g: (g.m_degree, g.name))


def products(model: Model, d: int, d_gamma: int, k: int, include_new: bool = False
             ) -> list[tuple[int, ...]]:
    r"""Multisets (index tuples) of generators whose product $F$ has $M$-degree $d$ and $F D^k$ is
    a polynomial of $\gamma$-degree $\le d_\gamma$: the known integrals that lie in the box."""
    gens = generators(model, include_new)
    dD = _energy_degrees(model)[1]
    out = []

    def rec(start, deg, gdeg, kp, acc):
        if deg == d:
            if kp <= k and gdeg + dD * (k - kp) <= d_gamma:
                out.append(tuple(acc))
            return
        for i in range(start, len(gens)):
            g = gens[i]
            if deg + g.m_degree <= d:
                rec(i, deg + g.m_degree, gdeg + g.g_degree, kp + g.d_power, acc + [i])

    rec(0, 0, 0, 0, [])
    return out


def _pfaffian(A, p):
    """Pfaffian of a batch of skew matrices mod p (expansion along the first row)."""
    m = A.shape[1]
    if m == 0:
        return np.ones(A.shape[0], dtype=np.int64)
    out = np.zeros(A.shape[0], dtype=np.int64)
    for j in range(1, m):
        keep = [i for i in range(m) if i not in (0, j)]
        sub = A[:, keep][:, :, keep]
        out = (out + (-1) ** (j + 1) * A[:, 0, j] % p * _pfaffian(sub, p)) % p
    return out


def values(model: Model, z: np.ndarray, p: int, include_new: bool = False) -> np.ndarray:
    """Values mod p of the generators (columns, in the order of :func:`generators`) at the points
    ``z`` (rows); H as the function P_H/D."""
    n = model.n
    pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]
    R = z.shape[0]
    M = np.zeros((R, n, n), dtype=np.int64)
    for c, (i, j) in enumerate(pairs):
        M[:, i, j], M[:, j, i] = z[:, c] % p, (-z[:, c]) % p
    g = z[:, len(pairs):] % p
    cp0 = np.zeros((R, n + 1), dtype=np.int64)
    cp1 = np.zeros((R, n + 1), dtype=np.int64)
    for r in range(R):
        A = M[r].tolist()
        B = (M[r] + np.outer(g[r], g[r]) % p).tolist()
        c0 = flint.nmod_mat(A, p).charpoly().coeffs()
        c1 = flint.nmod_mat(B, p).charpoly().coeffs()
        cp0[r, :len(c0)] = [int(c) for c in c0]
        cp1[r, :len(c1)] = [int(c) for c in c1]
    cols = {}
    for k in range(n + 1):
        cols[f"p0[lambda^{k}]"] = cp0[:, k]
        cols[f"p1[sigma lambda^{k}]"] = (cp1[:, k] - cp0[:, k]) % p
    if n % 2 == 0:
        cols["Pf(M)"] = _pfaffian(M, p)
    else:
        v = np.zeros((R,), dtype=np.int64)
        for i in range(n):
            keep = [t for t in range(n) if t != i]
            v = (v + (-1) ** i * _pfaffian(M[:, keep][:, :, keep], p) % p * g[:, i]) % p
        cols["<v, gamma>"] = v
        if include_new and model.kind == "axisymmetric":
            a, b = sampled_field.mod(model.a, p), sampled_field.mod(model.b, p)
            x = g[:, -1]
            w = np.zeros((R,), dtype=np.int64)
            for i in range(n):
                keep = [t for t in range(n) if t != i]
                vi = (-1) ** i * _pfaffian(M[:, keep][:, :, keep], p) % p
                ui = (b * x % p * g[:, i] + ((2 + a) if i == n - 1 else 0)) % p
                w = (w + vi * ui) % p
            delta = ((2 + a) * (2 + b) - a * b % p * x % p * x) % p
            cols["F"] = w * w % p * backend.inv_mod(delta, p) % p
    if include_new and model.kind == "axisymmetric" and n == 6:
        cols["G"] = _g6(M, g, model, p)
    elif include_new and model.kind == "axisymmetric" and n > 6:
        cols["G"] = _g_general(M, g, model, p)
    f = sampled_field.field_at(model, z, p)
    Om = f["Omega"]
    cols["H"] = sum(M[:, i, j] * Om[:, i, j] % p for i, j in pairs) % p * pow(2, p - 2, p) % p
    return np.stack([cols[gen.name] for gen in generators(model, include_new)], axis=1)


def _g6(M, g, model: Model, p: int) -> np.ndarray:
    """G of symbolic/search/found_integral.py (n = 6) mod p at the points, as a function (numerator / Delta)."""
    import itertools

    n = 6
    inv8 = pow(8, p - 2, p)
    W = np.zeros(M.shape, dtype=np.int64)
    for i in range(n):
        for j in range(n):
            if i == j:
                continue
            rest = [t for t in range(n) if t not in (i, j)]
            acc = np.zeros(M.shape[0], dtype=np.int64)
            for q in itertools.permutations(rest):
                t = (i, j) + q
                sgn = (-1) ** sum(1 for u in range(6) for v in range(u + 1, 6) if t[u] > t[v])
                acc = (acc + sgn * (M[:, q[0], q[1]] * M[:, q[2], q[3]] % p)) % p
            W[:, i, j] = acc * inv8 % p
    a, b = sampled_field.mod(model.a, p), sampled_field.mod(model.b, p)
    x = g[:, -1]
    P = W[:, :, -1] % p
    Q = np.einsum("rij,rj->ri", W, g) % p
    pp = (P * P % p).sum(1) % p
    pq = (P * Q % p).sum(1) % p
    qq = (Q * Q % p).sum(1) % p
    pg = (P * g % p).sum(1) % p
    num = (2 * a * (a + 2) % p * pp + 4 * a * b % p * x % p * pq + 2 * b * (b + 2) % p * qq
           + a * b % p * ((a + b + 4) % p) % p * (pg * pg % p)) % p
    delta = ((2 + a) * (2 + b) - a * b % p * x % p * x) % p
    return num * backend.inv_mod(delta, p) % p


def _g_general(M, g, model: Model, p: int) -> np.ndarray:
    """G_n of symbolic/search/found_integral.py ``general_integral`` mod p at the points (numerator / Delta)."""
    import itertools

    n = model.n
    w = {S: (M[:, S[0], S[1]] * M[:, S[2], S[3]] - M[:, S[0], S[2]] * M[:, S[1], S[3]]
             + M[:, S[0], S[3]] * M[:, S[1], S[2]]) % p for S in itertools.combinations(range(n), 4)}

    def wedge(form, deg, vec):
        return {S: sum((-1) ** (deg - t) * form[S[:t] + S[t + 1:]] * vec[:, S[t]] % p
                       for t in range(deg + 1)) % p
                for S in itertools.combinations(range(n), deg + 1)}

    e = np.zeros_like(g)
    e[:, -1] = 1
    we, wg = wedge(w, 4, e), wedge(w, 4, g)
    weg = wedge(we, 5, g)

    def dot(A, B):
        return sum(A[S] * B[S] % p for S in A) % p

    a, b = sampled_field.mod(model.a, p), sampled_field.mod(model.b, p)
    x = g[:, -1]
    num = (2 * a * (a + 2) % p * dot(we, we) + 4 * a * b % p * x % p * dot(we, wg)
           + 2 * b * (b + 2) % p * dot(wg, wg) + a * b % p * ((a + b + 4) % p) % p * dot(weg, weg)) % p
    delta = ((2 + a) * (2 + b) - a * b % p * x % p * x) % p
    return num * backend.inv_mod(delta, p) % p


def _gradients_at(model: Model, M: sp.Matrix, gamma: sp.Matrix) -> sp.Matrix:
    r"""Exact gradients in $(\mathrm{vec}\,M, \gamma)$ at a rational point of the non-constant
    coefficients of $p$ (Jacobi's formula over $\mathbb{Q}[\lambda, \sigma]$) and of $H$
    ($\partial_M H = \Omega$, $\partial_{\gamma_k}H = -\frac12\omega^T(\partial_k L)\omega$)."""
    from chaplygin_nd.symbolic import algebra
    from chaplygin_nd.symbolic.model import L_matrix, L_matrix_derivative
    from sympy.polys.matrices import DomainMatrix

    n = model.n
    lam, sig = sp.symbols("lambda sigma")
    ring = sp.QQ[lam, sig]
    A = DomainMatrix.from_Matrix(M + sig * gamma * gamma.T - lam * sp.eye(n)).convert_to(ring)
    adj = A.adjugate()
    dirs = list(algebra.so_basis(n))
    for k in range(n):
        e = algebra.basis_vector(n, k)
        dirs.append(sig * (e * gamma.T + gamma * e.T))
    base = A.det().to_dict()
    keys = sorted(m for m, c in base.items() if c and m not in ((n, 0), (n - 1, 1)) and sum(m) < n)
    rows = []
    for Dm in dirs:
        AD = adj * DomainMatrix.from_Matrix(Dm).convert_to(ring)
        tr = sum((AD[i, i].element for i in range(n)), ring.zero).to_dict()
        rows.append([sp.QQ.to_sympy(tr.get(m, sp.QQ.zero)) for m in keys])
    G = sp.Matrix(rows).T
    L = L_matrix(gamma, sp.diag(*model.J), model.b)
    om = L.LUsolve(algebra.vec(M))
    dH = list(om) + [-sp.Rational(1, 2) * (om.T * L_matrix_derivative(gamma, model.b, k) * om)[0]
                     for k in range(n)]
    return G.col_join(sp.Matrix([dH]))


def _new_gradient(model: Model, M: sp.Matrix, gamma: sp.Matrix) -> list:
    """Exact gradient of F (symbolic/search/found_integral.py) at the point, in (vec M, gamma)."""
    from chaplygin_nd.symbolic.algebra import skew_symbols, vec, vector_symbols
    from chaplygin_nd.symbolic.search import found_integral

    n = model.n
    Ms, gs = skew_symbols("m", n), vector_symbols("g", n)
    num, den = found_integral.new_integral(Ms, gs, model.a, model.b)
    syms = list(vec(Ms)) + list(gs)
    ctx = flint.fmpq_mpoly_ctx.get(tuple(f"x{i}" for i in range(len(syms))), "lex")

    def fl(e):
        P = sp.Poly(sp.expand(e), *syms)
        return ctx.from_dict({m: flint.fmpq(int(c.p), int(c.q)) for m, c in P.terms()})

    N, D = fl(num), fl(den)
    args = [flint.fmpq(int(sp.Rational(v).p), int(sp.Rational(v).q)) for v in list(vec(M)) + list(gamma)]
    n0, d0 = N(*args), D(*args)
    out = []
    for i in range(len(syms)):
        q = (N.derivative(i)(*args) * d0 - n0 * D.derivative(i)(*args)) / (d0 * d0)
        out.append(sp.Rational(int(q.p), int(q.q)))
    return out


def jacobian_rank(model: Model, seed: int, include_new: bool = False) -> dict:
    r"""The number of functionally independent known integrals: the exact rank of their gradients
    restricted to $T_{(M,\gamma)}P$ at a seeded rational point, by SymPy (``DomainMatrix`` over
    $\mathbb{Q}$) and FLINT (``fmpq_mat``); they must agree. The square roots have gradients
    proportional to their squares' and are not counted again."""
    from chaplygin_nd.symbolic.exact import points
    from chaplygin_nd.symbolic.exact.flint_engine import to_fmpq
    from sympy.polys.matrices import DomainMatrix

    rng = points.generator(seed, "S6:first-integrals", model.n, model.kind)
    gamma = points.sphere_point(rng, model.n)
    M = points.skew_matrix(rng, model.n)
    G = _gradients_at(model, M, gamma)
    if include_new and model.kind == "axisymmetric" and model.n % 2:
        G = G.col_join(sp.Matrix([_new_gradient(model, M, gamma)]))
    dim = model.n * (model.n - 1) // 2
    T = G * sp.diag(sp.eye(dim), sp.eye(model.n) - gamma * gamma.T)
    r1 = DomainMatrix.from_Matrix(T).convert_to(sp.QQ).rank()
    r2 = flint.fmpq_mat(T.rows, T.cols, [to_fmpq(v) for v in T]).rank()
    if r1 != r2:
        raise ArithmeticError(f"the engines disagree on the Jacobian rank: {r1} vs {r2}")
    return {"rank": r1, "functions": T.rows, "engines": "SymPy+FLINT"}


def jacobian_rank_mod_p(model: Model, include_new: bool = True, prime_index: int = 0,
                        seed: int = 0) -> dict:
    r"""A lower bound of the exact Jacobian rank (on $TP$) of the generators that are not square
    roots, at an integer-seeded rational point of $P$: the rank modulo $p$ of the reduction of the
    rational Jacobian (rank$_p \le$ rank$_\mathbb{Q}$). Each directional derivative is the linear
    coefficient of $\varepsilon \mapsto D^k f(z + \varepsilon e)$ (a polynomial of degree $< 24$),
    interpolated exactly mod $p$, then divided by $D$. Full rank mod $p$ proves independence."""
    p = sampled_field.PRIMES[prime_index]
    gens = generators(model, include_new)
    keep = [i for i, g in enumerate(gens) if g.name not in ("Pf(M)", "<v, gamma>")]
    n = model.n
    dim = n * (n - 1) // 2
    z0 = sampled_field.sample(model, 1, p, np.random.default_rng([seed, 17, n]))["z"][0]
    eps = np.arange(1, 25, dtype=np.int64)
    grads = []
    for c in range(dim + n):
        pts = np.array([(z0 + e * (np.arange(dim + n) == c)) % p for e in eps])
        f = values(model, pts, p, include_new)[:, keep]
        D = sampled_field.field_at(model, pts, p)["D"]
        cols = []
        for j, i in enumerate(keep):
            num = f[:, j] * (D if gens[i].d_power else 1) % p
            cols.append(_linear_coefficient(eps, num, p))
        grads.append(cols)
    J = np.array(grads, dtype=np.int64).T % p            # functions x coordinates
    D0 = sampled_field.field_at(model, z0[None, :], p)["D"][0]
    f0 = values(model, z0[None, :], p, include_new)[0, keep]
    inv = int(backend.inv_mod(np.array([D0]), p)[0])
    for j, i in enumerate(keep):   # d(P/D) = (dP - f dD)/D with P = f D for the rational ones
        if gens[i].d_power:
            dD = np.array([_linear_coefficient(
                eps, sampled_field.field_at(model, np.array([(z0 + e * (np.arange(dim + n) == c)) % p
                                                        for e in eps]), p)["D"], p)
                for c in range(dim + n)])
            J[j] = (J[j] - f0[j] * dD) % p * inv % p
    g = z0[dim:] % p
    proj = (np.eye(n, dtype=np.int64) - np.outer(g, g)) % p
    T = np.concatenate([J[:, :dim], J[:, dim:] @ proj % p], axis=1) % p
    r = backend.get().rank(T, p)
    return {"rank_mod_p": r, "functions": len(keep), "prime": p,
            "names": [gens[i].name for i in keep]}


def _linear_coefficient(xs: np.ndarray, ys: np.ndarray, p: int) -> int:
    """The coefficient of x in the interpolating polynomial of (xs, ys) mod p (exact when the
    polynomial has degree < len(xs)); the values at x = xs, the constant term is f(0)."""
    A = flint.nmod_mat([[pow(int(x), k, p) for k in range(len(xs))] for x in xs], p)
    b = flint.nmod_mat([[int(y)] for y in ys], p)
    return int(A.solve(b)[1, 0])
