"""Nothing is written under the installation: from an installed wheel, a proof,
a built-in scene (``--out`` elsewhere) and an evidence row (in its own test, marked ``slow``: it
integrates its orbits) run with ``CHAPLYGIN_ND_CACHE`` pointed at a temporary folder, and the
installed tree is byte-for-byte what pip wrote (every file's bytes and mtime, every folder's
mtime, no file added or removed). The evidence row's orbits land in the cache folder instead.
The wheel also carries LICENSE and NOTICE in its metadata.

The wheel is built and installed once per pytest process (tests/conftest.py: ``installed``, with
``pip install --no-deps --target DIR``), run by this interpreter in isolated mode with DIR first
on ``sys.path``.
"""

from __future__ import annotations

import hashlib
import os
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest


def _snapshot(root: Path) -> dict[str, tuple]:
    """path -> (kind, mtime_ns, size, sha256) for every file and folder under ``root``."""
    out = {}
    for dirpath, _dirnames, filenames in os.walk(root):
        d = Path(dirpath)
        out[str(d.relative_to(root))] = ("dir", d.stat().st_mtime_ns, 0, "")
        for name in filenames:
            f = d / name
            st = f.stat()
            out[str(f.relative_to(root))] = ("file", st.st_mtime_ns, st.st_size,
                                             hashlib.sha256(f.read_bytes()).hexdigest())
    return out


def _run(target: Path, cwd: Path, cache: Path, *args: str) -> subprocess.CompletedProcess:
    """``python -m chaplygin_nd args`` with only the wheel's copy of the project importable and
    the cache moved to ``cache``."""
    code = (f"import sys, runpy; sys.path.insert(0, {str(target)!r}); "
            f"sys.argv = ['chaplygin', *{list(args)!r}]; "
            "runpy.run_module('chaplygin_nd', run_name='__main__', alter_sys=True)")
    env = {**os.environ, "CHAPLYGIN_ND_CACHE": str(cache)}
    return subprocess.run([sys.executable, "-I", "-c", code], capture_output=True, text=True,
                          cwd=cwd, env=env, timeout=900)


def test_licence_files_ship_in_the_metadata(installed):  # noqa: F811
    wheel, target, _ = installed
    names = zipfile.ZipFile(wheel).namelist()
    dist_info = next(n.split("/")[0] for n in names if ".dist-info/" in n)
    assert {f"{dist_info}/licenses/LICENSE", f"{dist_info}/licenses/NOTICE"} <= set(names)
    notice = (target / dist_info / "licenses" / "NOTICE").read_text(encoding="utf-8")
    assert "not covered" in notice.lower() and "García-Naranjo" in notice


def _runs_write_nothing_under(target: Path, work: Path, cache: Path, runs) -> list[str]:
    """Each run succeeds and the installed tree is byte-for-byte what it was before them; the
    runs' standard outputs."""
    work.mkdir(exist_ok=True)
    before = _snapshot(target)
    outs = []
    for args in runs:
        r = _run(target, work, cache, *args)
        assert r.returncode == 0, (args, r.stderr[-2000:])
        outs.append(r.stdout)
    after = _snapshot(target)
    changed = sorted(k for k in before.keys() | after.keys() if before.get(k) != after.get(k))
    assert changed == [], changed
    return outs


def test_a_proof_and_a_scene_write_nothing_under_the_installation(installed):
    _, target, base = installed
    work, cache = base / "user-folder", base / "user-cache"
    outs = _runs_write_nothing_under(target, work, cache, [
        ("prove", "P:inversion"),
        ("simulate", "steady4d", "--out", str(work / "steady"), "--no-plots"),
        ("prove", "--list")])
    assert "P:inversion" in outs[-1]
    assert (work / "steady" / "outputs.npz").is_file()


@pytest.mark.slow
def test_an_evidence_row_writes_nothing_under_the_installation(installed):
    """The evidence row integrates its orbits (~30 s of CPU from an empty cache): `make test-slow`."""
    _, target, base = installed
    work, cache = base / "user-folder-evidence", base / "user-cache-evidence"
    _runs_write_nothing_under(target, work, cache, [("prove", "S5:EJ-tori")])
    assert any((cache / "evidence").iterdir())  # the evidence row cached its orbits here
