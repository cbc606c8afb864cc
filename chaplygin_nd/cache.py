"""The one cache folder of chaplygin-nd and the one variable that moves it.

``$CHAPLYGIN_ND_CACHE`` if set, else the platform's user cache folder: ``$XDG_CACHE_HOME/chaplygin-nd``
(``~/.cache/chaplygin-nd`` when ``XDG_CACHE_HOME`` is unset) on Linux and other POSIX systems,
``~/Library/Caches/chaplygin-nd`` on macOS, ``%LOCALAPPDATA%\\chaplygin-nd\\Cache`` on Windows. Never
inside the installed package. Each user of the cache has its own subfolder
(:func:`cache_dir`): ``heyoka/`` (compiled integrators, :mod:`chaplygin_nd.runtime.jit_cache`),
``evidence/`` (orbits and spectra of the evidence rows, :mod:`chaplygin_nd.simulate.analysis.evidence`).
A cache only saves time: deleting the folder is always safe. When a cache cannot be used, the run
goes on and says why once, as a :class:`CacheWarning`: one line ``warning: ...`` on stderr.
"""

from __future__ import annotations

import os
import stat
import sys
from pathlib import Path

from chaplygin_nd.console import OneLineWarning

__all__ = ["ENV", "CacheWarning", "cache_root", "cache_dir", "unsafe_reason", "first_refusal", "place_matplotlib_cache",
           "forget_refusals"]

#: The environment variable that moves the whole cache.
ENV = "CHAPLYGIN_ND_CACHE"

_REFUSED: set[tuple[str, str]] = set()


class CacheWarning(OneLineWarning):
    """A cache entry or folder was unusable (corrupt, stale, unsafe, unwritable); the run goes on
    (recomputing, or uncached). Shown as one line ``warning: ...`` (:mod:`chaplygin_nd.console`)."""


def cache_root() -> Path:
    """The cache folder (see the module docstring); not created here."""
    if os.environ.get(ENV):
        return Path(os.environ[ENV]).expanduser()
    if sys.platform == "darwin":
        return Path.home() / "Library" / "Caches" / "chaplygin-nd"
    if os.name == "nt":
        base = os.environ.get("LOCALAPPDATA") or str(Path.home() / "AppData" / "Local")
        return Path(base) / "chaplygin-nd" / "Cache"
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "chaplygin-nd"


def cache_dir(kind: str) -> Path:
    """The subfolder ``kind`` (``"heyoka"``, ``"evidence"``) of :func:`cache_root`; not created."""
    return cache_root() / kind


def unsafe_reason(path: Path) -> str | None:
    """Why ``path`` (a file or folder of the cache) may not be trusted, or None — the rule ssh
    applies to its keys: owned by this user, not a symbolic link, not writable by group or others.
    Both caches (compiled integrators, evidence) ask this before reading anything. Not applicable
    where there are no POSIX owners (Windows: None)."""
    if os.name == "nt" or not hasattr(os, "getuid"):
        return None
    try:
        st = path.lstat()
    except OSError as exc:
        return f"cannot be inspected ({exc.strerror})"
    if stat.S_ISLNK(st.st_mode):
        return "is a symbolic link"
    if st.st_uid != os.getuid():
        return f"is owned by another user (uid {st.st_uid}, not {os.getuid()})"
    if st.st_mode & (stat.S_IWGRP | stat.S_IWOTH):
        return (f"is writable by group or others (mode {stat.S_IMODE(st.st_mode):04o}); "
                f"`chmod go-w {path}` makes it private")
    return None


def first_refusal(path: Path, reason: str) -> bool:
    """True the first time in this process that ``path`` is refused for ``reason``
    (:func:`unsafe_reason`): every cache that meets an unsafe folder (compiled integrators,
    heyoka's object code, evidence) asks, so the warning is given once, not once per cache."""
    key = (str(path), reason)
    if key in _REFUSED:
        return False
    _REFUSED.add(key)
    return True


def forget_refusals() -> None:
    """Forget the refusals reported (for tests: a new cache folder, a new warning)."""
    _REFUSED.clear()


def place_matplotlib_cache() -> None:
    """Before matplotlib is imported: its font cache goes to the ``matplotlib/`` subfolder of the
    cache folder (``MPLCONFIGDIR``, created private), not to ``~/.cache/matplotlib`` or, when that
    cannot be written, a new folder in the temporary directory at every run. A ``MPLCONFIGDIR``
    the user set is kept; a cache folder that cannot be created or may not be trusted leaves
    matplotlib's choice."""
    if os.environ.get("MPLCONFIGDIR") or "matplotlib" in sys.modules:
        return
    folder = cache_dir("matplotlib")
    try:
        folder.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
        if unsafe_reason(folder.parent) is not None:  # nothing is created in an unsafe root
            return
        folder.mkdir(exist_ok=True, mode=0o700)
    except OSError:
        return
    if unsafe_reason(folder) is None:
        os.environ["MPLCONFIGDIR"] = str(folder)
