"""How the project writes a file: whole or not at all, with the mode a plain ``open()`` gives
(issue 25; beyond the paper).

* :func:`write_atomic` writes through a temporary file beside the target and ``os.replace``: a
  reader never sees half a file, and an interrupted write leaves the old file and no temporary.
* Modes: a new file gets ``0o666 & ~umask``, as ``open(path, "w")`` gives it
  (``tempfile.mkstemp`` gives 0600: the round-22 trial found the mutation JSONs written so); a file
  that is replaced keeps its mode; ``mode=`` forces one (the private caches ask for 0600).
* :func:`write_temporary` is the first half alone (the whole file at its temporary name), for a
  writer that moves several files into place together (:func:`chaplygin_nd.ledger.report.write_files`).
  The temporary name is ``.NAME.XXXXXXXX.tmpSUFFIX``, the target's suffix kept, so that
  ``np.savez`` or ``savefig`` see the format they expect.
"""

from __future__ import annotations

import os
import secrets
from collections.abc import Callable
from pathlib import Path

__all__ = ["write_atomic", "write_temporary"]

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
