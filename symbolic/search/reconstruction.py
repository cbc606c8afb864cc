r"""From an $\mathbb{F}_p$ kernel to integrals over $\mathbb{Q}$, proved (row S6:first-integrals).

A candidate of the search (symbolic/search/integral_search.py) is only a candidate. Here:

1. The block's unknowns are re-expressed in a **real** basis: complex conjugation maps each
   orbit column to $\pm$ an orbit column ($\mathrm{conj}\,c = s\,c'$), and the columns
   $c + s c'$, $i(c - s c')$ (or $c$, $ic$ when $c' = c$) are real polynomials with rational
   coefficients in $(M_{ij}, \gamma_i)$. The integrals of the block then have a basis over
   $\mathbb{Q}$ in these columns.
2. The reduced row echelon form of the kernel (its rows: a basis) is canonical, so that of
   several primes agree with the reduction of the rational one; entries are lifted by the
   Chinese remainder theorem and rational reconstruction, and accepted only if one more prime
   reproduces them.
3. Each reconstructed $P$ is proved: $D\,X(P) - kP\,X(D) \equiv 0$ modulo $\|\gamma\|^2 - 1$ as an
   exact polynomial identity, SymPy and FLINT (symbolic/exact/identity.py ``rational_identity``), with
   the project's derived numerator of $L_\gamma^{-1}$ (P:inversion). Axisymmetric model only.
"""

from __future__ import annotations

import flint
import numpy as np
import sympy as sp
from chaplygin_nd.symbolic.search import backend as backends
from chaplygin_nd.symbolic.search import candidate_basis, conditions, sampled_field
from chaplygin_nd.symbolic.search.box_search import MARGIN, BoxSearch
from chaplygin_nd.symbolic.search.sampled_field import Model

__all__ = ["real_columns", "kernel_rref", "reconstruct", "real_symbols", "to_expression",
           "prove_integral"]


def _conjugation(co: candidate_basis.Coordinates):
    perm, sign = [], []
    C = co.re + 1j * co.im
    for r in range(len(C)):
        img = np.conj(C[r])
        for t in range(len(C)):
            if np.allclose(img, C[t]):
                perm.append(t)
                sign.append(1)
                break
            if np.allclose(img, -C[t]):
                perm.append(t)
                sign.append(-1)
                break
        else:
            raise ArithmeticError("conjugation does not permute the coordinates")
    return np.array(perm), np.array(sign)


def real_columns(B: candidate_basis.Basis, blk: candidate_basis.Block) -> list[list[tuple[int, int, int]]]:
    """Real basis of the block: each entry a list of (complex column, coefficient, power of i);
    every column is mapped to +- itself by conjugation (see the loop), so each entry is one column,
    real (power 0) or i times an imaginary one (power 1)."""
    perm, sign = _conjugation(B.coords)
    members: dict[int, dict[tuple, int]] = {}
    where: dict[tuple, int] = {}
    for m, s, c in zip(blk.monomial, blk.sign, blk.column):
        members.setdefault(int(c), {})[tuple(B.exponents[m])] = int(s)
        where[tuple(B.exponents[m])] = int(c)
    out, done = [], set()
    for c in range(blk.columns):
        if c in done:
            continue
        e, s0 = next(iter(members[c].items()))
        image = [0] * len(e)
        s = s0
        for i, x in enumerate(e):
            if x:
                image[perm[i]] = x
                if sign[i] < 0 and x % 2:
                    s = -s
        img = tuple(image)
        c2 = where[img]
        s = s * members[c2][img]           # conj(column c) = s * column c2
        done |= {c, c2}
        if c2 != c:  # never: conjugation is the product of the reflections of each plane's
            # second axis (z_k -> conj z_k), so it maps every orbit sum of the group to +- itself
            raise ArithmeticError(f"conjugation moves column {c} of block {blk.character} to {c2}")
        out.append([(c, 1, 0)] if s == 1 else [(c, 1, 1)])   # real, or i times imaginary
    return out


def _real_matrix(A: np.ndarray, cols, p: int, i_p: int) -> np.ndarray:
    out = np.zeros((A.shape[0], len(cols)), dtype=np.int64)
    for j, combo in enumerate(cols):
        for c, coeff, ipow in combo:
            f = coeff * (i_p if ipow else 1) % p
            out[:, j] = (out[:, j] + A[:, c] * f) % p
    return out


def kernel_rref(model: Model, d: int, d_gamma: int, k: int, character: int, prime_index: int,
                seed: int = 0, backend: str = "flint"):
    """The RREF (rows) of the kernel of the block ``character`` in the real basis, mod p."""
    p = sampled_field.PRIMES[prime_index]
    i_p = backends.sqrt_minus_one(p)
    B = candidate_basis.basis(model.n, d, d_gamma, model.planes)
    blk = next(b for b in B.blocks if b.character == character)
    cols = real_columns(B, blk)
    rng = np.random.default_rng([seed, 99, model.n, d, d_gamma, k, prime_index])
    rows = blk.columns + MARGIN
    s = sampled_field.sample(model, rows + rows // 8 + 8, p, rng)
    cv = conditions.coordinate_values(B.coords, s["z"], p, i_p)
    cd = conditions.coordinate_values(B.coords, s["zdot"], p, i_p)
    cv, cd, dlog = conditions.admissible(cv, cd, s["dlogD"], rows)
    Y = conditions.condition_values(B.exponents, cv, cd, dlog, k, p)
    A = _real_matrix(conditions.block_apply(Y, blk, p), cols, p, i_p)
    R = BoxSearch(model, backend=backend).kernel_rref(A, p)
    return R, B, blk, cols


def reconstruct(model: Model, d: int, d_gamma: int, k: int, character: int, primes: int = 4):
    """Rational kernel RREF of a block from ``primes`` primes (the last one checks; the lifting of
    symbolic/search/box_search.py)."""
    found = {}

    def at(i):
        found[i] = kernel_rref(model, d, d_gamma, k, character, i)
        return found[i][0]

    out = BoxSearch(model).rational_kernel(at, primes)
    _R, B, blk, cols = found[0]
    return out, B, blk, cols


def real_symbols(n: int):
    """The symbols M_<i><j> (i < j, 1-based) and gamma_<i> of the row's text."""
    Ms = [sp.Symbol(f"M_{i + 1}{j + 1}") for i in range(n) for j in range(i + 1, n)]
    gs = [sp.Symbol(f"gamma_{i + 1}") for i in range(n)]
    return Ms, gs


def to_expression(B: candidate_basis.Basis, blk: candidate_basis.Block, cols, coeffs) -> sp.Expr:
    """The real polynomial sum_j coeffs[j] * (real column j), as a SymPy expression in
    :func:`real_symbols` (built with FLINT fmpq_mpoly complex arithmetic)."""
    co = B.coords
    n = co.n
    Ms, gs = real_symbols(n)
    syms = Ms + gs
    ctx = flint.fmpq_mpoly_ctx.get(tuple(str(s) for s in syms), "lex")
    X = ctx.gens()
    zero = ctx.from_dict({})
    lin = [(sum((int(co.re[r, j]) * X[j] for j in range(len(syms)) if co.re[r, j]), zero),
            sum((int(co.im[r, j]) * X[j] for j in range(len(syms)) if co.im[r, j]), zero))
           for r in range(len(co.names))]
    one = (ctx.constant(1), zero)

    def mul(u, v):
        return (u[0] * v[0] - u[1] * v[1], u[0] * v[1] + u[1] * v[0])

    cache: dict = {}

    def mono(i):
        if i not in cache:
            acc = one
            for r, e in enumerate(B.exponents[i]):
                for _ in range(int(e)):
                    acc = mul(acc, lin[r])
            cache[i] = acc
        return cache[i]

    colpoly: dict = {}

    def column(c):
        if c not in colpoly:
            acc = (zero, zero)
            for m, s, cc in zip(blk.monomial, blk.sign, blk.column):
                if cc == c:
                    t = mono(int(m))
                    acc = (acc[0] + int(s) * t[0], acc[1] + int(s) * t[1])
            colpoly[c] = acc
        return colpoly[c]

    total = zero
    for q, combo in zip(coeffs, cols):
        if q == 0:
            continue
        re = zero
        for c, coeff, ipow in combo:
            u = column(c)
            re += coeff * (u[0] if not ipow else -u[1])   # Re(i^ipow * u)
        total += flint.fmpq(int(sp.Rational(q).p), int(sp.Rational(q).q)) * re
    terms = total.to_dict()
    return sp.Add(*[sp.Rational(int(c.p), int(c.q)) * sp.Mul(*[s**int(e) for s, e in zip(syms, mon)])
                    for mon, c in terms.items()])


def prove_integral(expr: sp.Expr, model: Model, k: int, a=None, b=None):
    r"""Exact proof (SymPy and FLINT) that ``expr``$/\Delta^k$ is a first integral of the
    axisymmetric sphere: $\Delta\,\nabla P\cdot\dot z(N) - kP\,\nabla\Delta\cdot\dot z(N) \equiv 0$ modulo
    the sphere, $N = 2\Delta(2+a+b)\,\Omega$ the derived numerator (P:inversion). ``a``, ``b``:
    rationals (default the model's) or SymPy symbols."""
    from chaplygin_nd.symbolic.algebra import commutator, unvec
    from chaplygin_nd.symbolic.axisym_inverse import inverse_numerator
    from chaplygin_nd.symbolic.exact.identity import rational_identity

    n = model.n
    a = model.a if a is None else a
    b = model.b if b is None else b
    Ms, gs = real_symbols(n)
    M, g = unvec(Ms, n), sp.Matrix(gs)
    N = inverse_numerator(M, g, a, b)
    Mdot, gdot = commutator(M, N), -N * g
    params = [s for s in (a, b) if isinstance(s, sp.Symbol)]
    R, *_ = sp.ring(list(reversed(gs)) + Ms + params, sp.QQ)
    P = R(sp.expand(expr))
    delta = R(sp.expand((2 + a) * (2 + b) - a * b * gs[-1] ** 2))
    zdot = [R(sp.expand(Mdot[i, j])) for i in range(n) for j in range(i + 1, n)] + \
           [R(sp.expand(v)) for v in gdot]
    syms = [R(s) for s in Ms + gs]
    XP = sum((P.diff(s) * v for s, v in zip(syms, zdot)), R.zero)
    XD = sum((delta.diff(s) * v for s, v in zip(syms, zdot)), R.zero)
    residual = delta * XP - k * P * XD
    return rational_identity([residual], sphere=gs, label="first integral")
