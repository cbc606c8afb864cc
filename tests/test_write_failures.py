"""A full disk, an exhausted quota or a read-only file system while a command writes: one line,
a non-zero exit, nothing half-written — in every command that writes.

The fault is injected where every writer of the project goes through
(:func:`chaplygin_nd.writing.write_temporary`, under ``write_atomic`` and the output folders), after
the commands' own checks of their folders (which create and remove a probe file): the fault
arrives when the work is done, as a disk that fills meanwhile does.
"""

from __future__ import annotations

import errno
import os

import pytest

from chaplygin_nd import cli, writing

FAULTS = [errno.ENOSPC, errno.EDQUOT, errno.EROFS]

SCENE = """n = 4
a = 0.5
b = 1.0
[initial]
family = "steady-rotation"
seed = 3
[times]
t_end = 1.0
samples = 5
[outputs]
want = ["M", "gamma"]
"""


@pytest.fixture
def faulty(monkeypatch, request):
    """Every write (not the folder probes) fails with the errno of the test's parameter."""
    code = request.param
    real = writing.write_temporary

    def write_temporary(path, data, **kw):
        if os.path.basename(str(path)) == ".chaplygin-probe":
            return real(path, data, **kw)
        raise OSError(code, os.strerror(code), str(path))

    monkeypatch.setattr(writing, "write_temporary", write_temporary)
    return code


def _one_line(capsys, status, *words):
    text = capsys.readouterr().err
    errors = [line for line in text.splitlines() if line.startswith("error: ")]
    assert status != 0 and "Traceback" not in text, text
    assert len(errors) == 1 and text.strip().splitlines()[-1] == errors[0], text  # progress before it
    for w in words:
        assert w in errors[0], errors[0]
    return errors[0]


def _files(folder):
    return sorted(p.name for p in folder.rglob("*"))


@pytest.mark.parametrize("faulty", FAULTS, indirect=True)
def test_simulate(tmp_path, capsys, faulty):
    scene = tmp_path / "s.toml"
    scene.write_text(SCENE)
    status = cli.main(["simulate", str(scene), "--out", str(tmp_path / "o"), "--no-plots"])
    _one_line(capsys, status, os.strerror(faulty))
    assert _files(tmp_path) == ["s.toml"]  # no output folder, no sibling, no lock


@pytest.mark.parametrize("faulty", FAULTS, indirect=True)
def test_first_integrals_json(tmp_path, capsys, faulty):
    out = tmp_path / "table.json"
    status = cli.main(["first-integrals", "3", "1", "--a", "1/2", "--b", "1", "--json", str(out)])
    _one_line(capsys, status, "--json", os.strerror(faulty))
    assert _files(tmp_path) == []


@pytest.mark.parametrize("faulty", FAULTS, indirect=True)
def test_any_command_that_lets_a_storage_error_through(tmp_path, capsys, monkeypatch, faulty):
    """The net of the ``chaplygin`` program: a subcommand whose writer lets the error through
    (as ``verify``, ``bench`` or the mutation tools could on a disk that fills) still ends with
    one line naming the file."""
    import types

    def run(argv):
        writing.write_atomic(tmp_path / "report.json", "{}")

    module = types.ModuleType("fake_command")
    module.run = run
    monkeypatch.setitem(__import__("sys").modules, "fake_command", module)
    monkeypatch.setitem(cli.COMMANDS, "verify", ("fake_command", "run", "a writer"))
    status = cli.main(["verify"])
    _one_line(capsys, status, "report.json", os.strerror(faulty))
    assert _files(tmp_path) == []
