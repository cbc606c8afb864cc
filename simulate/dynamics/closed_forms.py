r"""Closed-form solutions: relative equilibria $t\mapsto e^{Xt}\cdot(M_0, \gamma_0)$ and their reconstruction.

Three models of the planner are one formula with a different velocity $X \in \mathfrak{so}(n)$:

* vertical momentum, $M_0\gamma_0 = 0$ (Th:Re): $X = \zeta$ from the generated kernel;
* steady rotation, $n = 4$, $\eta_0\times\xi_0 = 0$ (P:steady-rot), and the spherical case $a = 0$
  ($\dot\Omega = 0$, Section 4 after eq:M-O-axi-symm): $X = -\Omega_0$.

.. math::
    M(t) = e^{Xt}M_0e^{-Xt},\quad \gamma(t) = e^{Xt}\gamma_0,\quad \Omega(t) = e^{Xt}\Omega_0e^{-Xt}.

Reconstruction (our derivation; convention and derivation in :mod:`simulate.dynamics.field`: $\gamma = g^TE_n$,
$\dot g = g\Omega$, $\dot c = r\,g\Omega\gamma$). With $W := \Omega_0 + X$,

.. math::
    g(t) = g_0\,e^{Wt}e^{-Xt}, \qquad c(t) = c_0 + r\,g_0\int_0^t e^{Ws}\,ds\;\Omega_0\gamma_0 .

Proof: $\dot g = g_0e^{Wt}(W - X)e^{-Xt} = g_0e^{Wt}e^{-Xt}\,e^{Xt}\Omega_0e^{-Xt} = g\,\Omega(t)$, and
$g\Omega\gamma = g_0e^{Wt}\Omega_0e^{-Xt}e^{Xt}\gamma_0 = g_0e^{Wt}\Omega_0\gamma_0$. Consistency
$g(t)^TE_n = \gamma(t)$ needs $W\gamma_0 = 0$: true for $X = -\Omega_0$, and for $X = \zeta$ by Th:Re
($\zeta\gamma_0 = -\Omega_0\gamma_0$). For $X = -\Omega_0$: $W = 0$, $g = g_0e^{\Omega_0t}$ and the contact
point moves on a straight line, $c(t) = c_0 + rt\,g_0\Omega_0\gamma_0$.

Horizontal momentum, $n = 4$, reduced invariants only (S5:H-linear, corrected; eq:A-on-J;
S5:H-SO3): $(x(t), G(t))$ and $A(x, G; h)$ come from :mod:`generated` (with $F_2, H$ from the
reduced integrals at $t = 0$); the remaining invariants follow from the equations that define
$\mathcal H/SO(3)$ (row S5:H-SO3, verdict holds) and from $F_2 = A + B$ (S5:red-integrals):
$E = F_1 = 0$, $\delta = -xA$, $B = F_2 - A$.

Horizontal momentum, any $n \ge 3$ (S5:H-linear-nD): $x(t)$, $G(t)$ from the same kernel with
$x_0 = \gamma_{0,n}$, $G_0 = \langle M_0E_n, \gamma_0\rangle$, $F_2 = \lVert M_0\rVert_\kappa^2$,
$H = \tfrac12\langle M_0, \Omega_0\rangle_\kappa$ (definitions, evaluated once at $t = 0$), and the
blocks $A = \lVert M - (ME_n)\wedge E_n\rVert_\kappa^2$, $B = \lVert ME_n\rVert^2$ from the generated
``horizontal_blocks``. Nothing else of $(M, \gamma)$ is determined by $(x, G)$: the output is
$(x, G, A, B)$.
"""

from __future__ import annotations

import numpy as np
from chaplygin_nd.simulate.dynamics import so
from chaplygin_nd.simulate.kernels import active

__all__ = ["relative_equilibrium", "horizontal", "horizontal_invariants", "horizontal_nd"]


def relative_equilibrium(X: np.ndarray, M0: np.ndarray, gamma0: np.ndarray, Omega0: np.ndarray,
                         t: np.ndarray, g0: np.ndarray | None = None, radius: float = 1.0
                         ) -> dict[str, np.ndarray]:
    r"""The solution through one point $(M_0, \gamma_0)$, $\Omega_0 = L_{\gamma_0}^{-1}M_0$, with velocity
    ``X`` (Th:Re: $X = \zeta$; P:steady-rot and $a = 0$: $X = -\Omega_0$), sampled at ``t``.
    Returns arrays ``M, Omega (S, n, n)``, ``gamma (S, n)``, and with ``g0`` also
    ``g (S, n, n)``, ``c (S, n)`` ($c_0 = 0$). Domain: $X\gamma_0 = -\Omega_0\gamma_0$, $X E_n = 0$
    or $X = -\Omega_0$ (not checked here: the planner only calls it on such points)."""
    E = so.expm_skew_t(X, t)
    Et = np.swapaxes(E, -1, -2)
    out = {"M": E @ M0 @ Et, "gamma": E @ gamma0, "Omega": E @ Omega0 @ Et}
    if g0 is not None:
        W = Omega0 + X
        out["g"] = g0 @ so.expm_skew_t(W, t) @ Et
        out["c"] = radius * (so.expm_integral(W, Omega0 @ gamma0, t) @ g0.T)
    return out


def horizontal(r0: np.ndarray, a: float, b: float, t: np.ndarray) -> np.ndarray:
    r"""$r(t) = (A, B, E, G, F_1, x, \delta)(t)$ on $\mathcal H/SO(3)$ from $r_0$ (``(count, 7)``), sampled at
    ``t``; shape ``(S, count, 7)``. Domain: $n = 4$, $(M_0, \gamma_0)\in\mathcal H$, $|x| < 1$ along
    the motion (S5:H-linear, eq:A-on-J, S5:H-SO3; see the module docstring)."""
    k = active()
    F = k.require("reduced_integrals")(r0, a, b)
    F2, H = F[..., 1], F[..., 3]
    xG = k.require("horizontal")(r0[..., 5], r0[..., 3], F2, H, a, b, t[:, None])
    x, G = xG[..., 0], xG[..., 1]
    A = k.require("horizontal_A")(x, G, H, a, b)[..., 0]
    zero = np.zeros_like(x)
    return np.stack([A, F2 - A, zero, G, zero, x, -x * A], axis=-1)


def horizontal_invariants(M: np.ndarray, gamma: np.ndarray) -> np.ndarray:
    r"""$(x, G, A, B)$ of $(M, \gamma)$ by their definitions (S5:H-linear-nD): $x = \gamma_n$,
    $G = \langle ME_n, \gamma\rangle$, $A = \lVert M - (ME_n)\wedge E_n\rVert_\kappa^2$,
    $B = \lVert ME_n\rVert^2$; any $n$, batched (``(..., n, n)``, ``(..., n)`` -> ``(..., 4)``)."""
    Me = M[..., :, -1]
    G = np.einsum("...i,...i->...", Me, gamma)
    B = np.einsum("...i,...i->...", Me, Me)
    A = so.killing(M, M) - B
    return np.stack([gamma[..., -1], G, A, B], axis=-1)


def horizontal_nd(M0: np.ndarray, gamma0: np.ndarray, Omega0: np.ndarray, a: float, b: float,
                  t: np.ndarray) -> np.ndarray:
    r"""$(x, G, A, B)(t)$ on $\mathcal H$ for any $n \ge 3$ from ``(count, n, n)``, ``(count, n)`` initial
    conditions, sampled at ``t``; shape ``(S, count, 4)``. Domain: $(M_0, \gamma_0)\in\mathcal H$,
    $\Omega_0 = L_{\gamma_0}^{-1}M_0$ (S5:H-linear-nD; see the module docstring)."""
    k = active()
    x0, G0 = gamma0[..., -1], np.einsum("...i,...i->...", M0[..., :, -1], gamma0)
    F2, H = so.killing(M0, M0), 0.5 * so.killing(M0, Omega0)
    xG = k.require("horizontal")(x0, G0, F2, H, a, b, t[:, None])
    x, G = xG[..., 0], xG[..., 1]
    AB = k.require("horizontal_blocks")(x, G, np.broadcast_to(F2, x.shape))
    return np.stack([x, G, AB[..., 0], AB[..., 1]], axis=-1)
