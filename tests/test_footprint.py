"""Nothing outside the output folder and the project's cache: a scene (heyoka when installed,
so that its own object-code cache is written; figures drawn, so matplotlib's font cache is), a refused scene and a ledger row (``chaplygin prove``; a whole ``verify`` is
minutes, and it writes only its reports beside these) run with ``HOME``, ``TMPDIR`` and the
working folder new and empty; every file created outside ``--out`` and ``$CHAPLYGIN_ND_CACHE`` is
listed, and the list is empty. Also the smaller rules of a tidy checkout and short errors."""

from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

SCENE = """n = 3
a = 0.5
b = 1.0
[initial]
family = "generic"
seed = 1
[times]
t_end = 2.0
samples = 21
[outputs]
want = ["M", "x", "integrals"]
"""


def _snapshot(*roots: Path) -> set[Path]:
    return {p for r in roots for p in r.rglob("*")}


def test_runs_leave_nothing_outside_the_output_folder_and_the_cache(tmp_path):
    home, tmp, work, cache = (tmp_path / x for x in ("home", "tmp", "work", "cache"))
    for folder in (home, tmp, work):
        folder.mkdir()
    heyoka = importlib.util.find_spec("heyoka") is not None
    (work / "s.toml").write_text(SCENE + ('[accuracy]\nmethod = "heyoka"\n' if heyoka else ""))
    (work / "bad.toml").write_text(SCENE.replace("a = 0.5", "a = -3"))
    env = {k: v for k, v in os.environ.items()
           if k not in ("XDG_CACHE_HOME", "MPLCONFIGDIR", "PYTHONPYCACHEPREFIX")}
    env.update(HOME=str(home), TMPDIR=str(tmp), CHAPLYGIN_ND_CACHE=str(cache))
    before = _snapshot(home, tmp, work)
    runs = [(["simulate", "s.toml", "--out", "out"], 0),
            (["simulate", "bad.toml", "--out", "refused"], 2),
            (["prove", "eq:axisymm"], 0)]
    for argv, status in runs:
        r = subprocess.run([sys.executable, "-B", "-m", "chaplygin_nd", *argv], cwd=work, env=env,
                           capture_output=True, text=True, timeout=600)
        assert r.returncode == status, (argv, r.stderr)
    assert (work / "out" / "x.png").is_file() and not (work / "refused").exists()
    created = sorted(str(p.relative_to(tmp_path)) for p in _snapshot(home, tmp, work) - before
                     if not (p == work / "out" or work / "out" in p.parents))
    assert created == [], created
    assert (cache / "matplotlib").is_dir()  # what the runs kept, they kept there
    if heyoka:  # its own object-code cache too (heyoka >= 7.10 has one)
        assert (cache / "heyoka").is_dir() and any((cache / "heyoka-llvm").iterdir())


def test_no_tracked_file_is_ignored():
    """A file is either a tracked record or ignored, never both (mutation-derivations.json was)."""
    r = subprocess.run(["git", "-C", str(ROOT), "ls-files", "-ci", "--exclude-standard"],
                       capture_output=True, text=True)
    if r.returncode != 0:  # not a git checkout (an installed copy of the tests)
        return
    assert r.stdout.split() == []


def test_an_error_naming_thousands_of_unknown_ids_is_short(capsys):
    from chaplygin_nd import cli

    ids = [f"no-such-row-{i}" for i in range(5000)] + ["P:inversoin", "x" * 10_000]
    assert cli.main(["prove", *ids]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and len(err[0]) < 400, (len(err), len(err[0]))
    assert "and 4997 more (5002 in all)" in err[0], err[0]
