r"""The ``[initial]`` table of a scene: a family to draw from (with a seed, a count or the members of
the draw, a scale) or an explicit point ($M$ or $\Omega$, and $\gamma$), checked before anything runs:
$\|\gamma\| = 1$, $M$ skew, and a family an explicit point claims (vertical, horizontal, steady
rotation) within ``tolerance``."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from chaplygin_nd.simulate.dynamics import families
from chaplygin_nd.simulate.scene.fields import array, number, unknown

__all__ = ["Initial", "table", "condition", "check_claim"]

_INITIAL = {"family", "seed", "count", "scale", "M", "Omega", "gamma", "tolerance", "members"}


@dataclass(frozen=True)
class Initial:
    """The validated keys of ``[initial]``: ``raw`` the table, ``explicit`` whether it gives the
    point, ``count`` the members asked for, ``drawn`` how many the draw makes."""

    raw: dict
    tol: float
    explicit: bool
    family: str
    seed: int | None
    count: int
    members: list | None
    drawn: int
    scale: float


def table(raw: dict, n: int, fail) -> Initial:
    """Validate the keys of ``raw["initial"]`` (the point itself is read by :func:`condition`)."""
    init = raw.get("initial", {})
    unknown(init, _INITIAL, "initial.", fail)
    tol = number(init, "tolerance", fail, default=1e-10, where="initial.tolerance")
    if not 0 < tol < 1:
        fail("initial.tolerance", f"{tol} is not in (0, 1)", "use e.g. 1e-10")
    explicit = any(k in init for k in ("M", "Omega", "gamma"))
    family = init.get("family", "explicit" if explicit else None)
    choices = families.FAMILIES + ("explicit",)
    if family not in choices:
        fail("initial.family", f"{family!r} is not a family", f"use one of {', '.join(choices)}"
             + (" or give M (or Omega) and gamma" if family is None else ""))
    if family == "explicit" and not explicit:  # no family to draw from: the point must be given
        fail("initial.M", "family = \"explicit\" needs the initial condition itself",
             f"give M (or Omega), an n x n skew-symmetric matrix, and gamma, a list of {n} "
             "numbers with |gamma| = 1; or choose a family to draw from: "
             + ", ".join(families.FAMILIES))
    if family == "steady-rotation" and n != 4:
        fail("initial.family", "steady rotation (P:steady-rot) is a 4D family",
             "set n = 4 or choose another family")
    seed = number(init, "seed", fail, integer=True, default=None, where="initial.seed")
    if seed is not None and seed < 0:
        fail("initial.seed", f"seed = {seed} is negative", "use a seed >= 0")
    count = number(init, "count", fail, integer=True, default=1, where="initial.count")
    if count < 1:
        fail("initial.count", f"count = {count}", "use count >= 1")
    members = init.get("members")
    if members is not None:
        if not (isinstance(members, list) and members and "count" not in init and all(
                isinstance(m, int) and not isinstance(m, bool) and m >= 0 for m in members)):
            fail("initial.members", f"{str(members)[:60]!r}", "a list of member indices >= 0 of "
                 "the family draw (instead of count)")
        count = len(members)  # the size check counts what is asked for and what is drawn
    drawn = max(members) + 1 if members is not None else count
    scale = number(init, "scale", fail, default=1.0, where="initial.scale")
    if not scale > 0:
        fail("initial.scale", f"scale = {scale} is not positive", "choose scale > 0")
    return Initial(init, tol, explicit, family, seed, count, members, drawn, scale)


def condition(ini: Initial, n: int, a: float, b: float, ball, fail):
    r"""``(M0, gamma0, Omega0)``: the explicit point (``Omega0`` set when $\Omega_0$ was given; an
    explicit ``M`` of a ``[ball]`` scene is the ball's, divided by $s$), or the family's draw."""
    init, tol, family, members = ini.raw, ini.tol, ini.family, ini.members
    Omega0 = None
    if not ini.explicit:
        seed = ini.seed
        if seed is None:
            fail("initial.seed", f"the {family} family needs a seed", "add seed = <integer>")
        assert seed is not None  # fail raises
        if members is not None:
            M0, gamma0 = families.draw(family, n, a, b, seed, ini.drawn, ini.scale)
            return M0[members], gamma0[members], Omega0
        M0, gamma0 = families.draw(family, n, a, b, seed, ini.count, ini.scale)
        return M0, gamma0, Omega0
    if "M" in init and "Omega" in init:
        fail("initial", "both M and Omega are given", "give one of them")
    if "gamma" not in init:
        fail("initial.gamma", "missing", f"give gamma, a list of {n} numbers with |gamma| = 1")
    if "M" not in init and "Omega" not in init:
        fail("initial.M", "missing", "give M (or Omega), an n x n skew-symmetric matrix")
    if ini.count != 1 or members is not None:
        fail("initial.count", "an explicit initial condition is one point",
             "drop count and members")
    gamma0 = array(init["gamma"], (n,), "initial.gamma", fail)
    name = "M" if "M" in init else "Omega"
    X = array(init[name], (n, n), f"initial.{name}", fail)
    skew = float(np.linalg.norm(X + X.T)) / max(1.0, float(np.linalg.norm(X)))
    if skew > tol:
        fail(f"initial.{name}", f"not skew-symmetric (|X + X^T|/|X| = {skew:.3g})",
             "give X with X[j][i] = -X[i][j] and zero diagonal")
    norm = float(np.linalg.norm(gamma0))
    if norm == 0:
        fail("initial.gamma", "gamma = 0 is not a unit vector",
             f"give a unit vector of {n} numbers, e.g. the last axis E_n")
    if abs(norm - 1.0) > tol:
        fail("initial.gamma", f"|gamma| = {norm:.17g} is not 1 within {tol:g}",
             f"normalise it: gamma / {norm:.17g}")
    if name == "M" and ball is not None:
        X = X / ball.s  # the ball's M about the contact point -> the paper's M
    if name == "Omega":
        from chaplygin_nd.simulate.kernels import active
        Omega0 = X[None]
        M0 = active().require("L_gamma")(X, gamma0, a, b)[None]
    else:
        M0 = X[None]
    gamma0 = gamma0[None]
    check_claim(family, M0[0], gamma0[0], a, b, tol, fail, Omega0)
    return M0, gamma0, Omega0


def check_claim(family, M, gamma, a, b, tol, fail, Omega):
    """Fail when an explicit point is not on the family it claims (eq:def-H-V, P:steady-rot)."""
    if family in ("vertical", "horizontal"):
        r = families.claim_residual(family, M, gamma)
        if r > tol:
            what = "M0 gamma0 = 0" if family == "vertical" else "M0 = (M0 gamma0) ^ gamma0"
            fail("initial.family", f"claims {family} momentum but {what} fails "
                 f"(relative residual {r:.3g} > {tol:g}, eq:def-H-V)",
                 f"fix M/gamma so that {what}, or set family = \"explicit\"")
    elif family == "steady-rotation":
        if Omega is None:
            from chaplygin_nd.simulate.kernels import active
            Omega = active().require("angular_velocity")(M, gamma, a, b)
        else:
            Omega = Omega[0]
        r = families.steady_residual(Omega)
        if r > tol:
            fail("initial.family", f"claims a steady rotation but eta0 x xi0 != 0 "
                 f"(relative {r:.3g} > {tol:g}, P:steady-rot)",
                 "give Omega with eta0 parallel to xi0, or set family = \"explicit\"")
