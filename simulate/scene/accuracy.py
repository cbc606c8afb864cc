r"""From ``accuracy.target`` to an integrator's settings: calibrated, with a safety factor, or refused.

What a target means: every output of the run is within ``target x max|output|`` of the exact
solution (max over samples, initial conditions and components) — the measure the cross-check
(:mod:`simulate.scene.crosscheck`) judges. For each method the worst ratio

.. math:: K = \frac{\max|y - y_\text{ref}| / \max|y_\text{ref}|}{\text{setting}}

(over the settings above the method's floor) and the worst error $E$ at the floor (rounding:
the error no setting removes) were measured by ``chaplygin bench calibration`` (:mod:`bench.bench_calibration`, written to
``bench/out/calibration.json``/``.md``) on every built-in scene that integrates and on a seeded
set of generic initial conditions (n = 3, 4, 5; prolate, oblate and flat bodies; scales 1 and 5),
against heyoka in ``real128`` at tolerance $10^{-28}$. A run uses

* DOP853 and RK45 (SciPy), heyoka: the error model is $K\,\text{setting} + E$, so
  ``rtol = atol`` (SciPy) or ``tol`` (heyoka) $= (\text{target}/\text{SAFETY} - E)/K$, at least
  the floor: $100\varepsilon$ (SciPy), $2^{-52}$ (heyoka double), $2^{-112}$ (``real128``, with
  heyoka's $K$ and $E$ scaled by $2^{-60}$); when that is below the floor the method *cannot*
  honour the target. Past the calibrated horizon (:data:`CALIBRATED_SPAN`) $K$ is scaled by
  span/128: the global error grows about linearly in time on the tori;
* RKMK4 (``lie``): a fixed step whose error is modelled as $C h^4 (t_\text{end} - t_0)$ (order 4,
  error growing linearly in time on the tori); the step is ``min(accuracy.step, (target /
  (C SAFETY span))^{1/4})``, so a target is always honoured (the cost may then be refused);
* the mpmath Taylor method (``reference``): ``dps = max(accuracy.dps, digits(target) + 6)`` when
  the scene names it, ``digits(target) + 6`` when ``auto`` chose it.

:func:`choose` returns the settings of a method for a scene (typed by what the number means:
:class:`Tolerance`, :class:`Step`, :class:`Digits`; each integrator's calibration is registered in
:mod:`simulate.integrators.registry`, its constants are :mod:`simulate.integrators.settings`); for ``method = "auto"``
the planner tries heyoka, then DOP853, then the mpmath Taylor method, and takes the first that
honours the target. No method promises less than :data:`FLOAT64_REACH` (4 ulps, 8.9e-16): the
outputs are float64 arrays whatever the arithmetic of the run (heyoka's ``real128``, the mpmath
Taylor method), and a target below it is refused when the scene is read. A method the scene *names* runs even when it cannot honour the target (the
plan line says what it promises instead); a method chosen automatically never does — when none
honours the target the run is refused (:class:`Unattainable`, exit 2).
"""

from __future__ import annotations

import dataclasses

from chaplygin_nd.simulate.integrators import registry
from chaplygin_nd.simulate.integrators.heyoka_taylor import WITHOUT_HEYOKA
from chaplygin_nd.simulate.integrators.settings import (
    CALIBRATED_SPAN,
    FLOAT64_REACH,
    FLOORS,
    MEASURED,
    ROUNDING,
    SAFETY,
    Digits,
    Settings,
    Step,
    Tolerance,
)
from chaplygin_nd.simulate.integrators.stops import RunStopped

__all__ = ["SAFETY", "MEASURED", "ROUNDING", "FLOORS", "CALIBRATED_SPAN", "WITHOUT_HEYOKA",
           "Settings", "Tolerance", "Step", "Digits", "Unattainable", "choose", "automatic",
           "heyoka_usable", "estimated_error"]


class Unattainable(RunStopped):
    """No method the planner may choose honours ``accuracy.target``."""


def heyoka_usable() -> bool:
    """heyoka is importable and not hidden by ``CHAPLYGIN_ND_WITHOUT_HEYOKA=1``."""
    return registry.get("heyoka").available()


def estimated_error(s: Settings, span: float = 1.0) -> float:
    """The calibrated (measured worst, no safety) relative error of the run ``s`` describes."""
    return registry.get(s.method).error(s, span)


def choose(method: str, target: float, span: float, step: float = 0.01, dps: int = 30,
           precision: str = "double") -> Settings:
    r"""The settings of the integrator ``method`` (its registered calibration,
    :mod:`simulate.integrators.registry`) for relative error ``target`` over a time span ``span``
    (rules in the module docstring). Domain: the integrators of eq:motion-general and
    eq:red-system; ``0 < target < 1``."""
    s = registry.get(method).calibrate(target, span, step=step, dps=dps, precision=precision)
    if s.promised < FLOAT64_REACH:  # the outputs are float64 arrays, whatever the arithmetic
        s = dataclasses.replace(s, promised=FLOAT64_REACH,
                                honoured=s.honoured and target >= FLOAT64_REACH)
    return s


def automatic(target: float, span: float, dps: int, reduced: bool) -> Settings:
    """``accuracy.method = "auto"``: the registered integrators in their ``auto`` order (heyoka
    when usable, DOP853, the mpmath Taylor method — the last for the full system only), the first
    that honours ``target``; raises :class:`Unattainable` naming what each reaches when none does."""
    tried = []
    for method in registry.names("auto"):
        entry = registry.get(method)
        if not entry.available() or (reduced and not entry.reduced):
            continue
        s = choose(method, target, span, dps=15)  # auto: the digits the target needs, no more
        if s.honoured:
            return s
        tried.append(f"{s.method} reaches about {s.promised:.2g}")
    raise Unattainable(f"accuracy.target = {target:g} cannot be honoured by any method available "
                       f"here ({'; '.join(tried)}); loosen accuracy.target, install heyoka "
                       "(pip install 'chaplygin-nd[fast]'), or name a method in accuracy.method")
