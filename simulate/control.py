r"""The control system of the frequency evidence: the $n$-dimensional Chaplygin sphere with a
*generic* (non-axisymmetric) diagonal mass tensor $\mathbb{J} = \mathrm{diag}(J_1, \dots, J_n)$.

Same equations eq:motion-general, same inertia operator eq:Inertia $\mathbb{I}(\Omega) = \mathbb{J}\Omega +
\Omega\mathbb{J}$ and the same $L_\gamma(\Omega) = \mathbb{I}(\Omega) + b(\Omega\gamma)\wedge\gamma$ (eq:M-O) as
the axisymmetric sphere; only $\mathbb{J}$ differs. Why it is a control. For $n = 4$ the phase space
$\mathfrak{so}(4)\times S^3$ has dimension 9; the known integrals are $H$ and the coefficients of
$p(\lambda, \sigma)$ (eq:pol-first-integrals: $F_1, F_2, F_3$), 4 in all, plus the invariant measure
(eq:invmeasuredet). The Euler–Jacobi theorem would need 7. The axisymmetric case gets its
integrability from the $SO(3)$ symmetry, which a generic $\mathbb{J}$ destroys, and no further
integral is known. So the level sets have dimension 5 and nothing forces quasi-periodicity. (For
$n = 3$ the general-$\mathbb{J}$ sphere is Chaplygin's integrable case: not a control.) Whether its
orbits are actually irregular is *measured* (frequency diffusion), not assumed.

$L_\gamma^{-1}$ has no closed form here; it is a batched linear solve of the matrix of $L_\gamma$ in the
basis $e_{ij} = E_i\wedge E_j$ ($i < j$), assembled from the definition above. Nothing derived is
written by hand.
"""

from __future__ import annotations

import numpy as np
from chaplygin_nd.simulate import so
from chaplygin_nd.simulate.dispatch import Kernels

__all__ = ["general_inertia_kernels", "L_gamma_general"]


def L_gamma_general(Omega: np.ndarray, gamma: np.ndarray, J: np.ndarray, b: float) -> np.ndarray:
    r"""$L_\gamma(\Omega) = \mathbb{J}\Omega + \Omega\mathbb{J} + b(\Omega\gamma)\wedge\gamma$ (eq:M-O, eq:Inertia),
    batched; ``J`` the diagonal of $\mathbb{J}$. Domain: $\Omega$ skew, any $\gamma$."""
    Jm = np.diag(np.asarray(J, dtype=float))
    Og = np.einsum("...ij,...j->...i", Omega, gamma)
    return Jm @ Omega + Omega @ Jm + b * so.wedge(Og, gamma)


def general_inertia_kernels(J, b: float) -> Kernels:
    r"""A :class:`simulate.dispatch.Kernels` whose ``angular_velocity(M, gamma, a, b)`` solves
    $L_\gamma(\Omega) = M$ for the diagonal mass tensor ``J`` (the ``a`` argument is ignored: $\mathbb{J}$
    is fixed here). Domain: $J_i > 0$, $b > 0$, $\|\gamma\| = 1$ ($L_\gamma$ is then positive definite)."""
    J = np.asarray(J, dtype=float)
    n = len(J)
    basis = so.unvec(np.eye(so.so_dim(n)), n)  # (N, n, n)

    def angular_velocity(M, gamma, a_ignored, b_ignored):
        lead = M.shape[:-2]
        gs = gamma.reshape(-1, 1, n)
        cols = L_gamma_general(basis[None], gs, J, b)          # (count, N, n, n)
        L = np.swapaxes(so.vec(cols), -1, -2)                  # columns = images of e_ij
        w = np.linalg.solve(L, so.vec(M.reshape(-1, n, n))[..., None])[..., 0]
        return so.unvec(w, n).reshape(lead + (n, n))

    return Kernels(name=f"general J = diag{tuple(float(j) for j in J)} (control)",
                   angular_velocity=angular_velocity, note="linear solve of eq:M-O")
