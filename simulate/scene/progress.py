"""Progress lines of long runs, with an ETA (issue 25: every run expected to last more than
about 10 s shows one): :func:`eta`, and :class:`Tally` for runs counted in pieces (the orbits of a
frequency map). :class:`Line` is what both share; the time-based line of an integration is
:class:`simulate.scene.run.Progress`."""

from __future__ import annotations

import sys
import time

__all__ = ["eta", "Line", "Tally"]


def eta(fraction: float, elapsed: float) -> str:
    """``ETA 3 min`` (or ``ETA 40 s``, ``ETA 1.2 h``) for ``fraction`` of the work done in
    ``elapsed`` seconds at the same rate; ``ETA ?`` before any work is done."""
    if not fraction > 0:
        return "ETA ?"
    left = elapsed * (1 - min(fraction, 1.0)) / fraction
    if left < 90:
        return f"ETA {left:.0f} s"
    return f"ETA {left / 60:.0f} min" if left < 5400 else f"ETA {left / 3600:.1f} h"


class Line:
    """One progress line on stderr: shown once a run has lasted ``after`` seconds, rewritten at
    most once a second (or when ``final``), ``<text> (<percent>, <seconds>, <ETA>)``."""

    def __init__(self, label: str, after: float = 2.0, stream=sys.stderr):
        self.label, self.after, self.stream = label, after, stream
        self.start = self.last = time.perf_counter()
        self.shown = False

    def show(self, text: str, fraction: float, final: bool = False) -> None:
        """Write ``text`` with ``fraction`` of the work done, if it is time to."""
        now = time.perf_counter()
        if now - self.start >= self.after and (now - self.last >= 1.0 or final):
            self.stream.write(f"\r{text} ({100 * fraction:5.1f}%, {now - self.start:.0f} s, "
                              f"{eta(fraction, now - self.start)})")
            self.stream.flush()
            self.last, self.shown = now, True

    def done(self) -> None:
        """End the progress line."""
        if self.shown:
            self.stream.write("\n")
            self.stream.flush()
            self.shown = False


class Tally(Line):
    """Progress of a run counted in pieces (``orbits 1280 / 80000 (1.6 %, 35 s, ETA 30 min)``) on
    stderr, for runs longer than ``after`` seconds, at most one line a second; monotone (the
    count only grows)."""

    def __init__(self, total: int, label: str, after: float = 2.0, stream=sys.stderr):
        super().__init__(label, after, stream)
        self.total = total
        self.done_count = 0

    def add(self, count: int) -> None:
        """``count`` more pieces are done."""
        self.done_count = min(self.total, self.done_count + max(0, int(count)))
        self.show(f"{self.label} {self.done_count} / {self.total}",
                  self.done_count / self.total if self.total else 1.0,
                  final=self.done_count == self.total)
