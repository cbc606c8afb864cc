r"""Derivations for the classical 3D sphere (Section 2.1) from the definition eq:mom3D.

$L_\gamma$ is read off eq:mom3D as the Jacobian of $\Omega \mapsto \mathbb{I}\Omega +
b\gamma\times(\Omega\times\gamma)$; its inverse is Cramer's rule, $L_\gamma^{-1} =
\operatorname{adj}(L_\gamma)/\det L_\gamma$. Nothing here comes from the printed eq:invL3D.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.symbolic.model import cross, mom3d

__all__ = ["L_gamma_matrix_3d", "angular_velocity_3d", "velocity_field_3d", "tilde_inertia"]


def L_gamma_matrix_3d(gamma: sp.Matrix, inertia: sp.Matrix, b) -> sp.Matrix:
    r"""The matrix of $L_\gamma$ (eq:mom3D): the Jacobian of $M(\Omega)$, which is linear in $\Omega$.
    Any $\gamma \in \mathbb{R}^3$."""
    Omega = sp.Matrix(sp.symbols("_O1:4"))
    return mom3d(Omega, gamma, inertia, b).jacobian(Omega)


def angular_velocity_3d(M: sp.Matrix, gamma: sp.Matrix, inertia: sp.Matrix, b) -> sp.Matrix:
    r"""$\Omega = L_\gamma^{-1}M = \operatorname{adj}(L_\gamma)M/\det L_\gamma$ (inverse of eq:mom3D),
    each entry an expanded polynomial over the expanded determinant; defined where
    $\det L_\gamma \ne 0$ (on $S^2$ with $I_j, b > 0$, see S2.1:detL3D).

    No ``factor()``: multivariate factorisation here took from 3 s to 9 min depending on the
    process's hash seed, which made ``make generate`` slow and unpredictable."""
    L = L_gamma_matrix_3d(gamma, inertia, b)
    adj, det = L.adjugate(), sp.expand(L.det())
    return sp.Matrix([sp.expand((adj * M)[i]) / det for i in range(3)])


def velocity_field_3d(Omega: sp.Matrix, gamma: sp.Matrix, inertia: sp.Matrix, b):
    r"""eq:motion3D in the coordinates $(\Omega, \gamma)$, derived from the definitions only:
    differentiating $M = L_\gamma\Omega$ along $\dot M = M\times\Omega$, $\dot\gamma = \gamma\times\Omega$
    gives $L_\gamma\dot\Omega = M\times\Omega - (\partial_\gamma M)\dot\gamma$. Returns
    ``(numerator, det)`` with $\dot\Omega = \text{numerator}/\det L_\gamma$ (polynomials), and $\dot\gamma$."""
    L = L_gamma_matrix_3d(gamma, inertia, b)
    M = mom3d(Omega, gamma, inertia, b)
    gamma_dot = cross(gamma, Omega)
    rhs = cross(M, Omega) - M.jacobian(gamma) * gamma_dot
    return (L.adjugate() * rhs).expand(), L.det().expand(), gamma_dot


def tilde_inertia(inertia: sp.Matrix, b) -> sp.Matrix:
    r"""$\tilde{\mathbb{I}} = \mathbb{I} + b\,\mathrm{Id}_3$ (Section 2.1)."""
    return inertia + b * sp.eye(3)
