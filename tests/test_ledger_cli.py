"""`chaplygin verify/prove` as a user meets it (--report-dir too):
ids checked before any proof is imported, with "did you mean"; one-line option errors; the two
reports written as one result naming the run; report paths that cannot be written named in one
line; Ctrl-C one line, exit 130."""

from __future__ import annotations

import hashlib
import json
import os
import signal
import subprocess
import sys

import pytest
from chaplygin_nd.ledger import report
from chaplygin_nd.ledger.__main__ import _report_paths, main
from chaplygin_nd.ledger.catalog import resolve


def test_ids_are_stripped_and_near_misses_suggested():
    assert resolve([" eq:invL3D "]) == ["eq:invL3D"]
    assert resolve(["K:Delta", "eq:invL3D", " K:Delta"]) == ["K:Delta", "eq:invL3D"]  # each row once
    for wrong in ("EQ:INVL3D", "eq:invl3d", "eq:invL3"):
        with pytest.raises(KeyError, match="did you mean eq:invL3D"):
            resolve([wrong])


def test_an_unknown_id_is_answered_before_any_proof_is_imported():
    code = ("import sys; from chaplygin_nd.ledger.__main__ import main; c = main(['nonexistent:id']);"
            " sys.exit(10 + c if not [m for m in sys.modules if m.startswith('chaplygin_nd.proofs.')]"
            " else 99)")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert r.returncode == 12, r.stderr
    assert r.stderr.strip().splitlines() == [
        "error: unknown ledger id 'nonexistent:id'; `chaplygin prove --list` lists them"]


def test_a_bad_seed_is_one_line_naming_the_option(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["--seed", "1.5"])
    assert exc.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["error: chaplygin verify: --seed: not a non-negative integer: '1.5'"]


def test_the_two_reports_are_one_result(tmp_path):
    info = report.RunInfo(7, commit="abc1234", started="2026-01-01T00:00:00Z",
                          generation="g1", graph="claim-graph.svg")
    md, js = tmp_path / "VERIFICATION.md", tmp_path / "verification.json"
    report.write_pair([], md, js, info)
    data = json.loads(js.read_text())
    assert data["markdown_sha256"] == hashlib.sha256(md.read_bytes()).hexdigest()
    assert data["generation"] == "g1" and data["seed"] == 7 and data["commit"] == "abc1234"
    assert "generation g1" in md.read_text() and "commit abc1234" in md.read_text()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["VERIFICATION.md", "verification.json"]


def test_an_unwritable_report_is_named(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("mine")
    assert _report_paths(str(blocker), whole=True) == 2
    assert _report_paths(str(blocker / "sub"), whole=True) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 2 and all(line.startswith("error: --report-dir ") for line in err)
    with pytest.raises(OSError) as exc:
        report.write_files({blocker / "sub" / "VERIFICATION.md": "x"})
    assert exc.value.filename and "sub" in str(exc.value.filename)
    assert blocker.read_text() == "mine"


@pytest.mark.parametrize("moment", ["signals-taken", "pool-starting", "rows-running"])
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_ctrl_c_is_one_line_and_exit_130(sig, moment):
    """Ctrl-C (130) or SIGTERM (143) at an observed moment of ``prove --jobs 2``: once the program
    has taken the signals (imports still running), while its pool starts (the fork server is
    there: a starting worker's traceback was once seen), while the rows run (two workers)."""
    from process_helpers import cmdline, descendants, takes_signals, wait_for

    proc = subprocess.Popen([sys.executable, "-m", "chaplygin_nd", "prove", "eq:invL3D",
                             "P:inversion", "--jobs", "2"], stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True, env=dict(os.environ))

    def servers(count):
        return lambda: len([p for p in descendants(proc.pid) if "forkserver" in cmdline(p)]) >= count

    try:
        wait_for(lambda: takes_signals(proc.pid), "the program's signal handlers", process=proc)
        if moment != "signals-taken":
            wait_for(servers(1 if moment == "pool-starting" else 3), moment, process=proc)
    finally:
        proc.send_signal(sig)
        _, err = proc.communicate(timeout=120)
    assert "Traceback" not in err, err
    if proc.returncode != 0:  # not already done
        assert proc.returncode == 128 + sig and err.strip().splitlines() == ["interrupted"], err


def test_an_interrupted_verify_leaves_no_report_folder(tmp_path):
    """``verify --report-dir NEW`` interrupted while its rows run leaves nothing it created."""
    from process_helpers import wait_for

    new = tmp_path / "new" / "reports"
    proc = subprocess.Popen([sys.executable, "-m", "chaplygin_nd", "verify", "--jobs", "1",
                             "--report-dir", str(new)], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=dict(os.environ))
    try:
        wait_for(lambda: proc.stdout.readline().startswith("id "), "the ledger's header line",
                 process=proc)  # the rows run now
    finally:
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130 and err.strip().splitlines() == ["interrupted"], err
    assert list(tmp_path.iterdir()) == [], list(tmp_path.rglob("*"))


def test_report_files_cut_short_remove_the_folders_they_created(tmp_path, monkeypatch):
    """An interrupt (or an error) before the files are in place: the new folders go again."""
    def interrupted(*args):
        raise KeyboardInterrupt

    monkeypatch.setattr(report.os, "replace", interrupted)
    with pytest.raises(KeyboardInterrupt):
        report.write_files({tmp_path / "a" / "b" / "VERIFICATION.md": "x",
                            tmp_path / "a" / "b" / "verification.json": "{}"})
    assert list(tmp_path.iterdir()) == []
    (tmp_path / "kept").mkdir()
    with pytest.raises(KeyboardInterrupt):
        report.write_files({tmp_path / "kept" / "new" / "VERIFICATION.md": "x"})
    assert [p.name for p in tmp_path.rglob("*")] == ["kept"]
