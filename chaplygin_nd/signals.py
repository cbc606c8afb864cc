"""How the ``chaplygin`` program takes Ctrl-C and SIGTERM. Imported first, before
anything heavy, so it imports nothing but built-in modules: an interrupt is one line from the
moment :func:`take_signals` has run (the ``chaplygin`` program's first statement).

* The handler raises :class:`Interrupted` (a :class:`KeyboardInterrupt`) for both signals, so the
  ``finally`` clauses that keep an output folder whole run on both.
* A signal that lands while a module is being imported waits until the import is done: an
  import cut half-way leaves a half-made module (NumPy then says its C extensions are broken,
  SymPy has no ``core``). The handler looks again every :data:`RETRY_SECONDS` and raises at the
  first moment outside every import.
* A signal whose exception cannot propagate (it landed in a weakref callback or a ``__del__``, where
  Python prints "Exception ignored in ..." with a traceback) is not printed: :func:`take_signals`
  installs an unraisable hook that raises it again in the main thread a moment later.
* Once a signal was received, nothing the interrupt leaves behind is printed: an object it cut
  half-way through its constructor can fail in its ``__del__`` (matplotlib's first figure builds
  its mathtext grammar with pyparsing, outside any import: a ``Forward`` cut there says "no
  attribute 'expr'"), and a library may turn the interrupt into another exception on its way out.
  The unraisable hook drops the first; :func:`chaplygin_nd.cli.main` says ``interrupted`` for any
  exception once a signal was received.
* :func:`received` remembers the first signal, so none is lost even if something on the way
  swallows the exception; the program exits 128 + its number (130 Ctrl-C, 143 SIGTERM).
"""

from __future__ import annotations

import _thread
import signal
import sys
import time

__all__ = ["Interrupted", "take_signals", "handler", "received", "forget_received"]

#: How often a signal that landed in an import looks again whether the import is done (s).
RETRY_SECONDS = 0.02

_received: list[int] = []
_waiting: list[int] = []  # a deferred signal whose retry is scheduled


class Interrupted(KeyboardInterrupt):
    """Ctrl-C or SIGTERM."""


def received() -> int | None:
    """The first SIGINT or SIGTERM this process received through :func:`handler`, or ``None``."""
    return _received[0] if _received else None


def forget_received() -> None:
    """Start a new command: no signal received yet (see :func:`received`)."""
    _received.clear()


def _importing(frame) -> bool:
    while frame is not None:
        if frame.f_code.co_filename.startswith("<frozen importlib"):
            return True
        frame = frame.f_back
    return False


def _again(signum: int) -> None:
    time.sleep(RETRY_SECONDS)
    _waiting.clear()
    _thread.interrupt_main(signal.Signals(signum))  # the handler runs again, in the main thread


def handler(signum, frame):
    """The handler of SIGINT and SIGTERM (module docstring)."""
    if not _received:
        _received.append(signum)
    if _importing(frame):  # let the import finish; look again shortly
        if not _waiting:
            _waiting.append(signum)
            _thread.start_new_thread(_again, (signum,))
        return
    raise Interrupted(signal.Signals(signum).name)


_previous_hook = sys.unraisablehook


def _unraisable(unraisable) -> None:
    """``sys.unraisablehook``: an :class:`Interrupted` raised where it cannot propagate (a weakref
    callback during garbage collection, seen in CI: a traceback before ``interrupted``) is raised
    again in the main thread instead of printed; anything else goes to the previous hook."""
    if isinstance(unraisable.exc_value, Interrupted) and _received:
        if not _waiting:
            _waiting.append(_received[0])
            _thread.start_new_thread(_again, (_received[0],))
        return
    if _received:  # the debris of an interrupt: an object half-built when it landed
        return  # (pyparsing's Forward.__del__: "no attribute 'expr'"); the run says `interrupted`
    _previous_hook(unraisable)


def take_signals() -> None:
    """From now on Ctrl-C and SIGTERM go to :func:`handler` (main thread only)."""
    sys.unraisablehook = _unraisable
    try:
        for s in (signal.SIGINT, signal.SIGTERM):  # SIGTERM last: caught => both are ours
            signal.signal(s, handler)
    except ValueError:  # not the main thread
        pass
