"""One MyST page per ledger row, from the row of verification.json and the sources it names.

Nothing on a page is written by hand: the verdict, method, n, seconds, seed, parts and
counterexamples come from the JSON; the statement from the .tex (:mod:`sitegen.tex`); the proof
from the claim script (``inspect``); the kernels from the ``Claims:`` lines of generated/; the
tests from the test files that name the row.
"""

from __future__ import annotations

import ast
import html
import inspect
import re
from pathlib import Path

from chaplygin_nd.ledger import graph

from sitegen import svg, tex

VERDICT_NOTE = {
    "holds": "proved exactly", "definition": "a definition, checked for consistency",
    "corrected": "false as printed; a correction is proved", "evidence": "numerical evidence "
    "for a qualitative statement (never counted as holds)", "open": "not decided",
    "fails": "false, no correction proved", "error": "the proof raised an exception"}


def fill(row: dict) -> str:
    """The node colour of the claim graph for a row of the JSON."""
    if row.get("kind"):
        return graph.KIND_COLOUR[row["kind"]]
    return graph.VERDICT_COLOUR.get(row["verdict"], "#ffffff")


def raw(text: str) -> str:
    return "\n```{raw} html\n" + text + "\n```\n"


def code(text: str, lang: str = "python") -> str:
    fence = "````" if "```" in text else "```"
    return f"\n{fence}{lang}\n{text.rstrip()}\n{fence}\n"


def kernels_by_claim(generated: Path) -> dict[str, list[str]]:
    """claim id -> ``module.function`` of generated/ whose docstring's ``Claims:`` line names it."""
    out: dict[str, list[str]] = {}
    for path in sorted(generated.glob("*.py")):
        for node in ast.parse(path.read_text(encoding="utf-8")).body:
            if isinstance(node, ast.FunctionDef) and not node.name.startswith("_"):
                doc = ast.get_docstring(node) or ""
                m = re.search(r"Claims:\s*([^\n]*?)\.?(?:\s+Operations|\n|$)", doc)
                for cid in (c.strip() for c in (m.group(1).split(",") if m else [])):
                    out.setdefault(cid, []).append(f"{path.stem}.{node.name}")
    return out


def tests_by_claim(tests: Path, ids: list[str]) -> dict[str, list[str]]:
    """claim id -> ``file::test`` of every test function whose source contains the id in quotes."""
    out: dict[str, list[str]] = {}
    for path in sorted(tests.glob("test_*.py")):
        text = path.read_text(encoding="utf-8")
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, ast.FunctionDef) and node.name.startswith("test"):
                body = ast.get_source_segment(text, node) or ""
                for cid in ids:
                    if f'"{cid}"' in body or f"'{cid}'" in body:
                        out.setdefault(cid, []).append(f"tests/{path.name}::{node.name}")
    return out


def _proof_source(spec) -> tuple[str, str]:
    """(module docstring, source of the ``@claim`` function) of a registered proof."""
    module = inspect.getmodule(spec.run)
    return inspect.getdoc(module) or "", inspect.getsource(spec.run)


def _badge(row: dict, seed) -> str:
    v = row["verdict"]
    kind = f'<span class="kind kind-{row["kind"]}">kind: {row["kind"]}</span>' if row["kind"] else ""
    argued = '<span class="kind">has argued parts</span>' if row.get("argued") else ""
    ns = ", ".join(str(n) for n in row["n_values"]) or "—"
    return (f'<div class="badge-row"><span class="verdict verdict-{v}" '
            f'style="background:{fill(row)}">{v}</span>{kind}{argued}'
            f'<span class="meta">{html.escape(VERDICT_NOTE.get(v, ""))}</span></div>'
            f'<table class="facts"><tr><th>method</th><td>{html.escape(row["method"])}</td></tr>'
            f'<tr><th>backed for n</th><td>{ns}</td></tr>'
            f'<tr><th>seconds</th><td>{row["seconds"]}</td></tr>'
            f'<tr><th>seed</th><td>{seed}</td></tr>'
            f'<tr><th>proof module</th><td><code>{html.escape(row["proof_module"] or "—")}</code>'
            "</td></tr></table>")


def _parts(row: dict) -> str:
    if not row["parts"]:
        return ""
    lines = ["\n## Parts: as printed, and what is proved instead\n",
             "| part | verdict | kind | method | exact counterexample to the printed text |",
             "|---|---|---|---|---|"]
    for p in row["parts"]:
        cells = [p["name"], f"**{p['verdict']}**" + (" (argued)" if p.get("argued") else ""),
                 p.get("kind") or "", p["method"], p.get("counterexample") or ""]
        lines.append("| " + " | ".join(_cell(c) for c in cells) + " |")
    return "\n".join(lines) + "\n"


def _cell(text: str) -> str:
    return html.escape(str(text).replace("|", "\\|").replace("\n", " "), quote=False) or " "


def _printed_sources(names: list[str]) -> str:
    """Source of the symbolic/printed functions the row called (the literal transcription)."""
    import importlib

    out = []
    for name in names:
        module, _, func = name.partition(".")
        try:
            obj = getattr(importlib.import_module(f"chaplygin_nd.symbolic.printed.{module}"), func)
            out.append(f"# chaplygin_nd.symbolic.printed.{name}\n" + inspect.getsource(obj))
        except (ImportError, AttributeError, TypeError, OSError):
            out.append(f"# chaplygin_nd.symbolic.printed.{name}: source not found")
    return "\n".join(out)


def page(row: dict, ctx) -> str:
    """The MyST source of the page of ``row`` (``ctx``: see :class:`build_pages.Context`)."""
    cid = row["id"]
    link = ctx.html_link
    out = [f"({graph.page_name(cid)})=\n# {cid}\n",
           f"*{html.escape(row['section'])}* — {_cell(row['claim'])}\n",
           raw(_badge(row, ctx.seed))]
    if row.get("notes"):
        out.append(f"\n**Notes.** {_cell(row['notes'])}\n")
    if row.get("remark"):
        out.append(f"\n**Remark.** {_cell(row['remark'])}\n")
    out.append("\n## The paper's statement\n")
    found = tex.passages(ctx.tex_lines, cid, ctx.printed_lines)
    if not found:
        out.append("\nNo passage of the paper carries this row's label or was transcribed for it: "
                   "it is a row this project added, or a claim of the prose (see the claim above).\n")
    for p in found:
        text = "\n".join(ctx.tex_lines[p.first - 1:p.last])
        out.append(f"\nchaplygin-sphere-nd.tex, lines {p.first}–{p.last} ({html.escape(p.how)}):\n")
        out.append(raw('<div class="statement mathjax_process">' + tex.to_html(text, link) + "</div>"))
    if row.get("counterexample"):
        out.append(f"\n**Exact counterexample to the text as printed:** {_cell(row['counterexample'])}\n")
    out.append(_parts(row))
    if row["printed"]:
        out.append("\n## As printed: the literal transcription used\n")
        out.append(code(_printed_sources(row["printed"])))
    if row.get("evidence"):
        out.append("\n## Evidence: measured, the control, and the rule fixed beforehand\n")
        ev = row["evidence"]
        lines = ["| field | value |", "|---|---|"]
        for key in ("measured", "initial_conditions", "tolerance", "contradiction", "control",
                    "control_separates"):
            if key in ev:
                lines.append(f"| {key} | {_cell(ev[key])} |")
        out.append("\n".join(lines) + "\n")
        out.append("\nFigures: `chaplygin simulate tori4d` draws the Poincaré section and writes "
                   "`frequencies.json` (not built with the site).\n")
    spec = ctx.registry.get(cid)
    if spec is not None:
        doc, source = _proof_source(spec)
        out.append(f"\n## The proof: `{spec.module}`\n")
        if doc:
            out.append(code(doc, "text"))
        out.append("\nThe `@claim` function that decides the row:\n")
        out.append(code(source))
    out.append("\n## Uses and used by\n")
    uses = [u for u in row["uses"] if u in ctx.ids]
    used_by = [r["id"] for r in ctx.rows if cid in r["uses"]]
    out.append("\n**Uses:** " + (", ".join(ctx.md_link(u) for u in uses) or "nothing") + "\n")
    out.append("\n**Used by:** " + (", ".join(ctx.md_link(u) for u in used_by) or "no row") + "\n")
    if uses:
        out.append("\nEvery row it rests on (an arrow goes from a row to a row that uses it):\n")
        out.append(raw('<div class="graph">' + svg.subgraph(
            cid, ctx.order, ctx.uses, ctx.fills, lambda i: f"{graph.page_name(i)}.html") + "</div>"))
    out.append("\n## Kernels and tests\n")
    kernels = ctx.kernels.get(cid, [])
    out.append("\n**Generated kernels that implement it** (generated/, `Claims:` line): "
               + (", ".join(f"`{k}`" for k in kernels) or "none") + "\n")
    tests = ctx.tests.get(cid, [])
    out.append("\n**Tests that name this row:** " + (", ".join(f"`{t}`" for t in tests) or "none")
               + "\n")
    return "".join(out)
