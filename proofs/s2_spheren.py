r"""Section 2.2 — the $n$-dimensional Chaplygin sphere with a general diagonal mass tensor.

The model (definitions eq:motion-general, eq:M-O, eq:Inertia), on $P = \mathfrak{so}(n)\times S^{n-1}$:

.. math::
    \dot M = [M,\Omega],\quad \dot\gamma = -\Omega\gamma,\qquad
    M = L_\gamma(\Omega) = \mathbb{J}\Omega + \Omega\mathbb{J} + b(\Omega\gamma)\wedge\gamma,\qquad
    \mathbb{J} = \operatorname{diag}(J_1,\dots,J_n),\ J_i, b > 0.

Claims decided here, and why the checks cover every $n$:

* eq:motion-velocitynD — the residual of $\dot M = [M,\Omega]$ (with $M = L_\gamma\Omega$,
  $\dot\gamma = -\Omega\gamma$) *equals* the residual of the printed velocity form, as polynomials
  in $(\Omega, \dot\Omega, \gamma, \mathbb{J}, b)$. So either equation holds iff the other does.
* eq:iso-spectral — $\tfrac{d}{dt}(M + \sigma\gamma\gamma^T) = [M + \sigma\gamma\gamma^T, \Omega]$ for
  *any* skew $\Omega$.
* eq:pol-first-integrals — the Lie derivative of $p(\lambda,\sigma) = \det(M + \sigma\gamma\gamma^T -
  \lambda)$ vanishes identically in $(\lambda,\sigma)$, for any skew $\Omega$ (so for any inertia).
* S2.2:energy — $\dot H = 0$ for $H = \tfrac12\langle M,\Omega\rangle_\kappa$, $\Omega = L_\gamma^{-1}M$.
* eq:invmeasuredet — $\operatorname{div}((\det L_\gamma)^{-1/2}X) = 0$ on $\lVert\gamma\rVert = 1$
  (ambient divergence and Leray form, :mod:`symbolic.measure`); the second form follows from
  $dM = \det L_\gamma\, d\Omega$ (the Jacobian of $\Omega\mapsto L_\gamma\Omega$ in $\mathfrak{so}(n)$).

All $n$: the first three are identities of matrix algebra proved symbolically for
$n = 3,\dots,6$ and at seeded exact points up to $n = 24$; each is a formal consequence of
$\tfrac{d}{dt}(u v^T) = \dot u v^T + u\dot v^T$ and $[AB, \cdot]$ rules that do not depend on $n$.
The energy and the measure need $L_\gamma^{-1}$, for which no closed form is known for a general
$\mathbb{J}$: they are decided symbolically for $n = 3$ (and the energy for $n = 4$) and at exact
rational points, where $\Omega = L_\gamma^{-1}M$ is an exact linear solve, up to $n = 24$
(every $n \le 12$, then 16, 20, 24: :func:`symbolic.exact.points.all_n`).
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.symbolic.algebra import (
    basis_vector,
    commutator,
    killing,
    skew_symbols,
    unvec,
    vec,
    vector_symbols,
    wedge,
)
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.exact.identity import (
    SYMPY_INVERSE_MAX_N,
    point_engines,
    rational_identity,
    zero_at_points,
)
from chaplygin_nd.symbolic.measure import chaplygin_divergence_at
from chaplygin_nd.symbolic.model import (
    L_gamma,
    L_matrix,
    angular_velocity,
    inertia_operator,
    mass_tensor_symbols,
    motion,
)
from chaplygin_nd.symbolic.printed import section2 as printed
from sympy.polys.domains import QQ
from sympy.polys.matrices import DomainMatrix

SYMBOLIC_N = (3, 4, 5, 6)
POINT_N = tuple(points.all_n(3))
#: the rows whose point step inverts L_gamma exactly: SymPy decides their points up to n = 8
#: (full inverse), FLINT at every n; FLINT's divergence takes one solve with n + 1 right-hand
#: sides instead of the full inverse (flint_model.divergence_at_fmpq: 0.4 s at n = 24, not 2.7 s)
ENERGY_N = points.all_n(3)
MEASURE_N = points.all_n(3)
eps = sp.Symbol("epsilon")
b = sp.Symbol("b", positive=True)


def _positive(rng):
    return points.rational(rng, 0, 4, 6, open_lo=True)


def _samplers(J):
    return {s: _positive for s in list(J.diagonal()) + [b]}


def _directional(expr: sp.Matrix, moves: list[tuple[sp.Matrix, sp.Matrix]]) -> sp.Matrix:
    """d/dt of ``expr`` when each variable matrix X moves with velocity Xdot (exact, by d/d eps)."""
    subs = {}
    for X, Xdot in moves:
        for x, xd in zip(X, Xdot):
            if isinstance(x, sp.Symbol):
                subs[x] = x + eps * xd
    return sp.diff(expr.xreplace(subs), eps).subs(eps, 0)


def _point(n: int):
    def sample(rng):
        return {"M": points.skew_matrix(rng, n), "gamma": points.sphere_point(rng, n),
                "Omega": points.skew_matrix(rng, n),
                "J": sp.diag(*[_positive(rng) for _ in range(n)]), "b": _positive(rng)}
    return sample


def _both(name: str, symbolic_residual, point_residual, *, sphere: bool = False,
          symbolic_n=SYMBOLIC_N, point_n=POINT_N, count: int = 2, sympy_max: int | None = None):
    """Symbolic identity for ``symbolic_n`` and exact points for ``point_n``: a list of checks."""
    checks = []
    for n in symbolic_n:
        residual, J = symbolic_residual(n)
        gamma = vector_symbols("gamma", n)
        checks.append((f"{name}, symbolic n={n}", rational_identity(
            residual, sphere=tuple(gamma) if sphere else None,
            samplers=_samplers(J) if J is not None else None, label=f"{name}{n}")))
    for n in point_n:
        checks.append((f"{name}, points n={n}", zero_at_points(
            lambda p, n=n: point_residual(n, p), _point(n), count=count if n <= 12 else 1,
            label=f"{name}{n}",
            describe=f"so({n}) x S^{n - 1} x (J, b)", engines=point_engines(n, sympy_max))))
    return checks


def _ns(symbolic_n=SYMBOLIC_N, point_n=POINT_N):
    return tuple(sorted(set(symbolic_n) | set(point_n)))


@claim("eq:motion-general")
def motion_general_definition() -> Verdict:
    def residual(n):
        M, Om, gamma = skew_symbols("M", n), skew_symbols("Omega", n), vector_symbols("gamma", n)
        Mdot, gdot = motion(M, gamma, Om)
        return sp.Matrix([list(Mdot + Mdot.T), [(gamma.T * gdot)[0]]][0] + [(gamma.T * gdot)[0]]), None
    return Verdict.definition(
        "definition; consistency: the flow keeps M skew and ||gamma|| constant for any skew Omega",
        n_values=(3, 4, 5, 6),
        consistency=_both("skew and sphere preserved", residual,
                          lambda n, p: list(motion(p["M"], p["gamma"], p["Omega"])[0]
                                            + motion(p["M"], p["gamma"], p["Omega"])[0].T),
                          point_n=()))


@claim("eq:M-O", uses=("eq:Inertia",))
def m_o_definition() -> Verdict:
    # <L_gamma Omega, Omega>_kappa = sum_{i<j} (J_i + J_j) Omega_ij^2 + b |Omega gamma|^2 > 0:
    # L_gamma is positive definite, hence invertible, for every gamma (J_i, b > 0).
    def residual(n):
        J, Om, gamma = mass_tensor_symbols(n), skew_symbols("Omega", n), vector_symbols("gamma", n)
        quad = killing(L_gamma(Om, gamma, J, b), Om)
        sos = sum((J[i, i] + J[j, j]) * Om[i, j] ** 2 for i in range(n) for j in range(i + 1, n))
        sos += b * ((Om * gamma).T * (Om * gamma))[0]
        symmetric = L_matrix(gamma, J, b) - L_matrix(gamma, J, b).T
        return sp.Matrix([quad - sos] + list(symmetric)), J
    return Verdict.definition(
        "definition; consistency: L_gamma is Killing-self-adjoint and <L Omega, Omega> is the "
        "positive sum of squares sum (J_i+J_j) Omega_ij^2 + b|Omega gamma|^2 (so L_gamma is invertible)",
        n_values=(3, 4, 5),
        consistency=_both("self-adjoint, positive definite", residual, None, symbolic_n=(3, 4, 5),
                          point_n=()))


@claim("eq:Inertia")
def inertia_definition() -> Verdict:
    def residual(n):
        J = mass_tensor_symbols(n)
        rows = []
        for i in range(n):
            for j in range(i + 1, n):
                Eij = wedge(basis_vector(n, i), basis_vector(n, j))
                rows += list(inertia_operator(Eij, J) - (J[i, i] + J[j, j]) * Eij)
        return sp.Matrix(rows), J
    return Verdict.definition(
        "definition; consistency: I(E_i^E_j) = (J_i + J_j) E_i^E_j, so I maps so(n) to itself "
        "with positive eigenvalues", n_values=(3, 4, 5, 6),
        consistency=_both("eigenbasis", residual, None, point_n=()))


def _velocity_residuals(n, values=None):
    if values is None:
        J, Om, Omd = mass_tensor_symbols(n), skew_symbols("Omega", n), skew_symbols("W", n)
        gamma, bb = vector_symbols("gamma", n), b
    else:
        J, Om, gamma, bb = values["J"], values["Omega"], values["gamma"], values["b"]
        Omd = values["M"]  # any skew matrix serves as the free velocity Omega-dot
    # Symbolic route: d/dt of L_gamma(Omega) by the product rule, written out.
    gdot = -Om * gamma
    dM = inertia_operator(Omd, J) + bb * (wedge(Omd * gamma + Om * gdot, gamma)
                                           + wedge(Om * gamma, gdot))
    momentum = dM - commutator(L_gamma(Om, gamma, J, bb), Om)
    velocity = printed.motion_velocity_nd_residual(
        Om, Omd, gamma, lambda X: inertia_operator(X, J), bb)
    # not expanded here: the exact engines read the residual as polynomials (symbolic/exact/identity.py);
    # SymPy's expand of the symbolic n = 3..6 residual was 60 % of the row, and at a
    # point the entries are already numbers
    return momentum - velocity, J


@claim("eq:motion-velocitynD", uses=("eq:motion-general", "eq:M-O", "eq:Inertia"))
def motion_velocity_nd() -> Verdict:
    checks = _both("residual(Mdot=[M,Omega]) - residual(velocity form)",
                   lambda n: _velocity_residuals(n),
                   lambda n, p: _velocity_residuals(n, p)[0])
    return Verdict.all_of(checks, n_values=_ns(),
                          method="the two residuals are equal as polynomials: exact symbolic for "
                                 f"n=3..6, exact at 2 seeded rational points each for n=3..12 and 1 each for "
                                 f"n={points.n_text(points.all_n(13))}",
                          notes="Holds for every gamma in R^n, not only on the sphere.")


def _iso_residual(n, p=None):
    sigma = sp.Symbol("sigma")
    if p is None:
        M, Om, gamma = skew_symbols("M", n), skew_symbols("Omega", n), vector_symbols("gamma", n)
        A = M + sigma * gamma * gamma.T
        Mdot, gdot = motion(M, gamma, Om)
        lhs = _directional(A, [(M, Mdot), (gamma, gdot)])
        return (lhs - printed.iso_spectral_rhs(M, gamma, Om, sigma)).expand(), None
    M, Om, gamma, s = p["M"], p["Omega"], p["gamma"], p["b"]
    Mdot, gdot = motion(M, gamma, Om)
    lhs = Mdot + s * (gdot * gamma.T + gamma * gdot.T)
    return lhs - printed.iso_spectral_rhs(M, gamma, Om, s)


@claim("eq:iso-spectral", uses=("eq:motion-general",))
def iso_spectral() -> Verdict:
    checks = _both("d/dt(M + s gg^T) - [M + s gg^T, Omega]", _iso_residual,
                   lambda n, p: _iso_residual(n, p))
    return Verdict.all_of(checks, n_values=_ns(),
                          method="identity for any skew Omega: exact symbolic for n=3..6, exact at "
                                 "2 seeded rational points each for n=3..12 and 1 each for "
                                 f"n={points.n_text(points.all_n(13))} (sigma rational)")


def _charpoly_symbolic(n):
    sigma, lam = sp.symbols("sigma lambda")
    M, Om, gamma = skew_symbols("M", n), skew_symbols("Omega", n), vector_symbols("gamma", n)
    p = printed.characteristic_polynomial(M, gamma, sigma, lam)
    Mdot, gdot = motion(M, gamma, Om)
    # not expanded: both engines read the residual as polynomials (SymPy's expand took 2 s at
    # n = 4 and decided the identity alone; both engines take 0.1 s)
    return _directional(sp.Matrix([p]), [(M, Mdot), (gamma, gdot)])[0], None


def _charpoly_point(n, p):
    # Jacobi: d/dt det(B) = tr(adj(B) dB/dt) = det(B) tr(B^-1 dB/dt), B = M + sigma gg^T - lambda,
    # at rational sigma, lambda (B is invertible there: lambda is not an eigenvalue, checked).
    sigma, lam = p["b"], p["J"][0, 0]
    M, Om, gamma = p["M"], p["Omega"], p["gamma"]
    Mdot, gdot = motion(M, gamma, Om)
    B = DomainMatrix.from_Matrix(M + sigma * gamma * gamma.T - lam * sp.eye(n)).convert_to(QQ)
    Bdot = DomainMatrix.from_Matrix(Mdot + sigma * (gdot * gamma.T + gamma * gdot.T)).convert_to(QQ)
    det = B.det()
    if det == 0:
        raise ValueError("lambda is an eigenvalue at this point; pick another seed")
    return QQ.to_sympy(det) * (B.inv() * Bdot).to_Matrix().trace()


def _emitted_coefficients(n: int):
    r"""The coefficients of $p$ the kernels evaluate (:func:`symbolic.codegen.emit.axisym.p_coefficients`,
    entry $(i, j)$ at $\lambda^i\sigma^j$) minus those of the printed $p$, exactly."""
    from chaplygin_nd.symbolic.codegen.emit.axisym import M_symbols, gamma_symbols, p_coefficients

    sigma, lam = sp.symbols("sigma lambda")
    M, _ = M_symbols(n)
    shown = sp.Poly(printed.characteristic_polynomial(M, sp.Matrix(gamma_symbols(n)), sigma, lam),
                    lam, sigma)
    C = p_coefficients(n)
    return rational_identity([C[i, j] - shown.coeff_monomial(lam**i * sigma**j)
                              for i in range(n + 1) for j in range(2)]
                             + [shown.as_expr() - sum(C[i, j] * lam**i * sigma**j for i in range(n + 1)
                                                      for j in range(2))], label=f"p-coeffs{n}")


@claim("eq:pol-first-integrals", uses=("eq:iso-spectral",))
def polynomial_integrals() -> Verdict:
    checks = _both("d/dt p(lambda, sigma)", _charpoly_symbolic, _charpoly_point,
                   symbolic_n=(3, 4), point_n=points.all_n(3), count=3)
    checks += [(f"the emitted coefficients of p are those of the printed p, n={n}",
                _emitted_coefficients(n)) for n in (3, 4)]
    return Verdict.all_of(
        checks, n_values=_ns((3, 4)),
        method="the Lie derivative of det(M + sigma gg^T - lambda) along the flow, for any skew "
               "Omega, is the zero polynomial in (lambda, sigma, M, gamma, Omega): exact symbolic "
               "for n=3,4; exact at 3 seeded rational (M, gamma, Omega, lambda, sigma) for n=3..12 and 1 "
               f"for n={points.n_text(points.all_n(13))} "
               "(Jacobi's formula)")


def _energy_at(n, p):
    M, gamma, J, bb = p["M"], p["gamma"], p["J"], p["b"]
    Om = angular_velocity(M, gamma, J, bb)
    Mdot, gdot = motion(M, gamma, Om)
    # Differentiate M = L_gamma(Omega): L_gamma(Omega') = M' - b((Omega gamma')^gamma + (Omega gamma)^gamma').
    rhs = Mdot - bb * (wedge(Om * gdot, gamma) + wedge(Om * gamma, gdot))
    Omd = angular_velocity(rhs, gamma, J, bb)
    return (killing(Mdot, Om) + killing(M, Omd)) / 2


def _energy_symbolic(n):
    # Coordinates (Omega, gamma): H = <L_gamma Omega, Omega>/2 is a polynomial; Omega' =
    # adj(L) r / det(L). Multiply the Lie derivative by det(L) to get a polynomial identity.
    J, Om, gamma = mass_tensor_symbols(n), skew_symbols("Omega", n), vector_symbols("gamma", n)
    M = L_gamma(Om, gamma, J, b)
    Mdot, gdot = motion(M, gamma, Om)
    r = Mdot - b * (wedge(Om * gdot, gamma) + wedge(Om * gamma, gdot))
    L = L_matrix(gamma, J, b)
    dm = DomainMatrix.from_Matrix(L)
    adj, det = dm.adj_det()
    Omd_num = unvec(adj.to_Matrix() * vec(r), n)
    H = printed.energy_nd(M, Om)
    coords_O = [Om[i, j] for i in range(n) for j in range(i + 1, n)]
    dH = sum(sp.diff(H, c) * Omd_num[i, j] for c, (i, j) in
             zip(coords_O, [(i, j) for i in range(n) for j in range(i + 1, n)]))
    dH += det.as_expr() * sum(sp.diff(H, gamma[k]) * gdot[k] for k in range(n))
    return dH, J   # not expanded, as in _charpoly_symbolic


def _momentum_is_gradient(n: int = 4):
    r"""The printed $H$ is the energy whose $\Omega$-gradient (for $\langle\,,\rangle_\kappa$) is the
    momentum $M = L_\gamma(\Omega)$ of eq:M-O: $\partial H/\partial\Omega_{ij} = M_{ij}$ ($i < j$) with
    $M = L_\gamma(\Omega)$ substituted, symbolic in general $J$, $b$, $\gamma$ (as for any quadratic
    kinetic energy). Conservation alone would not see a factor or another integral such as
    $\lVert M\rVert^2$."""
    J, Om, gamma = mass_tensor_symbols(n), skew_symbols("Omega", n), vector_symbols("gamma", n)
    M = L_gamma(Om, gamma, J, b)
    H = printed.energy_nd(M, Om)
    return rational_identity([sp.diff(H, Om[i, j]) - M[i, j]
                              for i in range(n) for j in range(i + 1, n)])


@claim("S2.2:energy", uses=("eq:motion-general", "eq:M-O"))
def energy() -> Verdict:
    checks = _both("dH/dt", _energy_symbolic, _energy_at, sphere=True, symbolic_n=(3,),
                   point_n=ENERGY_N, sympy_max=SYMPY_INVERSE_MAX_N)
    checks.append(("dH/dOmega = M = L_gamma(Omega) (H is the energy of eq:M-O), n = 4",
                   _momentum_is_gradient()))
    return Verdict.all_of(
        checks, n_values=_ns((3,), ENERGY_N),
        method="exact symbolic for n=3 (general J, in coordinates (Omega, gamma), modulo "
               f"||gamma||^2=1); exact at 2 seeded rational points each for n=3..12 and 1 each "
               f"for n={points.n_text(points.all_n(13))} (Omega and "
               "Omega' by exact linear solves of eq:M-O); the Omega-gradient of H is M, exact "
               "symbolic n = 4")


def _measure_at(n, p):
    d = chaplygin_divergence_at(p["M"], p["gamma"], p["J"], p["b"])
    power = printed.measure_nd_exponents()["dM dgamma"]
    return d["div"] + power * sum(g * l for g, l in zip(d["gamma_dot"], d["dlogdet"]))


@claim("eq:invmeasuredet", uses=("eq:motion-general", "eq:M-O"))
def invariant_measure() -> Verdict:
    checks = [(f"div(rho X)/rho, points n={n}", zero_at_points(
        lambda p, n=n: _measure_at(n, p), _point(n), count=2 if n <= 8 else 1, label=f"measure{n}",
        describe=f"so({n}) x S^{n - 1} x (J, b)",
        engines=point_engines(n, SYMPY_INVERSE_MAX_N))) for n in MEASURE_N]
    # dM = det(L_gamma) dOmega (coordinates vec), so the exponent in front of dOmega is one more.
    exps = printed.measure_nd_exponents()
    checks.append(("exponent shift dOmega vs dM is 1", rational_identity(
        sp.Rational(exps["dOmega dgamma"] - exps["dM dgamma"]) - 1)))
    return Verdict.all_of(
        checks, n_values=MEASURE_N,
        method="ambient divergence of (det L)^(-1/2) X at seeded exact points (2 for n<=8, 1 above) of "
               f"so(n) x S^(n-1) (general diagonal J, b) for each n={points.n_text(MEASURE_N)}, computed exactly via "
               "d(L^-1) = -L^-1 dL L^-1 and Jacobi's formula (symbolic.measure; SymPy with the full "
               "inverse of L_gamma for n<=8, FLINT at every n with one solve L_gamma [Omega | Y] = "
               "[M | e_r ^ gamma] and the trace identities of a symmetric L_gamma, "
               "flint_model.divergence_at_fmpq); the Leray-form "
               "argument reduces invariance on P to the ambient divergence on ||gamma||=1",
        notes="The general-J claim (Fedorov-Kozlov) is backed by exact evidence at points, not a "
              "symbolic proof; the axisymmetric case is proved symbolically under P:Measure.")

