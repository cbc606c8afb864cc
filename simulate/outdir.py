"""The output folder of a run: write only files this program owns, each atomically.

Rules (checked by :func:`claim` *before* any computation, so a refusal costs nothing and touches
nothing):

* the folder may be new (its nearest existing ancestor must be a writable folder), empty, or a
  folder this program wrote before for the *same scene*: it then holds a manifest
  ``.chaplygin-run.json`` listing the files written, and only those files may be replaced;
* anything else is refused with a one-line :class:`OutputError`: an existing file or device
  (``/dev/null``), a folder holding files the program did not write (a user's ``thesis.tex``,
  or ``.`` with its contents), a folder that belongs to another scene, a read-only folder, a path
  under an existing file, a read-only parent.

Writes (:meth:`OutputFolder.write`): each file goes to a temporary name in the same folder and is
moved into place with :func:`os.replace`; files get the permissions of an ordinary new file (the
process umask applies; :func:`tempfile.mkstemp` would leave them 0600), folders likewise. The
manifest is written first with the union of the old and the new names (so an interrupted run
still owns everything it may have left), and last with the new names only, after the files of
the previous run that this run no longer produces were removed. Nothing is ever renamed away.
"""

from __future__ import annotations

import json
import os
import tempfile
from collections.abc import Callable, Iterable
from pathlib import Path

__all__ = ["MANIFEST", "OutputError", "OutputFolder", "claim"]

MANIFEST = ".chaplygin-run.json"
PROGRAM = "chaplygin-nd simulate"


class OutputError(Exception):
    """``--out`` names a place this program may not write to; the message says why and what to do."""


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _probe_writable(folder: Path) -> bool:
    """True when a file can really be created in ``folder`` (``os.access`` alone is wrong for
    root, which bypasses permission bits but not read-only mounts); the probe file is removed."""
    if not os.access(folder, os.W_OK | os.X_OK):
        return False
    try:
        fd, name = tempfile.mkstemp(prefix=".chaplygin-probe-", dir=folder)
    except OSError:
        return False
    os.close(fd)
    os.unlink(name)
    return True


def _read_manifest(folder: Path) -> dict | None:
    path = folder / MANIFEST
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    files = data.get("files") if isinstance(data, dict) else None
    if (data.get("program") != PROGRAM or not isinstance(files, list)
            or not all(isinstance(f, str) and f and "/" not in f and f not in (".", "..")
                       for f in files)):
        return None
    return data


def _is_leftover(entry: str, owned: set[str]) -> bool:
    """A temporary file of :meth:`OutputFolder._atomic` for an owned name (left by a killed run)."""
    return any(entry.startswith(f".{name}.") and f".tmp{Path(name).suffix}" in entry
               for name in owned)


class OutputFolder:
    """A folder :func:`claim` found safe to write to; ``owned`` are the names it may replace."""

    def __init__(self, path: Path, scene: str, owned: Iterable[str] = ()):
        self.path = path
        self.scene = scene
        self.owned = set(owned)
        self.written: list[str] = []

    def _manifest(self, names: Iterable[str]) -> None:
        data = {"program": PROGRAM, "scene": self.scene, "files": sorted(set(names))}
        self._atomic(MANIFEST, lambda p: p.write_text(json.dumps(data, indent=1) + "\n",
                                                      encoding="utf-8"))

    def _atomic(self, name: str, writer: Callable[[Path], None]) -> None:
        fd, tmp = tempfile.mkstemp(prefix=f".{name}.", suffix=f".tmp{Path(name).suffix}",
                                   dir=self.path)
        os.close(fd)
        try:
            writer(Path(tmp))
            os.chmod(tmp, 0o666 & ~_umask())
            os.replace(tmp, self.path / name)
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise

    def write(self, files: dict[str, Callable[[Path], None]]) -> Path:
        """Write every ``name -> writer(path)`` of ``files`` atomically, then remove the files of
        the previous run (listed in its manifest) that are not written again. Returns the folder."""
        for name in files:
            if not name or "/" in name or name in (".", "..", MANIFEST):
                raise ValueError(f"not a plain output file name: {name!r}")
        self.path.mkdir(parents=True, exist_ok=True)  # mode 0777 & ~umask, like mkdir(1)
        self._manifest(self.owned | set(files))
        for name, writer in files.items():
            self._atomic(name, writer)
            self.written.append(name)
        for name in self.owned - set(files):
            (self.path / name).unlink(missing_ok=True)
        self._manifest(files)
        self.owned = set(files)
        return self.path


def claim(path: str | Path, scene: str) -> OutputFolder:
    """Check that ``path`` may receive the outputs of ``scene`` (rules in the module docstring);
    raises :class:`OutputError` otherwise. Creates nothing."""
    given = str(path)
    path = Path(path)
    if path.is_symlink() or (path.exists() and not path.is_dir()):
        kind = ("a symbolic link" if path.is_symlink() else
                "a file, not a folder" if path.is_file() else "a device or special file, not a folder")
        raise OutputError(f"--out {given}: exists and is {kind}; give a new or empty folder")
    if path.is_dir():
        entries = sorted(os.listdir(path))
        manifest = _read_manifest(path) if MANIFEST in entries else None
        if entries and manifest is None:
            shown = ", ".join(entries[:3]) + (f" and {len(entries) - 3} more" if len(entries) > 3 else "")
            raise OutputError(f"--out {given}: the folder holds files this program did not write "
                              f"({shown}); give a new or empty folder")
        owned = set(manifest["files"]) if manifest else set()
        leftovers = {e for e in entries if _is_leftover(e, owned | {MANIFEST})}
        foreign = [e for e in entries if e != MANIFEST and e not in owned | leftovers]
        if foreign:
            raise OutputError(f"--out {given}: the folder holds files this program did not write "
                              f"({', '.join(foreign[:3])}); give a new or empty folder")
        if manifest and manifest.get("scene") != scene:
            raise OutputError(f"--out {given}: the folder holds the results of another scene "
                              f"({manifest.get('scene')}); give a folder of its own, "
                              "e.g. out/<scene name>")
        if not _probe_writable(path):
            raise OutputError(f"--out {given}: the folder is not writable; give another folder")
        return OutputFolder(path, scene, owned | leftovers)
    ancestor = path.absolute().parent
    while not ancestor.exists() and not ancestor.is_symlink():
        ancestor = ancestor.parent
    if not ancestor.is_dir():
        raise OutputError(f"--out {given}: {ancestor} is a file, not a folder; give a path "
                          "under a folder")
    if not _probe_writable(ancestor):
        raise OutputError(f"--out {given}: cannot create it, {ancestor} is not writable; give "
                          "a path under a writable folder")
    return OutputFolder(path, scene)
