r"""eq:axisymm and eq:M-O-axi-symm — the axisymmetric mass tensor, $L_\gamma$ and the velocity form.

Claims (Section 4, lines 366-383):

.. math::
    \mathbb{J} = \mathrm{Id}_n + aE_nE_n^t \ \text{(eq:axisymm)}, \quad n = 3:\ \mathbb{I} = \mathrm{diag}(2+a, 2+a, 2);

    \mathbb{I}(\Omega) = 2\Omega + a(\Omega E_n)\wedge E_n, \quad
    M = L_\gamma(\Omega) = 2\Omega + a(\Omega E_n)\wedge E_n + b(\Omega\gamma)\wedge\gamma \ \text{(eq:M-O-axi-symm)};

    2\dot\Omega + a(\dot\Omega E_n)\wedge E_n + b(\dot\Omega\gamma)\wedge\gamma = a[(\Omega E_n)\wedge E_n, \Omega],
    \qquad a = 0 \Rightarrow \dot\Omega = 0.

In our words: with the mass tensor of eq:axisymm the general inertia $\mathbb{J}\Omega + \Omega\mathbb{J}$
(eq:Inertia) takes the printed short form; the equation $\dot M = [M, \Omega]$ is equivalent to
the printed equation for $\dot\Omega$; for a spherical body ($a = 0$) the angular velocity is
constant.

How. The derivation (:mod:`symbolic.axisymmetric`) builds $\mathbb{I}$ from $\mathbb{J}$ and
$L_\gamma$ from eq:M-O. The velocity form: differentiating $M = L_\gamma(\Omega)$ along
$\dot\gamma = -\Omega\gamma$ gives $\dot M = L_\gamma(\dot\Omega) + b(\Omega\dot\gamma)\wedge\gamma +
b(\Omega\gamma)\wedge\dot\gamma$; we prove that $\dot M - [M, \Omega]$ *equals* the printed
left-minus-right side identically in $(\dot\Omega, \Omega, \gamma)$, so the two equations are
equivalent. It is quadratic in $\Omega$, so (s4_common) the symbolic checks run to $n = 6$ and cover
every $n$. For $a = 0$ we differentiate the derived closed form of $L_\gamma^{-1}$ along the flow
and get $\dot\Omega \equiv 0$ on $\mathfrak{so}(n)\times S^{n-1}$ (symbolic $n = 3, 4$; linear in the
tangent data, so $n = 4$ covers every $n$).

Uses: eq:Inertia, eq:M-O, eq:motion-general (Section 2); P:inversion (closed form, for $a = 0$).
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.proofs.s4_common import (
    REDUCTION,
    a,
    b,
    combine,
    frame_gamma,
    generic,
    point_checks,
    sym_checks,
)
from chaplygin_nd.symbolic.algebra import commutator, skew_symbols, wedge
from chaplygin_nd.symbolic.axisym_inverse import inverse_closed_form
from chaplygin_nd.symbolic.axisymmetric import L_gamma_axisym, inertia_axisym, mass_tensor
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.exact.identity import rational_identity
from chaplygin_nd.symbolic.printed import section4 as printed
from chaplygin_nd.symbolic.vertical import inertia_matrix_3d


@claim("eq:axisymm", uses=("eq:Inertia",))
def eq_axisymm() -> Verdict:
    """Definition; consistency: printed J equals ours, and the 3D inertia matrix is diag(2+a,2+a,2)."""
    same_J = sym_checks(lambda n: mass_tensor(n, a) - printed.J_axisymm(n, a), (3, 4, 5),
                        sphere=False, label="J")
    inertia3 = rational_identity(inertia_matrix_3d(a) - printed.inertia_3d(a))
    return Verdict.definition(
        "J = Id + a E_n E_n^T (the mass tensor of the axisymmetric body)", n_values=(3, 4, 5),
        consistency=[("printed J", same_J), ("3D inertia diag(2+a,2+a,2) via the hat map", inertia3)],
        notes="Physical range stated: a in [-1, 1]. J > 0 needs only a > -1; the 3D triangle "
              "inequality of (2+a, 2+a, 2) needs a >= -1; nothing in Section 4 needs a <= 1.")


def _velocity_residual_difference(n: int):
    Omega, W = skew_symbols("w", n), skew_symbols("v", n)
    g = frame_gamma(n)
    g_dot = -Omega * g
    M = L_gamma_axisym(Omega, g)
    M_dot = L_gamma_axisym(W, g) + b * wedge(Omega * g_dot, g) + b * wedge(Omega * g, g_dot)
    derived = M_dot - commutator(M, Omega)
    printed_res = printed.velocity_form_lhs(W, g, a, b) - printed.velocity_form_rhs(Omega, a)
    return (derived - printed_res).applyfunc(sp.expand)


def _a0_Omega_dot(n: int):
    M, g = generic(n)
    Omega = inverse_closed_form(M, g, 0, b)
    M_dot, g_dot = commutator(M, Omega), -Omega * g
    eps = sp.Symbol("epsilon")
    moved = inverse_closed_form(M + eps * M_dot, g + eps * g_dot, 0, b)
    return moved.diff(eps).subs(eps, 0).applyfunc(sp.expand)


@claim("eq:M-O-axi-symm", uses=("eq:axisymm", "eq:Inertia", "eq:M-O", "eq:motion-general",
                                "P:inversion"))
def eq_m_o_axisymm() -> Verdict:
    inertia = combine([
        sym_checks(lambda n: inertia_axisym(skew_symbols("w", n)) - printed.inertia_axisymm(
            skew_symbols("w", n), a), (3, 4), sphere=False, label="I"),
        point_checks(lambda p: inertia_axisym(p["M"], p["a"]) - printed.inertia_axisymm(p["M"], p["a"]),
                     points.all_n(5), label="I")])
    L = combine([
        sym_checks(lambda n: L_gamma_axisym(*generic(n)) - printed.L_axisymm(*generic(n), a, b),
                   (3, 4), sphere=False, label="L"),
        point_checks(lambda p: L_gamma_axisym(p["M"], p["gamma"], p["a"], p["b"])
                     - printed.L_axisymm(p["M"], p["gamma"], p["a"], p["b"]), points.all_n(5), label="L")])
    velocity = sym_checks(_velocity_residual_difference, (3, 4, 5, 6), sphere=False, label="vel",
                          uses_gamma=True)
    a0 = sym_checks(_a0_Omega_dot, (3, 4), label="a0")
    return Verdict.of_parts([
        Verdict.decide(inertia, n_values=(3, 4), method=inertia.method + "; linear in Omega, "
                       "span{E_n, u, v}: n = 3 covers all n").as_part("I(Omega) = 2 Omega + a (Omega E_n)^E_n"),
        Verdict.decide(L, method=L.method + "; " + REDUCTION).as_part("L_gamma (eq:M-O-axi-symm)"),
        Verdict.decide(velocity, method=velocity.method + " (identity of the two residuals in "
                       "(Omega_dot, Omega, gamma), no sphere needed; quadratic in Omega: n = 6 "
                       "covers all n)").as_part("velocity form equivalent to M_dot = [M, Omega]"),
        Verdict.decide(a0, method=a0.method + " (d/dt of the derived L_gamma^{-1} along the flow at "
                       "a = 0); " + REDUCTION).as_part("a = 0 => Omega_dot = 0"),
    ], n_values=(3, 4, 5, 6, points.ALL_N_MAX))
