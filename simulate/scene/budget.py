"""What a run will cost, said before it starts, and refused past a limit unless ``--force``.

* memory — counted from the scene before any array is made: ``samples x count`` times the
  floats per sample of the state and of every output, times 3 (the integrator's samples, the
  collected outputs and their CSV rows live at the same time);
* time to draw an ensemble — ``count x`` :data:`DRAW_SECONDS`, before drawing;
* time — projected from a pilot: after :data:`PILOT_SECONDS` of integration the elapsed time
  is scaled by the share of ``[t[0], t[-1]]`` covered (:class:`Projection`). The clock measures
  the integration only: an integrator that compiles or loads compiled code first calls
  :meth:`Projection.restart` when it is ready (the compile or load time is predicted by the
  planner, :mod:`simulate.scene.cost`, and reported apart). Closed forms cost one matrix exponential
  per sample and are covered by the memory count.

Limits: :data:`LIMIT_SECONDS` and :func:`memory_limit`; ``--force`` lifts both.
"""

from __future__ import annotations

import os
import sys
import time

from chaplygin_nd.simulate.integrators.stops import TooCostly

__all__ = ["LIMIT_SECONDS", "PILOT_SECONDS", "DRAW_SECONDS", "memory_limit", "memory_bytes",
           "Projection", "human_bytes", "announce", "refuse_before", "CLEARLY_PAST"]

LIMIT_SECONDS = 600.0
PILOT_SECONDS = 0.5
#: Runs projected to take longer than this say so before going on.
ANNOUNCE_SECONDS = 10.0


def memory_limit() -> int:
    """Half the physical memory, at most 4 GiB."""
    try:
        physical = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError, AttributeError):
        physical = 8 << 30
    return min(4 << 30, physical // 2)


def human_bytes(x: float) -> str:
    """``1.5 GB``-style size."""
    for unit in ("B", "kB", "MB", "GB", "TB", "PB"):
        if x < 1000 or unit == "PB":
            return f"{x:.3g} {unit}"
        x /= 1000
    return f"{x:.3g} PB"  # pragma: no cover


def memory_bytes(n: int, count: int, samples: int, outputs) -> int:
    """Estimated peak bytes of a run (see the module docstring)."""
    size = {"M": n * n, "Omega": n * n, "orientation": n * n, "gamma": n, "x": 1,
            "reduced": 7, "contact_path": n, "integrals": 2 * (2 * (n + 1) + 2), "zeta": 0}
    state = 2 * (n * n + n)  # M, gamma and (with reconstruction) g, c
    per_sample = state + sum(size.get(o, n * n) for o in outputs)
    return 3 * 8 * per_sample * samples * count + 8 * count * (n * n + n)


#: Seconds to draw one initial condition of a family (measured: 50-150 us per member).
DRAW_SECONDS = 1.5e-4


def announce(text: str, stream=None) -> None:
    """Say something about the cost on stderr (before the run starts)."""
    stream = stream or sys.stderr
    stream.write(f"cost: {text}\n")
    stream.flush()


#: A run whose predicted cost (the planner's cost model, :mod:`simulate.scene.cost`, within 3x of the
#: measured integration time) is past this many times the limit is refused before it starts.
CLEARLY_PAST = 3.0


def refuse_before(plan, label: str, t, force: bool = False) -> None:
    """Refuse (:class:`TooCostly`) a run predicted to cost more than :data:`CLEARLY_PAST` x
    :data:`LIMIT_SECONDS` before anything is compiled or integrated; nearer the limit the
    :class:`Projection` of the run itself decides."""
    predicted = getattr(plan, "predicted_seconds", None)
    if force or predicted is None or not predicted > CLEARLY_PAST * LIMIT_SECONDS:
        return
    raise TooCostly(f"{label}: estimated {predicted:.3g} s for t in [{t[0]:g}, {t[-1]:g}] (the "
                    f"planner's prediction), past the limit of {LIMIT_SECONDS:g} s; shorten times, "
                    "loosen accuracy.target, or pass --force")


class Projection:
    """Projects the run time after a pilot and refuses a run past :data:`LIMIT_SECONDS`."""

    def __init__(self, t0: float, t_end: float, label: str, force: bool = False,
                 stream=sys.stderr):
        self.t0, self.t_end, self.label, self.force, self.stream = t0, t_end, label, force, stream
        self.start = time.perf_counter()
        self.decided = False

    def restart(self) -> None:
        """Start the clock now (the integrator exists: compile or load time is not run time)."""
        self.start = time.perf_counter()

    def __call__(self, t: float) -> None:
        """Called with the time the integrator reached."""
        if self.decided:
            return
        elapsed = time.perf_counter() - self.start
        if elapsed < PILOT_SECONDS or not t > self.t0:
            return
        self.decided = True
        projected = elapsed * (self.t_end - self.t0) / (t - self.t0)
        text = (f"{self.label}: estimated {projected:.3g} s for t in [{self.t0:g}, {self.t_end:g}] "
                f"(projected from {elapsed:.2f} s to t = {t:.4g})")
        if projected > LIMIT_SECONDS and not self.force:
            raise TooCostly(f"{text}, past the limit of {LIMIT_SECONDS:g} s; shorten times, "
                            "loosen accuracy.target, or pass --force")
        if projected > ANNOUNCE_SECONDS:
            announce(text, self.stream)
