r"""The hypotheses of the Euler–Jacobi theorem for the reduced $n = 5$ sphere, computed on the quotient
(row S6:euler-jacobi-n5).

The quotient $P/SO(4)$ is, on its regular part, an open subset of the 8-dimensional variety
$Z = \{R_1 = R_2 = 0\} \subset \mathbb{R}^{10}$ in the invariants $r = (x, A_\pm, B, G, E_\pm, S_{uu}, S_{uq}, S_{qq})$ of
S6:reduced-n5, with the reduced field $X = N/D$, $D = 2(2+a+b)\Delta(x)$ (:mod:`symbolic.reduction.reduced_n5`).

**Invariant measure on $Z$** (derived here, not assumed). $X$ preserves the ideal of the relations:
$D\,X(R_1) = C_{11}R_1$, $D\,X(R_2) = C_{21}R_1 + C_{22}R_2$ (cofactors by exact division). For a density
$\rho$ on $\mathbb{R}^{10}$ the Leray residue $\omega = \rho\,dr/(dR_1\wedge dR_2)$ on the regular part of $Z$ satisfies
$L_X\omega = \big(\operatorname{div}(\rho X)/\rho - (C_{11} + C_{22})/D\big)\,\omega$ on $Z$ (write $\rho\,dr = dR_1\wedge dR_2\wedge\tilde\omega$
and use $L_X dR_i = d(XR_i)$), so $\omega$ is invariant iff $\operatorname{div}(\rho X) = \rho\,(C_{11}+C_{22})/D$ on $Z$. The ansatz
$\rho = \Delta^\alpha$ turns this into $P_0 + \alpha P_1 = 0$ with
$P_0 = \Delta\sum_i\partial_iN_i - N_x\Delta' - \Delta(C_{11} + C_{22})$, $P_1 = N_x\Delta'$; :func:`measure_exponent` solves it
and the identity is then checked exactly. In a chart $(r \setminus \{y, y'\})$ of $Z$ the density is
$\Delta^\alpha/\lvert\partial(R_1, R_2)/\partial(y, y')\rvert$: the fibre factor is what a restriction of $\Delta^\alpha$ alone would miss
(the $n = 4$ erratum S5:red-measure).

**Integrals on $Z$.** Each of the six ($p$'s four non-constant coefficients, $H$, and $F$ of
S6:sixth-integral-n5) $f = P/Q$ has $Q\,X(P) - P\,X(Q) \in (R_1, R_2)$: exact division with zero
remainder, then the identity $D(Q\,X(P) - P\,X(Q)) = q_1R_1 + q_2R_2$ is checked by both engines.

**Positivity.** $\det(\lambda - L_\gamma) = (\lambda-2)^3(\lambda-2-a-b)\big(\lambda^2 - (4+a+b)\lambda + \Delta(x)\big)^3$ on $S^4$
(:func:`charpoly_residual`, at $\gamma \in \operatorname{span}\{E_4, E_5\}$ by $SO(4)$-conjugation); $\Delta$ is affine in $x^2 \in [0, 1]$ with end values $(2+a)(2+b)$ and $2(2+a+b)$.
"""

from __future__ import annotations

from functools import cache
from typing import Any

import sympy as sp
from chaplygin_nd.symbolic import model
from chaplygin_nd.symbolic.family import sixth_integral as si
from chaplygin_nd.symbolic.reduction import invariants_n5 as ri5
from chaplygin_nd.symbolic.reduction import reduced_n5 as r5

__all__ = ["coordinates", "field", "relations", "relation_cofactors", "measure_polynomials",
           "measure_exponent", "integral_fractions", "integral_memberships", "charpoly_residual",
           "quotient_point", "jacobian_at", "POSITIVITY_FORMS", "positivity_cells",
           "quadratic_reflection_residual", "generator_bounds", "equilibrium_equations",
           "equilibrium_kernel_residuals"]


def coordinates() -> dict:
    """Name -> generator of :data:`symbolic.reduction.invariants_n5.INV_RING` for the ten reduced coordinates."""
    g = ri5.INV_RING.gens
    return {n: g[2 + i] for i, n in enumerate(r5.COORDS)}


def _Delta():
    a, b, x = ri5.INV_RING.gens[:3]
    return (2 + a) * (2 + b) - a * b * x**2


def field() -> tuple[dict, Any]:
    r"""$(N, D)$: the numerators of the reduced field (S6:reduced-n5) and $D = 2(2+a+b)\Delta$."""
    a, b = ri5.INV_RING.gens[:2]
    return r5.field_numerators(), 2 * (2 + a + b) * _Delta()


def _X(f, N) -> Any:
    """$D\\,X(f)$ for a polynomial ``f`` of :data:`INV_RING`."""
    c = coordinates()
    return sum((f.diff(c[n]) * N[n] for n in r5.COORDS), ri5.INV_RING(0))


@cache
def relations() -> tuple:
    """$R_1, R_2$ (S6:reduced-n5, $s = 1 - x^2$) as elements of :data:`INV_RING`."""
    return tuple(ri5.INV_RING(r) for r in r5.relations_on_P())


@cache
def relation_cofactors() -> dict:
    r"""$C_{11}, C_{21}, C_{22}$ with $D\,X(R_1) = C_{11}R_1$, $D\,X(R_2) = C_{21}R_1 + C_{22}R_2$ (exact division;
    raises if a remainder is not zero: then the relations would not be invariant)."""
    N, _ = field()
    R1, R2 = relations()
    (c11, c12), rem1 = _X(R1, N).div([R1, R2])
    (c22, c21), rem2 = _X(R2, N).div([R2, R1])
    if rem1 or rem2 or c12:
        raise ArithmeticError("X does not preserve the ideal (R1, R2) in triangular form")
    return {"C11": c11, "C21": c21, "C22": c22}


def measure_polynomials() -> tuple:
    r"""$(P_0, P_1)$ of the module docstring: $\operatorname{div}(\Delta^\alpha X) - \Delta^\alpha\operatorname{tr}C/D = 0$ iff $P_0 + \alpha P_1 = 0$."""
    N, _ = field()
    c = coordinates()
    Dl = _Delta()
    dD = Dl.diff(c["x"])
    C = relation_cofactors()
    div = sum((N[n].diff(c[n]) for n in r5.COORDS), ri5.INV_RING(0))
    return Dl * div - N["x"] * dD - Dl * (C["C11"] + C["C22"]), N["x"] * dD


def measure_exponent() -> sp.Rational:
    r"""The $\alpha$ with $P_0 + \alpha P_1 = 0$, read off one coefficient (the identity is checked by the row)."""
    P0, P1 = measure_polynomials()
    mon, c1 = next(iter(P1.terms()))
    return -sp.Rational(str(dict(P0.terms()).get(mon, 0))) / sp.Rational(str(c1))


def integral_fractions() -> dict:
    r"""The six integrals on $Z$ as (numerator, denominator) in :data:`INV_RING`: the four
    coefficients of $p$ and $2DH$ of S6:reduced-n5, and $\Delta F$ of S6:sixth-integral-n5."""
    num = r5._integral_numerators()
    _, D = field()
    out = {n: (num[n], ri5.INV_RING(1)) for n in r5.INTEGRAL_NAMES[:4]}
    out["H"] = (num["H"], 2 * D)
    out["F"] = (si.numerator_in_invariants(), _Delta())
    return out


def integral_memberships() -> dict:
    r"""For each integral $f = P/Q$: $T = Q\,DX(P) - P\,DX(Q)$ and its cofactors $(q_1, q_2)$ with
    $T = q_1R_1 + q_2R_2$ (exact division; the remainder is returned too, zero when $f$ is conserved on $Z$)."""
    N, _ = field()
    R1, R2 = relations()
    out = {}
    for name, (P, Q) in integral_fractions().items():
        T = Q * _X(P, N) - P * _X(Q, N)
        if T == 0:   # conserved on all of R^10
            q1 = q2 = rem = ri5.INV_RING(0)
        else:
            (q1, q2), rem = T.div([R1, R2])
        out[name] = {"T": T, "q1": q1, "q2": q2, "remainder": rem}
    return out


def charpoly_residual():
    r"""$\det(\lambda - L_\gamma) - (\lambda-2)^3(\lambda-2-a-b)(\lambda^2-(4+a+b)\lambda+\Delta(x))^3$ for $n = 5$, symbolic
    $a, b$, at $\gamma = (0, 0, 0, s, x)$ (every $\gamma \in S^4$ is $h\gamma'$ of such a $\gamma'$ with $h \in SO(4)$, and
    $L_{h\gamma} = hL_{\gamma'}h^{-1}$ has the same spectrum: eq:action); zero modulo $s^2 + x^2 = 1$.
    Returns (residual, lambda, (s, x))."""
    from sympy.polys.matrices import DomainMatrix

    a, b, x = r5.a, r5.b, r5.x
    lam, s = sp.symbols("lambda s")
    gam = sp.Matrix([0, 0, 0, s, x])
    L = model.L_matrix(gam, sp.diag(1, 1, 1, 1, 1 + a), b)
    dm = DomainMatrix.from_Matrix(lam * sp.eye(10) - L)
    Dl = (2 + a) * (2 + b) - a * b * x**2
    target = (lam - 2) ** 3 * (lam - 2 - a - b) * (lam**2 - (4 + a + b) * lam + Dl) ** 3
    # the difference is formed in the determinant's polynomial ring (the expanded residual, without
    # expanding expressions)
    return dm.domain.to_sympy(dm.det() - dm.domain.from_sympy(target)), lam, (s, x)


def quotient_point(M, gamma) -> dict:
    """The reduced coordinates (name -> value) of a point ``(M, gamma)`` of $P$ (S6:reduced-n5)."""
    Ml = [[M[i, j] for j in range(5)] for i in range(5)]
    vals = ri5.generators_from(Ml, list(gamma[:4]))
    return {"x": gamma[4], **{n: vals[n] for n in r5.COORDS[1:]}}


def jacobian_at(point: dict, a, b) -> sp.Matrix:
    r"""The $8\times10$ Jacobian of $(f_1, \dots, f_6, R_1, R_2)$ in the reduced coordinates at ``point``,
    exactly (rank 8 there: the six are independent on $Z$)."""
    c = coordinates()
    at = [a, b] + [point[n] for n in r5.COORDS]

    def ev(p):
        return sp.Rational(str(p(*at))) if p else sp.Integer(0)
    rows = []
    for P, Q in integral_fractions().values():
        q0, p0 = ev(Q), ev(P)
        rows.append([(ev(P.diff(c[n])) * q0 - p0 * ev(Q.diff(c[n]))) / q0**2 for n in r5.COORDS])
    for Rr in relations():
        rows.append([ev(Rr.diff(c[n])) for n in r5.COORDS])
    return sp.Matrix(rows)


#: The linear forms whose signs decide positivity: $2 + a$, $2 + b$, $2 + a + b$, $4 + a + b$
#: (coefficients of $a$, $b$ and the constant).
POSITIVITY_FORMS = ((1, 0, 2), (0, 1, 2), (1, 1, 2), (1, 1, 4))


def _cad_samples(forms, num):
    r"""Sample points, one in every cell of the arrangement of the lines $\alpha a + \beta b + c = 0$ (a
    cylindrical decomposition: the $a$-coordinates of the vertical lines and of the pairwise
    intersections, the points between them and one beyond each end; over each, the $b$-roots of the
    other lines, the points between and beyond). Exact (``num`` makes the numbers)."""
    def around(vals):
        vals = sorted(set(vals))
        if not vals:
            return [num(0)]
        out = [vals[0] - 1, vals[-1] + 1] + vals
        out += [(u + v) / 2 for u, v in zip(vals, vals[1:], strict=False)]
        return out
    acrit = [num(-c) / al for al, be, c in forms if be == 0]
    for i, (a1, b1, c1) in enumerate(forms):
        for a2, b2, c2 in forms[i + 1:]:
            det = a1 * b2 - a2 * b1
            if det:
                acrit.append(num(-c1 * b2 + c2 * b1) / det)
    pts = []
    for av in around(acrit):
        broots = [(-(al * av) - c) / be for al, be, c in forms if be != 0]
        pts += [(av, bv) for bv in around(broots)]
    return pts


def positivity_cells(engine: str = "sympy", stated=None) -> dict:
    r"""Exact certificate that, with the eigenvalues of $L_\gamma$ on $S^4$ read off :func:`charpoly_residual`
    (2, $2+a+b$, the roots of $\lambda^2 - (4+a+b)\lambda + \Delta(x)$, real as $L_\gamma$ is symmetric), the set where
    all are positive for every $x \in [-1, 1]$, $\Phi = \{2+a+b > 0,\ 4+a+b > 0,\ \Delta(0) = (2+a)(2+b) > 0,\
    \Delta(1) = 2(2+a+b) > 0\}$ ($\Delta$ is affine in $x^2$; two real roots are positive iff their sum and product
    are), equals $\Psi = \{a > -2,\ b > -2,\ a + b > -2\}$: both are decided by the signs of
    :data:`POSITIVITY_FORMS`, and they agree on a sample point of every cell of their arrangement
    (:func:`_cad_samples`). Returns the number of samples and those where they differ. ``stated``: another
    condition on $(2+a, 2+b, 2+a+b)$ to compare instead of $\Psi$ (the tests' controls)."""
    if engine == "flint":
        import flint
        num = flint.fmpq
    else:
        num = sp.Rational
    bad, pts = [], _cad_samples(POSITIVITY_FORMS, num)
    for av, bv in pts:
        l1, l2, l3, l4 = (al * av + be * bv + c for al, be, c in POSITIVITY_FORMS)
        phi = l3 > 0 and l4 > 0 and l1 * l2 > 0 and 2 * l3 > 0
        psi = (l1 > 0 and l2 > 0 and l3 > 0) if stated is None else stated(l1, l2, l3)
        if phi != psi:
            bad.append((str(av), str(bv)))
    return {"samples": len(pts), "differ": bad}


def quadratic_reflection_residual():
    r"""$q(\Lambda - \lambda) - q(\lambda)$ for $q = \lambda^2 - \Lambda\lambda + \Delta(x)$, $\Lambda = 4 + a + b$: zero, so the two roots of $q$
    are $r$ and $\Lambda - r$; when both are positive each is $< \Lambda$, and with $2 < \Lambda$, $2 + a + b < \Lambda$ every
    eigenvalue of $L_\gamma$ is at most $\Lambda$: $H = \tfrac12\langle M, L_\gamma^{-1}M\rangle \ge \lVert M\rVert^2/(2\Lambda)$, so
    $\{H \le h\} \subset \{\lVert M\rVert^2 \le 2\Lambda h\}\times S^4$ is compact (H is proper)."""
    a, b, x = r5.a, r5.b, r5.x
    lam = sp.Symbol("lambda")
    Lam = 4 + a + b
    Dl = (2 + a) * (2 + b) - a * b * x**2

    def qf(t):
        return t**2 - Lam * t + Dl
    return sp.expand(qf(Lam - lam) - qf(lam))


def generator_bounds(engine: str = "sympy") -> dict:
    r"""For each reduced coordinate $g \ne x$ (the generators of :mod:`symbolic.reduction.invariants_n5` as polynomials in
    the entries $M_{ij}$, $i < j$, and $q = (\gamma_1..\gamma_4)$): its degree $d$ in $M$ (it must be homogeneous in $M$) and
    $C = \sum\lvert\text{coefficients}\rvert$. Since $\lvert M_{ij}\rvert \le \lVert M\rVert$ ($\lVert M\rVert^2 = \sum_{i<j}M_{ij}^2$, the norm of
    :func:`quadratic_reflection_residual`) and $\lvert q_k\rvert \le 1$ on $S^4$, every monomial is at most $\lVert M\rVert^d$ in absolute
    value, so $\lvert g\rvert \le C\lVert M\rVert^d$ on $P$; with $\lVert M\rVert^2 \le 2(4+a+b)h$ on $\{H \le h\}$ the image of
    $\{H \le h\}$ lies in the box $\lvert g\rvert \le C(2(4+a+b)h)^{d/2}$, $\lvert x\rvert \le 1$ of $\mathbb{R}^{10}$. ``engine``: ``sympy``
    (the generators in SymPy's sparse ring over QQ) or ``flint`` (rebuilt from the same formulas, :func:`generators_from`,
    over FLINT's ``fmpq_mpoly``). Returns name -> (d, C) with C a ``str`` of the exact rational; raises
    ``ArithmeticError`` if a generator is not homogeneous in $M$."""
    from chaplygin_nd.symbolic.reduction import invariants_n5 as inv

    n_m = 10                                      # the M entries come first, then q1..q4
    if engine == "flint":
        import flint
        ctx = flint.fmpq_mpoly_ctx.get(tuple(f"v{i}" for i in range(n_m + 4)), "lex")
        v = ctx.gens()
        Mm = [[ctx.from_dict({}) for _ in range(5)] for _ in range(5)]
        k = 0
        for i in range(5):
            for j in range(i + 1, 5):
                Mm[i][j], Mm[j][i] = v[k], -v[k]
                k += 1
        polys = inv.generators_from(Mm, list(v[n_m:]))
        terms = {name: [(m[:n_m], c) for m, c in zip(p.monoms(), p.coeffs(), strict=True)]
                 for name, p in polys.items()}
    else:
        polys = inv.generator_polys()
        first = 3                                 # RING's gens: a, b, x, M_ij, q
        terms = {name: [(m[first:first + n_m], c) for m, c in p.terms()] for name, p in polys.items()}
    out = {}
    for name in r5.COORDS[1:]:
        degs = {sum(m) for m, _ in terms[name]}
        if len(degs) != 1:
            raise ArithmeticError(f"{name} is not homogeneous in M: degrees {sorted(degs)}")
        total = sum((abs(c) for _, c in terms[name]), 0 * terms[name][0][1])
        out[name] = (degs.pop(), str(total))
    return out


def equilibrium_equations() -> dict:
    r"""The reduced field at $G = S_{uq} = 0$ (where every equilibrium lies for $b > -2$, :mod:`proofs.s6_euler_jacobi_n5`):
    ``vanishing``, the names of the components $N_i$ that are zero there as polynomials, and ``P`` $= (P_G, P_{uq})$ with
    $N_G = (2+a+b)P_G$, $N_{S_{uq}} = (2+a+b)P_{uq}$ at $G = S_{uq} = 0$ (exact division; raises if $2 + a + b$ does not divide).
    So for $a + b \ne -2$ the equilibria on $Z$ are $\{G = S_{uq} = P_G = P_{uq} = R_1 = R_2 = 0\}$; ``a_free`` says
    whether $P_G, P_{uq}, R_1, R_2$ at $G = S_{uq} = 0$ are free of $a$ (then so is that set)."""
    N, _ = field()
    c = coordinates()
    R = ri5.INV_RING
    a, b = R.gens[:2]

    def at0(p):
        return p.compose([(c["G"], R(0)), (c["Suq"], R(0))])
    vanishing = [n for n in r5.COORDS if at0(N[n]) == 0]
    P = []
    for n in ("G", "Suq"):
        q_, rem = at0(N[n]).div([2 + a + b])
        if rem != 0:
            raise ArithmeticError(f"2 + a + b does not divide N_{n} at G = Suq = 0")
        P.append(q_[0])
    rels = [at0(r) for r in relations()]
    a_free = all(p.degree(a) <= 0 for p in P + rels)
    return {"vanishing": vanishing, "P": tuple(P), "a_free": a_free, "at0": at0}


def _to_flint(polys: dict) -> dict:
    """Elements of :data:`INV_RING` as FLINT ``fmpq_mpoly`` in the same variables (same names, same order)."""
    import flint

    names = tuple(str(v) for v in ri5.INV_RING.symbols)
    ctx = flint.fmpq_mpoly_ctx.get(names, "lex")
    return {k: ctx.from_dict({m: flint.fmpq(int(c.numerator), int(c.denominator)) for m, c in p.terms()})
            for k, p in polys.items()}


def equilibrium_kernel_residuals(engine: str = "sympy") -> dict:
    r"""Exact certificate that at every equilibrium the six integrals are dependent on $Z$.

    Let $w = \partial_GN$ (the $G$-derivative of the field's numerators). For each row $\phi$ of the Jacobian of
    $(f_1..f_6, R_1, R_2)$ — for $f = P/Q$ the row $Q\,dP - P\,dQ$ — the polynomial $\phi\cdot w$ is written in the ideal of
    $(N_1, \dots, N_{10}, R_1, R_2, \partial_GR_1, \partial_GR_2)$ with explicit cofactors, obtained by differentiating in $G$ the identity
    $Q\,DX(P) - P\,DX(Q) = q_1R_1 + q_2R_2$ (:func:`integral_memberships`; $DX(R_1) = C_{11}R_1$, $DX(R_2) = C_{21}R_1 + C_{22}R_2$ for
    the relations): ``residuals`` (name -> $\phi\cdot w$ minus that combination) must all be 0. ``columns``: the $G$ and $S_{uq}$
    columns of every row, and $\partial_GR_1$, $\partial_GR_2$, at $G = S_{uq} = 0$ (must be 0). ``wx``: $\partial_GN_x - 2\Delta$ (must be 0).
    ``engine``: ``sympy`` (SymPy's sparse ring over QQ) or ``flint`` (the inputs $N$, $P$, $Q$, $q_i$, $R_i$, $C$ converted to
    FLINT ``fmpq_mpoly`` and every derivative, product and substitution done there).

    Consequence: at an equilibrium $p$ ($N(p) = 0$, $p \in Z$, with $G = S_{uq} = 0$ there) the $8\times10$ Jacobian has in its kernel
    $e_G$, $e_{S_{uq}}$ (zero columns) and $w(p)$, whose $x$-component is $2\Delta(p) \ne 0$: rank $\le 7 < 8$."""
    N, _ = field()
    R1, R2 = relations()
    C = relation_cofactors()
    mem = integral_memberships()
    fr = integral_fractions()
    inputs = {("N", n): N[n] for n in r5.COORDS} | {"R1": R1, "R2": R2, "Delta": _Delta()} | \
        {("C", k): v for k, v in C.items()} | {("P", k): P for k, (P, _) in fr.items()} | \
        {("Q", k): Q for k, (_, Q) in fr.items()} | \
        {("q", k, i): mem[k][f"q{i}"] for k in fr for i in (1, 2)}
    names = r5.COORDS
    if engine == "flint":
        v = _to_flint(inputs)

        def d(p, n):
            return p.derivative(n)

        def at0(p):
            return p.subs({"G": 0, "Suq": 0})
    else:
        v = inputs
        c = coordinates()

        def d(p, n):
            return p.diff(c[n])
        at0 = equilibrium_equations()["at0"]
    zero = v["R1"] * 0
    Nv = {n: v[("N", n)] for n in names}
    R1, R2 = v["R1"], v["R2"]
    w = {n: d(Nv[n], "G") for n in names}
    dGR = (d(R1, "G"), d(R2, "G"))

    def dot(grad):
        return sum((grad[n] * w[n] for n in names), zero)

    def along_N(f):
        return sum((d(f, n) * Nv[n] for n in names), zero)
    residuals, columns = {}, []
    for name in fr:
        P, Q, q1, q2 = v[("P", name)], v[("Q", name)], v[("q", name, 1)], v[("q", name, 2)]
        row = {n: Q * d(P, n) - P * d(Q, n) for n in names}
        combo = (d(q1, "G") * R1 + q1 * dGR[0] + d(q2, "G") * R2 + q2 * dGR[1]
                 - (d(Q, "G") * along_N(P) + Q * along_N(d(P, "G")) - d(P, "G") * along_N(Q) - P * along_N(d(Q, "G"))))
        residuals[name] = dot(row) - combo
        columns += [at0(row["G"]), at0(row["Suq"])]
    C11, C21, C22 = v[("C", "C11")], v[("C", "C21")], v[("C", "C22")]
    dcof = {"R1": d(C11, "G") * R1 + C11 * dGR[0],                     # d/dG of C11 R1
            "R2": d(C21, "G") * R1 + C21 * dGR[0] + d(C22, "G") * R2 + C22 * dGR[1]}
    for name, Rr in (("R1", R1), ("R2", R2)):
        row = {n: d(Rr, n) for n in names}
        residuals[name] = dot(row) - (dcof[name] - along_N(d(Rr, "G")))
        columns += [at0(row["G"]), at0(row["Suq"])]
    columns += [at0(p) for p in dGR]
    return {"residuals": residuals, "columns": columns, "wx": w["x"] - 2 * v["Delta"], "w": w}
