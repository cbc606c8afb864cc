r"""P:inversion and eq:aux-inversion — the explicit inverse of $L_\gamma$ for the axisymmetric sphere.

Claim (Proposition P:inversion, lines 437-451):

.. math::
    \Omega = L_\gamma^{-1}(M) = \tfrac12 M + \frac{1}{2\Delta(x)}K, \quad
    K = abx(M\gamma)\wedge E_n - a(2+b)(ME_n)\wedge E_n + abx(ME_n)\wedge\gamma - b(2+a)(M\gamma)\wedge\gamma
        - \frac{ab(4+a+b)\langle M\gamma, E_n\rangle}{2+a+b}\gamma\wedge E_n .

and, in its proof (eq:aux-inversion, lines 456-481): $\langle\Omega\gamma, E_n\rangle =
\langle M\gamma, E_n\rangle/(2+a+b)$; the $2\times 2$ system $(2+a)U + bxZ = (ME_n)\wedge E_n +
b\frac{\langle M\gamma,E_n\rangle}{2+a+b}\gamma\wedge E_n$, $axU + (2+b)Z = (M\gamma)\wedge E_n$ for
$U = (\Omega E_n)\wedge E_n$, $Z = (\Omega\gamma)\wedge E_n$, with determinant $\Delta(x)$; and the
solved forms of $U$ and of $(\Omega\gamma)\wedge\gamma$.

How. Our $L_\gamma^{-1}$ is *derived* (:mod:`symbolic.axisym_inverse`): an equivariant ansatz
$\sum_k c_k T_k(M)$ solved by exact linear algebra. Here we prove, modulo $\lVert\gamma\rVert^2 = 1$,
(i) $L_\gamma(\sum c_kT_k(M)) = M$ (symbolic $n = 3, 4$ after clearing the denominator
$2\Delta(2+a+b)$), (ii) the printed $\Omega$ equals ours (symbolic $n = 3, 4, 5$), and (iii) the
printed $\Omega$ equals an exact linear solve of $L_\gamma$ at seeded rational points for
$n = 6..12, 16, 20, 24$ — a route that uses neither formula. All identities are linear in $M$ and natural, so
the reduction argument of :mod:`proofs.s4_common` extends $n = 4$ to every $n \ge 4$. Every
intermediate formula of the proof is compared with the same derived $\Omega$.

Uses: eq:M-O-axi-symm, eq:Delta, P:Measure (invertibility: $\det L_\gamma \ne 0$).
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.proofs.s4_common import (
    REDUCTION,
    a,
    b,
    combine,
    generic,
    point_checks,
    sym_checks,
)
from chaplygin_nd.symbolic.algebra import skew_symbols, wedge
from chaplygin_nd.symbolic.axisym_inverse import (
    inverse_closed_form,
    inverse_denominator,
    inverse_numerator,
)
from chaplygin_nd.symbolic.axisymmetric import Delta, E_n, L_gamma_axisym, mass_tensor, x
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.exact.identity import rational_identity
from chaplygin_nd.symbolic.model import angular_velocity
from chaplygin_nd.symbolic.printed import section4 as printed


def _solves(n: int):
    M, g = generic(n)
    lhs = L_gamma_axisym(inverse_numerator(M, g), g)
    return (lhs - inverse_denominator(x_=g[n - 1]) * M).applyfunc(sp.expand)


def _printed_vs_derived(n: int):
    M, g = generic(n)
    return printed.Omega_inverse(M, g, a, b) - inverse_closed_form(M, g)


def _printed_vs_solve(p: dict):
    n, g, M = p["n"], p["gamma"], p["M"]
    # an exact solve of eq:M-O in the engine of this evaluation (DomainMatrix or fmpq_mat)
    Omega = angular_velocity(M, g, mass_tensor(n, p["a"]), p["b"])
    return printed.Omega_inverse(M, g, p["a"], p["b"]) - Omega


@claim("P:inversion", uses=("eq:M-O-axi-symm", "eq:Delta", "P:Measure"))
def p_inversion() -> Verdict:
    solves = sym_checks(_solves, (3, 4), label="inv-solves")
    same = combine([sym_checks(_printed_vs_derived, (3, 4, 5), label="inv-printed"),
                    point_checks(_printed_vs_solve, points.all_n(6), label="inv-solve")])
    return Verdict.of_parts([
        Verdict.decide(solves, method=solves.method + " (derived ansatz inverse, denominators "
                       "cleared); " + REDUCTION).as_part("derived inverse solves L_gamma(Omega) = M"),
        Verdict.decide(same, method=same.method + " against an exact linear solve; "
                       + REDUCTION).as_part("Omega = M/2 + K/(2 Delta) with the printed K"),
    ], n_values=(3, 4, 5, points.ALL_N_MAX))


def _parts(n: int):
    M, g = generic(n)
    e = E_n(n)
    Omega = inverse_closed_form(M, g)
    return M, g, e, Omega


def _system_matrix() -> sp.Matrix:
    r"""The $2\times2$ coefficient matrix of the printed system (lines 466-467) in $(U, Z)$, read off
    the printed residuals with $U = u\,\mathrm{Id}$, $Z = z\,\mathrm{Id}$ at $\gamma = (0, s, x)$."""
    u_, z_, s_ = sp.symbols("u_ z_ s_")
    g = sp.Matrix([0, s_, x])
    r1, r2 = printed.system_U_Z(u_ * sp.eye(3), z_ * sp.eye(3), skew_symbols("m", 3), g, a, b)
    return sp.Matrix([[sp.diff(r[0, 0], v) for v in (u_, z_)] for r in (r1, r2)])


@claim("eq:aux-inversion", uses=("eq:M-O-axi-symm", "P:inversion", "eq:Delta"))
def eq_aux_inversion() -> Verdict:
    def aux(n):
        M, g, e, Omega = _parts(n)
        return (e.T * Omega * g)[0, 0] - printed.aux_inversion(M, g, a, b)

    def system(n):
        M, g, e, Omega = _parts(n)
        r1, r2 = printed.system_U_Z(wedge(Omega * e, e), wedge(Omega * g, e), M, g, a, b)
        return list(r1) + list(r2)

    def U(n):
        M, g, e, Omega = _parts(n)
        return wedge(Omega * e, e) - printed.U_solution(M, g, a, b)

    def Y(n):
        M, g, e, Omega = _parts(n)
        return wedge(Omega * g, g) - printed.Y_solution(M, g, a, b)

    def U_at(p):
        e = E_n(p["n"])
        Om = inverse_closed_form(p["M"], p["gamma"], p["a"], p["b"])
        return wedge(Om * e, e) - printed.U_solution(p["M"], p["gamma"], p["a"], p["b"])

    def Y_at(p):
        g = p["gamma"]
        Om = inverse_closed_form(p["M"], g, p["a"], p["b"])
        return wedge(Om * g, g) - printed.Y_solution(p["M"], g, p["a"], p["b"])

    ns = (3, 4)
    det = rational_identity(_system_matrix().det() - Delta())
    checks = [
        ("<Omega gamma, E_n> = <M gamma, E_n>/(2+a+b)", sym_checks(aux, ns, label="aux")),
        ("the linear system for U, Z", sym_checks(system, ns, label="aux-sys")),
        ("its determinant is Delta", det),
        ("U = (Omega E_n)^E_n solved", combine([sym_checks(U, ns, label="aux-U"),
                                               point_checks(U_at, points.all_n(5), label="aux-U")])),
        ("(Omega gamma)^gamma solved", combine([sym_checks(Y, ns, label="aux-Y"),
                                               point_checks(Y_at, points.all_n(5), label="aux-Y")])),
    ]
    return Verdict.of_parts(
        [Verdict.decide(c, method=c.method + ("; " + REDUCTION if name != "its determinant is Delta"
                                              else "")).as_part(name) for name, c in checks],
        n_values=(3, 4, points.ALL_N_MAX))
