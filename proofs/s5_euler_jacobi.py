r"""Section 5's Euler–Jacobi argument for $n = 4$ (lines 879–885), each hypothesis computed (row S5:euler-jacobi).

**The paper's argument.** "Considering that the generic dimension of $P/SO(3)$ is 6, and there exist 4
independent integrals and an invariant measure, the Euler–Jacobi Theorem implies that the reduced system is
integrable. In particular, the regular compact level sets of the integrals which have no equilibrium points
are 2-tori where the flow is quasi-periodic after a time reparametrisation."

**The hypotheses, and the rows that compute them.** On the regular part of $\mathcal{R} = \{\delta^2 = \det\Lambda\}
\subset \mathbb{R}^7$ (dimension 6):

* *measure*: the printed "restriction of $\mu_r$" is the `reading` remark of S5:red-measure; its correction, the
  residue $dA\,dB\,dE\,dG\,dF_1\,dx/(2\Delta\lvert\delta\rvert)$ along the first integral $(\delta^2 - \det\Lambda)/\Delta$, is proved
  invariant there (chart divergences, exact) — used here, not repeated;
* *four independent integrals*: S5:red-integrals (conserved, exact rank 5 with $d\Phi$);
* *compact level sets* (computed here): $\det(\lambda - L_\gamma) = (\lambda-2)(\lambda-2-a-b)(\lambda^2 - (4+a+b)\lambda + \Delta(x))^2$
  on $S^3$, so $L_\gamma > 0$ for every $\gamma$ exactly when $a, b > -2$, $a + b > -2$ (the same cell certificate as
  for $n = 5$, :func:`symbolic.family.euler_jacobi_n5.positivity_cells`), every eigenvalue is at most $4 + a + b$
  and $H \ge \lVert M\rVert^2/(2(4+a+b))$ is proper;
* *equilibria in the critical set* (computed here at exact points, argued in general as for $n = 5$,
  :mod:`symbolic.family.equilibria_n5`): $D\dot x = 2\Delta G$, so $G = 0$ at every equilibrium; on the family
  $\Omega E_4 = 0$ ($\xi = 0$) the reduced field vanishes and $(dF_1, dF_2, dF_3, dH, d\Phi)$ has rank $< 5$. In general an
  equilibrium on the principal stratum is a point fixed by some $\eta = \Omega + \xi'$, $\xi' \in \mathfrak{so}(3)$: $\eta = 0$ is
  that family (the collapse identity makes $dH$ vanish on the $SO(4)$ directions $Y_{w\wedge E_4}$, as do the
  $SO(4)$-invariant $F_1, F_2, F_3$), and $\eta \ne 0$ gives a positive-dimensional $SO(4)$-isotropy, where
  the point is conjugate to $(\mu e_1\wedge e_2 + m\,e_3\wedge e_4, E_4)$ (a rank-2 $\eta = \theta v_1\wedge v_2$ fixes $(M, \gamma)$ iff
  $\gamma \perp v_1, v_2$ and $M \in \mathfrak{so}(\Pi)\oplus\mathfrak{so}(\Pi^\perp)$; a rank-4 $\eta$ fixes no $\gamma \ne 0$), where the three
  $SO(4)$-invariant coefficients of $p(\lambda, \sigma)$ have rank $\le 2$ (computed: :func:`isotropy_family_rank`).

**Verdict.** Every hypothesis holds on the range $a, b > -2$, $a + b > -2$ (the physical range inside it); the
one that fails as printed (the measure's restriction) is already the reading remark of S5:red-measure, so no
new correction. **Argued** (one part): the theorem (cited as the paper cites it) and the same standard facts as
for $n = 5$ (compact images, equilibria as fixed points, normal forms).

**Uses** S5:red-integrals, S5:red-measure, eq:red-system, S6:wedge-integrals. $n = 4$.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.ledger.registry import Part, Verdict, claim
from chaplygin_nd.proofs.s5_common import exact, invariants_at
from chaplygin_nd.symbolic import algebra, fourd, model
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.exact.identity import Check, rational_identity
from chaplygin_nd.symbolic.exact.points import ledger_seed
from chaplygin_nd.symbolic.family import euler_jacobi_n5 as ej
from chaplygin_nd.symbolic.reduction import invariants_n4 as ri
from chaplygin_nd.symbolic.reduction import reduced_n4

SECTION = "Section 5 — n = 4"
RANGE = "a > -2, b > -2, a + b > -2"
a, b, x = fourd.a, fourd.b, fourd.x
COORDS = [reduced_n4.SYMBOLS[n] for n in reduced_n4.COORDS]


def charpoly_residual_n4():
    r"""$\det(\lambda - L_\gamma) - (\lambda-2)(\lambda-2-a-b)(\lambda^2 - (4+a+b)\lambda + \Delta)^2$ at $\gamma = (0, 0, s, x)$ ($n = 4$;
    every $\gamma$ is such a point after a rotation fixing $E_4$, which keeps the spectrum); zero modulo
    $s^2 + x^2 = 1$."""
    from sympy.polys.matrices import DomainMatrix

    lam, s = sp.symbols("lambda s")
    L = model.L_matrix(sp.Matrix([0, 0, s, x]), sp.diag(1, 1, 1, 1 + a), b)
    dm = DomainMatrix.from_Matrix(lam * sp.eye(6) - L)
    det = dm.domain.to_sympy(dm.det())
    Dl = (2 + a) * (2 + b) - a * b * x**2
    return sp.expand(det - (lam - 2) * (lam - 2 - a - b) * (lam**2 - (4 + a + b) * lam + Dl) ** 2), (s, x)


def positivity_part() -> Part:
    res, sph = charpoly_residual_n4()
    cells = {eng: ej.positivity_cells(eng) for eng in ("sympy", "flint")}
    return Verdict.all_of([
        ("char. polynomial of L_gamma (n = 4)", rational_identity(res, sphere=sph, label="EJ4 charpoly")),
        (f"all eigenvalues positive for every x iff {RANGE}", Check(
            all(not c["differ"] for c in cells.values()),
            f"agree on a sample of each of the {cells['sympy']['samples']} cells (SymPy QQ and FLINT fmpq)")),
        ("eigenvalues <= 4 + a + b, so H >= |M|^2/(2(4+a+b))",
         rational_identity([ej.quadratic_reflection_residual()], label="EJ4 reflection"))],
        n_values=(4,)).as_part(f"L_gamma positive definite on S^3 iff {RANGE}; H proper")


def equilibria_part() -> Part:
    X = reduced_n4.field_numerators()
    Dl = (2 + a) * (2 + b) - a * b * x**2
    xdot = exact(X["x"].as_expr() - 2 * Dl * ri.G, "EJ4 x'")
    ints = reduced_n4.integrals()
    fs = [ints[n] for n in ("F1", "F2", "F3", "H")] + [ri.delta**2 - ri.det_Lambda().as_expr()]
    field = reduced_n4.field()
    results = []
    for t in range(3):
        rng = points.generator(ledger_seed(), "S5:euler-jacobi relative equilibria", t)
        gamma = points.sphere_point(rng, 4)
        par = points.axisymmetric_parameters(rng)
        eta = points.rationals(rng, 3)
        Om = sp.Matrix(fourd.block(eta, (0, 0, 0)))      # Omega E_4 = 0
        L = model.L_matrix(gamma, sp.diag(1, 1, 1, 1 + par["a"]), par["b"])
        M = algebra.unvec(list(L * sp.Matrix(algebra.vec(Om))), 4)
        kv, uv = fourd.unblock(M.tolist())
        pt = invariants_at({"a": par["a"], "b": par["b"], "k": sp.Matrix(kv), "u": sp.Matrix(uv),
                            "q": gamma[:3, 0], "x": gamma[3]})
        zero = all(sp.cancel(field[n].xreplace(pt)) == 0 for n in reduced_n4.COORDS)
        J = sp.Matrix([[sp.diff(f, c).xreplace(pt) for c in COORDS] for f in fs])
        from chaplygin_nd.symbolic.exact import flint_engine
        with flint_engine.use_engine("flint"):
            ranks = (J.rank(), flint_engine.rank(J))
        results.append((zero, ranks))
    ok = all(z and max(r) < 5 for z, r in results)
    vanish, iso_ranks = isotropy_family_rank()
    from chaplygin_nd.symbolic.family import independence_all_n as ia
    crng = points.generator(ledger_seed(), "S5:euler-jacobi isotropy control")
    ctrl = ia.c_rank(points.skew_matrix(crng, 4), points.sphere_point(crng, 4), "flint")   # generic: 3
    return Verdict.all_of([
        ("D x' = 2 Delta G: G = 0 at every equilibrium", xdot),
        ("Omega E_4 = 0: equilibria in the critical set", Check(
            ok, f"at 3 seeded points (xi = 0, eta and gamma drawn): reduced field zero and rank of "
                f"(dF1, dF2, dF3, dH, dPhi) (SymPy, FLINT) {[r for _, r in results]} < 5")),
        ("fixed by eta != 0: rank dc <= 2", Check(
            vanish and max(iso_ranks) <= 2 and ctrl == 3,
            f"on (mu e_12 + m e_34, E_4), which every point fixed by eta != 0 is conjugate to: every 3x3 minor of dc "
            f"expands to 0 (SymPy): {vanish}; ranks {iso_ranks} at 3 seeded points (FLINT); control: {ctrl} at a "
            f"generic point")),
    ], n_values=(4,)).as_part("equilibria lie in the critical set")


def isotropy_family_rank() -> tuple[bool, list]:
    r"""The three non-constant coefficients $c$ of $p(\lambda, \sigma) = \det(M + \sigma\gamma\gamma^T - \lambda)$ ($\lambda^2$, $1$, $\sigma\lambda$)
    differentiated on $TP$ along $M = \mu\,e_1\wedge e_2 + m\,e_3\wedge e_4$, $\gamma = E_4$: whether every $3\times3$ minor
    expands to zero (SymPy), and the ranks at three seeded points (FLINT)."""
    import itertools

    import flint
    from sympy.polys.matrices import DomainMatrix

    n = 4
    pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]
    Ms = sp.symbols("M12 M13 M14 M23 M24 M34")
    g = sp.symbols("g1:5")
    lam, sig, mu, m = sp.symbols("lambda sigma mu m")
    M = sp.zeros(n, n)
    for (i, j), s_ in zip(pairs, Ms, strict=True):
        M[i, j], M[j, i] = s_, -s_
    dm = DomainMatrix.from_Matrix(M + sig * sp.Matrix(g) * sp.Matrix(g).T - lam * sp.eye(n))
    P = sp.Poly(dm.domain.to_sympy(dm.det()), lam, sig)
    coeffs = [P.coeff_monomial(lam**i * sig**j) for i, j in ((2, 0), (0, 0), (1, 1))]
    family = dict(zip(Ms, (mu, 0, 0, 0, 0, m), strict=True)) | dict(zip(g, (0, 0, 0, 1), strict=True))
    G = sp.Matrix([[sp.expand(sp.diff(c, v).xreplace(family)) for v in (*Ms, *g[:3])] for c in coeffs])
    vanish = all(sp.expand(G.extract([0, 1, 2], list(c)).det(method="berkowitz")) == 0
                 for c in itertools.combinations(range(G.cols), 3))
    ranks = []
    for t in range(3):
        vals = points.rationals(points.generator(ledger_seed(), "S5:euler-jacobi isotropy", t), 2)
        Gv = G.xreplace({mu: vals[0], m: vals[1]})
        ranks.append(flint.fmpq_mat(3, G.cols, [flint.fmpq(int(v.p), int(v.q)) for v in Gv]).rank())
    return vanish, ranks


ARGUED = ("the Euler-Jacobi theorem (as the paper cites it at line 884: Arnold-Kozlov-Neishtadt; "
          "Borisov-Mamaev 2008), applied on the principal stratum of P/SO(3) with the measure of S5:red-measure "
          "(corrected) and the integrals of S5:red-integrals, through the standard facts used for n = 5: a "
          "continuous image of a compact set is compact; equilibria on the principal stratum are the points fixed "
          "by some eta = Omega + xi', xi' in so(3); at eta = 0 the collapse identity (S6:wedge-integrals, k = 1) "
          "makes dH vanish with dF_1, dF_2, dF_3 on the SO(4) directions; a point fixed by eta != 0 is conjugate "
          "(normal forms) to (mu e_12 + m e_34, E_4), where rank <= 2 of the SO(4)-invariant coefficients of p is "
          "computed")


@claim("S5:euler-jacobi", uses=("S5:red-integrals", "S5:red-measure", "eq:red-system", "S6:wedge-integrals"),
       adds=(SECTION, "the hypotheses of the Euler-Jacobi theorem for the reduced n = 4 system (line 884), "
                      "each computed: measure (S5:red-measure, corrected), integrals, compact level sets for "
                      "a, b > -2, a + b > -2, equilibria in the critical set"))
def s5_euler_jacobi() -> Verdict:
    return Verdict.of_parts([positivity_part(), equilibria_part(),
                             Verdict.by_argument(ARGUED).as_part("the theorem (cited) and how it applies")],
                            n_values=(4,), notes=(
                                "L_gamma > 0 on S^3 iff " + RANGE + "; H proper; every equilibrium has G = 0; "
                                "the Omega E_4 = 0 equilibria are critical (exact points); the measure is the "
                                "corrected residue of S5:red-measure"),
                            method="exact identities (SymPy and FLINT): characteristic polynomial of L_gamma, "
                                   "cell certificate of the positivity range, equilibrium identities and ranks; "
                                   "the theorem cited")
