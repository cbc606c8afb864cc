"""The wheel works outside the repository: the paper, CLAIMS.md and the
example scenes ship as package data, a proof and a built-in scene run from another folder.

To stay cheap the wheel is installed with ``--no-deps --target DIR`` and run by this
interpreter in isolated mode (``-I``: no PYTHONPATH, no current folder on ``sys.path``) with DIR
first on ``sys.path``; the dependencies come from the test environment. The test checks that
every project module is loaded from DIR, not from the (editable) checkout.
"""

from __future__ import annotations

import subprocess
import sys
import zipfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def _module(target: Path, cwd: Path, module: str, *args: str) -> subprocess.CompletedProcess:
    """``python -m module args`` with only the wheel's copy of the project importable."""
    code = (f"import sys, runpy; sys.path.insert(0, {str(target)!r}); "
            f"sys.argv = [{module!r}, *{list(args)!r}]; "
            "import atexit, importlib\n"
            "def where():\n"
            "    for p, m in list(sys.modules.items()):\n"
            "        if p.startswith('chaplygin_nd') and getattr(m, '__file__', None):\n"
            "            print('LOADED', p, m.__file__, file=sys.stderr)\n"
            "atexit.register(where)\n"
            f"runpy.run_module({module!r}, run_name='__main__', alter_sys=True)")
    return subprocess.run([sys.executable, "-I", "-c", code], capture_output=True, text=True,
                          cwd=cwd, timeout=300)


def _loaded_from(stderr: str, target: Path) -> dict[str, str]:
    found = dict(line.split()[1:3] for line in stderr.splitlines() if line.startswith("LOADED "))
    assert found and all(Path(f).is_relative_to(target) for f in found.values()), found
    return found


def test_wheel_contents(installed):
    wheel, _, _ = installed
    names = zipfile.ZipFile(wheel).namelist()
    assert "chaplygin_nd/paper/CLAIMS.md" in names
    assert "chaplygin_nd/paper/chaplygin-sphere-nd.tex" in names
    assert "chaplygin_nd/scenes/generic4d.toml" in names
    assert "chaplygin_nd/py.typed" in names
    tops = {n.split("/")[0] for n in names}
    dist_info = {t for t in tops if t.startswith("chaplygin_nd-") and t.endswith(".dist-info")}
    assert len(dist_info) == 1 and tops == {"chaplygin_nd"} | dist_info, tops  # nothing else


def test_the_build_warns_of_nothing_and_the_tree_has_no_link(installed):
    """The package data are real folders mapped as packages: setuptools has no
    "Package would be ignored" (nor any other of its warnings) to say about the layout."""
    _, _, base = installed
    log = (base / "build.log").read_text()
    assert "would be ignored" not in log and "SetuptoolsDeprecationWarning" not in log \
        and "SetuptoolsWarning" not in log, log[-3000:]
    links = [str(p.relative_to(ROOT)) for folder in ("paper", "scenes", "proofs", "simulate",
                                                      "symbolic", "ledger", "runtime", "generated",
                                                      "bench", "chaplygin_nd", "docs", "tests")
             for p in (ROOT / folder).rglob("*") if p.is_symlink()]
    assert links == []


def test_a_proof_and_the_list_run_from_the_wheel(installed):
    _, target, base = installed
    elsewhere = base / "elsewhere"
    elsewhere.mkdir(exist_ok=True)
    r = _module(target, elsewhere, "chaplygin_nd", "prove", "eq:invL3D")
    assert r.returncode == 0, r.stderr
    assert "eq:invL3D" in r.stdout and "holds" in r.stdout
    _loaded_from(r.stderr, target)
    r = _module(target, elsewhere, "chaplygin_nd", "prove", "--list")
    assert r.returncode == 0, r.stderr
    assert "eq:invL3D" in r.stdout and "P:inversion" in r.stdout
    assert sorted(p.name for p in elsewhere.iterdir()) == []


def test_a_built_in_scene_runs_from_the_wheel(installed):
    _, target, base = installed
    elsewhere = base / "scene-run"
    elsewhere.mkdir(exist_ok=True)
    r = _module(target, elsewhere, "chaplygin_nd", "simulate", "steady4d", "--out", "res", "--no-plots")
    assert r.returncode == 0, r.stderr
    assert "model: constant-Omega" in r.stdout
    assert (elsewhere / "res" / "outputs.npz").is_file()
    found = _loaded_from(r.stderr, target)
    assert {"chaplygin_nd.simulate", "chaplygin_nd.generated"} <= set(found)


def test_version_from_the_wheel(installed):
    _, target, base = installed
    r = _module(target, base, "chaplygin_nd", "--version")
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("chaplygin-nd ") and "commit" not in r.stdout  # not a checkout
