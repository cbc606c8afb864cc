r"""P:n3special — for $n = 3$ the two expressions of $\zeta$ agree; the proof's $\mu$ and case analysis.

Claim (Proposition P:n3special, lines 650-680): for $n = 3$, eq:xiVnD and eq:xiV3D coincide on
$\mathcal{V}$. The proof writes, for $x_0 \ne 0$ and $\hat\Omega_0E_3 \ne 0$,
$\mu\big(\hat\Omega_0 - (\hat\Omega_0E_3)\wedge E_3\big) = (\hat\Omega_0E_3)\wedge(\gamma_0 - x_0E_3)$,
multiplies by $\gamma_0$ to get $\big(-\mu x_0\frac{a+b+2}{2+b} - 1 + x_0^2\big)\hat\Omega_0E_3 = 0$, and
concludes $\mu = -\frac{(1-x_0^2)(2+b)}{x_0(2+a+b)}$. The two special cases are said to give
$\zeta = 0$ for both expressions.

What is proved (all exact, symbolic in $a, b$ on a generic point of $\mathcal{V}$ with
$\Omega_0 = L_\gamma^{-1}M_0$, modulo $\lVert\gamma\rVert^2 = 1$):
* eq:xiVnD $=$ eq:xiV3D (printed vs printed), and the derived $\zeta$ (Th:Re) equals the derived
  3D rotation (eq:xiV3D): the proposition **holds**;
* $B = \mu A$ with the printed $\mu$ (as an identity on $\mathcal{V}$ after clearing $x_0$), and the
  printed scalar factor of line 671: $\mu A\gamma_0 - B\gamma_0 = (\text{factor})\,\hat\Omega_0E_3$
  identically in $\mu$;
* the proportionality step (two matrices of $\mathfrak{so}(3)$ with the same null vector $v \ne 0$
  are proportional) as an ideal membership: $v_k(a\times c)_i \in \langle a\times v, c\times v\rangle$
  (Gröbner normal form $0$, quotients checked), and both matrices of the proof annihilate $E_3$;
  the case split ($x_0 = 0$; $\hat\Omega_0E_3 = 0$; both non-zero) is exhaustive by construction;
* the case $\hat\Omega_0E_3 = 0$ — a finding about the proof (row P:n3special:case-OmegaE3):
  on $\mathcal{V}$ it forces $\Omega_0 \parallel E_3$ and ($\Omega_0 = 0$ or $\gamma_0 = \pm E_3$),
  and for $\gamma_0 = \pm E_3$, $\Omega_0 = \omega E_3$ (a point of $\mathcal{V}$: spin about the
  vertical symmetry axis) both expressions equal $-\frac{a\omega}{2+a+b}\hat E_3 \ne 0$, not $0$.
  The conclusion of the proposition survives (they still agree).

Uses: eq:xiVnD, eq:xiV3D, eq:V-velocity, Th:Re, P:inversion.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.proofs.s4_common import SAMPLERS, a, b, combine, generic_vertical, sym_checks
from chaplygin_nd.symbolic.algebra import hat, unhat, wedge
from chaplygin_nd.symbolic.axisym_inverse import inverse_closed_form
from chaplygin_nd.symbolic.axisymmetric import E_n, L_gamma_axisym
from chaplygin_nd.symbolic.exact.identity import Check, rational_identity
from chaplygin_nd.symbolic.printed import section4 as printed
from chaplygin_nd.symbolic.vertical import zeta, zeta_3d


def _on_V():
    M0, g = generic_vertical(3)
    W0 = inverse_closed_form(M0, g)
    return M0, g, W0


@claim("P:n3special", uses=("eq:xiVnD", "eq:xiV3D", "eq:V-velocity", "Th:Re", "P:inversion"))
def p_n3special() -> Verdict:
    E3 = E_n(3)

    def printed_agree(n):
        M0, g, W0 = _on_V()
        return printed.zeta_xiVnD(W0, g, a, b) - printed.zeta_3d_wedge(unhat(W0), a, b)

    def derived_agree(n):
        M0, g, W0 = _on_V()
        return zeta(M0, g) - zeta_3d(unhat(W0))

    def mu_identity(n):
        M0, g, W0 = _on_V()
        A = W0 - wedge(W0 * E3, E3)
        B = wedge(W0 * E3, g - g[2] * E3)
        return B - printed.mu_n3(g[2], a, b) * A

    def mu_factor(n):
        M0, g, W0 = _on_V()
        mu = sp.Symbol("mu")
        A = W0 - wedge(W0 * E3, E3)
        B = wedge(W0 * E3, g - g[2] * E3)
        return mu * A * g - B * g - printed.mu_n3_equation(mu, g[2], a, b) * (W0 * E3)

    def case_x0_zero():
        """Case x_0 = 0 of the proof: on V both printed expressions vanish (gamma_0 = (g1, g2, 0))."""
        M0, g = generic_vertical(3)
        sub = {g[2]: 0}
        M0, g0 = M0.xreplace(sub).applyfunc(sp.expand), g.xreplace(sub)
        W0 = inverse_closed_form(M0, g0)
        both = list(printed.zeta_xiVnD(W0, g0, a, b)) + list(printed.zeta_3d_wedge(unhat(W0), a, b))
        return rational_identity(both, sphere=(g[0], g[1]), samplers=SAMPLERS, label="n3-x0")

    x0_zero = case_x0_zero()
    agree = combine([sym_checks(printed_agree, (3,), label="n3-printed"),
                     sym_checks(derived_agree, (3,), label="n3-derived")])
    mu = sym_checks(mu_identity, (3,), label="n3-mu")
    factor = sym_checks(mu_factor, (3,), label="n3-factor")
    return Verdict.of_parts([
        Verdict.decide(agree).as_part("eq:xiVnD = eq:xiV3D for n = 3 on V"),
        Verdict.decide(mu, method=mu.method + " (identity B = mu A on V, x_0 != 0)").as_part(
            "mu = -(1-x_0^2)(2+b)/(x_0(2+a+b))"),
        Verdict.decide(factor).as_part("the scalar factor of line 671"),
        Verdict.decide(x0_zero, method=x0_zero.method + " (generic point of V with x_0 = 0)")
        .as_part("case x_0 = 0: both expressions vanish"),
        Verdict.decide(combine([null_vector_premises(), proportionality()])).as_part(
            "proportionality: matrices of so(3) with the same null vector are proportional"),
    ], n_values=(3,), notes="The proof's case Omega_0 E_3 = 0 is mis-stated; see row "
                            "P:n3special:case-OmegaE3. The case split (x_0 = 0; x_0 != 0 with "
                            "hat(Omega_0) E_3 = 0; both non-zero) is exhaustive by construction.")


def null_vector_premises():
    r"""Both matrices of the proof, $A = \hat\Omega_0 - (\hat\Omega_0E_3)\wedge E_3$ and
    $B = (\hat\Omega_0E_3)\wedge(\gamma_0 - x_0E_3)$, annihilate $E_3$: exact on $\mathcal{V}$."""
    E3 = E_n(3)

    def residual(n):
        M0, g, W0 = _on_V()
        A = W0 - wedge(W0 * E3, E3)
        B = wedge(W0 * E3, g - g[2] * E3)
        return (A * E3).col_join(B * E3)
    return sym_checks(residual, (3,), label="n3-null")


def proportionality():
    r"""The step that introduces $\mu$, computed. For $\hat a v = a\times v$: if $a\times v = 0$,
    $c\times v = 0$ and $v \ne 0$ then $a\times c = 0$, because every $v_k(a\times c)_i$ lies in the
    ideal $\langle a\times v, c\times v\rangle$ of $\mathbb{Q}[a, c, v]$: its normal form modulo a
    Gröbner basis (grevlex) is $0$, and the quotients are checked as the polynomial identity
    $v_k(a\times c)_i = \sum_j q_jG_j$. Then $\lVert a\rVert^2c - \langle a, c\rangle a =
    -a\times(a\times c) = 0$, so $c = \mu a$ with $\mu = \langle a, c\rangle/\lVert a\rVert^2$ when
    $a \ne 0$ (and $B = \mu A$ with the printed $\mu$ is the part proved above)."""
    av, cv, v = (sp.Matrix(sp.symbols(f"{s}1:4", real=True)) for s in ("a", "c", "v"))
    gens = list(av.cross(v)) + list(cv.cross(v))
    X = (*av, *cv, *v)
    basis = sp.groebner(gens, *X, order="grevlex")
    residuals = []
    for i in range(3):
        for k in range(3):
            f = sp.expand(v[k] * av.cross(cv)[i])
            quotients, remainder = basis.reduce(f)
            residuals += [remainder, f - sum(q * g for q, g in zip(quotients, basis.exprs))]
    residuals += list(av.dot(av) * cv - av.dot(cv) * av + av.cross(av.cross(cv)))
    check = rational_identity(residuals, label="n3-ideal")
    return Check(check.ok, "v_k (a x c)_i in <a x v, c x v>: normal form 0 modulo a Groebner basis "
                           "(grevlex) and the quotient identity, exact; |a|^2 c - <a,c> a = "
                           "-a x (a x c) (" + check.method + ")", check.counterexample,
                 check.seconds)


@claim("P:n3special:case-OmegaE3", uses=("P:n3special", "eq:V-velocity"),
       adds=("Section 4 — the axisymmetric sphere",
             "proof of P:n3special, case hat(Omega_0) E_3 = 0: 'both expressions for zeta vanish'"))
def p_n3special_case() -> Verdict:
    w = sp.Symbol("omega", real=True)
    E3 = E_n(3)
    residual_printed, residual_fixed, on_V = [], [], []
    for sign in (1, -1):
        g0 = sign * E3
        W0 = hat([0, 0, w])
        on_V += list(L_gamma_axisym(W0, g0) * g0)  # M_0 gamma_0 = 0: the point lies in V
        target = -a * w / (2 + a + b) * hat([0, 0, 1])
        z_nD, z_3D = printed.zeta_xiVnD(W0, g0, a, b), printed.zeta_3d_wedge(unhat(W0), a, b)
        residual_printed += list(z_nD) + list(z_3D)          # the proof says: both are 0
        residual_fixed += list(z_nD - target) + list(z_3D - target)
    samplers = dict(SAMPLERS)
    samplers[w] = lambda r: sp.Integer(1)
    in_V = rational_identity(on_V)
    printed_chk = rational_identity(residual_printed, samplers=samplers, label="n3-case")
    fixed_chk = combine([in_V, rational_identity(residual_fixed)],
                        method="exact symbolic in (a, b, omega): the points lie in V and both "
                               "expressions equal -a omega/(2+a+b) hat(E_3)")
    return Verdict.decide(
        printed_chk, corrected=fixed_chk, n_values=(3,), kind="proof",
        printed_latex=r"\hat\Omega_0E_3 = 0 \;\Rightarrow\; \text{both expressions for } \zeta \text{ equal } 0",
        correction_latex=r"\begin{gathered}\hat\Omega_0E_3 = 0 \text{ on } \mathcal{V} \Rightarrow \Omega_0 = \omega E_3 "
                         r"\text{ and } (\omega = 0 \text{ or } \gamma_0 = \pm E_3); \\ \text{then both "
                         r"expressions equal } -\frac{a\,\omega}{2+a+b}\,\hat E_3 \text{ (they agree, "
                         r"but vanish only if } a\omega = 0)\end{gathered}",
        method="exact symbolic in (a, b, omega) at gamma_0 = +-E_3, Omega_0 = omega E_3",
        notes="Counterexample: gamma_0 = E_3, Omega_0 = E_3 (spin about the vertical symmetry "
              "axis, a point of V). The proposition itself holds (row P:n3special).")
