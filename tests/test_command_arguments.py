"""Arguments and written results of the commands, one test each: a negative fraction is an
option's value (``--a -1/3``), the first-integral command's ``--json`` is refused before the
search or written whole, and a formula in a row's notes keeps its ``*`` on the site."""

from __future__ import annotations

import re

import pytest
from cli_helpers import exit_code, one_error_line

from chaplygin_nd.console import OneLineParser


@pytest.mark.parametrize("text", ["-1/3", "-3/2", "-1", "-0.5", "-.5", "-1e-3", "-2.5E+2"])
def test_a_negative_number_or_fraction_is_a_value(text):
    parser = OneLineParser(prog="p")
    parser.add_argument("--a")
    assert parser.parse_args(["--a", text]).a == text


def test_an_option_after_an_option_is_still_missing_its_value(capsys):
    parser = OneLineParser(prog="p")
    parser.add_argument("--a")
    parser.add_argument("--b")
    with pytest.raises(SystemExit):
        parser.parse_args(["--a", "--b", "1"])
    assert "--a: expected one argument" in one_error_line(capsys)


def test_first_integrals_reads_the_documented_negative_a(capsys):
    """symbolic/search/command.py documents ``--a -1/3``; it was refused as a missing value."""
    from chaplygin_nd.symbolic.search.command import main

    assert exit_code(main, ["4", "2", "--a", "-5/3", "--b", "3/2"]) == 2  # parsed, then judged
    assert "a = -5/3 is outside the domain a >= -1" in one_error_line(capsys)


def test_a_formula_in_the_notes_has_no_emphasis_marker(monkeypatch):
    """The notes of S6:sixth-integral-n5 (F = (2*a*b*gamma_5*(M_12*M_34 ...) rendered in italics
    with the products' stars eaten; every ``*`` of report text is escaped for MyST."""
    from chaplygin_nd.ledger.catalog import ROOT

    monkeypatch.syspath_prepend(str(ROOT / "docs"))
    from sitegen import claims

    text = "F = (2*a*b*gamma_5*(M_12*M_34 - M_13*M_24) + x**2)/Delta | w = *(M^M)/2"
    cell = claims._cell(text)
    assert not re.search(r"(?<!\\)[*|]", cell), cell
    assert cell.replace("\\", "") == text


@pytest.mark.parametrize("where, needle", [
    ("", "an empty path"),
    (".", "is a folder"),
    ("no/such/folder/x.json", "no folder"),
])
def test_first_integrals_refuses_a_bad_json_path_before_the_search(tmp_path, monkeypatch, capsys,
                                                                   where, needle):
    """``--json /tmp`` ran the search, then raised IsADirectoryError and left ``/tmpXXXX.tmp``;
    ``--json ''`` wrote nothing without a word; a missing folder raised FileNotFoundError."""
    from chaplygin_nd.symbolic.search.command import main

    monkeypatch.chdir(tmp_path)
    assert exit_code(main, ["4", "1", "--a", "0", "--b", "1", "--json", where]) == 2
    assert needle in one_error_line(capsys)
    assert list(tmp_path.iterdir()) == [] and list(tmp_path.parent.glob("*.tmp")) == []


def test_first_integrals_json_is_written_whole(tmp_path, monkeypatch):
    import json

    from chaplygin_nd.symbolic.search.command import main

    monkeypatch.chdir(tmp_path)
    assert exit_code(main, ["4", "1", "--a", "-1/3", "--b", "3/2", "--json", "t.json"]) == 0
    assert [p.name for p in tmp_path.iterdir()] == ["t.json"]
    (row,) = json.loads((tmp_path / "t.json").read_text())
    assert row["n"] == 4 and row["d"] == 1 and row["settled"]
