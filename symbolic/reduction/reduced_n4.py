r"""The $SO(3)$-reduced 4D axisymmetric Chaplygin sphere (Section 5), derived from scratch.

**The reduced field (derives eq:red-system).** Each invariant $f \in \{A, B, E, G, F_1, x, \delta\}$
(:mod:`symbolic.reduction.invariants_n4`) is differentiated along the explicit 4D field of
:mod:`symbolic.fourd` (itself derived from $\dot M = [M,\Omega]$, $\dot\gamma = -\Omega\gamma$ and the
solved inverse of $L_\gamma$):

.. math::
    \dot A = 2\langle k, \dot k\rangle,\ \dot B = 2\langle u, \dot u\rangle,\
    \dot E = \langle\dot k, q\rangle + \langle k, \dot q\rangle,\
    \dot G = \langle\dot u, q\rangle + \langle u, \dot q\rangle,\
    \dot F_1 = \langle\dot k, u\rangle + \langle k, \dot u\rangle,\
    \dot\delta = \langle\dot q, k\times u\rangle + \langle q, \dot k\times u\rangle + \langle q, k\times\dot u\rangle.

Times the common denominator $D = 2(2+a+b)\Delta(x)$ each is an $SO(3)$-invariant polynomial, which
:func:`symbolic.reduction.invariants_n4.in_invariants` writes in its unique normal form, linear in
$\delta$ with $\lVert q\rVert^2 = 1 - x^2$ (invariant theory + exact linear algebra). The result is a
vector field on $\mathbb{R}^7 \ni (A, B, E, G, F_1, x, \delta)$ whose restriction to the reduced space
$\mathcal{R}$ is the reduced dynamics.

**Reduced measure.** The pushforward of $\mu = \Delta^{-1}dk\,du\,d\sigma_{S^3}$ (S5:measure4D) to
$\mathcal{R}$ has density $\Delta(x)^{-1}|\delta|^{-1}$ in the chart $(A, B, E, G, F_1, x)$ of each sheet
$\pm\delta > 0$ (the Gram map pushes $dk\,du\,dq$ to $\propto(\det\Lambda)^{-1/2}$ times Lebesgue).
Row S5:red-measure proves it, and that $\Delta^{-2}$ is the density on $\mathbb{R}^7$ preserved by the
normal-form field (the kernel ``reduced_measure_density`` evaluates both).
"""

from __future__ import annotations

from functools import cache

import sympy as sp
from chaplygin_nd.symbolic import fourd
from chaplygin_nd.symbolic.reduction import invariants_n4 as ri
from chaplygin_nd.symbolic.reduction.invariants_n4 import F1, A, B, E, G, delta

__all__ = [
    "COORDS", "field_numerators", "field", "integrals", "horizontal_set", "vertical_set",
    "horizontal_level_A", "horizontal_frequency_squared", "horizontal_solution",
    "horizontal_blocks",
]

a, b, x = fourd.a, fourd.b, fourd.x
#: Coordinates of the ambient $\mathbb{R}^7$, in the order of the paper's eq:red-system.
COORDS = ("A", "B", "E", "G", "F1", "x", "delta")
SYMBOLS = {"A": A, "B": B, "E": E, "G": G, "F1": F1, "x": x, "delta": delta}
S = 2 + a + b
Delta = (2 + a) * (2 + b) - a * b * x**2
D = 2 * S * Delta


@cache
def field_numerators():
    r"""$D\cdot\dot f$ for $f$ in :data:`COORDS`, derived, as elements of
    :data:`symbolic.reduction.invariants_n4.INV_RING` (normal form, linear in $\delta$). eq:red-system."""
    dot, cross = fourd.dot, fourd.cross
    k, u, q = fourd._k, fourd._u, fourd._q
    Nk, Nu, Nq, Nx = fourd.field_numerators()
    raw = {
        "A": 2 * dot(k, Nk), "B": 2 * dot(u, Nu), "E": dot(Nk, q) + dot(k, Nq),
        "G": dot(Nu, q) + dot(u, Nq), "F1": dot(Nk, u) + dot(k, Nu), "x": Nx,
        "delta": dot(Nq, cross(k, u)) + dot(q, cross(Nk, u)) + dot(q, cross(k, Nu)),
    }
    return {name: ri.in_invariants(N) for name, N in raw.items()}


def field():
    r"""The reduced vector field on $\mathbb{R}^7$ (eq:red-system, derived): dict coordinate name ->
    SymPy rational expression in $a, b, A, B, E, G, F_1, x, \delta$ (denominator $D$)."""
    return {n: p.as_expr() / D for n, p in field_numerators().items()}


@cache
def _integral_numerators():
    F3 = ri.in_invariants(fourd.F3())
    H2D = ri.in_invariants(fourd.energy())  # 2 D H
    return F3, H2D


def integrals():
    r"""The integrals in the invariants (S5:red-integrals, derived from the 4D integrals
    $F_1, F_2, F_3, H$ by :func:`symbolic.reduction.invariants_n4.in_invariants`): dict
    ``F1, F2, F3, H`` -> SymPy expression in $a, b, A, B, E, G, F_1, x, \delta$."""
    F3, H2D = _integral_numerators()
    return {"F1": F1, "F2": A + B, "F3": F3.as_expr(), "H": H2D.as_expr() / (2 * D)}


def horizontal_set():
    r"""$\mathcal{H}/SO(3)$ (S5:H-SO3, derived from $k = q\times u/x$ on $\mathcal{H}$, $x\neq0$):
    substitutions expressing $F_1, E, \delta, B$ through the coordinates $(A, G, x)$."""
    return {F1: 0, E: 0, delta: -x * A, B: (x**2 * A + G**2) / (1 - x**2)}


def vertical_set():
    r"""$\mathcal{V}/SO(3)$ (S5:V-SO3, derived from $u = -k\times q/x$ on $\mathcal{V}$, $x\ne0$):
    substitutions expressing $G, F_1, \delta, A$ through the coordinates $(B, E, x)$."""
    return {G: 0, F1: 0, delta: x * B, A: (E**2 + x**2 * B) / (1 - x**2)}


def horizontal_level_A(h):
    r"""$A$ on $\mathcal{H}/SO(3)\cap\{H = h\}$ as a function of $(x, G)$, solved from the derived $H$
    (eq:A-on-J): $A = \Delta(x)\,(2hS(1-x^2) - G^2)/(S(2 + a(1-x^2)))$, $S = 2+a+b$; $|x| < 1$."""
    H = integrals()["H"].subs(horizontal_set(), simultaneous=True)
    sol = sp.solve(sp.Eq(sp.together(H), h), A)
    if len(sol) != 1:
        raise ArithmeticError("H is not linear in A on H/SO(3)")
    return sp.factor(sol[0])


def horizontal_frequency_squared(h, f2):
    r"""$\nu^2 = (f_2 - 2bh)/((2+a)(2+a+b))$: on $\mathcal{H}/SO(3)$, $\dot x = G/S$ and
    $\dot G = -\tfrac{f_2-2bh}{2+a}x$ give $\ddot x = -\nu^2 x$ (S5:H-linear, corrected frequency)."""
    return (f2 - 2 * b * h) / ((2 + a) * S)


def horizontal_solution(t, x0, G0, nu):
    r"""$(x(t), G(t))$ on $\mathcal{H}/SO(3)$ (S5:H-linear, corrected): with $\nu$ from
    :func:`horizontal_frequency_squared` ($\nu > 0$),
    $x = x_0\cos\nu t + \tfrac{G_0}{S\nu}\sin\nu t$, $G = S\dot x = G_0\cos\nu t - S x_0\nu\sin\nu t$."""
    c, s_ = sp.cos(nu * t), sp.sin(nu * t)
    return x0 * c + G0 / (S * nu) * s_, G0 * c - S * x0 * nu * s_


def horizontal_blocks(x_, G_, f2):
    r"""$(A, B)$ on $\mathcal{H}$ for every $n \ge 3$ (S5:H-linear-nD; for $n = 4$ the $A, B$ of
    Section 5): $A = \lVert M - (ME_n)\wedge E_n\rVert_\kappa^2$, $B = \lVert ME_n\rVert^2$ from
    $x = \gamma_n$, $G = \langle ME_n, \gamma\rangle$, $f_2 = \lVert M\rVert_\kappa^2 = A + B$.
    Derivation: on $\mathcal{H}$, $M = m\wedge\gamma$ with $m = M\gamma \perp \gamma$, so $f_2 = \lVert m\rVert^2$,
    $ME_n = x\,m - m_n\gamma$, $G = -m_n$ and $B = x^2\lVert m\rVert^2 + m_n^2 = x^2f_2 + G^2$;
    $A = f_2 - B = (1-x^2)f_2 - G^2$ (proved exactly in row S5:H-linear-nD, eq:A-on-J second form)."""
    B_ = x_**2 * f2 + G_**2
    return f2 - B_, B_
