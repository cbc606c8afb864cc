r"""Vertical momentum for the axisymmetric sphere (Section 4.3-4.4): $\mathcal{V}$, $\zeta$, $\chi$, 3D.

* $\mathcal{V} = \{M\gamma = 0\}$ (eq:def-H-V). On the sphere every point of $\mathcal{V}$ is
  $M = P A P$ with $P = \mathrm{Id} - \gamma\gamma^T$ and $A \in \mathfrak{so}(n)$ (take $A = M$):
  :func:`vertical_point` is a polynomial parametrisation of $\mathcal{V}$.
* $\zeta$ (Th:Re) is *derived* from what a relative equilibrium needs: a $\zeta \in
  \mathfrak{so}(n-1)$ ($\zeta E_n = 0$) with $[\zeta, M_0] = [M_0, \Omega_0]$ and $\zeta\gamma_0 =
  -\Omega_0\gamma_0$. Any $\zeta = -\Omega_0 + \kappa M_0$ meets the last two on $\mathcal{V}$;
  $\zeta E_n = 0$ fixes $\kappa(x_0)$, solved for in :func:`zeta_coefficient`.
* $\chi$ (eq:solManakov) is derived the same way for the rigid body $\tilde{\mathbb{I}} =
  \mathbb{I} + b\,\mathrm{Id}$ (eq:Manakov): $\chi = -\Omega_0 + \tilde\kappa\,\tilde{\mathbb{I}}(\Omega_0)$,
  $\chi E_n = 0$ fixes $\tilde\kappa$ (:func:`chi_coefficient`).
* 3D (eq:xiV3D): the Euler top $\tilde{\mathbb{I}}\dot\Omega = (\tilde{\mathbb{I}}\Omega)\times\Omega$
  with $\tilde{\mathbb{I}}$ obtained from eq:axisymm through the hat map, and its rotating solution
  $\Omega(t) = e^{\zeta t}\Omega_0$ with $\zeta = \hat z$, $z = z_3 E_3$ solved for.
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp
from chaplygin_nd.symbolic.algebra import hat, skew_symbols, unhat, vector_symbols
from chaplygin_nd.symbolic.axisym_inverse import inverse_closed_form
from chaplygin_nd.symbolic.axisymmetric import E_n, a, b, inertia_axisym, x

__all__ = [
    "vertical_point", "zeta_coefficient", "zeta", "inertia_tilde", "chi_coefficient", "chi",
    "inertia_matrix_3d", "euler_rhs_3d", "zeta_3d_coefficient", "zeta_3d",
]


def vertical_point(A: sp.Matrix, gamma: sp.Matrix) -> sp.Matrix:
    r"""$M = PAP$, $P = \mathrm{Id} - \gamma\gamma^T$: a point of $\mathcal{V} = \{M\gamma = 0\}$
    (eq:def-H-V) for $\gamma \in S^{n-1}$; every point of $\mathcal{V}$ arises (take $A = M$)."""
    P = sp.eye(gamma.rows) - gamma * gamma.T
    return P * A * P


def _frame_vertical_point(n: int):
    """Generic symbolic point of V in the frame gamma = (0, .., 0, s, x), s^2 = 1 - x^2."""
    s = sp.Symbol("s", positive=True)
    gamma = sp.Matrix([0] * (n - 2) + [s, x])
    M0 = vertical_point(skew_symbols("A", n), gamma).applyfunc(
        lambda t: sp.expand(t).subs(s**2, 1 - x**2))
    return s, gamma, M0


def _solve_scalar(equations, unknown, s):
    """The unique value of ``unknown`` making every expression vanish modulo s^2 = 1 - x^2."""
    nums = []
    for e in equations:
        num = sp.expand(sp.numer(sp.together(sp.expand(e))))
        num = sp.expand(num.subs(s**2, 1 - x**2))  # s appears to low degree here
        if num != 0:
            nums.append(num)
    sol = sp.solve(nums[:1], unknown, dict=True)
    if len(sol) != 1:
        raise ArithmeticError(f"no unique {unknown}")
    value = sp.factor(sol[0][unknown])
    for num in nums[1:]:  # the same value must solve every other equation
        if sp.expand(sp.numer(sp.together(num.subs(unknown, value))).subs(s**2, 1 - x**2)) != 0:
            raise ArithmeticError(f"{unknown} not consistent")
    return value


@lru_cache(maxsize=1)
def zeta_coefficient() -> sp.Expr:
    r"""$\kappa(x)$ with $(\kappa M_0 - \Omega_0) E_n = 0$ on $\mathcal{V}$, $\Omega_0 = L_\gamma^{-1}M_0$
    (Th:Re), solved at a generic symbolic point of $\mathcal{V} \subset \mathfrak{so}(4)\times S^3$."""
    kappa = sp.Symbol("kappa")
    s, gamma, M0 = _frame_vertical_point(4)
    Omega0 = inverse_closed_form(M0, gamma)
    residual = (kappa * M0 - Omega0) * E_n(4)
    return _solve_scalar(list(residual), kappa, s)


def zeta(M0: sp.Matrix, gamma0: sp.Matrix, a_=a, b_=b) -> sp.Matrix:
    r"""The velocity $\zeta = \kappa(x_0) M_0 - L_{\gamma_0}^{-1}(M_0) \in \mathfrak{so}(n-1)$ of the
    relative equilibrium through $(M_0, \gamma_0) \in \mathcal{V}$ (Th:Re); $n \ge 3$."""
    kappa = zeta_coefficient().xreplace({a: a_, b: b_, x: gamma0[gamma0.rows - 1]})
    return kappa * M0 - inverse_closed_form(M0, gamma0, a_, b_)


def inertia_tilde(Omega: sp.Matrix, a_=a, b_=b) -> sp.Matrix:
    r"""$\tilde{\mathbb{I}}(\Omega) = \mathbb{I}(\Omega) + b\,\Omega$ with $\mathbb{I}$ of eq:axisymm
    (the inertia tensor of eq:Manakov; compare eq:itildendim)."""
    return inertia_axisym(Omega, a_) + b_ * Omega


@lru_cache(maxsize=1)
def chi_coefficient() -> sp.Expr:
    r"""$\tilde\kappa$ with $(\tilde\kappa\,\tilde{\mathbb{I}}(\Omega_0) - \Omega_0)E_n = 0$ for every
    $\Omega_0 \in \mathfrak{so}(4)$ (eq:solManakov)."""
    kt = sp.Symbol("kappa_t")
    Omega0 = skew_symbols("w", 4)
    residual = (kt * inertia_tilde(Omega0) - Omega0) * E_n(4)
    return _solve_scalar(list(residual), kt, sp.Symbol("s", positive=True))


def chi(Omega0: sp.Matrix, a_=a, b_=b) -> sp.Matrix:
    r"""$\chi = \tilde\kappa\,\tilde{\mathbb{I}}(\Omega_0) - \Omega_0 \in \mathfrak{so}(n-1)$, the velocity
    of the relative equilibrium of eq:Manakov through $(\Omega_0, \gamma_0) \in \mathcal{V}$ (eq:solManakov)."""
    kt = chi_coefficient().subs({a: a_, b: b_}, simultaneous=True)
    return kt * inertia_tilde(Omega0, a_, b_) - Omega0


def inertia_matrix_3d(a_=a) -> sp.Matrix:
    r"""The $3\times 3$ inertia matrix $\mathbb{I}$ with $\mathbb{I}(\hat w) = \widehat{\mathbb{I}w}$
    for $\mathbb{J}$ of eq:axisymm, $n = 3$: column $k$ is $\mathbb{I}E_k$."""
    cols = [unhat(inertia_axisym(hat(sp.eye(3)[:, k]), a_)) for k in range(3)]
    return sp.Matrix.hstack(*cols)


def euler_rhs_3d(Omega: sp.Matrix, a_=a, b_=b) -> sp.Matrix:
    r"""$\dot\Omega = \tilde{\mathbb{I}}^{-1}\big((\tilde{\mathbb{I}}\Omega)\times\Omega\big)$,
    $\tilde{\mathbb{I}} = \mathbb{I} + b\,\mathrm{Id}_3$ (eq:vert-3D with eq:axisymm); $\Omega \in \mathbb{R}^3$."""
    It = inertia_matrix_3d(a_) + b_ * sp.eye(3)
    return It.LUsolve((It * Omega).cross(Omega))


@lru_cache(maxsize=1)
def zeta_3d_coefficient() -> sp.Expr:
    r"""$c$ with $z = c\,\Omega_3 E_3$ and $z \times \Omega = $ :func:`euler_rhs_3d` for all $\Omega$
    (eq:xiV3D): the rotation rate of the 3D vertical solution per unit $\Omega_3$."""
    c = sp.Symbol("c")
    W = vector_symbols("W", 3)
    z = sp.Matrix([0, 0, c * W[2]])
    residual = z.cross(W) - euler_rhs_3d(W)
    return _solve_scalar(list(residual), c, sp.Symbol("s", positive=True))


def zeta_3d(Omega0: sp.Matrix, a_=a, b_=b) -> sp.Matrix:
    r"""$\zeta = \hat z$, $z = c\,\bar\Omega_3 E_3$: $\Omega(t) = e^{\zeta t}\Omega_0$ solves eq:vert-3D
    (eq:xiV3D); $\Omega_0 \in \mathbb{R}^3$."""
    c = zeta_3d_coefficient().subs({a: a_, b: b_}, simultaneous=True)
    return hat([0, 0, c * Omega0[2]])
