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

1. **an invariant measure**: the density $\Delta^{-3/2}/\lvert J_{yy'}\rvert$ in every chart $z = r \setminus \{y, y'\}$ of $Z$ with
   $J_{yy'} = \det\partial(R_1, R_2)/\partial(y, y') \ne 0$ (44 pairs; they cover the regular part of $Z$), each invariant by
   Liouville's criterion computed in that chart (:mod:`symbolic.family.quotient_measure_n5`); they are one density
   (computed: on every overlap $\lvert\det\partial z'/\partial z\rvert = \lvert J_{c'}/J_c\rvert$, 946 pairs of charts). It is positive where $\Delta > 0$ (item 3).
   Its relation to the measure $\Delta^{-3/2}dM\,d\gamma$ of $P$ (P:Measure) is computed, not used: the push-forward with
   its fibre-volume factor is the chart density times one constant at seeded points. The exponent $-3/2$ is
   also derived from the ansatz $\Delta^\alpha$ and the invariance of the ideal $(R_1, R_2)$, not assumed;
2. **six first integrals** on $Z$ (the four non-constant coefficients of $p(\lambda, \sigma)$, $H$, and $F$ of
   S6:sixth-integral-n5), independent at a seeded point of $Z$ (so on an open dense set);
3. **compact level sets**: $L_\gamma$ is positive definite for every $\gamma \in S^4$ exactly when $a > -2$, $b > -2$,
   $a + b > -2$; every eigenvalue is at most $4 + a + b$, so $\lVert M\rVert^2 \le 2(4+a+b)h$ on $\{H \le h\}$, and every
   reduced coordinate $g \ne x$ satisfies $\lvert g\rvert \le C_g\lVert M\rVert^{d_g}$ with exact $C_g$, $d_g$ (sum of the absolute values of
   its coefficients, its degree in $M$): the image of $\{H \le h\}$ lies in an exact box of $\mathbb{R}^{10}$, so a level set
   of the integrals in $\pi(P)$ is bounded; it is closed (below), hence compact (Heine–Borel);

hence, by the theorem, every compact connected regular level set of the six integrals that carries
no equilibrium is a 2-torus with quasi-periodic motion after a change of time.
**Equilibria**: at every equilibrium of the reduced field $G = S_{uq} = 0$ (for $b > -2$; exact, from
$\dot x = G/(2+a+b)$ and the $\dot S_{qq}$, $\dot E_+$ components at $G = 0$). At $G = S_{uq} = 0$ eight of the ten
components of the field vanish identically and the other two are $(2+a+b)P_G$, $(2+a+b)P_{uq}$: the equilibria on $Z$
are exactly $\{G = S_{uq} = P_G = P_{uq} = R_1 = R_2 = 0\}$, a set free of $a$ (exact). **Every equilibrium is critical**
(computed, :func:`critical_equilibria_part`): with $w = \partial_GN$, each row $\phi$ of the Jacobian of $(f_1..f_6, R_1, R_2)$
has $\phi\cdot w$ in the ideal of $(N, R_1, R_2, \partial_GR_1, \partial_GR_2)$ — explicit cofactors, from the $G$-derivative of the
conservation identities, symbolic $a, b$, formed in SymPy's ring and recomputed from the inputs in FLINT — so
$Jw = 0$ at an equilibrium; there $G = S_{uq} = 0$, where the $G$ and $S_{uq}$ columns of $J$ and
$\partial_GR_i$ vanish, and $w_x = 2\Delta \ne 0$: the kernel of the $8\times10$ matrix $J$ has dimension $\ge 3$, rank $\le 7 < 8$. So
the proviso "no equilibrium" is automatic on regular level sets, at every equilibrium on $Z$ (not only on the
principal stratum). The two kinds of equilibria of :mod:`symbolic.family.equilibria_n5` ($\Omega E_5 = 0$, and points
fixed by some $\eta \ne 0$) are computed at exact points as well, with the rank of $dc$ on the normal-form family; the
argument through them is no longer needed.

**Computed here** (SymPy and FLINT, exact): $D\,X(R_1) = C_{11}R_1$, $D\,X(R_2) = C_{21}R_1 + C_{22}R_2$;
$\alpha = -3/2$ from the ansatz and the identity $\operatorname{div}(\Delta^\alpha X) = \Delta^\alpha(C_{11}+C_{22})/D$ on $\mathbb{R}^{10}$
(with the control that without the cofactor term no $\Delta^\alpha$ works); Liouville in each of the 44 charts: the
divergence of $\Delta^{-3/2}X/J_{yy'}$ along $Z$, cleared of denominators, is $q_1R_1 + q_2R_2$ (symbolic $a, b$; the cofactors from
division by $R_1$, $R_2$ and their reduced S-polynomial $g_3 = uR_1 + vR_2$, every identity checked); the
push-forward: $\det\operatorname{Gram}(\text{orbit})\,J^2/\det(dz\,\Pi\,dz^T)$ is one constant at seeded points of $P$ (control:
without $J$ it varies); $Q\,X(P) - P\,X(Q) = 0$ for each integral $P/Q$ (on all of $\mathbb{R}^{10}$); the rank 8 of
$(df_1..df_6, dR_1, dR_2)$ at the image of a seeded rational point; $\dim P/SO(4) = 8$ (orbit rank 6);
$\det(\lambda - L_\gamma) = (\lambda-2)^3(\lambda-2-a-b)(\lambda^2 - (4+a+b)\lambda + \Delta)^3$ on $S^4$, and that "all eigenvalues
positive for every $x \in [-1, 1]$" ($2+a+b$, $4+a+b$, $\Delta(0) = (2+a)(2+b)$, $\Delta(1) = 2(2+a+b)$ positive) is the
range $a, b > -2$, $a + b > -2$ (exact on one sample of every cell of the arrangement of those linear forms,
:func:`symbolic.family.euler_jacobi_n5.positivity_cells`); every eigenvalue is at most $4 + a + b$ (the
quadratic is symmetric under $\lambda \mapsto 4 + a + b - \lambda$), so $H \ge \lVert M\rVert^2/(2(4+a+b))$; the box
$\lvert g\rvert \le C_g\lVert M\rVert^{d_g}$ (:func:`symbolic.family.euler_jacobi_n5.generator_bounds`, both engines, with the control that
$d_g - 1$ fails); the equilibrium identities, the equilibrium set on $Z$ and the kernel vector $w$ of the Jacobian at
every equilibrium; exact points of both kinds of equilibria
(:mod:`symbolic.family.equilibria_n5`: $\Omega E_5 = 0$, and $\eta \ne 0$ fixing $p$), each with the reduced field zero, on the
principal stratum and of rank $< 8$. **Argued** (one part, :data:`ARGUED`): the theorem (the citation), applied on the
principal stratum, with named definition-level facts: Heine–Borel; the level set $\pi(P) \cap \{f = c\}$ is closed, as a
limit of $\pi(p_k)$ with $p_k$ in the closed bounded $\{H \le h\}$ is $\pi$ of a limit point of the $p_k$ (Bolzano–Weierstrass).
That the chart densities agree on overlaps is computed (:func:`symbolic.family.quotient_measure_n5.chart_transition_residuals`).
Note: $Z(\mathbb{R})$ is larger than $\pi(P)$ (e.g. $A_+ = -1$, every other coordinate $0$, lies on $Z$; $A_+ = \lVert k_+\rVert^2 \ge 0$
on $\pi(P)$), so the level sets are taken in $\pi(P)$, where the box bounds them, not in all of $Z$.

**Uses** S6:reduced-n5, S6:sixth-integral-n5, S6:open-reduced-n5, eq:Delta, eq:action.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.ledger.registry import Part, Verdict, claim
from chaplygin_nd.symbolic import algebra, model
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
    cells = {eng: ej.positivity_cells(eng) for eng in ("sympy", "flint")}
    same = all(not c["differ"] for c in cells.values())
    # control: the cell check tells ranges apart (the physical range a > -1, b > 0 is smaller)
    control = any(not (av > -1 and bv > 0) and av > -2 and bv > -2 and av + bv > -2
                  for av, bv in ej._cad_samples(ej.POSITIVITY_FORMS, sp.Rational))
    return _part(f"L_gamma positive definite on S^4 iff {RANGE}; H proper", [
        ("char. polynomial of L_gamma", rational_identity(res, sphere=sph, label="EJ5 charpoly")),
        ("Delta(0) = (2+a)(2+b), Delta(1) = 2(2+a+b)", rational_identity(list(ends), label="EJ5 ends")),
        (f"all eigenvalues positive for every x iff {RANGE}", Check(
            same and control, f"the two conditions agree on a sample of each of the "
            f"{cells['sympy']['samples']} cells of the arrangement of 2+a, 2+b, 2+a+b, 4+a+b "
            f"(SymPy QQ and FLINT fmpq); control: a sample cell lies in the range but not in a > -1, b > 0")),
        ("eigenvalues <= 4 + a + b, so H >= |M|^2/(2(4+a+b))", rational_identity(
            [ej.quadratic_reflection_residual()], label="EJ5 reflection"))])


def compactness_part() -> Part:
    r"""The image of $\{H \le h\}$ in $\mathbb{R}^{10}$ is bounded, by an exact box: $\lvert g\rvert \le C_g\lVert M\rVert^{d_g}$ for every
    reduced coordinate $g \ne x$ (:func:`symbolic.family.euler_jacobi_n5.generator_bounds`, SymPy and FLINT), with
    $\lVert M\rVert^2 \le 2(4+a+b)h$ there (:func:`positivity_part`). Checked at seeded points of $P$, with the control that
    one degree less fails at a scaled point (the degrees are needed)."""
    bounds = {eng: ej.generator_bounds(eng) for eng in ("sympy", "flint")}
    agree = bounds["sympy"] == bounds["flint"]
    held, sharp = [], False
    for t in range(2):
        rng = points.generator(ledger_seed(), "S6:euler-jacobi-n5 box", t)
        M, g = points.skew_matrix(rng, 5), points.sphere_point(rng, 5)
        for scale in (1, 1000):
            Ms = M * scale
            vals = ej.quotient_point(Ms, g)
            norm2 = sum(Ms[i, j] ** 2 for i in range(5) for j in range(i + 1, 5))
            for name, (d, C) in bounds["sympy"].items():
                C = sp.Rational(C)
                held.append(vals[name] ** 2 <= C**2 * norm2**d)
                sharp |= vals[name] ** 2 > C**2 * norm2 ** (d - 1)
    box = ", ".join(f"|{n}| <= {C} R^{d}" for n, (d, C) in bounds["sympy"].items())
    return _part("the image of {H <= h} lies in an exact box of R^10 (bounded)", [
        ("|g| <= C_g ||M||^d_g for every reduced coordinate", Check(
            agree and all(held) and sharp,
            f"with R^2 = 2(4+a+b)h and |x| <= 1: {box} (degree in M and sum of |coefficients|, SymPy ring and FLINT "
            f"fmpq_mpoly agree: {agree}); holds at {len(held)} seeded evaluations; control: with one degree less the "
            f"bound fails at a scaled point: {sharp}"))])


def measure_chart_part() -> Part:
    r"""The density $\Delta^{-3/2}/J$ in the chart $r \setminus \{S_{qq}, A_+\}$ of $Z$: invariant (Liouville in the chart,
    exact identity modulo $R_1, R_2$), and equal to the push-forward of $\Delta^{-3/2}dM\,d\gamma$ with its
    fibre-volume factor (a constant ratio at seeded points of $P$, both engines)."""
    from chaplygin_nd.symbolic.family import quotient_measure_n5 as qm

    T, (q1, q2), rem = qm.chart_divergence()
    R1, R2 = ej.relations()
    liouville = rational_identity([T - q1 * R1 - q2 * R2], label="EJ5 chart divergence")
    # every chart (y, y') with J_yy' != 0: together they cover the regular part of Z
    g3, (u, v) = qm.relation_s_polynomial()
    certs = {out: qm.chart_divergence(out) for out in qm.charts()}
    every = rational_identity([g3 - u * R1 - v * R2] + [Tc - c1 * R1 - c2 * R2 for Tc, (c1, c2), _ in certs.values()],
                              label="EJ5 every chart")
    every_rem = [out for out, (_, _, r) in certs.items() if r != 0]
    transitions = qm.chart_transition_residuals()
    one_density = rational_identity(transitions, label="EJ5 chart transitions")
    ratios, naive = {"sympy": [], "flint": []}, []
    for t in range(2):
        rng = points.generator(ledger_seed(), "S6:euler-jacobi-n5 push-forward", t)
        M, g = points.skew_matrix(rng, 5), points.sphere_point(rng, 5)
        for eng in ratios:
            ratios[eng].append(qm.pushforward_ratio(M, g, eng))
        J, _ = qm.chart_jacobian()
        Jv = qm.ev_inv(J, ej.quotient_point(M, g), sp.Rational, sp.Integer(0), sp.Integer(1))
        naive.append(ratios["sympy"][-1] / Jv**2)   # without the chart factor J: must vary
    same = all(len({str(v) for v in vals}) == 1 for vals in ratios.values()) and \
        str(ratios["sympy"][0]) == str(ratios["flint"][0])
    varies = len(set(naive)) > 1
    return _part("the chart density is invariant and is the push-forward of the measure of P", [
        ("Liouville in the chart: T = q1 R1 + q2 R2, remainder 0", liouville),
        ("remainder zero", Check(rem == 0, "multivariate division of T by (R1, R2, g3) leaves 0")),
        (f"Liouville in every chart: T_yy' = q1 R1 + q2 R2 for the {len(certs)} pairs (y, y') with J_yy' != 0, "
         "and g3 = u R1 + v R2", every),
        ("every chart: remainder zero, the charts cover the regular part of Z", Check(
            not every_rem and len(certs) == 44,
            f"division by (R1, R2, g3) leaves 0 in all {len(certs)} charts (not zero: {every_rem}); the 45th pair "
            "(A+, A-) has J = 0 identically, and where dR1 ^ dR2 != 0 one of the J_yy' (its coefficients) is not 0")),
        (f"the chart densities are one density: |det dz'/dz| = |J_c'/J_c| for the {len(transitions)} pairs of "
         "charts (polynomial identities, Cramer's rule on the implicit functions)", one_density),
        ("push-forward = Delta^(-3/2)/J up to a constant", Check(
            same and varies, f"det Gram(orbit) J^2 / det(dz Pi dz^T) = {ratios['sympy'][0]} at 2 seeded points "
            f"(SymPy QQ and FLINT fmpq); control: without J the ratio varies ({len(set(naive))} values)"))])


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
    eq = ej.equilibrium_equations()
    at0, (PG, Puq) = eq["at0"], eq["P"]
    others = [n for n in ej.r5.COORDS if n not in ("G", "Suq")]
    checks += [
        ("at G = S_uq = 0 the other eight components vanish; N_G, N_uq = (2+a+b) P_G, (2+a+b) P_uq", rational_identity(
            [at0(N[n]) for n in others] + [at0(N["G"]) - (2 + a + b) * PG, at0(N["Suq"]) - (2 + a + b) * Puq],
            label="EJ5 equilibrium set")),
        ("the equilibrium set on Z is {G = S_uq = P_G = P_uq = R_1 = R_2 = 0}, free of a", Check(
            eq["vanishing"] == others and eq["a_free"],
            f"components zero at G = S_uq = 0: {eq['vanishing']}; P_G ({len(PG.terms())} terms), P_uq "
            f"({len(Puq.terms())} terms), R_1, R_2 there free of a: {eq['a_free']} (for a + b != -2)"))]
    return _part("at every equilibrium G = S_uq = 0 (b > -2), and the equilibrium set on Z", checks)


def _omega_e5_point(label: str, t: int, a, b) -> tuple:
    r"""A seeded exact equilibrium of the first kind, $\Omega E_5 = 0$: $\gamma$ on $S^4$, $\Omega$ a random skew
    matrix on the first four axes, $M = L_\gamma\Omega$ (eq:M-O-axi-symm, $n = 5$)."""
    rng = points.generator(ledger_seed(), label, t)
    g = points.sphere_point(rng, 5)
    Om = sp.zeros(5, 5)
    Om[:4, :4] = points.skew_matrix(rng, 4)
    L = model.L_matrix(g, sp.diag(1, 1, 1, 1, 1 + a), b)
    return algebra.unvec(list(L * sp.Matrix(algebra.vec(Om))), 5), g


def critical_equilibria_part(a, b) -> Part:
    r"""Every equilibrium on $Z$ lies in the critical set of the six integrals, computed
    (:func:`symbolic.family.euler_jacobi_n5.equilibrium_kernel_residuals`): with $w = \partial_GN$, each row of the Jacobian of
    $(f_1..f_6, R_1, R_2)$ applied to $w$ lies in the ideal of $(N, R_1, R_2, \partial_GR_1, \partial_GR_2)$ (explicit cofactors, symbolic
    $a, b$); at $G = S_{uq} = 0$ (every equilibrium, :func:`equilibria_part`) the $G$ and $S_{uq}$ columns and $\partial_GR_i$ vanish and
    $w_x = 2\Delta \ne 0$, so the kernel has dimension $\ge 3$ and the rank is $\le 7$. Evaluated at exact equilibria
    ($\Omega E_5 = 0$), with the control that $J w \ne 0$ at a point that is not one."""

    k = ej.equilibrium_kernel_residuals()
    ident = rational_identity(list(k["residuals"].values()), label="EJ5 kernel vector")
    cols = rational_identity(k["columns"] + [k["wx"]], label="EJ5 zero columns")
    kf = ej.equilibrium_kernel_residuals("flint")      # recomputed from the inputs in FLINT fmpq_mpoly
    flint_zero = all(r == 0 for r in kf["residuals"].values()) and all(c == 0 for c in kf["columns"]) \
        and kf["wx"] == 0
    R = ri5.INV_RING

    def Jw(pt):
        at = [a, b] + [pt[n] for n in ej.r5.COORDS]
        J = ej.jacobian_at(pt, a, b)
        wv = sp.Matrix([sp.Rational(str(k["w"][n](*at))) if k["w"][n] != R(0) else 0 for n in ej.r5.COORDS])
        return J * wv, J
    at_eq = []
    for t in range(2):
        M, g = _omega_e5_point("S6:euler-jacobi-n5 kernel", t, a, b)
        v, J = Jw(ej.quotient_point(M, g))
        at_eq.append(v.is_zero_matrix and J.rank() < 8)
    rng = points.generator(ledger_seed(), "S6:euler-jacobi-n5 kernel control")
    ctrl, _ = Jw(ej.quotient_point(points.skew_matrix(rng, 5), points.sphere_point(rng, 5)))
    return _part("every equilibrium on Z lies in the critical set (computed)", [
        ("J w in the ideal of (N, R1, R2, d_G R1, d_G R2), w = d_G N (explicit cofactors)", ident),
        ("G and S_uq columns and d_G R_i zero at G = S_uq = 0; w_x = 2 Delta", cols),
        ("the same residuals recomputed in FLINT", Check(
            flint_zero, f"N, P, Q, q_i, R_i and the cofactors C converted to fmpq_mpoly; every derivative, product and "
            f"substitution redone there: residuals, columns and w_x - 2 Delta all zero: {flint_zero}")),
        ("at exact equilibria J w = 0 and rank < 8; control", Check(
            all(at_eq) and not ctrl.is_zero_matrix,
            f"at 2 seeded points with Omega E_5 = 0 (a = {a}, b = {b}): J w = 0 and rank < 8: {at_eq}; control: "
            f"J w != 0 at a seeded point that is not an equilibrium: {not ctrl.is_zero_matrix}"))])


def relative_equilibria_part(a, b) -> Part:
    r"""Both kinds of equilibria of :mod:`symbolic.family.equilibria_n5`, at seeded exact points: the reduced
    field is zero there, the $SO(4)$-orbit has dimension 6 (principal stratum) and $(df_1..df_6, dR_1, dR_2)$ has rank
    $< 8$ (both engines). First kind ($\Omega E_5 = 0$): the $SO(5)$-orbit has dimension 10 and $dc_i$, $dH$ vanish on
    $Y_{e_m\wedge E_5}$. Second kind ($\eta \ne 0$ fixes $p$): $Y_\eta(p) = 0$ and the $SO(5)$-orbit has dimension $< 10$."""
    from chaplygin_nd.symbolic.exact import flint_engine
    from chaplygin_nd.symbolic.family import equilibria_n5 as eqm
    from chaplygin_nd.symbolic.family import independence_all_n as ia

    field = ej.r5.field()

    def at_point(M, g):
        pt = ej.quotient_point(M, g)
        at = {ej.r5.SYMBOLS[n]: v for n, v in pt.items()} | {ej.r5.a: a, ej.r5.b: b}
        zero = all(sp.cancel(field[n].xreplace(at)) == 0 for n in ej.r5.COORDS)
        J = ej.jacobian_at(pt, a, b)
        with flint_engine.use_engine("flint"):
            ranks = (J.rank(), flint_engine.rank(J))
        orb = {eng: eqm.orbit_checks(M, g, a, b, eng) for eng in ("sympy", "flint")}
        return zero, ranks, orb

    first, second = [], []
    for t in range(2):
        M, g = _omega_e5_point("S6:euler-jacobi-n5 relative equilibria", t, a, b)
        zero, ranks, orb = at_point(M, g)
        first.append(zero and max(ranks) < 8 and all(o["orbit_rank"] == 10 and o["so4_rank"] == 6
                                                     and not any(o["values"]) for o in orb.values()))
    tries = 0
    while len(second) < 2 and tries < 10:
        rng = points.generator(ledger_seed(), "S6:euler-jacobi-n5 fixed equilibria", tries)
        tries += 1
        drawn = eqm.eta_point(rng, a, b)
        if drawn is None:
            continue
        M, g, eta = drawn
        zero, ranks, orb = at_point(M, g)
        crank = {eng: ia.c_rank(M, g, eng) for eng in ("sympy", "flint")}
        second.append(zero and max(ranks) < 8 and eqm.fixed_by(M, g, eta)
                      and not (eta * sp.Matrix([0, 0, 0, 0, 1])).is_zero_matrix
                      and max(crank.values()) <= 3
                      and all(o["orbit_rank"] < 10 and o["so4_rank"] == 6 for o in orb.values()))
    # every point fixed by some eta != 0: the SO(5)-invariant c have rank <= 3 (symbolic, and FLINT at points)
    import itertools

    import flint

    G, syms = eqm.isotropy_family_matrix()
    cols = [j for j in range(G.cols) if any(G[i, j] != 0 for i in range(G.rows))]
    minors = [sp.expand(G.extract(list(range(4)), list(c)).det(method="berkowitz"))
              for c in itertools.combinations(cols, 4)]
    vanish = all(m == 0 for m in minors)            # every 4x4 minor vanishes identically: rank <= 3
    r_pts = []
    for t in range(3):
        vals = points.rationals(points.generator(ledger_seed(), "S6:euler-jacobi-n5 isotropy", t), 4)
        Gv = G.xreplace(dict(zip(syms, vals, strict=True)))
        r_pts.append(flint.fmpq_mat(4, 14, [flint.fmpq(int(v.p), int(v.q)) for v in Gv]).rank())
    rng = points.generator(ledger_seed(), "S6:euler-jacobi-n5 isotropy control")
    ctrl = ia.c_rank(points.skew_matrix(rng, 5), points.sphere_point(rng, 5), "flint")   # generic: 4
    return _part("equilibria of both kinds lie in the critical set", [
        ("fixed by eta != 0: rank dc <= 3", Check(
            vanish and max(r_pts) <= 3 and ctrl == 4,
            f"rank of dc on the family (mu e_12 + M', e_5) that every point with a fixed eta != 0 is conjugate to: "
            f"<= 3 over QQ(mu, m1, m2, m3) (SymPy: each of the {len(minors)} 4x4 minors expands to 0: {vanish}), {r_pts} at 3 seeded points (FLINT); control: {ctrl} at a "
            f"generic point")),
        ("Omega E = 0", Check(len(first) == 2 and all(first),
                              f"at 2 seeded points: reduced field zero, SO(4)-orbit 6, SO(5)-orbit 10, dc_i and dH "
                              f"zero on Y_(e_m ^ E_5), rank < 8 (SymPy and FLINT), a = {a}, b = {b}: {first}")),
        ("eta != 0 fixes p", Check(len(second) == 2 and all(second),
                                   f"at 2 seeded points (eta of rank 2): Y_eta(p) = 0, eta E_5 != 0, reduced field "
                                   f"zero, SO(4)-orbit 6, SO(5)-orbit < 10, the SO(5)-invariant coefficients of p of rank <= 3 "
                                   f"(as on the family), rank < 8 (SymPy and FLINT): {second}"))])


ARGUED = ("the Euler-Jacobi theorem (as the paper cites it at line 884: Arnold-Kozlov-Neishtadt, "
          "Mathematical Aspects of Classical and Celestial Mechanics; Borisov-Mamaev 2008), applied on the "
          "principal stratum of P/SO(4) (charted by the regular part of Z), with definition-level facts named, "
          "not computed: Heine-Borel (the level set pi(P) & {f = c} is bounded by the computed box, and closed: a "
          "limit of pi(p_k), p_k in the closed bounded {H <= h}, is pi of a limit point of the p_k, "
          "Bolzano-Weierstrass). Everything else (the measure in every chart and its agreement between charts, "
          "the integrals, compactness bounds, every equilibrium critical) is computed")


@claim("S6:euler-jacobi-n5", uses=("S6:reduced-n5", "S6:sixth-integral-n5", "S6:open-reduced-n5",
                                   "eq:Delta", "eq:action"),
       adds=(SECTION, "for n = 5 and a > -2, b > -2, a + b > -2 the reduced system on P/SO(4) "
                      "(dimension 8) has the invariant measure Delta^{-3/2} dr/(dR_1 ^ dR_2) (derived on "
                      "the quotient, invariant in each of its 44 charts), six independent integrals and compact level sets: by Euler-Jacobi "
                      "its compact connected regular level sets without equilibria are 2-tori with "
                      "quasi-periodic motion after a change of time"))
def s6_euler_jacobi_n5() -> Verdict:
    rng = points.generator(ledger_seed(), "S6:euler-jacobi-n5 parameters")
    a, b = points.rational(rng, -1, 1, nonzero=True), points.rational(rng, 1, 3)
    measure, alpha = measure_part()
    parts = [quotient_part(), measure, measure_chart_part(), integrals_part(a, b), positivity_part(),
             compactness_part(), equilibria_part(), critical_equilibria_part(a, b),
             relative_equilibria_part(a, b),
             Verdict.by_argument(ARGUED).as_part("the theorem (cited) and how it applies")]
    notes = (f"invariant density on the quotient: Delta^({alpha}) / |d(R_1, R_2)/d(y, y')| in the chart "
             "r minus {y, y'} (invariant in all 44 charts); L_gamma > 0 on S^4 iff " + RANGE + "; the image of {H <= h} in "
             "an exact box; at every equilibrium G = S_uq = 0; "
             "every equilibrium lies in the critical set (computed: J d_G N = 0 there, with the G and S_uq columns zero "
             "and (d_G N)_x = 2 Delta != 0, so rank <= 7), so regular level sets carry none")
    return Verdict.of_parts(parts, n_values=(5,), notes=notes, method=(
        "exact identities on the quotient R^10 (SymPy and FLINT): invariant ideal of the relations, the "
        "measure exponent derived from an ansatz, the integrals, the characteristic polynomial of L_gamma; "
        "exact ranks; the theorem cited"))
