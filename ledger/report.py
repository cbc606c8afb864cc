"""Render ledger results: one console line per row, VERIFICATION.md and verification.json.

Everything here is general over :data:`ledger.registry.VERDICTS` and :data:`ledger.registry.KINDS`: a
new verdict or kind needs only its one-line description in :data:`VERDICT_TEXT` / :data:`KIND_TEXT`
(a test checks that every one has one). The Markdown is written for a renderer with TeX math
(GitHub, pandoc, MathJax, KaTeX): labels stay outside the math, one formula per ``$$`` display.
"""

from __future__ import annotations

import hashlib
import json
import os
import platform
import signal
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import sympy
from chaplygin_nd.ledger import sources
from chaplygin_nd.ledger.registry import ERRATA_KINDS, KINDS, NEEDS_KIND, VERDICTS, registry
from chaplygin_nd.ledger.runner import Result
from chaplygin_nd.symbolic.exact.points import n_text

from chaplygin_nd.writing import write_temporary

#: What each verdict means, for the reader of the report (one entry per verdict of the ledger).
VERDICT_TEXT = {
    "holds": "the printed statement equals an independent derivation (a remark may add what the "
             "paper leaves implicit)",
    "definition": "a definition (with consistency checks where they apply)",
    "evidence": "numerical support for a qualitative statement, with a control showing the method "
                "can tell the difference; never counted as holds",
    "corrected": "false as printed; an exact counterexample and a proved correction are recorded",
    "open": "not decided; the reason is given",
    "fails": "false as printed, no correction proved yet",
    "error": "the proof raised an exception (a fault of the ledger, not a verdict on the paper)",
}

#: What each kind of finding means; errata are the kinds in ``ERRATA_KINDS``, the rest remarks.
KIND_TEXT = {
    "formula": "a displayed formula is false",
    "proof": "a step of a proof is false; the statement holds",
    "scope": "the statement fails on a parameter value or stratum the paper does not exclude",
    "reading": "the printed text is ambiguous: false in one reading, true in another (both stated)",
}

#: Where the claim graph is written (relative to the repository root; tracked, so links work).
GRAPH_PATH = "docs/claim-graph.svg"
#: The first line of VERIFICATION.md (how ``chaplygin verify --report-dir`` knows its own file).
HEADING = "# Verification ledger"


@dataclass(frozen=True)
class RunInfo:
    """What a reader needs to repeat the run and to tell runs apart: the seed, whether generated/
    was checked, the commit (``None`` outside a checkout), the UTC time it started and a
    generation id shared by the two reports of one run."""

    seed: int
    #: ``"up to date"``, ``"STALE"`` or ``"not checked"``
    generated: str = "not checked"
    problems: tuple[str, ...] = ()
    commit: str | None = None
    started: str = ""
    generation: str = ""
    #: the claim graph, relative to the reports (``docs/claim-graph.svg`` in a checkout)
    graph: str = GRAPH_PATH

    def names(self) -> str:
        """``seed S, commit C, started T, generation G`` — the run, in one line."""
        return (f"seed {self.seed}, commit {self.commit or 'none (not a checkout)'}, "
                f"started {self.started or 'unknown'}, generation {self.generation or 'none'}")

    @property
    def trustworthy(self) -> bool:
        return self.generated != "STALE" and not self.problems


def line(result: Result) -> str:
    """``id  verdict  seconds  method [n=...]`` — one line, as printed by ``make verify``."""
    v = result.verdict
    ns = f" [n={n_text(v.n_values)}]" if v.n_values else ""
    method = v.method if result.status != "open" else f"open: {v.notes.strip() or 'NO REASON'}"
    if result.error:
        method = "ERROR: " + result.error.strip().splitlines()[-1]
    status = result.status + (f" ({v.kind})" if v.kind else "")
    head = f"{result.row.id:<24} {status:<20} {result.seconds:7.2f}s  "
    room = 220 - len(head) - len(ns)  # the method is shortened, never the [n] it is backed for
    return head + (method if len(method) <= room else method[:room - 3] + "...") + ns


def totals(results: Sequence[Result]) -> Counter:
    return Counter(r.status for r in results)


def argued(results: Sequence[Result]) -> list[tuple[str, str]]:
    """(row id, part name) of everything argued in prose rather than computed."""
    return [(r.row.id, name) for r in results for name in r.verdict.argued_parts]


def summary(results: Sequence[Result]) -> str:
    """The totals line: rows per verdict (in the order of VERDICTS), findings per kind, the parts
    argued in prose, and the proof time."""
    count = totals(results)
    parts = ", ".join(f"{count[k]} {k}" for k in VERDICTS if count[k])
    kinds = Counter(r.verdict.kind for r in results if r.verdict.kind)
    found = f" [{', '.join(f'{kinds[k]} {k}' for k in KINDS if kinds[k])}]" if kinds else ""
    seconds = sum(r.seconds for r in results)
    rows, argued_parts = len(results), len(argued(results))
    return (f"{rows} row{'' if rows == 1 else 's'}: {parts}{found}; {argued_parts} "
            f"part{'' if argued_parts == 1 else 's'} argued, not machine-checked "
            f"({seconds:.1f} s of proof time)")


def missing_kind(results: Sequence[Result]) -> list[str]:
    """Rows that found something (``corrected``/``fails``) without saying which kind: an error of
    the ledger, reported as a problem by ``chaplygin verify``."""
    return [r.row.id for r in results if r.status in NEEDS_KIND and not r.verdict.kind]


def json_text(results: Sequence[Result], info: RunInfo, markdown_sha256: str | None = None) -> str:
    """verification.json; ``markdown_sha256`` names the VERIFICATION.md written with it. Each row
    carries ``sources`` (:func:`ledger.sources.collect`): what the site shows beside the verdict."""
    where = sources.collect([(r.row.id, r.printed) for r in results], registry())
    data = {"seed": info.seed, "commit": info.commit, "started": info.started,
            "generation": info.generation, "markdown_sha256": markdown_sha256,
            "generated": info.generated, "problems": list(info.problems),
            "summary": dict(totals(results)),
            "kinds": dict(Counter(r.verdict.kind for r in results if r.verdict.kind)),
            "argued": [{"id": i, "part": name} for i, name in argued(results)],
            "claim_graph": info.graph,
            "rows": [dict(r.to_dict(), sources=where[r.row.id]) for r in results],
            "environment": {"python": platform.python_version(), "sympy": sympy.__version__}}
    return json.dumps(data, indent=2, ensure_ascii=False) + "\n"


def write_json(results: Sequence[Result], path: Path, info: RunInfo) -> None:
    """verification.json alone (atomically); :func:`write_pair` writes it with the Markdown."""
    write_files({Path(path): json_text(results, info)})


def write_markdown(results: Sequence[Result], path: Path, info: RunInfo) -> None:
    """VERIFICATION.md alone (atomically); :func:`write_pair` writes it with the JSON."""
    write_files({Path(path): markdown_text(results, info)})


def write_pair(results: Sequence[Result], markdown: Path, json_path: Path, info: RunInfo,
               extra: dict[Path, str] | None = None) -> None:
    """VERIFICATION.md and verification.json as one result: both carry ``info``'s generation id,
    the JSON names the Markdown's SHA-256, and both are written to unique temporary names first
    and then moved into place together (:func:`write_files`), with the files of ``extra`` (the
    claim graph)."""
    md = markdown_text(results, info)
    sha = hashlib.sha256(md.encode("utf-8")).hexdigest()
    write_files({Path(markdown): md, Path(json_path): json_text(results, info, sha),
                 **(extra or {})})


def write_files(texts: dict[Path, str]) -> None:
    """Write every ``path -> text`` through a unique temporary file in the same folder, then move
    them all into place with Ctrl-C and SIGTERM held back, so that an interrupted run leaves all
    old or all new files (never one of each) and two concurrent runs never share a temporary.
    The folders it had to create are removed again when it does not get to the end (an
    interrupted ``verify --report-dir NEW`` leaves nothing it created). An ``OSError`` names the
    path that failed (``exc.filename``)."""
    temps: list[tuple[Path, Path]] = []
    created: list[Path] = []
    done = False
    try:
        for path, text in texts.items():
            missing = [p for p in (path.parent, *path.parent.parents) if not p.exists()]
            path.parent.mkdir(parents=True, exist_ok=True)
            created += [p for p in missing if p not in created]
            # whole, at a unique temporary name, with the mode of a plain open() (or the old file's)
            temps.append((write_temporary(path, text), path))
        held = {signal.SIGINT, signal.SIGTERM}
        old = signal.pthread_sigmask(signal.SIG_BLOCK, held)
        try:
            for tmp, path in temps:
                os.replace(tmp, path)
            done = True
        finally:
            signal.pthread_sigmask(signal.SIG_SETMASK, old)
    except OSError as exc:
        if exc.filename is None:
            exc.filename = str(next(iter(texts)))
        raise
    finally:
        for tmp, _ in temps:
            Path(tmp).unlink(missing_ok=True)
        if not done:
            for folder in sorted(created, key=lambda p: len(p.parts), reverse=True):
                try:
                    folder.rmdir()  # only if empty: never another process's files
                except OSError:
                    pass


_MARKDOWN_SPECIAL = str.maketrans({c: "\\" + c for c in "\\`*_[]<>|$#"})


def _cell(text: str | None) -> str:
    """Plain text (a method, a note) inside Markdown: no character may start markup or math."""
    return (text or "").translate(_MARKDOWN_SPECIAL).replace("\n", " ")


def _inline_math(latex: str | None) -> str:
    """A formula inside a table cell: ``|`` would end the cell, so ``\\|`` becomes ``\\Vert`` and
    ``|`` becomes ``\\vert``."""
    if not latex:
        return ""
    return "$" + " ".join(latex.split()).replace(r"\|", r"\Vert ").replace("|", r"\vert ") + "$"


#: A display longer than this (characters of LaTeX) that is a counterexample is set on two lines.
_LONG_DISPLAY = 160


def _display(latex: str) -> list[str]:
    return ["$$", latex.strip(), "$$", ""]


def _counterexample_display(latex: str) -> list[str]:
    """A long counterexample on two lines: the point, then the residual it gives."""
    arrow = r" \;\Rightarrow\; "
    if len(latex) > _LONG_DISPLAY and arrow in latex:
        point, residual = latex.split(arrow, 1)
        latex = r"\begin{gathered}" + point + r" \\ \Rightarrow\; " + residual + r"\end{gathered}"
    return _display(latex)


def _anchor(row_id: str) -> str:
    return "finding-" + "".join(c if c.isalnum() else "-" for c in row_id.lower())


def _findings(r: Result):
    """The pieces of a row that carry its finding: its bad parts, or the row itself."""
    bad = [p for p in r.verdict.parts if p.verdict in NEEDS_KIND]
    return bad or ([r.verdict] if r.status in NEEDS_KIND else [])


def markdown_text(results: Sequence[Result], info: RunInfo) -> str:
    """VERIFICATION.md: run facts, errata, remarks, the full table, then each finding in LaTeX."""
    out = [HEADING, ""]
    if info.generated == "STALE":
        out += ["> **STALE — do not rely on this report.** `generated/` differs from what "
                "`symbolic/` emits now (run `make generate`, then `make verify`).", ""]
    if info.problems:
        out += ["> **This run has problems** (`make verify` exits non-zero):", ">"]
        out += [f"> - {_cell(p.splitlines()[0])}" for p in info.problems] + [""]
    out += [f"Written by `make verify` (`chaplygin verify`) with **seed {info.seed}** (repeat with "
            f"`make verify SEED={info.seed}`); `generated/`: {info.generated}.", "",
            f"Run: {info.names()} (verification.json carries the same generation id).", "",
            f"**{summary(results)}**", "",
            "One row per computable claim of the paper (`paper/CLAIMS.md`, plus rows this project "
            "added). Verdicts:", ""]
    out += [f"- **{v}** — {VERDICT_TEXT[v]}" for v in VERDICTS]
    out += ["", "Every `corrected`/`fails` row has a kind: "
            + "; ".join(f"**{k}** — {KIND_TEXT[k]}" for k in KINDS)
            + f". Errata are {' and '.join(ERRATA_KINDS)}; the other kinds are remarks.", "",
            f"The claim graph (what each row uses, coloured by verdict and kind): "
            f"[{info.graph}]({info.graph}).", "", f"![claim graph]({info.graph})", ""]
    out += _errata_table(results) + _remarks_table(results)
    out += ["## All rows", "", "| id | verdict | kind | seconds | n | method | proof |",
            "|---|---|---|---|---|---|---|"]
    for r in results:
        v = r.verdict
        ns = n_text(v.n_values) if v.n_values else ""
        method = v.method if r.status != "open" else f"open: {v.notes}"
        out.append(f"| `{r.row.id}` | **{r.status}** | {v.kind or ''} | {r.seconds:.2f} | {ns} "
                   f"| {_cell(method)} | {r.module} |")
    out += ["", "## Findings in detail", ""]
    detailed = [r for r in results if _findings(r) or r.error]
    out += [] if detailed else ["None.", ""]
    for r in detailed:
        out += _finding(r)
    out += _argued_section(results)
    parted = [r for r in results if r.verdict.parts]
    if parted:
        out += ["## Rows made of parts", ""]
        for r in parted:
            out += [f"### `{r.row.id}`", "", "| part | verdict | kind | method |", "|---|---|---|---|"]
            out += [f"| {_cell(p.name)} | {p.verdict}{' (argued)' if p.argued else ''} "
                    f"| {p.kind or ''} | {_cell(p.method)} |" for p in r.verdict.parts]
            out.append("")
    measured = [r for r in results if r.verdict.evidence]
    if measured:
        out += ["## Numerical evidence", ""]
        for r in measured:
            e = r.verdict.evidence or {}
            out += [f"### `{r.row.id}` — {r.status}", "", f"Claim: {_cell(str(r.row.claim))}", "",
                    f"- measured: {_cell(str(e['measured']))}", f"- initial conditions: {_cell(str(e['initial_conditions']))}",
                    f"- tolerance: {_cell(str(e['tolerance']))}",
                    f"- would have contradicted it: {_cell(str(e['contradiction']))}",
                    f"- control: {_cell(str(e['control']))} (separates: {e['control_separates']})", ""]
    notes = [r for r in results if r.verdict.notes and r.status != "open"]
    if notes:
        out += ["## Notes", ""]
        out += [f"- `{r.row.id}`: {_cell(r.verdict.notes)}" for r in notes]
        out.append("")
    return "\n".join(out).rstrip("\n") + "\n"


def _errata_table(results: Sequence[Result]) -> list[str]:
    rows = [r for r in results if r.verdict.kind in ERRATA_KINDS]
    out = [f"## Errata ({', '.join(ERRATA_KINDS)})", ""]
    if not rows:
        return out + ["None.", ""]
    out += ["| row | kind | as printed | proved instead |", "|---|---|---|---|"]
    for r in rows:
        groups: dict[tuple, list[str]] = {}  # parts with the same formulas share one line
        for item in _findings(r):
            key = (item.printed_latex, item.correction_latex)
            groups.setdefault(key, []).append(item.name if item is not r.verdict else "")
        for (printed, fixed), names in groups.items():
            label = "; ".join(_cell(n) for n in names if n)
            out.append(f"| [`{r.row.id}`](#{_anchor(r.row.id)}) | {r.verdict.kind} "
                       f"| {label + ': ' if label else ''}{_inline_math(printed)} "
                       f"| {_inline_math(fixed) or r.status} |")
    return out + [""]


def _remarks_table(results: Sequence[Result]) -> list[str]:
    rows = [r for r in results
            if (r.verdict.kind and r.verdict.kind not in ERRATA_KINDS) or r.verdict.remark]
    out = [f"## Remarks ({', '.join(k for k in KINDS if k not in ERRATA_KINDS)}; "
           "rows that hold with a remark)", ""]
    if not rows:
        return out + ["None.", ""]
    out += ["| row | verdict | kind | remark |", "|---|---|---|---|"]
    for r in rows:
        link = f"[`{r.row.id}`](#{_anchor(r.row.id)})" if _findings(r) else f"`{r.row.id}`"
        out.append(f"| {link} | {r.status} | {r.verdict.kind or ''} "
                   f"| {_cell(r.verdict.remark or r.verdict.notes)} |")
    return out + [""]


def _finding(r: Result) -> list[str]:
    v = r.verdict
    kind = f" · {v.kind} ({'erratum' if v.kind in ERRATA_KINDS else 'remark'})" if v.kind else ""
    out = [f'<a id="{_anchor(r.row.id)}"></a>', "", f"### `{r.row.id}` — {r.status}{kind}", "",
           f"Claim: {_cell(r.row.claim)}", ""]
    if r.error:
        return out + ["```", r.error.strip(), "```", ""]
    if v.remark:
        out += [f"Remark: {_cell(v.remark)}", ""]
    shown: set[str] = set()  # each formula once: a later part refers to it
    for item in _findings(r):
        if item is not v:
            out += [f"**Part: {_cell(item.name)}** ({item.verdict}{', ' + item.kind if item.kind else ''})", ""]
        for label, latex in (("As printed", item.printed_latex),
                             ("Counterexample (exact)", item.counterexample_latex),
                             ("Corrected (proved)", item.correction_latex)):
            if latex and latex in shown:
                out += [f"{label}: the formula shown above.", ""]
            elif latex:
                shown.add(latex)
                out += [f"{label}:", ""] + (_counterexample_display(latex)
                                            if label.startswith("Counterexample") else _display(latex))
            elif label.startswith("Counterexample") and item.counterexample:
                out += [f"Counterexample (exact): {_cell(item.counterexample)}", ""]
        if item is not v and item.notes:
            out += [f"Notes: {_cell(item.notes)}", ""]
    if v.notes:
        out += [f"Notes: {_cell(v.notes)}", ""]
    return out + [f"Method: {_cell(v.method)}", ""]


def _argued_section(results: Sequence[Result]) -> list[str]:
    items = argued(results)
    out = ["## Argued, not machine-checked", ""]
    if not items:
        return out + ["Nothing: every part of every row is computed.", ""]
    return out + [f"- `{i}`: {_cell(name)}" for i, name in items] + [""]
