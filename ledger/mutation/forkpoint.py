r"""Run a ledger row with a mutant from a process parked at the mutated function's first call.

A row run with a mutant of ``f`` does, up to the first call of ``f``, exactly what the unmutated
row does: nothing before that call can see the mutant. :class:`Parked` runs the row once,
unmutated, in a forked process (the *parked* process) and stops it at that first call; for each
mutant the parked process forks again, the copy puts the mutant's code in ``f``, returns the
mutant's value from that first call and finishes the row, and sends back what the row gave. The
work before the first call (and every cache it filled) is done once per function and row rather
than once per mutant, and the worker's own caches are never touched by a mutant (the copy
exits).

What the copy computes is what the worker's :func:`.checks.run_row` with the mutant in place
would compute: the same row, from the same state, with the same code from the first call of
``f`` on. The row's time budget goes on in the copy where the parked process stopped it (an
interval timer is not inherited by a fork: the parked process stops its timer and the copy
starts one with what was left). The part watch of ``run_row`` (the stop at the first final part
that differs) is ordinary memory, copied with the rest.

The caller falls back to running the row in the worker (``None`` from :meth:`Parked.run`) when
the row never calls ``f``, when the parked process or a copy dies without an answer, or when the
answer cannot be pickled. A copy that does not answer within :data:`GRACE` seconds past the
row's budget is killed and reported as ``("timeout",)``: in the worker that mutant would have held
it forever (a loop in compiled code that the budget's signal cannot interrupt).
"""

from __future__ import annotations

import marshal
import os
import pickle
import signal
import struct
import sys
import time
from collections.abc import Callable
from types import FunctionType

#: Seconds a copy may run past the row's budget before it is killed.
GRACE = 30.0
_HEADER = struct.Struct("!I")


def _send(fd: int, obj) -> None:
    data = pickle.dumps(obj)
    os.write(fd, _HEADER.pack(len(data)))
    view = memoryview(data)
    while view:
        view = view[os.write(fd, view):]


def _receive(fd: int):
    """One message from ``fd``; ``EOFError`` when the writer is gone."""
    def read(n: int) -> bytes:
        out = b""
        while len(out) < n:
            chunk = os.read(fd, n - len(out))
            if not chunk:
                raise EOFError
            out += chunk
        return out

    return pickle.loads(read(_HEADER.unpack(read(_HEADER.size))[0]))


class Parked:
    """``run()`` (one unmutated row, e.g. :func:`.checks.run_row`) started in a forked process
    and stopped at the first call of ``fn``; :meth:`run` finishes it with a mutant, once per
    mutant, each in a fork of that stopped process. :meth:`close` ends the parked process."""

    def __init__(self, fn: FunctionType, run: Callable[[], object],
                 on_fork: Callable[[], object] | None = None):
        self.first_call: float | None = None  # CPU seconds of the row before the first call
        self._dead = False
        cmd_r, self._cmd = os.pipe()
        self._res, res_w = os.pipe()
        sys.stdout.flush()
        sys.stderr.flush()
        pid = os.fork()
        if pid == 0:  # the parked process: it never returns from here
            os.close(self._cmd)
            os.close(self._res)
            _parked_main(fn, run, cmd_r, res_w, on_fork)
        self.pid = pid
        os.close(cmd_r)
        os.close(res_w)
        try:
            kind, value = _receive(self._res)
        except (EOFError, OSError, pickle.UnpicklingError):
            kind, value = "dead", None
        if kind == "parked":
            self.first_call = value
        else:  # the row ended without calling fn (or the process died): nothing to fork from
            self.close()

    @property
    def usable(self) -> bool:
        return not self._dead

    def run(self, code, budget_grace: float = GRACE) -> object | None:
        """What ``run()`` returns with ``code`` in ``fn`` from its first call on, or None (the
        caller then runs the row itself): see the module docstring."""
        if self._dead:
            return None
        try:
            _send(self._cmd, (marshal.dumps(code), budget_grace))
            kind, value = _receive(self._res)
            if kind == "result":
                kind, _ = _receive(self._res)
                return value if kind == "ended" else None
            if kind == "killed":
                return ("timeout",), "ran past its budget (the copy was killed)"
            if kind == "ended":  # the copy died without an answer
                return None
            raise EOFError
        except (EOFError, OSError, pickle.PickleError):
            self.close()
            return None

    def close(self) -> None:
        """End the parked process (and wait for it). It is killed, not told: a parked process
        forked later from the same worker holds a copy of this one's command pipe, so closing
        the pipe here is no end of file there."""
        if self._dead:
            return
        self._dead = True
        for fd in (self._cmd, self._res):
            try:
                os.close(fd)
            except OSError:
                pass
        _kill(self.pid)
        try:
            os.waitpid(self.pid, 0)
        except ChildProcessError:
            pass


def _kill(pid: int) -> None:
    try:
        os.kill(pid, signal.SIGKILL)
    except ProcessLookupError:
        pass


def _wait(pid: int, seconds: float) -> bool:
    """Wait for the copy ``pid``; past ``seconds``, kill it: whether it was killed."""
    deadline, pause = time.monotonic() + seconds, 0.001
    while os.waitpid(pid, os.WNOHANG) == (0, 0):
        if time.monotonic() > deadline:
            os.kill(pid, signal.SIGKILL)
            os.waitpid(pid, 0)
            return True
        time.sleep(pause)
        pause = min(0.05, 2 * pause)
    return False


def _parked_main(fn: FunctionType, run, cmd_r: int, res_w: int, on_fork=None) -> None:
    """The parked process: run ``run()`` with ``fn``'s first call caught; serve mutants there
    (``on_fork()`` is called first thing in each copy)."""
    from chaplygin_nd import processes

    status = 1
    try:
        processes.die_with_parent(os.getppid())
        original = fn.__code__
        start = time.process_time()
        state = {"copy": False}

        def hook(*args, **kwargs):
            fn.__code__ = original  # the trampoline is no longer needed, here or in a copy
            budget = signal.setitimer(signal.ITIMER_REAL, 0)[0]  # no alarm while parked
            _send(res_w, ("parked", time.process_time() - start))
            while True:
                try:
                    message = _receive(cmd_r)
                except EOFError:
                    os._exit(0)
                code, grace = marshal.loads(message[0]), message[1]
                sys.stdout.flush()
                sys.stderr.flush()
                child = os.fork()
                if child == 0:
                    processes.die_with_parent(os.getppid())
                    state["copy"] = True
                    if on_fork is not None:
                        on_fork()
                    fn.__code__ = code
                    if budget:
                        signal.setitimer(signal.ITIMER_REAL, budget)
                    mutant = FunctionType(code, fn.__globals__, fn.__name__, fn.__defaults__,
                                          fn.__closure__)
                    mutant.__kwdefaults__ = fn.__kwdefaults__
                    return mutant(*args, **kwargs)
                _send(res_w, ("killed" if _wait(child, budget + grace) else "ended", None))

        from chaplygin_nd.ledger.mutation.replay import calls_through

        with calls_through(fn, hook):
            result = run()
        if state["copy"]:
            try:
                _send(res_w, ("result", result))
            except (pickle.PickleError, TypeError, AttributeError):
                pass  # the parked process then says "ended": the caller runs the row itself
        else:
            _send(res_w, ("not called", None))
        status = 0
    except BaseException:  # noqa: BLE001 - a copy or the parked process ends here, whatever happened
        status = 1
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(status)
