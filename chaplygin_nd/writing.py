"""How the project writes a file: whole or not at all, with the mode a plain ``open()`` gives; and
how a command checks, before any work, that it will be able to (beyond the paper).

* :func:`write_atomic` writes through a temporary file beside the target and ``os.replace``: a
  reader never sees half a file, and an interrupted write leaves the old file and no temporary.
* Modes: a new file gets ``0o666 & ~umask``, as ``open(path, "w")`` gives it
  (``tempfile.mkstemp`` gives 0600: the mutation JSONs were once written so); a file
  that is replaced keeps its mode; ``mode=`` forces one (the private caches ask for 0600).
* :func:`write_temporary` is the first half alone (the whole file at its temporary name), for a
  writer that moves several files into place together (:func:`chaplygin_nd.ledger.report.write_files`).
  The temporary name is ``.NAME.XXXXXXXX.tmpSUFFIX``, the target's suffix kept, so that
  ``np.savez`` or ``savefig`` see the format they expect.
* :func:`folder_problem` says why a folder cannot be created or written into, found by really
  creating what the program would create (the missing folders and a file in the last one) and
  removing it again: ``os.access`` says yes to root on ``/proc`` or a read-only mount. Every option
  that names an output folder checks it so before any work (``verify --report-dir``, ``simulate
  --out``, ``bench --out``, the folder of ``first-integrals --json``). :func:`probe_problem` is the
  file part alone, for a folder that exists.
"""

from __future__ import annotations

import os
import secrets
from collections.abc import Callable
from pathlib import Path

__all__ = ["write_atomic", "write_temporary", "folder_problem", "probe_problem"]

_FLAGS = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_CLOEXEC", 0)


def _old_mode(path: Path) -> int | None:
    try:
        return os.stat(path).st_mode & 0o7777
    except (OSError, ValueError):
        return None


def write_temporary(path: str | Path, data: str | bytes | Callable[[Path], object], *,
                    mode: int | None = None, encoding: str = "utf-8") -> Path:
    """Write ``data`` whole into a new temporary file beside ``path`` and return its path, with the
    mode the file at ``path`` should get (module docstring): ``mode`` if given, else the mode of the
    file it replaces, else ``0o666 & ~umask``. ``data`` is a ``str`` (in ``encoding``), ``bytes``,
    or a writer called with the temporary path (``np.savez``, ``fig.savefig``). The caller moves it
    into place (``os.replace``) or removes it; on an error it is removed here and the error raised."""
    path = Path(path)
    keep = mode if mode is not None else _old_mode(path)
    for _ in range(100):
        tmp = path.parent / f".{path.name}.{secrets.token_hex(4)}.tmp{path.suffix}"
        try:
            # 0o666 through the umask: exactly what a plain open() gives a new file; a kept or
            # forced mode is set once the file is written (it may not allow writing)
            fd = os.open(tmp, _FLAGS, 0o666 if keep is None else 0o600)
            break
        except FileExistsError:
            continue
    else:
        raise FileExistsError(f"no free temporary name beside {path}")
    try:
        if callable(data):
            os.close(fd)
            fd = -1
            data(tmp)
        else:
            with os.fdopen(fd, "wb") as fh:
                fd = -1
                fh.write(data.encode(encoding) if isinstance(data, str) else data)
        if keep is not None:
            os.chmod(tmp, keep)
    except BaseException:
        if fd >= 0:
            os.close(fd)
        tmp.unlink(missing_ok=True)
        raise
    return tmp


def write_atomic(path: str | Path, data: str | bytes | Callable[[Path], object], *,
                 mode: int | None = None, encoding: str = "utf-8") -> Path:
    """Write ``data`` to ``path`` whole or not at all (:func:`write_temporary`, then
    ``os.replace``); the folder must exist. Returns ``path``."""
    path = Path(path)
    tmp = write_temporary(path, data, mode=mode, encoding=encoding)
    try:
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    return path


def probe_problem(folder: str | Path) -> str:
    """Why no file can be created in the existing folder ``folder`` (``""`` when one can): a file
    is really created there (as :func:`write_temporary` would) and removed."""
    try:
        tmp = write_temporary(Path(folder) / ".chaplygin-probe", b"", mode=0o600)
    except OSError as exc:
        return exc.strerror or str(exc)
    try:
        tmp.unlink()
    except OSError as exc:
        return f"a file created there cannot be removed ({exc.strerror or exc})"
    return ""


def folder_problem(path: str | Path) -> str:
    """Why ``path`` cannot be a folder this program creates (if missing) and writes files into
    (``""`` when it can), in words that follow ``--option PATH:``. Checked by doing it: the missing
    folders are created, a file is created in the last one, and all of it is removed again (also
    when interrupted: nothing is left that was not there)."""
    path = Path(path)
    if path.is_symlink() and not path.exists():
        return "is a broken symbolic link"
    if path.exists() and not path.is_dir():
        return "exists and is not a folder"
    absolute = path.absolute()
    missing = []
    base = absolute
    while not (base.exists() or base.is_symlink()):
        missing.append(base)
        base = base.parent
    if not base.is_dir():
        return f"cannot create it ({base} is not a folder)"
    created: list[Path] = []
    try:
        for folder in reversed(missing):
            try:
                folder.mkdir()  # 0o777 & ~umask, as the program's own mkdir
            except OSError as exc:
                return f"cannot create it (creating {folder}: {exc.strerror or exc})"
            created.append(folder)
        problem = probe_problem(absolute)
        if problem:
            return (f"cannot create files in it ({problem})" if created else
                    f"the folder is not writable ({problem})")
        return ""
    finally:
        for folder in reversed(created):
            try:
                folder.rmdir()
            except OSError:
                pass  # something else put a file there meanwhile: left as it is
