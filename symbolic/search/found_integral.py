r"""The integral found by the exact search beyond the known ones (row S6:first-integrals).

For odd $n$ let $v(M) \in \mathbb{R}^n$ be the Pfaffian vector of $M \in \mathfrak{so}(n)$,
$v_i = (-1)^{i+1}\,\mathrm{Pf}(M_{\hat\imath\hat\imath})$ (so $Mv = 0$ and $\mathrm{adj}(M) = vv^T$;
for $n = 3$, $v$ is $-\hat m$), $x = \gamma_n$ and $\Delta = (2+a)(2+b) - abx^2$ (eq:Delta). Then

.. math::
    F = \frac{\langle v,\ (2+a)E_n + b\,x\,\gamma\rangle^2}{\Delta}

is a first integral of the axisymmetric sphere (eq:axisymm, eq:motion-general), of $M$-degree
$n - 1$. The search found it for $n = 5$ at $M$-degree 4, $\gamma$-degree 4, denominator $\Delta^1$
(reconstructed over $\mathbb{Q}$ from four primes at $a = -1/3$, $b = 3/2$); its closed form was
read off the reconstructed kernel (an ansatz in $v_n^2$, $x v_n\langle v,\gamma\rangle$,
$\langle v,\gamma\rangle^2$, $x^2\langle v,\gamma\rangle^2$) and is proved here for symbolic $a, b$.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.symbolic.algebra import unvec

__all__ = ["pfaffian", "pfaffian_vector", "denominator", "new_integral", "new_integral_text", "prove_symbolic",
           "prove_at_points", "varies_in_M", "hodge_square", "new_integral_6", "new_integral_6_text",
           "general_integral", "expand_polynomial", "in_ring"]


def pfaffian(A: sp.Matrix):
    r"""$\mathrm{Pf}(A)$ of an even-dimensional skew matrix (expansion along the first row)."""
    m = A.shape[0]
    if m == 0:
        return sp.Integer(1)
    if m % 2:
        return sp.Integer(0)
    out = sp.Integer(0)
    for j in range(1, m):
        if A[0, j] == 0:
            continue
        keep = [i for i in range(m) if i not in (0, j)]
        out += (-1) ** (j + 1) * A[0, j] * pfaffian(A.extract(keep, keep))
    return out


def pfaffian_vector(M: sp.Matrix) -> sp.Matrix:
    r"""$v_i = (-1)^{i+1}\mathrm{Pf}(M_{\hat\imath\hat\imath})$ (1-based $i$), odd $n$."""
    n = M.shape[0]
    if n % 2 == 0:
        raise ValueError("the Pfaffian vector needs odd n")
    return sp.Matrix([(-1) ** i * pfaffian(M.extract([t for t in range(n) if t != i],
                                                     [t for t in range(n) if t != i]))
                      for i in range(n)])


def denominator(gamma: sp.Matrix, a, b) -> sp.Expr:
    r"""$\Delta = (2+a)(2+b) - abx^2$, $x = \gamma_n$ (eq:Delta): the denominator of $F$, $G$, $G_n$."""
    x = gamma[len(gamma) - 1]
    return (2 + a) * (2 + b) - a * b * x**2


def new_integral(M: sp.Matrix, gamma: sp.Matrix, a, b) -> tuple[sp.Expr, sp.Expr]:
    r"""(numerator, $\Delta$) of $F$ (module docstring); odd $n \ge 3$."""
    n = M.shape[0]
    v = pfaffian_vector(M)
    x = gamma[n - 1]
    e = sp.zeros(n, 1)
    e[n - 1] = 1
    u = (2 + a) * e + b * x * gamma
    return expand_polynomial((v.T * u)[0, 0] ** 2), denominator(gamma, a, b)


def hodge_square(M: sp.Matrix) -> sp.Matrix:
    r"""$W = \star(M\wedge M)/8 \in \mathfrak{so}(6)$ for $M \in \mathfrak{so}(6)$:
    $W_{ij} = \frac18\sum \varepsilon_{ijklmn} M_{kl}M_{mn}$ (quadratic in $M$, equivariant)."""
    n = M.shape[0]
    if n != 6:
        raise ValueError("hodge_square is the n = 6 object")
    _R, (Mr,) = in_ring(M)
    return sp.Matrix([[w.as_expr() for w in row] for row in _hodge_square(Mr)])


def _hodge_square(M: list) -> list:
    """:func:`hodge_square` on the rows ``M`` of a 6 x 6 matrix of ring elements."""
    n = 6
    W = [[M[0][0] * 0 for _ in range(n)] for _ in range(n)]
    for (i, j), terms in _hodge_terms():
        W[i][j] = sum((s * M[k][l] * M[m][o] for s, (k, l, m, o) in terms), W[i][j]) / 8
    return W


def _hodge_terms() -> list:
    r"""$[((i, j), [(\varepsilon_{ijklmn}, (k, l, m, n))])]$ over the permutations of the complement of
    $\{i, j\}$: the sum of :func:`hodge_square` (720 terms; formed on each call)."""
    import itertools

    def sign(t):
        s = 1
        for i in range(len(t)):
            for j in range(i + 1, len(t)):
                if t[i] > t[j]:
                    s = -s
        return s

    out = []
    for i in range(6):
        for j in range(6):
            if i != j:
                rest = [t for t in range(6) if t not in (i, j)]
                out.append(((i, j), [(sign((i, j) + q), q) for q in itertools.permutations(rest)]))
    return out


def new_integral_6(M: sp.Matrix, gamma: sp.Matrix, a, b) -> tuple[sp.Expr, sp.Expr]:
    r"""(numerator, $\Delta$) of the integral the search found for $n = 6$ at $M$-degree 4 over
    $\Delta$ (read off an exact ansatz over $\mathbb{Q}(a, b)$), with $W$ of :func:`hodge_square`,
    $p = WE_6$, $q = W\gamma$:
    $G = \big(2a(a+2)\|p\|^2 + 4abx\langle p, q\rangle + 2b(b+2)\|q\|^2 + ab(a+b+4)\langle p,
    \gamma\rangle^2\big)/\Delta$. Computed in the polynomial ring of the inputs' symbols
    (:func:`in_ring`)."""
    _R, (Mr, g, A_, B_) = in_ring(M, gamma, a, b)
    W = _hodge_square(Mr)
    x = g[5]
    p = [W[i][5] for i in range(6)]
    q = [sum((W[i][j] * g[j] for j in range(6)), W[0][0] * 0) for i in range(6)]

    def dot(u, w):
        return sum((ui * wi for ui, wi in zip(u, w)), W[0][0] * 0)

    num = (2 * A_ * (A_ + 2) * dot(p, p) + 4 * A_ * B_ * x * dot(p, q) + 2 * B_ * (B_ + 2) * dot(q, q)
           + A_ * B_ * (A_ + B_ + 4) * dot(g, p) ** 2)
    return num.as_expr(), (2 + a) * (2 + b) - a * b * gamma[5]**2


def general_integral(M: sp.Matrix, gamma: sp.Matrix, a, b) -> tuple[sp.Expr, sp.Expr]:
    r"""(numerator, $\Delta$) of the family found by the search, for every $n \ge 5$: with the
    4-form $\omega = \tfrac12 M\wedge M$ ($\omega_{ijkl} = M_{ij}M_{kl} - M_{ik}M_{jl} + M_{il}M_{jk}$),
    $e = E_n$, $x = \gamma_n$ and $\|\cdot\|$ the sum of squares over increasing index sets,
    $G_n = \big(2a(a+2)\|\omega\wedge e\|^2 + 4abx\langle\omega\wedge e, \omega\wedge\gamma\rangle
    + 2b(b+2)\|\omega\wedge\gamma\|^2 + ab(a+b+4)\|\omega\wedge e\wedge\gamma\|^2\big)/\Delta$.
    $n = 6$: :func:`new_integral_6`; $n = 5$: $a(2+a)^{-1}$ times $F$'s numerator plus a known
    integral; $n = 4$: $0$. Guessed from $n = 5, 6$, checked at exact points (row S6:first-integrals).
    Computed in the polynomial ring of the inputs' symbols (:func:`in_ring`)."""
    import itertools

    n = M.shape[0]
    _R, (Mr, g, A_, B_) = in_ring(M, gamma, a, b)

    def om(S):
        i, j, k, l = S
        return Mr[i][j] * Mr[k][l] - Mr[i][k] * Mr[j][l] + Mr[i][l] * Mr[j][k]

    def wedge(form, deg, vec):
        return {S: sum((-1) ** (deg - t) * form[S[:t] + S[t + 1:]] * vec[S[t]]
                       for t in range(deg + 1))
                for S in itertools.combinations(range(n), deg + 1)}

    w = {S: om(S) for S in itertools.combinations(range(n), 4)}
    e = [0] * (n - 1) + [1]
    we, wg = wedge(w, 4, e), wedge(w, 4, g)
    weg = wedge(we, 5, g)
    x = g[n - 1]

    def dot(A, B):
        return sum(A[S] * B[S] for S in A)

    num = (2 * A_ * (A_ + 2) * dot(we, we) + 4 * A_ * B_ * x * dot(we, wg)
           + 2 * B_ * (B_ + 2) * dot(wg, wg) + A_ * B_ * (A_ + B_ + 4) * dot(weg, weg))
    return num.as_expr(), (2 + a) * (2 + b) - a * b * gamma[n - 1]**2


def new_integral_6_text() -> str:
    """G (n = 6) as text SymPy parses, in M_<i><j>, gamma_<i>, a, b."""
    from chaplygin_nd.symbolic.search.reconstruction import real_symbols

    Ms, gs = real_symbols(6)
    a, b = sp.symbols("a b")
    num, den = new_integral_6(unvec(Ms, 6), sp.Matrix(gs), a, b)
    return f"({sp.sstr(num)})/({sp.sstr(den)})"


def new_integral_text(n: int) -> str:
    """F as text SymPy parses, in M_<i><j> (i < j), gamma_<i> (1-based), a, b."""
    from chaplygin_nd.symbolic.search.reconstruction import real_symbols

    Ms, gs = real_symbols(n)
    a, b = sp.symbols("a b")
    # the square is written, not expanded: expanding it (as new_integral does) cost a third of
    # the row S6:first-integrals at n = 7, for a numerator the text never used
    den = denominator(sp.Matrix(gs), a, b)
    v = pfaffian_vector(unvec(Ms, n))
    inner = sum(v[i] * ((2 + a) * (1 if i == n - 1 else 0) + b * gs[-1] * gs[i]) for i in range(n))
    return f"({sp.sstr(expand_polynomial(inner))})**2/({sp.sstr(den)})"


def prove_symbolic(n: int, a=None, b=None, builder=None):
    r"""Exact proof of $X(F) = 0$ with both engines (symbolic/exact/identity.py), for symbolic $a, b$ by
    default: $\Delta X(P) - P X(\Delta) \equiv 0$ modulo the sphere (search.reconstruction)."""
    from chaplygin_nd.symbolic.search.reconstruction import prove_integral, real_symbols
    from chaplygin_nd.symbolic.search.sampled_field import Model

    a = sp.Symbol("a") if a is None else a
    b = sp.Symbol("b") if b is None else b
    Ms, gs = real_symbols(n)
    num, _ = (builder or new_integral)(unvec(Ms, n), sp.Matrix(gs), a, b)
    model = Model(n, (), sp.Integer(1), "axisymmetric", sp.Integer(0))
    return prove_integral(num, model, 1, a=a, b=b)


def prove_at_points(n: int, count: int = 2, seed: int | None = None, builder=None):
    r"""$X(F) = 0$ at seeded exact rational points of $P$ with random $a \in [-1, 1]$, $b > 0$
    (symbolic/exact/identity.py ``zero_at_points``, both engines where they apply): $X(F)$ from the
    exact $\Omega = L_\gamma^{-1}M$ (a linear solve of eq:M-O) and the exact directional
    derivatives $\frac{d}{d\varepsilon}$ of $F$ along $(\dot M, \dot\gamma)$; odd $n$."""
    from chaplygin_nd.symbolic import model as mdl
    from chaplygin_nd.symbolic.algebra import commutator
    from chaplygin_nd.symbolic.exact import points
    from chaplygin_nd.symbolic.exact.identity import zero_at_points

    eps = sp.Symbol("eps")

    def sample(rng):
        par = points.axisymmetric_parameters(rng)
        return {"M": points.skew_matrix(rng, n), "gamma": points.sphere_point(rng, n), **par}

    def residual(pt):
        M, g, a, b = pt["M"], pt["gamma"], pt["a"], pt["b"]
        J = sp.diag(*([1] * (n - 1) + [1 + a]))
        Om = mdl.angular_velocity(M, g, J, b)
        Md, gd = commutator(M, Om), -Om * g
        num, den = (builder or new_integral)(M + eps * Md, g + eps * gd, a, b)
        F = sp.Poly(sp.expand(num), eps)
        D = sp.Poly(sp.expand(den), eps)
        f0, f1 = F.coeff_monomial(1), F.coeff_monomial(eps)
        d0, d1 = D.coeff_monomial(1), D.coeff_monomial(eps)
        return sp.Rational(f1 * d0 - f0 * d1)    # the derivative of num/den times den^2

    return zero_at_points(residual, sample, count=count, seed=seed,
                          label=f"S6:first-integrals n={n}")


def varies_in_M(n: int, builder, seed: int) -> tuple[bool, str]:
    r"""Whether the integral of ``builder`` (numerator $P$, denominator a power of $\Delta$, which
    depends on $\gamma$ alone) is **not constant**: $\frac{d}{d\varepsilon}P(M + \varepsilon N,
    \gamma)|_0 \ne 0$ at a seeded exact rational point with a random skew $N$ and random
    $a, b$. An exact non-zero rational is a witness. Without it, $X(F) = 0$ says nothing: the
    zero function passes it (row S6:first-integrals)."""
    from chaplygin_nd.symbolic.exact import points

    eps = sp.Symbol("eps")
    rng = points.generator(seed, f"S6:first-integrals varies n={n}", 0)
    par = points.axisymmetric_parameters(rng)
    M, N = points.skew_matrix(rng, n), points.skew_matrix(rng, n)
    gamma = points.sphere_point(rng, n)
    num, _den = builder(M + eps * N, gamma, par["a"], par["b"])
    slope = sp.Poly(sp.expand(num), eps).coeff_monomial(eps)
    verdict = "non-zero, so the integral is not constant" if slope != 0 else "zero"
    return slope != 0, (f"dP/d eps = {slope} at a seeded rational point (seed {seed}, a = "
                        f"{par['a']}, b = {par['b']}): {verdict}")


def expand_polynomial(expr) -> sp.Expr:
    r"""The expanded form of a polynomial expression (the value of ``sp.expand``), computed by
    ring arithmetic in $\mathbb{Q}[\text{its free symbols}]$ (``PolyRing.from_expr`` walks the
    tree once and multiplies out in the ring, then ``as_expr``): the same polynomial, the same
    canonical expression, without SymPy's term-by-term expansion of products of sums, which
    was most of the time of the builders above. Domain: polynomials with rational
    coefficients; anything else (a negative power, a float, a function) is expanded by
    ``sp.expand`` as before."""
    expr = sp.sympify(expr)
    symbols = tuple(sorted(expr.free_symbols, key=sp.default_sort_key))
    if not symbols:
        return sp.expand(expr)
    try:
        return _ring(symbols).from_expr(expr).as_expr()
    except (ValueError, sp.polys.polyerrors.CoercionFailed):
        return sp.expand(expr)


def in_ring(*objects):
    r"""$(R, \text{images})$: $R = \mathbb{Q}[\text{the free symbols of } objects]$ and each
    object (a matrix as a list of rows, a vector as a list, a scalar) with its entries in $R$.
    Domain: polynomial entries with rational coefficients (``ValueError`` otherwise)."""
    exprs = [sp.sympify(o) if not isinstance(o, sp.MatrixBase) else o for o in objects]
    free = set().union(*(e.free_symbols for e in exprs))
    symbols = tuple(sorted(free, key=sp.default_sort_key))
    R = _ring(symbols)
    out = []
    for e in exprs:
        if isinstance(e, sp.MatrixBase) and e.cols == 1:
            out.append([R.from_expr(v) for v in e])
        elif isinstance(e, sp.MatrixBase):
            out.append([[R.from_expr(v) for v in e.row(i)] for i in range(e.rows)])
        else:
            out.append(R.from_expr(e))
    return R, out


def _ring(symbols: tuple):
    r"""$\mathbb{Q}[\text{symbols}]$, a new ``PolyRing`` (a fraction of a millisecond once SymPy has seen the symbols)."""
    from sympy.polys.rings import ring

    return ring(symbols, sp.QQ)[0]
