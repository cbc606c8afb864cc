"""``--cross-check``: run the full system (DOP853, tight tolerance) and compare every output.

The difference reported per output is $\\max|a - b|$ over all samples, initial conditions and
components (outputs a full run does not produce, such as ``zeta``, are not compared).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from simulate.outputs import collect
from simulate.planner import plan
from simulate.run import execute

__all__ = ["cross_check", "CROSS_CHECK_RTOL"]

#: Tolerance of the full DOP853 run used as the comparison.
CROSS_CHECK_RTOL = 1e-13


def cross_check(scene, arrays: dict[str, np.ndarray], progress: bool = True
                ) -> dict[str, float]:
    """Largest absolute difference per output between ``arrays`` and a full-system run."""
    full_scene = dataclasses.replace(scene, method="dop853", target=10 * CROSS_CHECK_RTOL)
    p = plan(full_scene, force_full=True)
    traj = execute(full_scene, p, progress=progress)
    other = collect(full_scene, traj)
    diffs = {}
    for key, v in arrays.items():
        if key == "t" or key not in other or key.startswith("drift."):
            continue
        diffs[key] = float(np.max(np.abs(np.asarray(v) - other[key])))
    return diffs
