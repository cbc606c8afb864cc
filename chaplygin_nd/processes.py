"""Every process the project starts ends when the process that started it ends.

One mechanism for every pool (the ledger's ``verify --jobs``, the frequency-map workers, the Dask
local cluster, the mutation runs, the benchmarks' subprocesses): the first thing a worker does is
:func:`die_with_parent`.

* On Linux it asks the kernel for SIGKILL when its parent dies (``prctl(PR_SET_PDEATHSIG)``), so
  a parent killed by SIGKILL — which runs no ``finally`` and no pool shutdown — still takes its
  workers with it. The request holds for the worker's direct parent: a ``forkserver`` worker's
  parent is the fork server, which exits when the last holder of its ``alive`` pipe is gone. The
  owner holds that pipe, and so does every worker (multiprocessing hands it over): a worker
  therefore closes its copy first, so the server ends with the owner and its workers follow.
* The parent may die before the request is made (between the fork and the ``prctl``): the worker
  then checks that the pool's owner (``owner``, the pid that made the pool) is still alive, and
  exits at once if not. The check comes after the request, so no moment is left uncovered.
* Elsewhere (macOS, Windows) a daemon thread polls the owner every second and ends the worker
  when it is gone.

A worker also ignores Ctrl-C: the terminal sends SIGINT to the whole process group, and the
parent alone decides what an interrupt means (one line ``interrupted``, the pool shut down by
the parent). A worker started by a thread other than the main one would be killed when that
thread ends (the kernel's "parent" is the thread): every pool here is made by the main thread.

:func:`pool` is the project's :class:`~concurrent.futures.ProcessPoolExecutor` (:class:`Pool`: its
workers are all started, with Ctrl-C held, before it is used); :func:`popen_kwargs` gives a
:mod:`subprocess` child the same guarantee.

The parent waits for its futures with :func:`as_completed`, which wakes every
:data:`POLL_SECONDS`: the kernel gives a process's SIGINT or SIGTERM to any thread that does not
block it (a pool's queue feeder, heyoka's TBB workers), and Python runs the handler only in the
main thread, at its next bytecode; a main thread asleep in ``concurrent.futures.as_completed``
then slept on until a task finished (seen: ``chaplygin mutate-derivations`` ignored a Ctrl-C for
minutes).
"""

from __future__ import annotations

import contextlib
import ctypes
import multiprocessing as mp
import os
import signal
import sys
import threading
import time
from collections.abc import Callable
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait

__all__ = ["die_with_parent", "worker_start", "held_signals", "Pool", "pool", "popen_kwargs",
           "as_completed",
           "alive"]

#: ``<linux/prctl.h>``: the signal a process gets when its parent dies.
PR_SET_PDEATHSIG = 1
#: How often the fallback watcher (not Linux) looks at the owner, in seconds.
WATCH_SECONDS = 1.0

_armed: set[int] = set()


def alive(pid: int) -> bool:
    """Whether process ``pid`` runs (a zombie — dead, not yet reaped — counts as dead)."""
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    except OSError:
        return False
    try:
        with open(f"/proc/{pid}/stat", "rb") as f:
            state = f.read().rsplit(b")", 1)[1].split()[0]
    except (OSError, IndexError):
        return True
    return state not in (b"Z", b"X")


def _prctl_pdeathsig() -> bool:
    if not sys.platform.startswith("linux"):
        return False
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        return libc.prctl(PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0) == 0
    except (OSError, AttributeError):
        return False


def _watch(owner: int) -> None:
    import time

    while alive(owner):
        time.sleep(WATCH_SECONDS)
    os._exit(1)


def die_with_parent(owner: int) -> None:
    """Make this process end when ``owner`` (the process that made its pool) or its own parent
    ends, whatever kills it (see the module docstring). Idempotent; safe in any process."""
    if owner in _armed or owner == os.getpid():
        return
    if not _prctl_pdeathsig():
        threading.Thread(target=_watch, args=(owner,), daemon=True,
                         name="chaplygin-owner-watch").start()
    _armed.add(owner)
    if not alive(owner):  # it died before the request was made
        os._exit(1)


def _release_fork_server() -> None:
    """In a worker: close this process's copy of the fork server's ``alive`` pipe (see the module
    docstring) and forget the server, so that a nested pool would start its own."""
    from multiprocessing import forkserver

    server = forkserver._forkserver
    fd = getattr(server, "_forkserver_alive_fd", None)
    if fd is not None:
        try:
            os.close(fd)
        except OSError:
            pass
        # CPython-private attributes of multiprocessing.forkserver.ForkServer (3.11-3.13)
        server._forkserver_alive_fd = None  # type: ignore[attr-defined]
        server._forkserver_pid = None  # type: ignore[attr-defined]
        server._forkserver_address = None  # type: ignore[attr-defined]


def worker_start(owner: int, ready=None, then: Callable[..., object] | None = None,
                 *args) -> None:
    """The initializer of every pool worker: ignore Ctrl-C (the parent's), die of SIGTERM (the
    parent's :meth:`Pool.stop`), :func:`die_with_parent`
    ``owner``, let go of the signals the parent held while it started the pool (inherited as
    blocked; a SIGTERM the parent sent in the meantime ends the worker here), tell the parent
    (``ready``), then run the pool's own initializer ``then(*args)``."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # drops a Ctrl-C held since the fork
    # the parent's SIGTERM ends a worker (Pool.stop): a forked worker inherited the handler of
    # held_signals (which only notes the signal), so a worker of a fork pool outlived stop() and
    # the parent's Ctrl-C waited for its task to end
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    if os.getpid() != owner:
        _release_fork_server()
    die_with_parent(owner)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, HELD)
    if ready is not None:
        ready.release()
    if then is not None:
        then(*args)


#: The signals held back while a pool starts.
HELD = {signal.SIGINT, signal.SIGTERM}


@contextlib.contextmanager
def held_signals():
    """Within the block Ctrl-C and SIGTERM wait (main thread only): they are blocked, so the
    processes started here inherit them blocked, and a signal that reaches another thread is
    recorded; after the block the first one is raised again, with the handlers of before."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    held: list[int] = []

    def hold(signum, frame):
        held.append(signum)

    old = {s: signal.signal(s, hold) for s in HELD}
    mask = signal.pthread_sigmask(signal.SIG_BLOCK, HELD)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, mask)  # a pending one runs hold() now
        for s, handler in old.items():
            signal.signal(s, handler if handler is not None else signal.SIG_DFL)
        if held:
            signal.raise_signal(held[0])


class Pool(ProcessPoolExecutor):
    """A :class:`~concurrent.futures.ProcessPoolExecutor` whose workers die with this process
    (:func:`worker_start`), all started before the constructor returns, with Ctrl-C and SIGTERM
    held until every worker is past its start-up (:func:`held_signals`): an interrupt never
    tears the pool down under a worker that is still unpickling its queues (a starting
    forkserver worker then printed a ``FileNotFoundError`` traceback from ``SemLock._rebuild``).
    Leaving a ``with`` block by an exception (Ctrl-C included) ends the workers at once instead
    of waiting for the tasks in progress."""

    def __init__(self, workers: int, context=None, initializer=None, initargs: tuple = ()):
        context = context or mp.get_context()
        self._ready = context.Semaphore(0)
        super().__init__(workers, mp_context=context, initializer=worker_start,
                         initargs=(os.getpid(), self._ready, initializer, *initargs))
        try:
            with held_signals():
                self._launch_processes()  # type: ignore[attr-defined]  # CPython-private
                started = 0
                deadline = time.monotonic() + START_SECONDS
                while started < workers and time.monotonic() < deadline:
                    if self._ready.acquire(timeout=0.1):
                        started += 1
                    elif any(p.exitcode is not None for p in list(self._processes.values())):
                        break  # a worker that died starting: the pool reports it as broken
                # The executor's manager thread, too, starts here with the signals held: started by
                # the first submit, a Ctrl-C landing in Thread.start() left it unstarted and the
                # teardown's join raised "cannot join thread before it is started" (a traceback).
                self._start_executor_manager_thread()
        except BaseException:  # a signal held during the start is raised on leaving the block:
            self.stop()        # the caller never gets the pool, so it is ended here
            raise

    def stop(self) -> None:
        """End the workers now (SIGTERM) and drop the tasks not yet done."""
        for process in list((self._processes or {}).values()):
            process.terminate()
        self.shutdown(wait=True, cancel_futures=True)

    def __exit__(self, exc_type, exc, tb):
        if exc_type is None:
            self.shutdown(wait=True)
        else:
            self.stop()
        return False


#: The longest wait for a pool's workers to start (a loaded machine; spawn imports NumPy).
START_SECONDS = 300.0


def pool(workers: int, context=None, initializer: Callable[..., object] | None = None,
         initargs: tuple = ()) -> Pool:
    """A :class:`Pool` of ``workers`` processes (start method ``context``, a :mod:`multiprocessing`
    context; default the platform's) running ``initializer(*initargs)`` after their start."""
    return Pool(workers, context, initializer, initargs)


#: How often a parent waiting for its workers looks at the signals it received (s).
POLL_SECONDS = 0.2


def as_completed(futures, poll: float = POLL_SECONDS, on_wake=None):
    """The ``futures`` as they finish (like ``concurrent.futures.as_completed``), waking every
    ``poll`` seconds so that a Ctrl-C or SIGTERM taken by another thread reaches the main thread
    (module docstring); ``on_wake()``, if given, is called at each wake (e.g. a progress line
    while a long task runs)."""
    pending: set[Future] = set(futures)
    while pending:
        done, pending = wait(pending, timeout=poll, return_when=FIRST_COMPLETED)
        if on_wake is not None:
            on_wake()
        yield from done


def popen_kwargs() -> dict:
    """Keyword arguments for :func:`subprocess.run` / :class:`subprocess.Popen`: the child dies
    with this process (the same request, made between fork and exec)."""
    owner = os.getpid()

    def _arm():  # runs in the child, before exec; the request survives exec
        if _prctl_pdeathsig() and not alive(owner):
            os._exit(1)

    return {"preexec_fn": _arm} if sys.platform.startswith("linux") else {}
