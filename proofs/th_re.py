r"""Th:Re, its corollary and eq:xiVnD — vertical momentum gives relative equilibria, for every $n$.

Claims (Theorem Th:Re, lines 580-622; corollary lines 624-633; eq:xiVnD lines 636-645). For
$(M_0, \gamma_0) \in \mathcal{V}$, $x_0 = \langle E_n, \gamma_0\rangle$:

.. math::
    \zeta = -\frac{a(2+b(1-x_0^2))}{2\Delta(x_0)}M_0 + \frac{1}{2\Delta(x_0)}\big(a(2+b)(M_0E_n)\wedge E_n
            - abx_0(M_0E_n)\wedge\gamma_0\big),

$\zeta E_n = 0$; $\Omega_0 = -\zeta + \frac{2+b}{\Delta(x_0)}M_0$; $[M_0, \Omega_0] = [\zeta, M_0]$;
$\zeta\gamma_0 = -\Omega_0\gamma_0$; hence $M(t) = e^{\zeta t}M_0e^{-\zeta t}$, $\gamma(t) = e^{\zeta t}\gamma_0$
solve eq:motion-general and $x(t) = x_0$. Corollary: $\Omega(t) = e^{\zeta t}\Omega_0e^{-\zeta t}$.
eq:xiVnD: $\zeta = -\frac{a(2+b(1-x_0^2))}{\Delta}(\Omega_0 - (\Omega_0E_n)\wedge E_n) -
\frac{abx_0}{\Delta}(\Omega_0E_n)\wedge(\gamma_0 - x_0E_n)$, using $0 = M_0\gamma_0 = \Omega_0((2+b)\gamma_0 + ax_0E_n)$.

How. Our $\zeta$ is *derived* (:mod:`symbolic.vertical`): the relative-equilibrium conditions force
$\zeta = \kappa M_0 - \Omega_0$, and $\zeta E_n = 0$ fixes $\kappa$. Every displayed step is compared
with it, exactly, on a generic symbolic point of $\mathcal{V}$ ($M_0 = PAP$) modulo
$\lVert\gamma\rVert^2 = 1$ for $n = 3, 4$, and at seeded rational points of $\mathcal{V}$ for
$n \le 12$. The identities are linear in $M_0 \in \mathcal{V} = \Lambda^2\gamma_0^\perp$, so the
reduction argument (s4_common, with $u, v \perp \gamma_0$) carries $n = 4$ to every $n$; the
commutator identity follows algebraically from the linear one ($[M_0, -\zeta + \kappa M_0] =
[\zeta, M_0]$). "The curve is a solution": its velocity at $t = 0$ equals the vector field (the
two identities) and both are $SO(n-1)$-equivariant (eq:action), with $e^{\zeta t} \in SO(n-1)$
since $\zeta E_n = 0$; the numerical confirmation (mpmath, 30 digits, several periods, n = 3..6)
is in tests/test_section4_relative_equilibria.py. The corollary is the equivariance of
$L_\gamma^{-1}$ (eq:action); its infinitesimal form $D\Omega\cdot([\zeta, M_0], \zeta\gamma_0) =
[\zeta, \Omega_0]$ is checked exactly as well.

Uses: eq:def-H-V, P:inversion, eq:action, eq:V-velocity, eq:aux-inversion.
"""

from __future__ import annotations

from proofs.ledger import Verdict, claim
from proofs.s4_common import REDUCTION, a, b, combine, generic_vertical, point_checks, sym_checks
from symbolic.algebra import commutator, wedge
from symbolic.axisym_inverse import inverse_closed_form
from symbolic.axisymmetric import E_n, L_gamma_axisym
from symbolic.printed import section4 as printed
from symbolic.vertical import zeta

NS = (3, 4)
POINTS = range(5, 13)
LINEAR = "; linear in M_0 on V = Lambda^2 gamma_0^perp: " + REDUCTION


def _sym(n):
    M0, g = generic_vertical(n)
    return M0, g, inverse_closed_form(M0, g), printed.zeta_Th_Re(M0, g, a, b)


def _pt(p):
    M0, g, av, bv = p["M"], p["gamma"], p["a"], p["b"]
    return M0, g, inverse_closed_form(M0, g, av, bv), printed.zeta_Th_Re(M0, g, av, bv), av, bv


def _both(sym_fn, pt_fn, label):
    return combine([sym_checks(sym_fn, NS, label=label),
                    point_checks(pt_fn, POINTS, vertical=True, label=label)])


@claim("Th:Re", uses=("eq:def-H-V", "P:inversion", "eq:action", "eq:V-velocity", "eq:aux-inversion"))
def th_re() -> Verdict:
    zeta_same = _both(lambda n: _sym(n)[3] - zeta(*generic_vertical(n)),
                      lambda p: _pt(p)[3] - zeta(p["M"], p["gamma"], p["a"], p["b"]), "ThRe-zeta")
    zeta_E = _both(lambda n: _sym(n)[3] * E_n(n), lambda p: _pt(p)[3] * E_n(p["n"]), "ThRe-zE")

    def omega0_sym(n):
        M0, g, Om, z = _sym(n)
        return printed.Omega0_Th_Re(M0, g, z, a, b) - Om

    def omega0_pt(p):
        M0, g, Om, z, av, bv = _pt(p)
        return printed.Omega0_Th_Re(M0, g, z, av, bv) - Om

    def comm_sym(n):
        M0, g, Om, z = _sym(n)
        return commutator(M0, Om) - commutator(z, M0)

    def comm_pt(p):
        M0, g, Om, z, *_ = _pt(p)
        return commutator(M0, Om) - commutator(z, M0)

    def gam_sym(n):
        M0, g, Om, z = _sym(n)
        return z * g + Om * g

    def gam_pt(p):
        M0, g, Om, z, *_ = _pt(p)
        return z * g + Om * g

    def xdot_sym(n):
        M0, g, Om, z = _sym(n)
        return (E_n(n).T * (-Om * g))[0, 0]

    omega0 = _both(omega0_sym, omega0_pt, "ThRe-O0")
    comm = _both(comm_sym, comm_pt, "ThRe-comm")
    gam = _both(gam_sym, gam_pt, "ThRe-gam")
    xdot = sym_checks(xdot_sym, NS, label="ThRe-x")
    curve = combine([comm, gam], method="velocity of the curve at t = 0 equals the field "
                    "(both identities above) + SO(n-1)-equivariance (eq:action), exp(zeta t) in "
                    "SO(n-1) since zeta E_n = 0")
    parts = [
        Verdict.decide(zeta_same, method=zeta_same.method + LINEAR).as_part("zeta (printed = derived)"),
        Verdict.decide(zeta_E, method=zeta_E.method + LINEAR).as_part("zeta E_n = 0"),
        Verdict.decide(omega0, method=omega0.method + LINEAR).as_part(
            "Omega_0 = -zeta + (2+b)/Delta M_0"),
        Verdict.decide(comm, method=comm.method + "; all n: follows from the previous part").as_part(
            "[M_0, Omega_0] = [zeta, M_0]"),
        Verdict.decide(gam, method=gam.method + LINEAR).as_part("zeta gamma_0 = -Omega_0 gamma_0"),
        Verdict.decide(curve).as_part("the curve is a solution"),
        Verdict.decide(xdot, method=xdot.method + " (x_dot = -<Omega gamma, E_n> = 0 on V, and V is "
                       "invariant); " + REDUCTION).as_part("x constant"),
    ]
    return Verdict.of_parts(parts, n_values=(3, 4, 12))


def _corollary(M0, g, av, bv):
    r"""$L_\gamma([\zeta, \Omega_0]) + b(\Omega_0\zeta\gamma_0)\wedge\gamma_0 + b(\Omega_0\gamma_0)\wedge\zeta\gamma_0
    - [\zeta, M_0]$: zero iff $D\Omega\cdot([\zeta, M_0], \zeta\gamma_0) = [\zeta, \Omega_0]$ (differentiate
    $M = L_\gamma(\Omega)$ along the curve)."""
    z = zeta(M0, g, av, bv)
    Om = inverse_closed_form(M0, g, av, bv)
    zg = z * g
    return (L_gamma_axisym(commutator(z, Om), g, av, bv) + bv * wedge(Om * zg, g)
            + bv * wedge(Om * g, zg) - commutator(z, M0))


@claim("Th:Re-corollary", uses=("Th:Re", "eq:action"))
def th_re_corollary() -> Verdict:
    sym = sym_checks(lambda n: _corollary(*generic_vertical(n, frame=True), a, b), (3, 4),
                     label="cor", frame_n3=True)
    inf = combine([sym, point_checks(lambda p: _corollary(p["M"], p["gamma"], p["a"], p["b"]),
                                     range(5, 13), vertical=True, label="cor")])
    return Verdict.decide(inf, n_values=(3, 4, 12), method=inf.method + " (infinitesimal form: "
                          "d/dt Omega(M(t), gamma(t)) = [zeta, Omega] at t = 0)" + LINEAR + "; for all t "
                          "it is the equivariance Omega -> h Omega h^{-1} (eq:action) with "
                          "h = exp(zeta t) in SO(n-1)")


@claim("eq:xiVnD", uses=("Th:Re", "eq:M-O-axi-symm", "eq:V-velocity"))
def eq_xivnd() -> Verdict:
    def sym(n):
        M0, g, Om, _ = _sym(n)
        return printed.zeta_xiVnD(Om, g, a, b) - zeta(M0, g)

    def pt(p):
        M0, g, Om, _, av, bv = _pt(p)
        return printed.zeta_xiVnD(Om, g, av, bv) - zeta(M0, g, av, bv)

    def inline_sym(n):
        M0, g, Om, _ = _sym(n)
        return Om * ((2 + b) * g + a * g[n - 1] * E_n(n))

    same = _both(sym, pt, "xiVnD")
    inline = sym_checks(inline_sym, NS, label="xiVnD-inline")
    return Verdict.of_parts([
        Verdict.decide(same, method=same.method + LINEAR).as_part("zeta in terms of Omega_0, gamma_0"),
        Verdict.decide(inline, method=inline.method + LINEAR).as_part(
            "0 = M_0 gamma_0 = Omega_0((2+b) gamma_0 + a x_0 E_n) on V"),
    ], n_values=(3, 4, 12))
