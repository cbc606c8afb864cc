"""Whole or marked incomplete, never mixed: runs into one output folder are
interrupted (8 times) at seeded random moments by SIGINT, SIGTERM or SIGKILL, the scene is edited between
runs, and after every run the folder holds either nothing, or the complete result of exactly one
run (every file of its manifest, no other, the CSV equal to the NPZ, the summary naming that run),
or says it is incomplete; a final run repairs it. A second run into a locked folder is refused."""

from __future__ import annotations

import json
import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from chaplygin_nd.simulate.scene.outdir import MANIFEST, SIBLING, lock_file

ROOT = Path(__file__).resolve().parent.parent

SCENE = """title = "run {tag}"
n = 3
a = 0.5
b = 1.0
[initial]
family = "generic"
seed = {seed}
count = 3
[times]
t_end = 4.0
samples = 161
[outputs]
want = ["M", "gamma", "x", "integrals"]
[accuracy]
target = 1e-8
method = "dop853"
"""


def _start(scene: Path, out: Path) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-m", "chaplygin_nd", "simulate", str(scene),
                             "--out", str(out)], stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True, env=dict(os.environ))


def _check_invariant(out: Path) -> str:
    """'absent', 'complete:<tag>' or 'incomplete'; fails on anything else."""
    if not out.exists():
        return "absent"
    manifest = json.loads((out / MANIFEST).read_text())
    names = {p.name for p in out.iterdir()} - {MANIFEST}
    if manifest.get("status") == "incomplete":
        assert names <= set(manifest["files"]), names
        return "incomplete"
    assert names == set(manifest["files"]), (names, manifest)
    with np.load(out / "outputs.npz") as data:
        x = data["x"]
    csv = np.loadtxt(out / "x.csv", delimiter=",", skiprows=1)
    # rows: (t, member, x) ordered by member then time; the npz is (samples, members)
    assert np.array_equal(csv[:, 2], x.T.ravel()), "x.csv and outputs.npz come from two runs"
    summary = (out / "summary.txt").read_text()
    tag = summary.split("scene   run ", 1)[1].split()[0]
    seed = int(tag.split("-")[1])
    from chaplygin_nd.simulate.scene.spec import loads

    expect = loads(SCENE.format(tag=tag, seed=seed)).gamma0[:, -1]
    assert np.array_equal(x[0], expect), "the outputs are not those of the run the summary names"
    return f"complete:{tag}"


@pytest.mark.slow
def test_interrupted_runs_leave_a_whole_result_or_an_incomplete_mark(tmp_path):
    rng = random.Random(19)
    scene, out = tmp_path / "edited.toml", tmp_path / "result"
    states, codes = [], []
    scene.write_text(SCENE.format(tag="first-1", seed=1))
    started = time.perf_counter()
    proc = _start(scene, out)
    _, err = proc.communicate(timeout=300)
    assert proc.returncode == 0, err
    durations = [time.perf_counter() - started]  # of a whole run, on this machine now
    for k in range(8):
        seed = rng.randrange(1000)
        scene.write_text(SCENE.format(tag=f"{k}-{seed}", seed=seed))
        sig = rng.choice([signal.SIGINT, signal.SIGTERM, signal.SIGKILL])
        proc = _start(scene, out)
        started = time.perf_counter()
        time.sleep(rng.uniform(0.3, 1.1) * max(durations))
        proc.send_signal(sig)
        _, err = proc.communicate(timeout=300)
        codes.append(proc.returncode)
        if proc.returncode == 0:
            durations.append(time.perf_counter() - started)
        elif sig != signal.SIGKILL:
            assert proc.returncode == 128 + sig, err  # 130 for SIGINT, 143 for SIGTERM
            assert err.strip().splitlines()[-1] == "interrupted" and "Traceback" not in err, err
        else:
            assert proc.returncode == -signal.SIGKILL
        states.append(_check_invariant(out))
        assert sorted(p.name for p in tmp_path.iterdir() if not p.name.startswith(".")) \
            == sorted(["edited.toml"] + (["result"] if out.exists() else []))
    assert any(c != 0 for c in codes), codes  # some runs were really interrupted
    print("exit codes", codes, "states", states)
    seed = 4242
    scene.write_text(SCENE.format(tag=f"final-{seed}", seed=seed))
    proc = _start(scene, out)
    _, err = proc.communicate(timeout=300)
    assert proc.returncode == 0, err
    assert _check_invariant(out) == f"complete:final-{seed}"
    assert not [p for p in tmp_path.iterdir() if SIBLING in p.name], "a staging folder was left"


def test_a_second_run_into_a_locked_folder_is_refused(tmp_path):
    scene, out, log = tmp_path / "s.toml", tmp_path / "result", tmp_path / "first.err"
    # a first run that lasts (the mpmath Taylor method, forced past the time limit) holds the lock
    scene.write_text(SCENE.format(tag="0-1", seed=1).replace("t_end = 4.0", "t_end = 40000.0")
                     .replace('method = "dop853"', 'method = "reference"'))
    with open(log, "w") as err_file:
        first = subprocess.Popen([sys.executable, "-m", "chaplygin_nd", "simulate", str(scene),
                                  "--out", str(out), "--force"], stdout=subprocess.DEVNULL,
                                 stderr=err_file, text=True, env=dict(os.environ))
    try:
        lock, expected = lock_file(out), f"{first.pid} {os.path.realpath(out)}"
        deadline = time.time() + 240
        while time.time() < deadline and first.poll() is None:  # until the first run holds it
            if lock.exists() and lock.read_text().strip() == expected:
                break
            time.sleep(0.05)
        assert first.poll() is None, log.read_text()
        assert lock.read_text().strip() == expected, "the first run never took the lock"
        second = subprocess.run([sys.executable, "-m", "chaplygin_nd", "simulate", str(scene),
                                 "--out", str(out), "--no-plots"], capture_output=True, text=True,
                                timeout=300)
        assert second.returncode == 2, second.stderr
        lines = second.stderr.strip().splitlines()
        assert len(lines) == 1 and "another run is writing into this folder" in lines[0]
        # interrupt the first run while it integrates (after its cost line), as a user would
        while time.time() < deadline and first.poll() is None and "cost:" not in log.read_text():
            time.sleep(0.05)
    finally:
        first.send_signal(signal.SIGINT)
        first.wait(timeout=300)
    err = log.read_text()
    assert first.returncode == 130 and err.strip().splitlines()[-1] == "interrupted", err
    assert not out.exists()  # interrupted before writing: nothing, not half a result


@pytest.mark.slow
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_seeded_interrupts_at_0_to_2_s_are_one_line(tmp_path, sig):
    """A handful of seeded trials (300-trial runs of the same loop passed): a run
    of a long scene, from an empty cache, is sent ``sig`` at a seeded moment 0-2 s after the
    program has taken the signals (observed in /proc) — during the imports, the planning, the
    compile or the integration. Every trial ends with the one line ``interrupted`` and exit 130
    (SIGINT) or 143 (SIGTERM): no traceback, no crash, no lost interrupt (the scene lasts
    minutes, so exit 0 would be one), no output folder."""
    from process_helpers import takes_signals, wait_for

    scene = tmp_path / "long.toml"
    scene.write_text((ROOT / "scenes" / "generic4d.toml").read_text()
                     .replace("t_end = 100.0", "t_end = 1000000.0"))
    rng = random.Random(25 + sig)
    for trial in range(4):
        out = tmp_path / f"out-{trial}"
        env = dict(os.environ, CHAPLYGIN_ND_CACHE=str(tmp_path / f"cache-{trial}"),
                   PYTHONFAULTHANDLER="1")
        proc = subprocess.Popen([sys.executable, "-m", "chaplygin_nd", "simulate", str(scene),
                                 "--out", str(out), "--no-plots", "--force"],
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                                env=env)
        delay = rng.uniform(0.0, 2.0)
        try:
            wait_for(lambda p=proc.pid: takes_signals(p), "the program's signal handlers",
                     process=proc)
            time.sleep(delay)  # the seeded moment of this trial, after the observed state
        finally:
            proc.send_signal(sig)
            _, err = proc.communicate(timeout=300)
        lines = err.strip().splitlines()
        # Before the signal a run may have printed its projected cost (budget.Projection announces
        # a run longer than 10 s once its 0.5 s pilot is done: on an idle machine the pilot ends
        # within the 2 s); the interrupt itself adds exactly the one line.
        assert proc.returncode == 128 + sig and lines[-1:] == ["interrupted"] \
            and all(line.startswith("cost: ") for line in lines[:-1]), \
            (trial, delay, proc.returncode, err)
        assert not out.exists(), (trial, delay)
