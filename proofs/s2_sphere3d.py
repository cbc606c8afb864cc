r"""Section 2.1 — the classical 3D Chaplygin sphere, decided exactly.

The model (definitions, eq:motion3D and eq:mom3D):

.. math::
    \dot M = M\times\Omega,\quad \dot\gamma = \gamma\times\Omega,\qquad
    M = L_\gamma\Omega = \mathbb{I}\Omega + b\,\gamma\times(\Omega\times\gamma),\qquad
    \mathbb{I} = \operatorname{diag}(I_1, I_2, I_3),\; I_j, b > 0,\; \lVert\gamma\rVert = 1.

Claims decided here, all for $n = 3$ with symbolic $I_1, I_2, I_3, b$ (exact rational-function
identities, reduced modulo $\lVert\gamma\rVert^2 = 1$ where the claim lives on the sphere):

* eq:motion-velocity3D — $\mathbb{I}\dot\Omega = \mathbb{I}\Omega\times\Omega - b\gamma\times(\dot\Omega
  \times\gamma)$ is equivalent to $\dot M = M\times\Omega$: the two residuals are *the same
  polynomial* in $(\Omega, \dot\Omega, \gamma)$, for every $\gamma$ (not only on the sphere).
* S2.1:detL3D — $\det L_\gamma = c\,(1 - b\langle\tilde{\mathbb{I}}^{-1}\gamma,\gamma\rangle)$,
  $c = \prod_j (I_j + b)$, and positivity through the certificate
  $1 - b\langle\tilde{\mathbb{I}}^{-1}\gamma,\gamma\rangle \equiv \sum_j \gamma_j^2 I_j/(I_j + b)$ on $S^2$.
* eq:invL3D — the printed inverse equals Cramer's rule applied to eq:mom3D.
* S2.1:integrals3D — $f_1 = \langle M,\gamma\rangle$, $f_2 = \lVert M\rVert^2$ (for *any* $\Omega$) and
  $H = \tfrac12\langle M,\Omega\rangle$ (for $\Omega = L_\gamma^{-1}M$) have zero Lie derivative.
* S2.1:measure3D — $\operatorname{div}(\rho X) = 0$ on $S^2$ for $\rho = (\det L_\gamma)^{-1/2}$, with the
  sphere handled by the ambient/Leray-form argument of :mod:`symbolic.measure`; and
  $dM = \det L_\gamma\, d\Omega$ at fixed $\gamma$, so $\rho\,dM\,d\gamma = (\det L_\gamma)^{1/2}d\Omega\,d\gamma$.

Uses: eq:motion3D, eq:mom3D (definitions), and the consistency of both with their
$n$-dimensional forms eq:motion-general, eq:M-O (checked in the definition rows below).
"""

from __future__ import annotations

from functools import cache

import sympy as sp
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.symbolic.algebra import hat, vector_symbols, wedge
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.exact.identity import rational_identity
from chaplygin_nd.symbolic.measure import measure_residual
from chaplygin_nd.symbolic.model import commutator, inertia_operator, mom3d, motion3d
from chaplygin_nd.symbolic.printed import section2 as printed
from chaplygin_nd.symbolic.sphere3d import L_gamma_matrix_3d, angular_velocity_3d, velocity_field_3d

M = vector_symbols("M", 3)
gamma = vector_symbols("gamma", 3)
Omega = vector_symbols("Omega", 3)
Omega_dot = vector_symbols("Omegadot", 3)
I1, I2, I3 = sp.symbols("I1:4", positive=True)
b = sp.Symbol("b", positive=True)
inertia = sp.diag(I1, I2, I3)
SPHERE = tuple(gamma)
# Counterexamples must be physical: I_j > 0, b > 0.
SAMPLERS = {s: (lambda r: points.rational(r, 0, 4, 6, open_lo=True)) for s in (I1, I2, I3, b)}
N3 = (3,)


def _identity(residual, *, sphere=True, label=""):
    return rational_identity(residual, sphere=SPHERE if sphere else None, samplers=SAMPLERS,
                             label=label)


@cache
def _omega_of_M() -> sp.Matrix:
    return angular_velocity_3d(M, gamma, inertia, b)


def _lie_derivative(f: sp.Expr, Mdot: sp.Matrix, gdot: sp.Matrix) -> sp.Expr:
    return sum(sp.diff(f, M[i]) * Mdot[i] + sp.diff(f, gamma[i]) * gdot[i] for i in range(3))


def velocity_field_residual() -> sp.Matrix:
    r"""The derived field in $(\Omega, \gamma)$ (:func:`symbolic.sphere3d.velocity_field_3d`, emitted
    as the 3D equations of motion in velocity form) against eq:motion3D itself: with
    $M = \mathbb{I}\Omega + b\gamma\times(\Omega\times\gamma)$ (eq:mom3D), the field's
    $\dot\Omega = N/\det L_\gamma$ and $\dot\gamma$ must satisfy
    $\det L_\gamma\,\tfrac{d}{dt}M = L_\gamma N + \det L_\gamma\,(\partial_\gamma M)\dot\gamma
    = \det L_\gamma\,M\times\Omega$ and $\dot\gamma = \gamma\times\Omega$ — a polynomial identity
    in $(\Omega, \gamma, I, b)$ for every $\gamma$. $L_\gamma = \partial M/\partial\Omega$ is taken from
    the definition here, not from :mod:`symbolic.sphere3d`."""
    numerator, det_L, gdot = velocity_field_3d(Omega, gamma, inertia, b)
    M_of_Omega = mom3d(Omega, gamma, inertia, b)
    Mdot_def, gdot_def = motion3d(M_of_Omega, gamma, Omega)
    dMdt = (M_of_Omega.jacobian(Omega) * numerator
            + det_L * M_of_Omega.jacobian(gamma) * gdot)
    return (dMdt - det_L * Mdot_def).col_join(gdot - gdot_def)


@claim("eq:motion3D")
def motion3d_definition() -> Verdict:
    # Consistency: through the hat map, eq:motion3D is eq:motion-general at n = 3.
    Mdot, gdot = motion3d(M, gamma, Omega)
    return Verdict.definition(
        "definition (the reduced equations of the 3D sphere)", n_values=N3,
        consistency=[
            ("hat(M x Omega) = [hat M, hat Omega]",
             _identity(hat(Mdot) - commutator(hat(M), hat(Omega)), sphere=False)),
            ("gamma x Omega = -hat(Omega) gamma",
             _identity(gdot + hat(Omega) * gamma, sphere=False)),
            ("the derived field in (Omega, gamma): L_gamma Omega_dot = M x Omega - "
             "(d_gamma M) gamma_dot, gamma_dot = gamma x Omega (exact, every gamma)",
             _identity(velocity_field_residual(), sphere=False, label="field3d")),
        ])


@claim("eq:mom3D")
def mom3d_definition() -> Verdict:
    # Consistency with eq:M-O and eq:Inertia at n = 3: I = diag(J2+J3, J1+J3, J1+J2).
    J = sp.diag(*sp.symbols("J1:4", positive=True))
    I_of_J = sp.diag(J[1, 1] + J[2, 2], J[0, 0] + J[2, 2], J[0, 0] + J[1, 1])
    nd = inertia_operator(hat(Omega), J) + b * wedge(hat(Omega) * gamma, gamma)
    return Verdict.definition(
        "definition (momentum about the contact point)", n_values=N3,
        consistency=[("hat(eq:mom3D) = eq:M-O with I_1 = J_2+J_3, ...",
                      _identity(hat(mom3d(Omega, gamma, I_of_J, b)) - nd, sphere=False))])


@claim("eq:motion-velocity3D", uses=("eq:motion3D", "eq:mom3D"))
def motion_velocity_3d() -> Verdict:
    # d/dt M(Omega, gamma) - M x Omega, with gamma' = gamma x Omega and Omega' free symbols:
    M_of_Omega = mom3d(Omega, gamma, inertia, b)
    gdot = gamma.cross(Omega)
    dMdt = M_of_Omega.jacobian(Omega) * Omega_dot + M_of_Omega.jacobian(gamma) * gdot
    momentum_residual = dMdt - M_of_Omega.cross(Omega)
    velocity_residual = printed.motion_velocity_3d_residual(Omega, Omega_dot, gamma, inertia, b)
    check = _identity(momentum_residual - velocity_residual, sphere=False, label="mv3d")
    return Verdict.decide(
        check, n_values=N3,
        method="the residual of Mdot = M x Omega equals the residual of the printed velocity form "
               "identically in (Omega, Omegadot, gamma, I, b): " + check.method,
        notes="Stronger than claimed: the equivalence holds for every gamma, not only on S^2.")


@claim("S2.1:detL3D", uses=("eq:mom3D",))
def det_L_3d() -> Verdict:
    L = L_gamma_matrix_3d(gamma, inertia, b)
    formula = _identity(L.det() - printed.det_L_3d(gamma, inertia, b), label="det")
    # Positivity certificate: 1 - b<I~^{-1} gamma, gamma> = sum gamma_j^2 I_j / (I_j + b) on S^2,
    # a sum of non-negative terms, positive because |gamma| = 1 and I_j > 0.
    tilde = inertia + b * sp.eye(3)
    certificate = sum(gamma[j] ** 2 * inertia[j, j] / tilde[j, j] for j in range(3))
    c = tilde.det()
    positive = _identity(printed.det_L_3d(gamma, inertia, b) / c - certificate, label="det>0")
    return Verdict.all_of(
        [("det L_gamma = c(1 - b<I~^-1 gamma, gamma>)", formula),
         ("> 0 via the certificate sum_j gamma_j^2 I_j/(I_j+b)", positive)], n_values=N3)


@claim("eq:invL3D", uses=("eq:mom3D", "S2.1:detL3D"))
def inverse_3d() -> Verdict:
    check = _identity(printed.inverse_L_3d(M, gamma, inertia, b) - _omega_of_M(), label="inv")
    return Verdict.decide(
        check, n_values=N3,
        method="printed inverse - Cramer's rule on eq:mom3D: " + check.method)


@claim("S2.1:integrals3D", uses=("eq:motion3D", "eq:invL3D"))
def integrals_3d() -> Verdict:
    # f1 and f2 are integrals for ANY angular velocity: Omega stays a free symbol.
    free = printed.integrals_3d(M, gamma, Omega)
    Mdot, gdot = motion3d(M, gamma, Omega)
    checks = [(f"d{name}/dt = 0 for any Omega",
               _identity(_lie_derivative(free[name], Mdot, gdot), sphere=False))
              for name in ("f1", "f2")]
    # H needs the dynamics. In the coordinates (Omega, gamma) -- a diffeomorphism of P, as
    # det L_gamma > 0 -- H(Omega, gamma) = <L_gamma Omega, Omega>/2 is a polynomial and only
    # Omega' carries the denominator det L_gamma: multiply the Lie derivative by it.
    numerator, det_L, gdot = velocity_field_3d(Omega, gamma, inertia, b)
    H = printed.integrals_3d(mom3d(Omega, gamma, inertia, b), gamma, Omega)["H"]
    dH = sum(sp.diff(H, Omega[i]) * numerator[i] + det_L * sp.diff(H, gamma[i]) * gdot[i]
             for i in range(3))
    checks.append(("det(L) dH/dt = 0 along the field in (Omega, gamma)",
                   _identity(sp.expand(dH), label="H")))
    return Verdict.all_of(checks, n_values=N3)


@claim("S2.1:measure3D", uses=("eq:motion3D", "S2.1:detL3D"))
def measure_3d() -> Verdict:
    exponents = printed.measure_3d_exponents()
    Omega_M = _omega_of_M()
    Mdot, gdot = motion3d(M, gamma, Omega_M)
    det_L = L_gamma_matrix_3d(gamma, inertia, b).det()
    residual = measure_residual(list(Mdot) + list(gdot), list(M) + list(gamma),
                                [(det_L, exponents["dM dgamma"])])
    invariant = _identity(residual, label="div")
    # Change of variables M = L_gamma Omega at fixed gamma: dM dgamma = det(d(M,gamma)/d(Omega,gamma)).
    jac = sp.Matrix.vstack(mom3d(Omega, gamma, inertia, b), gamma).jacobian(list(Omega) + list(gamma))
    jacobian = _identity(jac.det() - det_L, sphere=False)
    # (det L)^p dM = (det L)^(p+1) dOmega: the printed second exponent must be p + 1.
    shift = exponents["dOmega dgamma"] - exponents["dM dgamma"]
    return Verdict.all_of(
        [("div((det L)^(-1/2) X) = 0 on S^2 (ambient divergence, Leray form)", invariant),
         ("Jacobian of (Omega, gamma) -> (M, gamma) is det L_gamma", jacobian),
         ("exponent shift dOmega vs dM is 1",
          _identity(sp.Rational(shift) - 1, sphere=False))], n_values=N3)
