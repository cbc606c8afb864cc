r"""A cache of compiled heyoka objects (integrators, compiled functions): in memory and on disk.

heyoka objects pickle together with their LLVM-compiled code, so the second run of a system loads
in milliseconds instead of compiling for seconds.

**Keys.** An entry is keyed by what *identifies* the compiled code, known without building
anything: the kind of object and its system (name, $n$), tolerance, precision, mode (compact,
batch size) and the versions — heyoka's, and :func:`code_version`, a SHA-256 of the source of the
modules that build the expression graphs (generated builders, their assembly, the systems). The
in-memory lookup is a dictionary lookup on that key (a warm call costs microseconds); the text of
the expressions (their own SHA-256, ``source``) is computed only on a disk miss, when the graph
is built anyway, and stored beside the object for the record.

**A cache is an optimisation, never a failure and never a way in.**

* Nothing is unpickled (``pickle.load`` runs code) from a folder another user could write: before
  reading, the file, its folder and the cache root must be owned by this user and not writable by
  group or others (as ssh checks its keys). Otherwise the cache is refused with one warning and the
  run goes on uncached (nothing read, nothing written there).
* An entry that does not unpickle, whose stored key differs, or whose object is not of the expected
  type is rebuilt with a warning and overwritten; it is never trusted.
* A cache that cannot be written (read-only or full file system, ``$CHAPLYGIN_ND_CACHE`` naming a
  file) warns once and the run goes on with the built object.

Every warning names the path and the variable ``CHAPLYGIN_ND_CACHE`` that moves the cache, and is
given once per process and path. Folders are created private (0700), files 0600, writes atomic
(a temporary file in the same folder, then ``os.replace``).

heyoka >= 7.10 also keeps its own cache of compiled object code (an SQLite file ``cache.db``, by
default in ``~/.cache/heyoka``), keyed by the LLVM IR; a hit there still rebuilds the decomposition
and the IR. Measured (2 shared cores): n = 4 full field, tol 1e-11 — construction with a heyoka
disk-cache hit 54 ms, our unpickle 17 ms; a cold compile is 1–20 s. Both caches are on, and both
live in the project's cache folder: before the first compile :func:`place_heyoka_cache` points
heyoka's at ``heyoka-llvm/`` there (``llvm_state.set_diskcache_path``), or turns it off
(``set_diskcache_enabled(False)``) when that folder may not be trusted or created — heyoka loads
and runs the object code it finds there, so it gets the trust rule of our own entries.

Folder: the ``heyoka/`` subfolder of the project's one cache folder (:mod:`chaplygin_nd.cache`).
"""

from __future__ import annotations

import hashlib
import json
import pickle
import sys
import time
import warnings
from collections.abc import Callable
from functools import cache
from pathlib import Path

from chaplygin_nd import cache as project_cache
from chaplygin_nd.writing import write_atomic

__all__ = ["cache_dir", "load_or_build", "place_heyoka_cache", "memory_hit", "CacheWarning", "code_version", "forget_memory",
           "cache_state", "unsafe_reason"]

ENV = project_cache.ENV
_MEMORY: dict[tuple, object] = {}
_WARNED: set[tuple[str, str]] = set()

#: Modules whose source decides the expression graphs heyoka compiles (see :func:`code_version`):
#: every module that builds a :class:`simulate.integrators.heyoka_systems.System` (a system keeps
#: its name when its formula changes: the general-J control, the MEGNO tangent, GALI's deviation
#: vectors, the study's pendula)
CODE_MODULES = ("chaplygin_nd.generated.expression_builders", "chaplygin_nd.runtime.expressions",
                "chaplygin_nd.simulate.integrators.heyoka_systems", "chaplygin_nd.runtime.compiled",
                "chaplygin_nd.simulate.integrators.heyoka_taylor",
                "chaplygin_nd.simulate.analysis.chaos", "chaplygin_nd.simulate.analysis.control",
                "chaplygin_nd.simulate.analysis.gali", "chaplygin_nd.simulate.analysis.gali_study",
                "chaplygin_nd.simulate.analysis.fma")


class CacheWarning(project_cache.CacheWarning):
    """A cache entry was corrupt, stale or unsafe, or the cache could not be written; the run goes on."""


def cache_dir() -> Path:
    """The folder of the compiled heyoka objects (see the module docstring); not created here."""
    return project_cache.cache_dir("heyoka")


@cache
def code_version() -> str:
    """SHA-256 (16 hex digits) of the source files of :data:`CODE_MODULES` (read once per process)
    and of any function of theirs whose code was replaced in memory (compiled from elsewhere than
    its module's file, e.g. a mutant of ``make mutate-derivations``), so that such code never gets
    the file's compiled objects nor leaves its own for them. Cached: whoever replaces code calls
    ``code_version.cache_clear()`` (the mutation tools clear every cache)."""
    import importlib.util
    from types import FunctionType

    h = hashlib.sha256()
    for name in CODE_MODULES:
        spec = importlib.util.find_spec(name)
        h.update(name.encode())
        if spec is not None and spec.origin:
            h.update(Path(spec.origin).read_bytes())
        module = sys.modules.get(name)  # not loaded: its functions are its file's
        for attr, obj in sorted(vars(module).items()) if module is not None else ():
            if not (isinstance(obj, FunctionType) and obj.__module__ == name and spec is not None):
                continue
            code = obj.__code__
            if code.co_filename != spec.origin:
                h.update(f"{attr}:{code.co_filename}".encode() + code.co_code
                         + repr(code.co_names).encode())
    return h.hexdigest()[:16]


def _refuse(where: Path, reason: str) -> None:
    """The one warning for a cache folder or file that may not be trusted: given once per process
    and place, whether reading, writing or placing heyoka's own cache met it first, or the
    evidence cache (:func:`chaplygin_nd.cache.first_refusal`)."""
    if not project_cache.first_refusal(where, reason):
        return
    _warn(where, f"{reason}; refused (nothing is read from or written to a folder another user "
                 "could write: make it private, chmod 700, owned by you)",
          "running uncached, heyoka's own object-code cache off")


def _warn(path: Path, problem: str, what: str) -> None:
    if (str(path), problem) in _WARNED:
        return
    _WARNED.add((str(path), problem))
    warnings.warn(f"heyoka cache {path}: {problem}; {what} (the cache folder is set by {ENV})",
                  CacheWarning, stacklevel=4)


#: The trust rule of every cache of the project (:func:`chaplygin_nd.cache.unsafe_reason`).
unsafe_reason = project_cache.unsafe_reason


def _chain_unsafe(path: Path) -> tuple[Path, str] | None:
    """The first of the file, its folder and the cache root that may not be trusted."""
    root = project_cache.cache_root()
    for p in (path, path.parent, root):
        reason = unsafe_reason(p)
        if reason is not None:
            return p, reason
    return None


def _write_atomic(path: Path, payload: bytes) -> None:
    write_atomic(path, payload, mode=0o600)  # private, as its folder: it is unpickled


def _memory_key(key: dict) -> tuple:
    return tuple(sorted((k, v if isinstance(v, str | int | float | bool) else repr(v))
                        for k, v in key.items()))


def _file_name(key: dict) -> str:
    return hashlib.sha256(json.dumps(key, sort_keys=True).encode()).hexdigest()[:32] + ".pkl"


def cache_state(key: dict, use_disk: bool = True) -> str:
    """Where the object of ``key`` would come from now: ``"in memory"``, ``"on disk"`` (an entry
    exists; it may still turn out stale) or ``"cold"``; used by the planner's cost model."""
    key = dict(key, code=code_version())
    if _memory_key(key) in _MEMORY:
        return "in memory"
    if use_disk:
        try:
            if (cache_dir() / _file_name(key)).is_file():
                return "on disk"
        except OSError:
            pass
    return "cold"


_PLACED: list[str] = []


def place_heyoka_cache(hy) -> str:
    """Put heyoka's own disk cache of object code (module docstring) in the ``heyoka-llvm/``
    subfolder of the project's cache folder, created private (0700), or turn it off when that
    folder cannot be created or may not be trusted (:func:`unsafe_reason` on it and on the cache
    root); once per process. Returns the path used, or ``""`` when turned off. Never raises
    because of the cache."""
    if _PLACED:
        return _PLACED[0]
    state = getattr(hy, "llvm_state", None)
    if state is None or not hasattr(state, "set_diskcache_path"):  # heyoka < 7.10: no disk cache
        _PLACED.append("")
        return ""
    folder = project_cache.cache_dir("heyoka-llvm")
    try:
        folder.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
        reason = unsafe_reason(folder.parent)  # nothing is created in an unsafe root
        if reason is None:
            folder.mkdir(exist_ok=True, mode=0o700)
        unsafe = _chain_unsafe(folder) if reason is None else (folder.parent, reason)
    except OSError as exc:  # the same words as a store that fails: one warning for both
        state.set_diskcache_enabled(False)
        _warn(project_cache.cache_root(), f"cannot be written ({exc.strerror or exc})",
              "running uncached")
        _PLACED.append("")
        return ""
    if unsafe is None:
        state.set_diskcache_path(str(folder))
        state.set_diskcache_enabled(True)
        _PLACED.append(str(folder))
    else:
        state.set_diskcache_enabled(False)
        _refuse(*unsafe)
        _PLACED.append("")
    return _PLACED[0]


def memory_hit(token: tuple):
    """The object stored in memory under ``token`` (see :func:`load_or_build`), or None: the
    cheapest warm lookup, before a key is even made."""
    return _MEMORY.get(("token", code_version()) + token)


def load_or_build(key: dict, build: Callable[[], object], use_disk: bool = True,
                  source: Callable[[], str] | None = None, expect: tuple[type, ...] = (),
                  token: tuple | None = None):
    r"""``(object, seconds, how)``: the object for ``key`` from memory (``how = "in memory"``), from
    disk (``"warm load"``) or from ``build()`` (``"cold compile"``, then stored); ``seconds`` is the
    time of that load or compile. ``key``: a JSON-serialisable dict of what identifies the object
    (:func:`code_version` is added); ``source()``: the expressions' text hash, called on a disk miss
    only; ``expect``: the types a loaded object must have; ``token``: a hashable alias of ``key``
    for :func:`memory_hit`. Never raises because of the cache."""
    key = dict(key, code=code_version())
    mkey = _memory_key(key)
    hit = _MEMORY.get(mkey)
    if hit is not None:
        if token is not None:
            _MEMORY[("token", key["code"]) + token] = hit
        return hit, 0.0, "in memory"
    obj, seconds, how = _load_or_build(key, mkey, build, use_disk, source, expect)
    if token is not None:
        _MEMORY[("token", key["code"]) + token] = obj
    return obj, seconds, how


def _load_or_build(key, mkey, build, use_disk, source, expect):
    start = time.perf_counter()
    path = cache_dir() / _file_name(key)
    if use_disk:
        obj = _load(path, key, expect)
        if obj is not None:
            _MEMORY[mkey] = obj
            return obj, time.perf_counter() - start, "warm load"
        start = time.perf_counter()
    if "heyoka" in sys.modules:  # imported by whoever builds: its own cache placed before a compile
        place_heyoka_cache(sys.modules["heyoka"])
    obj = build()
    seconds = time.perf_counter() - start
    if use_disk:
        _store(path, key, obj, source)
    _MEMORY[mkey] = obj
    return obj, seconds, "cold compile"


def _load(path: Path, key: dict, expect: tuple[type, ...]):
    """The trusted object at ``path`` or None (after a warning when there was something wrong)."""
    try:
        if not path.is_file():
            return None
    except OSError:
        return None
    unsafe = _chain_unsafe(path)
    if unsafe is not None:
        where, reason = unsafe
        _refuse(where, reason)
        return None
    problem = None
    try:
        with path.open("rb") as fh:
            entry = pickle.load(fh)
        if not isinstance(entry, dict) or entry.get("key") != key:
            problem = "stale (its stored key differs)"
        elif expect and not isinstance(entry.get("object"), expect):
            problem = f"wrong-shaped (holds a {type(entry.get('object')).__name__})"
        else:
            return entry["object"]
    except Exception as exc:  # noqa: BLE001 - a truncated or foreign file: never trusted
        problem = f"corrupt ({type(exc).__name__}: {exc})"
    _warn(path, f"entry is {problem}", "rebuilding it")
    return None


def _store(path: Path, key: dict, obj, source) -> None:
    try:
        entry = {"key": key, "source": source() if source else None, "object": obj}
        payload = pickle.dumps(entry)
    except Exception as exc:  # noqa: BLE001 - an object heyoka cannot pickle: stay in memory
        _warn(path, f"cannot be pickled ({type(exc).__name__}: {exc})", "kept in memory only")
        return
    try:
        path.parent.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
        root_reason = unsafe_reason(path.parent.parent)
        if root_reason is not None:  # nothing is created in an unsafe root
            _refuse(path.parent.parent, root_reason)
            return
        path.parent.mkdir(exist_ok=True, mode=0o700)
        unsafe = _chain_unsafe(path.parent)
        if unsafe is not None:
            where, reason = unsafe
            _refuse(where, reason)
            return
        _write_atomic(path, payload)
    except OSError as exc:
        root = project_cache.cache_root()
        _warn(root, f"cannot be written ({exc.strerror or exc})", "running uncached")


def forget_memory() -> None:
    """Drop the in-process copies and the record of warnings given (for tests and benchmarks)."""
    _MEMORY.clear()
    _WARNED.clear()
    _PLACED.clear()
    project_cache.forget_refusals()

