"""The ``[times]`` table of a scene: ``t_end`` and ``samples`` (uniform), or an explicit increasing
list ``t``; the sample times must be distinct in float64."""

from __future__ import annotations

import numpy as np
from chaplygin_nd.simulate.scene.fields import array, number

__all__ = ["samples", "times", "KEYS"]

#: The keys of ``[times]``.
KEYS = {"t_end", "samples", "t"}


def samples(times, fail):
    """The number of samples the times table asks for, checked before any array is made."""
    if "t" in times:
        return len(times["t"]) if isinstance(times["t"], list) else 2
    samples = number(times, "samples", fail, integer=True, default=201, where="times.samples")
    if samples < 2:
        fail("times.samples", f"samples = {samples}", "use samples >= 2")
    return samples


def times(times, fail):
    """The sample times ``[times]`` asks for."""
    if "t" in times:
        if "t_end" in times or "samples" in times:
            fail("times", "both t and t_end/samples are given", "give one of them")
        if not isinstance(times["t"], list):
            fail("times.t", "not a list", "e.g. t = [0.0, 1.0, 2.0]")
        t = array(times["t"], (len(times["t"]),), "times.t", fail)
        if t.size < 2 or t[0] < 0 or np.any(np.diff(t) <= 0):
            fail("times.t", "not an increasing list of >= 2 times starting at t >= 0",
                 "e.g. t = [0.0, 1.0, 2.0]")
        _resolvable(t, "times.t", fail)
        return t
    t_end = number(times, "t_end", fail, required=True, where="times.t_end")
    if not t_end > 0:
        fail("times.t_end", f"t_end = {t_end} is not positive", "choose t_end > 0")
    samples = number(times, "samples", fail, integer=True, default=201, where="times.samples")
    if samples < 2:
        fail("times.samples", f"samples = {samples}", "use samples >= 2")
    t = np.linspace(0.0, t_end, samples)
    _resolvable(t, "times.t_end", fail)
    return t


def _resolvable(t, where, fail):
    """Consecutive times at least 16 ulp apart (``t_end = 5e-324`` gives equal float64 samples)."""
    if np.any(np.diff(t) <= 16 * np.spacing(np.abs(t[1:]))) or not np.isfinite(t).all():
        fail(where, f"the sample times are not distinct in float64 (t_end = {t[-1]:g} with "
             f"{len(t)} samples)", "choose a larger t_end or fewer samples")
