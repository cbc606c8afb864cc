"""``--out`` writes only files it owns: every refusal is one line, exit 2,
before any computation, and leaves everything as it was."""

from __future__ import annotations

import json
import os
import stat
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest
from chaplygin_nd.simulate.scene import cli
from chaplygin_nd.simulate.scene.outdir import MANIFEST, OutputError, claim

ROOT = Path(__file__).resolve().parent.parent
SCENE = """title = "small"
n = 4
a = 0.5
b = 1.0
[initial]
family = "steady-rotation"
seed = 3
[times]
t_end = 1.0
samples = 5
[outputs]
want = ["M", "gamma"]
"""


@pytest.fixture
def scene(tmp_path):
    path = tmp_path / "small.toml"
    path.write_text(SCENE)
    return path


def _snapshot(folder: Path) -> dict[str, tuple[bytes | None, int]]:
    return {str(p.relative_to(folder)): (p.read_bytes() if p.is_file() else None,
                                         stat.S_IMODE(p.lstat().st_mode))
            for p in sorted(folder.rglob("*"))}


def _refused(capsys, scene, out, *words):
    """The run is refused with exit 2 and one line on stderr naming the reason."""
    capsys.readouterr()
    assert cli.main([str(scene), "--out", str(out), "--no-plots"]) == 2
    captured = capsys.readouterr()
    assert captured.out == ""  # refused before planning: the plan line is not even printed
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: --out"), captured.err
    for w in words:
        assert w in lines[0]


def test_a_folder_with_a_users_file_survives(tmp_path, scene, capsys):
    thesis = tmp_path / "Documents" / "thesis"
    thesis.mkdir(parents=True)
    (thesis / "ch1.tex").write_text("\\chapter{One}\n")
    before = _snapshot(tmp_path / "Documents")
    _refused(capsys, scene, thesis, "did not write", "ch1.tex")
    assert _snapshot(tmp_path / "Documents") == before


def test_existing_file_and_device_are_refused(tmp_path, scene, capsys):
    f = tmp_path / "notes.txt"
    f.write_text("mine")
    _refused(capsys, scene, f, "is a file")
    assert f.read_text() == "mine"
    _refused(capsys, scene, "/dev/null", "not a folder")
    assert Path("/dev/null").is_char_device()


def test_dot_with_foreign_files_is_refused(tmp_path, scene, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)  # holds small.toml, which this program did not write
    before = _snapshot(tmp_path)
    _refused(capsys, scene, ".", "did not write", "small.toml")
    assert _snapshot(tmp_path) == before


def test_path_under_an_existing_file_is_refused(tmp_path, scene, capsys):
    f = tmp_path / "report.pdf"
    f.write_bytes(b"%PDF")
    _refused(capsys, scene, f / "sub" / "out", "is a file, not a folder")
    assert f.read_bytes() == b"%PDF"


def _really_read_only_folder(tmp_path: Path) -> Path | None:
    """A folder no file can be created in: chmod 0555 for a normal user; for root (which
    ignores permission bits) an empty folder of a read-only file system such as sysfs."""
    if os.geteuid() != 0:
        ro = tmp_path / "ro"
        ro.mkdir()
        ro.chmod(0o555)
        return ro
    for cand in ("/sys/kernel/software_nodes", "/sys/kernel/iommu_groups", "/sys/firmware"):
        p = Path(cand)
        if p.is_dir() and not any(p.iterdir()):
            try:
                fd, name = tempfile.mkstemp(dir=p)
            except OSError:
                return p
            os.close(fd)
            os.unlink(name)
    return None


def test_read_only_folder_and_parent_are_refused(tmp_path, scene, capsys):
    ro = _really_read_only_folder(tmp_path)
    if ro is None:
        pytest.skip("running as root with no read-only empty folder on this machine "
                    "(root bypasses chmod; sysfs is not mounted)")
    _refused(capsys, scene, ro, "not writable")
    _refused(capsys, scene, ro / "child" / "out", "not writable")
    assert not (ro / "child").exists()


def test_chmod_read_only_is_judged_by_a_real_write(tmp_path, scene, capsys):
    """A 0555 folder refuses a normal user; root can write into it, so the run is allowed —
    the decision comes from an actual probe, not from the permission bits alone."""
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    try:
        code = cli.main([str(scene), "--out", str(ro), "--no-plots"])
        capsys.readouterr()
        assert code == (0 if os.geteuid() == 0 else 2)
    finally:
        ro.chmod(0o755)


def test_rerun_replaces_only_its_own_files(tmp_path, scene, capsys):
    out = tmp_path / "result"
    assert cli.main([str(scene), "--out", str(out), "--no-plots"]) == 0
    manifest = json.loads((out / MANIFEST).read_text())
    assert set(manifest["files"]) == {p.name for p in out.iterdir()} - {MANIFEST}
    first = (out / "M.csv").read_bytes()
    # the second run asks for fewer outputs: M.csv (owned, not produced again) is removed
    scene.write_text(SCENE.replace('want = ["M", "gamma"]', 'want = ["gamma"]'))
    assert cli.main([str(scene), "--out", str(out), "--no-plots"]) == 0
    assert first and not (out / "M.csv").exists() and (out / "gamma.csv").exists()
    # a user's file added to the folder makes it foreign again
    (out / "mine.txt").write_text("keep")
    _refused(capsys, scene, out, "mine.txt")
    assert (out / "mine.txt").read_text() == "keep"


def test_a_second_scene_does_not_wipe_the_first(tmp_path, scene, capsys):
    out = tmp_path / "out"
    assert cli.main([str(scene), "--out", str(out), "--no-plots"]) == 0
    other = tmp_path / "other.toml"
    other.write_text(SCENE)
    before = _snapshot(out)
    _refused(capsys, other, out, "another scene", "small")
    assert _snapshot(out) == before


def test_default_folder_is_out_slash_scene_name(tmp_path, scene, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert cli.main([str(scene), "--no-plots"]) == 0
    assert (tmp_path / "out" / "small" / "summary.txt").is_file()


def test_folders_and_files_get_normal_permissions(tmp_path, scene, capsys):
    out = tmp_path / "a" / "b"
    old = os.umask(0o022)
    try:
        assert cli.main([str(scene), "--out", str(out), "--no-plots"]) == 0
    finally:
        os.umask(old)
    for folder in (tmp_path / "a", out):
        assert stat.S_IMODE(folder.stat().st_mode) == 0o755
    for f in out.iterdir():
        assert stat.S_IMODE(f.stat().st_mode) == 0o644, f


def test_empty_folder_and_symlink(tmp_path):
    empty = tmp_path / "empty"
    empty.mkdir()
    assert claim(empty, "s").owned == set()
    link = tmp_path / "link"
    link.symlink_to(empty)
    with pytest.raises(OutputError, match="symbolic link"):
        claim(link, "s")


def test_refusal_costs_no_computation():
    """A refused --out returns at once although the scene would run for minutes."""
    code = ("import sys, time; from chaplygin_nd.simulate.scene import cli; "
            "t = time.perf_counter(); "
            "c = cli.main(['long4d', '--out', '/dev/null']); "
            "sys.exit(c if time.perf_counter() - t < 5 else 99)")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT,
                       timeout=60)
    assert r.returncode == 2, r.stderr
    assert "Traceback" not in r.stderr and r.stderr.count("\n") == 1


def test_a_killed_runs_temporary_files_are_its_own(tmp_path, scene, capsys):
    """A run killed between writing a temporary file and moving it leaves '.M.csv.XXXX.tmp.csv';
    the next run recognises it (its name is in the manifest) and cleans it up."""
    out = tmp_path / "result"
    assert cli.main([str(scene), "--out", str(out), "--no-plots"]) == 0
    (out / ".M.csv.abc123.tmp.csv").write_text("partial")
    assert cli.main([str(scene), "--out", str(out), "--no-plots"]) == 0
    assert not [p for p in out.iterdir() if ".tmp" in p.name]
    (out / ".thesis.tex.abc.tmp.tex").write_text("not ours")  # not a name in the manifest
    _refused(capsys, scene, out, "thesis")


def test_the_lock_lives_beside_the_folder_and_goes_with_the_run(tmp_path):
    """The lock is a hidden sibling while a run holds it (a second claim is refused), and it is
    removed when the run ends; missing parents made for it are removed again if left empty."""
    from chaplygin_nd.simulate.scene.outdir import lock_file

    out = tmp_path / "deep" / "er" / "result"
    first = claim(out, "s")
    lock = lock_file(out)
    assert lock.parent == tmp_path / "deep" / "er" and lock.read_text().split()[0] == str(os.getpid())
    with pytest.raises(OutputError, match="another run is writing"):
        claim(out, "s")
    first.release()
    assert sorted(tmp_path.iterdir()) == []  # no lock, no empty parents
    again = claim(out, "s")  # free again
    again.write({"a.txt": lambda p: p.write_text("x")})
    assert sorted(p.name for p in out.parent.iterdir()) == ["result"]


def test_a_run_refused_after_the_claim_leaves_no_lock(tmp_path, capsys):
    """A run refused after --out was claimed (at T = 1e12 the closed form's bound misses the
    target and an integrator would take years): exit 2, and nothing is left."""
    scene = tmp_path / "s.toml"
    scene.write_text(SCENE.replace("t_end = 1.0", "t_end = 1e12"))
    out = tmp_path / "o"
    assert cli.main([str(scene), "--out", str(out), "--no-plots"]) == 2
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.toml"], capsys.readouterr().err


def test_a_file_at_the_lock_path_that_is_not_a_lock_is_left_alone(tmp_path):
    """The lock's name is ours, but a file already there that the program did not write (or a
    symbolic link) is neither truncated nor removed: the claim is refused in one line."""
    from chaplygin_nd.simulate.scene.outdir import lock_file

    out = tmp_path / "result"
    lock = lock_file(out)
    lock.write_text("my notes\n")
    with pytest.raises(OutputError, match="is not a lock file"):
        claim(out, "s")
    assert lock.read_text() == "my notes\n" and not out.exists()
    lock.unlink()
    target = tmp_path / "elsewhere.txt"
    target.write_text("keep\n")
    lock.symlink_to(target)
    with pytest.raises(OutputError, match="cannot open the lock file"):
        claim(out, "s")
    assert target.read_text() == "keep\n" and lock.is_symlink()
    lock.unlink()
    stale = claim(out, "s")  # an empty file (a run killed before writing) or a stale lock is ours
    stale.release()
    lock.write_text("12345 /some/where\n")
    claim(out, "s").release()
    assert not lock.exists()
