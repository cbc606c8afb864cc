r"""Scenes: TOML files that name a sphere, an initial condition, times, outputs and an accuracy.

.. code-block:: toml

    title = "generic 4D sphere"
    n = 4                 # dimension, n >= 3
    a = 0.5               # eq:axisymm, J = Id + a E_n E_n^T, a >= -1 (the paper states
                          # -1 <= a <= 1; a > 1, a prolate body, runs with a note)
    b = 1.0               # eq:M-O, b = m r^2 > 0 (a ball exists iff b >= n + a; otherwise
                          # summary.txt says that no ball has (a, b); the paper's system runs)
    radius = 1.0          # r, only used by the contact path (optional, default 1)

    # or, instead of a, b and radius, a physical ball (S4:physical-ball):
    # [ball]
    # mass = 2.0
    # radius = 0.1
    # inertia = [I1, In]  # moment of inertia in a plane containing the axis E_n, and in a
    #                     # plane orthogonal to it (n = 3: principal moments (I1, I1, I3))
    # mass_tensor = [j1, jn]  # or the mass tensor diag(j1, ..., j1, jn) about the centre
    # Then s = In/2, a = 2(I1 - In)/In, b = 2 m r^2/In; outputs are in the paper's variables
    # (M_ball = s M, H_ball = s H; Omega, gamma, x, t unchanged); an explicit initial.M is
    # the ball's angular momentum about the contact point (divided by s on input).

    [initial]             # explicit (M or Omega, and gamma) or a family with a seed
    family = "generic"    # generic | vertical | horizontal | steady-rotation | explicit
    seed = 7
    count = 1             # > 1: an ensemble, integrated vectorised
    scale = 1.0           # ||M0|| in the Killing norm (families only)
    # M = [[...], ...]    # or Omega = [[...], ...]; gamma = [...]; with family = a claim to check
    tolerance = 1e-10     # for |gamma| = 1, skewness and family claims; the planner's own
                          # membership tests use min(tolerance, 1e-12) (never looser)

    [times]
    t_end = 100.0
    samples = 1001        # or: t = [3.0, 3.5, ...] (increasing, t[0] >= 0); the initial
                          # condition is the state at t[0], for every model

    [outputs]
    want = ["M", "gamma", "x", "integrals"]

    [accuracy]
    target = 1e-10        # wanted error of every output, relative to its largest value; each
                          # method's settings come from a calibration (simulate/scene/accuracy.py)
    method = "auto"       # auto (heyoka if installed, else DOP853, else the mpmath Taylor method:
                          # the first that honours target) | heyoka | dop853 | lie | reference
    dps = 30              # digits of the reference method (at least what target needs)
    step = 0.01           # largest step of the Lie-group method (smaller when target asks)

:func:`load` reads only a regular file of at most 1 MiB (not a device or FIFO) and
validates everything before anything runs and raises one :class:`SceneError`
naming the field and the fix; that includes a memory or drawing cost past the limits of
:mod:`simulate.scene.budget` (lifted by ``force``, the command line's ``--force``), and a cost worth
mentioning is said on stderr. :func:`find` also accepts the name of a built-in scene.
"""

from __future__ import annotations

import difflib
import math
import os
import stat
import tomllib
import unicodedata
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from chaplygin_nd.simulate.dynamics import families
from chaplygin_nd.simulate.dynamics.ball import (
    Ball,
    ball_violations,
    from_mass_tensor,
    from_moments,
    parameter_violations,
)
from chaplygin_nd.simulate.integrators.settings import FLOAT64_REACH
from chaplygin_nd.simulate.scene import budget

if TYPE_CHECKING:  # pragma: no cover
    from chaplygin_nd.simulate.scene.frequency_map import FrequencyMapScene

__all__ = ["Scene", "SceneError", "OUTPUTS", "METHODS", "load", "loads", "find", "builtin_scenes"]

#: Output names a scene may ask for.
OUTPUTS = ("M", "Omega", "gamma", "x", "integrals", "zeta", "reduced", "horizontal",
           "orientation", "contact_path", "frequencies", "poincare")
METHODS = ("auto", "heyoka", "dop853", "lie", "reference")
_TOP = {"title", "n", "a", "b", "radius", "ball", "initial", "times", "outputs", "accuracy"}
_BALL = {"mass", "radius", "inertia", "mass_tensor"}
_INITIAL = {"family", "seed", "count", "scale", "M", "Omega", "gamma", "tolerance", "members"}
_TIMES = {"t_end", "samples", "t"}
_ACCURACY = {"target", "method", "dps", "step"}


class SceneError(ValueError):
    """A scene is invalid; the message names the field (not for ``where = "file"``: the file as a
    whole, which ``source`` names already) and the fix."""

    def __init__(self, source: str, where: str, problem: str, fix: str):
        self.field = where
        field = "" if where == "file" else f"{where}: "
        super().__init__(f"{source}: {field}{problem}. Fix: {fix}")


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
    name: str = "scene"
    ball: Ball | None = None
    notes: tuple[str, ...] = ()  # caveats the plan prints (e.g. a outside the paper's range)
    remarks: tuple[str, ...] = ()  # facts for the report file only (no ball has these a, b)
    figures: bool = True  # outputs.figures = false: no PNG figures (as --no-plots)

    @property
    def count(self) -> int:
        """Number of initial conditions (ensemble size)."""
        return self.M0.shape[0]


def _builtin_folder():
    return resources.files("chaplygin_nd.scenes")


def builtin_scenes() -> dict[str, str]:
    """The example scenes shipped with the package (``scenes/`` of the repository): name -> title."""
    out = {}
    for entry in sorted(_builtin_folder().iterdir(), key=lambda e: e.name):
        if entry.name.endswith(".toml"):
            title = tomllib.loads(entry.read_text(encoding="utf-8")).get("title", "")
            out[entry.name[:-5]] = title
    return out


def find(arg: str, force: bool = False) -> Scene | FrequencyMapScene:
    """The scene named by ``arg``: a scene file, else a built-in scene of that name (with or
    without ``.toml``); a :class:`SceneError` names the built-in scenes when neither exists (an
    empty or blank ``arg`` too: ``Path("")`` would be the current folder)."""
    if not str(arg).strip():
        raise SceneError(repr(arg), "file", "an empty scene name",
                         "give the path of a scene file or one of the built-in scenes: "
                         + ", ".join(builtin_scenes()))
    path = Path(arg)
    name = path.name[:-5] if path.name.endswith(".toml") else path.name
    if not path.exists() and str(path) in (name, name + ".toml"):
        entry = _builtin_folder() / f"{name}.toml"
        if entry.is_file():
            scene = loads(entry.read_text(encoding="utf-8"), source=f"built-in scene {name}",
                          force=force)
            scene.name = name
            return scene
    if not path.exists():
        close = difflib.get_close_matches(name, builtin_scenes(), n=1)
        guess = f" (did you mean {close[0]}?)" if close and str(path) in (name, name + ".toml") else ""
        raise SceneError(arg, "file", f"no such scene file or built-in scene{guess}",
                         "give the path of a scene file or one of the built-in scenes: "
                         + ", ".join(builtin_scenes()))
    return load(path, force=force)


def _check_title(raw: dict, fail) -> None:
    """A scene's ``title`` is printed on the terminal and drawn in figures: a string without
    control characters (an escape sequence such as ``\\u001b[2J`` would reach the terminal)."""
    title = raw.get("title")
    if title is None:
        return
    if not isinstance(title, str):
        fail("title", f"must be a string, not {type(title).__name__}", 'write title = "..."')
    bad = next((i for i, c in enumerate(title)
                if unicodedata.category(c) == "Cc" or c in "\u2028\u2029"), None)
    if bad is not None:
        fail("title", f"contains the control character U+{ord(title[bad]):04X} at position "
             f"{bad + 1} (escape sequences would reach the terminal)",
             "write the title as plain text, on one line")


def load(path: str | Path, force: bool = False) -> Scene | FrequencyMapScene:
    """Read and validate a scene file (see the module docstring); ``force`` lifts the memory
    limit of :mod:`simulate.scene.budget`."""
    path = Path(path)
    try:
        text = _read_limited(path).decode("utf-8")
    except OSError as exc:
        raise SceneError(str(path), "file", f"cannot read it ({exc.strerror})",
                         "give the path of a scene, e.g. scenes/generic4d.toml") from None
    except UnicodeDecodeError as exc:
        raise SceneError(str(path), "file", f"not UTF-8 text (byte {exc.start} is "
                         f"0x{exc.object[exc.start]:02x})",
                         "give a TOML scene file saved as UTF-8") from None
    scene = loads(text, source=str(path), force=force)
    scene.name = path.name[:-5] if path.name.endswith(".toml") else path.name
    return scene


#: Fewest samples a ``frequencies``/``poincare`` run accepts (simulate/analysis/naff.py: >= 14 samples).
MIN_SPECTRAL_SAMPLES = 64
#: Largest scene file read (a scene is a few hundred bytes; /dev/zero or a FIFO is refused).
MAX_BYTES = 1 << 20


def _read_limited(path: Path) -> bytes:
    """The bytes of ``path`` if it is a regular file of at most :data:`MAX_BYTES` (opened without
    blocking, so a FIFO cannot hang the run); a :class:`SceneError` otherwise."""
    fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise SceneError(str(path), "file", "not a regular file (a device, FIFO or folder)",
                             "give the path of a scene file, e.g. scenes/generic4d.toml")
        with os.fdopen(fd, "rb", closefd=False) as fh:
            data = fh.read(MAX_BYTES + 1)
    finally:
        os.close(fd)
    if len(data) > MAX_BYTES:
        raise SceneError(str(path), "file", f"larger than {MAX_BYTES >> 20} MiB, not a scene",
                         "give a scene file (a few hundred bytes of TOML)")
    return data


def loads(text: str, source: str = "<scene>", force: bool = False) -> Scene | FrequencyMapScene:
    """Validate a scene given as TOML text; raises :class:`SceneError` (also when the predicted
    memory is past the limit of :mod:`simulate.scene.budget` and ``force`` is not given)."""
    def fail(where, problem, fix):
        raise SceneError(source, where, problem, fix)

    if text.startswith("\ufeff"):  # tomllib's answer: "Invalid statement (line 1, column 1)"
        fail("file", "starts with a UTF-8 byte-order mark (BOM: the bytes EF BB BF), which TOML "
             "does not allow", "save the file as UTF-8 without a BOM")
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        fail("TOML", f"not valid TOML ({exc})", "correct the syntax at the position given")
    except RecursionError:
        fail("TOML", "arrays or tables nested too deeply", "write plain arrays of numbers")
    _check_title(raw, fail)
    if "fma" in raw:  # a frequency map (issue 16): its own keys, validated by simulate/scene/frequency_map.py
        from chaplygin_nd.simulate.scene.frequency_map import load_map
        return load_map(raw, source, fail)
    _unknown(raw, _TOP, "", fail)
    for table in ("ball", "initial", "times", "outputs", "accuracy"):
        if table in raw and not isinstance(raw[table], dict):
            fail(table, "must be a table", f"write it as [{table}]")
    n = _number(raw, "n", fail, integer=True, required=True)
    if n < 3:
        fail("n", f"n = {n} is below 3", "use n >= 3 (the sphere S^{n-1} rolls on R^{n-1})")
    a, b, radius, ball, notes, remarks = _body(raw, n, fail)

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
    if family == "explicit" and not explicit:  # no family to draw from: the point must be given
        fail("initial.M", "family = \"explicit\" needs the initial condition itself",
             f"give M (or Omega), an n x n skew-symmetric matrix, and gamma, a list of {n} "
             "numbers with |gamma| = 1; or choose a family to draw from: "
             + ", ".join(families.FAMILIES))
    if family == "steady-rotation" and n != 4:
        fail("initial.family", "steady rotation (P:steady-rot) is a 4D family",
             "set n = 4 or choose another family")
    seed = _number(init, "seed", fail, integer=True, default=None, where="initial.seed")
    if seed is not None and seed < 0:
        fail("initial.seed", f"seed = {seed} is negative", "use a seed >= 0")
    count = _number(init, "count", fail, integer=True, default=1, where="initial.count")
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
    scale = _number(init, "scale", fail, default=1.0, where="initial.scale")
    if not scale > 0:
        fail("initial.scale", f"scale = {scale} is not positive", "choose scale > 0")
    times = raw.get("times", {})
    _unknown(times, _TIMES, "times.", fail)
    samples = _samples(times, fail)
    want_list = raw.get("outputs", {}).get("want")
    outputs = [w for w in want_list if isinstance(w, str)] if isinstance(want_list, list) else []
    need = max(budget.memory_bytes(n, count, samples, outputs), 3 * 8 * drawn * (n * n + n))
    if need > budget.memory_limit() and not force:
        fail("initial.members" if members is not None else
             "times.samples" if count == 1 else "initial.count",
             f"{samples} samples x {count} initial condition(s) ({drawn} drawn) in n = {n} need about "
             f"{budget.human_bytes(need)} of memory, past the limit of "
             f"{budget.human_bytes(budget.memory_limit())}",
             "use fewer samples or initial conditions, or pass --force")
    if need > budget.memory_limit() / 8:
        budget.announce(f"about {budget.human_bytes(need)} of memory ({samples} samples x "
                        f"{count} initial condition(s))")
    draw = 0.0 if explicit else drawn * budget.DRAW_SECONDS
    if draw > budget.LIMIT_SECONDS and not force:
        fail("initial.members" if members is not None else "initial.count",
             f"drawing {drawn} initial conditions takes about {draw:.3g} s, "
             f"past the limit of {budget.LIMIT_SECONDS:g} s", "use a smaller count or pass --force")
    if draw > budget.ANNOUNCE_SECONDS:
        budget.announce(f"drawing {drawn} initial conditions: about {draw:.3g} s")
    Omega0 = None
    if explicit:
        if "M" in init and "Omega" in init:
            fail("initial", "both M and Omega are given", "give one of them")
        if "gamma" not in init:
            fail("initial.gamma", "missing", f"give gamma, a list of {n} numbers with |gamma| = 1")
        if "M" not in init and "Omega" not in init:
            fail("initial.M", "missing", "give M (or Omega), an n x n skew-symmetric matrix")
        if count != 1 or members is not None:
            fail("initial.count", "an explicit initial condition is one point",
                 "drop count and members")
        gamma0 = _array(init["gamma"], (n,), "initial.gamma", fail)
        name = "M" if "M" in init else "Omega"
        X = _array(init[name], (n, n), f"initial.{name}", fail)
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
        _check_claim(family, M0[0], gamma0[0], a, b, tol, fail, Omega0)
    else:
        if seed is None:
            fail("initial.seed", f"the {family} family needs a seed", "add seed = <integer>")
        if members is not None:
            M0, gamma0 = families.draw(family, n, a, b, seed, drawn, scale)
            M0, gamma0 = M0[members], gamma0[members]
        else:
            M0, gamma0 = families.draw(family, n, a, b, seed, count, scale)

    t = _times(times, fail)

    want = raw.get("outputs", {}).get("want")
    _unknown(raw.get("outputs", {}), {"want", "figures"}, "outputs.", fail)
    figures = raw.get("outputs", {}).get("figures", True)
    if not isinstance(figures, bool):
        fail("outputs.figures", f"figures = {figures!r} is not true or false",
             "write figures = false to skip the PNG figures (as --no-plots)")
    if not isinstance(want, list) or not want or not all(isinstance(w, str) for w in want):
        fail("outputs.want", "missing or not a list of names", f"list some of {', '.join(OUTPUTS)}")
    for w in want:
        if w not in OUTPUTS:
            fail("outputs.want", f"unknown output {w!r}", f"use names from {', '.join(OUTPUTS)}")
    spectral = [w for w in ("frequencies", "poincare") if w in want]
    if spectral and (len(t) < MIN_SPECTRAL_SAMPLES or "t" in times):
        fail("times", f"{' and '.join(spectral)} need uniformly spaced samples, at least "
             f"{MIN_SPECTRAL_SAMPLES} (NAFF splits the run in halves of >= 7 turns each)",
             "give times.t_end and times.samples >= 64 (e.g. tori4d: 4097)")
    for name in ("reduced", "frequencies", "poincare"):
        if name in want and n != 4:
            fail("outputs.want", f"{name!r} uses the reduced invariants (eq:red-system), which "
                 "exist for n = 4 only", f"remove {name!r} or set n = 4")
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
    if target < FLOAT64_REACH:  # the outputs are float64 arrays (simulate/integrators/settings.py)
        fail("accuracy.target", f"target = {target:g} is below what float64 outputs can carry "
             f"(relative {FLOAT64_REACH:.2g}: every output is stored and derived in float64)",
             f"use a target >= {FLOAT64_REACH:.2g}")
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
                 source=source, raw=raw, ball=ball, notes=tuple(notes), remarks=tuple(remarks),
                 figures=figures)


def _body(raw, n, fail):
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
        a = _number(raw, "a", fail, required=True)
        if not a >= -1.0:
            fail("a", f"a = {a:g} < -1: J = Id + a E_n E_n^T (eq:axisymm) is not positive "
                 "semidefinite, no mass distribution has it", "choose a >= -1")
        b = _number(raw, "b", fail, required=True)
        if not b > 0:
            fail("b", f"b = {b:g} is not positive (b = m r^2, eq:M-O)", "choose b > 0")
        radius = _number(raw, "radius", fail, default=1.0)
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
    _unknown(table, _BALL, "ball.", fail)
    mass = _number(table, "mass", fail, required=True, where="ball.mass")
    radius = _number(table, "radius", fail, required=True, where="ball.radius")
    for key, v in (("mass", mass), ("radius", radius)):
        if not v > 0:
            fail(f"ball.{key}", f"{key} = {v:g} is not positive", f"choose {key} > 0")
    if ("inertia" in table) == ("mass_tensor" in table):
        fail("ball", "give exactly one of inertia = [I1, In] and mass_tensor = [j1, jn]",
             "e.g. inertia = [0.4, 0.4] for a solid homogeneous ball of mass 1, radius 1")
    key = "inertia" if "inertia" in table else "mass_tensor"
    pair = _array(table[key], (2,), f"ball.{key}", fail)
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
    except (TypeError, ValueError, RecursionError, OverflowError):
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
            from chaplygin_nd.simulate.kernels import active
            Omega = active().require("angular_velocity")(M, gamma, a, b)
        else:
            Omega = Omega[0]
        r = families.steady_residual(Omega)
        if r > tol:
            fail("initial.family", f"claims a steady rotation but eta0 x xi0 != 0 "
                 f"(relative {r:.3g} > {tol:g}, P:steady-rot)",
                 "give Omega with eta0 parallel to xi0, or set family = \"explicit\"")


def _samples(times, fail):
    """The number of samples the times table asks for, checked before any array is made."""
    if "t" in times:
        return len(times["t"]) if isinstance(times["t"], list) else 2
    samples = _number(times, "samples", fail, integer=True, default=201, where="times.samples")
    if samples < 2:
        fail("times.samples", f"samples = {samples}", "use samples >= 2")
    return samples


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
        _resolvable(t, "times.t", fail)
        return t
    t_end = _number(times, "t_end", fail, required=True, where="times.t_end")
    if not t_end > 0:
        fail("times.t_end", f"t_end = {t_end} is not positive", "choose t_end > 0")
    samples = _number(times, "samples", fail, integer=True, default=201, where="times.samples")
    if samples < 2:
        fail("times.samples", f"samples = {samples}", "use samples >= 2")
    t = np.linspace(0.0, t_end, samples)
    _resolvable(t, "times.t_end", fail)
    return t


def _resolvable(t, where, fail):
    """Consecutive times at least 16 ulp apart (``t_end = 5e-324`` gives equal float64 samples)."""
    if np.any(np.diff(t) <= 16 * np.spacing(np.abs(t[1:]))) or not np.isfinite(t).all():
        fail(where, f"the sample times are not distinct in float64 (t_end = {t[-1]:g} with "
             f"{len(t)} samples)", "choose a larger t_end or fewer samples")
