"""One MyST page per ledger row, from the row of verification.json and the sources it names.

Nothing on a page is written by hand: the verdict, method, n, seconds, seed, parts and
counterexamples come from the JSON; the statement from the .tex (:mod:`sitegen.tex`); the proof,
the printed functions, the kernels and the tests from the row's ``sources`` record, which the run
wrote (:mod:`chaplygin_nd.ledger.sources`).
"""

from __future__ import annotations

import html
import re

from chaplygin_nd.ledger import graph

from sitegen import sections, svg, tex

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


def math(latex: str | None, display: bool = False) -> str:
    """HTML for MathJax: ``\\( … \\)`` (or ``\\[ … \\]``) around the escaped LaTeX; empty when none."""
    if not latex:
        return ""
    open_, close = (r"\[", r"\]") if display else (r"\(", r"\)")
    return open_ + html.escape(latex.strip().strip("$")) + close


def counterexample(finding: dict) -> str:
    """The exact counterexample of a row or a part: typeset when the report has its LaTeX."""
    if finding.get("counterexample_latex"):
        return math(finding["counterexample_latex"])
    return html.escape(finding.get("counterexample") or "")


def split_top(text: str, sep: str) -> list[str]:
    """``text`` split at ``sep`` outside parentheses, brackets and braces."""
    out, depth, start, i = [], 0, 0, 0
    while i < len(text):
        ch = text[i]
        if ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth = max(0, depth - 1)
        elif depth == 0 and text.startswith(sep, i):
            out.append(text[start:i])
            start = i + len(sep)
            i = start
            continue
        i += 1
    out.append(text[start:])
    return [s.strip() for s in out if s.strip()]


def _clauses(method: str) -> tuple[list[str], str]:
    """The ``; ``-separated clauses of a method, each once, and the engines clause apart."""
    engines, out = "", []
    for clause in split_top(method, "; "):
        if clause.startswith("engines:"):
            engines = clause[len("engines:"):].strip()
        elif clause.rstrip(";") not in out:
            out.append(clause.rstrip(";"))
    return out, engines


def checks(row: dict) -> tuple[list[tuple[str, list[str]]], list[str], str]:
    """The method of a row as a list of checks ``(what, [how, ...])`` — one per part when the
    row has parts, else one per clause of its method — with every clause once; a long
    parenthesis that several checks share is moved to a footnote (returned second, each cited
    as ``[k]``); the engines (third) are listed once for the row."""
    _, engines = _clauses(row["method"])
    items: list[tuple[str, list[str]]] = []
    if row.get("parts"):
        for p in row["parts"]:
            hows, _ = _clauses(p["method"])
            items.append((p["name"], hows))
    else:
        hows, _ = _clauses(row["method"])
        for how in hows:
            head = split_top(how, ": ")
            if len(head) > 1 and len(head[0]) < 90:
                items.append((head[0], [": ".join(head[1:])]))
            else:
                items.append(("", [how]))
    counts: dict[str, int] = {}
    for _, hows in items:
        for how in hows:
            for par in set(re.findall(r"\([^()]{40,}(?:\([^()]*\)[^()]*)*\)", how)):
                counts[par] = counts.get(par, 0) + 1
    notes = [par for par, c in counts.items() if c > 1]
    for i, par in enumerate(notes, 1):
        items = [(what, [how.replace(par, f"[{i}]") for how in hows]) for what, hows in items]
    return items, [par[1:-1] for par in notes], engines


def checks_html(row: dict) -> str:
    """The checks of a row as an HTML list: what is checked, how (for which n), the engines."""
    items, notes, engines = checks(row)
    lis = []
    for what, hows in items:
        lead = f"<strong>{html.escape(what)}</strong>: " if what else ""
        lis.append(f"<li>{lead}{html.escape('; '.join(hows))}</li>")
    if engines:
        lis.append(f"<li><strong>engines</strong>: {html.escape(engines)}</li>")
    foot = "".join(f'<p class="check-note">[{i}] {html.escape(n)}</p>'
                   for i, n in enumerate(notes, 1))
    return '<ul class="checks">' + "".join(lis) + "</ul>" + foot


def _badge(row: dict, seed) -> str:
    v = row["verdict"]
    kind = f'<span class="kind kind-{row["kind"]}">kind: {row["kind"]}</span>' if row["kind"] else ""
    argued = '<span class="kind">has argued parts</span>' if row.get("argued") else ""
    ns = ", ".join(str(n) for n in row["n_values"]) or "—"
    return (f'<div class="badge-row"><span class="verdict verdict-{v}" '
            f'style="background:{fill(row)}">{v}</span>{kind}{argued}'
            f'<span class="meta">{html.escape(VERDICT_NOTE.get(v, ""))}</span></div>'
            f'<table class="facts"><tr><th>checks</th><td>{checks_html(row)}</td></tr>'
            f'<tr><th>backed for n</th><td>{ns}</td></tr>'
            f'<tr><th>seconds</th><td>{row["seconds"]}</td></tr>'
            f'<tr><th>seed</th><td>{seed}</td></tr>'
            f'<tr><th>proof module</th><td><code>{html.escape(row["proof_module"] or "—")}</code>'
            "</td></tr></table>")


def _parts(row: dict) -> str:
    """The parts: verdict, kind and — typeset — the text as printed, what is proved instead and
    the exact counterexample (each part's checks are in the list of checks above)."""
    if not row["parts"]:
        return ""
    typeset = any(p.get(k) for p in row["parts"]
                  for k in ("printed_latex", "correction_latex", "counterexample_latex",
                            "counterexample"))
    head = "<tr><th>part</th><th>verdict</th><th>kind</th>" + (
        "<th>as printed</th><th>proved instead (correction)</th><th>exact counterexample</th>"
        if typeset else "") + "</tr>"
    body = []
    for p in row["parts"]:
        verdict = f"<strong>{html.escape(p['verdict'])}</strong>" + (" (argued)" if p.get("argued") else "")
        cells = (f"<td>{math(p.get('printed_latex'))}</td><td>{math(p.get('correction_latex'))}</td>"
                 f"<td>{counterexample(p)}</td>") if typeset else ""
        body.append(f"<tr><td>{html.escape(p['name'])}</td><td>{verdict}</td>"
                    f"<td>{html.escape(p.get('kind') or '')}</td>{cells}</tr>")
    title = ("\n## Parts: as printed, and what is proved instead\n" if typeset
             else "\n## Parts\n\nEach part's checks are listed above; every part holds as printed.\n"
             if all(p["verdict"] in ("holds", "definition") for p in row["parts"])
             else "\n## Parts\n")
    return title + raw(f'<div class="table-wrap"><table class="parts mathjax_process">{head}'
                       f'{"".join(body)}</table></div>')


def _correction(row: dict) -> str:
    """For a finding: the paper's formula, the proved correction and the counterexample, typeset
    side by side (from the row, or from each part that carries them)."""
    found = [dict(row, name="")] if row.get("correction_latex") or row.get("printed_latex") else \
        [p for p in row["parts"] if p.get("correction_latex") or p.get("printed_latex")]
    if not found:
        return ""
    blocks = []
    for f in found:
        name = f'<p class="part-name">{html.escape(f["name"])}</p>' if f["name"] else ""
        blocks.append(f'{name}<div class="correction-grid">'
                      f'<div><h4>As printed</h4>{math(f.get("printed_latex"), True)}</div>'
                      f'<div><h4>Proved instead</h4>{math(f.get("correction_latex"), True)}</div>'
                      f'<div><h4>Exact counterexample</h4>{counterexample(f)}</div></div>')
    return ("\n## The correction\n\nThe paper's text as printed, the correction this row proves, "
            "and an exact point where the printed text fails.\n"
            + raw('<div class="correction mathjax_process">' + "".join(blocks) + "</div>"))


def _cell(text: str) -> str:
    """Plain text of the report on one Markdown line: ``|`` and ``*`` escaped (the products
    ``2*a*b*gamma_5`` of a formula in the notes were read as emphasis), HTML escaped."""
    text = str(text).replace("|", "\\|").replace("*", "\\*").replace("\n", " ")
    return html.escape(text, quote=False) or " "


def _printed_sources(records: list[dict]) -> str:
    """Source of the symbolic/printed functions the row called (the literal transcription), as
    the run recorded it."""
    return "\n".join(f"# chaplygin_nd.symbolic.printed.{p['name']} ({p['path']}, lines "
                     f"{p['lines'][0]}–{p['lines'][1]})\n" + p["source"] if "source" in p
                     else f"# chaplygin_nd.symbolic.printed.{p['name']}: source not found"
                     for p in records)


def page(row: dict, ctx) -> str:
    """The MyST source of the page of ``row`` (``ctx``: see :class:`build_pages.Context`)."""
    cid = row["id"]
    link = ctx.html_link
    title = sections.short_title(row["claim"])
    added = "" if cid in ctx.paper_ids else " (a row this project adds)"
    out = [f"({graph.page_name(cid)})=\n# {cid} — {_cell(title)}\n",
           f"*{html.escape(row['section'])}*{added}"
           + ("" if title == row["claim"].strip() else f" — {_cell(row['claim'])}") + "\n",
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
    if row["verdict"] in ("corrected", "fails"):
        out.append(_correction(row))
    elif row.get("counterexample"):
        out.append(f"\n**Exact counterexample to the text as printed:** {_cell(row['counterexample'])}\n")
    out.append(_parts(row))
    if row["printed"]:
        out.append("\n## As printed: the literal transcription used\n")
        out.append(code(_printed_sources(row["sources"]["printed"])))
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
    proof = row["sources"]["proof"]
    if proof is not None:
        out.append(f"\n## The proof: `{proof['module']}`\n")
        if proof["doc"]:
            out.append(code(proof["doc"], "text"))
        first, last = proof["lines"]
        out.append(f"\nThe `@claim` function that decides the row ({proof['path']}, lines "
                   f"{first}–{last}):\n")
        out.append(code(proof["source"]))
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
    kernels = row["sources"]["kernels"]
    out.append("\n**Generated kernels that implement it** (generated/, `Claims:` line): "
               + (", ".join(f"`{k}`" for k in kernels) or "none") + "\n")
    tests = row["sources"]["tests"]
    out.append("\n**Tests that name this row:** " + (", ".join(f"`{t}`" for t in tests) or "none")
               + "\n")
    return "".join(out)
