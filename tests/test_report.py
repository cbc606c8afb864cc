"""The report: kinds, remarks and argued parts are counted and shown; the seed flows through the
workers and is recorded; a stale generated/ cannot give a clean-looking report; the Markdown keeps
prose out of the math; the claim graph is drawn deterministically."""

import json
import os
import re

import chaplygin_nd.ledger.__main__ as cli
import pytest
import sympy as sp
from chaplygin_nd.ledger import graph, report
from chaplygin_nd.ledger.catalog import Row
from chaplygin_nd.ledger.registry import KINDS, NEEDS_KIND, VERDICTS, Part, Verdict
from chaplygin_nd.ledger.runner import Result, run, select
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.exact.identity import Check, Counterexample, rational_identity

x = sp.Symbol("x")
TRUE, FALSE = rational_identity(x - x), rational_identity(x - 1)

#: Cheap rows (a second or two each), some of them seeded, one corrected.
FAST_ROWS = ("K:Delta", "eq:motion-n4", "S5:ku", "eq:PrincMinors", "eq:inverse-Leg",
             "P:n3special:case-OmegaE3")


def _result(row_id: str, verdict: Verdict, uses=()) -> Result:
    return Result(Row(row_id, "Section X", f"claim {row_id}"), verdict, 0.01, "chaplygin_nd.proofs.x", tuple(uses))


def _matrix_counterexample() -> Check:
    cx = Counterexample((("gamma2", sp.Rational(3, 5)), ("gamma1", sp.Rational(4, 5)),
                         ("k", sp.Matrix([[0, sp.Rational(1, 2), 0]])), ("a", sp.Rational(1, 3))),
                        sp.Rational(7, 9), "component 1")
    return Check(False, "exact", cx)


def _sample_results() -> list[Result]:
    wrong = _matrix_counterexample()
    formula = Verdict.decide(wrong, corrected=TRUE, kind="formula", printed_latex=r"p = -F_1^2",
                             correction_latex=r"p = +F_1^2")
    same = Verdict.decide(wrong, corrected=TRUE, kind="formula", printed_latex=r"p = -F_1^2",
                          correction_latex=r"p = +F_1^2")
    scope = Verdict.decide(wrong, corrected=TRUE, kind="scope", printed_latex=r"\dim = 1",
                           correction_latex=r"\dim = 1 \text{ off } k = 0",
                           remark="holds off the point k = 0")
    argued = Part("an argued step", "holds", "argued in prose", argued=True)
    return [
        _result("A", Verdict.decide(TRUE)),
        _result("B", Verdict.of_parts([formula.as_part("first"), same.as_part("second"),
                                       Verdict.decide(TRUE).as_part("fine")]), uses=("A",)),
        _result("C", Verdict.of_parts([scope.as_part("isotropy"), argued]), uses=("B",)),
        _result("D", Verdict.decide(TRUE, remark="equal up to the constant 2 the proof names"),
                uses=("C", "A")),
    ]


def test_every_verdict_and_kind_is_described():
    assert set(VERDICTS) <= set(report.VERDICT_TEXT)
    assert set(KINDS) <= set(report.KIND_TEXT)
    assert set(NEEDS_KIND) <= set(VERDICTS)


def test_kind_is_kept_only_on_a_finding_and_must_be_known():
    assert Verdict.decide(TRUE, kind="formula").kind is None
    assert Verdict.decide(FALSE, kind="proof").kind == "proof"
    assert Verdict.all_of([("x", FALSE)], kind="scope").kind == "scope"
    with pytest.raises(ValueError):
        Verdict.decide(FALSE, kind="typo")


def test_a_row_of_parts_takes_the_most_serious_kind_of_its_findings():
    reading = Verdict.decide(FALSE, corrected=TRUE, correction_latex="x = 1", kind="reading")
    proof = Verdict.decide(FALSE, corrected=TRUE, correction_latex="x = 1", kind="proof")
    row = Verdict.of_parts([reading.as_part("r"), proof.as_part("p")])
    assert row.verdict == "corrected" and row.kind == "proof"


def test_a_finding_without_a_kind_is_an_error_of_the_ledger():
    results = [_result("ok", Verdict.decide(TRUE)),
               _result("bad", Verdict.decide(FALSE, corrected=TRUE, correction_latex="x = 1"))]
    assert report.missing_kind(results) == ["bad"]


def test_totals_count_kinds_and_argued_parts():
    line = report.summary(_sample_results())
    assert "2 holds, 2 corrected" in line
    assert "[1 formula, 1 scope]" in line
    assert "1 part argued, not machine-checked" in line


def test_markdown_keeps_prose_out_of_math_and_shows_each_formula_once(tmp_path):
    path = tmp_path / "VERIFICATION.md"
    report.write_markdown(_sample_results(), path, report.RunInfo(seed=5, generated="up to date"))
    text = path.read_text(encoding="utf-8")
    assert "seed 5" in text and "Matrix(" not in text
    displays = re.findall(r"^\$\$\n(.*?)\n\$\$$", text, flags=re.M | re.S)
    assert displays and all("\n" not in d for d in displays)          # one formula per display
    assert not any(re.match(r"^[\w ]+:", d) for d in displays)         # no label inside the math
    for finding in text.split("\n### ")[1:]:                          # each formula once a row
        shown = re.findall(r"^\$\$\n(.*?)\n\$\$$", finding, flags=re.M | re.S)
        assert len(shown) == len(set(shown))
    assert "the formula shown above" in text
    assert r"\gamma = (\tfrac{4}{5}, \tfrac{3}{5})" in text            # components as a vector
    assert "## Errata (formula, proof)" in text and "## Remarks" in text
    errata = text.split("## Errata")[1].split("## Remarks")[0]
    remarks = text.split("## Remarks")[1].split("## All rows")[0]
    assert "`B`" in errata and "`C`" not in errata
    assert "`C`" in remarks and "`D`" in remarks and "constant 2" in remarks
    assert "`C`: an argued step" in text


def test_a_stale_generated_folder_gives_a_report_that_says_stale(tmp_path, monkeypatch):
    import chaplygin_nd.symbolic.codegen.kernels as codegen

    real_select = cli.select
    monkeypatch.setattr(cli, "ROOT", tmp_path)
    monkeypatch.setattr(cli, "select", lambda ids: real_select(["K:Delta", "eq:motion-n4"]))
    monkeypatch.setattr(codegen, "stale_report", lambda: "generated/x.py differs")
    assert cli.main(["--check-generated", "--jobs", "1", "--seed", "11"]) == 1
    md = (tmp_path / "VERIFICATION.md").read_text(encoding="utf-8")
    assert md.splitlines()[2].startswith("> **STALE")
    data = json.loads((tmp_path / "verification.json").read_text(encoding="utf-8"))
    assert data["generated"] == "STALE" and data["seed"] == 11 and data["problems"]
    assert (tmp_path / report.GRAPH_PATH).exists()


def test_two_seeds_give_the_same_verdicts_and_the_seed_reaches_the_workers():
    rows = select(list(FAST_ROWS))
    first, second = (run(rows, jobs=2, seed=s) for s in (points.DEFAULT_SEED, 7))
    assert [r.status for r in first] == [r.status for r in second]
    assert [r.verdict.kind for r in first] == [r.verdict.kind for r in second]
    leg = {r.row.id: r for r in second}["eq:inverse-Leg"]
    assert "(seed 7)" in leg.verdict.method                 # drawn in a worker with seed 7
    assert points.ledger_seed() == points.DEFAULT_SEED      # the parent's seed is untouched


def test_rows_start_longest_first_and_come_back_in_ledger_order(monkeypatch):
    from chaplygin_nd.ledger import runner

    ids = ["a", "b", "c", "d"]
    assert runner.longest_first(ids, {"b": 3.0, "d": 9.0, "a": 0.5}) == ["d", "b", "c", "a"]
    assert runner.longest_first(ids, {}) == ids                 # no timings: ledger order
    # ``also`` (verify's regeneration of generated/) is handed out first, not after every row
    # (then it ran alone after the last one)
    order = runner.hand_out_order(ids, {"b": 3.0, "d": 9.0, "a": 0.5}, also=True)
    assert order == [runner.ALSO_TASK, "d", "b", "c", "a"]
    assert runner.hand_out_order(ids, {}, also=False) == ids
    # the stored timings make the slowest fast row start first, yet the results, and the
    # verdicts, are those of the ledger order
    rows = select(list(FAST_ROWS))
    seen: list[str] = []
    timings = {row.id: float(k) for k, row in enumerate(rows)}   # the last row is the "longest"
    monkeypatch.setattr(runner, "stored_seconds", lambda: timings)
    beside: list = []
    results = run(rows, jobs=2, on_result=lambda r: seen.append(r.row.id), also=os.getpid,
                  on_also=beside.append)
    assert [r.row.id for r in results] == [row.id for row in rows]
    assert sorted(seen) == sorted(row.id for row in rows)
    assert len(beside) == 1 and beside[0] != os.getpid()   # ``also`` ran once, in a worker
    in_order = run(rows, jobs=1, also=os.getpid, on_also=beside.append)
    assert beside[1:] == [os.getpid()]                     # in one process: here, after the rows
    assert [r.status for r in results] == [r.status for r in in_order]
    assert [r.verdict.method for r in results] == [r.verdict.method for r in in_order]


def test_stored_timings_are_read_and_a_bad_map_means_ledger_order(monkeypatch):
    from chaplygin_nd.ledger import reach, runner

    assert runner.stored_seconds()                      # the committed ledger/reach.json
    monkeypatch.setattr(reach, "load", lambda: ({}, ["not", "a", "dict"]))
    assert runner.stored_seconds() == {}

    def broken():
        raise ValueError("damaged")

    monkeypatch.setattr(reach, "load", broken)
    assert runner.stored_seconds() == {}


def test_uses_cycles_are_split_and_the_graph_is_layered():
    ids = ["a", "b", "c", "d"]
    uses = {"a": ("b",), "b": ("a",), "c": ("a", "b"), "d": ("c", "e")}
    acyclic, back = graph.split_cycles(ids, uses)
    assert back == [("a", "b")] and acyclic["b"] == ["a"]
    assert graph.layers(ids, acyclic) == {"a": 0, "b": 1, "c": 2, "d": 3}


def test_rows_resting_on_an_erratum_are_found():
    resting = graph.rests_on_erratum(_sample_results())
    assert resting == {"C": "formula", "D": "formula"}


def test_claim_graph_svg_is_deterministic(tmp_path):
    path = tmp_path / "g.svg"
    results = _sample_results()
    assert graph.write(results, path) is True
    first = path.read_bytes()
    assert graph.write(results, path) is False and path.read_bytes() == first
    assert b"<svg" in first and b"B" in first


def test_committed_claim_graph_names_every_ledger_row():
    """docs/claim-graph.svg is tracked (README links it); a row added since the last `make verify`
    that was committed is missing from it. (Verdict colours are checked by verify, which redraws.)"""
    from chaplygin_nd.ledger.catalog import ROOT, all_rows, discover

    discover()
    svg = (ROOT / report.GRAPH_PATH).read_text(encoding="utf-8")
    labels = set(re.findall(r"<text[^>]*>([^<]*)</text>", svg))
    missing = [r.id for r in all_rows() if r.id not in labels]
    assert missing == [], f"run `make verify` and commit {report.GRAPH_PATH}; missing {missing}"


def test_the_json_records_what_the_site_shows_of_each_row():
    """verification.json carries each row's sources (the site reads them instead of importing
    proofs, printed modules, generated/ or tests/): the @claim function at its recorded lines, the
    printed functions it called with their source, the .tex lines of the transcription, the
    kernels whose Claims: line names it, and the tests that name it."""
    from chaplygin_nd.ledger.catalog import ROOT

    results = run(select(["K:Delta", "eq:inverse-Leg"]), jobs=1)
    info = report.RunInfo(seed=points.DEFAULT_SEED, commit="x", started="now", generation="g",
                          generated="not checked", problems=(), graph="")
    rows = {r["id"]: r for r in json.loads(report.json_text(results, info))["rows"]}
    for cid, row in rows.items():
        proof = row["sources"]["proof"]
        assert proof["module"] == row["proof_module"] and proof["path"].startswith("proofs/")
        first, last = proof["lines"]
        text = (ROOT / proof["path"]).read_text(encoding="utf-8").splitlines(keepends=True)
        assert "".join(text[first - 1:last]) == proof["source"]
        assert f'@claim("{cid}"' in proof["source"] and proof["doc"]
    kernels = rows["K:Delta"]["sources"]["kernels"]
    assert "axisym.Delta" in kernels, kernels              # the form K:Delta certifies
    leg = rows["eq:inverse-Leg"]
    assert leg["printed"] and [p["name"] for p in leg["sources"]["printed"]] == leg["printed"]
    assert all(p["path"].startswith("symbolic/printed/") and "def " in p["source"]
               for p in leg["sources"]["printed"])
    assert leg["sources"]["paper_lines"]
    assert any(t.startswith("tests/") for t in leg["sources"]["tests"] + rows["K:Delta"]["sources"]["tests"])


def test_the_graph_import_beside_the_rows_ends_with_matplotlib_ready():
    from chaplygin_nd.ledger import graph

    thread = graph.import_beside()
    thread.join(timeout=120)
    assert not thread.is_alive() and thread.daemon
    import matplotlib

    assert matplotlib.get_backend().lower() == "agg"
