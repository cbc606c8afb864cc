r"""Section 2 of the paper, as printed (transcribed literally; DESIGN rule 1).

Each function is one displayed formula; its docstring gives the claim id and the LaTeX source.
Vectors are SymPy column matrices, ``inertia`` is the 3x3 matrix $\mathbb{I}$ (3D) and ``J`` the
mass tensor (nD). Nothing here is used by a derivation; only ``proofs/`` compares.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.symbolic.algebra import commutator, killing, wedge


def _dot(u: sp.Matrix, v: sp.Matrix) -> sp.Expr:
    return (u.T * v)[0]


def motion_velocity_3d_residual(Omega, Omega_dot, gamma, inertia, b) -> sp.Matrix:
    r"""eq:motion-velocity3D (line 163): the difference of the two sides of
    ``\I ( \dot \Omega) =  \I(\Omega)  \times \Omega -b \gamma \times (\dot \Omega \times \gamma).``"""
    lhs = inertia * Omega_dot
    rhs = (inertia * Omega).cross(Omega) - b * gamma.cross(Omega_dot.cross(gamma))
    return lhs - rhs


def det_L_3d(gamma, inertia, b) -> sp.Expr:
    r"""S2.1:detL3D (line 169): ``\det (L_\gamma)  = c\left ( 1- b \langle {\tilde \I}^{-1}\gamma,
    \gamma \rangle \right )>0`` with ``{\tilde \I}:= \I+b\mbox{Id}_3`` and
    ``c=\prod_{j=1}^3(I_j+b)=\det ({\tilde \I})``."""
    tilde = inertia + b * sp.eye(3)
    c = tilde.det()
    return c * (1 - b * _dot(tilde.inv() * gamma, gamma))


def inverse_L_3d(M, gamma, inertia, b) -> sp.Matrix:
    r"""eq:invL3D (line 176): ``\Omega= L_\gamma^{-1}(M)={\tilde \I}^{-1}M + \frac{ bc \langle
    {\tilde \I}^{-1} M , \gamma\rangle }{ \det (L_\gamma) }\tilde{\I}^{-1}\gamma.``
    Here $\det(L_\gamma)$ is taken as printed in S2.1:detL3D."""
    tilde_inv = (inertia + b * sp.eye(3)).inv()
    c = (inertia + b * sp.eye(3)).det()
    return tilde_inv * M + b * c * _dot(tilde_inv * M, gamma) / det_L_3d(gamma, inertia, b) \
        * tilde_inv * gamma


def integrals_3d(M, gamma, Omega) -> dict[str, sp.Expr]:
    r"""S2.1:integrals3D (lines 185 and 187): ``f_1= \langle M,\gamma \rangle, \qquad f_2=\| M \|^2``
    and ``H=\frac{1}{2}\langle M,\Omega \rangle``."""
    return {"f1": _dot(M, gamma), "f2": _dot(M, M), "H": _dot(M, Omega) / 2}


def measure_3d_exponents() -> dict[str, sp.Rational]:
    r"""S2.1:measure3D (line 189): ``\mu = \frac{1}{ \sqrt{\det  (L_\gamma) }} \, dM\, d\gamma =
    \sqrt{\det  (L_\gamma) } \, d\Omega\, d\gamma`` — the powers of $\det L_\gamma$ in front of
    $dM\,d\gamma$ and of $d\Omega\,d\gamma$."""
    return {"dM dgamma": sp.Rational(-1, 2), "dOmega dgamma": sp.Rational(1, 2)}


def motion_velocity_nd_residual(Omega, Omega_dot, gamma, inertia_operator, b) -> sp.Matrix:
    r"""eq:motion-velocitynD (line 232): the difference of the two sides of
    ``\I ( \dot \Omega) = [ \I(\Omega) , \Omega]  -b  (\dot \Omega \gamma)\wedge \gamma.``
    ``inertia_operator`` is the map $\Omega \mapsto \mathbb{I}(\Omega)$."""
    lhs = inertia_operator(Omega_dot)
    rhs = commutator(inertia_operator(Omega), Omega) - b * wedge(Omega_dot * gamma, gamma)
    return lhs - rhs


def iso_spectral_rhs(M, gamma, Omega, sigma) -> sp.Matrix:
    r"""eq:iso-spectral (line 247): the right side of ``\frac{d}{dt} (M+\sigma \gamma \gamma^t)=
    \left [ M+\sigma \gamma \gamma^t, \Omega \right ].``"""
    A = M + sigma * gamma * gamma.T
    return commutator(A, Omega)


def characteristic_polynomial(M, gamma, sigma, lam) -> sp.Expr:
    r"""eq:pol-first-integrals (line 252): ``p(\lambda, \sigma) = \det ( M+\sigma \gamma \gamma^t -
    \lambda \mbox{Id}_n)``; its coefficients in $(\lambda, \sigma)$ are claimed first integrals."""
    n = gamma.rows
    return (M + sigma * gamma * gamma.T - lam * sp.eye(n)).det(method="berkowitz")


def energy_nd(M, Omega) -> sp.Expr:
    r"""S2.2:energy (lines 257-260): ``H=\frac{1}{2} \langle M, \Omega \rangle_\kappa`` with
    ``\langle \xi_1, \xi_2 \rangle_\kappa = -\frac{1}{2}\mbox{tr}(\xi_1\xi_2)``."""
    return killing(M, Omega) / 2


def measure_nd_exponents() -> dict[str, sp.Rational]:
    r"""eq:invmeasuredet (line 266): ``\mu = \frac{1}{ \sqrt{\det  (L_\gamma) }} \, dMd\gamma=
    \sqrt{\det  (L_\gamma) } \, d\Omega\, d\gamma .`` (general diagonal $\mathbb{J}$)."""
    return {"dM dgamma": sp.Rational(-1, 2), "dOmega dgamma": sp.Rational(1, 2)}
