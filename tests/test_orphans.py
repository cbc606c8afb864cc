"""No orphans: every kind of pool the project starts loses its workers when its parent
is killed with SIGKILL (no ``finally``, no shutdown), within 5 s. Each test waits until the
workers are observed at work (a file a worker wrote, or the worker processes present), kills the
parent, and polls the recorded workers with a deadline.

The pools: :func:`chaplygin_nd.processes.pool` under each start method the project uses (fork:
the mutation runs; forkserver: ``verify --jobs``; spawn: the frequency-map workers), a
:mod:`subprocess` child (the benchmarks), and the real commands ``chaplygin prove --jobs 2``,
``chaplygin simulate fma4d --workers 2`` and ``--scheduler local`` (Dask). A last test reads the
sources: every pool is made through :mod:`chaplygin_nd.processes`."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
from process_helpers import cmdline, descendants, kill_all, none_alive, wait_for

ROOT = Path(__file__).resolve().parent.parent

POOL_SCRIPT = textwrap.dedent("""
    import multiprocessing as mp, os, sys, time
    from pathlib import Path
    from chaplygin_nd import processes

    def work(i):
        Path(sys.argv[2], f"worker-{os.getpid()}").write_text("busy")
        time.sleep(600)

    if __name__ == "__main__":
        with processes.pool(2, mp.get_context(sys.argv[1])) as pool:
            list(pool.map(work, range(2)))
""")

POPEN_SCRIPT = textwrap.dedent("""
    import subprocess, sys
    from chaplygin_nd import processes
    child = "import os, sys, time, pathlib; pathlib.Path(sys.argv[1], f'worker-{os.getpid()}').write_text('busy'); time.sleep(600)"
    subprocess.run([sys.executable, "-c", child, sys.argv[1]], **processes.popen_kwargs())
""")


def _kill_parent_and_check(proc: subprocess.Popen, workers: set[int]) -> None:
    everything = descendants(proc.pid) | workers
    try:
        proc.send_signal(signal.SIGKILL)
        proc.wait(timeout=30)
        left = none_alive(everything, timeout=5.0)
        assert not left, [(p, cmdline(p)[:120]) for p in left]
    finally:
        kill_all(everything)


def _busy_workers(folder: Path, count: int) -> set[int]:
    return {int(p.name.split("-")[1]) for p in folder.glob("worker-*")} \
        if len(list(folder.glob("worker-*"))) >= count else set()


@pytest.mark.parametrize("method", ["fork", "forkserver", "spawn"])
def test_pool_workers_die_with_a_killed_parent(tmp_path, method):
    script = tmp_path / "pool.py"
    script.write_text(POOL_SCRIPT)
    proc = subprocess.Popen([sys.executable, str(script), method, str(tmp_path)])
    try:
        workers = wait_for(lambda: _busy_workers(tmp_path, 2), "two busy workers", process=proc)
    except BaseException:
        kill_all(descendants(proc.pid) | {proc.pid})
        raise
    _kill_parent_and_check(proc, workers)


def test_a_subprocess_dies_with_a_killed_parent(tmp_path):
    script = tmp_path / "popen.py"
    script.write_text(POPEN_SCRIPT)
    proc = subprocess.Popen([sys.executable, str(script), str(tmp_path)])
    try:
        workers = wait_for(lambda: _busy_workers(tmp_path, 1), "the child at work", process=proc)
    except BaseException:
        kill_all(descendants(proc.pid) | {proc.pid})
        raise
    _kill_parent_and_check(proc, workers)


def _command_workers(proc, marker: str, count: int):
    def found():
        pids = {p for p in descendants(proc.pid) if marker in cmdline(p)}
        return pids if len(pids) >= count else set()
    return found


@pytest.mark.parametrize("argv, marker, count", [
    (["prove", "eq:invL3D", "P:inversion", "--jobs", "2"], "forkserver", 3),  # server + 2 workers
    (["simulate", str(ROOT / "scenes" / "fma4d.toml"), "--workers", "2"], "spawn", 2),
    (["simulate", str(ROOT / "scenes" / "fma4d.toml"), "--workers", "2", "--scheduler", "local"],
     "spawn", 2),
], ids=["verify-jobs", "fma-workers", "dask-local"])
def test_the_commands_pools_die_with_a_killed_parent(tmp_path, argv, marker, count):
    """The frequency maps are killed mid-run: once their progress line (orbits done / total)
    shows that the workers compute."""
    if argv[0] == "simulate":
        argv = [*argv, "--out", str(tmp_path / "out"), "--force"]
    log = tmp_path / "stderr.txt"
    with open(log, "w") as err:
        proc = subprocess.Popen([sys.executable, "-m", "chaplygin_nd", *argv], cwd=tmp_path,
                                stdout=subprocess.DEVNULL, stderr=err, env=dict(os.environ))
    try:
        workers = wait_for(_command_workers(proc, marker, count), f"{count} {marker} processes",
                           process=proc)
        if argv[0] == "simulate":
            wait_for(lambda: "frequency map: orbits" in log.read_text(), "the progress line",
                     process=proc)
            workers = _command_workers(proc, marker, count)() or workers
    except BaseException:
        kill_all(descendants(proc.pid) | {proc.pid})
        raise
    _kill_parent_and_check(proc, workers)


def test_every_pool_is_made_through_the_processes_module():
    """Read the sources: no ProcessPoolExecutor, multiprocessing Pool or Process but through
    chaplygin_nd.processes; every LocalCluster arms its workers; every subprocess of the
    benchmarks gets popen_kwargs."""
    offenders = []
    for folder in ("chaplygin_nd", "ledger", "simulate", "symbolic", "runtime", "bench", "proofs"):
        for path in sorted((ROOT / folder).rglob("*.py")):
            if path.name == "processes.py":
                continue
            text = path.read_text()
            if re.search(r"ProcessPoolExecutor\(|\.Pool\(|mp\.Process\(|multiprocessing\.Process\(",
                         text):
                offenders.append(f"{path.relative_to(ROOT)}: a pool not made by processes.pool")
            if "LocalCluster(" in text and "processes.die_with_parent" not in text:
                offenders.append(f"{path.relative_to(ROOT)}: a LocalCluster whose workers are not armed")
            if folder == "bench" and re.search(r"subprocess\.(run|Popen)\(", text) \
                    and "popen_kwargs" not in text:
                offenders.append(f"{path.relative_to(ROOT)}: a subprocess without popen_kwargs")
    assert not offenders, offenders


THREAD_SIGNAL_SCRIPT = textwrap.dedent("""
    import multiprocessing as mp, os, signal, sys, threading, time
    from pathlib import Path
    from chaplygin_nd import processes

    def work(i):
        Path(sys.argv[1], f"worker-{os.getpid()}").write_text("busy")
        time.sleep(600)

    if __name__ == "__main__":
        # Python's Ctrl-C handling, whatever this process inherited: a job a script starts with
        # `&` (or nohup) inherits SIGINT ignored, Python then keeps it ignored, and the SIGINT
        # below would be lost (the test then hung for its whole timeout)
        signal.signal(signal.SIGINT, signal.default_int_handler)
        with processes.pool(1, mp.get_context("fork")) as pool:
            futures = [pool.submit(work, 0)]
            def interrupt():   # the Ctrl-C lands in another thread, as the kernel may choose
                while not any(Path(sys.argv[1]).iterdir()):
                    time.sleep(0.05)
                signal.pthread_kill(threading.get_ident(), signal.SIGINT)
            threading.Thread(target=interrupt, daemon=True).start()
            for f in processes.as_completed(futures):
                f.result()
""")


def test_a_ctrl_c_taken_by_another_thread_ends_the_wait_for_the_workers(tmp_path):
    """The kernel gives a process's SIGINT to any thread not blocking it (a queue feeder, heyoka's
    TBB threads); Python handles it in the main thread only. processes.as_completed wakes to take
    it: the parent raises KeyboardInterrupt while its worker still sleeps (the standard library's
    as_completed slept on until the task ended: 600 s here), and the worker goes with the pool."""
    proc = subprocess.run([sys.executable, "-c", THREAD_SIGNAL_SCRIPT, str(tmp_path)],
                          capture_output=True, text=True, timeout=300, cwd=ROOT)
    assert proc.returncode != 0 and "KeyboardInterrupt" in proc.stderr, proc.stderr[-2000:]
    workers = {int(p.name.split("-")[1]) for p in tmp_path.iterdir()}
    assert len(workers) == 1 and not none_alive(workers)
