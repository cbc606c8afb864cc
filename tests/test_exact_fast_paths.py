"""The fast exact routes agree with the routes they replace: Delta at rational points evaluated
in Q[x, a, b] against the determinant of block_C, and the Jacobi residual of the Poisson proof in
sparse polynomials against its expression form (the same polynomials, structurally)."""

from random import Random

import sympy as sp
from chaplygin_nd.symbolic import axisymmetric as ax
from chaplygin_nd.symbolic.search import bivector_ansatz as ba
from chaplygin_nd.symbolic.search import poisson_proof as pp


def test_delta_rational_fast_path_equals_determinant():
    rng = Random(20261127)
    for _ in range(60):
        x, a, b = (sp.Rational(rng.randint(-40, 40), rng.randint(1, 30)) for _ in range(3))
        fast = ax.Delta(x, a, b)
        assert fast.is_Rational
        assert fast == sp.expand(ax.block_C(x, a, b).det())
    assert ax.Delta(1, 0, 2) == sp.expand(ax.block_C(1, 0, 2).det())


def test_delta_symbolic_is_the_expanded_determinant():
    g = sp.Symbol("g")
    assert ax.Delta(g) == sp.expand(ax.block_C(g, ax.a, ax.b).det())
    assert ax.Delta() == sp.expand(ax.block_C().det())


def test_jacobi_residual_ring_equals_expression_route():
    sa, sb = sp.symbols("a b", real=True)
    coords = ba.coordinates(3)[2]
    P = pp.borisov_mamaev(sa, sb)
    fast = pp._jacobi_residual_ring(P, coords, sa, sb, sp.Rational(-1, 2))
    slow = pp._jacobi_residual_expr(P, coords, sa, sb, sp.Rational(-1, 2))
    assert fast is not None and len(fast) == len(slow) == 20
    assert all(f == s for f, s in zip(fast, slow, strict=True))
    # a perturbed (non-Poisson) structure: both routes give the same non-zero residuals
    Q = P + sp.Matrix(6, 6, lambda i, j: 0 if i == j else (1 if i < j else -1)) * coords[0]
    fast = pp._jacobi_residual_ring(Q, coords, sa, sb, sp.Rational(1, 3))
    slow = pp._jacobi_residual_expr(Q, coords, sa, sb, sp.Rational(1, 3))
    assert any(s != 0 for s in slow)
    assert all(f == s for f, s in zip(fast, slow, strict=True))


def test_jacobi_residual_falls_back_on_denominators():
    sa, sb = sp.symbols("a b", real=True)
    coords = ba.coordinates(3)[2]
    P = pp.borisov_mamaev(sa, sb) / (1 + sa**2)
    assert pp._jacobi_residual_ring(P, coords, sa, sb, sp.Rational(-1, 2)) is None
    assert len(pp.jacobi_residual(P, coords, 3, sa, sb, sp.Rational(-1, 2))) == 20


def _L_entries_reference(gamma, Jdiag, b, zero, one, derivative=None):
    """The assembly of L_gamma entry by entry with every Kronecker delta multiplied out (the
    definition of eq:M-O written literally), to compare the resolved assembly with."""
    n = len(gamma)
    pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]

    def d(p, q):
        return one if p == q else zero

    def g(p):
        return gamma[p] if derivative is None else d(p, derivative)

    rows = []
    for k, l in pairs:
        row = []
        for i, j in pairs:
            if derivative is None:
                entry = gamma[j] * (d(k, i) * gamma[l] - d(l, i) * gamma[k]) \
                    - gamma[i] * (d(k, j) * gamma[l] - d(l, j) * gamma[k])
            else:
                entry = g(j) * (d(k, i) * gamma[l] - d(l, i) * gamma[k]) \
                    + gamma[j] * (d(k, i) * g(l) - d(l, i) * g(k)) \
                    - g(i) * (d(k, j) * gamma[l] - d(l, j) * gamma[k]) \
                    - gamma[i] * (d(k, j) * g(l) - d(l, j) * g(k))
            entry = b * entry
            if derivative is None and (k, l) == (i, j):
                entry = entry + Jdiag[i] + Jdiag[j]
            row.append(entry)
        rows.append(row)
    return rows


def test_L_entries_equals_the_literal_assembly():
    import flint
    from chaplygin_nd.symbolic.mass_operator import L_entries
    from sympy.polys.domains import QQ

    rng = Random(7)
    for n in (3, 4, 5, 7):
        gs = list(sp.symbols(f"g1:{n + 1}"))
        Js = list(sp.symbols(f"J1:{n + 1}"))
        qs = [sp.Rational(rng.randint(-9, 9), rng.randint(1, 9)) for _ in range(n)]
        cases = [(gs, Js, sp.Symbol("b"), sp.S.Zero, sp.S.One),
                 ([QQ.from_sympy(q) for q in qs], [QQ(k + 2) for k in range(n)], QQ(2, 5), QQ.zero, QQ.one),
                 ([flint.fmpq(int(q.p), int(q.q)) for q in qs], [flint.fmpq(k + 2) for k in range(n)],
                  flint.fmpq(2, 5), flint.fmpq(0), flint.fmpq(1))]
        for gamma, J, b, zero, one in cases:
            for derivative in (None, 0, n - 1):
                new = L_entries(gamma, J, b, zero, one, derivative)
                old = _L_entries_reference(gamma, J, b, zero, one, derivative)
                assert new == old
                assert [type(v) for r in new for v in r] == [type(v) for r in old for v in r]


def test_block_coefficients_equal_the_forms_at_the_basis():
    from chaplygin_nd.symbolic.algebra import so_basis

    for n in (3, 4):
        gamma0 = sp.zeros(n, 1)
        gamma0[n - 2], gamma0[n - 1] = sp.Rational(3, 5), sp.Rational(4, 5)
        basis, E = so_basis(n), ba._E(n)
        coefficients = ba._linear_coefficients(n, gamma0, E)
        m = len(basis)
        for p in range(m):
            for q in range(p + 1, m):
                for c in range(m):
                    at = [sp.expand(v) for v in ba.mm_blocks(basis[p], basis[q], basis[c], gamma0, E)]
                    assert coefficients[(p, q, c)] == at


def _mm_blocks_literal(xi, eta, M, gamma, E):
    """The MM forms as the module docstring of bivector_ansatz writes them (left-to-right products)."""
    from chaplygin_nd.symbolic.axisym_inverse import ansatz_terms

    T = ansatz_terms(M, gamma)
    br = xi * eta - eta * xi
    lx, ly = ba._dot(xi * gamma, E), ba._dot(eta * gamma, E)
    out = [ba._kil(t, br) for t in T]
    out += [lx * ba._kil(eta, t) - ly * ba._kil(xi, t) for t in T]
    out.append(ba._dot(M * gamma, E) * (ba._dot(xi * gamma, eta * E) - ba._dot(eta * gamma, xi * E)))
    out.append(ba._dot(xi * gamma, M * eta * gamma))
    out.append(ba._dot(xi * E, M * eta * E))
    out.append(ba._dot(xi * gamma, M * eta * E) - ba._dot(eta * gamma, M * xi * E))
    for u in (gamma, E):
        for w in (M * gamma, M * E):
            out.append(ba._dot(xi * u, eta * w) - ba._dot(eta * u, xi * w))
    return out


def test_mm_blocks_equal_the_literal_forms():
    from chaplygin_nd.symbolic.algebra import so_basis

    for n in (3, 4):
        M, gamma, _ = ba.coordinates(n)
        E = ba._E(n)
        basis = so_basis(n)
        xi = sum((sp.Rational(k + 1, 3) * B for k, B in enumerate(basis)), sp.zeros(n, n))
        for eta in basis:
            new = [sp.expand(v) for v in ba.mm_blocks(xi, eta, M, gamma, E)]
            assert new == [sp.expand(v) for v in _mm_blocks_literal(xi, eta, M, gamma, E)]


def test_rational_draws_the_integers_of_ceiling_and_floor():
    """The bounds of a seeded draw in integer arithmetic are SymPy's ceiling(lo q) and floor(hi q)."""
    from chaplygin_nd.symbolic.exact import points

    rng = Random(11)
    for _ in range(500):
        lo = sp.Rational(rng.randint(-30, 30), rng.randint(1, 9))
        hi = lo + 1 + sp.Rational(rng.randint(0, 40), rng.randint(1, 9))   # an integer p in [lo q, hi q]
        q = rng.randint(1, 15)
        r1, r2 = Random(q), Random(q)
        mine = points.rational(r1, lo, hi, q)
        qq = r2.randint(1, q)
        assert mine == sp.Rational(r2.randint(int(sp.ceiling(lo * qq)), int(sp.floor(hi * qq))), qq)


def test_power_blocks_are_the_expanded_products():
    M, gamma, _ = ba.coordinates(3)
    x = gamma[2]
    for j, B in enumerate(ba._symbolic_blocks(3)):
        for k in (1, 2, 3):
            mine = ba._power_block(3, j, k)
            assert [sp.srepr(v) for v in mine] == [sp.srepr(sp.expand(x**k * v)) for v in B]
