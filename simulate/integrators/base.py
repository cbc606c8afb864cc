r"""The narrow interface shared by every integrator.

``integrate(field, y0, t, **options) -> Solution``: ``field(t, y)`` maps a state array of shape
``(count, dim)`` to its derivative; ``y0`` has shape ``(count, dim)``; ``t`` is the increasing array
of output times with ``t[0]`` the initial time. The solution holds ``y`` of shape
``(len(t), count, dim)`` and the cost: steps, right-hand-side calls (one call evaluates the
whole ensemble), seconds of wall time of the run, and, for compiled integrators, the seconds of
the compilation (cold) or of loading it from the cache (warm) in ``compile_seconds`` (not part of
``seconds``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Solution"]


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
