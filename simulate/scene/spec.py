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
from chaplygin_nd.simulate.dynamics.ball import Ball
from chaplygin_nd.simulate.integrators.settings import FLOAT64_REACH
from chaplygin_nd.simulate.scene import budget, initial
from chaplygin_nd.simulate.scene import times as sample_times
from chaplygin_nd.simulate.scene.body import body
from chaplygin_nd.simulate.scene.fields import SceneError
from chaplygin_nd.simulate.scene.fields import number as _number
from chaplygin_nd.simulate.scene.fields import unknown as _unknown

if TYPE_CHECKING:  # pragma: no cover
    from chaplygin_nd.simulate.scene.frequency_map import FrequencyMapScene

__all__ = ["Scene", "SceneError", "outputs", "methods", "load", "loads", "find", "builtin_scenes"]

_TOP = {"title", "n", "a", "b", "radius", "ball", "initial", "times", "outputs", "accuracy"}
_ACCURACY = {"target", "method", "dps", "step"}


def outputs() -> tuple[str, ...]:
    """Output names a scene may ask for (:mod:`simulate.scene.output_registry`)."""
    from chaplygin_nd.simulate.scene import output_registry

    return output_registry.names()


def methods() -> tuple[str, ...]:
    """What ``accuracy.method`` may say: ``auto`` or an integrator a scene may name
    (:mod:`simulate.integrators.registry`)."""
    from chaplygin_nd.simulate.integrators import registry

    return ("auto", *registry.named())


def __getattr__(name: str):
    """``OUTPUTS`` and ``METHODS``, read from the registries when first asked for."""
    if name == "OUTPUTS":
        return outputs()
    if name == "METHODS":
        return methods()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


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
    without ``.toml``; a folder of that name, e.g. the output folder of an earlier run, is not a
    scene file and does not hide it); a :class:`SceneError` names the built-in scenes when neither
    exists (an empty or blank ``arg`` too: ``Path("")`` would be the current folder)."""
    if not str(arg).strip():
        raise SceneError(repr(arg), "file", "an empty scene name",
                         "give the path of a scene file or one of the built-in scenes: "
                         + ", ".join(builtin_scenes()))
    path = Path(arg)
    name = path.name[:-5] if path.name.endswith(".toml") else path.name
    if not path.is_file() and str(path) in (name, name + ".toml"):
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
    memory is past the limit of :mod:`simulate.scene.budget` and ``force`` is not given). The
    tables are checked in this order: the body, ``[initial]``, the size of the run, the initial
    point, ``[times]``, ``[outputs]``, ``[accuracy]``."""
    def fail(where, problem, fix):
        raise SceneError(source, where, problem, fix)

    raw = _parse(text, fail)
    if "fma" in raw:  # a frequency map: its own keys, validated by simulate/scene/frequency_map.py
        from chaplygin_nd.simulate.scene.frequency_map import load_map
        return load_map(raw, source, fail)
    _unknown(raw, _TOP, "", fail)
    for table in ("ball", "initial", "times", "outputs", "accuracy"):
        if table in raw and not isinstance(raw[table], dict):
            fail(table, "must be a table", f"write it as [{table}]")
    n = _number(raw, "n", fail, integer=True, required=True)
    if n < 3:
        fail("n", f"n = {n} is below 3", "use n >= 3 (the sphere S^{n-1} rolls on R^{n-1})")
    a, b, radius, ball, notes, remarks = body(raw, n, fail)
    ini = initial.table(raw, n, fail)
    times = raw.get("times", {})
    _unknown(times, sample_times.KEYS, "times.", fail)
    _check_size(raw, n, ini, sample_times.samples(times, fail), force, fail)
    M0, gamma0, Omega0 = initial.condition(ini, n, a, b, ball, fail)
    t = sample_times.times(times, fail)
    want, figures = _outputs(raw, n, t, times, ini, M0, gamma0, fail)
    target, method, dps, step = _accuracy(raw, fail)
    return Scene(title=str(raw.get("title", source)), n=n, a=a, b=b, radius=radius,
                 family=ini.family, claimed=ini.explicit and ini.family != "explicit",
                 seed=ini.seed, M0=M0, gamma0=gamma0, Omega0=Omega0, t=t,
                 outputs=tuple(dict.fromkeys(want)), target=target, method=method, dps=dps,
                 step=step, tolerance=ini.tol, source=source, raw=raw, ball=ball,
                 notes=tuple(notes), remarks=tuple(remarks), figures=figures)


def _parse(text: str, fail) -> dict:
    """The TOML of a scene, its title checked."""
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
    return raw


def _check_size(raw: dict, n: int, ini: initial.Initial, samples: int, force: bool, fail) -> None:
    """Refuse (unless ``force``) or announce the memory of the run and the time of the draw
    (:mod:`simulate.scene.budget`), before any array is made."""
    count, drawn, members = ini.count, ini.drawn, ini.members
    want_list = raw.get("outputs", {}).get("want")
    wanted = [w for w in want_list if isinstance(w, str)] if isinstance(want_list, list) else []
    need = max(budget.memory_bytes(n, count, samples, wanted), 3 * 8 * drawn * (n * n + n))
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
    draw = 0.0 if ini.explicit else drawn * budget.DRAW_SECONDS
    if draw > budget.LIMIT_SECONDS and not force:
        fail("initial.members" if members is not None else "initial.count",
             f"drawing {drawn} initial conditions takes about {draw:.3g} s, "
             f"past the limit of {budget.LIMIT_SECONDS:g} s", "use a smaller count or pass --force")
    if draw > budget.ANNOUNCE_SECONDS:
        budget.announce(f"drawing {drawn} initial conditions: about {draw:.3g} s")


def _outputs(raw: dict, n: int, t, times: dict, ini: initial.Initial, M0, gamma0, fail):
    """``(want, figures)`` of ``[outputs]``, each name checked against what its registered output
    needs (:mod:`simulate.scene.output_registry`: the one n it exists for, uniformly spaced
    samples, vertical momentum)."""
    from chaplygin_nd.simulate.scene import output_registry

    names = outputs()
    want = raw.get("outputs", {}).get("want")
    _unknown(raw.get("outputs", {}), {"want", "figures"}, "outputs.", fail)
    figures = raw.get("outputs", {}).get("figures", True)
    if not isinstance(figures, bool):
        fail("outputs.figures", f"figures = {figures!r} is not true or false",
             "write figures = false to skip the PNG figures (as --no-plots)")
    if not isinstance(want, list) or not want or not all(isinstance(w, str) for w in want):
        fail("outputs.want", "missing or not a list of names", f"list some of {', '.join(names)}")
    for w in want:
        if w not in names:
            fail("outputs.want", f"unknown output {w!r}", f"use names from {', '.join(names)}")
    entries = [output_registry.get(name) for name in names if name in want]
    spectral = [e.name for e in entries if e.spectral]
    if spectral and (len(t) < MIN_SPECTRAL_SAMPLES or "t" in times):
        fail("times", f"{' and '.join(spectral)} need uniformly spaced samples, at least "
             f"{MIN_SPECTRAL_SAMPLES} (NAFF splits the run in halves of >= 7 turns each)",
             "give times.t_end and times.samples >= 64 (e.g. tori4d: 4097)")
    for e in entries:
        if e.only_n is not None and n != e.only_n:
            fail("outputs.want", f"{e.name!r} uses the reduced invariants (eq:red-system), which "
                 f"exist for n = {e.only_n} only", f"remove {e.name!r} or set n = {e.only_n}")
    def vertical() -> bool:
        return ini.family == "vertical" or (ini.family == "explicit" and all(
            families.claim_residual("vertical", M, g) <= ini.tol
            for M, g in zip(M0, gamma0, strict=True)))

    for e in entries:
        if e.vertical and not vertical():
            fail("outputs.want", f"{e.name} (Th:Re) is defined for vertical momentum only",
                 f"remove '{e.name}' or use a vertical initial condition (M0 gamma0 = 0)")
    return want, figures


def _accuracy(raw: dict, fail) -> tuple[float, str, int, float]:
    """``(target, method, dps, step)`` of ``[accuracy]``."""
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
    allowed = methods()
    if method not in allowed:
        fail("accuracy.method", f"unknown method {method!r}", f"use one of {', '.join(allowed)}")
    dps = _number(acc, "dps", fail, integer=True, default=30, where="accuracy.dps")
    if not 15 <= dps <= 200:
        fail("accuracy.dps", f"dps = {dps}", "use 15 <= dps <= 200")
    step = _number(acc, "step", fail, default=0.01, where="accuracy.step")
    if not step > 0:
        fail("accuracy.step", f"step = {step} is not positive", "use e.g. 0.01")
    return target, method, dps, step
