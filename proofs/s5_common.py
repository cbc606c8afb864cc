r"""Shared helpers of the Section 5 proofs (no claims are registered here).

* the sphere $S^3 \ni (q, x)$ and the physical samplers $a \in [-1, 1]$, $b > 0$ for the engine;
* exact rational points of the phase space $P = \mathbb{R}^3\times\mathbb{R}^3\times S^3$ and of the
  horizontal set $\mathcal{H}$;
* :func:`reduced_check`: an identity between functions of the invariants $(A,B,E,G,F_1,x,\delta)$ is
  proved in the normal form (unique, see :mod:`symbolic.reduction.invariants_n4`); if it fails, the
  counterexample is searched on $P$ through the quotient map, so it is a point of the reduced space.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.symbolic import fourd
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.exact.identity import Check, rational_identity, zero_at_points
from chaplygin_nd.symbolic.reduction import invariants_n4 as ri

a, b, x = fourd.a, fourd.b, fourd.x
k, u, q = fourd.k, fourd.u, fourd.q
SPHERE = (*q, x)
SAMPLERS = {a: lambda r: points.rational(r, -1, 1, 8),
            b: lambda r: points.rational(r, 0, 4, 8, open_lo=True)}


def on_P(residual, label: str) -> Check:
    """Engine proof of ``residual == 0`` on $P$ (modulo $\\lVert q\\rVert^2 + x^2 = 1$)."""
    return rational_identity(residual, sphere=SPHERE, samplers=SAMPLERS, label=label)


def exact(residual, label: str) -> Check:
    """Engine proof of ``residual == 0`` as a rational-function identity (no sphere relation)."""
    return rational_identity(residual, samplers=SAMPLERS, label=label)


def phase_point(rng) -> dict:
    """An exact rational point of $P$ with physical parameters: keys a, b, k, u, q, x (vectors as
    SymPy 3x1 matrices)."""
    gamma = points.sphere_point(rng, 4)
    par = points.axisymmetric_parameters(rng)
    return {"a": par["a"], "b": par["b"], "k": sp.Matrix(points.rationals(rng, 3)),
            "u": sp.Matrix(points.rationals(rng, 3)), "q": gamma[:3, 0], "x": gamma[3]}


def horizontal_point(rng) -> dict:
    r"""An exact rational point of $\mathcal{H}$ with $x \ne 0$: $k = q\times u/x$ (S5:HV4D)."""
    while True:
        pt = phase_point(rng)
        if pt["x"] != 0:
            pt["k"] = pt["q"].cross(pt["u"]) / pt["x"]
            return pt


def subs_point(pt: dict) -> dict:
    """The substitution {symbol: value} of a phase point for the symbols of :mod:`symbolic.fourd`."""
    sub = {a: pt["a"], b: pt["b"], x: pt["x"]}
    for name, vec in (("k", k), ("u", u), ("q", q)):
        sub.update(zip(vec, pt[name], strict=False))
    return sub


def invariants_at(pt: dict) -> dict:
    """The invariants $(A, B, E, G, F_1, \\delta)$ of a phase point, keyed by the symbols of
    :mod:`symbolic.reduction.invariants_n4` (plus a, b, x)."""
    kk, uu, qq = pt["k"], pt["u"], pt["q"]
    d = lambda p, r: (p.T * r)[0, 0]  # noqa: E731
    return {ri.A: d(kk, kk), ri.B: d(uu, uu), ri.E: d(kk, qq), ri.G: d(uu, qq), ri.F1: d(kk, uu),
            ri.delta: d(qq, kk.cross(uu)), a: pt["a"], b: pt["b"], x: pt["x"]}


def reduced_check(residual: sp.Expr, label: str, *, point=phase_point, count: int = 40) -> Check:
    r"""``residual`` (a rational function of $a, b, x$ and the invariants) vanishes on the reduced
    space $\mathcal{R}$. Proved when its $\delta$-linear normal form is zero (numerator reduced by
    $\delta^2 \to \det\Lambda$). The normal form is unique, so a *non-zero* normal form already
    refutes the identity on $\mathcal{R}$; the check then looks for an exact witness: up to
    ``count`` seeded points of $P$ pushed to $\mathcal{R}$ by the quotient map. If none of them
    gives a non-zero value, ``ArithmeticError`` is raised (the row becomes an error): there is no
    path from a non-zero normal form to ``holds``."""
    num, _den = sp.fraction(sp.together(residual))
    poly = ri.reduce_delta(ri.INV_RING(sp.expand(num)))
    if not poly:
        return Check(True, "exact: the numerator's delta-linear normal form (delta^2 -> det Lambda, "
                           "|q|^2 = 1 - x^2) is the zero polynomial of Q[a,b,x,A,B,E,G,F1,delta]")

    def value(pt):
        return sp.expand(residual.xreplace(invariants_at(pt)))
    found = zero_at_points(value, point, count=count, label=label,
                           describe="P pushed to the reduced space")
    if found.ok:
        raise ArithmeticError(
            f"{label}: the delta-linear normal form is non-zero (so the identity is false on R), "
            f"but no exact counterexample was found at {count} seeded points of P; refusing to decide")
    return Check(False, "exact: the numerator's delta-linear normal form is non-zero (unique normal "
                        "form, so false on R); witness " + found.method, found.counterexample)


def ring_on_P(p, label: str, *, sphere: bool = True) -> Check:
    r"""Engine proof that a polynomial ``p`` of :data:`symbolic.fourd.RING` vanishes on $P$ (its
    remainder modulo $\lVert q\rVert^2 + x^2 - 1$ is zero, computed in the sparse ring), or its
    refutation at an exact point of $P$ with physical $a, b$."""
    return rational_identity(p, sphere=SPHERE if sphere else None, samplers=SAMPLERS, label=label)
