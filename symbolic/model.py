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
from sympy.polys.domains import QQ
from sympy.polys.matrices import DomainMatrix

__all__ = [
    "mass_tensor_symbols", "inertia_operator", "L_gamma", "L_matrix", "L_matrix_derivative", "L_matrix_qq",
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


def _pairs(n: int) -> list[tuple[int, int]]:
    return [(i, j) for i in range(n) for j in range(i + 1, n)]


def _wedge_coordinate(u, v, k: int, l: int):
    return u[k] * v[l] - u[l] * v[k]


def _L_entries(gamma, Jdiag, b, zero, one, derivative: int | None = None):
    r"""Rows of the matrix of $L_\gamma$ (or of $\partial L_\gamma/\partial\gamma_m$) with entries
    computed in the arithmetic of the inputs (SymPy expressions or QQ elements)."""
    n = len(gamma)
    pairs = _pairs(n)

    def d(p, q):  # Kronecker delta in the input arithmetic
        return one if p == q else zero

    def g(p):  # gamma_p, or its derivative d gamma_p / d gamma_m
        return gamma[p] if derivative is None else d(p, derivative)

    rows = []
    for k, l in pairs:
        row = []
        for i, j in pairs:
            # coordinate (k, l) of ((E_i ^ E_j) gamma) ^ gamma = gamma_j E_i^gamma - gamma_i E_j^gamma
            if derivative is None:
                entry = gamma[j] * (d(k, i) * gamma[l] - d(l, i) * gamma[k]) \
                    - gamma[i] * (d(k, j) * gamma[l] - d(l, j) * gamma[k])
            else:  # product rule on the two gamma factors
                entry = g(j) * (d(k, i) * gamma[l] - d(l, i) * gamma[k]) \
                    + gamma[j] * (d(k, i) * g(l) - d(l, i) * g(k)) \
                    - g(i) * (d(k, j) * gamma[l] - d(l, j) * gamma[k]) \
                    - gamma[i] * (d(k, j) * g(l) - d(l, j) * g(k))
            entry = b * entry
            if derivative is None and (k, l) == (i, j):
                entry = entry + Jdiag[i] + Jdiag[j]
            row.append(entry)
        rows.append(row)
    return rows


def L_matrix(gamma: sp.Matrix, J: sp.Matrix, b) -> sp.Matrix:
    r"""The matrix of $L_\gamma$ (eq:M-O) in the Killing-orthonormal basis $E_i\wedge E_j$ of
    $\mathfrak{so}(n)$ (column $c$ = coordinates of $L_\gamma$ of basis element $c$). Symmetric.

    Assembled entrywise from $\mathbb{I}(E_i\wedge E_j) = (J_i + J_j)E_i\wedge E_j$ and
    $((E_i\wedge E_j)\gamma)\wedge\gamma = \gamma_j E_i\wedge\gamma - \gamma_i E_j\wedge\gamma$
    (a test compares it with ``vec(L_gamma(basis element))``)."""
    rows = _L_entries(list(gamma), list(J.diagonal()), b, sp.Integer(0), sp.Integer(1))
    return sp.Matrix(rows)


def L_matrix_derivative(gamma: sp.Matrix, b, k: int) -> sp.Matrix:
    r"""$\partial L_\gamma / \partial \gamma_k$ in the same basis (derivative of eq:M-O in $\gamma$)."""
    rows = _L_entries(list(gamma), [0] * gamma.rows, b, sp.Integer(0), sp.Integer(1), k)
    return sp.Matrix(rows)


def L_matrix_qq(gamma: sp.Matrix, J: sp.Matrix, b, derivative: int | None = None) -> DomainMatrix:
    r"""``L_matrix`` (or ``L_matrix_derivative`` for ``derivative = k``) at an exact rational point,
    as a ``DomainMatrix`` over $\mathbb{Q}$ (fast exact linear algebra for large $n$)."""
    conv = QQ.from_sympy
    rows = _L_entries([conv(sp.Rational(x)) for x in gamma],
                      [conv(sp.Rational(x)) for x in J.diagonal()], conv(sp.Rational(b)),
                      QQ.zero, QQ.one, derivative)
    return DomainMatrix(rows, (len(rows), len(rows)), QQ).to_sparse()


def angular_velocity(M: sp.Matrix, gamma: sp.Matrix, J: sp.Matrix, b) -> sp.Matrix:
    r"""$\Omega = L_\gamma^{-1}(M)$ by an exact linear solve of eq:M-O in $\mathfrak{so}(n)$.

    At exact rational points (any $n$) the solve is over $\mathbb{Q}$ with ``DomainMatrix``, or
    with FLINT's ``fmpq_mat`` inside ``flint_engine.use_engine("flint")``; for
    symbolic entries (small $n$) with SymPy. Raises if $L_\gamma$ is singular at the point."""
    n = gamma.rows
    rhs = vec(M)
    if all(sp.sympify(e).is_Rational for e in list(gamma) + list(J.diagonal()) + [b] + list(rhs)):
        from chaplygin_nd.symbolic import flint_engine  # the engine of this evaluation
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
