r"""Kernels of the $SO(3)$-reduced 4D sphere on $r = (A, B, E, G, F_1, x, \delta) \in \mathbb{R}^7$.

Sources (derived): :mod:`symbolic.reduction.reduced_n4` — the reduced field (eq:red-system, derived from
scratch), the integrals $F_1, F_2, F_3, H$ (S5:red-integrals), the measure densities
(S5:red-measure), $A$ on $\mathcal{H}/SO(3)$ (eq:A-on-J) and the horizontal solution
(S5:H-linear, corrected; for every n, S5:H-linear-nD, with the blocks $A, B$ of
:func:`symbolic.reduction.reduced_n4.horizontal_blocks`). Rational quantities are numerators over $D = 2(2+a+b)\Delta(x)$ with
$\Delta$ in the stable form of row K:Delta. The horizontal solution uses
$\sin(\nu t)/\nu = t\,\operatorname{sinc}(\nu t)$ (row K:horizontal-sinc): no $0/0$ as $\nu \to 0$.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.symbolic.codegen.emit.axisym import stable_Delta
from chaplygin_nd.symbolic.codegen.emit.fourd import stable_D
from chaplygin_nd.symbolic.codegen.kernels import Argument, Kernel
from chaplygin_nd.symbolic.reduction import reduced_n4
from chaplygin_nd.symbolic.reduction.invariants_n4 import F1, A, B, E, G, delta

__all__ = ["kernels", "horizontal_solution_stable"]

a, b, x = reduced_n4.a, reduced_n4.b, reduced_n4.x
t, x0, G0, F2s, Hs, h = sp.symbols("t x0 G0 F2 H h", real=True)


def horizontal_solution_stable(t_, x0_, G0_, nu2):
    r"""$(x(t), G(t))$ of S5:H-linear (corrected, :func:`symbolic.reduction.reduced_n4.horizontal_solution`) with
    $\sin(\nu t)/\nu = t\,\operatorname{sinc}(\nu t)$ and $\nu\sin\nu t = \nu^2 t\,\operatorname{sinc}(\nu t)$,
    $\nu = \sqrt{\nu^2}$ (row K:horizontal-sinc); $\nu^2 \ge 0$."""
    S = 2 + a + b
    nu = sp.sqrt(nu2)
    c, sc = sp.cos(nu * t_), sp.sinc(nu * t_)
    return x0_ * c + G0_ * t_ * sc / S, G0_ * c - S * x0_ * nu2 * t_ * sc


def kernels() -> list[Kernel]:
    """The kernel list of ``generated/reduced_n4.py``."""
    R = Argument("r", (A, B, E, G, F1, x, delta))
    A_, B_ = Argument("a", (a,), True), Argument("b", (b,), True)
    D = stable_D()
    N = reduced_n4.field_numerators()
    F3n, H2D = reduced_n4._integral_numerators()
    nu2 = reduced_n4.horizontal_frequency_squared(Hs, F2s)
    xt, Gt = horizontal_solution_stable(t, x0, G0, nu2)
    A_level = reduced_n4.horizontal_level_A(h)
    A_level = sp.numer(A_level) / sp.factor(sp.denom(A_level))
    return [
        Kernel("reduced_field", ("eq:red-system", "K:Delta"),
               "dr/dt of the reduced field on R^7, r = (A, B, E, G, F1, x, delta) (eq:red-system, derived\n"
               "    in symbolic.reduction.reduced_n4); shape (..., 7). Domain: the reduced space delta^2 = det Lambda.",
               (R, A_, B_), sp.Matrix([N[c].as_expr() / D for c in reduced_n4.COORDS]), (7,)),
        Kernel("reduced_integrals", ("S5:red-integrals", "K:Delta"),
               "(F1, F2, F3, H) in the invariants (S5:red-integrals, derived); shape (..., 4).",
               (R, A_, B_), sp.Matrix([F1, A + B, F3n.as_expr(), H2D.as_expr() / (2 * D)]), (4,)),
        Kernel("reduced_measure_density", ("S5:red-measure", "K:Delta"),
               "(Delta^-2, 1/(Delta |delta|)): the density on R^7 preserved by the field and the density on\n"
               "    R in the chart (A, B, E, G, F1, x) of a sheet delta != 0 (S5:red-measure, corrected).",
               (R, A_, B_), sp.Matrix([1 / stable_Delta(x, a, b)**2,
                                       1 / (stable_Delta(x, a, b) * sp.Abs(delta))]), (2,)),
        Kernel("horizontal_A", ("eq:A-on-J",),
               "A on H/SO(3) at H = h as a function of (x, G) (eq:A-on-J, derived); |x| < 1.",
               (Argument("x", (x,), True), Argument("G", (G,), True), Argument("h", (h,), True), A_, B_),
               sp.Matrix([A_level]), (1,)),
        Kernel("horizontal_solution", ("S5:H-linear", "S5:H-linear-nD", "K:horizontal-sinc"),
               "(x(t), G(t)) on H/SO(3) with x(0) = x0, G(0) = G0 at F2, H (S5:H-linear, corrected):\n"
               "    nu^2 = (F2 - 2bH)/((2+a)(2+a+b)) >= 0, sin(nu t)/nu as t sinc(nu t) (K:horizontal-sinc).\n"
               "    Every n >= 3 (S5:H-linear-nD): x = gamma_n, G = <M E_n, gamma>, F2 = ||M||_kappa^2, H.",
               tuple(Argument(n_, (s_,), True) for n_, s_ in (("x0", x0), ("G0", G0), ("F2", F2s), ("H", Hs)))
               + (A_, B_, Argument("t", (t,), True)), sp.Matrix([xt, Gt]), (2,)),
        Kernel("horizontal_blocks", ("S5:H-linear-nD",),
               "(A, B) on H for every n >= 3 (S5:H-linear-nD): A = ||M - (M E_n) ^ E_n||_kappa^2,\n"
               "    B = ||M E_n||^2 from x = gamma_n, G = <M E_n, gamma>, F2 = ||M||_kappa^2 (n = 4: A, B of Section 5).",
               (Argument("x", (x,), True), Argument("G", (G,), True), Argument("F2", (F2s,), True)),
               sp.Matrix(list(reduced_n4.horizontal_blocks(x, G, F2s))), (2,)),
    ]
