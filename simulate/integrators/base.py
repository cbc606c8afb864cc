r"""The narrow interface shared by every integrator.

``integrate(field, y0, t, **options) -> Solution``: ``field(t, y)`` maps a state array of shape
``(count, dim)`` to its derivative; ``y0`` has shape ``(count, dim)``; ``t`` is the increasing array
of output times with ``t[0]`` the initial time. The solution holds ``y`` of shape
``(len(t), count, dim)`` and the cost: steps, right-hand-side calls (one call evaluates the
whole ensemble), seconds of wall time of the run, and, for compiled integrators, the seconds of
the compilation (cold) or of loading it from the cache (warm) in ``compile_seconds`` (not part of
``seconds``).

What a run would cost is predicted before it (:mod:`simulate.scene.cost`): a DOP853
:class:`Pilot` on the scene's own field measures the steps per unit time, and each integrator
registered ``costed`` turns it into its :class:`Candidate` runs (its registry entry's ``cost``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Solution", "Candidate", "Pilot"]


@dataclass
class Solution:
    """Samples of a trajectory (or an ensemble) at the requested times, and what they cost."""

    t: np.ndarray
    y: np.ndarray
    method: str
    steps: int
    calls: int
    seconds: float
    note: str = ""
    y_high: np.ndarray | None = None  # mpmath values (object array) from a reference method
    compile_seconds: float = 0.0  # JIT compile (cold) or cache load (warm); not in ``seconds``


@dataclass(frozen=True)
class Pilot:
    """What a short DOP853 run on the scene's own field and states measured: ``rate`` steps per
    unit time and ``per_step`` seconds per step at relative tolerance ``rtol``; with the run's
    ``span``, ``samples``, the states ``y0`` ``(count, dim)``, the heyoka ``system`` of the field
    and the dimension ``n``."""

    rate: float
    per_step: float
    rtol: float
    span: float
    samples: int
    y0: np.ndarray
    system: object
    n: int


@dataclass
class Candidate:
    """One way to run the scene, and its predicted cost in seconds; ``compact`` is heyoka's mode
    (``None``: a method that compiles nothing)."""

    method: str
    compact: bool | None
    startup: float
    run: float
    state: str = ""  # compile-cache state: "in memory", "on disk", "cold" ("" without compiling)

    @property
    def total(self) -> float:
        """Start-up plus run."""
        return self.startup + self.run

    @property
    def label(self) -> str:
        """``heyoka compact`` / ``heyoka unrolled`` / ``DOP853``."""
        if self.compact is None:
            return self.method.upper()
        return f"{self.method} {'compact' if self.compact else 'unrolled'}"

    def describe(self) -> str:
        """``heyoka compact ~1.2 s (cold compile 0.9 s + run 0.3 s)``."""
        if self.compact is None:
            return f"{self.label} ~{_s(self.run)}"
        start = {"in memory": "in memory", "on disk": "load", "cold": "compile"}[self.state]
        return f"{self.label} ~{_s(self.total)} ({start} {_s(self.startup)} + run {_s(self.run)})"


def _s(x: float) -> str:
    return f"{x:.2g} s" if x >= 0.01 else f"{x * 1e3:.2g} ms"
