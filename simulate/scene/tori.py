r"""The scene outputs ``frequencies`` and ``poincare`` ($n = 4$), registered here
(:mod:`simulate.scene.output_registry`) and written by :func:`files`, not collected as arrays.

``frequencies`` writes ``frequencies.json`` with three entries, each with ``"frequencies"`` (the
independent frequencies of the first orbit, rad per unit time), ``"diffusion"`` (its frequency
diffusion), ``"max_diffusion"`` and ``"orbits"`` (the analysis of every orbit):

* ``"reduced"`` — eq:red-system from the reduced point of every initial condition, plus two
  orbits moved along the first one's level set (:func:`simulate.analysis.evidence.level_set_points`);
* ``"full"``    — the trajectory of the scene itself on $P$ (the planner runs the full system
  when ``frequencies`` is asked: frequencies on $P$ need it);
* ``"control"`` — the same initial conditions for the generic-$\mathbb{J}$ sphere
  (:mod:`simulate.analysis.control`, $\mathbb{J}$ = ``simulate.analysis.frequencies.CONTROL_J``).

``poincare`` (needs only the reduced model) writes ``poincare.png``: the section
$\{G = 0, \dot G < 0\}$ in $(E, \delta)$ of the reduced orbits, with the level set
$(F_1, F_2, F_3, H)$ of the first one in the title, and beside it the control's section.
The times of the scene must be uniform (NAFF needs equal spacing).
"""

from __future__ import annotations

import json
from typing import Any

import numpy as np
from chaplygin_nd.simulate.analysis import frequencies as fq
from chaplygin_nd.simulate.analysis import naff
from chaplygin_nd.simulate.analysis.control import general_inertia_kernels
from chaplygin_nd.simulate.analysis.evidence import Experiment, Orbits, level_set_points, signals
from chaplygin_nd.simulate.analysis.poincare import figure, section
from chaplygin_nd.simulate.dynamics import so
from chaplygin_nd.simulate.dynamics.field import FullField, ReducedField
from chaplygin_nd.simulate.dynamics.so import reduced_invariants
from chaplygin_nd.simulate.integrators import dop853
from chaplygin_nd.simulate.kernels import active
from chaplygin_nd.simulate.scene.output_registry import Output, register
from chaplygin_nd.simulate.scene.spec import SceneError

#: Both use the reduced invariants of $n = 4$ and NAFF's uniformly spaced samples; frequencies on
#: $P$ need the full system, the Poincaré section only the reduced one.
FREQUENCIES_OUTPUT = register(Output(
    "frequencies", None, only_n=4, spectral=True,
    full_reason="frequencies on P (the reconstruction) need the full system eq:motion-general; "
                "the 'reduced' frequencies come from eq:red-system and the 'control' from the "
                "generic-J sphere (simulate/scene/tori.py)"))
POINCARE_OUTPUT = register(Output("poincare", None, reduced=True, only_n=4, spectral=True))

__all__ = ["wants", "files"]

SHIFTS = (0.05, 0.1)


def wants(scene) -> bool:
    """True when the scene asks for ``frequencies`` or ``poincare``."""
    return bool({"frequencies", "poincare"} & set(scene.outputs))


def _rtol(scene) -> float:
    return max(scene.target / 100, 2.3e-14)


def _experiment(scene, model: str) -> Experiment:
    dt = float(scene.t[1] - scene.t[0])
    return Experiment(f"scene-{model}", model, 4, scene.a, scene.b, "generic", scene.seed or 0,
                      tuple(range(scene.count)), dt, len(scene.t) - 1, _rtol(scene),
                      J=fq.CONTROL_J if model == "control" else ())


def _reduced(scene, traj) -> Orbits:
    r0 = reduced_invariants(scene.M0, scene.gamma0)
    r0 = np.concatenate([r0[:1], level_set_points(r0[0], SHIFTS, scene.a, scene.b), r0[1:]])
    sol = dop853.integrate(ReducedField(scene.a, scene.b), r0, scene.t, rtol=_rtol(scene),
                           atol=_rtol(scene))
    return Orbits(_experiment(scene, "reduced"), scene.t, sol.y, sol.seconds, sol.steps)


def _reduced_origin(m: int) -> str:
    """Where reduced orbit ``m`` of :func:`_reduced` starts: the first initial condition (level set
    L), a point of L near it (one per shift), or a later initial condition (on its own level set)."""
    if m == 0:
        return "initial condition 1, on L"
    if m <= len(SHIFTS):
        return f"on L (shift {SHIFTS[m - 1]:g} from 1)"
    return f"initial condition {m - len(SHIFTS) + 1}, own level set"


def _control(scene) -> Orbits:
    f = FullField(4, scene.a, scene.b, kernels=general_inertia_kernels(fq.CONTROL_J, scene.b))
    sol = dop853.integrate(f, f.pack(scene.M0, scene.gamma0), scene.t, rtol=_rtol(scene),
                           atol=_rtol(scene))
    return Orbits(_experiment(scene, "control"), scene.t, sol.y, sol.seconds, sol.steps)


def _entry(orb: Orbits, note: str) -> dict:
    """The analysis of every orbit; the entry's ``frequencies`` and ``diffusion`` are those of the
    first orbit. An irregular orbit (D >= REGULAR) has no meaningful frequency count: its
    ``frequencies`` are then its three strongest lines and ``regular`` is false."""
    specs = [naff.analyse(signals(orb, m), orb.experiment.dt) for m in range(orb.y.shape[1])]
    first = specs[0]
    regular = first.diffusion < fq.REGULAR
    strongest = sorted({round(abs(w), 12) for w, _ in first.lines[:6]})[:3]
    return {"frequencies": first.frequencies if regular else strongest,
            "diffusion": first.diffusion, "regular": bool(regular),
            "max_diffusion": max(s.diffusion for s in specs),
            "model": note, "integration_seconds": round(orb.seconds, 3),
            "orbits": [s.to_dict() for s in specs]}


def files(scene, traj, plots: bool = True) -> tuple[dict, list[str]]:
    """The requested files as ``{name: writer(path)}`` for :meth:`simulate.scene.outdir.OutputFolder.write`
    (computed here, written atomically there) and one summary line per file; ``plots`` false
    (``--no-plots``) only rewords the Poincaré line (the figure is left out by
    :func:`simulate.scene.outputs.without_figures`, with every other)."""
    dt = np.diff(scene.t)
    if not np.allclose(dt, dt[0], rtol=1e-12, atol=0):
        raise SceneError(scene.source, "times.t", "frequencies/poincare need uniformly spaced times",
                         "give times.t_end and times.samples")
    lines: list[str] = []
    out: dict = {}
    reduced = _reduced(scene, traj)
    control = _control(scene)
    if "frequencies" in scene.outputs:
        y = np.concatenate([so.vec(traj.data["M"]), traj.data["gamma"]], axis=-1)
        full = Orbits(_experiment(scene, "full"), scene.t, y, traj.seconds, traj.steps)
        data: dict[str, Any] = {"reduced": _entry(reduced, "eq:red-system (generated kernel), DOP853; orbits "
                                           "1-3 share the first level set"),
                "full": _entry(full, "eq:motion-general on P (the scene's own trajectory)"),
                "control": _entry(control, f"generic J = diag{fq.CONTROL_J} (simulate/analysis/control.py)"),
                "regular_threshold": fq.REGULAR, "separation_factor": fq.SEPARATION}
        text = json.dumps(data, indent=1) + "\n"
        out["frequencies.json"] = lambda path: path.write_text(text, encoding="utf-8")
        lines.append("frequencies " + ", ".join(
            f"{k}: " + (f"{len(data[k]['frequencies'])} independent" if data[k]["regular"] else
                        "irregular, strongest lines") +
            f" {np.round(data[k]['frequencies'], 6)} (diffusion {data[k]['diffusion']:.1e})"
            for k in ("reduced", "full", "control")))
    if "poincare" in scene.outputs:
        F = active().require("reduced_integrals")(reduced.y[0, 0], scene.a, scene.b)
        level = ", ".join(f"{v:.4f}" for v in F)
        red = [(f"orbit {m + 1}: " + _reduced_origin(m), section(reduced.y[:, m]))
               for m in range(reduced.y.shape[1])]
        ctl = [(f"control orbit {m + 1}", section(reduced_invariants(
            so.unvec(control.y[:, m, :6], 4), control.y[:, m, 6:]))) for m in range(scene.count)]
        panels = [(f"axisymmetric sphere, a = {scene.a:g}, b = {scene.b:g}: reduced flow "
                   "eq:red-system", red),
                  (f"control: generic J = diag{fq.CONTROL_J}, same initial conditions", ctl)]
        title = (f"Poincaré section G = 0, dG/dt < 0 (maxima of x = γ₄), t ≤ {scene.t[-1]:g}; "
                 f"level set L: (F₁, F₂, F₃, H) = ({level})")
        out["poincare.png"] = lambda path: figure(path, panels, title)
        lines.append(f"poincare    {'poincare.png' if plots else 'not drawn (no figures)'}: "
                     f"section of {reduced.y.shape[1]} reduced and {scene.count} control orbits")
    return out, lines
