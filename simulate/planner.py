r"""The planner: the cheapest model that is exact for a scene, and why.

Models, cheapest first (each applies to every initial condition of the scene):

1. ``constant-Omega`` — $a = 0$ (spherical inertia: $\dot\Omega = 0$, stated after
   eq:M-O-axi-symm and proved in that ledger row), or $n = 4$ and $\eta_0\times\xi_0 = 0$ (P:steady-rot):
   $M(t) = e^{-\Omega_0t}M_0e^{\Omega_0t}$, $\gamma(t) = e^{-\Omega_0t}\gamma_0$;
2. ``vertical`` — $M_0\gamma_0 = 0$ (eq:def-H-V), Th:Re with $\zeta$ from :mod:`generated`;
3. ``horizontal-4D`` — $n = 4$, $M_0 = (M_0\gamma_0)\wedge\gamma_0$ and only reduced outputs
   (S5:H-linear, from :mod:`generated`);
4. ``reduced-7D`` — $n = 4$ and only reduced invariants / $x$ / integrals asked (eq:red-system);
5. ``full`` — eq:motion-general with $L_\gamma^{-1}$ from :mod:`generated`.

Integrator of the reduced and full models (``accuracy.method = "auto"``): heyoka's Taylor method
(:mod:`simulate.integrators.heyoka_taylor`) when heyoka is importable, else DOP853; the plan line
says which ("heyoka Taylor, order p, tol ..."). A scene may ask for ``heyoka``, ``dop853``, ``lie``
or ``reference`` explicitly.

The reconstruction ($g$, contact path) is added only when ``orientation`` or ``contact_path`` is
asked for; the closed forms 1–2 reconstruct in closed form (:mod:`simulate.closed_forms`), the
reduced models cannot (they forget the $SO(3)$ orbit), so those outputs force ``full``. A model
whose kernel :mod:`generated` lacks is skipped, and the reason says so.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from simulate import families
from simulate.dispatch import Kernels, active
from simulate.integrators import heyoka_taylor
from simulate.scene import Scene

__all__ = ["Plan", "plan", "REDUCED_OUTPUTS", "MODELS"]

MODELS = ("constant-Omega", "vertical", "horizontal-4D", "reduced-7D", "full")
#: Outputs a reduced (SO(3)-invariant) model can produce.
REDUCED_OUTPUTS = frozenset({"reduced", "x", "integrals"})
RECONSTRUCTION = frozenset({"orientation", "contact_path"})


@dataclass
class Plan:
    """The chosen model, the reason in words, whether to reconstruct, and the skipped models."""

    model: str
    reason: str
    reconstruct: bool
    method: str
    Omega0: np.ndarray
    skipped: list[str] = field(default_factory=list)
    detail: str = ""  # what the integrator runs with (plan line)

    def describe(self) -> str:
        """One paragraph: model, why, and what was ruled out."""
        how = self.detail if self.detail and self.detail != self.method else self.method
        text = f"model: {self.model} ({how}) — {self.reason}"
        if self.reconstruct:
            text += "; with reconstruction (orientation g, contact path)"
        if self.skipped:
            text += "\n  not used: " + "; ".join(self.skipped)
        return text


def _method(scene: Scene, model: str) -> str:
    if model in ("constant-Omega", "vertical", "horizontal-4D"):
        return "closed form"
    if scene.method == "auto":
        return "heyoka" if heyoka_taylor.available() else "dop853"
    if model == "reduced-7D" and scene.method not in ("dop853", "heyoka"):
        return "dop853"  # the Lie-group and Taylor methods act on (M, gamma) only
    return scene.method


def heyoka_tolerance(target: float) -> float:
    """heyoka's tolerance for an accuracy target: target/100, at least 2^-52 (the bench measures
    global errors up to ~50 tol on generic n = 4 to T = 100)."""
    return max(target / 100, 2.0 ** -52)


def method_detail(scene: Scene, method: str) -> str:
    """What the integrator ``method`` runs with for this scene (for the plan line)."""
    if method == "heyoka":
        tol = heyoka_tolerance(scene.target)
        return f"heyoka Taylor, order {heyoka_taylor.order_for(tol)}, tol {tol:g}"
    if method == "reference":
        return f"{scene.dps} digits"
    if method == "lie":
        return f"step h <= {scene.step:g}; accuracy.target is not used"
    if method == "dop853":
        return f"DOP853, rtol = target/100 = {max(scene.target / 100, 2.3e-14):g}"
    return method


def plan(scene: Scene, kernels: Kernels | None = None, force_full: bool = False) -> Plan:
    r"""Choose the model for ``scene`` (rules in the module docstring). ``force_full`` skips the
    cheaper models (used by ``--cross-check``)."""
    k = kernels or active()
    omega = k.require("angular_velocity")
    Omega0 = scene.Omega0 if scene.Omega0 is not None else omega(scene.M0, scene.gamma0,
                                                                  scene.a, scene.b)
    wants = set(scene.outputs)
    reconstruct = bool(wants & RECONSTRUCTION)
    tol = scene.tolerance
    skipped: list[str] = []

    def make(model, reason):
        method = _method(scene, model)
        return Plan(model, reason, reconstruct, method, Omega0, skipped,
                    detail=method_detail(scene, method))

    if force_full:
        return make("full", "forced (cross-check)")
    if scene.method != "auto":
        skipped.append(f"closed forms and reduced models: accuracy.method = {scene.method!r} "
                       "asks for an integrator of the full system")
        return make("full", f"integrator {scene.method} requested "
                    f"({method_detail(scene, scene.method)})")
    vertical = all(families.claim_residual("vertical", M, g) <= tol
                   for M, g in zip(scene.M0, scene.gamma0, strict=True))
    if scene.a == 0.0:
        return make("constant-Omega", "a = 0: spherical inertia, Omega is constant "
                    "(eq:M-O-axi-symm: a = 0 implies dOmega/dt = 0); M(t) = exp(-Omega0 t) M0 exp(Omega0 t)")
    if scene.n == 4 and all(families.steady_residual(O) <= tol for O in Omega0):
        return make("constant-Omega", "n = 4 and eta0 x xi0 = 0: steady rotation (P:steady-rot), "
                    "M(t) = exp(-Omega0 t) M0 exp(Omega0 t), gamma(t) = exp(-Omega0 t) gamma0")
    if vertical:
        if k.has("zeta"):
            return make("vertical", "M0 gamma0 = 0: vertical momentum, relative equilibrium "
                        "M(t) = exp(zeta t) M0 exp(-zeta t), gamma(t) = exp(zeta t) gamma0 (Th:Re)")
        skipped.append("vertical closed form (Th:Re): the zeta kernel is not in generated/")
    reduced_only = wants <= REDUCED_OUTPUTS and scene.n == 4
    needs = ["reduced_integrals"] if "integrals" in wants else []
    if reduced_only and all(families.claim_residual("horizontal", M, g) <= tol
                            for M, g in zip(scene.M0, scene.gamma0, strict=True)):
        if all(k.has(x) for x in ("horizontal", "horizontal_A", "reduced_integrals")):
            return make("horizontal-4D", "n = 4, horizontal momentum and only reduced outputs: "
                        "the linear system for (x, G) (S5:H-linear)")
        skipped.append("horizontal closed form (S5:H-linear): its kernels are not in generated/")
    if reduced_only:
        missing = [x for x in ["reduced_field"] + needs if not k.has(x)]
        if not missing:
            return make("reduced-7D", "n = 4 and only SO(3)-invariant outputs: the reduced "
                        "7-dimensional field eq:red-system")
        skipped.append(f"reduced 7D system (eq:red-system): kernel(s) {', '.join(missing)} "
                       "not in generated/")
    elif scene.n == 4:
        other = sorted(wants - REDUCED_OUTPUTS)
        skipped.append(f"reduced 7D system: outputs {', '.join(other)} are not SO(3)-invariant")
    return make("full", "no closed form or reduction applies to these initial conditions "
                "and outputs: the full system eq:motion-general")
