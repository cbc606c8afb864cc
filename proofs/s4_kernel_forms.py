r"""K:* — the stable rewrites used by the generated kernels, each proved equal to what it replaces.

* **K:Delta** — $\Delta(x) = (2+a)(2+b) - abx^2 = 2(2+a+b) + ab\,(1-x)(1+x)$. The kernels
  (generated/axisym.py, fourd.py, reduced_n4.py) evaluate the right-hand side; proved against the
  *derived* $\Delta$ of :mod:`symbolic.axisymmetric` (the determinant of the block $C$), exactly, as
  a polynomial identity in $a, b, x$. Measured: both forms are within 1.1 ulp over the hard cases
  ($\Delta \ge 2 + b$ is never a small difference of large terms), so this row certifies the form
  evaluated, not an accuracy gain.
* **K:rodrigues** — $e^{Z} = I + \operatorname{sinc}\theta\,Z + \tfrac12\operatorname{sinc}^2(\theta/2)\,Z^2$
  for $Z = \hat z \in \mathfrak{so}(3)$, $\theta = \lVert z\rVert$ (runtime.axisym.expm_skew, used by
  the vertical solution of Th:Re for $n = 4$): Rodrigues' $(1 - \cos\theta)/\theta^2$ is replaced by
  $\tfrac12\operatorname{sinc}^2(\theta/2)$, which has no $0/0$ at $\theta \to 0$. Proved with the
  half-angle point $(c, s) = (\cos\tfrac\theta2, \sin\tfrac\theta2)$ on the circle $c^2 + s^2 = 1$
  ($\cos\theta = c^2 - s^2$, $\sin\theta = 2cs$): the identity $1 - \cos\theta = 2s^2$ modulo
  $c^2+s^2-1$, and that the resulting $R(\theta)$ is orthogonal and solves $R' = \hat zR$ for
  $\theta = \lVert z\rVert t$ (so $R = e^{t\hat z}$ by uniqueness), exactly.
* **K:horizontal-sinc** — in the horizontal solution (S5:H-linear, corrected, from
  :func:`symbolic.reduction.reduced_n4.horizontal_solution`), $\sin(\nu t)/\nu = t\operatorname{sinc}(\nu t)$ and
  $\nu\sin\nu t = \nu^2 t\operatorname{sinc}(\nu t)$, so the kernel needs only $\nu^2 \ge 0$ and stays
  accurate as $\nu \to 0$: proved by substituting $\operatorname{sinc}(\nu t) = \sin(\nu t)/(\nu t)$
  into the kernel's expression and comparing with the derived one, exactly (sin, cos as symbols).
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.symbolic.algebra import hat
from chaplygin_nd.symbolic.exact.identity import rational_identity

SECTION = "Kernels — stable rewrites"


@claim("K:Delta", uses=("eq:Delta",), adds=(SECTION, "Δ(x) = 2(2+a+b) + ab(1−x)(1+x), the form the kernels evaluate, equals the derived Δ (certifies the form; no accuracy gain is claimed)"))
def k_delta() -> Verdict:
    from chaplygin_nd.symbolic.axisymmetric import Delta, a, b, x
    from chaplygin_nd.symbolic.codegen.emit.axisym import stable_Delta
    from chaplygin_nd.symbolic.codegen.emit.fourd import stable_D

    check = rational_identity(stable_Delta(x, a, b) - Delta(x, a, b))
    common = rational_identity(stable_D() - 2 * (2 + a + b) * Delta(x, a, b))  # same a, b, x
    return Verdict.all_of([("stable form = derived Delta", check),
                           ("D = 2(2+a+b) Delta of the 4D and reduced kernels", common)],
                          method=check.method)


@claim("K:rodrigues", uses=("Th:Re",), adds=(SECTION, "exp(ẑ) = I + sinc θ ẑ + ½ sinc²(θ/2) ẑ², the form of the vertical-solution kernel"))
def k_rodrigues() -> Verdict:
    c, s, w = sp.symbols("c s omega", real=True)  # half-angle point (cos, sin)(theta/2); omega = |z|
    z = sp.Matrix(sp.symbols("z1:4", real=True))  # unit axis: |z|^2 = 1 (reduced exactly below)
    Zu = hat(list(z))
    cos_t, sin_t = c**2 - s**2, 2 * c * s
    half = rational_identity(1 - cos_t - 2 * s**2, sphere=(c, s))
    # The kernel's R for Z = theta Zu: sinc(theta) theta Zu = sin(theta) Zu and
    # (1/2) sinc^2(theta/2) theta^2 Zu^2 = 2 s^2 Zu^2.
    R = sp.eye(3) + sin_t * Zu + 2 * s**2 * Zu * Zu
    # theta = omega t: d/dt sin(theta) = omega cos(theta), d/dt 2 s^2 = d/dt (1 - cos theta) = omega sin(theta).
    dR = w * cos_t * Zu + w * sin_t * Zu * Zu
    checks = [("1 - cos(theta) = 2 sin^2(theta/2)", half),
              ("R' = omega Zu R, R(0) = I: R = exp(t omega Zu) by uniqueness", _mod_both(dR - w * Zu * R, z, c)),
              ("R^T R = I", _mod_both(R.T * R - sp.eye(3), z, c))]
    return Verdict.all_of(checks, method="exact polynomial identities modulo c^2+s^2 = 1 and "
                          "|z|^2 = 1 (half-angle point on the circle, unit axis)")


def _mod_both(residual: sp.Matrix, z, c):
    """Exact check of ``residual == 0`` modulo |z|^2 = 1 and c^2 + s^2 = 1: substitute
    c^2 -> 1 - s^2 (an exact normal form for polynomials in c), then reduce modulo |z|^2 - 1."""
    S = sp.Symbol("s", real=True)

    def normal_c(e):
        p = sp.Poly(sp.expand(e), c)
        out = 0
        for (k,), coeff in p.terms():
            out += coeff * (1 - S**2) ** (k // 2) * c ** (k % 2)
        return sp.expand(out)

    return rational_identity(residual.applyfunc(normal_c), sphere=tuple(z))


@claim("K:horizontal-sinc", uses=("S5:H-linear",), adds=(SECTION, "sin(νt)/ν = t sinc(νt) in the horizontal-solution kernel, equal to the derived solution"))
def k_horizontal_sinc() -> Verdict:
    from chaplygin_nd.symbolic.codegen.emit.reduced import horizontal_solution_stable
    from chaplygin_nd.symbolic.reduction import reduced_n4

    t, x0, G0 = sp.symbols("t x0 G0", real=True)
    nu = sp.Symbol("nu", positive=True)
    sn, cs = sp.symbols("sin_nut cos_nut", real=True)
    derived = reduced_n4.horizontal_solution(t, x0, G0, nu)
    stable = horizontal_solution_stable(t, x0, G0, nu**2)
    rule = {sp.sin(nu * t): sn, sp.cos(nu * t): cs, sp.sinc(nu * t): sn / (nu * t)}
    residual = [sp.expand(sp.sympify(p).subs(rule) - sp.sympify(q).subs(rule))
                for p, q in zip(stable, derived)]
    check = rational_identity(residual)
    return Verdict.all_of([("stable = derived (sin, cos as symbols)", check)], method=check.method)
