r"""eq:xiV3D — the closed-form vertical solution of the axisymmetric sphere in 3D.

Claims (Section 4.3, "The 3D case", lines 519-571): $\tilde{\mathbb{I}} = \mathrm{diag}(2+a+b,
2+a+b, 2+b)$; eq:vert-3D becomes $\dot\Omega_1 = \frac{a\Omega_2\Omega_3}{2+a+b}$,
$\dot\Omega_2 = -\frac{a\Omega_1\Omega_3}{2+a+b}$, $\dot\Omega_3 = 0$; its solution is
$\hat\Omega(t) = e^{\zeta t}\hat\Omega_0e^{-\zeta t}$ with

.. math::
    \zeta = \frac{-a}{2+a+b}\begin{pmatrix}0 & -\bar\Omega_3 & 0\\ \bar\Omega_3 & 0 & 0\\ 0&0&0\end{pmatrix}
          = \frac{-a}{2+a+b}\big(\hat\Omega_0 - (\hat\Omega_0E_3)\wedge E_3\big);

on $\mathcal{V}$, $\zeta\gamma_0 = -\hat\Omega_0\gamma_0 = \gamma_0\times\Omega_0$, so
$\gamma(t) = e^{\zeta t}\gamma_0$; and $\hat M(t) = e^{\zeta t}\hat M_0e^{-\zeta t}$.

How. :mod:`symbolic.vertical` derives $\tilde{\mathbb{I}}$ from eq:axisymm through the hat map,
writes the Euler equations from eq:vert-3D, and *solves* for the rotation $z = c\,\Omega_3E_3$ with
$z\times\Omega = \dot\Omega$. Each printed item is compared with these exactly (symbolic in
$a, b, \Omega$). On $\mathcal{V}$ (generic symbolic point $M_0 = PAP$, $\Omega_0 = L_\gamma^{-1}M_0$,
modulo $\lVert\gamma\rVert^2 = 1$) we check $\zeta\gamma_0 = -\hat\Omega_0\gamma_0 = \gamma_0\times\Omega_0$,
$\zeta E_3 = 0$ and $[\zeta, \hat M_0] = [\hat M_0, \hat\Omega_0]$: the curve
$(e^{\zeta t}\hat M_0 e^{-\zeta t}, e^{\zeta t}\gamma_0)$ has the velocity of the vector field at
$t = 0$ and, by $SO(2)$-equivariance (eq:action), at every $t$. Only $n = 3$ is concerned.

Uses: P:EulerTop, eq:vert-3D, eq:axisymm, eq:V-velocity, P:inversion, eq:action.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.proofs.s4_common import a, b, generic_vertical, sym_checks
from chaplygin_nd.symbolic.algebra import commutator, unhat, vector_symbols
from chaplygin_nd.symbolic.axisym_inverse import inverse_closed_form
from chaplygin_nd.symbolic.axisymmetric import E_n
from chaplygin_nd.symbolic.exact.identity import rational_identity
from chaplygin_nd.symbolic.printed import section4 as printed
from chaplygin_nd.symbolic.vertical import euler_rhs_3d, inertia_matrix_3d, zeta_3d


def _on_V():
    M0, g = generic_vertical(3)
    W0 = inverse_closed_form(M0, g)  # the matrix hat(Omega_0)
    return M0, g, W0, unhat(W0)


@claim("eq:xiV3D", uses=("P:EulerTop", "eq:vert-3D", "eq:axisymm", "eq:V-velocity", "P:inversion",
                         "eq:action"))
def eq_xiv3d() -> Verdict:
    W = vector_symbols("W", 3)
    It = rational_identity(inertia_matrix_3d(a) + b * sp.eye(3) - printed.Itilde_3d(a, b))
    ode = rational_identity(euler_rhs_3d(W) - printed.euler_3d_rhs(W, a, b))
    z = zeta_3d(W)
    rotation = rational_identity(list(z * W - euler_rhs_3d(W)) + [euler_rhs_3d(W)[2]])
    zeta_forms = rational_identity(list(printed.zeta_3d_matrix(W, a, b) - z)
                                   + list(printed.zeta_3d_wedge(W, a, b) - z))

    def gamma_sol(n):
        M0, g, W0, w0 = _on_V()
        zeta = printed.zeta_3d_wedge(w0, a, b)
        return list(zeta * g + W0 * g) + list(-W0 * g - g.cross(w0))

    def M_sol(n):
        M0, g, W0, w0 = _on_V()
        zeta = printed.zeta_3d_wedge(w0, a, b)
        return list(zeta * E_n(3)) + list(commutator(zeta, M0) - commutator(M0, W0))

    g_chk = sym_checks(gamma_sol, (3,), label="xiV3D-gamma")
    M_chk = sym_checks(M_sol, (3,), label="xiV3D-M")
    return Verdict.of_parts([
        Verdict.decide(It, method="exact: derived (hat map of eq:axisymm) + b Id").as_part(
            "Itilde = diag(2+a+b, 2+a+b, 2+b)"),
        Verdict.decide(ode, method="exact rational identity against Itilde^{-1}((Itilde W) x W)").as_part(
            "the Euler equations for Omega_1, Omega_2, Omega_3"),
        Verdict.decide(rotation, method="exact: hat(z) W = W_dot for all W and W_3 constant").as_part(
            "Omega(t) = exp(zeta t) Omega_0 solves them"),
        Verdict.decide(zeta_forms, method="exact: both printed forms equal the derived zeta").as_part(
            "zeta (both printed forms)"),
        Verdict.decide(g_chk).as_part("zeta gamma_0 = -hat(Omega_0) gamma_0 = gamma_0 x Omega_0 on V"),
        Verdict.decide(M_chk, method=M_chk.method + " + SO(2)-equivariance (eq:action)").as_part(
            "M(t) = exp(zeta t) M_0 exp(-zeta t) (zeta E_3 = 0, velocity at t = 0)"),
    ], n_values=(3,))


