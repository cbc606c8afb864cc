r"""The Chaplygin sphere from its definitions (Section 2), for a general diagonal mass tensor.

$n$-dimensional model (Section 2.2), on $P = \mathfrak{so}(n) \times S^{n-1}$:

.. math::
    \dot M = [M, \Omega], \quad \dot\gamma = -\Omega\gamma \quad \text{(eq:motion-general)}, \qquad
    M = L_\gamma(\Omega) = \mathbb{I}(\Omega) + b(\Omega\gamma)\wedge\gamma \quad \text{(eq:M-O)}, \qquad
    \mathbb{I}(\Omega) = \mathbb{J}\Omega + \Omega\mathbb{J} \quad \text{(eq:Inertia)}.

Classical model (Section 2.1), on $\mathbb{R}^3 \times S^2$:

.. math::
    \dot M = M \times \Omega, \quad \dot\gamma = \gamma\times\Omega \quad \text{(eq:motion3D)}, \qquad
    M = \mathbb{I}\Omega + b\,\gamma\times(\Omega\times\gamma) \quad \text{(eq:mom3D)}.

$\Omega = L_\gamma^{-1}(M)$ is obtained here only by an exact linear solve of the definition in
the basis :func:`symbolic.algebra.so_basis` — never from a printed inverse.
"""

from __future__ import annotations

import sympy as sp

from symbolic.algebra import commutator, so_basis, unvec, vec, wedge

__all__ = [
    "mass_tensor_symbols", "inertia_operator", "L_gamma", "L_matrix", "L_matrix_derivative",
    "angular_velocity", "motion", "mom3d", "motion3d", "cross",
]


def mass_tensor_symbols(n: int, name: str = "J") -> sp.Matrix:
    r"""A generic diagonal mass tensor $\mathbb{J} = \operatorname{diag}(J_1, \dots, J_n)$ (eq:Inertia)."""
    return sp.diag(*sp.symbols(f"{name}1:{n + 1}", positive=True))


def inertia_operator(Omega: sp.Matrix, J: sp.Matrix) -> sp.Matrix:
    r"""$\mathbb{I}(\Omega) = \mathbb{J}\Omega + \Omega\mathbb{J}$ (eq:Inertia); $\Omega \in \mathfrak{so}(n)$, $\mathbb{J}$ symmetric."""
    return J * Omega + Omega * J


def L_gamma(Omega: sp.Matrix, gamma: sp.Matrix, J: sp.Matrix, b) -> sp.Matrix:
    r"""$L_\gamma(\Omega) = \mathbb{I}(\Omega) + b(\Omega\gamma)\wedge\gamma$ (eq:M-O); any $\gamma \in \mathbb{R}^n$."""
    return inertia_operator(Omega, J) + b * wedge(Omega * gamma, gamma)


def L_matrix(gamma: sp.Matrix, J: sp.Matrix, b) -> sp.Matrix:
    r"""The matrix of $L_\gamma$ (eq:M-O) in the Killing-orthonormal basis $E_i\wedge E_j$ of
    $\mathfrak{so}(n)$: column $c$ is ``vec(L_gamma(basis[c]))``. Symmetric (self-adjoint $L_\gamma$)."""
    n = gamma.rows
    return sp.Matrix.hstack(*[vec(L_gamma(B, gamma, J, b)) for B in so_basis(n)])


def L_matrix_derivative(gamma: sp.Matrix, b, k: int) -> sp.Matrix:
    r"""$\partial L_\gamma / \partial \gamma_k$ in the same basis: $\Omega \mapsto
    b\big((\Omega E_k)\wedge\gamma + (\Omega\gamma)\wedge E_k\big)$ (derivative of eq:M-O)."""
    n = gamma.rows
    e = sp.zeros(n, 1)
    e[k] = 1
    cols = [vec(b * (wedge(B * e, gamma) + wedge(B * gamma, e))) for B in so_basis(n)]
    return sp.Matrix.hstack(*cols)


def angular_velocity(M: sp.Matrix, gamma: sp.Matrix, J: sp.Matrix, b) -> sp.Matrix:
    r"""$\Omega = L_\gamma^{-1}(M)$ by an exact linear solve of eq:M-O in $\mathfrak{so}(n)$.

    Meant for exact rational points (any $n$) or small symbolic $n$; raises if $L_\gamma$ is
    singular at the point."""
    n = gamma.rows
    return unvec(L_matrix(gamma, J, b).LUsolve(vec(M)), n)


def motion(M: sp.Matrix, gamma: sp.Matrix, Omega: sp.Matrix) -> tuple[sp.Matrix, sp.Matrix]:
    r"""$(\dot M, \dot\gamma) = ([M, \Omega], -\Omega\gamma)$ (eq:motion-general)."""
    return commutator(M, Omega), -Omega * gamma


def cross(u: sp.Matrix, v: sp.Matrix) -> sp.Matrix:
    r"""The cross product $u \times v$ in $\mathbb{R}^3$."""
    return u.cross(v)


def mom3d(Omega: sp.Matrix, gamma: sp.Matrix, inertia: sp.Matrix, b) -> sp.Matrix:
    r"""$M = \mathbb{I}\Omega + b\,\gamma\times(\Omega\times\gamma)$ (eq:mom3D); $\mathbb{I}$ a 3x3 matrix."""
    return inertia * Omega + b * cross(gamma, cross(Omega, gamma))


def motion3d(M: sp.Matrix, gamma: sp.Matrix, Omega: sp.Matrix) -> tuple[sp.Matrix, sp.Matrix]:
    r"""$(\dot M, \dot\gamma) = (M\times\Omega, \gamma\times\Omega)$ (eq:motion3D)."""
    return cross(M, Omega), cross(gamma, Omega)
