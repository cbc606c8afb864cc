r"""A physical ball (mass $m$, radius $r$, axisymmetric moments of inertia) as the paper's sphere.

Definitions (Section 2.2, eq:M-O and eq:Inertia, in the units of a real body):

* a body is a finite set of point masses $\mu_k$ at $X_k \in \mathbb{R}^n$ (body frame, origin at
  the geometric centre, which is the centre of mass); a density is the limit of such sums and
  every identity below is linear in the rank-one terms $\mu_k X_kX_k^T$, so it carries over;
* its **mass tensor** is $\mathbb{J} = \sum_k \mu_k X_kX_k^T$ (the second moments about the centre);
  the kinetic energy of the rotation $\dot X = \Omega X$ is $\tfrac12\sum_k\mu_k\|\Omega X_k\|^2 =
  \tfrac12\langle\mathbb{I}(\Omega), \Omega\rangle_\kappa$ with $\mathbb{I}(\Omega) = \mathbb{J}\Omega +
  \Omega\mathbb{J}$ (eq:Inertia), $\langle A, B\rangle_\kappa = -\tfrac12\operatorname{tr}AB$;
* the **moment of inertia in the plane** $(i, j)$ is $\langle\mathbb{I}(E_i\wedge E_j), E_i\wedge
  E_j\rangle_\kappa = J_i + J_j$ (for $n = 3$ the plane $(2,3)$ is the axis $E_1$: $I_1 = J_2 + J_3$);
* for an axisymmetric body $\mathbb{J} = \operatorname{diag}(j_1, \dots, j_1, j_n)$ there are two plane
  moments: $I_1 := j_1 + j_n$ in every plane that contains the axis $E_n$, and $I_n := 2j_1$ in
  every plane orthogonal to it. For $n = 3$ these are the classical principal moments
  $(I_1, I_1, I_3)$ about the axes $E_1, E_2, E_3$;
* rolling without slipping: the centre moves with speed $r\|\Omega\gamma\|$, so the energy is
  $T = \tfrac12\langle\mathbb{I}(\Omega), \Omega\rangle_\kappa + \tfrac12 mr^2\|\Omega\gamma\|^2 =
  \tfrac12\langle L_\gamma(\Omega), \Omega\rangle_\kappa$ with $L_\gamma$ of eq:M-O and $b = mr^2$,
  and $M = L_\gamma(\Omega)$ is its momentum ($L_\gamma$ is $\kappa$-symmetric).

The paper normalises $\mathbb{J} = \mathrm{Id} + aE_nE_n^T$ (eq:axisymm). Dividing the physical
$L_\gamma$ by $s$ gives the paper's; :func:`paper_parameters` *solves*
$\mathbb{J}_{\text{ball}} = s(\mathrm{Id} + aE_nE_n^T)$, $mr^2 = sb$ for $(s, a, b)$. Then
$M_{\text{ball}} = sM$ and $H_{\text{ball}} = sH$, while $\Omega$, $\gamma$ and $t$ are unchanged
(the equations $\dot M = [M, \Omega]$ are homogeneous of degree one in $M$).

Realisability. For a body inside the ball of radius $r$ about its centre, $\mathbb{J}$ is positive
semidefinite ($v^T\mathbb{J}v = \sum\mu_k\langle v, X_k\rangle^2$) and $\operatorname{tr}\mathbb{J} =
\sum_k\mu_k\|X_k\|^2 \le mr^2$. Conversely every diagonal $\mathbb{J} \succeq 0$ with
$\operatorname{tr}\mathbb{J} \le mr^2$ is realised (:func:`witness_body`). In the paper's parameters
($s > 0$): $j_n \ge 0 \iff a \ge -1$ and $mr^2 - \operatorname{tr}\mathbb{J} = s(b - n - a)$, so a
ball exists iff $a \ge -1$ and $b \ge n + a$.
"""

from __future__ import annotations

from collections.abc import Sequence

import sympy as sp
from chaplygin_nd.symbolic.algebra import basis_vector, killing, wedge
from chaplygin_nd.symbolic.model import inertia_operator

__all__ = [
    "m", "r", "I1", "In", "j1", "jn", "mass_tensor_of_points", "kinetic_energy_of_points",
    "plane_moment", "axisymmetric_mass_tensor", "mass_tensor_from_moments", "paper_parameters",
    "trace_slack", "witness_body",
]

#: mass, radius, the two plane moments ($I_1$: planes containing $E_n$; $I_n$: planes orthogonal
#: to $E_n$) and the two entries of the axisymmetric mass tensor.
m, r, I1, In, j1, jn = sp.symbols("m r I_1 I_n j_1 j_n", positive=True)


def mass_tensor_of_points(masses: Sequence, positions: Sequence[sp.Matrix]) -> sp.Matrix:
    r"""$\mathbb{J} = \sum_k \mu_k X_kX_k^T$, the mass tensor of point masses (eq:Inertia's $\mathbb{J}$
    in physical units); positions in the body frame about the centre; any $n$."""
    n = positions[0].rows
    J = sp.zeros(n, n)
    for mu, X in zip(masses, positions, strict=True):
        J += mu * X * X.T
    return J


def kinetic_energy_of_points(masses: Sequence, positions: Sequence[sp.Matrix],
                             Omega: sp.Matrix) -> sp.Expr:
    r"""$\tfrac12\sum_k\mu_k\|\Omega X_k\|^2$, the kinetic energy of the rotation $\dot X = \Omega X$
    about the centre; $\Omega \in \mathfrak{so}(n)$."""
    return sp.Rational(1, 2) * sum(mu * ((Omega * X).T * (Omega * X))[0, 0]
                                   for mu, X in zip(masses, positions, strict=True))


def plane_moment(J: sp.Matrix, i: int, j: int) -> sp.Expr:
    r"""Moment of inertia of the mass tensor $\mathbb{J}$ for rotation in the plane $(E_i, E_j)$
    (0-based): $\langle\mathbb{I}(E_i\wedge E_j), E_i\wedge E_j\rangle_\kappa$, eq:Inertia
    ($E_i\wedge E_j$ has $\kappa$-norm 1)."""
    n = J.rows
    P = wedge(basis_vector(n, i), basis_vector(n, j))
    return sp.expand(killing(inertia_operator(P, J), P))


def axisymmetric_mass_tensor(n: int, j_1=j1, j_n=jn) -> sp.Matrix:
    r"""$\operatorname{diag}(j_1, \dots, j_1, j_n)$: an axisymmetric body with axis $E_n$."""
    return sp.diag(*([j_1] * (n - 1) + [j_n]))


def mass_tensor_from_moments(n: int, I_1=I1, I_n=In) -> sp.Matrix:
    r"""The axisymmetric $\mathbb{J}$ whose plane moments are $I_1$ (plane $(E_1, E_n)$, containing
    the axis) and $I_n$ (plane $(E_1, E_2)$, orthogonal to it): solved from :func:`plane_moment`."""
    J = axisymmetric_mass_tensor(n)
    sol = sp.solve([plane_moment(J, 0, n - 1) - I_1, plane_moment(J, 0, 1) - I_n], [j1, jn],
                   dict=True)
    if len(sol) != 1:
        raise ArithmeticError(f"plane moments do not determine J uniquely: {sol}")
    return J.xreplace(sol[0])


def paper_parameters(n: int, mass=m, radius=r, I_1=I1, I_n=In) -> dict[str, sp.Expr]:
    r"""$(s, a, b)$ with $\mathbb{J}_{\text{ball}} = s(\mathrm{Id}_n + aE_nE_n^T)$ (eq:axisymm) and
    $mr^2 = sb$ (eq:M-O), solved (linear in $s$, $p = as$, $q = bs$) for the ball of
    :func:`mass_tensor_from_moments`; so $L^{\text{ball}}_\gamma = sL_\gamma$."""
    s, p, q = sp.symbols("s p q")
    e = basis_vector(n, n - 1)
    J = mass_tensor_from_moments(n, I_1, I_n)
    eqs = list(J - (s * sp.eye(n) + p * e * e.T)) + [mass * radius**2 - q]
    sol = sp.solve(eqs, [s, p, q], dict=True)
    if len(sol) != 1:
        raise ArithmeticError(f"no unique (s, a, b): {sol}")
    S, P, Q = sol[0][s], sol[0][p], sol[0][q]
    return {"s": sp.factor(S), "a": sp.factor(P / S), "b": sp.factor(Q / S)}


def trace_slack(J: sp.Matrix, mass=m, radius=r) -> sp.Expr:
    r"""$mr^2 - \operatorname{tr}\mathbb{J}$, non-negative for every body inside radius $r$."""
    return mass * radius**2 - J.trace()


def witness_body(diagonal: Sequence, mass, radius) -> tuple[list, list[sp.Matrix]]:
    r"""Point masses inside the closed ball of radius $r$ with centre of mass $0$, total mass $m$
    and mass tensor $\operatorname{diag}(J_1, \dots, J_n)$: $J_i/(2r^2)$ at each of $\pm rE_i$ and
    the rest, $m - \operatorname{tr}\mathbb{J}/r^2 \ge 0$, at the centre. Domain: $J_i \ge 0$,
    $\sum J_i \le mr^2$."""
    n = len(diagonal)
    masses, positions = [], []
    for i, Ji in enumerate(diagonal):
        for sign in (1, -1):
            masses.append(Ji / (2 * radius**2))
            positions.append(sign * radius * basis_vector(n, i))
    masses.append(mass - sum(diagonal) / radius**2)
    positions.append(sp.zeros(n, 1))
    return masses, positions
