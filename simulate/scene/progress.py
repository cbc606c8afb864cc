"""Progress lines of long runs, with an ETA (issue 25: every run expected to last more than
about 10 s shows one): :func:`eta`, and :class:`Tally` for runs counted in pieces (the orbits of a
frequency map). The time-based line of an integration is :class:`simulate.scene.run.Progress`."""

from __future__ import annotations

import sys
import time

__all__ = ["eta", "Tally"]


def eta(fraction: float, elapsed: float) -> str:
    """``ETA 3 min`` (or ``ETA 40 s``, ``ETA 1.2 h``) for ``fraction`` of the work done in
    ``elapsed`` seconds at the same rate; ``ETA ?`` before any work is done."""
    if not fraction > 0:
        return "ETA ?"
    left = elapsed * (1 - min(fraction, 1.0)) / fraction
    if left < 90:
        return f"ETA {left:.0f} s"
    return f"ETA {left / 60:.0f} min" if left < 5400 else f"ETA {left / 3600:.1f} h"


class Tally:
    """Progress of a run counted in pieces (``orbits 1280 / 80000 (1.6 %, 35 s, ETA 30 min)``) on
    stderr, for runs longer than ``after`` seconds, at most one line a second; monotone (the
    count only grows)."""

    def __init__(self, total: int, label: str, after: float = 2.0, stream=sys.stderr):
        self.total, self.label, self.after, self.stream = total, label, after, stream
        self.done_count = 0
        self.start = self.last = time.perf_counter()
        self.shown = False

    def add(self, count: int) -> None:
        """``count`` more pieces are done."""
        self.done_count = min(self.total, self.done_count + max(0, int(count)))
        now = time.perf_counter()
        if now - self.start >= self.after and (now - self.last >= 1.0
                                               or self.done_count == self.total):
            frac = self.done_count / self.total if self.total else 1.0
            self.stream.write(f"\r{self.label} {self.done_count} / {self.total} "
                              f"({100 * frac:5.1f}%, {now - self.start:.0f} s, "
                              f"{eta(frac, now - self.start)})")
            self.stream.flush()
            self.last, self.shown = now, True

    def done(self) -> None:
        """End the progress line."""
        if self.shown:
            self.stream.write("\n")
            self.stream.flush()
            self.shown = False
