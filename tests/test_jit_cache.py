"""The compile cache is an optimisation, never a failure and never a way in (runtime/jit_cache.py).

No heyoka needed: the cache stores any picklable object; ``build`` counts its calls.
"""

from __future__ import annotations

import errno
import os
import pickle
import stat
import warnings

import pytest
from chaplygin_nd.runtime import jit_cache

KEY = {"object": "test", "system": "toy n=3", "tol": "1e-10"}


class Builder:
    """``build()`` returning a fresh payload and counting its calls."""

    def __init__(self):
        self.calls = 0

    def __call__(self):
        self.calls += 1
        return {"payload": self.calls}


@pytest.fixture
def cache_root(tmp_path, monkeypatch):
    root = tmp_path / "cache"
    monkeypatch.setenv(jit_cache.ENV, str(root))
    jit_cache.forget_memory()
    yield root
    jit_cache.forget_memory()


def _entry(root):
    files = sorted((root / "heyoka").glob("*.pkl"))
    assert len(files) == 1
    return files[0]


def test_cold_warm_memory_and_private_modes(cache_root):
    build = Builder()
    obj, _, how = jit_cache.load_or_build(KEY, build, expect=(dict,))
    assert how == "cold compile" and obj == {"payload": 1}
    assert jit_cache.load_or_build(KEY, build)[2] == "in memory"
    jit_cache.forget_memory()
    obj, _, how = jit_cache.load_or_build(KEY, build, expect=(dict,))
    assert how == "warm load" and obj == {"payload": 1} and build.calls == 1
    entry = _entry(cache_root)
    assert stat.S_IMODE(entry.stat().st_mode) & 0o077 == 0
    assert stat.S_IMODE(entry.parent.stat().st_mode) & 0o077 == 0


def test_source_hash_only_on_a_disk_miss(cache_root):
    """The text hash (expensive for large graphs) is computed when building, never on a hit."""
    hashed = []

    def source():
        hashed.append(1)
        return "abc"

    jit_cache.load_or_build(KEY, Builder(), source=source)
    jit_cache.load_or_build(KEY, Builder(), source=source)
    jit_cache.forget_memory()
    jit_cache.load_or_build(KEY, Builder(), source=source)
    assert len(hashed) == 1
    assert pickle.loads(_entry(cache_root).read_bytes())["source"] == "abc"


def test_token_lookup(cache_root):
    assert jit_cache.memory_hit(("toy", 3)) is None
    obj, _, _ = jit_cache.load_or_build(KEY, Builder(), token=("toy", 3))
    assert jit_cache.memory_hit(("toy", 3)) is obj
    # a later lookup with another token that finds the object in memory records that token too
    again, _, how = jit_cache.load_or_build(KEY, Builder(), token=("toy", "alias"))
    assert how == "in memory" and again is obj and jit_cache.memory_hit(("toy", "alias")) is obj


def test_cache_state_cold_on_disk_in_memory(cache_root):
    """What the planner's cost model is told: cold, then in memory, then (memory dropped) on disk."""
    assert jit_cache.cache_state(KEY) == "cold"
    jit_cache.load_or_build(KEY, Builder())
    assert jit_cache.cache_state(KEY) == "in memory"
    jit_cache.forget_memory()
    assert jit_cache.cache_state(KEY) == "on disk"
    assert jit_cache.cache_state(KEY, use_disk=False) == "cold"


@pytest.mark.parametrize("damage", ["truncated", "garbage", "wrong type", "stale key"])
def test_damaged_entry_warns_once_and_rebuilds(cache_root, damage):
    jit_cache.load_or_build(KEY, Builder(), expect=(dict,))
    entry = _entry(cache_root)
    data = entry.read_bytes()
    if damage == "truncated":
        entry.write_bytes(data[: len(data) // 2])
    elif damage == "garbage":
        entry.write_bytes(b"\x00not a pickle")
    elif damage == "wrong type":
        entry.write_bytes(pickle.dumps({"key": dict(KEY, code=jit_cache.code_version()),
                                        "object": "a string, not the object"}))
    else:
        entry.write_bytes(pickle.dumps({"key": dict(KEY, tol="other"), "object": {}}))
    jit_cache.forget_memory()
    build = Builder()
    with pytest.warns(jit_cache.CacheWarning) as record:
        obj, _, how = jit_cache.load_or_build(KEY, build, expect=(dict,))
    assert how == "cold compile" and obj == {"payload": 1}
    assert len(record) == 1 and str(entry) in str(record[0].message)
    assert jit_cache.ENV in str(record[0].message)
    jit_cache.forget_memory()
    assert jit_cache.load_or_build(KEY, Builder(), expect=(dict,))[2] == "warm load"  # repaired


def test_crafted_pickle_in_a_group_writable_folder_is_not_executed(cache_root, tmp_path):
    """An entry another user could have written (group-writable folder) is never unpickled: the
    payload would create a file; it is not created, the run warns and goes on uncached."""
    jit_cache.load_or_build(KEY, Builder())
    entry = _entry(cache_root)
    marker = tmp_path / "pwned"

    class Payload:
        def __reduce__(self):
            return (open, (str(marker), "w"))

    entry.write_bytes(pickle.dumps(Payload()))
    os.chmod(entry.parent, 0o770)
    jit_cache.forget_memory()
    build = Builder()
    with pytest.warns(jit_cache.CacheWarning, match="writable by group") as record:
        obj, _, how = jit_cache.load_or_build(KEY, build)
    assert not marker.exists()
    assert how == "cold compile" and obj == {"payload": 1}
    assert jit_cache.ENV in str(record[0].message)
    assert entry.read_bytes() == pickle.dumps(Payload())
    assert not marker.exists()


def test_world_writable_entry_and_root_are_refused(cache_root, tmp_path):
    jit_cache.load_or_build(KEY, Builder())
    entry = _entry(cache_root)
    os.chmod(entry, 0o666)
    jit_cache.forget_memory()
    with pytest.warns(jit_cache.CacheWarning, match="writable by"):
        assert jit_cache.load_or_build(KEY, Builder())[2] == "cold compile"
    os.chmod(entry, 0o600)
    os.chmod(cache_root, 0o777)
    jit_cache.forget_memory()
    with pytest.warns(jit_cache.CacheWarning, match="writable by"):
        assert jit_cache.load_or_build(KEY, Builder())[2] == "cold compile"
    os.chmod(cache_root, 0o700)


def test_variable_naming_a_file_warns_and_runs_uncached(tmp_path, monkeypatch):
    target = tmp_path / "a-file"
    target.write_text("mine")
    monkeypatch.setenv(jit_cache.ENV, str(target))
    jit_cache.forget_memory()
    with pytest.warns(jit_cache.CacheWarning, match="cannot be written") as record:
        obj, _, how = jit_cache.load_or_build(KEY, Builder())
    assert how == "cold compile" and obj == {"payload": 1} and target.read_text() == "mine"
    assert jit_cache.ENV in str(record[0].message) and str(target) in str(record[0].message)
    jit_cache.forget_memory()


@pytest.mark.parametrize("code", [errno.EROFS, errno.ENOSPC])
def test_unwritable_cache_warns_once_and_runs_uncached(cache_root, monkeypatch, code):
    """A read-only or full file system (simulated: root ignores modes) fails the write; the run
    goes on with the built object, and the second failure in the same run says nothing more."""
    def refuse(path, payload):
        raise OSError(code, os.strerror(code), str(path))

    monkeypatch.setattr(jit_cache, "_write_atomic", refuse)
    with pytest.warns(jit_cache.CacheWarning, match="cannot be written") as record:
        obj, _, how = jit_cache.load_or_build(KEY, Builder())
    assert how == "cold compile" and obj == {"payload": 1}
    assert str(cache_root) in str(record[0].message) and jit_cache.ENV in str(record[0].message)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert jit_cache.load_or_build(dict(KEY, tol="1e-12"), Builder())[2] == "cold compile"


class _FakeState:
    """Stands for ``heyoka.llvm_state``'s disk-cache controls (heyoka >= 7.10)."""

    def __init__(self):
        self.path, self.enabled = None, True

    def set_diskcache_path(self, path):
        self.path = path

    def set_diskcache_enabled(self, flag):
        self.enabled = flag


def test_heyokas_own_cache_lives_in_the_project_cache(cache_root, monkeypatch):
    """heyoka's object-code cache goes to heyoka-llvm/ in the project's folder, private."""
    fake = type("hy", (), {"llvm_state": _FakeState()})
    monkeypatch.setitem(__import__("sys").modules, "heyoka", fake)
    jit_cache.load_or_build(KEY, Builder())
    assert fake.llvm_state.path == str(cache_root / "heyoka-llvm") and fake.llvm_state.enabled
    assert stat.S_IMODE((cache_root / "heyoka-llvm").stat().st_mode) & 0o077 == 0


def test_a_group_writable_cache_is_warned_about_once(cache_root, monkeypatch):
    """Placing heyoka's cache, storing an entry and the evidence cache all meet the same unsafe
    root: one warning in all, and heyoka's own cache is turned off."""
    from chaplygin_nd.simulate.analysis import result_cache

    fake = type("hy", (), {"llvm_state": _FakeState()})
    monkeypatch.setitem(__import__("sys").modules, "heyoka", fake)
    cache_root.mkdir(mode=0o700)
    os.chmod(cache_root, 0o770)
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        jit_cache.load_or_build(KEY, Builder())
        jit_cache.load_or_build(dict(KEY, tol="1e-12"), Builder())
        assert result_cache.private_folder("evidence") is None
    lines = [str(w.message) for w in record if issubclass(w.category, Warning)]
    assert len(lines) == 1 and "writable by group" in lines[0], lines
    assert fake.llvm_state.enabled is False


def test_a_cache_variable_naming_a_file_is_one_warning_with_heyoka_too(tmp_path, monkeypatch):
    """With heyoka loaded (its own cache is placed before the compile), a cache that cannot be
    created is still one warning, the one a failed store gives."""
    fake = type("hy", (), {"llvm_state": _FakeState()})
    monkeypatch.setitem(__import__("sys").modules, "heyoka", fake)
    target = tmp_path / "a-file"
    target.write_text("mine")
    monkeypatch.setenv(jit_cache.ENV, str(target))
    jit_cache.forget_memory()
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        assert jit_cache.load_or_build(KEY, Builder())[2] == "cold compile"
    lines = [str(w.message) for w in record]
    assert len(lines) == 1 and "cannot be written" in lines[0], lines
    assert fake.llvm_state.enabled is False
    jit_cache.forget_memory()
