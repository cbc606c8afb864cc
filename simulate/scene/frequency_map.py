r"""Scenes with an ``[fma]`` table: a frequency map of the 4D sphere beside one of a control
(:mod:`simulate.analysis.fma`). Validated here, run by ``chaplygin simulate``.

.. code-block:: toml

    title = "..."
    n = 4                    # frequency maps are for n = 4
    a = -0.5                 # eq:axisymm, a > -1
    b = 0.5                  # eq:M-O, b > 0

    [fma]
    energy = 0.5             # the level set H = energy (S2.2:energy), > 0
    grid = 200               # grid x grid initial conditions per map, 2..2000
    samples = 2048           # samples per half orbit (>= 64); the orbit lasts 2 samples dt
    dt = 0.5                 # sampling step (Nyquist pi/dt above the fundamental frequencies)
    seed = 1                 # of the two skew matrices P, Q spanning the M0 directions
    x_range = [-0.9, 0.9]    # the x0 = gamma_4 axis, inside (-1, 1)
    control_J = [1.0, 1.3, 0.75, 0.5]   # the control's diagonal mass tensor, J_i > 0
    tol = 1e-12              # Taylor tolerance (heyoka)
    chunk = 64               # orbits per task

Writes ``fma_axisymmetric.png``, ``fma_control.png`` (the two maps; not with ``--no-plots``),
``fma.npz`` (the diffusion arrays and the axes) and ``summary.txt``.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace

import numpy as np
from chaplygin_nd.simulate.analysis.fma import MapSpec, run_map

__all__ = ["FrequencyMapScene", "load_map", "run", "REGULAR_D", "CHAOTIC_D"]

_KEYS = {"energy", "grid", "samples", "dt", "seed", "x_range", "control_J", "tol", "chunk"}
#: Classes of the summary: regular D < -6, chaotic D > -4 (fixed after a trial of 16 orbits per
#: sphere at T = 1024 — axisymmetric D from -10 to -3.5, control from -5.5 to -2.6 — before any map).
REGULAR_D, CHAOTIC_D = -6.0, -4.0


@dataclass
class FrequencyMapScene:
    """A validated frequency-map scene: the axisymmetric map ``spec`` and the ``control``."""

    title: str
    n: int
    a: float
    b: float
    spec: MapSpec
    control: MapSpec
    source: str = "<scene>"
    name: str = "scene"
    raw: dict = field(default_factory=dict, repr=False)
    #: the map figures are drawn unless ``--no-plots`` is given (no [outputs] table to turn them off)
    figures: bool = True

    @property
    def orbits(self) -> int:
        """Orbits of both maps together."""
        return 2 * self.spec.size ** 2


def _num(table, key, fail, integer=False, default=None, low=None, high=None):
    where = f"fma.{key}" if key in _KEYS else key
    if key not in table:
        if default is None:
            fail(where, "missing", f"add {key} = <{'integer' if integer else 'number'}>")
        return default
    v = table[key]
    ok = isinstance(v, int) if integer else isinstance(v, (int, float))
    if isinstance(v, bool) or not ok or not math.isfinite(v):
        fail(where, f"{v!r} is not a finite {'integer' if integer else 'number'}",
             f"write {key} = <{'integer' if integer else 'number'}>")
    if (low is not None and not v >= low) or (high is not None and not v <= high):
        fail(where, f"{v!r} is outside [{low}, {high}]", f"choose {low} <= {key} <= {high}")
    return int(v) if integer else float(v)


def load_map(raw: dict, source: str, fail) -> FrequencyMapScene:
    """Validate a scene with an ``[fma]`` table (see the module docstring); ``fail(where, problem,
    fix)`` raises the scene's one-line error."""
    for key in raw:
        if key not in ("title", "n", "a", "b", "fma"):
            fail(key, "not a key of a frequency-map scene", "use only title, n, a, b and [fma]")
    table = raw["fma"]
    if not isinstance(table, dict):
        fail("fma", "must be a table", "write it as [fma]")
    for key in table:
        if key not in _KEYS:
            fail(f"fma.{key}", "unknown key", f"use only {', '.join(sorted(_KEYS))}")
    n = _num(raw, "n", fail, integer=True)
    if n != 4:
        fail("n", f"n = {n}: frequency maps are implemented for n = 4", "set n = 4")
    a = _num(raw, "a", fail)
    if not a > -1:
        fail("a", f"a = {a:g}: the map needs J_4 = 1 + a > 0", "choose a > -1")
    b = _num(raw, "b", fail)
    if not b > 0:
        fail("b", f"b = {b:g} is not positive (b = m r^2, eq:M-O)", "choose b > 0")
    h = _num(table, "energy", fail)
    if not h > 0:
        fail("fma.energy", f"energy = {h:g} is not positive (H is positive definite in M)",
             "choose energy > 0")
    size = _num(table, "grid", fail, integer=True, low=2, high=2000)
    samples = _num(table, "samples", fail, integer=True, low=64, high=1 << 16)
    dt = _num(table, "dt", fail)
    if not dt > 0:
        fail("fma.dt", f"dt = {dt:g} is not positive", "choose e.g. dt = 0.5")
    seed = _num(table, "seed", fail, integer=True, default=1, low=0)
    tol = _num(table, "tol", fail, default=1e-12, low=1e-16, high=1e-6)
    chunk = _num(table, "chunk", fail, integer=True, default=64, low=1, high=4096)
    x_range = table.get("x_range", [-0.9, 0.9])
    if not (isinstance(x_range, list) and len(x_range) == 2
            and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in x_range)
            and -1 < x_range[0] < x_range[1] < 1):
        fail("fma.x_range", f"{x_range!r}", "two increasing numbers inside (-1, 1), e.g. [-0.9, 0.9]")
    J = table.get("control_J")
    if not (isinstance(J, list) and len(J) == n and all(
            isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and v > 0
            for v in J)):
        fail("fma.control_J", f"{J!r}", f"{n} positive numbers, the control's diagonal mass tensor")
    spec = MapSpec(a=a, b=b, h=h, size=size, samples=samples, dt=dt, seed=seed,
                   x_range=(float(x_range[0]), float(x_range[1])), tol=tol, chunk=chunk)
    return FrequencyMapScene(title=str(raw.get("title", source)), n=n, a=a, b=b, spec=spec,
                             control=replace(spec, J=tuple(float(v) for v in J)), source=source,
                             raw=raw)


def _classes(D: np.ndarray) -> str:
    finite = D[np.isfinite(D)]
    total = D.size
    return (f"D < {REGULAR_D:g}: {np.sum(finite < REGULAR_D) / total:.1%}, "
            f"{REGULAR_D:g} <= D <= {CHAOTIC_D:g}: "
            f"{np.sum((finite >= REGULAR_D) & (finite <= CHAOTIC_D)) / total:.1%}, "
            f"D > {CHAOTIC_D:g}: {np.sum(finite > CHAOTIC_D) / total:.1%}, "
            f"median {np.median(finite):.2f}" + (f", {total - finite.size} not finite"
                                                   if finite.size < total else ""))


def _figure(path, D, x0, phi, title):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 5.2), dpi=100)
    step_x, step_p = (x0[1] - x0[0]) / 2, (phi[1] - phi[0]) / 2
    im = ax.imshow(np.where(np.isfinite(D), D, 0.0), origin="lower", aspect="auto",
                   cmap="viridis", vmin=-12, vmax=-1,
                   extent=(x0[0] - step_x, x0[-1] + step_x, phi[0] - step_p, phi[-1] + step_p))
    fig.colorbar(im, ax=ax, label=r"$D = \log_{10}|\omega^{(1)} - \omega^{(2)}|$")
    ax.set_xlabel(r"$x_0 = \gamma_4(0)$")
    ax.set_ylabel(r"$\varphi$: $M_0 \propto \cos\varphi\,P + \sin\varphi\,Q$")
    ax.set_title(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(path, format="png")
    plt.close(fig)


def run(scene: FrequencyMapScene, workers: int | None = None,
        scheduler: str | None = None) -> tuple[dict, str]:
    """Compute both maps; ``({file name: writer(path)}, summary text)``."""
    from chaplygin_nd.simulate.analysis.fma import initial_conditions
    from chaplygin_nd.simulate.analysis.fma import where as fma_where
    from chaplygin_nd.simulate.scene.progress import Tally

    s = scene.spec
    _, x0, phi = initial_conditions(s)
    tally = Tally(2 * s.size ** 2, "frequency map: orbits")  # both maps: orbits done / total
    start = time.perf_counter()
    try:
        D_sym = run_map(s, workers=workers, scheduler=scheduler, on_orbits=tally.add)
        mid = time.perf_counter()
        D_ctl = run_map(scene.control, workers=workers, scheduler=scheduler, on_orbits=tally.add)
    finally:
        tally.done()
    end = time.perf_counter()
    where = fma_where(workers, scheduler)
    text = "\n".join([
        f"scene   {scene.title}  (n = 4, a = {s.a:g}, b = {s.b:g}, H = {s.h:g}, "
        f"{s.size} x {s.size} orbits per map, T = {2 * s.samples * s.dt:g}, dt = {s.dt:g})",
        f"model   full field eq:motion-general, heyoka Taylor batch mode, tol {s.tol:g}; "
        f"NAFF fundamental of x + iG/(a+b+2) and E + i delta on each half; {where}",
        f"axisymmetric J = diag{s.mass_tensor}: {_classes(D_sym)}; {mid - start:.1f} s",
        f"control      J = diag{scene.control.mass_tensor}: {_classes(D_ctl)}; {end - mid:.1f} s"])
    sub = f"H = {s.h:g}, T = {2 * s.samples * s.dt:g}, {s.size}×{s.size}"
    files = {
        "fma.npz": lambda p: np.savez(p, D_axisymmetric=D_sym, D_control=D_ctl, x0=x0, phi=phi),
        "fma_axisymmetric.png": lambda p: _figure(
            p, D_sym, x0, phi, f"axisymmetric sphere J = diag{s.mass_tensor}, a = {s.a:g}, "
            f"b = {s.b:g}\n{sub}"),
        "fma_control.png": lambda p: _figure(
            p, D_ctl, x0, phi, f"control J = diag{scene.control.mass_tensor}, b = {s.b:g}\n{sub}"),
        "summary.txt": lambda p: p.write_text(text + "\n", encoding="utf-8")}
    return files, text
