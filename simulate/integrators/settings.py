r"""What an integrator runs with, typed by what its number means, and the calibration of each
integrator: the measured error model that turns ``accuracy.target`` into a setting.

Each integrator states its own :class:`Calibration` on its registry entry
(:mod:`simulate.integrators.registry`); the tables :data:`MEASURED`, :data:`ROUNDING` and
:data:`FLOORS` are read from those entries. Three kinds of settings, one class each (a setting never means rtol, a step or digits by
convention): :class:`Tolerance` (``tol``: rtol = atol of SciPy, heyoka's tolerance),
:class:`Step` (``h``: a fixed step) and :class:`Digits` (``dps``: working decimal digits).
Every one carries the relative error the run ``promised`` and whether that ``honoured`` the
target. The calibration (measured by ``chaplygin bench calibration`` against heyoka in
``real128``; rules in :mod:`simulate.scene.accuracy`): error $\approx K\,\text{tol} + E$ above the
floor (tolerance methods), $C h^4\,\text{span}$ (RKMK4), $10^{2-\text{dps}}$ (Taylor).
"""

from __future__ import annotations

import math
from collections import UserDict
from dataclasses import dataclass

__all__ = ["Settings", "Tolerance", "Step", "Digits", "Calibration", "SAFETY", "MEASURED",
           "ROUNDING", "FLOORS", "CALIBRATED_SPAN", "FLOAT64_REACH", "tolerance", "step", "digits"]

#: Factor between the measured worst ratio and the ratio a run assumes.
SAFETY = 4.0
#: Smallest relative error float64 outputs can carry: the arrays are stored in float64 (half an
#: ulp) and the derived outputs (Omega, the integrals) are computed in it (a few ulps more). A
#: target below it is refused (simulate.scene.spec); no method promises less.
FLOAT64_REACH = 4 * 2.0 ** -52
#: Longest horizon of the calibration (tori4d cut to T = 128); beyond it K grows linearly with the
#: span (measured: tori4d, DOP853 at the T = 128 calibration missed by 1.9x at T = 2048).
CALIBRATED_SPAN = 128.0


@dataclass(frozen=True)
class Calibration:
    """What one integrator (at one precision) was measured to deliver (bench/out/calibration.json),
    rounded up: ``measured`` = the worst error/setting ratio K above the floor (for a fixed step
    the constant C of C h^4 span), ``rounding`` = the worst error E at the floor setting, ``floor``
    = the smallest setting it accepts (tolerance methods). Each integrator module states its own
    on its registry entry."""

    measured: float
    rounding: float = 0.0
    floor: float | None = None


class _ByMethod(UserDict):
    """One column of the calibrations (``measured``, ``rounding`` or ``floor``) keyed by method
    (or precision: ``real128``), read from the registered integrators on first use. A mapping a
    test may patch one entry of."""

    def __init__(self, column: str):  # no UserDict.__init__: ``data`` is filled on first use
        self._column = column
        self._data: dict | None = None

    @property
    def data(self) -> dict:  # type: ignore[override]
        if self._data is None:
            from chaplygin_nd.simulate.integrators import registry

            data: dict = {}
            for entry in registry.entries():
                for key, calibration in entry.calibration:
                    value = getattr(calibration, self._column)
                    if value is not None:
                        data.setdefault(key, value)
            self._data = data
        return self._data


#: Worst measured error/setting ratio K per method above its floor (for ``lie`` the constant C of
#: C h^4 span), from each integrator's :class:`Calibration`.
MEASURED = _ByMethod("measured")
#: Worst measured error E at the floor setting (rounding); real128: heyoka's x 2^-60.
ROUNDING = _ByMethod("rounding")
#: Smallest setting each tolerance method accepts.
FLOORS = _ByMethod("floor")


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
