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
from chaplygin_nd.symbolic.algebra import commutator, unvec, vec, wedge
from chaplygin_nd.symbolic.mass_operator import L_entries, L_matrix_qq
from sympy.polys.domains import QQ
from sympy.polys.matrices import DomainMatrix

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
    $\mathfrak{so}(n)$ (column $c$ = coordinates of $L_\gamma$ of basis element $c$). Symmetric.

    Assembled entrywise from $\mathbb{I}(E_i\wedge E_j) = (J_i + J_j)E_i\wedge E_j$ and
    $((E_i\wedge E_j)\gamma)\wedge\gamma = \gamma_j E_i\wedge\gamma - \gamma_i E_j\wedge\gamma$
    (a test compares it with ``vec(L_gamma(basis element))``)."""
    rows = L_entries(list(gamma), list(J.diagonal()), b, sp.Integer(0), sp.Integer(1))
    return sp.Matrix(rows)


def L_matrix_derivative(gamma: sp.Matrix, b, k: int) -> sp.Matrix:
    r"""$\partial L_\gamma / \partial \gamma_k$ in the same basis (derivative of eq:M-O in $\gamma$)."""
    rows = L_entries(list(gamma), [0] * gamma.rows, b, sp.Integer(0), sp.Integer(1), k)
    return sp.Matrix(rows)


def angular_velocity(M: sp.Matrix, gamma: sp.Matrix, J: sp.Matrix, b) -> sp.Matrix:
    r"""$\Omega = L_\gamma^{-1}(M)$ by an exact linear solve of eq:M-O in $\mathfrak{so}(n)$.

    At exact rational points (any $n$) the solve is over $\mathbb{Q}$ with ``DomainMatrix``, or
    with FLINT's ``fmpq_mat`` inside ``flint_engine.use_engine("flint")``; for
    symbolic entries (small $n$) with SymPy. Raises if $L_\gamma$ is singular at the point."""
    n = gamma.rows
    rhs = vec(M)
    if all(sp.sympify(e).is_Rational for e in list(gamma) + list(J.diagonal()) + [b] + list(rhs)):
        from chaplygin_nd.symbolic.exact import flint_engine  # the engine of this evaluation
        flint_engine.note_call()
        if flint_engine.current_engine() == "flint":
            from chaplygin_nd.symbolic.flint_model import angular_velocity_fmpq
            return angular_velocity_fmpq(M, gamma, J, b)
        dL = L_matrix_qq(gamma, J, b)
        col = DomainMatrix([[QQ.from_sympy(e)] for e in rhs], (len(rhs), 1), QQ).to_sparse()
        return unvec(dL.lu_solve(col).to_Matrix(), n)
    return unvec(L_matrix(gamma, J, b).LUsolve(rhs), n)


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
