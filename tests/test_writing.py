"""Files written atomically get the mode a plain open() gives (0o666 & ~umask) or keep the mode of the
file they replace (chaplygin_nd/writing.py; the round-22 trial found the mutation JSONs written
0600 by tempfile.mkstemp)."""

from __future__ import annotations

import contextlib
import json
import os
import stat

import pytest
from chaplygin_nd.ledger.reach import write_json_atomic

from chaplygin_nd.writing import write_atomic, write_temporary


@contextlib.contextmanager
def umask(mask: int):
    old = os.umask(mask)
    try:
        yield
    finally:
        os.umask(old)


def mode(path) -> int:
    return stat.S_IMODE(os.stat(path).st_mode)


def plain_open_mode(tmp_path, mask: int) -> int:
    """The mode ``open(path, "w")`` gives a new file under ``mask``: the reference."""
    with umask(mask):
        ref = tmp_path / f"plain-{mask:o}"
        ref.write_text("x")
    return mode(ref)


@pytest.mark.parametrize("mask", [0o022, 0o002, 0o077])
def test_write_json_atomic_gives_the_mode_of_a_plain_open(tmp_path, mask):
    target = tmp_path / "mutation.json"
    with umask(mask):
        write_json_atomic({"b": 1, "a": [2]}, target)
    assert mode(target) == plain_open_mode(tmp_path, mask) == 0o666 & ~mask
    assert json.loads(target.read_text()) == {"a": [2], "b": 1}
    assert target.read_text().endswith("\n")
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        ["mutation.json", f"plain-{mask:o}"])  # no temporary left


@pytest.mark.parametrize("old", [0o640, 0o604, 0o444])
def test_write_json_atomic_keeps_the_mode_of_the_file_it_replaces(tmp_path, old):
    target = tmp_path / "mutation.json"
    target.write_text("{}\n")
    os.chmod(target, old)
    with umask(0o077):  # the umask does not narrow a kept mode
        write_json_atomic({"x": 1}, target)
    assert mode(target) == old
    assert json.loads(target.read_text()) == {"x": 1}


@pytest.mark.parametrize("data", ["text ✓\n", b"\x00bytes", "writer"])
def test_write_atomic_takes_text_bytes_or_a_writer(tmp_path, data):
    target = tmp_path / "out.npz"
    seen = []

    def writer(p):
        seen.append(p)
        assert p.name.startswith(".out.npz.") and p.name.endswith(".tmp.npz")
        p.write_bytes(b"from the writer")

    with umask(0o022):
        write_atomic(target, writer if data == "writer" else data)
    expected = (b"from the writer" if data == "writer" else
                data.encode() if isinstance(data, str) else data)
    assert target.read_bytes() == expected and mode(target) == 0o644
    assert [p.name for p in tmp_path.iterdir()] == ["out.npz"]


def test_forced_mode_and_no_temporary_left_on_error(tmp_path):
    target = tmp_path / "entry.pkl"
    write_atomic(target, b"secret", mode=0o600)
    assert mode(target) == 0o600

    def broken(p):
        p.write_bytes(b"half")
        raise RuntimeError("writer failed")

    with pytest.raises(RuntimeError):
        write_atomic(target, broken)
    assert target.read_bytes() == b"secret"  # the old file, whole
    assert [p.name for p in tmp_path.iterdir()] == ["entry.pkl"]
    tmp = write_temporary(target, "new")
    assert tmp.parent == tmp_path and tmp.read_text() == "new" and mode(tmp) == 0o600
