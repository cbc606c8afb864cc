"""docs/sitegen/theorem.py: the theorem page and its LaTeX twin come from one text and one report."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "docs"))

from sitegen import theorem  # noqa: E402

PAGE = (ROOT / "docs" / "pages" / "theorem.md").read_text(encoding="utf-8")


def _part(name, verdict="holds", method="exact", argued=False):
    return {"name": name, "verdict": verdict, "method": method, "argued": argued}


def _report(wedge_verdict="holds"):
    wedge = {"id": "S6:wedge-integrals", "verdict": wedge_verdict,
             "parts": [_part(f"collapse, n = {n}", wedge_verdict) for n in range(4, 13)]
             + [_part("the identities hold in every dimension", method="argued, not machine-checked: why",
                      argued=True)], "data": None}
    indep = {"id": "S6:wedge-independence", "verdict": "holds",
             "parts": [_part(f"exceptional b, n = {n}") for n in range(5, 9)]
             + [_part("steps (i)-(v) hold in every dimension", method="argued, not machine-checked: because",
                      argued=True)],
             "data": {"rank_table": [{"n": 5, "rank": 6, "expected": 6, "functions": 6, "method": "exact"}]}}
    ej = {"id": "S6:euler-jacobi-n5", "verdict": "holds", "parts": [_part("invariant measure on the quotient")],
          "data": None}
    return [wedge, indep, ej]


def test_every_marker_is_filled_and_the_verdicts_come_from_the_report():
    md = theorem.markdown(PAGE, _report(), 7)
    assert "<!-- ledger:" not in md
    assert "- collapse: *holds* (n = 4..12)" in md
    assert "**argued**: why" in md and "| 5 | 6 | 6 | 6 | exact |" in md
    assert "Row `S6:wedge-independence`: **holds**." in md and "- exceptional b: *holds* (n = 5..8)" in md
    assert "**argued**: because" in md
    assert "seed 7" in md and "{download}`theorem.tex <theorem.tex>`" in md
    failed = theorem.markdown(PAGE, _report("fails"), 7)
    assert "Row `S6:wedge-integrals`: **fails**." in failed and "- collapse: *fails*" in failed


def test_the_latex_twin_says_the_same_and_is_plain_ascii():
    tex = theorem.latex(PAGE, _report(), 7)
    assert tex.startswith(r"\documentclass") and tex.rstrip().endswith(r"\end{document}")
    assert tex.isascii() and "<!--" not in tex and "$$" not in tex
    assert tex.count(r"\begin{itemize}") == tex.count(r"\end{itemize}") > 0
    assert tex.count(r"\begin{enumerate}") == tex.count(r"\end{enumerate}") == 1
    assert r"\item collapse: \emph{holds} (n = 4..12)" in tex and "seed 7" in tex
    body = re.sub(r"\\[{}]", "", tex)
    assert body.count("{") == body.count("}")
    assert tex.count(r"\[") == tex.count(r"\]") == PAGE.count("$$") // 2


def test_a_row_the_page_names_must_be_in_the_report():
    with pytest.raises(KeyError, match="S6:euler-jacobi-n5"):
        theorem.markdown(PAGE, [r for r in _report() if r["id"] != "S6:euler-jacobi-n5"], 7)
    with pytest.raises(KeyError, match="S6:wedge-independence"):
        theorem.markdown(PAGE, [r for r in _report() if r["id"] != "S6:wedge-independence"], 7)
