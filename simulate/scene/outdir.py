"""The output folder of a run: whole or marked incomplete, never mixed; only files this program owns.

Rules (checked by :func:`claim` *before* any computation, so a refusal costs nothing and touches
nothing):

* the folder may be new (its nearest existing ancestor must be a writable folder), empty, or a
  folder this program wrote before for the *same scene*: it then holds a manifest
  ``.chaplygin-run.json`` listing the files written, and only those files may be replaced;
* anything else is refused with a one-line :class:`OutputError`: an existing file or device
  (``/dev/null``), a folder holding files the program did not write (a user's ``thesis.tex``,
  or ``.`` with its contents), a folder that belongs to another scene, a read-only folder, a path
  under an existing file, a read-only parent, a name longer than the file system allows;
* one run at a time: :func:`claim` takes an exclusive lock keyed by the folder's real path: a
  hidden file ``.NAME.chaplygin-lock`` beside the folder (where the staging sibling goes too), or,
  when that parent is read-only, a ``flock`` on the existing folder itself (no file at all). The
  lock file is removed when the run ends, written or refused (nothing is left outside the output
  folder and the project's cache); a second run into the same folder is refused with one line
  while the first holds it. The place depends only on the parent's writability, so every run
  into one folder looks in the same place whatever its environment (``TMPDIR``, the cache).

Writes (:meth:`OutputFolder.write`), whole or nothing:

* when the parent folder is writable, every file goes into a new hidden sibling folder
  ``.NAME.chaplygin-new-XXXX`` whose manifest (``"status": "complete"``) is written last; the
  sibling then takes the place of the folder in one atomic exchange (Linux ``renameat2``
  ``RENAME_EXCHANGE``; elsewhere two renames) and the previous result is removed file by file
  (only names its manifest lists). An interrupted run leaves the previous result untouched and a
  hidden sibling that the next run into the same folder removes;
* otherwise (an existing empty folder, or a folder in a read-only parent) the files are written in
  place: the manifest says ``"status": "incomplete"`` first (listing the old and the new names, the
  old files are removed before any new one is written), ``"complete"`` last. An interrupted run
  leaves a folder that says it is incomplete; a rerun repairs it.

Files and folders get the permissions of ordinary new ones (the process umask applies). Nothing is
ever deleted that a manifest of this program does not list.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import errno
import fcntl
import json
import os
import re
import tempfile
import uuid
from collections.abc import Callable, Iterable
from pathlib import Path

from chaplygin_nd.writing import probe_problem, write_atomic

__all__ = ["MANIFEST", "OutputError", "OutputFolder", "claim", "lock_file", "SIBLING"]

MANIFEST = ".chaplygin-run.json"
PROGRAM = "chaplygin-nd simulate"
SIBLING = ".chaplygin-new-"


class OutputError(Exception):
    """``--out`` names a place this program may not write to; the message says why and what to do."""


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _probe_writable(folder: Path) -> bool:
    """True when a file can really be created in ``folder`` (``os.access`` alone is wrong for
    root, which bypasses permission bits but not read-only mounts); the probe file is removed
    (:func:`chaplygin_nd.writing.probe_problem`, the check of every output option)."""
    return not probe_problem(folder)


def _read_manifest(folder: Path) -> dict | None:
    path = folder / MANIFEST
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError, RecursionError):
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


def _remove_owned(folder: Path) -> None:
    """Remove a folder this program wrote (a sibling or a replaced result): the files its manifest
    lists, their temporaries and the manifest; the folder itself only when that emptied it."""
    manifest = _read_manifest(folder)
    owned = set(manifest["files"]) if manifest else set()
    # the manifest goes last: an interruption in between leaves a folder still recognised as ours
    for entry in sorted(os.listdir(folder), key=lambda e: e == MANIFEST):
        if entry in owned or entry == MANIFEST or _is_leftover(entry, owned | {MANIFEST}):
            (folder / entry).unlink(missing_ok=True)
    try:
        folder.rmdir()
    except OSError:
        pass  # something not ours is in it: left as it is


def _exchange(a: Path, b: Path) -> bool:
    """Swap two paths atomically (Linux renameat2 RENAME_EXCHANGE); False when not supported."""
    name = ctypes.util.find_library("c")
    try:
        libc = ctypes.CDLL(name, use_errno=True)
        renameat2 = libc.renameat2
    except (OSError, AttributeError, TypeError):
        return False
    at_fdcwd, rename_exchange = -100, 2
    r = renameat2(at_fdcwd, os.fsencode(a), at_fdcwd, os.fsencode(b), rename_exchange)
    if r == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.EINVAL, errno.ENOSYS, errno.ENOTSUP, errno.EOPNOTSUPP):
        return False
    raise OSError(err, os.strerror(err), str(b))


LOCK = ".chaplygin-lock"


def lock_file(path: str | Path) -> Path:
    """The file whose exclusive ``flock`` marks a run writing into the output folder ``path``: a
    hidden sibling of its real path (module docstring); while held it holds ``"<pid> <real
    path>"``, and it is removed when the run ends."""
    real = Path(os.path.realpath(path))
    return real.parent / f".{real.name}{LOCK}"


def _looks_like_a_lock(content: bytes) -> bool:
    """Empty (just created, or its run was killed between create and write) or ``"<pid> <path>\\n"``
    as :class:`_Lock` writes it."""
    return content == b"" or re.fullmatch(rb"\d+ /.*\n", content, re.S) is not None


class _Lock:
    """An exclusive lock on an output folder, keyed by its real path (see the module docstring)."""

    def __init__(self, path: Path, given: str):
        real = os.path.realpath(path)
        self.file: Path | None = lock_file(path)
        self.fd: int | None = None
        self.created: list[Path] = []  # missing parents made for the lock, removed if left empty
        missing = []
        for folder in self.file.parents:
            if folder.exists():
                break
            missing.append(folder)
        try:
            for folder in reversed(missing):
                folder.mkdir()  # 0o777 & ~umask, as the write would make it
                self.created.append(folder)
        except OSError as exc:
            self.release()
            raise OutputError(f"--out {given}: cannot create {folder} ({exc.strerror or exc}); "
                              "give a path under a writable folder") from None
        busy = OutputError(f"--out {given}: another run is writing into this folder now; "
                           "wait for it to end or give another folder")
        if not _probe_writable(self.file.parent):  # a read-only parent: lock the folder itself
            self.file = None
            self.fd = os.open(real, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
            if not self._flock():
                raise busy
            return
        while True:
            try:  # never through a symbolic link: the lock file is ours or nothing
                fd = os.open(self.file, os.O_RDWR | os.O_CREAT | getattr(os, "O_CLOEXEC", 0)
                             | getattr(os, "O_NOFOLLOW", 0), 0o600)
            except OSError as exc:
                self.release()
                raise OutputError(f"--out {given}: cannot open the lock file {self.file} "
                                  f"({exc.strerror or exc}); remove it if no run holds it") from None
            self.fd = fd
            if not self._flock():
                raise busy
            try:  # the file may have been removed by the run that held it: lock the new one
                same = os.path.samestat(os.fstat(fd), os.stat(self.file))
            except FileNotFoundError:
                same = False
            if same:
                break
            os.close(fd)
            self.fd = None
        if not _looks_like_a_lock(os.pread(fd, 4096, 0)):  # a file we did not write: keep it
            os.close(fd)
            self.fd = None
            self.file = None
            self.release()
            raise OutputError(f"--out {given}: {lock_file(path)} exists and is not a lock file of "
                              "chaplygin-nd; it is left as it is (move it, or give another folder)")
        os.ftruncate(fd, 0)
        os.write(fd, f"{os.getpid()} {real}\n".encode())

    def _flock(self) -> bool:
        assert self.fd is not None
        try:
            fcntl.flock(self.fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            os.close(self.fd)
            self.fd = None
            return False
        return True

    def release(self) -> None:
        """Remove the lock file (still holding it, so no other run has it yet) and drop the lock."""
        fd = getattr(self, "fd", None)
        if fd is not None:
            if self.file is not None:
                try:
                    self.file.unlink()
                except OSError:
                    pass  # gone already, or the parent turned read-only: the flock still ends
            os.close(fd)
            self.fd = None
        for folder in reversed(getattr(self, "created", [])):
            try:
                folder.rmdir()  # only if the run left it empty (refused or interrupted)
            except OSError:
                break
        self.created = []

    __del__ = release


class OutputFolder:
    """A folder :func:`claim` found safe to write to; ``owned`` are the names it may replace."""

    def __init__(self, path: Path, scene: str, owned: Iterable[str] = (), lock: _Lock | None = None):
        self.path = path
        self.scene = scene
        self.owned = set(owned)
        self.written: list[str] = []
        self.lock = lock
        self.run_id = uuid.uuid4().hex[:12]

    def release(self) -> None:
        """Drop the lock (the run is over)."""
        if self.lock is not None:
            self.lock.release()

    def _manifest(self, folder: Path, names: Iterable[str], status: str) -> None:
        data = {"program": PROGRAM, "scene": self.scene, "status": status, "run": self.run_id,
                "files": sorted(set(names))}
        self._atomic(folder, MANIFEST, lambda p: p.write_text(json.dumps(data, indent=1) + "\n",
                                                              encoding="utf-8"))

    @staticmethod
    def _atomic(folder: Path, name: str, writer: Callable[[Path], object]) -> None:
        write_atomic(folder / name, writer)  # '.NAME.XXXXXXXX.tmpSUFFIX' until it is whole

    def write(self, files: dict[str, Callable[[Path], None]]) -> Path:
        """Write every ``name -> writer(path)`` of ``files`` (rules in the module docstring);
        returns the folder. The lock is released when the write ends (written or not)."""
        try:
            return self._write(files)
        finally:
            self.release()

    def _write(self, files: dict[str, Callable[[Path], None]]) -> Path:
        for name in files:
            if not name or "/" in name or name in (".", "..", MANIFEST):
                raise ValueError(f"not a plain output file name: {name!r}")
        parent = self.path.absolute().parent
        parent.mkdir(parents=True, exist_ok=True)  # mode 0777 & ~umask, like mkdir(1)
        if self.path.is_dir() and not self.owned or not _probe_writable(parent):
            return self._write_in_place(files)
        staging = Path(tempfile.mkdtemp(prefix=f".{self.path.name}{SIBLING}", dir=parent))
        try:
            os.chmod(staging, 0o777 & ~_umask())
            self._manifest(staging, files, "incomplete")  # so that a rerun may remove it
            for name, writer in files.items():
                self._atomic(staging, name, writer)
                self.written.append(name)
            self._manifest(staging, files, "complete")
            if not self.path.exists():
                os.rename(staging, self.path)
            elif _exchange(staging, self.path):
                _remove_owned(staging)  # the previous result, now at the sibling's name
            else:
                old = parent / f".{self.path.name}{SIBLING}old-{self.run_id}"
                os.rename(self.path, old)
                os.rename(staging, self.path)
                _remove_owned(old)
        except BaseException:
            if staging.exists():
                _remove_owned(staging)
            raise
        self.owned = set(files)
        return self.path

    def _write_in_place(self, files) -> Path:
        self.path.mkdir(exist_ok=True)
        self._manifest(self.path, self.owned | set(files), "incomplete")
        for name in self.owned:
            (self.path / name).unlink(missing_ok=True)
        for name, writer in files.items():
            self._atomic(self.path, name, writer)
            self.written.append(name)
        self._manifest(self.path, files, "complete")
        self.owned = set(files)
        return self.path


def _check_names(path: Path, given: str) -> None:
    """Refuse a component longer than the file system allows (before any computation)."""
    ancestor = path.absolute()
    while not ancestor.exists():
        ancestor = ancestor.parent
    try:
        limit = os.pathconf(ancestor if ancestor.is_dir() else ancestor.parent, "PC_NAME_MAX")
    except (OSError, ValueError):
        limit = 255
    for part in path.parts:
        if len(os.fsencode(part)) + len(SIBLING) + 12 > limit:
            raise OutputError(f"--out {given}: the name {part[:40]}... is longer than this file "
                              f"system allows ({limit} bytes, with room for a temporary name); "
                              "give a shorter name")


def claim(path: str | Path, scene: str) -> OutputFolder:
    """Check that ``path`` may receive the outputs of ``scene`` (rules in the module docstring)
    and lock it; raises :class:`OutputError` otherwise. Creates nothing in the user's folders;
    call :meth:`OutputFolder.release` when the run is over."""
    given = str(path)
    path = Path(path)
    _check_names(path, given)
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
        folder = OutputFolder(path, scene, owned | leftovers, _Lock(path, given))
        _remove_siblings(path)
        return folder
    ancestor = path.absolute().parent
    while not ancestor.exists() and not ancestor.is_symlink():
        ancestor = ancestor.parent
    if not ancestor.is_dir():
        raise OutputError(f"--out {given}: {ancestor} is a file, not a folder; give a path "
                          "under a folder")
    if not _probe_writable(ancestor):
        raise OutputError(f"--out {given}: cannot create it, {ancestor} is not writable; give "
                          "a path under a writable folder")
    folder = OutputFolder(path, scene, (), _Lock(path, given))
    _remove_siblings(path)
    return folder


def _remove_siblings(path: Path) -> None:
    """Remove the hidden staging folders an interrupted run into ``path`` left (called under the
    lock, so no other run is writing them)."""
    parent = path.absolute().parent
    if not parent.is_dir():
        return
    prefix = f".{path.name}{SIBLING}"
    for entry in os.listdir(parent):
        candidate = parent / entry
        if entry.startswith(prefix) and candidate.is_dir() and not candidate.is_symlink():
            _remove_owned(candidate)
