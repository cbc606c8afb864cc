"""Wall and CPU time of a cold ``chaplygin verify`` (the target: ``make verify`` cold <= 45 s wall).

``python -m chaplygin_nd.bench.bench_verify_cold [ARGS...]`` runs ``chaplygin verify ARGS`` (default
``--check-generated``) with empty caches (``$CHAPLYGIN_ND_CACHE`` and ``$XDG_CACHE_HOME`` pointed at a
new temporary folder) and prints one line: the exit code, the wall time, the user and system CPU
time of every process the run started, and the load average before and after.

``time`` (and ``/usr/bin/time``) miss most of that CPU: the ledger's workers are children of the
multiprocessing fork server, which is orphaned when the run ends and never waited for by it. Here
the measuring process is a child subreaper (Linux ``PR_SET_CHILD_SUBREAPER``): the orphaned server
is re-parented to it and reaped, so ``RUSAGE_CHILDREN`` holds the CPU of the whole tree. On a shared
machine compare CPU rather than wall, and only runs made side by side.
"""

from __future__ import annotations

import ctypes
import os
import resource
import subprocess
import sys
import tempfile
import time

from chaplygin_nd import processes

#: ``<linux/prctl.h>``: become the reaper of orphaned descendants.
PR_SET_CHILD_SUBREAPER = 36


def measure(command: list[str], env: dict[str, str] | None = None) -> dict:
    """Run ``command`` to its end (with every descendant reaped); ``{"rc", "wall", "user",
    "sys", "load_before", "load_after"}`` (seconds; the load is the 1-minute average). Linux only
    for the descendants' CPU (elsewhere only the direct child's tree that was waited for counts)."""
    if sys.platform.startswith("linux"):
        ctypes.CDLL(None, use_errno=True).prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0)
    load_before = os.getloadavg()[0]
    start = time.perf_counter()
    rc = subprocess.run(command, env=env, check=False, **processes.popen_kwargs()).returncode
    while True:  # the fork server and anything else handed to this process
        try:
            os.wait()
        except ChildProcessError:
            break
    wall = time.perf_counter() - start
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return {"rc": rc, "wall": wall, "user": usage.ru_utime, "sys": usage.ru_stime,
            "load_before": load_before, "load_after": os.getloadavg()[0]}


def main(argv: list[str] | None = None) -> int:
    """Measure a cold ``chaplygin verify`` (arguments passed on) and print one line."""
    args = list(sys.argv[1:] if argv is None else argv) or ["--check-generated"]
    with tempfile.TemporaryDirectory(prefix="verify-cold-") as tmp:
        env = dict(os.environ, CHAPLYGIN_ND_CACHE=os.path.join(tmp, "cache"),
                   XDG_CACHE_HOME=os.path.join(tmp, "xdg"))
        m = measure([sys.executable, "-m", "chaplygin_nd", "verify", *args], env)
    print(f"verify cold: rc {m['rc']}, wall {m['wall']:.1f} s, CPU {m['user'] + m['sys']:.1f} s "
          f"(user {m['user']:.1f}, sys {m['sys']:.1f}), load {m['load_before']:.2f} -> "
          f"{m['load_after']:.2f} on {os.cpu_count()} cores")
    return m["rc"]


if __name__ == "__main__":
    raise SystemExit(main())
