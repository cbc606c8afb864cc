r"""The body of a scene: the paper's parameters $a$, $b$ and the radius, or a physical ball given by
its mass, radius and moments (S4:physical-ball), with what the plan and the report say about them."""

from __future__ import annotations

import math

from chaplygin_nd.simulate.dynamics.ball import (
    ball_violations,
    from_mass_tensor,
    from_moments,
    parameter_violations,
)
from chaplygin_nd.simulate.scene.fields import array, number, unknown

__all__ = ["body"]

_BALL = {"mass", "radius", "inertia", "mass_tensor"}


def body(raw, n, fail):
    """(a, b, radius, ball, notes, remarks) from either ``a, b[, radius]`` or a ``[ball]`` table
    (S4:physical-ball); realisability as in :mod:`simulate.dynamics.ball`.

    An ``(a, b)`` with ``b < n + a`` is the paper's system (eq:M-O holds for every ``b > 0``, and
    no claim needs more) but no ball of matter: ``tr J > m r^2`` puts the mass, on average, beyond
    the contact radius. That is a remark for the report file (summary.txt), not a caveat printed
    with the plan: the run is exactly what the scene asked for, most built-in scenes take such
    values from the paper's abstract setting, and a scene that means a physical ball gives a
    ``[ball]`` table, which refuses an impossible one with an error."""
    notes: list[str] = []
    remarks: list[str] = []
    if "ball" not in raw:
        a = number(raw, "a", fail, required=True)
        if not a >= -1.0:
            fail("a", f"a = {a:g} < -1: J = Id + a E_n E_n^T (eq:axisymm) is not positive "
                 "semidefinite, no mass distribution has it", "choose a >= -1")
        b = number(raw, "b", fail, required=True)
        if not b > 0:
            fail("b", f"b = {b:g} is not positive (b = m r^2, eq:M-O)", "choose b > 0")
        radius = number(raw, "radius", fail, default=1.0)
        if not radius > 0:
            fail("radius", f"radius = {radius:g} is not positive", "choose radius > 0")
        if a > 1.0:
            notes.append(f"a = {a:g} is outside the paper's stated range a in [-1, 1] "
                         "(eq:axisymm): a prolate body, physical (S4:physical-ball); Delta(x) > 0 "
                         "for every a > -2 (eq:Delta), so L_gamma is invertible (P:Measure)")
        bad = parameter_violations(n, a, b)
        if bad:
            remarks.append("no ball of matter has these (a, b): " + "; ".join(bad)
                           + "; the run is the paper's system, which holds for any b > 0 "
                           "(a physical ball is given as a [ball] table)")
        return a, b, radius, None, notes, remarks
    for key in ("a", "b", "radius"):
        if key in raw:
            fail(key, f"{key} is given together with [ball]",
                 f"remove {key}: it follows from the ball (S4:physical-ball)")
    table = raw["ball"]
    unknown(table, _BALL, "ball.", fail)
    mass = number(table, "mass", fail, required=True, where="ball.mass")
    radius = number(table, "radius", fail, required=True, where="ball.radius")
    for key, v in (("mass", mass), ("radius", radius)):
        if not v > 0:
            fail(f"ball.{key}", f"{key} = {v:g} is not positive", f"choose {key} > 0")
    if ("inertia" in table) == ("mass_tensor" in table):
        fail("ball", "give exactly one of inertia = [I1, In] and mass_tensor = [j1, jn]",
             "e.g. inertia = [0.4, 0.4] for a solid homogeneous ball of mass 1, radius 1")
    key = "inertia" if "inertia" in table else "mass_tensor"
    pair = array(table[key], (2,), f"ball.{key}", fail)
    make = from_moments if key == "inertia" else from_mass_tensor
    ball = make(n, mass, radius, *pair)
    bad = ball_violations(ball)
    if bad:
        fail(f"ball.{key}", "no mass distribution inside the radius has these moments: "
             + "; ".join(bad), "give moments with 2 I1 >= In > 0 and I1 + (n-2) In/2 <= m r^2")
    a, b = ball.a, ball.b
    if not (math.isfinite(a) and math.isfinite(b) and b > 0):
        fail(f"ball.{key}", f"the paper's parameters a = {a:g}, b = {b:g} are not finite positive "
             "numbers", "give moments of a size comparable with m r^2")
    notes.append(f"ball m = {mass:g}, r = {radius:g}, I1 = {ball.I1:g}, In = {ball.In:g} -> "
                 f"s = In/2 = {ball.s:g}, a = 2(I1 - In)/In = {a:g}, b = 2 m r^2/In = {b:g} "
                 "(S4:physical-ball); outputs are the paper's variables: M_ball = s M, "
                 "H_ball = s H; Omega, gamma, x, t unchanged")
    if a > 1.0:
        notes.append(f"a = {a:g} is outside the paper's stated range a in [-1, 1] (eq:axisymm): "
                     "a prolate body, physical (S4:physical-ball)")
    return a, b, radius, ball, notes, remarks
