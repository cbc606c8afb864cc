r"""A disk cache of computed results (orbits, spectra) that knows the code that computed them.

An entry is found by a *settings key* (the experiment's settings and the versions of Python,
NumPy, SciPy, PyNAFF and heyoka) and trusted only if the *code* that computed it is unchanged:
after the computation, :func:`code_manifest` records the SHA-256 of the source file of every
module of the project (``chaplygin_nd.*``) loaded in the process — a superset of what the
computation imported, so an edit anywhere in the code it ran (the field of
:mod:`simulate.dynamics.so`, a generated kernel, the integrator, the analysis) invalidates the entry. On a
lookup, :func:`code_unchanged` hashes the current source of each recorded module again (the
module in ``sys.modules``, else where the import system would find it); a module that changed,
or that can no longer be found, makes the lookup a miss, and the recomputed entry replaces it.

This is the one mechanism of every cache of computed results: the orbits and spectra
of :mod:`simulate.analysis.evidence` / :mod:`simulate.analysis.frequencies` (``.npz`` and JSON) and
the drawn ensembles of :mod:`simulate.analysis.drawn_evidence` (JSON through :func:`cached_json`).
No cache keeps a hand-made list of source files: the manifest is taken from ``sys.modules``.

A cache is an optimisation, never a failure and never a way in:

* entries are ``.npz`` read with ``allow_pickle=False`` and JSON: nothing is unpickled;
* an entry that does not parse or has the wrong shape (truncated, random bytes, a folder in its
  place) is reported once (one :class:`ResultCacheWarning` line naming the file and
  ``$CHAPLYGIN_ND_CACHE``), removed (:func:`damaged`), recomputed and written anew;
* a folder that cannot be created or written (read-only, the variable naming a file) is reported
  once and the run goes on uncached;
* a folder (the cache root or its subfolder) that is writable by group or others, or not owned by
  this user, is refused as ssh refuses such key folders: reported once, the run goes on uncached.
  The folders this module creates are private (mode 0700).
"""

from __future__ import annotations

import contextlib
import hashlib
import importlib.metadata
import importlib.util
import json
import os
import sys
import warnings
from collections.abc import Iterator
from pathlib import Path

from chaplygin_nd import cache as project_cache
from chaplygin_nd import writing

__all__ = ["ResultCacheWarning", "private_folder", "code_manifest", "code_unchanged",
           "environment", "write_atomic", "warn_once", "locked", "read_entry", "settings_key",
           "damaged", "cached_json"]

PROJECT = "chaplygin_nd"
_WARNED: set[str] = set()
_HASHES: dict[tuple[str, int, int], str] = {}


class ResultCacheWarning(project_cache.CacheWarning):
    """A cache folder or entry was unusable; the run goes on (recomputing, or uncached)."""


def warn_once(message: str) -> None:
    """Warn ``message`` (a :class:`ResultCacheWarning`) once per process, naming the variable
    that moves the cache."""
    if message in _WARNED:
        return
    _WARNED.add(message)
    warnings.warn(f"{message} (the cache folder is set by ${project_cache.ENV}; "
                  "deleting it is always safe)", ResultCacheWarning, stacklevel=3)


def read_entry(path: Path, parse):
    """``parse(text)`` of the cache entry at ``path`` (read as UTF-8), or ``None`` after one
    warning when the entry cannot be read or parsed (truncated, edited, not this version's
    format): a damaged entry is recomputed, never trusted, never a traceback."""
    try:
        return parse(path.read_text(encoding="utf-8"))
    except Exception as exc:  # noqa: BLE001 - any unreadable entry is a miss
        warn_once(f"cache entry {path} is damaged ({type(exc).__name__}: "
                  f"{str(exc)[:120]}); recomputing it")
        return None


def private_folder(kind: str) -> Path | None:
    """The subfolder ``kind`` of the project's cache folder, created private (0700) if needed;
    None (after one warning) when it cannot be created or written or is not private."""
    root = project_cache.cache_root()
    sub = project_cache.cache_dir(kind)
    try:
        for folder in (root, sub):
            if folder.exists() and not folder.is_dir():
                warn_once(f"the cache folder {folder} is not a folder; running uncached")
                return None
            folder.mkdir(mode=0o700, parents=True, exist_ok=True)
            reason = project_cache.unsafe_reason(folder)
            if reason is not None:
                if project_cache.first_refusal(folder, reason):  # once, whichever cache met it
                    warn_once(f"the cache folder {folder} {reason}: refused, running uncached")
                return None
        if not os.access(sub, os.W_OK | os.X_OK):
            warn_once(f"the cache folder {sub} is not writable; running uncached")
            return None
    except OSError as exc:
        warn_once(f"the cache folder {sub} cannot be used ({exc.strerror or exc}); running uncached")
        return None
    return sub


def _source_hash(path: str) -> str | None:
    try:
        st = os.stat(path)
    except OSError:
        return None
    key = (path, st.st_mtime_ns, st.st_size)
    if key not in _HASHES:
        try:
            _HASHES[key] = hashlib.sha256(Path(path).read_bytes()).hexdigest()
        except OSError:
            return None
    return _HASHES[key]


def _source_file(name: str) -> str | None:
    mod = sys.modules.get(name)
    origin = getattr(mod, "__file__", None) if mod is not None else None
    if origin is None:
        try:
            spec = importlib.util.find_spec(name)
        except (ImportError, ValueError):
            return None
        origin = spec.origin if spec is not None else None
    if origin is None or not origin.endswith(".py"):
        return None
    return origin


def code_manifest() -> dict[str, str]:
    """``{module: SHA-256 of its source}`` for every loaded module of the project (call it after
    the computation: every module the computation imported is loaded then)."""
    out = {}
    for name in sorted(list(sys.modules)):
        if name != PROJECT and not name.startswith(PROJECT + "."):
            continue
        path = _source_file(name)
        digest = _source_hash(path) if path else None
        if digest is not None:
            out[name] = digest
    return out


def code_unchanged(manifest) -> bool:
    """True when every module of ``manifest`` (from :func:`code_manifest`) is found and its
    source has the recorded hash. A manifest that is not a non-empty ``{str: str}`` is False."""
    if not isinstance(manifest, dict) or not manifest:
        return False
    for name, digest in manifest.items():
        if not isinstance(name, str) or not isinstance(digest, str):
            return False
        if not (name == PROJECT or name.startswith(PROJECT + ".")):
            return False
        path = _source_file(name)
        if path is None or _source_hash(path) != digest:
            return False
    return True


def environment(heyoka: bool = False) -> dict[str, str]:
    """The versions a cached number depends on: Python, NumPy, SciPy, PyNAFF (and heyoka)."""
    out = {"python": sys.version.split()[0]}
    for dist in ("numpy", "scipy", "PyNAFF") + (("heyoka",) if heyoka else ()):
        try:
            out[dist] = importlib.metadata.version(dist)
        except importlib.metadata.PackageNotFoundError:
            out[dist] = "absent"
    return out


def write_atomic(path: Path, write) -> bool:
    """``write(tmp_path)`` into a temporary file beside ``path``, then move it into place
    (:func:`chaplygin_nd.writing.write_atomic`; a cache entry is private, 0600, as its folder);
    False (after one warning) if the folder refuses the write. Never raises :class:`OSError`."""
    try:
        writing.write_atomic(path, write, mode=0o600)
        return True
    except OSError as exc:
        warn_once(f"writing the cache entry {path} failed ({exc.strerror or exc}); running uncached")
        return False


@contextlib.contextmanager
def locked(path: Path, wait: bool = True) -> Iterator[bool]:
    """Hold an exclusive lock on ``path.lock`` (one process computes an entry, the others wait);
    yields True. With ``wait=False`` it does not wait: it yields False if another process holds
    the lock. Without a lock (no ``fcntl``, or the lock file cannot be opened) the block still
    runs, with True."""
    try:
        import fcntl

        fh = open(path.with_suffix(".lock"), "a")  # noqa: SIM115 - closed below
    except (ImportError, OSError):
        yield True
        return
    try:
        try:
            fcntl.flock(fh, fcntl.LOCK_EX if wait else fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:  # only without waiting: another process holds it
            yield False
            return
        except OSError:
            pass
        yield True
    finally:
        fh.close()


def dumps(obj) -> str:
    """Canonical JSON (sorted keys) of a settings dict, for keys."""
    return json.dumps(obj, sort_keys=True)


def settings_key(settings, heyoka: bool = False) -> str:
    """The settings key of an entry: 20 hex digits of the SHA-256 of the canonical JSON of
    ``settings`` (a JSON-able object naming everything the result depends on except the code) and
    of the library versions (:func:`environment`). The code is checked apart, by the manifest."""
    text = dumps({"settings": settings, "versions": environment(heyoka=heyoka)})
    return hashlib.sha256(text.encode()).hexdigest()[:20]


def damaged(path: Path, exc: BaseException) -> None:
    """Report the unreadable entry ``path`` once (one line: why) and remove it (a file, or a
    folder found in its place), so that the recomputed entry can take its place."""
    why = " ".join(f"{type(exc).__name__}: {exc}".split())[:160]
    warn_once(f"cache entry {path} is corrupt ({why}); recomputing it")
    with contextlib.suppress(OSError):
        if path.is_dir() and not path.is_symlink():
            import shutil

            shutil.rmtree(path)
        else:
            path.unlink()


_MISS = object()


def _read_json(path: Path, decode):
    """The value of the JSON entry ``path`` (``{"manifest": ..., "value": ...}``) if it parses,
    ``decode`` accepts it and its manifest matches the code loaded now; ``_MISS`` otherwise."""
    if not os.path.lexists(path):
        return _MISS
    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
        if not isinstance(data, dict) or not isinstance(data.get("manifest"), dict):
            raise ValueError("not an entry (no manifest)")
        value = decode(data["value"])
    except Exception as exc:  # noqa: BLE001 - any unreadable entry is recomputed, never trusted
        damaged(path, exc)
        return _MISS
    return value if code_unchanged(data["manifest"]) else _MISS


def cached_json(kind: str, name: str, settings, compute, *, encode, decode,
                use_cache: bool = True, heyoka: bool = False):
    """``(value, cached)``: the result of ``compute()`` for ``settings``, from the entry
    ``KIND/NAME-KEY.json`` (:func:`settings_key`) when it parses, ``decode(stored)`` accepts it
    and every project module recorded with it has its recorded source (:func:`code_unchanged`);
    else computed, then stored with the manifest of the modules loaded after the computation
    (:func:`code_manifest`) as ``encode(value)``. A damaged entry is a miss (:func:`damaged`);
    a folder that cannot be used runs uncached (:func:`private_folder`). One process computes,
    the others wait (:func:`locked`)."""
    folder = private_folder(kind) if use_cache else None
    if folder is None:
        return compute(), False
    path = folder / f"{name}-{settings_key(settings, heyoka)}.json"
    with locked(path):
        found = _read_json(path, decode)
        if found is not _MISS:
            return found, True
        before = code_manifest()
        value = compute()
        manifest = code_manifest()
        if any(manifest.get(k, v) != v for k, v in before.items()):
            # the source changed while it ran: which code computed the value is not known
            warn_once(f"the source changed during the computation of {path.name}; not cached")
            return value, False
        text = json.dumps({"manifest": manifest, "value": encode(value)})
        if os.path.isdir(path) and not os.path.islink(path):   # appeared meanwhile: not ours
            damaged(path, IsADirectoryError("a folder in place of the entry"))
        write_atomic(path, lambda tmp: Path(tmp).write_text(text, encoding="utf-8"))
    return value, False
