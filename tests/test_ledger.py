"""The ledger covers the paper, verdicts are computed honestly, and the layout rules hold."""

import re
from pathlib import Path

import pytest
import sympy as sp
from chaplygin_nd.ledger.catalog import (
    CLAIMS_PATH,
    PAPER_PATH,
    ROOT,
    all_rows,
    claims_rows,
    discover,
    paper_labels,
)
from chaplygin_nd.ledger.registry import Verdict, registry
from chaplygin_nd.symbolic.exact.identity import rational_identity

x = sp.Symbol("x")
SECTIONING = re.compile(r"^S{1,2}:")


@pytest.fixture(scope="module")
def rows():
    discover()
    return all_rows()


def test_every_claims_id_is_a_ledger_row(rows):
    ids = {r.id for r in rows}
    assert [r.id for r in claims_rows() if r.id not in ids] == []


def test_every_paper_label_has_a_row(rows):
    ids = {r.id for r in rows}
    missing = [lab for lab in paper_labels() if not SECTIONING.match(lab) and lab not in ids]
    assert missing == [], f"paper labels without a ledger row: {missing}"


def test_every_row_names_a_label_or_a_section_object(rows):
    labels = set(paper_labels())
    registered_additions = {i for i, spec in registry().items() if spec.adds}
    for r in rows:
        if r.id in labels or r.id in registered_additions:
            continue
        assert re.match(r"^S\d(\.\d)?:\S+$", r.id) or any(
            r.id.startswith(lab + "-") for lab in labels), f"row {r.id} points nowhere"


def test_registered_proofs_are_ledger_rows(rows):
    ids = {r.id for r in rows}
    assert sorted(set(registry()) - ids) == []


def test_a_row_declared_twice_is_refused(rows, monkeypatch):
    """A row of CLAIMS.md that a proof also declares with ``adds=`` is one row declared twice:
    the ledger refuses it with one message naming both places, instead of keeping either."""
    import importlib

    reg = importlib.import_module("chaplygin_nd.ledger.registry")  # the package exports a function of that name
    spec = reg.registry()["eq:invL3D"]
    monkeypatch.setitem(reg._REGISTRY, "eq:invL3D", reg.ClaimSpec(
        "eq:invL3D", spec.run, spec.uses, "tests.duplicate", ("Section 2.1 — anywhere", "again")))
    with pytest.raises(ValueError, match=r"declared twice: eq:invL3D \(paper/CLAIMS\.md, "
                                         r"'Section 2\.1.*@claim\(adds=\.\.\.\) in tests\.duplicate"):
        all_rows()


def test_an_added_paper_label_sits_in_its_section(rows):
    """A row a proof adds for a labelled equation of the paper (eq:vert-3D, eq:SOnminus1) follows
    the last CLAIMS.md row of its section; the other added rows follow the paper's, in id order."""
    ids = [r.id for r in rows]
    paper = claims_rows()
    labels = set(paper_labels())
    for added in ("eq:vert-3D", "eq:SOnminus1"):
        spec = registry()[added]
        assert spec.adds is not None and added in labels
        last = [r.id for r in paper if r.section == spec.adds[0]][-1]
        assert ids.index(added) == ids.index(last) + 1
    labelled = [i for i, spec in registry().items() if spec.adds and i in labels]
    tail = ids[len(paper) + len(labelled):]
    assert tail == sorted(tail) and all(registry()[i].adds for i in tail)
    assert not hasattr(__import__("chaplygin_nd.ledger.catalog", fromlist=["x"]), "EXTRA_ROWS")


def test_paper_copies_match_shared_originals():
    shared = ROOT.parent / "shared"
    if not shared.exists():  # CI puts shared/ beside the clone; a bare clone has only the copies
        assert PAPER_PATH.exists() and CLAIMS_PATH.exists()
        return
    assert PAPER_PATH.read_bytes() == (shared / "paper" / PAPER_PATH.name).read_bytes()
    assert CLAIMS_PATH.read_bytes() == (shared / "CLAIMS.md").read_bytes()


def test_decide_is_computed_from_the_checks():
    true, false = rational_identity(x - x), rational_identity(x - 1)
    assert Verdict.decide(true).verdict == "holds"
    fixed = Verdict.decide(false, corrected=true, correction_latex="x = 1")
    assert fixed.verdict == "corrected" and "x = " in fixed.counterexample
    assert Verdict.decide(false, corrected=false, correction_latex="x = 2").verdict == "fails"
    assert Verdict.decide(false).verdict == "fails"


def test_parts_take_the_worst_verdict():
    true, false = rational_identity(x - x), rational_identity(x - 1)
    parts = [Verdict.decide(true).as_part("a"), Verdict.decide(false).as_part("b")]
    assert Verdict.of_parts(parts).verdict == "fails"
    assert Verdict.of_parts(parts[:1]).verdict == "holds"


def test_open_needs_a_reason():
    with pytest.raises(ValueError):
        Verdict.open("  ")
    assert Verdict.open("issue #3").verdict == "open"


def _imports(path: Path) -> set[str]:
    text = path.read_text(encoding="utf-8")
    return set(re.findall(r"^\s*(?:from|import)\s+([\w.]+)", text, re.M))


def test_derivations_never_import_printed_formulas():
    offenders = [str(p.relative_to(ROOT)) for p in (ROOT / "symbolic").rglob("*.py")
                 if "printed" not in p.parts and any(m.startswith("chaplygin_nd.symbolic.printed")
                                                     for m in _imports(p))]
    assert offenders == []


@pytest.mark.parametrize("package", ["generated", "simulate"])
def test_numeric_packages_import_no_sympy(package):
    offenders = [str(p.relative_to(ROOT)) for p in (ROOT / package).rglob("*.py")
                 if any(m == "sympy" or m.startswith(("sympy.", "chaplygin_nd.symbolic", "chaplygin_nd.proofs",
                                                           "chaplygin_nd.ledger"))
                        for m in _imports(p))]
    assert offenders == []
