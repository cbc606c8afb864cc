"""CITATION.cff is valid Citation File Format 1.2.0 and cites this version and the paper."""

from __future__ import annotations

import re
from pathlib import Path

import yaml

import chaplygin_nd

ROOT = Path(__file__).resolve().parent.parent
CFF = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
TEX = (ROOT / "paper" / "chaplygin-sphere-nd.tex").read_text(encoding="utf-8")


def _valid_person(p: dict) -> bool:
    """CFF 1.2.0: a person has ``family-names`` (or ``given-names``), an entity has ``name``."""
    return isinstance(p, dict) and bool(p.get("family-names") or p.get("given-names") or p.get("name"))


def test_required_fields_of_cff_1_2_0():
    assert CFF["cff-version"] == "1.2.0"
    for key in ("message", "title", "authors"):  # the keys the 1.2.0 schema requires
        assert isinstance(CFF[key], str | list) and CFF[key], key
    assert CFF["authors"] and all(_valid_person(p) for p in CFF["authors"])
    assert CFF["type"] in ("software", "dataset")


def test_version_is_the_package_version():
    assert str(CFF["version"]) == chaplygin_nd.__version__


def test_licence_matches_pyproject():
    pyproject = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
    assert f'license = "{CFF["license"]}"' in pyproject
    assert (ROOT / "LICENSE").read_text(encoding="utf-8").startswith("BSD 3-Clause License")


def test_the_paper_is_a_reference_with_the_title_and_author_of_the_tex():
    (paper,) = [r for r in CFF["references"] if r["type"] == "article"]
    assert all(_valid_person(p) for p in paper["authors"]) and "year" in paper
    title = re.search(r"\\title\{(.*?)\\footnote", TEX).group(1)
    assert paper["title"] == re.sub(r"\$n\$", "n", title).strip()
    author = re.search(r"\\author\{(.*?)\}", TEX).group(1)
    assert "Naranjo" in author and paper["authors"][0]["family-names"] == "García-Naranjo"
    notice = (ROOT / "NOTICE").read_text(encoding="utf-8")
    assert paper["title"] in notice.replace("\n    ", " ") and "not covered" in notice.lower()
