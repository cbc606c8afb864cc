"""Progress that can be trusted: the progress line of a long run is monotone (an
integrator's probe, a rejected step or the next pass of an ensemble never makes it go back),
shows an ETA, and a frequency map counts its orbits done out of the total. On a terminal it is
rewritten in place; in a log file or CI it is whole lines, at most one every 30 s."""

from __future__ import annotations

import io
import itertools
import re

import numpy as np
import pytest
from chaplygin_nd.simulate.scene import progress as progress_module
from chaplygin_nd.simulate.scene import run as run_module
from chaplygin_nd.simulate.scene.progress import Tally, eta


@pytest.fixture
def ticking(monkeypatch):
    """A clock that advances 1.5 s at every reading: every report is shown."""
    clock = itertools.count(0.0, 1.5)
    for module in (run_module, progress_module):
        monkeypatch.setattr(module.time, "perf_counter", lambda: next(clock))


class Terminal(io.StringIO):
    """A stream that says it is a terminal."""

    def isatty(self) -> bool:
        return True


def _shown(text: str) -> list[float]:
    return [float(x) for x in re.findall(r"\(\s*([0-9.]+)%", text)]


def test_the_progress_line_never_goes_back(ticking):
    stream = Terminal()
    bar = run_module.Progress(1.0, "full dop853", after=0.0, stream=stream)
    for t in (0.01, 0.081, 0.008, 0.02, 0.89, 0.243, 0.5, 0.95, 1.0):  # the jumps once seen
        bar(t)
    shown = _shown(stream.getvalue())
    assert shown == sorted(shown) and shown[-1] == 100.0, shown
    assert "ETA" in stream.getvalue()


@pytest.mark.parametrize("bar", ["time", "tally"])
def test_off_a_terminal_progress_is_whole_lines_at_most_every_30_s(ticking, bar):
    """A log file gets no carriage return: a whole line when the run has lasted ``after``, then
    at most one per 30 s of the (ticking, 1.5 s a reading) clock, and the last state at the end."""
    stream = io.StringIO()
    if bar == "time":
        line = run_module.Progress(100.0, "full dop853", after=0.0, stream=stream)
        report = line
    else:
        line = Tally(100, "frequency map: orbits", after=0.0, stream=stream)
        report = line.add
    for _ in range(100):
        report(1.0)
    line.done()
    text = stream.getvalue()
    assert "\r" not in text and text.endswith("\n")
    seconds = [int(x) for x in re.findall(r"%, (\d+) s, ETA", text)]
    assert len(seconds) == len(text.splitlines()) >= 3, text
    assert all(b - a >= 30 for a, b in zip(seconds, seconds[1:-1])), seconds
    assert _shown(text)[-1] == (1.0 if bar == "time" else 100.0), text


def test_eta_and_the_tally_of_pieces(ticking):
    assert eta(0.0, 10.0) == "ETA ?"
    assert eta(0.5, 10.0) == "ETA 10 s"
    assert eta(0.2, 600.0) == "ETA 40 min" and eta(0.1, 600.0) == "ETA 1.5 h"
    stream = io.StringIO()
    tally = Tally(100, "frequency map: orbits", after=0.0, stream=stream)
    for k in (8, 8, -3, 8, 76, 8):  # never more than the total, never fewer than before
        tally.add(k)
    tally.done()
    counts = [int(x) for x in re.findall(r"orbits (\d+) / 100", stream.getvalue())]
    assert counts == sorted(counts) and counts[-1] == 100, counts
    assert "ETA" in stream.getvalue() and stream.getvalue().endswith("\n")


def test_an_ensemble_in_several_passes_reports_the_whole_work():
    """heyoka runs an ensemble in passes of the SIMD width: the time reported covers every
    pass (it went from 100 % back to the next pass's fraction)."""
    pytest.importorskip("heyoka")
    from chaplygin_nd.simulate.dynamics import families
    from chaplygin_nd.simulate.dynamics.field import FullField
    from chaplygin_nd.simulate.dynamics.so import vec
    from chaplygin_nd.simulate.integrators import heyoka_taylor

    M0, gamma0 = families.draw("generic", 3, 0.5, 1.0, 1, 5, 1.0)
    field = FullField(3, 0.5, 1.0)
    y0 = np.concatenate([vec(M0), gamma0], axis=1)
    reported = []
    heyoka_taylor.integrate(field, y0, np.linspace(0.0, 2.0, 5), batch=2,
                            progress=reported.append)
    assert reported == sorted(reported) and reported[-1] == pytest.approx(2.0), reported


def test_a_frequency_map_counts_its_orbits():
    pytest.importorskip("heyoka")
    from chaplygin_nd.simulate.analysis import fma
    from test_fma import SMALL

    done = []
    fma.run_map(SMALL, workers=1, on_orbits=done.append)
    assert sum(done) == SMALL.size ** 2 and all(k > 0 for k in done)
