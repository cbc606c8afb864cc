"""What a mutation run is doing before (and while) it decides mutants: one line when a phase
starts (``planning: running the 42 unmutated rows that reach the mutants ...``) and, on a long
phase, a progress line at most every 30 s (``  ... 12 of 42 rows done in 31 s, about 1 min
left``), the same form as the run's own progress line (:func:`line`). Whole lines on stdout, so
a log file or CI reads them as a terminal does (``chaplygin mutate``, ``chaplygin
mutate-derivations``)."""

from __future__ import annotations

import sys
import time

__all__ = ["Phase", "line"]

#: Seconds between two progress lines of one phase.
EVERY = 30.0


def line(done: int, total: int, seconds: float, what: str) -> str:
    """``  ... N of M <what> in S s, about T min left`` (at the rate so far; ``no estimate yet``
    before the first piece is done)."""
    left = seconds / done * (total - done) if done else float("nan")
    eta = f"about {left / 60:.0f} min left" if done else "no estimate yet"
    return f"  ... {done} of {total} {what} in {seconds:.0f} s, {eta}"


class Phase:
    """A phase of ``total`` pieces (``what``: e.g. ``rows done``): :meth:`start` prints its line,
    :meth:`add` counts pieces and prints :func:`line` once ``every`` seconds have passed since the
    last line (:meth:`tick` also while no piece ends); ``total`` may be set later (e.g. once
    pytest has collected its tests). ``stream`` is the one at construction (a phase that runs
    pytest, which redirects ``sys.stdout``, still writes to the terminal or log)."""

    def __init__(self, text: str, total: int | None = None, what: str = "done",
                 every: float = EVERY, stream=None):
        self.text, self.total, self.what, self.every = text, total, what, every
        self.stream = stream or sys.stdout
        self.done = 0
        self.start_time = self.last = time.perf_counter()

    def start(self) -> Phase:
        """Print the phase's line; the phase's clock starts."""
        self.start_time = self.last = time.perf_counter()
        self._print(f"{self.text} ...")
        return self

    def add(self, count: int = 1) -> None:
        """``count`` more pieces are done; a progress line if ``every`` seconds have passed."""
        self.done += count
        self.tick()

    def tick(self) -> None:
        """A progress line if ``every`` seconds have passed since the last line (also while no
        piece ends: a caller waiting on workers calls this as it wakes)."""
        now = time.perf_counter()
        if now - self.last >= self.every and self.total:
            self.last = now
            self._print(line(min(self.done, self.total), self.total, now - self.start_time,
                             self.what))

    def _print(self, text: str) -> None:
        self.stream.write(text + "\n")
        self.stream.flush()
