r"""A disk cache of compiled heyoka objects (integrators, compiled functions).

heyoka objects pickle together with their LLVM-compiled code, so the second run of a system loads
in milliseconds instead of compiling for seconds. An entry is keyed by everything the compiled
code depends on — the SHA-256 of the expressions handed to heyoka (their source hash), the
tolerance, the precision, the mode (compact, batch size) and the heyoka version — and stores that
key beside the object. An entry that does not unpickle, or whose stored key differs from the one
asked for, is rebuilt with a warning and overwritten; it is never trusted. Writes are atomic
(a temporary file in the same folder, then ``os.replace``).

heyoka >= 7 also keeps its own cache of compiled object code (``~/.cache/heyoka``, on by default),
keyed by the LLVM IR; a hit there still rebuilds the decomposition and the IR. Measured (2 shared
cores): n = 4 full field, tol 1e-11 — construction with a heyoka disk-cache hit 54 ms, our unpickle
17 ms; n = 6 — 265 ms vs 17 ms; a cold compile is 3–20 s. Both caches are left on.

Folder: the ``heyoka/`` subfolder of the project's one cache folder (:mod:`chaplygin_nd.cache`:
``$CHAPLYGIN_ND_CACHE``, else the platform's user cache folder).
"""

from __future__ import annotations

import hashlib
import json
import os
import pickle
import tempfile
import time
import warnings
from collections.abc import Callable
from pathlib import Path

from chaplygin_nd import cache as project_cache

__all__ = ["cache_dir", "load_or_build", "CacheWarning"]

ENV = project_cache.ENV
_MEMORY: dict[str, object] = {}


class CacheWarning(UserWarning):
    """A cache entry was corrupt or stale and has been rebuilt."""


def cache_dir() -> Path:
    """The folder of the compiled heyoka objects (see the module docstring); not created here."""
    return project_cache.cache_dir("heyoka")


def _digest(key: dict) -> str:
    return hashlib.sha256(json.dumps(key, sort_keys=True).encode()).hexdigest()[:32]


def _write_atomic(path: Path, payload: bytes) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=path.name + ".", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(payload)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def load_or_build(key: dict, build: Callable[[], object], use_disk: bool = True):
    r"""``(object, seconds, how)``: the object for ``key`` from memory (``how = "in memory"``), from
    disk (``"warm load"``) or from ``build()`` (``"cold compile"``, then stored); ``seconds`` is the
    time of that load or compile. ``key``: a JSON-serialisable dict (see the module docstring)."""
    name = _digest(key)
    if name in _MEMORY:
        return _MEMORY[name], 0.0, "in memory"
    path = cache_dir() / f"{name}.pkl"
    start = time.perf_counter()
    if use_disk and path.exists():
        problem = None
        try:
            with path.open("rb") as fh:
                entry = pickle.load(fh)
            if not isinstance(entry, dict) or entry.get("key") != key:
                problem = "stale (its stored key differs)"
            else:
                obj = entry["object"]
        except Exception as exc:  # a truncated or foreign file: never trusted
            problem = f"corrupt ({type(exc).__name__}: {exc})"
        if problem is None:
            _MEMORY[name] = obj
            return obj, time.perf_counter() - start, "warm load"
        warnings.warn(f"heyoka cache entry {path} is {problem}; rebuilding it", CacheWarning,
                      stacklevel=3)
        start = time.perf_counter()
    obj = build()
    seconds = time.perf_counter() - start
    if use_disk:
        _write_atomic(path, pickle.dumps({"key": key, "object": obj}))
    _MEMORY[name] = obj
    return obj, seconds, "cold compile"


def forget_memory() -> None:
    """Drop the in-process copies (the next call loads from disk; for tests and benchmarks)."""
    _MEMORY.clear()
