"""Write the sources of the reading site from the ledger's JSON (``make docs`` runs this, then
``sphinx-build -c docs``): nothing on the site is written by hand but the tutorial texts and
the manual (``docs/pages/``, each page written once; the README links to them).

    python docs/build_pages.py [--report verification.json] [--out docs/_build/src]

Writes ``index.md`` (totals, errata and remarks typeset, the claim graph with every node a link,
the rows grouped by the paper's sections and then *Beyond the paper* (:mod:`sitegen.sections`),
and the sidebar's toctrees), one page ``claims/<page_name(id)>.md`` per ledger row
(:mod:`sitegen.claims`), the manual (``docs/pages/``, copied; the theorem page filled from the
report and written again as ``pages/theorem.tex``, :mod:`sitegen.theorem`; with the evidence
rules' validation study ``pages/evidence-study.md`` that ``chaplygin bench evidence`` writes) and the two tutorials executed now (:mod:`sitegen.tutorials`). Exit 2 with one line when the report is
missing or does not match this checkout's ledger (run ``chaplygin verify`` first).

The site reads the report and the paper only: the proof, the printed functions, the paper's lines,
the kernels and the tests of a row come from its ``sources`` record, written by the run
(:mod:`chaplygin_nd.ledger.sources`); no proof or printed module is imported here.
"""

from __future__ import annotations

import argparse
import html
import json
import shutil
import sys
from dataclasses import dataclass
from pathlib import Path
from types import SimpleNamespace

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(DOCS))

from chaplygin_nd.ledger import graph  # noqa: E402
from sitegen import claims, sections, theorem, tutorials  # noqa: E402


@dataclass
class Context:
    """What every page needs: the rows, the seed, the paper, the maps from ids to sources."""

    rows: list[dict]
    seed: int
    tex_lines: list[str]
    printed_lines: dict[str, set[int]]
    paper_sections: list[str]
    paper_ids: set[str]

    def __post_init__(self):
        self.ids = {r["id"] for r in self.rows}
        self.order = [r["id"] for r in self.rows]
        self.uses = {r["id"]: [u for u in r["uses"] if u in self.ids] for r in self.rows}
        self.fills = {r["id"]: claims.fill(r) for r in self.rows}

    def md_link(self, cid: str) -> str:
        """A MyST link from one claim page to another."""
        return f"[{cid}]({graph.page_name(cid)}.md)"

    def html_link(self, label: str) -> str:
        """HTML for a ``\\ref`` in the paper: a link when the label is a ledger row."""
        if label in self.ids:
            return f'<a href="{graph.page_name(label)}.html">{label}</a>'
        return label


def _rows_as_results(rows: list[dict]):
    """The JSON rows with the attributes :func:`ledger.graph.draw` reads."""
    return [SimpleNamespace(row=SimpleNamespace(id=r["id"]), uses=tuple(r["uses"]),
                            status=r["verdict"], verdict=SimpleNamespace(kind=r["kind"]))
            for r in rows]


def _findings(row: dict) -> list[dict]:
    """The row itself when it carries the printed formula, the correction or the counterexample,
    else its parts that do (a row of parts keeps them on the parts)."""
    keys = ("printed_latex", "correction_latex")
    if any(row.get(k) for k in keys):
        return [dict(row, name="")]
    return [p for p in row["parts"] if p.get("kind") and any(p.get(k) for k in keys)]


def _findings_table(rows: list[dict], prefix: str) -> str:
    """Errata or remarks: each finding as printed, what is proved instead and the exact
    counterexample, typeset by MathJax (raw HTML: MyST tables cannot hold display maths)."""
    head = ("<tr><th>row</th><th>kind</th><th>as printed</th><th>proved instead</th>"
            "<th>exact counterexample to the text as printed</th></tr>")
    body = []
    for r in rows:
        link = f'<a href="{prefix}{graph.page_name(r["id"])}.html">{html.escape(r["id"])}</a>'
        for f in _findings(r) or [dict(r, name="")]:
            name = f'<br><span class="part">{html.escape(f["name"])}</span>' if f["name"] else ""
            body.append(f"<tr><td>{link}{name}</td><td>{html.escape(r['kind'] or '')}</td>"
                        f"<td>{claims.math(f.get('printed_latex'))}</td>"
                        f"<td>{claims.math(f.get('correction_latex'))}</td>"
                        f"<td>{claims.counterexample(f)}</td></tr>")
    return claims.raw(f'<div class="table-wrap"><table class="findings mathjax_process">{head}'
                      f'{"".join(body)}</table></div>')


def _section_table(section: sections.Section, prefix: str, paper_ids: set[str]) -> str:
    lines = ["| row | statement | verdict |", "|---|---|---|"]
    for r in section.rows:
        verdict = r["verdict"] + (f" ({r['kind']})" if r["kind"] else "")
        added = " *(added)*" if r["id"] not in paper_ids else ""
        lines.append(f"| [{r['id']}]({prefix}{graph.page_name(r['id'])}.md) | "
                     f"{claims._cell(r['claim'])}{added} | {verdict} |")
    return "\n".join(lines) + "\n"


MANUAL = (("pages/verdicts", "Verdicts, kinds and reports"),
          ("pages/engines", "The two exact engines"),
          ("pages/printed", "Printed formulas, reach and mutation"),
          ("pages/evidence", "Evidence: Section 5's dynamics, measured"),
          ("pages/evidence-study", "Evidence: the chaos rule's validation study"),
          ("pages/open-problem", "Beyond the paper: the open problem for n ≥ 5"),
          ("pages/theorem", "Beyond the paper: the theorem"),
          ("pages/hamiltonisation", "Beyond the paper: a Hamiltonisation on P"),
          ("pages/scenes", "Scenes and the planner"),
          ("pages/accuracy", "Accuracy, cross-check and output folders"),
          ("pages/caches", "Caches"),
          ("pages/benchmarks", "Kernels and benchmarks"),
          ("pages/decisions", "Decisions that shape the code"),
          ("pages/site", "About this site"),
          ("tutorials/scene-to-figure", None), ("tutorials/p-inversion", None),
          ("pages/api", None))

_FILTER = """<div class="claim-filter"><label for="claim-filter">Find a claim by words of its
statement:</label> <input id="claim-filter" type="search" placeholder="e.g. inverse, measure, torus"
autocomplete="off"> <span id="claim-filter-count"></span></div>
<script>
document.addEventListener("DOMContentLoaded", function () {
  var box = document.getElementById("claim-filter"), count = document.getElementById("claim-filter-count");
  var rows = Array.prototype.slice.call(document.querySelectorAll(".claims-by-section tbody tr"));
  box.addEventListener("input", function () {
    var words = box.value.toLowerCase().split(/\\s+/).filter(Boolean), shown = 0;
    rows.forEach(function (tr) {
      var text = tr.textContent.toLowerCase();
      var hit = words.every(function (w) { return text.indexOf(w) >= 0; });
      tr.style.display = hit ? "" : "none"; shown += hit;
    });
    count.textContent = words.length ? shown + " of " + rows.length + " rows" : "";
  });
});
</script>"""


def _toctrees(groups: list[sections.Section]) -> str:
    """Hidden toctrees: they make the sidebar, one caption per section, each row as
    ``id — short title``."""
    out = ["\n```{toctree}\n:hidden:\n:caption: How it works\n:maxdepth: 1\n\n"]
    out += [f"{title} <{doc}>\n" if title else f"{doc}\n" for doc, title in MANUAL]
    out.append("```\n")
    for s in groups:
        caption = f"{sections.BEYOND}: {s.title}" if s.beyond else s.title
        out.append(f"\n```{{toctree}}\n:hidden:\n:caption: {caption}\n:maxdepth: 1\n\n")
        for r in s.rows:
            title = sections.short_title(r["claim"]).replace("<", "‹").replace(">", "›")
            out.append(f"{r['id']} — {title} <claims/{graph.page_name(r['id'])}>\n")
        out.append("```\n")
    return "".join(out)


def index(report: dict, ctx: Context) -> str:
    """The index page: totals, errata and remarks typeset, the claim graph, the rows grouped by
    the paper's sections (then the rows beyond the paper), the manual."""
    rows = report["rows"]
    summary = ", ".join(f"**{v}** {k}" for k, v in report["summary"].items())
    errata = [r for r in rows if r["kind"] in graph.ERRATA_KINDS]
    remarks = [r for r in rows if r["kind"] and r["kind"] not in graph.ERRATA_KINDS]
    svg = graph.render(_rows_as_results(rows), lambda i: f"claims/{graph.page_name(i)}.html")
    svg = svg[svg.index("<svg"):]
    out = ["# chaplygin-nd: the ledger of the paper, row by row\n",
           "A machine-checked reading of L. C. García-Naranjo, *Integrability of the "
           "n-dimensional axially symmetric Chaplygin sphere* (arXiv:1906.00261). Every claim "
           "page is generated from the ledger's report (`verification.json`, seed "
           f"{report['seed']}), the paper's source and the proof scripts; the pages under "
           "*How it works* in the sidebar are the manual.\n",
           f"\n**{len(rows)} rows:** {summary}.\n",
           "\nThe paper is the author's work, included unmodified for verification and not "
           "covered by the project's licence (NOTICE).\n",
           "\n## Errata\n\nA displayed formula (`formula`) or a step of a proof (`proof`) is "
           "false as printed: the paper's text, the proved correction and the exact "
           "counterexample.\n",
           _findings_table(errata, "claims/"),
           "\n## Remarks\n\nThe statement holds where the paper means it (`scope`: fails on a "
           "case the paper does not exclude; `reading`: ambiguous text).\n",
           _findings_table(remarks, "claims/"),
           "\n## The claim graph\n\nEvery node opens its row's page; an arrow goes from a row to "
           "a row that uses it.\n",
           claims.raw(f'<div class="claim-graph">{svg}</div>'),
           "\n## The claims, section by section\n\n",
           claims.raw(_FILTER)]
    groups = sections.group(rows, ctx.paper_sections)
    beyond_started = False
    for s in groups:
        if s.beyond and not beyond_started:
            beyond_started = True
            out.append(f"\n## {sections.BEYOND}\n\nRows this project adds: they answer questions "
                       "the paper leaves open, or certify what the kernels evaluate. They are "
                       "never mixed with the paper's claims.\n")
        out.append(f"\n({s.anchor})=\n{'####' if s.beyond else '###'} {s.title}\n\n")
        out.append("```{container} claims-by-section\n" + _section_table(s, "claims/", ctx.paper_ids) + "```\n")
    out.append(_toctrees(groups))
    return "".join(out)


def _stale(rows: list[dict], paper_ids: list[str]) -> str:
    """Why the report is not of this checkout ("" when it is): a row of CLAIMS.md missing, a row
    without its ``sources`` record (a report of an older run), or a proof whose recorded source is
    no longer at its recorded lines (the proof changed since the run)."""
    ids = {r["id"] for r in rows}
    missing = [i for i in paper_ids if i not in ids]
    if missing:
        return f"no row {', '.join(missing[:3])}"
    for r in rows:
        if "sources" not in r:
            return f"row {r['id']} has no sources record"
        proof = r["sources"]["proof"]
        if proof is None:
            continue
        path = ROOT / proof["path"]
        first, last = proof["lines"]
        lines = path.read_text(encoding="utf-8").splitlines(keepends=True) if path.is_file() else []
        if "".join(lines[first - 1:last]) != proof["source"]:
            return f"{proof['path']} changed since the run (row {r['id']})"
    return ""


def main(argv: list[str] | None = None) -> int:
    from chaplygin_nd.cache import place_matplotlib_cache

    place_matplotlib_cache()  # before the tutorials import matplotlib: not ~/.config/matplotlib
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--report", default=str(ROOT / "verification.json"))
    ap.add_argument("--out", default=str(DOCS / "_build" / "src"))
    args = ap.parse_args(argv)
    report_path = Path(args.report)
    if not report_path.is_file():
        print(f"error: {report_path} is missing: run `chaplygin verify` first", file=sys.stderr)
        return 2
    try:
        report = json.loads(report_path.read_text(encoding="utf-8"))
        if not all(r["id"] and isinstance(r["sources"], dict) for r in report["rows"]):
            raise ValueError("a row without id or sources")
    except (OSError, UnicodeDecodeError, ValueError, KeyError, TypeError) as exc:
        print(f"error: {report_path} is not a verification.json of `chaplygin verify` "
              f"({type(exc).__name__}: {exc})", file=sys.stderr)
        return 2

    from chaplygin_nd.ledger.catalog import CLAIMS_PATH, PAPER_PATH, claims_rows

    stale = _stale(report["rows"], [r.id for r in claims_rows()])
    if stale:
        print(f"error: {report_path} is not the ledger of this checkout ({stale}): run "
              "`chaplygin verify`", file=sys.stderr)
        return 2
    names = [graph.page_name(r["id"]) for r in report["rows"]]
    if len(set(names)) != len(names):
        print("error: two rows have the same page name", file=sys.stderr)
        return 2
    ctx = Context(report["rows"], report["seed"],
                  PAPER_PATH.read_text(encoding="utf-8").splitlines(),
                  {r["id"]: set(r["sources"]["paper_lines"]) for r in report["rows"]},
                  sections.paper_sections(CLAIMS_PATH.read_text(encoding="utf-8")),
                  {r.id for r in claims_rows()})
    out = Path(args.out)
    if out.exists():
        shutil.rmtree(out)
    (out / "claims").mkdir(parents=True)
    (out / "index.md").write_text(index(report, ctx), encoding="utf-8")
    for row in report["rows"]:
        (out / "claims" / f"{graph.page_name(row['id'])}.md").write_text(
            claims.page(row, ctx), encoding="utf-8")
    shutil.copytree(DOCS / "pages", out / "pages")
    page = (DOCS / "pages" / "theorem.md").read_text(encoding="utf-8")   # and its LaTeX twin
    (out / "pages" / "theorem.md").write_text(theorem.markdown(page, report["rows"], report["seed"]),
                                              encoding="utf-8")
    (out / "pages" / "theorem.tex").write_text(theorem.latex(page, report["rows"], report["seed"]),
                                               encoding="utf-8")
    shutil.copytree(DOCS / "figures", out / "figures")
    tutorials.execute_all(DOCS / "tutorials", out / "tutorials")
    print(f"wrote {len(report['rows'])} claim pages, the index, the manual and the tutorials "
          f"into {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
