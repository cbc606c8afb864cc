r"""Scenes: TOML files that name a sphere, an initial condition, times, outputs and an accuracy.

.. code-block:: toml

    title = "generic 4D sphere"
    n = 4                 # dimension, n >= 3
    a = 0.5               # eq:axisymm, J = Id + a E_n E_n^T, -1 <= a <= 1
    b = 1.0               # eq:M-O, b = m r^2 > 0
    radius = 1.0          # r, only used by the contact path (optional, default 1)

    [initial]             # explicit (M or Omega, and gamma) or a family with a seed
    family = "generic"    # generic | vertical | horizontal | steady-rotation | explicit
    seed = 7
    count = 1             # > 1: an ensemble, integrated vectorised
    scale = 1.0           # ||M0|| in the Killing norm (families only)
    # M = [[...], ...]    # or Omega = [[...], ...]; gamma = [...]; with family = a claim to check
    tolerance = 1e-10     # for |gamma| = 1, skewness and family claims

    [times]
    t_end = 100.0
    samples = 1001        # or: t = [0.0, 0.5, ...] (increasing, t[0] >= 0)

    [outputs]
    want = ["M", "gamma", "x", "integrals"]

    [accuracy]
    target = 1e-10        # wanted error; DOP853 runs at rtol = atol = target/100 (the bench
                          # measures global errors of about 8 rtol to T = 100), heyoka at
                          # tol = target/100
    method = "auto"       # auto (heyoka if installed, else dop853) | heyoka | dop853 | lie | reference
    dps = 30              # digits of the reference method
    step = 0.01           # step of the Lie-group method (which ignores target)

:func:`load` validates everything before anything runs and raises one :class:`SceneError`
naming the field and the fix.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from simulate import families

__all__ = ["Scene", "SceneError", "OUTPUTS", "METHODS", "load", "loads"]

#: Output names a scene may ask for.
OUTPUTS = ("M", "Omega", "gamma", "x", "integrals", "zeta", "reduced", "orientation",
           "contact_path")
METHODS = ("auto", "heyoka", "dop853", "lie", "reference")
_TOP = {"title", "n", "a", "b", "radius", "initial", "times", "outputs", "accuracy"}
_INITIAL = {"family", "seed", "count", "scale", "M", "Omega", "gamma", "tolerance"}
_TIMES = {"t_end", "samples", "t"}
_ACCURACY = {"target", "method", "dps", "step"}


class SceneError(ValueError):
    """A scene is invalid; the message names the field and the fix."""

    def __init__(self, source: str, where: str, problem: str, fix: str):
        self.field = where
        super().__init__(f"{source}: {where}: {problem}. Fix: {fix}")


@dataclass
class Scene:
    r"""A validated scene. ``M0`` ``(count, n, n)``, ``gamma0`` ``(count, n)``; ``Omega0`` is set when
    the scene gave $\Omega_0$ (else computed on demand by the planner)."""

    title: str
    n: int
    a: float
    b: float
    radius: float
    family: str
    claimed: bool
    seed: int | None
    M0: np.ndarray
    gamma0: np.ndarray
    Omega0: np.ndarray | None
    t: np.ndarray
    outputs: tuple[str, ...]
    target: float
    method: str
    dps: int
    step: float
    tolerance: float
    source: str = "<scene>"
    raw: dict = field(default_factory=dict, repr=False)

    @property
    def count(self) -> int:
        """Number of initial conditions (ensemble size)."""
        return self.M0.shape[0]


def load(path: str | Path) -> Scene:
    """Read and validate a scene file (see the module docstring)."""
    path = Path(path)
    try:
        text = path.read_text()
    except OSError as exc:
        raise SceneError(str(path), "file", f"cannot read it ({exc.strerror})",
                         "give the path of a scene, e.g. scenes/generic4d.toml") from None
    return loads(text, source=str(path))


def loads(text: str, source: str = "<scene>") -> Scene:
    """Validate a scene given as TOML text; raises :class:`SceneError`."""
    def fail(where, problem, fix):
        raise SceneError(source, where, problem, fix)

    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        fail("TOML", f"not valid TOML ({exc})", "correct the syntax at the position given")
    _unknown(raw, _TOP, "", fail)
    for table in ("initial", "times", "outputs", "accuracy"):
        if table in raw and not isinstance(raw[table], dict):
            fail(table, "must be a table", f"write it as [{table}]")
    n = _number(raw, "n", fail, integer=True, required=True)
    if n < 3:
        fail("n", f"n = {n} is below 3", "use n >= 3 (the sphere S^{n-1} rolls on R^{n-1})")
    a = _number(raw, "a", fail, required=True)
    if not -1.0 <= a <= 1.0:
        fail("a", f"a = {a} is outside [-1, 1] (eq:axisymm)", "choose -1 <= a <= 1")
    b = _number(raw, "b", fail, required=True)
    if not b > 0:
        fail("b", f"b = {b} is not positive (b = m r^2, eq:M-O)", "choose b > 0")
    radius = _number(raw, "radius", fail, default=1.0)
    if not radius > 0:
        fail("radius", f"radius = {radius} is not positive", "choose radius > 0")

    init = raw.get("initial", {})
    _unknown(init, _INITIAL, "initial.", fail)
    tol = _number(init, "tolerance", fail, default=1e-10, where="initial.tolerance")
    if not 0 < tol < 1:
        fail("initial.tolerance", f"{tol} is not in (0, 1)", "use e.g. 1e-10")
    explicit = any(k in init for k in ("M", "Omega", "gamma"))
    family = init.get("family", "explicit" if explicit else None)
    choices = families.FAMILIES + ("explicit",)
    if family not in choices:
        fail("initial.family", f"{family!r} is not a family", f"use one of {', '.join(choices)}"
             + (" or give M (or Omega) and gamma" if family is None else ""))
    if family == "steady-rotation" and n != 4:
        fail("initial.family", "steady rotation (P:steady-rot) is a 4D family",
             "set n = 4 or choose another family")
    seed = _number(init, "seed", fail, integer=True, default=None, where="initial.seed")
    count = _number(init, "count", fail, integer=True, default=1, where="initial.count")
    if count < 1:
        fail("initial.count", f"count = {count}", "use count >= 1")
    scale = _number(init, "scale", fail, default=1.0, where="initial.scale")
    if not scale > 0:
        fail("initial.scale", f"scale = {scale} is not positive", "choose scale > 0")
    Omega0 = None
    if explicit:
        if "M" in init and "Omega" in init:
            fail("initial", "both M and Omega are given", "give one of them")
        if "gamma" not in init:
            fail("initial.gamma", "missing", f"give gamma, a list of {n} numbers with |gamma| = 1")
        if "M" not in init and "Omega" not in init:
            fail("initial.M", "missing", "give M (or Omega), an n x n skew-symmetric matrix")
        if count != 1:
            fail("initial.count", "an explicit initial condition is one point", "drop count")
        gamma0 = _array(init["gamma"], (n,), "initial.gamma", fail)
        name = "M" if "M" in init else "Omega"
        X = _array(init[name], (n, n), f"initial.{name}", fail)
        skew = np.linalg.norm(X + X.T) / max(1.0, np.linalg.norm(X))
        if skew > tol:
            fail(f"initial.{name}", f"not skew-symmetric (|X + X^T|/|X| = {skew:.3g})",
                 "give X with X[j][i] = -X[i][j] and zero diagonal")
        norm = np.linalg.norm(gamma0)
        if abs(norm - 1.0) > tol:
            fail("initial.gamma", f"|gamma| = {norm!r} is not 1 within {tol:g}",
                 f"normalise it: gamma / {norm:.17g}")
        if name == "Omega":
            from simulate.dispatch import active
            Omega0 = X[None]
            M0 = active().require("L_gamma")(X, gamma0, a, b)[None]
        else:
            M0 = X[None]
        gamma0 = gamma0[None]
        _check_claim(family, M0[0], gamma0[0], a, b, tol, fail, Omega0)
    else:
        if seed is None:
            fail("initial.seed", f"the {family} family needs a seed", "add seed = <integer>")
        M0, gamma0 = families.draw(family, n, a, b, seed, count, scale)

    times = raw.get("times", {})
    _unknown(times, _TIMES, "times.", fail)
    t = _times(times, fail)

    want = raw.get("outputs", {}).get("want")
    _unknown(raw.get("outputs", {}), {"want"}, "outputs.", fail)
    if not isinstance(want, list) or not want or not all(isinstance(w, str) for w in want):
        fail("outputs.want", "missing or not a list of names", f"list some of {', '.join(OUTPUTS)}")
    for w in want:
        if w not in OUTPUTS:
            fail("outputs.want", f"unknown output {w!r}", f"use names from {', '.join(OUTPUTS)}")
    if "reduced" in want and n != 4:
        fail("outputs.want", "the reduced invariants (eq:red-system) exist for n = 4 only",
             "remove 'reduced' or set n = 4")
    if "zeta" in want and family not in ("vertical",) and not (
            family == "explicit" and all(
                families.claim_residual("vertical", M, g) <= tol for M, g in zip(M0, gamma0, strict=True))):
        fail("outputs.want", "zeta (Th:Re) is defined for vertical momentum only",
             "remove 'zeta' or use a vertical initial condition (M0 gamma0 = 0)")

    acc = raw.get("accuracy", {})
    _unknown(acc, _ACCURACY, "accuracy.", fail)
    target = _number(acc, "target", fail, default=1e-10, where="accuracy.target")
    if not 0 < target < 1:
        fail("accuracy.target", f"target = {target} is not in (0, 1)", "use e.g. 1e-10")
    method = acc.get("method", "auto")
    if method not in METHODS:
        fail("accuracy.method", f"unknown method {method!r}", f"use one of {', '.join(METHODS)}")
    dps = _number(acc, "dps", fail, integer=True, default=30, where="accuracy.dps")
    if not 15 <= dps <= 200:
        fail("accuracy.dps", f"dps = {dps}", "use 15 <= dps <= 200")
    step = _number(acc, "step", fail, default=0.01, where="accuracy.step")
    if not step > 0:
        fail("accuracy.step", f"step = {step} is not positive", "use e.g. 0.01")

    return Scene(title=str(raw.get("title", source)), n=n, a=a, b=b, radius=radius,
                 family=family, claimed=explicit and family != "explicit", seed=seed, M0=M0,
                 gamma0=gamma0, Omega0=Omega0, t=t, outputs=tuple(dict.fromkeys(want)),
                 target=target, method=method, dps=dps, step=step, tolerance=tol,
                 source=source, raw=raw)


def _unknown(table, allowed, prefix, fail):
    for key in table:
        if key not in allowed:
            fail(f"{prefix}{key}", "unknown key", f"use only {', '.join(sorted(allowed))}")


def _number(table, key, fail, integer=False, required=False, default=0.0, where=None):
    where = where or key
    if key not in table:
        if required:
            fail(where, "missing", f"add {key} = <{'integer' if integer else 'number'}>")
        return default
    v = table[key]
    ok = isinstance(v, int) if integer else isinstance(v, (int, float))
    if isinstance(v, bool) or not ok or (not integer and not math.isfinite(v)):
        fail(where, f"{v!r} is not a finite {'integer' if integer else 'number'}",
             f"write {key} = <{'integer' if integer else 'number'}>")
    return int(v) if integer else float(v)


def _array(value, shape, where, fail):
    try:
        arr = np.array(value, dtype=float)
    except (TypeError, ValueError):
        fail(where, "not a rectangular array of numbers", f"give an array of shape {shape}")
    if arr.shape != shape:
        fail(where, f"shape {arr.shape}, expected {shape}", f"give an array of shape {shape}")
    if not np.all(np.isfinite(arr)):
        fail(where, "contains a non-finite number", "give finite numbers")
    return arr


def _check_claim(family, M, gamma, a, b, tol, fail, Omega):
    if family in ("vertical", "horizontal"):
        r = families.claim_residual(family, M, gamma)
        if r > tol:
            what = "M0 gamma0 = 0" if family == "vertical" else "M0 = (M0 gamma0) ^ gamma0"
            fail("initial.family", f"claims {family} momentum but {what} fails "
                 f"(relative residual {r:.3g} > {tol:g}, eq:def-H-V)",
                 f"fix M/gamma so that {what}, or set family = \"explicit\"")
    elif family == "steady-rotation":
        if Omega is None:
            from simulate.dispatch import active
            Omega = active().require("angular_velocity")(M, gamma, a, b)
        else:
            Omega = Omega[0]
        r = families.steady_residual(Omega)
        if r > tol:
            fail("initial.family", f"claims a steady rotation but eta0 x xi0 != 0 "
                 f"(relative {r:.3g} > {tol:g}, P:steady-rot)",
                 "give Omega with eta0 parallel to xi0, or set family = \"explicit\"")


def _times(times, fail):
    if "t" in times:
        if "t_end" in times or "samples" in times:
            fail("times", "both t and t_end/samples are given", "give one of them")
        if not isinstance(times["t"], list):
            fail("times.t", "not a list", "e.g. t = [0.0, 1.0, 2.0]")
        t = _array(times["t"], (len(times["t"]),), "times.t", fail)
        if t.size < 2 or t[0] < 0 or np.any(np.diff(t) <= 0):
            fail("times.t", "not an increasing list of >= 2 times starting at t >= 0",
                 "e.g. t = [0.0, 1.0, 2.0]")
        return t
    t_end = _number(times, "t_end", fail, required=True, where="times.t_end")
    if not t_end > 0:
        fail("times.t_end", f"t_end = {t_end} is not positive", "choose t_end > 0")
    samples = _number(times, "samples", fail, integer=True, default=201, where="times.samples")
    if samples < 2:
        fail("times.samples", f"samples = {samples}", "use samples >= 2")
    return np.linspace(0.0, t_end, samples)
