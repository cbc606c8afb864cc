"""The evidence cache (simulate/analysis/result_cache.py, simulate/analysis/evidence.py, simulate/analysis/frequencies.py):
a cached orbit is keyed by the code that computed it, and the cache is an
optimisation, never a failure and never a way in.

The first test copies the project's packages into a temporary folder (laid out as the installed
package ``chaplygin_nd``, following pyproject's ``package-dir``), runs a short evidence
computation there in isolated subprocesses (``python -I``, the copy first on ``sys.path``),
flips the sign of the commutator of the field in the copy's ``simulate/dynamics/so.py`` and shows the hit
becomes a miss and the orbit changes.
"""

from __future__ import annotations

import errno
import json
import os
import shutil
import subprocess
import sys
import tomllib
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from chaplygin_nd.simulate.analysis import frequencies as fq
from chaplygin_nd.simulate.analysis import result_cache as rc
from chaplygin_nd.simulate.analysis.evidence import orbits

from chaplygin_nd import writing

ROOT = Path(__file__).resolve().parent.parent

_RUN = """
import json, sys
sys.path.insert(0, {pkg!r})
from dataclasses import replace
from chaplygin_nd.simulate.analysis import evidence, naff
from chaplygin_nd.simulate.analysis import frequencies as fq
calls = [0]
analyse = naff.analyse
def counted(*a, **k):
    calls[0] += 1
    return analyse(*a, **k)
naff.analyse = counted
exp = replace(fq.full_experiment(t_end=24.0, dt=0.5, rtol=1e-9), members=(1,))
orb = evidence.orbits(exp)
specs = fq.spectra(exp)
files = {{m.__file__ for n, m in sys.modules.items()
         if n.startswith("chaplygin_nd") and getattr(m, "__file__", None)}}
assert all(f.startswith({pkg!r}) for f in files), files
print(json.dumps({{"cached": orb.cached, "y": orb.y[-1].tolist(), "analysed": calls[0],
                  "lines": [s.lines for s in specs]}}))
"""


def _copy_package(dest: Path) -> Path:
    """The project's packages under ``dest/chaplygin_nd`` as pyproject maps them."""
    mapping = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["package-dir"]
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc")
    for package, folder in sorted(mapping.items()):
        shutil.copytree(ROOT / folder, dest.joinpath(*package.split(".")), ignore=ignore,
                        dirs_exist_ok=True)
    return dest


def _run(pkg: Path, cache: Path) -> dict:
    env = {k: v for k, v in os.environ.items() if not k.startswith("PYTHON")}
    env[rc.project_cache.ENV] = str(cache)
    # -B: no .pyc is written. The edit below keeps so.py's size, and Python trusts a .pyc whose
    # source has the same size and mtime second; on a fast machine the restored original ran the
    # edited bytecode (the CI run of 2026-11-24 saw it), while the cache key hashes the source.
    r = subprocess.run([sys.executable, "-I", "-B", "-c", _RUN.format(pkg=str(pkg))], env=env,
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout.strip().splitlines()[-1])


def test_editing_the_field_in_a_copy_of_the_project_invalidates_the_cache(tmp_path):
    pkg = _copy_package(tmp_path / "site")
    cache = tmp_path / "cache"
    cold = _run(pkg, cache)
    warm = _run(pkg, cache)
    assert not cold["cached"] and cold["analysed"] == 1
    assert warm["cached"] and warm["analysed"] == 0          # orbits and spectra from the cache
    assert warm["y"] == cold["y"] and warm["lines"] == cold["lines"]
    so = pkg / "chaplygin_nd" / "simulate" / "dynamics" / "so.py"
    text = so.read_text()
    assert text.count("return A @ B - B @ A") == 1
    so.write_text(text.replace("return A @ B - B @ A", "return B @ A - A @ B"))  # another system
    edited = _run(pkg, cache)
    assert not edited["cached"] and edited["analysed"] == 1  # both recomputed
    change = np.max(np.abs(np.array(edited["y"]) - np.array(cold["y"])))
    assert change > 1e-3, change
    again = _run(pkg, cache)
    assert again["cached"] and again["y"] == edited["y"]
    so.write_text(text)                                       # the original code again: a miss
    restored = _run(pkg, cache)
    assert not restored["cached"] and restored["y"] == cold["y"]


def test_manifest_names_the_field_and_rejects_changed_or_missing_modules():
    manifest = rc.code_manifest()
    assert "chaplygin_nd.simulate.dynamics.so" in manifest
    assert rc.code_unchanged(manifest)
    assert not rc.code_unchanged({**manifest, "chaplygin_nd.simulate.dynamics.so": "0" * 64})
    assert not rc.code_unchanged({**manifest, "chaplygin_nd.simulate.no_such_module": "0" * 64})
    assert not rc.code_unchanged({"os": manifest["chaplygin_nd.simulate.dynamics.so"]})  # not the project
    assert not rc.code_unchanged({}) and not rc.code_unchanged(["x"])


# -- a cache is an optimisation, never a failure, never a way in ------------------------------

def _small():
    return replace(fq.reduced_experiment(t_end=32.0, rtol=1e-9), members=(3,), level_shifts=())


@pytest.fixture
def cache(tmp_path, monkeypatch):
    folder = tmp_path / "cache"
    monkeypatch.setenv(rc.project_cache.ENV, str(folder))
    return folder


def _entries(cache: Path, pattern: str) -> list[Path]:
    return sorted((cache / "evidence").glob(pattern))


def test_a_truncated_orbit_entry_warns_once_and_is_recomputed(cache):
    exp = _small()
    first = orbits(exp)
    (path,) = _entries(cache, "*.npz")
    path.write_bytes(path.read_bytes()[:200])
    with pytest.warns(rc.ResultCacheWarning, match=r"corrupt.*CHAPLYGIN_ND_CACHE") as record:
        second = orbits(exp)
    assert len(record) == 1 and str(path) in str(record[0].message)
    assert not second.cached and np.array_equal(second.y, first.y)
    third = orbits(exp)                                       # overwritten: a clean hit now
    assert third.cached and np.array_equal(third.y, first.y)


def test_a_wrong_shaped_orbit_entry_is_recomputed(cache):
    exp = _small()
    first = orbits(exp)
    (path,) = _entries(cache, "*.npz")
    with np.load(path) as d:
        parts = dict(d)
    parts["y"] = parts["y"][:, :, :3]
    np.savez(path, **parts)
    with pytest.warns(rc.ResultCacheWarning, match="wrong shape"):
        again = orbits(exp)
    assert not again.cached and np.array_equal(again.y, first.y)


class _Payload:
    """Unpickling this creates a file: the proof that something was unpickled."""

    def __init__(self, marker: str):
        self.marker = marker

    def __reduce__(self):
        return (Path.touch, (Path(self.marker),))


def test_a_pickle_in_an_orbit_entry_is_never_loaded(cache, tmp_path):
    exp = _small()
    orbits(exp)
    (path,) = _entries(cache, "*.npz")
    marker = tmp_path / "unpickled"
    with np.load(path) as d:
        parts = dict(d)
    parts["y"] = np.array([_Payload(str(marker))], dtype=object)
    np.savez(path, **parts)                                   # an object array: a pickle
    with pytest.warns(rc.ResultCacheWarning, match="corrupt"):
        again = orbits(exp)
    assert not marker.exists() and not again.cached


def test_a_garbled_spectra_entry_warns_and_is_recomputed(cache):
    exp = _small()
    first = fq.spectra(exp)
    (path,) = _entries(cache, "*-spectra-*.json")
    for garbage in ('{"manifest": {}, "spectra": [{"lines": 3}]', '[1, 2]', '{"spectra": [{}]}'):
        rc._WARNED.clear()
        path.write_text(garbage)
        with pytest.warns(rc.ResultCacheWarning, match=r"corrupt.*CHAPLYGIN_ND_CACHE"):
            again = fq.spectra(exp)
        assert [s.to_dict() for s in again] == [s.to_dict() for s in first]
        assert json.loads(path.read_text())["spectra"]          # rewritten, valid


def test_a_cache_variable_naming_a_file_runs_uncached(tmp_path, monkeypatch):
    target = tmp_path / "a-file"
    target.write_text("mine")
    monkeypatch.setenv(rc.project_cache.ENV, str(target))
    with pytest.warns(rc.ResultCacheWarning, match="not a folder.*uncached"):
        orb = orbits(_small())
    assert not orb.cached and target.read_text() == "mine"


def test_a_read_only_cache_runs_uncached(cache, monkeypatch):
    exp = _small()
    cache.mkdir(mode=0o700)

    def read_only(*args, **kwargs):
        raise OSError(errno.EROFS, "Read-only file system")

    # every write of an entry fails (they all go through the project's one atomic writer)
    monkeypatch.setattr(writing, "write_temporary", read_only)
    with pytest.warns(rc.ResultCacheWarning, match="Read-only file system.*uncached"):
        orb = orbits(exp)
        specs = fq.spectra(exp)
    assert not orb.cached and specs and not _entries(cache, "*.npz")


@pytest.mark.skipif(hasattr(os, "geteuid") and os.geteuid() == 0,
                    reason="root writes into a folder of mode 0500; the EROFS test covers it")
def test_a_folder_without_write_permission_runs_uncached(cache):
    cache.mkdir(mode=0o500)
    try:
        with pytest.warns(rc.ResultCacheWarning, match="uncached"):
            orb = orbits(_small())
        assert not orb.cached and list(cache.iterdir()) == []
    finally:
        cache.chmod(0o700)


def test_a_group_writable_folder_is_refused(cache):
    cache.mkdir()
    cache.chmod(0o770)
    with pytest.warns(rc.ResultCacheWarning, match=r"writable by group or others.*refused"):
        orb = orbits(_small())
    assert not orb.cached and list(cache.iterdir()) == []     # nothing read, nothing written


def test_a_folder_of_another_user_is_refused(cache, monkeypatch):
    cache.mkdir(mode=0o700)
    uid = os.getuid()
    monkeypatch.setattr(rc.os, "getuid", lambda: uid + 1)
    with pytest.warns(rc.ResultCacheWarning, match="owned by another user"):
        orb = orbits(_small())
    assert not orb.cached and list(cache.iterdir()) == []


def test_the_folders_created_are_private(cache):
    orbits(_small())
    assert (cache.stat().st_mode & 0o077) == 0
    assert ((cache / "evidence").stat().st_mode & 0o077) == 0


# -- the drawn ensembles: the same mechanism ----------------------------------------

_DRAWN = """
import json, sys
sys.path.insert(0, {pkg!r})
from dataclasses import replace
from chaplygin_nd.simulate.analysis import draws, drawn_evidence as de, evidence_rows as er
calls = [0]
inner = de._measure
def counted(*a, **k):
    calls[0] += 1
    return inner(*a, **k)
de._measure = counted
s = replace(er.SETTINGS["full4"], name="cache-test", T=16.0)
ens = draws.draw("cache-test", "generic", 4, 2, 5)
res = de.measure(s, ens, er._full_state(ens), 5)
mods = sorted(n for n, m in sys.modules.items()
              if n.startswith("chaplygin_nd.") and getattr(m, "__file__", "") and m.__file__.endswith(".py"))
assert all(sys.modules[n].__file__.startswith({pkg!r}) for n in mods)
print(json.dumps({{"computed": calls[0], "megno": [r.megno for r in res], "modules": mods}}))
"""


def _drawn(pkg: Path, cache: Path) -> dict:
    env = {k: v for k, v in os.environ.items() if not k.startswith("PYTHON")}
    env[rc.project_cache.ENV] = str(cache)
    r = subprocess.run([sys.executable, "-I", "-B", "-c", _DRAWN.format(pkg=str(pkg))], env=env,
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout.strip().splitlines()[-1])


#: six measurements in fresh processes (~8 CPU-s): slow by nature, in make test-slow; the field's
#: own edit is also test_editing_the_field_in_a_copy_of_the_project_invalidates_the_cache (make test)
@pytest.mark.slow
def test_editing_any_module_the_drawn_measurement_loads_is_a_miss(tmp_path):
    """No hand-kept file list: the drawn ensembles' cache is keyed by the manifest of every
    project module loaded. Warm the cache in a copy of the project, then edit (one at a time, each
    against its own copy of the warm cache) the field's module, the thresholds' module and a
    seeded sample of the other modules the measurement loaded: every edit turns the hit into a
    miss."""
    import random

    pkg = _copy_package(tmp_path / "site")
    warm = tmp_path / "warm"
    cold = _drawn(pkg, warm)
    again = _drawn(pkg, warm)
    assert cold["computed"] == 1 and again["computed"] == 0 and again["megno"] == cold["megno"]
    loaded = cold["modules"]
    named = ["chaplygin_nd.simulate.dynamics.so", "chaplygin_nd.simulate.analysis.frequencies"]
    assert set(named) <= set(loaded)
    others = sorted(set(loaded) - set(named))
    sample = named + random.Random(24).sample(others, 3)
    mapping = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["package-dir"]
    for module in sample:
        parts = module.split(".")
        path = pkg.joinpath(*parts[:-1], parts[-1] + ".py")
        if not path.exists():                                  # a package: its __init__
            path = pkg.joinpath(*parts, "__init__.py")
        assert path.exists(), (module, mapping)
        text = path.read_text()
        cache = tmp_path / f"cache-{module}"
        shutil.copytree(warm, cache)
        path.write_text(text + "\n# edited by tests/test_evidence_cache.py\n")
        try:
            edited = _drawn(pkg, cache)
        finally:
            path.write_text(text)
        assert edited["computed"] == 1, f"an edit of {module} was answered from the cache"


def _tiny():
    from chaplygin_nd.simulate.analysis import draws
    from chaplygin_nd.simulate.analysis import evidence_rows as er

    s = replace(er.SETTINGS["full4"], name="damage-test", T=16.0)
    ens = draws.draw("damage-test", "generic", 4, 2, 5)
    return s, ens, er._full_state(ens)


@pytest.mark.parametrize("damage", ["truncated", "random bytes", "a folder", "valid JSON, wrong shape"])
def test_a_damaged_drawn_entry_is_one_warning_and_is_replaced(cache, monkeypatch, damage):
    from chaplygin_nd.simulate.analysis import drawn_evidence as de

    s, ens, y0 = _tiny()
    first = de.measure(s, ens, y0, 5)
    (path,) = _entries(cache, "drawn-damage-test-*.json")
    if damage == "truncated":
        path.write_bytes(path.read_bytes()[:100])
    elif damage == "random bytes":
        path.write_bytes(np.random.default_rng(1).bytes(300))
    elif damage == "a folder":
        path.unlink()
        path.mkdir()
        (path / "inside").write_text("x")
    else:
        path.write_text(json.dumps({"manifest": rc.code_manifest(), "value": [{"a": 1}]}))
    rc._WARNED.clear()
    calls = []
    inner = de._measure
    monkeypatch.setattr(de, "_measure", lambda *a, **k: calls.append(1) or inner(*a, **k))
    with pytest.warns(rc.ResultCacheWarning, match=r"corrupt.*recomputing.*CHAPLYGIN_ND_CACHE") as rec:
        again = de.measure(s, ens, y0, 5)
    assert len(rec) == 1 and "\n" not in str(rec[0].message) and calls == [1]
    assert [r.to_dict() for r in again] == [r.to_dict() for r in first]
    assert path.is_file() and json.loads(path.read_text())["value"]   # replaced, valid
    third = de.measure(s, ens, y0, 5)                                 # a clean hit now
    assert calls == [1] and [r.to_dict() for r in third] == [r.to_dict() for r in first]



def test_a_lock_taken_without_waiting_is_refused_while_another_holds_it(cache):
    # flock locks belong to an open file: a lock held through another open() of the lock file
    # is, for this call, exactly what another process holding it is
    path = rc.private_folder("evidence") / "entry.json"
    with rc.locked(path) as held:
        assert held
        with rc.locked(path, wait=False) as second:
            assert second is False
    with rc.locked(path, wait=False) as again:
        assert again is True


def test_a_shared_ensemble_is_computed_by_the_first_row_only(cache, monkeypatch):
    from chaplygin_nd.simulate.analysis import evidence_rows as er

    calls = []
    monkeypatch.setitem(er.SHARED, "control4", lambda seed: calls.append(seed))
    lock = rc.private_folder("evidence") / "shared-control4-7"
    with rc.locked(lock):                      # another row is computing it: do not wait
        assert er.start_shared("control4", 7) is False
    assert calls == []
    assert er.start_shared("control4", 7) is True and calls == [7]


def test_a_shared_ensemble_is_not_started_without_a_usable_cache(tmp_path, monkeypatch):
    from chaplygin_nd.simulate.analysis import evidence_rows as er

    target = tmp_path / "a-file"
    target.write_text("")
    monkeypatch.setenv(rc.project_cache.ENV, str(target))   # a file: the cache is unusable
    calls = []
    monkeypatch.setitem(er.SHARED, "full4", lambda seed: calls.append(seed))
    with pytest.warns(rc.ResultCacheWarning):
        assert er.start_shared("full4", 7) is False
    assert calls == []          # computed here and again by the row: twice the cost
