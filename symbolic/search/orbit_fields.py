r"""Exact identities modulo the sphere for the symmetry-field search
(symbolic/search/symmetry_fields.py, row S7:symmetry-fields): the proof that a polynomial vanishes
on $P$, the proof that a kernel vector is a field along the $SO(n-1)$-orbits, and the invariants
that proof uses.

**Vanishing on the sphere.** A polynomial $f \in \mathbb{Q}[M, \gamma]$ vanishes on
$\mathfrak{so}(n) \times S^{n-1}$ exactly when $\|\gamma\|^2 - 1$ divides it ($\|\gamma\|^2 - 1$ is
irreducible for $n \ge 2$ and its zero set is the sphere). The division is exact, in FLINT
(``fmpq_mpoly`` division with remainder: the remainder has no term divisible by the leading
monomial of the divisor, so for one divisor — a Gröbner basis of the ideal it generates — the
remainder is zero exactly when the divisor divides $f$). :func:`sphere_normal_form` is the same
test in SymPy (powers of $\gamma_n^2$ replaced), the second engine the tests compare it with.
"""

from __future__ import annotations

import flint
import sympy as sp
from chaplygin_nd.symbolic.algebra import so_basis, vec
from chaplygin_nd.symbolic.search import bivector_ansatz as ba
from chaplygin_nd.symbolic.search.box_columns import mpoly_context as _ctx
from chaplygin_nd.symbolic.search.box_columns import rref_solve as _rref_solve
from chaplygin_nd.symbolic.search.box_columns import sample_points as _points
from chaplygin_nd.symbolic.search.point_values import fq as _fq

__all__ = ["vanishes_on_sphere", "sphere_normal_form", "to_sympy", "invariants", "orbit_fields", "rho_x_combination"]


def _sphere(ctx, n: int):
    """$\\|\\gamma\\|^2 - 1$ in ``ctx`` (its last n generators are $\\gamma_1..\\gamma_n$)."""
    gens = ctx.gens()
    return sum((g * g for g in gens[len(gens) - n:]), ctx.from_dict({})) - 1


def vanishes_on_sphere(poly, n: int) -> bool:
    r"""Whether the ``fmpq_mpoly`` $f$ (coordinates $M$ then $\gamma$) vanishes on
    $\mathfrak{so}(n)\times S^{n-1}$: $\|\gamma\|^2 - 1$ divides $f$ over $\mathbb{Q}$ (module
    docstring; exact)."""
    if poly.is_zero():
        return True
    return divmod(poly, _sphere(poly.context(), n))[1].is_zero()


def to_sympy(poly, z) -> sp.Expr:
    """The ``fmpq_mpoly`` as a SymPy expression in the symbols ``z`` (one sum, linear in its terms)."""
    terms = []
    for mono, c in poly.to_dict().items():
        terms.append(sp.Rational(int(c.p), int(c.q)) * sp.Mul(*[v**int(e) for v, e in zip(z, mono, strict=True) if e]))
    return sp.Add(*terms)


def sphere_normal_form(expr: sp.Expr, gamma: list) -> sp.Expr:
    """Normal form of a SymPy polynomial modulo $\\|\\gamma\\|^2 - 1$ (powers of $\\gamma_n^2$
    replaced by $1 - \\gamma_1^2 - \\dots - \\gamma_{n-1}^2$); zero exactly when it vanishes on the
    sphere. The second engine beside :func:`vanishes_on_sphere`."""
    g = gamma[-1]
    rest = 1 - sum(v**2 for v in gamma[:-1])
    return sp.expand(sp.rem(sp.Poly(expr, g), sp.Poly(g**2 - rest, g)).as_expr())


def _E(n):
    e = sp.zeros(n, 1)
    e[n - 1] = 1
    return e


def invariants(n: int, M, gamma) -> list:
    r"""$O(n-1)$-invariant polynomials: $x = \gamma_n$, $\langle M^i u, M^j v\rangle$ ($u, v \in
    \{\gamma, E_n\}$, $i + j \le T$), $\operatorname{tr} M^{2k}$ ($2 \le 2k \le T$), with
    $T = 4$ for $n \le 6$ (where it spans) and $T = n - 1$ above ($n = 7$ needs degree 6). Where their
    differentials and $d\|\gamma\|^2$ have rank $\dim P + 1 - \dim(\text{orbit})$ they span the
    annihilator of the orbit (checked at a point in :func:`orbit_fields`)."""
    E = _E(n)
    top = 4 if n <= 6 else n - 1
    pw = [sp.eye(n)]
    for _ in range(top):
        pw.append(pw[-1] * M)
    out = [gamma[n - 1]] + [pw[k].trace() for k in range(2, top + 1, 2)]
    for i in range(top + 1):
        for j in range(i, top + 1 - i):
            for u, v in ((gamma, gamma), (E, E), (gamma, E)):
                if u is v and (i + j) % 2 == 1:
                    continue
                if (i, j) == (0, 0):
                    continue
                out.append(sp.expand(((pw[i] * u).T * (pw[j] * v))[0, 0]))
    return [e for e in out if e != 0]


def orbit_fields(n, z, cols, others, seed) -> list:
    r"""The combinations of ``others`` (kernel vectors on the columns ``cols``, ``fmpq_mpoly``
    components) that are fields along the $SO(n-1)$-orbits, each proved exactly, as (field, its
    coefficients on the columns): $Q(I)$ vanishes on the sphere (:func:`vanishes_on_sphere`) for
    every invariant $I$ of :func:`invariants`, whose differentials span the annihilator of the
    orbits at a seeded point (exact rank; if they do not, nothing is proved and [] is returned)."""
    M, gamma, _ = ba.coordinates(n)
    inv = invariants(n, M, gamma)
    ctx = _ctx(z)
    N = len(z)
    fl = [ctx.from_dict({mm: _fq(c) for mm, c in sp.Poly(e, *z).as_dict().items()}) for e in inv]
    grads = [[f.derivative(l) for l in range(N)] for f in fl]
    (Mp, gp), = _points(n, 1, seed, "orbit-span")
    pt = [_fq(v) for v in list(vec(Mp)) + list(gp)]
    rowsd = [[g(*pt) for g in gr] for gr in grads] + [[flint.fmpq(0)] * (N - n) + [2 * v for v in pt[N - n:]]]
    basis = [A for A in so_basis(n) if all(A[i, n - 1] == 0 for i in range(n))]
    zetas = [[_fq(v) for v in list(vec(A * Mp - Mp * A)) + list(A * gp)] for A in basis]
    rk = lambda r: flint.fmpq_mat(len(r), N, [v for row in r for v in row]).rref()[1]  # noqa: E731
    if rk(rowsd) != N - rk(zetas):
        return []
    zero = ctx.from_dict({})

    def field(v):
        return [sum((c * cols[u][i] for u, c in enumerate(v) if c != 0 and cols[u][i] is not None), zero)
                for i in range(N)]
    fields = [field(v) for v in others]
    rows = []
    for Mv, gv in _points(n, 6, seed, "orbit-fields"):
        ptv = [_fq(x) for x in list(vec(Mv)) + list(gv)]
        gvals = [[g(*ptv) for g in gr] for gr in grads]
        Qs = [[q(*ptv) for q in Q] for Q in fields]
        for gk in gvals:
            rows.append([sum((gk[i] * Q[i] for i in range(N)), flint.fmpq(0)) for Q in Qs])
    _, comb = _rref_solve(rows, [flint.fmpq(0)] * len(rows))
    proved = []
    for c in comb:
        Q = [sum((ci * F[i] for ci, F in zip(c, fields, strict=True) if ci != 0), zero) for i in range(N)]
        if all(vanishes_on_sphere(sum((Q[i] * gr[i] for i in range(N)), zero), n) for gr in grads):
            proved.append((Q, [sum((ci * v[u] for ci, v in zip(c, others, strict=True)), flint.fmpq(0))
                               for u in range(len(cols))]))
    return proved


def rho_x_combination(n, z, cols, dx: int, k: int, a, b, seed) -> list | None:
    r"""The field $\Delta^\tau X$ written in the box when $s = \tau - 1 - k$ ($k \ge 1$): $Y =
    \Delta^s Q$ with $Q = \Delta^k\,DX$ ($DX$ = column ``dx``), if $Q$ is a combination of the
    columns ``cols``. The coefficients are solved at seeded points and the identity
    $\sum_u c_u\,\mathrm{col}_u = \Delta(x)^k\,DX$ proved exactly modulo the sphere
    (:func:`vanishes_on_sphere`); returns them, or None when $Q$ is not in the span. Such a $Y$ is
    $\rho X$ itself (up to the constant $2(2+a+b)$): a trivial solution."""
    from chaplygin_nd.symbolic.axisymmetric import Delta

    ctx = _ctx(z)
    N = len(z)
    xs = sp.Symbol("x")
    Dp = sp.Poly(Delta(xs, sp.Rational(a), sp.Rational(b)), xs)
    xf = ctx.gens()[N - 1]
    Dk = sum((_fq(c) * xf**int(e) for (e,), c in Dp.as_dict().items()), ctx.from_dict({})) ** k
    target = [Dk * p if p is not None else None for p in cols[dx]]
    count = 2 * (len(cols) // N) + 6
    rows, rhs = [], []
    for M, g in _points(n, count, seed, "rho-x"):
        pt = [_fq(v) for v in list(vec(M)) + list(g)]
        for i in range(N):
            rows.append([c[i](*pt) if c[i] is not None else flint.fmpq(0) for c in cols])
            t = target[i]
            rhs.append(t(*pt) if t is not None else flint.fmpq(0))
    part, _ = _rref_solve(rows, rhs)
    if part is None:
        return None
    zero = ctx.from_dict({})
    for i in range(N):
        e = sum((c * cols[u][i] for u, c in enumerate(part) if c != 0 and cols[u][i] is not None), zero)
        if not vanishes_on_sphere(e - (target[i] if target[i] is not None else zero), n):
            return None
    return part
