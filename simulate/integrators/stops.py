"""Why a run stops before writing anything (exit status 2): a non-finite value or a cost past the limit.

Both are raised as soon as they are known: a non-finite value at the first right-hand-side
evaluation (or closed-form sample) that produces it, a cost at the scene check (memory) or after
a short pilot of the integrator (time), see :mod:`simulate.scene.budget`.
"""

from __future__ import annotations

import numpy as np

__all__ = ["RunStopped", "NonFinite", "TooCostly", "check_finite", "fmt"]


class RunStopped(Exception):
    """A run cannot give a right answer (or would cost too much); the message says why."""


class NonFinite(RunStopped):
    """A field of the solution became inf or nan."""


class TooCostly(RunStopped):
    """The predicted cost is past the limit and ``--force`` was not given."""


def fmt(x: float) -> str:
    """A number as a person writes it (``0.25``, ``1e+300``), never ``np.float64(...)``."""
    return f"{float(x):.6g}"


def check_finite(name: str, values: np.ndarray, t: np.ndarray | float, hint: str = "") -> None:
    """Raise :class:`NonFinite` naming ``name`` and the first time at which ``values`` (samples
    along the first axis when ``t`` is an array) is not finite."""
    values = np.asarray(values)
    if np.isfinite(values).all():
        return
    if np.ndim(t) == 0:
        when = fmt(float(np.asarray(t)))
    else:
        times = np.asarray(t)
        bad = ~np.isfinite(values.reshape(len(times), -1)).all(axis=1)
        when = fmt(times[int(np.argmax(bad))])
    raise NonFinite(f"{name} is not finite at t = {when}"
                    + (f" ({hint})" if hint else " (inf or nan in float64)"))
