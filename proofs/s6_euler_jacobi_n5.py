r"""Beyond the paper: Euler–Jacobi for the reduced $n = 5$ sphere, each hypothesis computed on the
quotient (row S6:euler-jacobi-n5).

**Theorem (cited).** Euler–Jacobi, as the paper cites it for $n = 4$ (line 884: Arnold–Kozlov–Neishtadt,
*Mathematical Aspects of Classical and Celestial Mechanics*; Borisov–Mamaev 2008): a smooth field $X$ on an
$m$-dimensional manifold with an invariant measure (smooth positive density) and $m - 2$ first integrals
independent on a compact connected level set $N$ that carries no equilibrium of $X$: $N$ is a 2-torus
and, after a change of time, the motion on it is quasi-periodic (in suitable angles, $\dot\varphi = \omega/\Phi(\varphi)$).

**Claim.** For $n = 5$ and $(a, b)$ with $a > -2$, $b > -2$, $a + b > -2$ (containing the physical range
$a \ge -1$, $b > 0$): on the regular part of $Z = P/SO(4) \subset \mathbb{R}^{10}$ (dimension $m = 8$, cut out
by $R_1 = R_2 = 0$, S6:reduced-n5) the reduced field has

1. **an invariant measure**: the Leray residue $\Delta^{-3/2}\,dr/(dR_1\wedge dR_2)$ — in a chart
   $r \setminus \{y, y'\}$ the density $\Delta^{-3/2}/\lvert\partial(R_1, R_2)/\partial(y, y')\rvert$; the exponent $-3/2$ is
   derived from the ansatz $\Delta^\alpha$ and the invariance of the ideal $(R_1, R_2)$, not assumed;
2. **six first integrals** on $Z$ (the four non-constant coefficients of $p(\lambda, \sigma)$, $H$, and $F$ of
   S6:sixth-integral-n5), independent at a seeded point of $Z$ (so on an open dense set);
3. **compact level sets**: $L_\gamma$ is positive definite for every $\gamma \in S^4$ exactly when $a > -2$, $b > -2$,
   $a + b > -2$, so $\{H \le h\} \subset P$ is compact and so are its images in $Z$;

hence, by the theorem, every compact connected regular level set of the six integrals that carries
no equilibrium is a 2-torus with quasi-periodic motion after a change of time.
**Equilibria**: at every equilibrium of the reduced field $G = S_{uq} = 0$ (for $b > -2$; exact, from
$\dot x = G/(2+a+b)$ and the $\dot S_{qq}$, $\dot E_+$ components at $G = 0$); on the family of relative
equilibria with $\Omega E_5 = 0$ (four parameters in the quotient) the six integrals are dependent (exact rank
at seeded points). *Not proved*: that they are dependent at every equilibrium (which would make the
proviso "no equilibrium" automatic on regular level sets).

**Computed here** (SymPy and FLINT, exact): $D\,X(R_1) = C_{11}R_1$, $D\,X(R_2) = C_{21}R_1 + C_{22}R_2$;
$\alpha = -3/2$ from the ansatz and the identity $\operatorname{div}(\Delta^\alpha X) = \Delta^\alpha(C_{11}+C_{22})/D$ on $\mathbb{R}^{10}$
(with the control that without the cofactor term no $\Delta^\alpha$ works); $Q\,X(P) - P\,X(Q) = 0$ for each
integral $P/Q$ (on all of $\mathbb{R}^{10}$); the rank 8 of $(df_1..df_6, dR_1, dR_2)$ at the image of a seeded
rational point; $\dim P/SO(4) = 8$ (orbit rank 6); $\det(\lambda - L_\gamma) = (\lambda-2)^3(\lambda-2-a-b)
(\lambda^2 - (4+a+b)\lambda + \Delta)^3$ on $S^4$ (so the eigenvalues are $2$, $2+a+b$ and the roots of the
quadratic, all positive iff $2 + a + b > 0$, $4 + a + b > 0$ and $\Delta(x) > 0$ on $[-1, 1]$, where $\Delta$
is affine in $x^2$ with end values $(2+a)(2+b)$ and $2(2+a+b)$: iff $a, b > -2$, $a + b > -2$);
the equilibrium identities. **Argued** (one part): the theorem, and the two textbook facts it is
applied through (the Leray residue lemma of :mod:`symbolic.family.euler_jacobi_n5`; a quotient by
the compact $SO(4)$ maps compact sets to compact sets, and $H \ge \lVert M\rVert^2/(2\lambda_{\max})$ on $P$).

**Uses** S6:reduced-n5, S6:sixth-integral-n5, S6:open-reduced-n5, eq:Delta, eq:action.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.ledger.registry import Part, Verdict, claim
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.exact.identity import Check, rational_identity
from chaplygin_nd.symbolic.exact.points import ledger_seed
from chaplygin_nd.symbolic.family import euler_jacobi_n5 as ej
from chaplygin_nd.symbolic.reduction import invariants_n5 as ri5

SECTION = "Conclusions — open problems (beyond the paper)"
RANGE = "a > -2, b > -2, a + b > -2"


def _part(name: str, checks: list[tuple[str, Check]]) -> Part:
    return Verdict.all_of(checks, n_values=(5,)).as_part(name)


def quotient_part() -> Part:
    from chaplygin_nd.proofs.s6_open_reduced_n5 import reduced_dimension_check

    exact = reduced_dimension_check()
    ok = exact["orbit_rank"] == (6, 6) and exact["invariant"]
    return _part("dim P/SO(4) = 8", [("orbit rank 6 of 14", Check(ok, f"orbit ranks {exact['orbit_rank']} "
                                      "(SymPy, DomainMatrix) at a seeded rational point"))])


def measure_part() -> tuple[Part, sp.Rational]:
    N, D = ej.field()
    R1, R2 = ej.relations()
    C = ej.relation_cofactors()
    c = ej.coordinates()

    def X(f):
        return sum((f.diff(c[n]) * N[n] for n in ej.r5.COORDS), ri5.INV_RING(0))
    ideal = [("D X(R1) = C11 R1", rational_identity([X(R1) - C["C11"] * R1], label="EJ5 XR1")),
             ("D X(R2) = C21 R1 + C22 R2", rational_identity([X(R2) - C["C21"] * R1 - C["C22"] * R2],
                                                             label="EJ5 XR2"))]
    alpha = ej.measure_exponent()
    P0, P1 = ej.measure_polynomials()
    q = alpha.q
    div = rational_identity([q * P0 + int(alpha * q) * P1], label="EJ5 measure")
    # control: without the cofactor trace (a density invariant on R^10, restricted naively) no
    # Delta^alpha works: P0 + Delta tr C is not a multiple of P1
    trC = C["C11"] + C["C22"]
    Pn = P0 + ej._Delta() * trC
    mon, c1 = next(iter(P1.terms()))
    beta = -sp.Rational(str(dict(Pn.terms()).get(mon, 0))) / sp.Rational(str(c1))
    naive = Pn * beta.q + int(beta * beta.q) * P1
    control = Check(naive != 0 and trC != 0,
                    f"without the cofactor term the ansatz forces alpha = {beta} and leaves a non-zero "
                    f"residual: the relations' cofactors (the fibre factor) are needed")
    return (_part("invariant measure on the quotient", ideal + [
        (f"div(Delta^alpha X) = Delta^alpha (C11 + C22)/D with alpha = {alpha} (derived)", div),
        ("control", control)]), alpha)


def integrals_part(a, b) -> Part:
    mem = ej.integral_memberships()
    checks = [(f"X({name}) = 0", rational_identity([m["T"] - m["q1"] * ej.relations()[0]
                                                      - m["q2"] * ej.relations()[1]], label=f"EJ5 {name}"))
              for name, m in mem.items()]
    checks.append(("remainders zero", Check(all(m["remainder"] == 0 for m in mem.values()),
                                            "each Q X(P) - P X(Q) lies in (R1, R2)")))
    from chaplygin_nd.symbolic.exact import flint_engine

    rng = points.generator(ledger_seed(), "S6:euler-jacobi-n5")
    M, g = points.skew_matrix(rng, 5), points.sphere_point(rng, 5)
    J = ej.jacobian_at(ej.quotient_point(M, g), a, b)
    r_s = J.rank()
    with flint_engine.use_engine("flint"):
        r_f = flint_engine.rank(J)
    checks.append(("rank 8 of (df_1..df_6, dR_1, dR_2)", Check(r_s == r_f == 8, f"rank {r_s} (SymPy), {r_f} "
                   f"(FLINT) at the image of a seeded rational point, a = {a}, b = {b}")))
    return _part("six independent integrals on the quotient", checks)


def positivity_part() -> Part:
    res, lam, sph = ej.charpoly_residual()
    a, b, x = ej.r5.a, ej.r5.b, ej.r5.x
    Dl = (2 + a) * (2 + b) - a * b * x**2
    ends = sp.expand(Dl.subs(x, 0) - (2 + a) * (2 + b)), sp.expand(Dl.subs(x, 1) - 2 * (2 + a + b))
    return _part(f"L_gamma positive definite on S^4 iff {RANGE}", [
        ("char. polynomial of L_gamma", rational_identity(res, sphere=sph, label="EJ5 charpoly")),
        ("Delta(0) = (2+a)(2+b), Delta(1) = 2(2+a+b)", rational_identity(list(ends), label="EJ5 ends"))])


def equilibria_part() -> Part:
    N, _ = ej.field()
    c = ej.coordinates()
    R = ri5.INV_RING
    a, b, x = R.gens[:3]
    G, Suq = c["G"], c["Suq"]

    def on_G0(p):
        return p.compose(G, R(0))
    checks = [("D x' = 2 G Delta", rational_identity([N["x"] - 2 * G * ej._Delta()], label="EJ5 x'")),
              ("D Sqq' = 2 Suq x (2+a+b)(b x^2 - b - 4) at G = 0", rational_identity(
                  [on_G0(N["Sqq"]) - 2 * Suq * x * (2 + a + b) * (b * x**2 - b - 4)], label="EJ5 Sqq'")),
              ("D Ep' = Suq (2+a+b)(2 b x^2 - b - 2) at G = 0", rational_identity(
                  [on_G0(N["Ep"]) - Suq * (2 + a + b) * (2 * b * x**2 - b - 2)], label="EJ5 Ep'"))]
    return _part("at every equilibrium G = S_uq = 0 (b > -2)", checks)


def relative_equilibria_part(a, b) -> Part:
    r"""At seeded points of the relative equilibria with $\Omega E_5 = 0$ ($\Omega \in \mathfrak{so}(4)$, any $\gamma$,
    $M = L_\gamma\Omega$: then $\dot M = [M, \Omega]$ and $\dot\gamma = -\Omega\gamma$ are the velocity of the $SO(4)$ orbit,
    a 4-parameter family of equilibria of the reduced field): the reduced field vanishes and the
    six integrals have rank < 6 + 2 there, i.e. these equilibria lie in the critical set."""
    from chaplygin_nd.symbolic import algebra, model
    from chaplygin_nd.symbolic.exact import flint_engine

    ranks, zero = [], True
    field = ej.r5.field()
    for t in range(3):
        rng = points.generator(ledger_seed(), "S6:euler-jacobi-n5 relative equilibria", t)
        g = points.sphere_point(rng, 5)
        Om = sp.zeros(5, 5)
        Om[:4, :4] = points.skew_matrix(rng, 4)
        L = model.L_matrix(g, sp.diag(1, 1, 1, 1, 1 + a), b)
        M = algebra.unvec(list(L * sp.Matrix(algebra.vec(Om))), 5)
        pt = ej.quotient_point(M, g)
        at = {ej.r5.SYMBOLS[n]: v for n, v in pt.items()} | {ej.r5.a: a, ej.r5.b: b}
        zero = zero and all(sp.cancel(field[n].xreplace(at)) == 0 for n in ej.r5.COORDS)
        J = ej.jacobian_at(pt, a, b)
        with flint_engine.use_engine("flint"):
            ranks.append((J.rank(), flint_engine.rank(J)))
    return _part("the relative equilibria with Omega E = 0 lie in the critical set", [
        ("reduced field zero, rank < 8", Check(zero and max(max(r) for r in ranks) < 8,
                                             f"at 3 seeded points: reduced field zero {zero}, ranks (SymPy, FLINT) {ranks} "
                                             f"of (df_1..df_6, dR_1, dR_2), a = {a}, b = {b}"))])


ARGUED = ("the Euler-Jacobi theorem (as the paper cites it at line 884: Arnold-Kozlov-Neishtadt, "
          "Mathematical Aspects of Classical and Celestial Mechanics; Borisov-Mamaev 2008), applied through two textbook facts: "
          "the Leray residue rho dr/(dR_1 ^ dR_2) is invariant on {R = 0} iff div(rho X) = rho tr(C)/D there "
          "(L_X dR_i = d(X R_i)); the image of a compact set under the quotient by the compact SO(4) is "
          "compact, and H >= |M|^2/(2 lambda_max(L_gamma)) makes {H <= h} compact when L_gamma > 0")


@claim("S6:euler-jacobi-n5", uses=("S6:reduced-n5", "S6:sixth-integral-n5", "S6:open-reduced-n5",
                                   "eq:Delta", "eq:action"),
       adds=(SECTION, "for n = 5 and a > -2, b > -2, a + b > -2 the reduced system on P/SO(4) "
                      "(dimension 8) has the invariant measure Delta^{-3/2} dr/(dR_1 ^ dR_2) (derived on "
                      "the quotient), six independent integrals and compact level sets: by Euler-Jacobi "
                      "its compact connected regular level sets without equilibria are 2-tori with "
                      "quasi-periodic motion after a change of time"))
def s6_euler_jacobi_n5() -> Verdict:
    rng = points.generator(ledger_seed(), "S6:euler-jacobi-n5 parameters")
    a, b = points.rational(rng, -1, 1, nonzero=True), points.rational(rng, 1, 3)
    measure, alpha = measure_part()
    parts = [quotient_part(), measure, integrals_part(a, b), positivity_part(), equilibria_part(),
             relative_equilibria_part(a, b),
             Verdict.by_argument(ARGUED).as_part("the theorem (cited) and how it applies")]
    notes = (f"invariant density on the quotient: Delta^({alpha}) / |d(R_1, R_2)/d(y, y')| in the chart "
             "r minus {y, y'}; L_gamma > 0 on S^4 iff " + RANGE + "; at every equilibrium G = S_uq = 0; "
             "the relative equilibria with Omega E = 0 (a 4-parameter family) lie in the critical set; "
             "open: that every equilibrium does (so that regular level sets carry none)")
    return Verdict.of_parts(parts, n_values=(5,), notes=notes, method=(
        "exact identities on the quotient R^10 (SymPy and FLINT): invariant ideal of the relations, the "
        "measure exponent derived from an ansatz, the integrals, the characteristic polynomial of L_gamma; "
        "exact ranks; the theorem cited"))
