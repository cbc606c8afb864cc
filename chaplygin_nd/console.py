"""What every command says on the console, and how it ends when interrupted.

* :func:`say` prints to stdout; a closed stdout (``| head -1``) is not an error — the rest of the
  output is dropped and the run goes on to write its files; a stdout that cannot encode a
  character (``PYTHONIOENCODING=ascii``) gets an ASCII spelling ("—" -> "-").
* :func:`fail` prints one line ``error: ...`` on stderr and returns the exit status.
* :func:`interruptible` turns SIGTERM into the same :class:`Interrupted` (a
  :class:`KeyboardInterrupt`) as Ctrl-C, so the ``finally`` clauses that keep an output folder whole
  run on both; the commands then print ``interrupted`` and exit 130 (the ``chaplygin`` program
  makes it 143 for SIGTERM). The handler is :func:`chaplygin_nd.signals.handler`: a signal that
  lands in an import waits for the import to end, and none is lost.
* :func:`usable_backend` replaces a bogus ``MPLBACKEND`` (which makes ``import matplotlib`` raise)
  by ``Agg``, with a one-line warning (the figures are drawn with Agg in any case).
* :class:`OneLineParser` is argparse with one-line usage errors (``error: PROG: --option: ...``,
  exit 2); :func:`path_argument` is the ``type`` of every path option (an empty path is an error,
  not the current folder or the default).
* :class:`OneLineWarning`, the base of the project's warnings (the caches'), is shown as one line
  ``warning: MESSAGE`` on stderr instead of Python's two-line ``file:line: Category: ...`` format.
  It stays a warning: filters, ``-W error`` and ``pytest.warns`` see it as before (only
  :func:`warnings.formatwarning` is wrapped, for this category alone, when this module is imported).
"""

from __future__ import annotations

import argparse
import contextlib
import os
import re
import signal
import sys
import threading
import warnings
from pathlib import Path

from chaplygin_nd.signals import Interrupted, forget_received, received, take_signals
from chaplygin_nd.signals import handler as _raise

__all__ = ["Interrupted", "say", "fail", "interruptible", "take_signals", "received",
           "forget_received", "usable_backend", "ascii_text", "shortlist",
           "OneLineParser", "path_argument", "OneLineWarning"]

_ASCII = str.maketrans({"—": "-", "–": "-", "−": "-", "×": "x", "≤": "<=", "≥": ">=",
                        "→": "->", "…": "...", "’": "'", "‘": "'", "“": '"', "”": '"',
                        "·": ".", "±": "+-", "²": "^2", "⁻": "^-", "¹": "1", "√": "sqrt"})

#: matplotlib's built-in backend names (``MPLBACKEND`` may also be ``module://...``).
BACKENDS = {"gtk3agg", "gtk3cairo", "gtk4agg", "gtk4cairo", "macosx", "nbagg", "notebook",
            "qtagg", "qtcairo", "qt5agg", "qt5cairo", "tkagg", "tkcairo", "webagg", "wx",
            "wxagg", "wxcairo", "agg", "cairo", "pdf", "pgf", "ps", "svg", "template", "inline"}


def shortlist(items: list[str], shown: int = 5, width: int = 60) -> str:
    """``items`` for a one-line message: the first ``shown`` (each cut at ``width`` characters)
    and how many more, so that an error naming 5 000 unknown names stays one short line."""
    cut = [i if len(i) <= width else i[:width - 3] + "..." for i in items[:shown]]
    rest = len(items) - len(cut)
    return "; ".join(cut) + (f" and {rest} more ({len(items)} in all)" if rest > 0 else "")


def ascii_text(text: str) -> str:
    """``text`` with the project's few non-ASCII symbols spelled in ASCII, the rest escaped."""
    return text.translate(_ASCII).encode("ascii", "backslashreplace").decode("ascii")


def _write(stream, text: str) -> None:
    try:
        stream.write(text + "\n")
    except UnicodeEncodeError:
        stream.write(ascii_text(text) + "\n")
    stream.flush()


def say(text: str) -> None:
    """Print ``text`` on stdout (see the module docstring); never raises for a closed pipe."""
    if sys.stdout is None:
        return
    try:
        _write(sys.stdout, text)
    except (BrokenPipeError, ValueError):  # closed pipe, or stdout already closed
        _silence_stdout()


def _silence_stdout() -> None:
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())  # the interpreter's final flush must not fail
        os.close(devnull)
    except (OSError, ValueError, AttributeError):
        pass


def fail(message: str, status: int = 2) -> int:
    """Print ``error: message`` (or ``interrupted``) as one line on stderr; return ``status``."""
    line = message if status == 130 else f"error: {message}"
    line = " ".join(line.split("\n"))
    try:
        _write(sys.stderr, line)
    except (BrokenPipeError, ValueError, OSError):
        pass
    return status


@contextlib.contextmanager
def interruptible():
    """Within the block SIGTERM raises :class:`Interrupted` as Ctrl-C does (main thread only)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    old = {s: signal.getsignal(s) for s in (signal.SIGTERM, signal.SIGINT)}
    signal.signal(signal.SIGTERM, _raise)
    signal.signal(signal.SIGINT, _raise)
    try:
        yield
    finally:
        for s, handler in old.items():
            signal.signal(s, handler if handler is not None else signal.SIG_DFL)


def usable_backend() -> None:
    """Replace an ``MPLBACKEND`` matplotlib would refuse by ``Agg`` (see the module docstring),
    and keep matplotlib's font cache in the project's cache folder
    (:func:`chaplygin_nd.cache.place_matplotlib_cache`)."""
    from chaplygin_nd.cache import place_matplotlib_cache

    place_matplotlib_cache()
    name = os.environ.get("MPLBACKEND")
    if name is None or name.lower() in BACKENDS or name.startswith("module://"):
        return
    os.environ["MPLBACKEND"] = "Agg"
    try:
        _write(sys.stderr, f"warning: MPLBACKEND={name!r} is not a matplotlib backend; "
                           "drawing with Agg")
    except (BrokenPipeError, ValueError, OSError):
        pass


class OneLineParser(argparse.ArgumentParser):
    """argparse whose usage errors are one line ``error: PROG: --option: ...`` on stderr (exit 2).

    A negative rational ``-1/3`` or ``-1e-3`` is a value, as ``-1`` and ``-0.5`` are in argparse
    (``--a -1/3`` was refused with "--a: expected one argument")."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = re.compile(
            r"^-(\d+|\d*\.\d+|\d+\.\d*)([eE][-+]?\d+)?(/\d+)?$")

    def error(self, message):
        fail(f"{self.prog}: {message.removeprefix('argument ')}")
        sys.exit(2)


def path_argument(text: str) -> Path:
    """The ``type`` of a path option: ``text`` as a :class:`~pathlib.Path`; an empty or blank
    ``text`` is refused (``Path("")`` would silently mean the current folder, and a test
    ``if args.out`` the default)."""
    if not text.strip():
        raise argparse.ArgumentTypeError(f"an empty path ({text!r}); give a file or folder name")
    return Path(text)


def positive_int(text: str) -> int:
    """The ``type`` of a count option (``--jobs``, ``--per-function``): an integer >= 1; 0 or a
    negative count is refused (``--jobs -3`` silently ran one worker, ``--jobs 0`` one per core)."""
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 1:
        raise argparse.ArgumentTypeError(f"not a positive integer: {text!r}")
    return value


class OneLineWarning(UserWarning):
    """A warning of this project, shown as one line ``warning: MESSAGE`` on stderr."""


def _one_line_format(previous):
    def formatwarning(message, category, filename, lineno, line=None):
        if isinstance(category, type) and issubclass(category, OneLineWarning):
            return "warning: " + " ".join(str(message).split("\n")) + "\n"
        return previous(message, category, filename, lineno, line)

    formatwarning.one_line_warnings = True
    return formatwarning


if not getattr(warnings.formatwarning, "one_line_warnings", False):
    warnings.formatwarning = _one_line_format(warnings.formatwarning)
