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

:func:`choose` returns the :class:`Settings` of a method for a scene; for ``method = "auto"``
the planner tries heyoka, then DOP853, then the mpmath Taylor method, and takes the first that
honours the target. A method the scene *names* runs even when it cannot honour the target (the
plan line says what it promises instead); a method chosen automatically never does — when none
honours the target the run is refused (:class:`Unattainable`, exit 2).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass

import numpy as np
from chaplygin_nd.simulate.integrators.stops import RunStopped

__all__ = ["SAFETY", "MEASURED", "ROUNDING", "FLOORS", "Settings", "Unattainable", "choose", "heyoka_usable",
           "estimated_error"]

#: Factor between the measured worst ratio and the ratio a run assumes.
SAFETY = 4.0
#: Worst measured error/setting ratio K per method above its floor (bench/out/calibration.json;
#: for ``lie`` the constant C of C h^4 span), rounded up.
MEASURED = {"dop853": 650.0, "rk45": 650.0, "heyoka": 12.0, "real128": 12.0, "lie": 0.02}
#: Worst measured error E at the floor setting (rounding), rounded up; real128: heyoka's x 2^-60.
ROUNDING = {"dop853": 3.5e-12, "rk45": 3.5e-12, "heyoka": 1.4e-13, "real128": 1.4e-13 * 2.0 ** -60,
            "lie": 0.0}
#: Smallest setting each method accepts.
FLOORS = {"dop853": 100 * float(np.finfo(float).eps), "rk45": 100 * float(np.finfo(float).eps),
          "heyoka": 2.0 ** -52, "real128": 2.0 ** -112}
#: Environment variable that hides heyoka from the planner (the base install, for tests).
WITHOUT_HEYOKA = "CHAPLYGIN_ND_WITHOUT_HEYOKA"


class Unattainable(RunStopped):
    """No method the planner may choose honours ``accuracy.target``."""


def heyoka_usable() -> bool:
    """heyoka is importable and not hidden by ``CHAPLYGIN_ND_WITHOUT_HEYOKA=1``."""
    from chaplygin_nd.simulate.integrators import heyoka_taylor

    return heyoka_taylor.available() and os.environ.get(WITHOUT_HEYOKA, "") in ("", "0")


@dataclass(frozen=True)
class Settings:
    """What an integrator runs with: ``value`` is rtol (dop853, rk45), tol (heyoka), the step
    h (lie) or the digits (reference); ``promised`` the relative error the run stands for."""

    method: str
    value: float
    promised: float
    honoured: bool
    precision: str = "double"

    @property
    def estimate(self) -> float:
        """The measured (not safety-padded) error the run is expected to have: promised/SAFETY."""
        return self.promised / SAFETY

    def describe(self) -> str:
        """The plan line's part about the integrator and what it promises."""
        what = {"dop853": f"DOP853, rtol = atol = {self.value:.3g}",
                "rk45": f"RK45, rtol = atol = {self.value:.3g}",
                "heyoka": f"heyoka Taylor, tol {self.value:.3g}"
                          + ("" if self.precision == "double" else f", {self.precision}"),
                "lie": f"RKMK4, step h = {self.value:.3g}",
                "reference": f"mpmath Taylor, {int(self.value)} digits"}[self.method]
        if self.honoured:
            return f"{what}; calibrated for relative error <= {self.promised:.2g}"
        return (f"{what}; CANNOT honour the target: it reaches about {self.promised:.2g} "
                "(run because the scene names the method)")


def _ratio(method: str, precision: str = "double") -> float:
    return MEASURED["real128" if precision == "real128" else method] * SAFETY


#: Longest horizon of the calibration (tori4d cut to T = 128); beyond it K grows linearly with the
#: span (measured: tori4d, DOP853 at the T = 128 calibration missed by 1.9x at T = 2048).
CALIBRATED_SPAN = 128.0


def _tolerance_method(method: str, target: float, precision: str = "double",
                      span: float = 1.0) -> Settings:
    key = "real128" if precision == "real128" else method
    floor, e = FLOORS[key], ROUNDING[key]
    k = MEASURED[key] * max(1.0, span / CALIBRATED_SPAN)
    value = max((target / SAFETY - e) / k, floor)
    promise = SAFETY * (k * value + e)
    return Settings(method, value, max(target, promise), promise <= target * (1 + 1e-9),
                    precision)


def estimated_error(method: str, value: float, span: float = 1.0,
                    precision: str = "double") -> float:
    """The calibrated (measured worst, no safety) relative error of ``method`` at ``value``."""
    if method == "lie":
        return MEASURED["lie"] * value ** 4 * span
    if method == "reference":
        return 10.0 ** (-int(value) + 2)
    key = "real128" if precision == "real128" else method
    return MEASURED[key] * value + ROUNDING[key]


def choose(method: str, target: float, span: float, step: float = 0.01, dps: int = 30,
           precision: str = "double") -> Settings:
    r"""The :class:`Settings` of ``method`` (dop853, rk45, heyoka, lie, reference) for relative
    error ``target`` over a time span ``span`` (rules in the module docstring). Domain: the
    integrators of eq:motion-general and eq:red-system; ``0 < target < 1``."""
    if method in ("dop853", "rk45", "heyoka"):
        return _tolerance_method(method, target, precision, span)
    if method == "lie":
        span = max(span, 1e-300)
        h = min(step, (target / (_ratio("lie") * span)) ** 0.25)
        return Settings("lie", h, max(target, _ratio("lie") * h ** 4 * span), True)
    if method == "reference":
        digits = max(dps, math.ceil(-math.log10(target)) + 6)
        return Settings("reference", digits, target, True)
    raise ValueError(f"no calibration for method {method!r}")


def automatic(target: float, span: float, dps: int, reduced: bool) -> Settings:
    """``accuracy.method = "auto"``: heyoka (when usable), else DOP853, else the mpmath Taylor
    method (the full system only), the first that honours ``target``; raises
    :class:`Unattainable` naming what each reaches when none does."""
    tried = []
    for method in (["heyoka"] if heyoka_usable() else []) + ["dop853"] + \
            ([] if reduced else ["reference"]):
        s = choose(method, target, span, dps=15)  # auto: the digits the target needs, no more
        if s.honoured:
            return s
        tried.append(f"{s.method} reaches about {s.promised:.2g}")
    raise Unattainable(f"accuracy.target = {target:g} cannot be honoured by any method available "
                       f"here ({'; '.join(tried)}); loosen accuracy.target, install heyoka "
                       "(pip install 'chaplygin-nd[fast]'), or name a method in accuracy.method")
