"""Helpers of the process tests (tests/test_orphans.py, tests/test_interrupts.py): a process's
descendants read from /proc, waiting on an observed state with a deadline (never a fixed sleep)."""

from __future__ import annotations

import os
import time
from collections.abc import Callable
from pathlib import Path

from chaplygin_nd.processes import alive


def parents() -> dict[int, int]:
    """{pid: parent pid} of every process (Linux /proc)."""
    out = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_bytes()
            except OSError:
                continue
            out[int(entry.name)] = int(stat.rsplit(b")", 1)[1].split()[1])
    return out


def descendants(pid: int) -> set[int]:
    """The living descendants of ``pid`` (children, their children, ...)."""
    tree = parents()
    found, frontier = set(), {pid}
    while frontier:
        frontier = {p for p, pp in tree.items() if pp in frontier} - found
        found |= frontier
    return {p for p in found if alive(p)}


def cmdline(pid: int) -> str:
    try:
        return Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode()
    except OSError:
        return ""


def wait_for(condition: Callable[[], object], what: str, timeout: float = 240.0,
             process=None) -> object:
    """Poll ``condition`` until it is true (returned) or ``timeout`` seconds pass (fails, naming
    ``what``); fails at once if ``process`` (a Popen) has ended."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        value = condition()
        if value:
            return value
        if process is not None and process.poll() is not None:
            raise AssertionError(f"the process ended (rc {process.returncode}) before {what}")
        time.sleep(0.02)
    raise AssertionError(f"timed out after {timeout} s waiting for {what}")


def none_alive(pids: set[int], timeout: float = 5.0) -> set[int]:
    """The pids of ``pids`` still alive after up to ``timeout`` seconds (polled; empty is good)."""
    deadline = time.monotonic() + timeout
    while True:
        left = {p for p in pids if alive(p)}
        if not left or time.monotonic() > deadline:
            return left
        time.sleep(0.05)


def kill_all(pids) -> None:
    """Clean up after a failed test: SIGKILL ``pids`` still alive (ours, by pid)."""
    import signal

    for p in pids:
        if alive(p):
            try:
                os.kill(p, signal.SIGKILL)
            except OSError:
                pass


def takes_signals(pid: int) -> bool:
    """Whether ``pid`` catches SIGTERM (``SigCgt`` in /proc): the ``chaplygin`` program has
    installed its handlers (chaplygin_nd.console.take_signals, SIGTERM last)."""
    import signal

    try:
        status = Path(f"/proc/{pid}/status").read_text()
    except OSError:
        return False
    mask = int(next(line.split()[1] for line in status.splitlines() if line.startswith("SigCgt:")), 16)
    return bool(mask >> (signal.SIGTERM - 1) & 1)
