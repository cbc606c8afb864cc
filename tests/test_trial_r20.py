"""Defects found by a new user's trial of the merged r20 round (notes/r20-trial.md), one test each:
``verify --report-dir`` never replaces report files it did not write, ``mutate --compare`` reads
its file before the run, worker counts must be positive, the notebook API refuses complex,
non-finite and n < 3 input, and ``chaplygin docs -h`` is help, not a report path."""

from __future__ import annotations

import json

import pytest
from chaplygin_nd.ledger.__main__ import _report_paths

from chaplygin_nd import cli


def _exit_code(call, argv) -> int:
    """The exit status of ``call(argv)``, whether it returns it or argparse exits with it."""
    try:
        return call(argv)
    except SystemExit as exc:
        return exc.code


def _one_error_line(capsys) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: "), err
    return err[0]


# verify --report-dir: a file the program did not write is refused before any proof runs
@pytest.mark.parametrize("name, text", [
    ("VERIFICATION.md", "my own notes\n"),
    ("verification.json", '{"mine": 1}'),
    ("verification.json", "not json"),
    ("claim-graph.svg", "<svg/>"),           # no verification.json of ours beside it
])
def test_report_dir_refuses_files_it_did_not_write(tmp_path, capsys, name, text):
    (tmp_path / name).write_text(text)
    assert _exit_code(cli.main, ["verify", "--report-dir", str(tmp_path)]) == 2
    line = _one_error_line(capsys)
    assert name in line and "not written by `chaplygin verify`" in line, line
    assert (tmp_path / name).read_text() == text
    assert sorted(p.name for p in tmp_path.iterdir()) == [name]


def test_report_dir_refuses_a_symlink(tmp_path, capsys):
    other = tmp_path / "elsewhere.md"
    other.write_text("keep")
    folder = tmp_path / "reports"
    folder.mkdir()
    (folder / "VERIFICATION.md").symlink_to(other)
    assert _report_paths(str(folder), whole=True) == 2
    assert "VERIFICATION.md" in _one_error_line(capsys)
    assert (folder / "VERIFICATION.md").is_symlink() and other.read_text() == "keep"


def test_report_dir_accepts_its_own_earlier_reports(tmp_path):
    (tmp_path / "VERIFICATION.md").write_text("# Verification ledger\n\nWritten by ...\n")
    (tmp_path / "verification.json").write_text(json.dumps({"generation": "x", "rows": []}))
    (tmp_path / "claim-graph.svg").write_text("<svg/>")
    md, js, svg = _report_paths(str(tmp_path), whole=True)
    assert (md.name, js.name, svg.name) == ("VERIFICATION.md", "verification.json",
                                            "claim-graph.svg")
    assert _report_paths(str(tmp_path / "new"), whole=True)[0].parent == tmp_path / "new"
