"""Progress lines of long runs, with an ETA (every run expected to last more than
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
    """One progress line on stderr, shown once a run has lasted ``after`` seconds:
    ``<text> (<percent>, <seconds>, <ETA>)``. On a terminal the line is rewritten in place (``\\r``)
    at most once a second; on anything else (a log file, CI) each report is a whole line, at most
    one every ``every`` seconds (30 s), and :meth:`done` writes the last report if it was held
    back, so a log ends on the final state. Writes when ``final`` whatever the time."""

    every = 30.0  # seconds between whole lines on a stream that is not a terminal

    def __init__(self, label: str, after: float = 2.0, stream=sys.stderr):
        self.label, self.after, self.stream = label, after, stream
        self.start = self.last = time.perf_counter()
        self.shown = False
        self.tty = _is_terminal(stream)
        self.held: tuple[str, float, float] | None = None  # held back (not a terminal): done() writes it

    def show(self, text: str, fraction: float, final: bool = False) -> None:
        """Write ``text`` with ``fraction`` of the work done, if it is time to."""
        now = time.perf_counter()
        if now - self.start < self.after:
            return
        if self.shown and now - self.last < (1.0 if self.tty else self.every) and not final:
            self.held = (text, fraction, now)
            return
        self._write(text, fraction, now)

    def _write(self, text: str, fraction: float, now: float) -> None:
        line = (f"{text} ({100 * fraction:5.1f}%, {now - self.start:.0f} s, "
                f"{eta(fraction, now - self.start)})")
        self.stream.write(f"\r{line}" if self.tty else f"{line}\n")
        self.stream.flush()
        self.last, self.shown, self.held = now, True, None

    def done(self) -> None:
        """End the progress line (on a terminal), or write the report held back (elsewhere)."""
        if self.shown:
            if not self.tty and self.held is not None:
                self._write(*self.held)
            elif self.tty:
                self.stream.write("\n")
                self.stream.flush()
            self.shown, self.held = False, None


def _is_terminal(stream) -> bool:
    """Whether ``stream`` is a terminal (a closed or odd stream counts as not one)."""
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError, OSError):
        return False


class Tally(Line):
    """Progress of a run counted in pieces (``orbits 1280 / 80000 (1.6 %, 35 s, ETA 30 min)``) on
    stderr, for runs longer than ``after`` seconds, as :class:`Line` writes it; monotone (the
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
