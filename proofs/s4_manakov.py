r"""eq:Manakov, eq:itildendim and eq:solManakov — the $n$-dimensional rigid body with $\tilde{\mathbb{I}}$.

Claims (Section 4.4, lines 683-745):

.. math::
    \tilde{\mathbb{I}}(\dot\Omega) = [\tilde{\mathbb{I}}(\Omega), \Omega],\; \dot\gamma = -\Omega\gamma,\;
    \tilde{\mathbb{I}} = \mathbb{I} + b\,\mathrm{Id}\ \text{(eq:Manakov)};\quad
    \tilde{\mathbb{I}}(\Omega) = (2+b)\Omega + a(\Omega E_n)\wedge E_n\ \text{(eq:itildendim)};

$\tilde{\mathbb{I}}(\Omega)\gamma = (2+b)\Omega\gamma + ax\Omega E_n + a\langle\Omega\gamma, E_n\rangle E_n$,
$\langle\tilde{\mathbb{I}}(\Omega)\gamma, E_n\rangle = (2+a+b)\langle\Omega\gamma, E_n\rangle$, so
$\{\tilde{\mathbb{I}}(\Omega)\gamma = 0\} = \mathcal{V}$, invariant under eq:Manakov; on $\mathcal{V}$,
$\Omega(t) = e^{\chi t}\Omega_0e^{-\chi t}$, $\gamma(t) = e^{\chi t}\gamma_0$ with
$\chi = \frac{-a}{2+a+b}(\Omega_0 - (\Omega_0E_n)\wedge E_n)$ (eq:solManakov), using
$\Omega_0 = -\chi + \frac{1}{2+a+b}\tilde{\mathbb{I}}(\Omega_0)$, $[\tilde{\mathbb{I}}\Omega_0, \Omega_0] =
[\chi, \tilde{\mathbb{I}}\Omega_0]$ and $-\Omega_0\gamma_0 = \chi\gamma_0$ on $\mathcal{V}$.

How. $\tilde{\mathbb{I}}$ is built from $\mathbb{J}$ (:func:`symbolic.vertical.inertia_tilde`) and $\chi$
is *derived* ($\chi = \tilde\kappa\tilde{\mathbb{I}}(\Omega_0) - \Omega_0$ with $\chi E_n = 0$ solved for
$\tilde\kappa$). Invariance: along eq:Manakov, $\frac{d}{dt}\tilde{\mathbb{I}}(\Omega)\gamma =
-\Omega\,\tilde{\mathbb{I}}(\Omega)\gamma$ identically (a linear ODE for $N = \tilde{\mathbb{I}}(\Omega)\gamma$,
so $N = 0$ is invariant). $\{\tilde{\mathbb{I}}(\Omega)\gamma = 0\} = \mathcal{V}$ follows from the identity
$L_\gamma(\Omega)\gamma = \tilde{\mathbb{I}}(\Omega)\gamma$ on $S^{n-1}$. The curve solves eq:Manakov:
velocity at $t = 0$, i.e. $\tilde{\mathbb{I}}([\chi, \Omega_0]) = [\tilde{\mathbb{I}}\Omega_0, \Omega_0]$ and
$\chi\gamma_0 = -\Omega_0\gamma_0$, plus $SO(n-1)$-equivariance. Identities linear in $\Omega$ are
symbolic for $n = 3, 4$ (+ reduction, all $n$); those quadratic in $\Omega$ symbolic for
$n = 3..6$ (which covers every $n$); seeded exact points to $n = 12$.

Uses: eq:axisymm, eq:M-O-axi-symm, eq:V-velocity, eq:action.
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
    generic_vertical,
    point_checks,
    sym_checks,
    sym_gamma,
)
from chaplygin_nd.symbolic.algebra import commutator, skew_symbols
from chaplygin_nd.symbolic.axisym_inverse import inverse_closed_form
from chaplygin_nd.symbolic.axisymmetric import E_n, L_gamma_axisym, inertia_axisym
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.exact.identity import rational_identity
from chaplygin_nd.symbolic.printed import section4 as printed
from chaplygin_nd.symbolic.vertical import chi, inertia_matrix_3d, inertia_tilde

QUAD = "; quadratic in Omega: n = 6 covers all n"


@claim("eq:Manakov", uses=("eq:axisymm", "eq:itildendim"))
def eq_manakov() -> Verdict:
    def invariance(n):
        Omega, g = skew_symbols("w", n), frame_gamma(n)
        It = inertia_tilde(Omega)
        N = It * g
        N_dot = commutator(It, Omega) * g + It * (-Omega * g)  # Itilde(Omega_dot) = [Itilde Omega, Omega]
        return N_dot + Omega * N

    inv = sym_checks(invariance, (3, 4, 5, 6), sphere=False, label="Manakov-inv", uses_gamma=True)
    tilde3 = rational_identity(inertia_matrix_3d(a) + b * sp.eye(3) - printed.Itilde_3d(a, b))
    return Verdict.definition(
        "Itilde = I + b Id_so(n) with I from eq:axisymm; the rigid body with Poisson vector",
        n_values=(3, 4, 5, 6),
        consistency=[("n = 3: Itilde = diag(2+a+b, 2+a+b, 2+b)", tilde3),
                     ("{Itilde(Omega) gamma = 0} is invariant: d/dt N = -Omega N",
                      combine([inv], method=inv.method + QUAD))])


@claim("eq:itildendim", uses=("eq:Manakov", "eq:M-O-axi-symm", "eq:V-velocity"))
def eq_itildendim() -> Verdict:
    def formula(n):
        Omega = skew_symbols("w", n)
        return inertia_tilde(Omega) - printed.Itilde(Omega, a, b)

    def gamma_formulas(n):
        Omega, g = skew_symbols("w", n), sym_gamma(n)
        N = inertia_tilde(Omega) * g
        return list(N - printed.Itilde_gamma(Omega, g, a, b)) + [
            (E_n(n).T * N)[0, 0] - printed.Itilde_gamma_En(Omega, g, a, b)]

    def equals_V(n):
        Omega, g = skew_symbols("w", n), sym_gamma(n)
        return L_gamma_axisym(Omega, g) * g - inertia_tilde(Omega) * g

    f = combine([sym_checks(formula, (3, 4), sphere=False, label="It"),
                 point_checks(lambda p: inertia_axisym(p["M"], p["a"]) + p["b"] * p["M"]
                              - printed.Itilde(p["M"], p["a"], p["b"]), points.all_n(5), label="It")])
    gf = sym_checks(gamma_formulas, (3, 4), label="It-gamma")
    ev = sym_checks(equals_V, (3, 4), label="It-V")
    return Verdict.of_parts([
        Verdict.decide(f, method=f.method + "; " + REDUCTION).as_part(
            "Itilde(Omega) = (2+b) Omega + a (Omega E_n)^E_n"),
        Verdict.decide(gf, method=gf.method + "; " + REDUCTION).as_part(
            "Itilde(Omega) gamma and <Itilde(Omega) gamma, E_n>"),
        Verdict.decide(ev, method=ev.method + " (L_gamma(Omega) gamma = Itilde(Omega) gamma, so "
                       "{Itilde(Omega) gamma = 0} = {M gamma = 0}); " + REDUCTION).as_part(
            "{Itilde(Omega) gamma = 0} = V"),
    ], n_values=(3, 4, points.ALL_N_MAX))


@claim("eq:solManakov", uses=("eq:Manakov", "eq:itildendim", "eq:action", "eq:V-velocity"))
def eq_solmanakov() -> Verdict:
    def chi_same(n):
        Omega = skew_symbols("w", n)
        return list(printed.chi(Omega, a, b) - chi(Omega)) + list(printed.chi(Omega, a, b) * E_n(n))

    def line736(n):
        Omega = skew_symbols("w", n)
        return printed.Omega0_Manakov(Omega, printed.chi(Omega, a, b), a, b) - Omega

    def commutators(n):
        Omega = skew_symbols("w", n)
        It, c = inertia_tilde(Omega), printed.chi(Omega, a, b)
        return list(commutator(It, Omega) - commutator(c, It)) + list(
            inertia_tilde(commutator(c, Omega)) - commutator(It, Omega))

    def on_V(n):
        M0, g = generic_vertical(n)
        Om = inverse_closed_form(M0, g)
        return printed.chi(Om, a, b) * g + Om * g

    def on_V_pt(p):
        Om = inverse_closed_form(p["M"], p["gamma"], p["a"], p["b"])
        return printed.chi(Om, p["a"], p["b"]) * p["gamma"] + Om * p["gamma"]

    same = sym_checks(chi_same, (3, 4), sphere=False, label="chi")
    l736 = sym_checks(line736, (3, 4), sphere=False, label="chi-736")
    comm = combine([sym_checks(commutators, (3, 4, 5, 6), sphere=False, label="chi-comm"),
                    point_checks(lambda p: inertia_tilde(commutator(printed.chi(p["M"], p["a"], p["b"]), p["M"]), p["a"], p["b"])
                                 - commutator(inertia_tilde(p["M"], p["a"], p["b"]), p["M"]),
                                 points.all_n(7), label="chi-comm")])
    gam = combine([sym_checks(on_V, (3, 4), label="chi-V"),
                   point_checks(on_V_pt, points.all_n(5), vertical=True, label="chi-V")])
    return Verdict.of_parts([
        Verdict.decide(same, method=same.method + "; " + REDUCTION).as_part(
            "chi (printed = derived) and chi E_n = 0"),
        Verdict.decide(l736, method=l736.method + "; " + REDUCTION).as_part(
            "Omega_0 = -chi + Itilde(Omega_0)/(2+a+b)"),
        Verdict.decide(comm, method=comm.method + QUAD).as_part(
            "[Itilde Omega_0, Omega_0] = [chi, Itilde Omega_0] = Itilde([chi, Omega_0])"),
        Verdict.decide(gam, method=gam.method + "; linear in M_0 on V: " + REDUCTION).as_part(
            "chi gamma_0 = -Omega_0 gamma_0 on V; with eq:action the curve is a solution"),
    ], n_values=(3, 4, 6, points.ALL_N_MAX))
