r"""What an integrator runs with, typed by what its number means, and the calibration of each
integrator: the measured error model that turns ``accuracy.target`` into a setting.

Three kinds of settings, one class each (a setting never means rtol, a step or digits by
convention): :class:`Tolerance` (``tol``: rtol = atol of SciPy, heyoka's tolerance),
:class:`Step` (``h``: a fixed step) and :class:`Digits` (``dps``: working decimal digits).
Every one carries the relative error the run ``promised`` and whether that ``honoured`` the
target. The calibration (measured by ``chaplygin bench calibration`` against heyoka in
``real128``; rules in :mod:`simulate.scene.accuracy`): error $\approx K\,\text{tol} + E$ above the
floor (tolerance methods), $C h^4\,\text{span}$ (RKMK4), $10^{2-\text{dps}}$ (Taylor).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Settings", "Tolerance", "Step", "Digits", "SAFETY", "MEASURED", "ROUNDING", "FLOORS",
           "CALIBRATED_SPAN", "FLOAT64_REACH", "tolerance", "step", "digits"]

#: Factor between the measured worst ratio and the ratio a run assumes.
SAFETY = 4.0
#: Worst measured error/setting ratio K per method above its floor (bench/out/calibration.json;
#: for ``lie`` the constant C of C h^4 span), rounded up.
MEASURED = {"dop853": 650.0, "rk45": 650.0, "heyoka": 12.0, "real128": 12.0, "lie": 0.02}
#: Worst measured error E at the floor setting (rounding), rounded up; real128: heyoka's x 2^-60.
ROUNDING = {"dop853": 3.5e-12, "rk45": 3.5e-12, "heyoka": 1.4e-13, "real128": 1.4e-13 * 2.0 ** -60,
            "lie": 0.0}
#: Smallest setting each tolerance method accepts.
FLOORS = {"dop853": 100 * float(np.finfo(float).eps), "rk45": 100 * float(np.finfo(float).eps),
          "heyoka": 2.0 ** -52, "real128": 2.0 ** -112}
#: Smallest relative error float64 outputs can carry: the arrays are stored in float64 (half an
#: ulp) and the derived outputs (Omega, the integrals) are computed in it (a few ulps more). A
#: target below it is refused (simulate.scene.spec); no method promises less.
FLOAT64_REACH = 4 * float(np.finfo(float).eps)
#: Longest horizon of the calibration (tori4d cut to T = 128); beyond it K grows linearly with the
#: span (measured: tori4d, DOP853 at the T = 128 calibration missed by 1.9x at T = 2048).
CALIBRATED_SPAN = 128.0


@dataclass(frozen=True)
class Settings:
    """Common to every integrator: its name, the relative error the run stands for, whether that
    honours the target, and the precision (``double``, ``real128``, ``mp``)."""

    method: str
    promised: float
    honoured: bool
    precision: str = "double"

    @property
    def estimate(self) -> float:
        """The measured (not safety-padded) error the run is expected to have: promised/SAFETY."""
        return self.promised / SAFETY

    def describe(self) -> str:
        """The plan line's part about the integrator (its registered description) and what it
        promises."""
        from chaplygin_nd.simulate.integrators import registry

        what = registry.get(self.method).describe(self)
        if self.honoured:
            return f"{what}; calibrated for relative error <= {self.promised:.2g}"
        return (f"{what}; CANNOT honour the target: it reaches about {self.promised:.2g} "
                "(run because the scene names the method)")


@dataclass(frozen=True)
class Tolerance(Settings):
    """An adaptive method: ``tol`` is rtol = atol (SciPy) or heyoka's tolerance."""

    tol: float = 0.0


@dataclass(frozen=True)
class Step(Settings):
    """A fixed-step method: ``h`` is the largest step."""

    h: float = 0.0


@dataclass(frozen=True)
class Digits(Settings):
    """A multiprecision method: ``dps`` decimal digits."""

    dps: int = 0


def tolerance(method: str, target: float, precision: str = "double", span: float = 1.0
              ) -> Tolerance:
    """Calibrated :class:`Tolerance` of ``method`` for ``target``: (target/SAFETY - E)/K, at least
    the floor; K scaled by span/CALIBRATED_SPAN past the calibrated horizon."""
    key = "real128" if precision == "real128" else method
    floor, e = FLOORS[key], ROUNDING[key]
    k = MEASURED[key] * max(1.0, span / CALIBRATED_SPAN)
    value = max((target / SAFETY - e) / k, floor)
    promise = SAFETY * (k * value + e)
    return Tolerance(method, max(target, promise), promise <= target * (1 + 1e-9), precision,
                     tol=value)


def tolerance_error(s: Settings, span: float = 1.0) -> float:
    """The calibrated (measured worst, no safety) relative error of a :class:`Tolerance`."""
    assert isinstance(s, Tolerance)
    key = "real128" if s.precision == "real128" else s.method
    return MEASURED[key] * s.tol + ROUNDING[key]


def step(method: str, target: float, span: float, largest: float) -> Step:
    """RKMK4's step: min(largest, (target/(C SAFETY span))^(1/4)); always honours the target."""
    span = max(span, 1e-300)
    ratio = MEASURED[method] * SAFETY
    h = min(largest, (target / (ratio * span)) ** 0.25)
    return Step(method, max(target, ratio * h ** 4 * span), True, h=h)


def step_error(s: Settings, span: float = 1.0) -> float:
    """C h^4 span."""
    assert isinstance(s, Step)
    return MEASURED[s.method] * s.h ** 4 * span


def digits(method: str, target: float, least: int, span: float = 1.0) -> Digits:
    """max(least, digits of the target + 6, plus the digits the horizon costs: log10 of
    span/CALIBRATED_SPAN past the calibrated horizon) decimal digits."""
    longer = math.ceil(math.log10(span / CALIBRATED_SPAN)) if span > CALIBRATED_SPAN else 0
    return Digits(method, target, True,
                  dps=max(least, math.ceil(-math.log10(target)) + 6 + longer))


def digits_error(s: Settings, span: float = 1.0) -> float:
    """10^(2 - dps), times span/CALIBRATED_SPAN past the calibrated horizon (the error of a phase
    grows linearly in time, as for the other methods)."""
    assert isinstance(s, Digits)
    return 10.0 ** (-s.dps + 2) * max(1.0, span / CALIBRATED_SPAN)
