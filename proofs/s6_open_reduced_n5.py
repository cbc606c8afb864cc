r"""Beyond the paper: its second open problem, measured for $n = 5$ (row S6:open-reduced-n5).

The paper ends: "Obtain the reduced equations on $P/\mathrm{SO}(n-1)$ for $n \ge 5$ and determine if they
are integrable." The reduced equations for $n = 5$ are derived in row S6:reduced-n5 and a sixth
integral is proved in row S6:sixth-integral-n5 (integrable with the measure, S6:euler-jacobi-n5);
this row is the measurement beside them: the flow on $P$ and on $SO(4)$-invariant observables
(which see exactly the reduced motion) for $n = 5$, with a rule fixed before the sixth integral
was known.

**What integrability would predict (derived here, exactly, at a seeded rational point).**
$P = \mathfrak{so}(5)\times S^4$ has dimension 14. (i) The $SO(4)$ action eq:action
$h\cdot(M, \gamma) = (hMh^{-1}, h\gamma)$ has 6-dimensional orbits at the point (the 6 generator
velocities $([X, M], X\gamma)$ have rank 6), so the isotropy is discrete and
$\dim P/SO(4) = 14 - 6 = 8$. (ii) The integrals: $p(\lambda, \sigma) = \det(M + \sigma\gamma\gamma^T -
\lambda)$ (eq:pol-first-integrals) has the non-constant coefficients $c_{\lambda^3}$, $c_{\lambda^1}$
(those of $\det(M - \lambda)$: $\|M\|^2$ and the sum of the squared $4\times 4$ Pfaffians) and the
$\sigma\lambda^2$, $\sigma\lambda^0$ coefficients; with the energy $H = \frac12\langle M, L_\gamma^{-1}M\rangle$
that is 5 functions; their differentials (Jacobi's formula for the coefficients) restricted to $T P$ have rank 5 at the point and vanish on
the group directions (exact zeros: they are invariant). So they descend to 5 independent integrals
of the 8-dimensional reduced space, whose regular level sets have dimension 3; the invariant
measure (P:Measure) descends too. Hence: **if the reduced system were integrable**, a quasi-periodic
reduced orbit would show **at most 3** independent frequencies (a 3-torus filling the level set),
**2** if a sixth integral exists (Euler–Jacobi on the 8-dimensional quotient needs $8 - 2 = 6$);
on $P$ the reconstruction adds at most rank $SO(4) = 2$: **at most 5**, 4 with a sixth integral.
Chaos (a positive Lyapunov exponent on a set of positive measure) would show that it is not.

**Measured** on 100 drawn orbits of the axisymmetric $n = 5$ sphere (simulate/analysis/evidence_rows.py
``n5_row``; $a \in \{-0.9, -0.5, 0.5, 2\}$, $b \in \{0.5, 2\}$, three energies): the count on the two
$SO(4)$-invariant observables (reduced frequencies) and on $P$, the frequency diffusion, MEGNO.

**Rule (fixed before the 100-orbit run; only an 8-orbit timing pilot had been seen).**
Verdict ``evidence`` that no chaos is resolved and the counts respect the bounds of integrability
iff: at most 2 % of the orbits are MEGNO-chaotic, at least 90 % MEGNO-regular, and at most 2 % of
the orbits that are resolved (D < 1e-5) have more than 3 reduced or more than 5 frequencies on $P$;
controls: the $n = 4$ sphere (integrable, proved; the 200 orbits of S5:reconstruction) must pass
the same MEGNO test, and the non-symmetric $n = 5$ sphere (``CHAOTIC_J[5]``, 24 orbits) must have
at least 90 % MEGNO-chaotic orbits (``CONTROL_CHAOTIC_MIN`` of :mod:`simulate.analysis.rules`)
and a median diffusion at least 100 times that of the symmetric
$n = 5$ orbits. Otherwise ``open`` with the numbers. Never ``holds``: this is a measurement.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.proofs import drawn_common as dc
from chaplygin_nd.simulate.analysis import evidence_rows as er
from chaplygin_nd.simulate.analysis import rules
from chaplygin_nd.simulate.analysis.control import CHAOTIC_J
from chaplygin_nd.simulate.analysis.drawn_evidence import BATCH, TOL
from chaplygin_nd.simulate.analysis.frequencies import REGULAR
from chaplygin_nd.symbolic import algebra, model
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.exact.points import ledger_seed

SECTION = "Conclusions — open problems (beyond the paper)"
N = 5


def _point(n: int = N):
    rng = points.generator(ledger_seed(), f"S6:open-reduced-n{n}")
    gamma = points.sphere_point(rng, n)
    M = points.skew_matrix(rng, n)
    a, b = points.rational(rng, -1, 1), points.rational(rng, 1, 3)
    return M, gamma, a, b


def _integral_gradients(M, gamma, a, b):
    r"""Exact gradients in $(\mathrm{vec}\,M, \gamma) \in \mathbb{R}^{15}$ of the non-constant coefficients of
    $p(\lambda, \sigma)$ and of $H$ at the point. Coefficients: Jacobi's formula
    $\partial\det A = \mathrm{tr}(\mathrm{adj}(A)\,\partial A)$ with $A = M + \sigma\gamma\gamma^T - \lambda$
    ($\partial A = E_i\wedge E_j$ for $M$, $\sigma(E_k\gamma^T + \gamma E_k^T)$ for $\gamma_k$), polynomials in
    $(\lambda, \sigma)$. $H$: $\partial_M H = \Omega$, $\partial_{\gamma_k} H = -\frac12\omega^T(\partial L/\partial\gamma_k)\omega$
    ($\omega = L^{-1}m$). The adjugate, determinant and products are exact polynomial matrices
    (``DomainMatrix`` over $\mathbb{Q}[\lambda, \sigma]$): the same polynomials as SymPy ``Matrix``
    arithmetic on expressions, which took 7 s of the row (checked equal entry by entry).
    Domain: rational $M$, $\gamma$, $a$, $b$."""
    from sympy.polys.matrices import DomainMatrix

    N = M.rows
    lam, sig = sp.symbols("lambda sigma")
    ring = sp.QQ[lam, sig]   # exact polynomial matrices (SymPy's DomainMatrix over QQ[lambda, sigma])

    def poly_matrix(X):
        return DomainMatrix.from_Matrix(X).convert_to(ring)

    A = poly_matrix(M + sig * gamma * gamma.T - lam * sp.eye(N))
    adj = A.adjugate()
    directions = list(algebra.so_basis(N))
    for k in range(N):
        e = algebra.basis_vector(N, k)
        directions.append(sig * (e * gamma.T + gamma * e.T))
    base = A.det().to_dict()                        # {(deg lambda, deg sigma): coefficient}
    coeffs = sorted(mon for mon, c in base.items() if c and mon not in ((N, 0), (N - 1, 1)))
    rows = []
    for D in directions:
        AD = adj * poly_matrix(D)
        d = sum((AD[i, i].element for i in range(N)), ring.zero).to_dict()   # the trace
        rows.append([sp.QQ.to_sympy(d.get(mon, sp.QQ.zero)) for mon in coeffs])
    grads = sp.Matrix(rows).T                       # one row per coefficient
    m0 = list(algebra.vec(M))
    J = sp.diag(*([1] * (N - 1) + [1 + a]))
    L = model.L_matrix(gamma, J, b)
    omega = L.LUsolve(sp.Matrix(m0))
    dH = list(omega) + [-sp.Rational(1, 2) * (omega.T * model.L_matrix_derivative(gamma, b, k) * omega)[0]
                        for k in range(N)]
    return coeffs, grads.col_join(sp.Matrix([dH]))


def _generators(M, gamma):
    r"""The velocities $(\mathrm{vec}[X, M], X\gamma)$ of the generators $X = E_i\wedge E_j$,
    $i < j < n$, of $SO(n-1) = \{h : hE_n = E_n\}$ (eq:SOnminus1, eq:action); 6 for $n = 5$."""
    N = M.rows
    rows = []
    for i in range(N - 1):
        for j in range(i + 1, N - 1):
            X = algebra.wedge(algebra.basis_vector(N, i), algebra.basis_vector(N, j))
            rows.append(list(algebra.vec(algebra.commutator(X, M))) + list(X * gamma))
    return sp.Matrix(rows)


def reduced_dimension_check(n: int = N) -> dict:
    """The exact part (module docstring (i), (ii)) in dimension ``n`` (5 for this row, 6 for
    S6:open-reduced-n6): ranks by SymPy's ``Matrix.rank`` and again by ``DomainMatrix.rank`` over QQ
    (two implementations); the invariance as exact zeros."""
    from sympy.polys.matrices import DomainMatrix

    N = n
    M, gamma, a, b = _point(n)
    coeffs, G = _integral_gradients(M, gamma, a, b)
    X = _generators(M, gamma)
    dim = algebra.so_dim(N)
    proj = sp.diag(sp.eye(dim), sp.eye(N) - gamma * gamma.T)   # onto T P (the sphere's tangent)
    GT = G * proj

    def ranks(A):
        return A.rank(), DomainMatrix.from_Matrix(A).convert_to(sp.QQ).rank()

    invariance = G * X.T
    return {"orbit_rank": ranks(X), "integral_rank": ranks(GT),
            "invariant": all(v == 0 for v in invariance), "integrals": len(coeffs) + 1,
            "coefficients": [f"lambda^{i} sigma^{j}" for i, j in coeffs],
            "point": f"a = {a}, b = {b}, gamma = {list(gamma)}"}


def _over(r, reduced_bound, full_bound) -> bool:
    return r.diffusion < REGULAR and (r.count > full_bound or (
        r.invariant_diffusion < REGULAR and r.invariant_count > reduced_bound))


@claim("S6:open-reduced-n5", uses=("eq:pol-first-integrals", "P:Measure", "eq:action",
                                    "S5:EJ-tori", "S5:reconstruction"),
       adds=(SECTION, "the paper's second open problem (is the reduced system on P/SO(n-1) "
                      "integrable for n >= 5?), measured for n = 5: frequency count, diffusion "
                      "and MEGNO on 100 drawn orbits, with the integrable n = 4 sphere and a "
                      "non-symmetric n = 5 sphere as controls"))
def s6_open_reduced_n5() -> Verdict:
    return open_problem_verdict(N)


def _prediction(n: int, exact: dict, dim_p: int, orbit: int, quotient: int, level: int,
                reduced_bound: int, full_bound: int) -> str:
    """The exact part of :func:`open_problem_verdict` in words: the orbit and integral ranks and
    the frequency bounds they give if the reduced system were integrable."""
    return (f"derived (exact, SymPy Matrix.rank and DomainMatrix.rank over QQ, at {exact['point']}): "
            f"SO({n - 1})-orbits of dimension {orbit}, so dim P/SO({n - 1}) = {dim_p} - {orbit} = "
            f"{quotient}; "
            f"{exact['integrals']} invariant integrals ({', '.join(exact['coefficients'])} of "
            f"p(lambda, sigma), and H) of rank {exact['integral_rank'][0]} on TP, so regular "
            f"reduced level sets of dimension {level}; if the reduced system were integrable: "
            f"at most {reduced_bound} reduced frequencies ({reduced_bound - 1} with "
            f"{'a sixth integral, Euler-Jacobi' if n == 5 else 'one more integral'}), at most "
            f"{full_bound} on P ({full_bound - 1})")


def open_problem_verdict(n: int) -> Verdict:
    r"""The rule of the module docstring in dimension ``n`` (rows S6:open-reduced-n5, S6:open-reduced-n6):
    the exact count (:func:`reduced_dimension_check`), the drawn orbits of
    :func:`simulate.analysis.evidence_rows.open_row`, the $n = 4$ and general-$\mathbb{J}$ controls."""
    exact = reduced_dimension_check(n)
    dim_p, group = algebra.so_dim(n) + n - 1, algebra.so_dim(n - 1)
    orbit = exact["orbit_rank"][0]
    quotient = dim_p - orbit
    level = quotient - exact["integral_rank"][0]
    derived = (exact["orbit_rank"] == (group, group) and exact["integral_rank"] == (n, n)
               and exact["invariant"])
    reduced_bound, full_bound = level, level + (n - 1) // 2     # + rank SO(n-1)
    prediction = _prediction(n, exact, dim_p, orbit, quotient, level, reduced_bound, full_bound)
    if reason := dc.without_heyoka():  # the exact part needs no heyoka: say what it gave
        return Verdict.open(f"{reason}. Computed here: {prediction}"
                            + ("" if derived else f" (NOT the expected ranks {group} and {n}, "
                                                  "or an integral not invariant)"))
    er.start_shared("full4", ledger_seed())  # the shared n = 4 control first, unless another row has it
    out = er.open_row(n, ledger_seed())
    res, rerun, ctl5 = out["symmetric"]["results"], out["symmetric"]["rerun"], out["control"]
    ctl4 = er.full4_row(ledger_seed())["results"]
    over = dc.fraction(res, lambda r: _over(r, reduced_bound, full_bound))
    no_chaos, ctl4_ok = rules.holds("chaos", res), rules.holds("chaos", ctl4)  # the MEGNO ladder
    d_sym = float(np.median([r.diffusion for r in res]))
    d_ctl = float(np.median([r.diffusion for r in ctl5]))
    ctl5_ok = (dc.fraction(ctl5, rules.get("chaos").contradicts) >= dc.CONTROL_CHAOTIC_MIN
               and d_ctl >= dc.SEPARATION * d_sym)
    inv: dict = {}
    for r in res:
        if r.invariant_diffusion < REGULAR:
            inv[r.invariant_count] = inv.get(r.invariant_count, 0) + 1
    inv_rerun: dict = {}
    for r in rerun:
        inv_rerun[r.invariant_count] = inv_rerun.get(r.invariant_count, 0) + 1
    kept_ok = dc.fraction(res, dc.keeps) >= dc.KEPT_MIN
    measured = (f"{prediction}. Measured: " + dc.integrals_text(res) + "; " + dc.ladder_text(res)
                + f"; SO({n - 1})-invariant observables resolved (D < 1e-5) on "
                f"{sum(inv.values())} of {len(res)} orbits: "
                + ", ".join(f"{c} frequenc{'y' if c == 1 else 'ies'} on {k} orbit{'' if k == 1 else 's'}"
                           for c, k in sorted(inv.items()))
                + "; " + dc.describe(res, "on P") + f"; the {len(rerun)} orbits unresolved at T after the "
                f"ladder (2T, 4T): {dc.tally(rerun) or 'none'}, counts on P "
                + str(sorted(r.count for r in rerun)) + ", invariant counts "
                + str(dict(sorted(inv_rerun.items()))))
    control = (dc.describe(ctl4, "n = 4 axisymmetric (integrable, proved)") + f": no chaos: {ctl4_ok}; "
               + dc.describe(ctl5, f"n = {n}, J = diag{CHAOTIC_J[n]}") + f": chaotic and diffusing: {ctl5_ok}")
    return Verdict.numerical(
        derived and no_chaos and kept_ok and over <= dc.CONTRADICTING_MAX,
        measured=measured, initial_conditions=len(res),
        tolerance=(f"heyoka Taylor tol {TOL:g}, batch {BATCH}, T = 4096 at energy scale 1, dt = 0.5; NAFF "
                   "vectorised; |coefficients| <= 4, lines beyond explained by |c| <= 12 when the "
                   "false-match probability is <= 1 %; D < 1e-5 regular (unresolved again at 2T, "
                   "4T); chaos by the MEGNO horizon ladder; " + dc.RULE),
        contradiction=("of integrability: more than 2 % chaotic orbits (MEGNO ladder), fewer than 90 % "
                       f"regular, fewer than 98 % keeping the proved integrals, or more than 2 % resolved orbits with more than {reduced_bound} "
                       f"reduced or {full_bound} frequencies on P (rule of the module docstring, fixed "
                       "before the run)"),
        control=control, control_separates=ctl4_ok and ctl5_ok,
        method=("exact ranks at a seeded rational point (SymPy) + numerical: eq:motion-general "
                f"n = {n} (expression builders), MEGNO over a horizon ladder, NAFF on drawn orbits, "
                "the proved integrals along every orbit; validation of the chaos rule on systems with "
                f"known answers: {dc.STUDY}"
                + ("; " + dc.PLANTED[f"S6:open-reduced-n{n}"] if f"S6:open-reduced-n{n}" in dc.PLANTED else "")),
        n_values=(n,),
        notes=("what the measurement says about the open problem: "
               + ("no chaos was resolved on any drawn orbit and the reduced observables show "
                  f"{max(inv, key=inv.get) if inv else '?'} independent frequencies on most resolved "
                  "orbits: consistent with an integrable reduced system (the count suggests invariant "
                  f"{max(inv, key=inv.get) if inv else '?'}-tori inside the {level}-dimensional level "
                  f"sets, as {quotient - (max(inv, key=inv.get) if inv else 0)} integrals would give "
                  f"against the {n} known; the missing ones are proved or checked in rows "
                  "S6:sixth-integral-n5 and S6:wedge-integrals); a measurement, not a proof" if no_chaos else
                  "chaos or undecided MEGNO on a fraction of the drawn orbits; see the numbers")
               + ("; n = 6: row S6:open-reduced-n6" if n == 5 else "")),
        data={"orbits": dc.record(res), "rerun": dc.record(rerun), f"control{n}": dc.record(ctl5),
              "parts": {"integrals": kept_ok, "chaos": no_chaos,
                        "frequencies": over <= dc.CONTRADICTING_MAX},
              "invariant_counts": inv, "exact": {k: (list(v) if isinstance(v, tuple) else v)
                                                 for k, v in exact.items()}})
