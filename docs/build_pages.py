"""Write the sources of the reading site from the ledger's JSON (``make docs`` runs this, then
``sphinx-build -c docs``): nothing on the site is written by hand but the tutorial texts.

    python docs/build_pages.py [--report verification.json] [--out docs/_build/src]

Writes ``index.md`` (totals, errata, remarks, the claim graph with every node a link), one page
``claims/<page_name(id)>.md`` per ledger row (:mod:`sitegen.claims`), ``api.md``,
``evidence-study.md`` (the last run of ``chaplygin bench evidence``, copied from bench/out) and the
two tutorials executed now (:mod:`sitegen.tutorials`). Exit 2 with one line when the report is
missing or does not match this checkout's ledger (run ``chaplygin verify`` first).
"""

from __future__ import annotations

import argparse
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
from sitegen import claims, tex, tutorials  # noqa: E402


@dataclass
class Context:
    """What every page needs: the rows, the seed, the paper, the maps from ids to sources."""

    rows: list[dict]
    seed: int
    tex_lines: list[str]
    printed_lines: dict[str, set[int]]
    registry: dict
    kernels: dict[str, list[str]]
    tests: dict[str, list[str]]

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


def _table(rows: list[dict], ctx: Context, prefix: str) -> str:
    lines = ["| row | kind | what is wrong, and the exact counterexample |", "|---|---|---|"]
    for r in rows:
        what = "; ".join(f"{p['name']}: {p.get('counterexample') or p['method']}"
                         for p in r["parts"] if p.get("kind")) or (r.get("counterexample") or "")
        lines.append(f"| [{r['id']}]({prefix}{graph.page_name(r['id'])}.md) | {r['kind']} | "
                     f"{claims._cell(what)} |")
    return "\n".join(lines) + "\n"


def index(report: dict, ctx: Context) -> str:
    """The index page: totals, errata and remarks, evidence, the clickable claim graph, all rows."""
    rows = report["rows"]
    summary = ", ".join(f"**{v}** {k}" for k, v in report["summary"].items())
    errata = [r for r in rows if r["kind"] in graph.ERRATA_KINDS]
    remarks = [r for r in rows if r["kind"] and r["kind"] not in graph.ERRATA_KINDS]
    svg = graph.render(_rows_as_results(rows), lambda i: f"claims/{graph.page_name(i)}.html")
    svg = svg[svg.index("<svg"):]
    out = ["# chaplygin-nd: the ledger of the paper, row by row\n",
           "A machine-checked reading of L. C. García-Naranjo, *Integrability of the "
           "n-dimensional axially symmetric Chaplygin sphere* (arXiv:1906.00261). Every page "
           "below is generated from the ledger's report (`verification.json`, seed "
           f"{report['seed']}), the paper's source and the proof scripts.\n",
           f"\n**{len(rows)} rows:** {summary}.\n",
           "\nThe paper is the author's work, included unmodified for verification and not "
           "covered by the project's licence (NOTICE).\n",
           "\n## Errata\n\nA displayed formula (`formula`) or a step of a proof (`proof`) is "
           "false as printed; the row's page shows what is proved instead.\n\n",
           _table(errata, ctx, "claims/"),
           "\n## Remarks\n\nThe statement holds where the paper means it (`scope`: fails on a "
           "case the paper does not exclude; `reading`: ambiguous text).\n\n",
           _table(remarks, ctx, "claims/"),
           "\n## The claim graph\n\nEvery node opens its row's page; an arrow goes from a row to "
           "a row that uses it.\n",
           claims.raw(f'<div class="claim-graph">{svg}</div>'),
           "\n## Every row\n\n| row | section | verdict | kind |\n|---|---|---|---|\n"]
    for r in rows:
        out.append(f"| [{r['id']}](claims/{graph.page_name(r['id'])}.md) | "
                   f"{claims._cell(r['section'])} | {r['verdict']} | {r['kind'] or ''} |\n")
    out.append("\n```{toctree}\n:hidden:\n:maxdepth: 1\n\ntutorials/scene-to-figure\n"
               "tutorials/p-inversion\napi\nevidence-study\n" + "".join(
                   f"claims/{graph.page_name(r['id'])}\n" for r in rows) + "```\n")
    return "".join(out)


def main(argv: list[str] | None = None) -> int:
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
        report_ids = [r["id"] for r in report["rows"]]
    except (OSError, UnicodeDecodeError, ValueError, KeyError, TypeError) as exc:
        print(f"error: {report_path} is not a verification.json of `chaplygin verify` "
              f"({type(exc).__name__}: {exc})", file=sys.stderr)
        return 2

    from chaplygin_nd.ledger.catalog import PAPER_PATH, all_rows, discover
    from chaplygin_nd.ledger.registry import registry

    discover()
    if [r.id for r in all_rows()] != report_ids:
        print(f"error: {report_path} is not the ledger of this checkout: run `chaplygin verify`",
              file=sys.stderr)
        return 2
    names = [graph.page_name(r["id"]) for r in report["rows"]]
    if len(set(names)) != len(names):
        print("error: two rows have the same page name", file=sys.stderr)
        return 2
    ctx = Context(report["rows"], report["seed"],
                  PAPER_PATH.read_text(encoding="utf-8").splitlines(),
                  tex.printed_lines(ROOT / "symbolic" / "printed"), registry(),
                  claims.kernels_by_claim(ROOT / "generated"),
                  claims.tests_by_claim(ROOT / "tests", [r["id"] for r in report["rows"]]))
    out = Path(args.out)
    if out.exists():
        shutil.rmtree(out)
    (out / "claims").mkdir(parents=True)
    (out / "index.md").write_text(index(report, ctx), encoding="utf-8")
    for row in report["rows"]:
        (out / "claims" / f"{graph.page_name(row['id'])}.md").write_text(
            claims.page(row, ctx), encoding="utf-8")
    shutil.copy(DOCS / "pages" / "api.md", out / "api.md")
    # the validation study of the evidence rows' chaos rule (chaplygin bench evidence, issue 24)
    shutil.copy(DOCS / "pages" / "evidence-study.md", out / "evidence-study.md")
    shutil.copy(DOCS / "figures" / "evidence-study.png", out / "evidence-study.png")
    tutorials.execute_all(DOCS / "tutorials", out / "tutorials")
    print(f"wrote {len(report['rows'])} claim pages, the index, the API page and the tutorials "
          f"into {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
