r"""The theorem page (``docs/pages/theorem.md``) filled from the ledger, and the same text as LaTeX.

The page is written once, in MyST Markdown with ``$...$`` maths; three markers stand where the
ledger's report speaks:

* ``<!-- ledger:parts ID -->``: the parts of row ID — each computed part with its verdict and the
  n it covers (parts named ``name, n = N`` are grouped), each argued part marked **argued**;
* ``<!-- ledger:rank-table ID -->``: the table ``data.rank_table`` of row ID (n, rank, expected, method);
* ``<!-- ledger:download -->``: on the site, the link to ``theorem.tex``; in the LaTeX file, the seed.

:func:`markdown` fills them for the site; :func:`latex` fills them and converts the little Markdown the
page uses (headings, lists, bold, emphasis, code, links, tables, ``$$`` displays) into a standalone
LaTeX document. Both read the same text and the same report, so the two cannot drift apart.
"""

from __future__ import annotations

import re

__all__ = ["markdown", "latex"]

_MARK = re.compile(r"<!-- ledger:(parts|rank-table|download)(?: (\S+))? -->")
_GROUP = re.compile(r"^(.*), n = (\d+)$")


def _row(rows: list[dict], cid: str) -> dict:
    for r in rows:
        if r["id"] == cid:
            return r
    raise KeyError(f"the theorem page names row {cid}, which the report does not have")


def _ranges(ns: list[int]) -> str:
    ns = sorted(ns)
    if len(ns) > 2 and ns == list(range(ns[0], ns[-1] + 1)):
        return f"n = {ns[0]}..{ns[-1]}"
    return "n = " + ", ".join(map(str, ns))


def _parts(row: dict) -> list[tuple[str, str, str, bool]]:
    """(name, verdict, detail, argued) per part, grouping ``name, n = N`` parts."""
    groups: dict[str, list[dict]] = {}
    order: list[str] = []
    for p in row["parts"]:
        m = _GROUP.match(p["name"])
        key = m.group(1) if m else p["name"]
        if key not in groups:
            groups[key], _ = [], order.append(key)
        groups[key].append(p)
    out = []
    for key in order:
        ps = groups[key]
        verdicts = sorted({p["verdict"] for p in ps})
        ns = [int(_GROUP.match(p["name"]).group(2)) for p in ps if _GROUP.match(p["name"])]
        argued = any(p["argued"] for p in ps)
        detail = _ranges(ns) if ns else ps[0]["method"].removeprefix("argued, not machine-checked: ")
        out.append((key, "/".join(verdicts), detail, argued))
    return out


def _fill(text: str, rows: list[dict], seed: int, *, tex: bool) -> str:
    def sub(m: re.Match) -> str:
        what, cid = m.group(1), m.group(2)
        if what == "download":
            if tex:
                return (f"Generated from the ledger's report (seed {seed}) by docs/sitegen/theorem.py; "
                        "the site's page of the same name is the same text.")
            return (f"Download this page as LaTeX: {{download}}`theorem.tex <theorem.tex>` (built from the "
                    f"same ledger report, seed {seed}).")
        row = _row(rows, cid)
        if what == "parts":
            lines = [f"Row `{cid}`: **{row['verdict']}**."] + [""]
            for name, verdict, detail, argued in _parts(row):
                tag = "**argued**" if argued else f"*{verdict}*"
                lines.append(f"- {name}: {tag} ({detail})" if not argued else f"- {name}: {tag}: {detail}")
            return "\n".join(lines)
        table = (row.get("data") or {}).get("rank_table")
        if not table:
            raise KeyError(f"row {cid} has no rank_table in its data")
        lines = ["| n | rank | expected 2n - 2 - floor(n/2) | functions | method |", "|---|---|---|---|---|"]
        lines += [f"| {r['n']} | {r['rank']} | {r['expected']} | {r['functions']} | {r['method']} |" for r in table]
        return "\n".join(lines)
    return _MARK.sub(sub, text)


def markdown(text: str, rows: list[dict], seed: int) -> str:
    """The page for the site: the markers filled (MyST)."""
    return _fill(text, rows, seed, tex=False)


_UNICODE = {"–": "--", "—": "---", "‘": "`", "’": "'", "“": "``", "”": "''", "≥": r"$\ge$",
            "≤": r"$\le$", "×": r"$\times$", "…": r"\dots{}", "→": r"$\to$"}


def _text(s: str) -> str:
    """Escape a stretch of prose (no maths) and convert bold, emphasis, code and links."""
    s = re.sub(r"\[([^\]]+)\]\([^)]+\)", r"\1", s)
    codes: list[str] = []

    def keep(m):
        codes.append(m.group(1))
        return f"\x00{len(codes) - 1}\x00"
    s = re.sub(r"`([^`]+)`", keep, s)
    for ch, rep in (("\\", r"\textbackslash{}"), ("&", r"\&"), ("%", r"\%"), ("#", r"\#"),
                    ("_", r"\_"), ("{", r"\{"), ("}", r"\}"), ("~", r"\textasciitilde{}"),
                    ("^", r"\textasciicircum{}")):
        s = s.replace(ch, rep) if ch != "\\" else s.replace(ch, "\x01")
    s = s.replace("\x01", r"\textbackslash{}")
    s = re.sub(r"\*\*(.+?)\*\*", r"\\textbf{\1}", s)
    s = re.sub(r"\*(.+?)\*", r"\\emph{\1}", s)
    for ch, rep in _UNICODE.items():
        s = s.replace(ch, rep)

    def code(m):
        c = codes[int(m.group(1))]
        for ch, rep in (("\\", r"\textbackslash{}"), ("_", r"\_"), ("&", r"\&"), ("%", r"\%"),
                        ("#", r"\#"), ("{", r"\{"), ("}", r"\}"), ("^", r"\textasciicircum{}")):
            c = c.replace(ch, rep) if ch != "\\" else c.replace(ch, "\x02")
        return r"\texttt{" + c.replace("\x02", r"\textbackslash{}") + "}"
    s = re.sub("\x00(\\d+)\x00", code, s)
    return "".join(ch if ord(ch) < 128 else "?" for ch in s)


def _inline(s: str) -> str:
    """Prose with ``$...$`` maths: maths kept verbatim, the rest through :func:`_text`."""
    maths: list[str] = []

    def keep(m):
        maths.append(m.group(0))
        return f"\x03{len(maths) - 1}\x03"
    prose = _text(re.sub(r"\$[^$]+\$", keep, s))
    return re.sub("\x03(\\d+)\x03", lambda m: maths[int(m.group(1))], prose)


def latex(text: str, rows: list[dict], seed: int) -> str:
    """The page as a standalone LaTeX document (markers filled, Markdown converted)."""
    body = _fill(text, rows, seed, tex=True)
    body = re.sub(r"\$\$(.+?)\$\$", lambda m: "\n\\[" + m.group(1) + "\\]\n", body, flags=re.S)
    out = [r"\documentclass[11pt]{article}", r"\usepackage[margin=2.5cm]{geometry}",
           r"\usepackage{amsmath,amssymb}", r"\begin{document}"]
    env: str | None = None
    lines = body.splitlines()
    i = 0
    while i < len(lines):
        ln = lines[i]
        item = re.match(r"^(\d+\.|-) (.*)$", ln)
        if env and not item and not ln.startswith("   ") and ln.strip():
            out.append(f"\\end{{{env}}}")
            env = None
        if ln.startswith("# "):
            out.append(r"\begin{center}\Large\bfseries " + _inline(ln[2:]) + r"\end{center}")
        elif ln.startswith("## "):
            out.append(r"\section*{" + _inline(ln[3:]) + "}")
        elif ln.startswith("|"):
            cells = []
            while i < len(lines) and lines[i].startswith("|"):
                if not re.match(r"^\|[-| ]+\|$", lines[i]):
                    cells.append([c.strip() for c in lines[i].strip("|").split("|")])
                i += 1
            cols = len(cells[0])
            out.append(r"\begin{center}\small\begin{tabular}{" + "l" * cols + r"}\hline")
            out += [" & ".join(_inline(c) for c in row) + r" \\" + (r" \hline" if k == 0 else "")
                    for k, row in enumerate(cells)]
            out.append(r"\hline\end{tabular}\end{center}")
            continue
        elif item:
            want = "enumerate" if item.group(1)[0].isdigit() else "itemize"
            if env != want:
                if env:
                    out.append(f"\\end{{{env}}}")
                out.append(f"\\begin{{{want}}}")
                env = want
            out.append(r"\item " + _inline(item.group(2)))
        elif ln.startswith("\\[") or ln.startswith("\\]"):
            out.append(ln)
        else:
            out.append(_inline(ln.strip()) if ln.strip() else "")
        i += 1
    if env:
        out.append(f"\\end{{{env}}}")
    out.append(r"\end{document}")
    return "\n".join(out) + "\n"
