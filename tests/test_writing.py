"""Files written atomically get the mode a plain open() gives (0o666 & ~umask) or keep the mode of the
file they replace (chaplygin_nd/writing.py; the mutation JSONs were once written
0600 by tempfile.mkstemp)."""

from __future__ import annotations

import contextlib
import json
import os
import stat
from pathlib import Path

import pytest
from chaplygin_nd.ledger.reach import write_json_atomic

from chaplygin_nd.writing import folder_problem, write_atomic, write_temporary


@contextlib.contextmanager
def umask(mask: int):
    old = os.umask(mask)
    try:
        yield
    finally:
        os.umask(old)


def mode(path) -> int:
    return stat.S_IMODE(os.stat(path).st_mode)


def plain_open_mode(tmp_path, mask: int) -> int:
    """The mode ``open(path, "w")`` gives a new file under ``mask``: the reference."""
    with umask(mask):
        ref = tmp_path / f"plain-{mask:o}"
        ref.write_text("x")
    return mode(ref)


@pytest.mark.parametrize("mask", [0o022, 0o002, 0o077])
def test_write_json_atomic_gives_the_mode_of_a_plain_open(tmp_path, mask):
    target = tmp_path / "mutation.json"
    with umask(mask):
        write_json_atomic({"b": 1, "a": [2]}, target)
    assert mode(target) == plain_open_mode(tmp_path, mask) == 0o666 & ~mask
    assert json.loads(target.read_text()) == {"a": [2], "b": 1}
    assert target.read_text().endswith("\n")
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        ["mutation.json", f"plain-{mask:o}"])  # no temporary left


@pytest.mark.parametrize("old", [0o640, 0o604, 0o444])
def test_write_json_atomic_keeps_the_mode_of_the_file_it_replaces(tmp_path, old):
    target = tmp_path / "mutation.json"
    target.write_text("{}\n")
    os.chmod(target, old)
    with umask(0o077):  # the umask does not narrow a kept mode
        write_json_atomic({"x": 1}, target)
    assert mode(target) == old
    assert json.loads(target.read_text()) == {"x": 1}


@pytest.mark.parametrize("data", ["text ✓\n", b"\x00bytes", "writer"])
def test_write_atomic_takes_text_bytes_or_a_writer(tmp_path, data):
    target = tmp_path / "out.npz"
    seen = []

    def writer(p):
        seen.append(p)
        assert p.name.startswith(".out.npz.") and p.name.endswith(".tmp.npz")
        p.write_bytes(b"from the writer")

    with umask(0o022):
        write_atomic(target, writer if data == "writer" else data)
    expected = (b"from the writer" if data == "writer" else
                data.encode() if isinstance(data, str) else data)
    assert target.read_bytes() == expected and mode(target) == 0o644
    assert [p.name for p in tmp_path.iterdir()] == ["out.npz"]


def test_forced_mode_and_no_temporary_left_on_error(tmp_path):
    target = tmp_path / "entry.pkl"
    write_atomic(target, b"secret", mode=0o600)
    assert mode(target) == 0o600

    def broken(p):
        p.write_bytes(b"half")
        raise RuntimeError("writer failed")

    with pytest.raises(RuntimeError):
        write_atomic(target, broken)
    assert target.read_bytes() == b"secret"  # the old file, whole
    assert [p.name for p in tmp_path.iterdir()] == ["entry.pkl"]
    tmp = write_temporary(target, "new")
    assert tmp.parent == tmp_path and tmp.read_text() == "new" and mode(tmp) == 0o600


# --- an output folder is checked by creating what the program would create ---
def _really_writable(folder) -> bool:
    """The oracle: can a file be opened for writing in ``folder`` right now (removed again)?"""
    probe = folder / "oracle-probe"
    try:
        probe.open("w").close()
    except OSError:
        return False
    probe.unlink()
    return True


def test_folder_problem_refuses_what_cannot_be_created_as_root_too(tmp_path):
    """``os.access`` says yes to root on /proc; creating a folder there fails for everyone."""
    for path in ("/proc/x", "/proc/x/y", "/sys/x"):
        assert folder_problem(path).startswith("cannot create it"), path
        assert not os.path.exists(path)
    blocker = tmp_path / "file"
    blocker.write_text("mine")
    assert folder_problem(blocker) == "exists and is not a folder"
    assert folder_problem(blocker / "sub") == f"cannot create it ({blocker} is not a folder)"
    assert blocker.read_text() == "mine"


def test_folder_problem_creates_nothing_it_leaves(tmp_path):
    assert folder_problem(tmp_path / "a" / "b" / "c") == ""
    assert folder_problem(tmp_path) == ""
    assert list(tmp_path.iterdir()) == []  # the folders and the probe file were removed again


def test_folder_problem_agrees_with_really_writing(tmp_path):
    """A read-only folder: refused unless a file can really be written there (root can)."""
    ro = tmp_path / "ro"
    ro.mkdir()
    os.chmod(ro, 0o555)
    try:
        writable = _really_writable(ro)
        assert (folder_problem(ro) == "") == writable
        assert (folder_problem(ro / "new") == "") == writable
        assert list(ro.iterdir()) == []
    finally:
        os.chmod(ro, 0o755)


def test_verify_refuses_an_uncreatable_report_dir_before_any_row(monkeypatch, capsys):
    """``chaplygin verify --report-dir /proc/x``: one ``error:`` line, exit 2, no row run."""
    from chaplygin_nd.ledger import __main__ as ledger_main

    def no_rows(*args, **kwargs):
        raise AssertionError("a row ran although --report-dir cannot be created")

    monkeypatch.setattr(ledger_main, "run", no_rows)
    assert ledger_main.main(["--report-dir", "/proc/x"]) == 2
    captured = capsys.readouterr()
    err = captured.err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: --report-dir /proc/x: cannot create it"), err
    assert "seed" not in captured.out and not os.path.exists("/proc/x")


@pytest.mark.parametrize("path", ["/proc/x", "/sys/x"])
def test_every_output_option_uses_the_same_check(tmp_path, capsys, path):
    """``simulate --out``, ``bench --out`` and ``first-integrals --json`` refuse the same places."""
    from chaplygin_nd.bench.__main__ import _unusable_out
    from chaplygin_nd.simulate.scene import cli as simulate_cli
    from chaplygin_nd.symbolic.search import command

    assert _unusable_out(Path(path)).startswith("cannot create it")
    assert simulate_cli.main(["steady4d", "--out", path, "--no-plots"]) == 2
    assert command.main(["3", "1", "--a", "1/2", "--b", "1", "--json", str(Path(path).parent / "t.json")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 2 and all(line.startswith("error: ") for line in err), err
    assert not os.path.exists(path)


# --- every atomic writer of the package goes through chaplygin_nd.writing ---
ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ("chaplygin_nd", "ledger", "symbolic", "runtime", "proofs", "simulate", "bench", "docs")


def test_no_atomic_writer_of_its_own():
    """A temporary file moved into place is made in one module; ledger/report.py moves its pair
    (written by writing.write_temporary) with the signals held, the one other os.replace; a
    hand-made '.tmp' name (bench wrote '.horizontal.md.tmp', shared by two concurrent runs) is
    refused too."""
    allowed = {"chaplygin_nd/writing.py": {"os.replace("}, "ledger/report.py": {"os.replace("},
               "simulate/scene/outdir.py": {'".tmp'}}  # it recognises the writer's leftovers
    found = []
    for folder in PACKAGE:
        for path in sorted((ROOT / folder).rglob("*.py")):
            rel = path.relative_to(ROOT).as_posix()
            text = path.read_text(encoding="utf-8")
            for pattern in ("mkstemp(", "os.replace(", "NamedTemporaryFile(", '".tmp', "'.tmp"):
                if pattern in text and pattern not in allowed.get(rel, set()):
                    found.append(f"{rel}: {pattern}")
    assert found == []


def test_the_report_pair_keeps_the_mode_of_the_files_it_replaces(tmp_path):
    from chaplygin_nd.ledger import report

    old, new = tmp_path / "VERIFICATION.md", tmp_path / "verification.json"
    old.write_text("old")
    os.chmod(old, 0o640)
    with umask(0o022):
        report.write_files({old: "new md", new: "{}"})
    assert (mode(old), mode(new)) == (0o640, 0o644)
    assert old.read_text() == "new md" and sorted(p.name for p in tmp_path.iterdir()) == [
        "VERIFICATION.md", "verification.json"]


def test_bench_files_keep_the_mode_of_the_files_they_replace(tmp_path):
    from chaplygin_nd.bench.report import write_atomic as bench_write

    target = tmp_path / "sub" / "rows.json"
    with umask(0o022):
        bench_write(target, "[]")
        assert mode(target) == 0o644
        os.chmod(target, 0o664)
        bench_write(target, b"[1]")
    assert mode(target) == 0o664 and target.read_text() == "[1]"


def test_first_integrals_json_gets_the_mode_of_a_plain_open(tmp_path, capsys):
    from chaplygin_nd.symbolic.search import command

    out = tmp_path / "table.json"
    with umask(0o022):
        assert command.main(["3", "1", "--a", "1/2", "--b", "1", "--json", str(out)]) == 0
    assert mode(out) == 0o644 and isinstance(json.loads(out.read_text()), list)
    assert [p.name for p in tmp_path.iterdir()] == ["table.json"]
