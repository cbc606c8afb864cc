r"""The planner: the cheapest model that is exact for a scene, and why.

Models, cheapest first (each applies to every initial condition of the scene):

1. ``constant-Omega`` — $a = 0$ (spherical inertia: $\dot\Omega = 0$, stated after
   eq:M-O-axi-symm and proved in that ledger row), or $n = 4$ and $\eta_0\times\xi_0 = 0$ (P:steady-rot):
   $M(t) = e^{-\Omega_0t}M_0e^{\Omega_0t}$, $\gamma(t) = e^{-\Omega_0t}\gamma_0$;
2. ``vertical`` — $M_0\gamma_0 = 0$ (eq:def-H-V), Th:Re with $\zeta$ from :mod:`generated`;
3. ``horizontal-4D`` — $n = 4$, $M_0 = (M_0\gamma_0)\wedge\gamma_0$ and only reduced outputs
   (S5:H-linear, from :mod:`generated`);
4. ``horizontal`` — any $n \ge 3$, $M_0 = (M_0\gamma_0)\wedge\gamma_0$ and only $x$ and the
   horizontal invariants $(x, G, A, B)$ asked (S5:H-linear-nD, from :mod:`generated`);
5. ``reduced-7D`` — $n = 4$ and only reduced invariants / $x$ / integrals asked (eq:red-system);
6. ``full`` — eq:motion-general with $L_\gamma^{-1}$ from :mod:`generated`.

Membership tests (steady rotation, $\mathcal V$, $\mathcal H$) are relative residuals, so they do not
depend on the scale of $M_0$; a point passes when its residual is at most
``min(initial.tolerance, APPLIES)``: a scene may tighten the test but not loosen it past
:data:`APPLIES`, the rounding level at which the closed forms are exact (a point at relative
distance $r$ from the family leaves it at a rate $\sim r\|\Omega\|$, an error no closed form
accounts for). The plan line says which residual was tested against which bound.

Integrator of the reduced and full models (``accuracy.method = "auto"``): among heyoka's Taylor
method (:mod:`simulate.integrators.heyoka_taylor`, when heyoka is importable; compact or unrolled),
DOP853 and the mpmath Taylor method, those whose calibrated settings honour ``accuracy.target``
(:mod:`simulate.scene.accuracy`; none honours it: the run is refused), and among those the one of least
predicted cost — compile or cache load plus run (:mod:`simulate.scene.cost`); the plan line says which,
with what, and prints every prediction. A scene may ask for ``heyoka``, ``dop853``, ``lie`` or
``reference`` explicitly.

A closed form is taken only when its float64 error bound at the scene's horizon
(:mod:`simulate.scene.bounds`: the phase error grows like $|\lambda| T\varepsilon$, and the rotation
rate's own error is measured) is at most ``accuracy.target``; otherwise the next model is tried,
and when no model meets the target the run stops with one line naming the closed form's bound,
what the integrators reach and the target.

The reconstruction ($g$, contact path) is added only when ``orientation`` or ``contact_path`` is
asked for; the closed forms 1–2 reconstruct in closed form (:mod:`simulate.dynamics.closed_forms`), the
reduced models cannot (they forget the $SO(3)$ orbit), so those outputs force ``full``. A model
whose kernel :mod:`generated` lacks is skipped, and the reason says so.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from chaplygin_nd.simulate.dynamics import families
from chaplygin_nd.simulate.integrators import registry
from chaplygin_nd.simulate.integrators.stops import check_finite
from chaplygin_nd.simulate.kernels import Kernels, active
from chaplygin_nd.simulate.scene import accuracy, bounds, output_registry
from chaplygin_nd.simulate.scene.spec import Scene

__all__ = ["Plan", "plan", "MODELS"]

MODELS = ("constant-Omega", "vertical", "horizontal-4D", "horizontal", "reduced-7D", "full")
#: Largest relative residual at which a point counts as on a family with a closed form (about
#: 4500 ulp: the rounding of a point built in float64, e.g. M0 = P A P or L_gamma(Omega0)).
APPLIES = 1e-12


def _residual_test(formula: str, residuals, bound: float) -> tuple[bool, str]:
    """Whether every residual is <= ``bound``, and a line saying what was tested."""
    worst = max(residuals)
    ok = bool(worst <= bound)
    return ok, f"{formula} = {worst:.1e} {'<=' if ok else '>'} {bound:.0e}"


@dataclass
class Plan:
    """The chosen model, the reason in words, whether to reconstruct, and the skipped models."""

    model: str
    reason: str
    reconstruct: bool
    method: str
    Omega0: np.ndarray
    skipped: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)  # about the scene's parameters (simulate.dynamics.ball)
    detail: str = ""  # what the integrator runs with (plan line)
    compact: bool | None = None  # heyoka's mode, chosen by the cost model (simulate.scene.cost)
    costs: str = ""  # the cost model's predictions (plan line)
    accuracy: accuracy.Settings | None = None  # the calibrated settings (simulate.scene.accuracy)
    predicted_seconds: float | None = None  # the chosen candidate's predicted total (simulate.scene.cost)
    bound: bounds.Bound | None = None  # a closed form's error bound at the horizon (simulate.scene.bounds)
    missed: list[str] = field(default_factory=list)  # closed forms whose bound misses the target

    def describe(self) -> str:
        """One paragraph: model, why, and what was ruled out."""
        how = self.detail if self.detail and self.detail != self.method else self.method
        text = f"model: {self.model} ({how}) — {self.reason}"
        if self.reconstruct:
            text += "; with reconstruction (orientation g, contact path)"
        if self.skipped:
            text += "\n  not used: " + "; ".join(self.skipped)
        text += "".join(f"\n  note: {note}" for note in self.notes)
        if self.costs:
            text += f"\n  cost: {self.costs}"
        return text


def _method(scene: Scene, model: str) -> str:
    if model in ("constant-Omega", "vertical", "horizontal-4D", "horizontal"):
        return "closed form"
    if scene.method == "auto":
        return "auto"
    if model == "reduced-7D" and not registry.get(scene.method).reduced:
        return "dop853"  # e.g. the Lie-group and Taylor methods act on (M, gamma) only
    return scene.method


def settings(scene: Scene, method: str, model: str = "full") -> accuracy.Settings | None:
    """The calibrated settings of ``method`` for ``scene`` (:mod:`simulate.scene.accuracy`); ``auto``
    picks the first method that honours the target. ``None`` for a closed form."""
    span = float(scene.t[-1] - scene.t[0])
    if method == "closed form":
        return None
    if method == "auto":
        return accuracy.automatic(scene.target, span, scene.dps, reduced=model == "reduced-7D")
    return accuracy.choose(method, scene.target, span, step=scene.step, dps=scene.dps)


def heyoka_tolerance(target: float) -> float:
    """heyoka's tolerance for an accuracy target (calibrated, :mod:`simulate.scene.accuracy`)."""
    s = accuracy.choose("heyoka", target, 1.0)
    assert isinstance(s, accuracy.Tolerance)
    return s.tol


def method_detail(scene: Scene, method: str, model: str = "full") -> str:
    """What the integrator ``method`` runs with for this scene (for the plan line)."""
    s = settings(scene, method, model)
    return method if s is None else s.describe()


def _make(scene: Scene, model: str, reason: str, reconstruct: bool, Omega0: np.ndarray,
          skipped: list[str], missed: list[str]) -> Plan:
    """The :class:`Plan` of ``model``: its calibrated settings and, for an integrated model of a
    method the cost model knows, the method of least predicted cost (compile + run). ``missed``:
    the closed forms whose bound at the horizon missed the target (named if no method meets it)."""
    method = _method(scene, model)
    try:
        chosen = settings(scene, method, model)  # calibrated; "auto": the first that honours it
    except accuracy.Unattainable as exc:
        if not missed:
            raise
        raise accuracy.Unattainable(f"{exc}; and the {'; the '.join(missed)}") from None
    compact, costs, predicted = None, "", None
    if model in ("full", "reduced-7D") and chosen is not None \
            and registry.get(chosen.method).costed:
        from chaplygin_nd.simulate.scene import (
            cost,  # the method by predicted cost (compile + run)
        )

        picked = cost.for_scene(scene, model, reconstruct, _competitors(scene, model, chosen),
                                _tol(settings(scene, "dop853", model)))  # the DOP853 pilot's
        if picked is not None:
            (best, costs) = picked
            compact, predicted = best.compact, best.total
            if best.method != chosen.method:
                chosen = settings(scene, best.method, model)
    method = chosen.method if chosen else "closed form"
    return Plan(model, reason, reconstruct, method, Omega0, skipped, list(scene.notes),
                detail=chosen.describe() if chosen else method, accuracy=chosen,
                compact=compact, costs=costs, predicted_seconds=predicted, missed=missed)


def _tol(s: accuracy.Settings | None) -> float:
    assert isinstance(s, accuracy.Tolerance)
    return s.tol


def _competitors(scene: Scene, model: str, chosen: accuracy.Settings) -> dict[str, float]:
    """The methods whose predicted cost competes, with their tolerances: with ``auto``, every
    usable integrator registered ``costed`` whose calibrated settings honour the target, if the
    first choice is one of them (in the registry's order); otherwise the chosen method alone."""
    if scene.method != "auto":
        return {chosen.method: _tol(chosen)}
    honoured = {e.name: settings(scene, e.name, model) for e in registry.entries()
                if e.costed and e.available()}
    honoured = {m: s for m, s in honoured.items() if s is not None and s.honoured}
    if chosen.method not in honoured:
        return {chosen.method: _tol(chosen)}
    return {m: _tol(s) for m, s in honoured.items()}


def _omega0(scene: Scene, k: Kernels) -> np.ndarray:
    r"""$\Omega_0 = L_\gamma^{-1}(M_0)$ of every initial condition (the scene's own when it gave
    one), checked finite."""
    omega = k.require("angular_velocity")
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):  # checked below
        Omega0 = scene.Omega0 if scene.Omega0 is not None else omega(scene.M0, scene.gamma0,
                                                                      scene.a, scene.b)
    check_finite("Omega0 = L_gamma^-1 M0", Omega0, float(scene.t[0]),
                 "a, b or the scale of M0 too large for float64")
    return Omega0


def plan(scene: Scene, kernels: Kernels | None = None, force_full: bool = False) -> Plan:
    r"""Choose the model for ``scene`` (rules in the module docstring). ``force_full`` skips the
    cheaper models (used by ``--cross-check``)."""
    k = kernels or active()
    Omega0 = _omega0(scene, k)
    wants = set(scene.outputs)
    reconstruct = bool(wants & output_registry.where("reconstruct"))
    tol = min(scene.tolerance, APPLIES)
    skipped: list[str] = []

    missed: list[str] = []  # closed forms whose bound at the horizon misses the target

    def closed(model, reason) -> Plan | None:
        """The closed form ``model`` if its bound at the horizon meets the target, else None."""
        bound = bounds.closed_form(model, scene, Omega0, k)
        if not bound.value <= scene.target:
            text = (f"{model} closed form: float64 bound {bound.value:.2g} at T = "
                    f"{bound.span:.3g} (worst output {bound.worst}) > accuracy.target "
                    f"{scene.target:g}")
            skipped.append(text)
            missed.append(text)
            return None
        return Plan(model, reason, reconstruct, "closed form", Omega0, skipped,
                    list(scene.notes), detail=f"closed form; {bound.describe()}", bound=bound)

    def make(model, reason):
        return _make(scene, model, reason, reconstruct, Omega0, skipped, missed)

    if force_full:
        return make("full", "forced (cross-check)")
    if scene.method != "auto":
        skipped.append(f"closed forms and reduced models: accuracy.method = {scene.method!r} "
                       "asks for an integrator of the full system")
        return make("full", f"integrator {scene.method} requested")
    is_vertical, v_text = _residual_test(
        "max |M0 gamma0|/|M0|",
        [families.claim_residual("vertical", M, g) for M, g in zip(scene.M0, scene.gamma0)], tol)
    if scene.a == 0.0:
        p = closed("constant-Omega", "a = 0: spherical inertia, Omega is constant "
                    "(eq:M-O-axi-symm: a = 0 implies dOmega/dt = 0); M(t) = exp(-Omega0 (t - t0)) M0 exp(Omega0 (t - t0))")
        if p is not None:
            return p
    if scene.n == 4:
        steady, s_text = _residual_test("max |eta0 x xi0|/(|eta0||xi0|)",
                                        [families.steady_residual(O) for O in Omega0], tol)
        if steady:
            p = closed("constant-Omega", f"n = 4 and eta0 x xi0 = 0 ({s_text}): steady rotation "
                        "(P:steady-rot), M(t) = exp(-Omega0 (t - t0)) M0 exp(Omega0 (t - t0)), "
                        "gamma(t) = exp(-Omega0 (t - t0)) gamma0")
            if p is not None:
                return p
        else:
            skipped.append(f"steady rotation (P:steady-rot): {s_text}")
    if is_vertical:
        if k.has("zeta"):
            p = closed("vertical", f"M0 gamma0 = 0 ({v_text}): vertical momentum, relative "
                     "equilibrium M(t) = exp(zeta (t - t0)) M0 exp(-zeta (t - t0)), "
                     "gamma(t) = exp(zeta (t - t0)) gamma0 (Th:Re)")
            if p is not None:
                return p
        else:
            skipped.append("vertical closed form (Th:Re): the zeta kernel is not in generated/")
    else:
        skipped.append(f"vertical closed form (Th:Re): {v_text}")
    reduced_only = wants <= output_registry.where("reduced") and scene.n == 4
    needs = [x for name in sorted(wants) for x in output_registry.get(name).reduced_kernels]
    is_horizontal, h_text = _residual_test(
        "max |M0 - (M0 gamma0) ^ gamma0|/|M0|",
        [families.claim_residual("horizontal", M, g) for M, g in zip(scene.M0, scene.gamma0)],
        tol)
    if reduced_only:
        if not is_horizontal:
            skipped.append(f"horizontal closed form (S5:H-linear): {h_text}")
        elif all(k.has(x) for x in ("horizontal", "horizontal_A", "reduced_integrals")):
            p = closed("horizontal-4D", f"n = 4, horizontal momentum ({h_text}) and only "
                     "reduced outputs: the linear system for (x, G) (S5:H-linear)")
            if p is not None:
                return p
        else:
            skipped.append("horizontal closed form (S5:H-linear): its kernels are not in generated/")
    if wants <= output_registry.where("horizontal"):
        if not is_horizontal:
            skipped.append(f"horizontal closed form (S5:H-linear-nD): {h_text}")
        elif all(k.has(x) for x in ("horizontal", "horizontal_blocks")):
            p = closed("horizontal", f"n = {scene.n}, horizontal momentum ({h_text}) and only x, "
                     "(x, G, A, B) asked: the linear system for (x, G) holds for every n "
                     "(S5:H-linear-nD)")
            if p is not None:
                return p
        else:
            skipped.append("horizontal closed form (S5:H-linear-nD): its kernels are not in generated/")
    if reduced_only:
        missing = [x for x in ["reduced_field"] + needs if not k.has(x)]
        if not missing:
            return make("reduced-7D", "n = 4 and only SO(3)-invariant outputs: the reduced "
                        "7-dimensional field eq:red-system")
        skipped.append(f"reduced 7D system (eq:red-system): kernel(s) {', '.join(missing)} "
                       "not in generated/")
    elif scene.n == 4:
        other = sorted(wants - output_registry.where("reduced"))
        skipped.append(f"reduced 7D system: outputs {', '.join(other)} are not SO(3)-invariant")
        for name in sorted(wants):
            if output_registry.get(name).full_reason:
                return make("full", output_registry.get(name).full_reason)
    if missed:
        return make("full", "the closed form's float64 error bound at the horizon misses "
                    "accuracy.target (not used, below): the full system eq:motion-general")
    return make("full", "no closed form or reduction applies to these initial conditions "
                "and outputs: the full system eq:motion-general")
