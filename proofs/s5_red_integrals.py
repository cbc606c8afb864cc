r"""S5:red-integrals and S5:red-measure — the reduced integrals and the reduced invariant measure.

**Claims (lines 869-882).** The integrals descend to $F_1$, $F_2 = A+B$,
$F_3 = x^2A + B(1-x^2) + E^2 - G^2 + 2x\delta$ and
$H = \frac{a+2+bx^2}{2\Delta}A + \frac{2+b(1-x^2)}{2\Delta}B - \frac{b(2+b)}{2(a+b+2)\Delta}G^2
+ \frac{b(2+a)}{4\Delta}E^2 + \frac{bx}{\Delta}\delta$ (4, generically independent); the invariant
measure "is the restriction of the volume form $\mu_r = \Delta^{-2}\,dA\,dB\,dE\,dG\,dF_1\,dx\,d\delta$ on
$\mathbb{R}^7$ to $\mathcal{R}$".

In our words. Integrals: the 4D integrals ($F_3 = -[\lambda\sigma]p$, $H = \tfrac12\langle M,\Omega\rangle_\kappa$)
written in the invariants by :mod:`symbolic.reduction.invariants_n4` agree with the printed ones; they
are conserved by the derived reduced field and their differentials (with $d\Phi$,
$\Phi = \delta^2 - \det\Lambda$) have rank 5 at a seeded point, i.e. they are independent on $\mathcal{R}$.

Measure: $\operatorname{div}(\Delta^{-2}X) = 0$ holds identically on $\mathbb{R}^7$ for the field
eq:red-system, so $\mu_r$ is an invariant 7-form there. But a 7-form has no restriction to the
6-dimensional $\mathcal{R}$; the induced measure is a Leray residue, and it depends on the defining
function. Along $\Phi$ (the relation the paper writes) it is $\Delta^{-2}/(2|\delta|)\,dA\,dB\,dE\,dG\,dF_1\,dx$
in the chart $(A,B,E,G,F_1,x)$ of a sheet $\pm\delta>0$ — **not** invariant, because $X(\Phi) =
-\tfrac{2abxG}{(2+a+b)\Delta}\Phi \ne 0$. Along the first integral $\Phi/\Delta$ of the $\mathbb{R}^7$ field
it is $\Delta^{-1}/(2|\delta|)$, which is invariant, and which is (up to a constant) the pushforward of
$\mu = \Delta^{-1}dk\,du\,d\sigma$ of S5:measure4D: the Gram map pushes $dk\,du\,dq$ forward to
$\propto(\det\Lambda)^{-1/2} = |\delta|^{-1}$, and $d\sigma = dq/|x|$, $ds = -2x\,dx$ cancel $|x|$.

**Uses** S5:F123, S5:H4D, eq:red-system, S5:measure4D. **Proves** the integrals as exact
identities of $\delta$-linear normal forms; the $\mathbb{R}^7$ divergence as an exact rational identity;
the chart divergences (with $\partial_y\delta = \partial_y\det\Lambda/(2\delta)$) as normal-form identities
modulo $\delta^2 = \det\Lambda$. $n = 4$.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.proofs.s5_common import exact, invariants_at, phase_point, reduced_check
from chaplygin_nd.symbolic import fourd
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.measure import measure_residual
from chaplygin_nd.symbolic.printed import section5 as printed
from chaplygin_nd.symbolic.reduction import invariants_n4 as ri
from chaplygin_nd.symbolic.reduction import reduced_n4

a, b, x = fourd.a, fourd.b, fourd.x
A, B, E, G, F1, delta = ri.A, ri.B, ri.E, ri.G, ri.F1, ri.delta
COORDS = [reduced_n4.SYMBOLS[n] for n in reduced_n4.COORDS]
DET = ri.det_Lambda().as_expr()


def _lie(f, X):
    return sum(sp.diff(f, c) * X[n] for n, c in zip(reduced_n4.COORDS, COORDS, strict=False))


def _independent() -> Verdict:
    ints = reduced_n4.integrals()
    fs = [ints[n] for n in ("F1", "F2", "F3", "H")] + [delta**2 - DET]
    pt = invariants_at(phase_point(points.generator(points.ledger_seed(), "red-int rank")))
    J = sp.Matrix([[sp.diff(f, c).xreplace(pt) for c in COORDS] for f in fs])
    rank = J.rank()
    return Verdict.all_of([("rank", exact(sp.Integer(rank - 5), "red-int rank"))], n_values=(4,),
                          method=f"exact Jacobian rank of (F1, F2, F3, H, Phi) at a seeded rational "
                                 f"point of R: {rank}")


@claim("S5:red-integrals", uses=("S5:F123", "S5:H4D", "eq:red-system"))
def red_integrals() -> Verdict:
    ints = reduced_n4.integrals()
    X = reduced_n4.field()
    shown = {"F1": F1, "F2": printed.red_F2(A, B), "F3": printed.red_F3(A, B, E, G, x, delta),
             "H": printed.red_H(A, B, E, G, x, delta, a, b)}
    parts = []
    for n in ("F1", "F2", "F3", "H"):
        parts.append(Verdict.all_of([
            ("printed = derived", reduced_check(shown[n] - ints[n], f"red-int {n}")),
            ("conserved by the reduced field", reduced_check(_lie(ints[n], X), f"red-int dot {n}")),
        ], n_values=(4,)).as_part(n))
    parts.append(_independent().as_part("generically independent on R"))
    return Verdict.of_parts(parts, n_values=(4,), method=(
        "derived 4D integrals written in the invariants (invariant theory); exact identities of "
        "delta-linear normal forms; exact Jacobian rank"))


def chart_residual(rho):
    r"""$\sum_y \tfrac{d}{dy}\big(\rho\,X_y\big)$ over the chart $y = (A,B,E,G,F_1,x)$ of a sheet of
    $\mathcal{R}$, for a density $\rho(x, \delta)$, with $\partial_y\delta = \partial_y\det\Lambda/(2\delta)$."""
    X = reduced_n4.field()
    total = sp.Integer(0)
    for n, y in zip(reduced_n4.COORDS, COORDS, strict=False):
        if n == "delta":
            continue
        F = rho * X[n]
        total += sp.diff(F, y) + sp.diff(F, delta) * sp.diff(DET, y) / (2 * delta)
    return total


@claim("S5:red-measure", uses=("eq:red-system", "S5:measure4D"))
def red_measure() -> Verdict:
    X = reduced_n4.field()
    rho7 = printed.red_measure_density(a, b, x)
    ambient = exact(measure_residual([X[n] for n in reduced_n4.COORDS], COORDS, [(rho7, 1)]),
                    "red-measure R7")
    Dl = printed.Delta(a, b, x)
    naive = reduced_check(chart_residual(printed.red_measure_on_R(a, b, x, delta)),
                          "red-measure naive residue")
    fixed = reduced_check(chart_residual(1 / (2 * Dl * delta)), "red-measure Leray residue")
    c = -2 * a * b * x * G / ((2 + a + b) * Dl)          # = X(Delta)/Delta
    xphi = exact(_lie(delta**2 - DET, X) - c * (delta**2 - DET), "red-measure XPhi")
    xdelta = exact(_lie(Dl, X) - c * Dl, "red-measure XDelta")
    return Verdict.of_parts([
        Verdict.all_of([("div(Delta^-2 X) = 0 on R^7", ambient)], n_values=(4,)).as_part(
            "mu_r invariant on R^7"),
        Verdict.all_of([("X(Phi) = c Phi on R^7, c = -2abxG/((2+a+b)Delta)", xphi),
                        ("X(Delta) = c Delta", xdelta)], n_values=(4,)).as_part(
            "R invariant; Phi/Delta a first integral"),
        Verdict.decide(
            naive, n_values=(4,), corrected=fixed, kind="reading",
            remark="'The restriction of mu_r to R' has two readings. False: the residue of mu_r "
                   "along the relation delta^2 - det Lambda = 0 that the paper writes (not "
                   "invariant, since X(delta^2 - det Lambda) = c (delta^2 - det Lambda) with "
                   "c = -2abxG/((2+a+b)Delta) != 0). True: mu_r is invariant on R^7, and its "
                   "residue along the first integral (delta^2 - det Lambda)/Delta, "
                   "dA dB dE dG dF_1 dx/(2 Delta |delta|), is invariant on R.",
            printed_latex=(r"\mu_r|_{\mathcal{R}} = \frac{dA\,dB\,dE\,dG\,dF_1\,dx}{\Delta(x)^2\,"
                           r"|\partial_\delta(\delta^2-\det\Lambda)|}"),
            correction_latex=(r"\mu_{\mathcal{R}} = \frac{\mu_r}{d\big((\delta^2-\det\Lambda)/\Delta\big)}"
                              r" = \frac{dA\,dB\,dE\,dG\,dF_1\,dx}{2\,\Delta(x)\,|\delta|}"
                              r"\quad(\text{chart } (A,B,E,G,F_1,x),\ \pm\delta>0)")).as_part(
            "induced measure on R"),
    ], n_values=(4,))
