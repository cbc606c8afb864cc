"""Render ledger results: one console line per row, VERIFICATION.md and verification.json."""

from __future__ import annotations

import json
import platform
from collections import Counter
from collections.abc import Sequence
from pathlib import Path

import sympy

from proofs.runner import Result

ORDER = ("holds", "definition", "corrected", "evidence", "open", "fails", "error")


def line(result: Result) -> str:
    """``id  verdict  seconds  method [n=...]`` — one line, as printed by ``make verify``."""
    v = result.verdict
    ns = f" [n={','.join(map(str, v.n_values))}]" if v.n_values else ""
    method = v.method if result.status != "open" else f"open: {v.notes.strip() or 'NO REASON'}"
    if result.error:
        method = "ERROR: " + result.error.strip().splitlines()[-1]
    text = f"{result.row.id:<24} {result.status:<10} {result.seconds:7.2f}s  {method}{ns}"
    return text if len(text) <= 220 else text[:217] + "..."


def totals(results: Sequence[Result]) -> Counter:
    return Counter(r.status for r in results)


def summary(results: Sequence[Result]) -> str:
    count = totals(results)
    parts = ", ".join(f"{count[k]} {k}" for k in ORDER if count[k])
    seconds = sum(r.seconds for r in results)
    return f"{len(results)} rows: {parts} ({seconds:.1f} s of proof time)"


def write_json(results: Sequence[Result], path: Path) -> None:
    data = {"summary": dict(totals(results)), "rows": [r.to_dict() for r in results],
            "environment": {"python": platform.python_version(), "sympy": sympy.__version__}}
    path.write_text(json.dumps(data, indent=2, ensure_ascii=False) + "\n", encoding="utf-8")


def _cell(text: str | None) -> str:
    return (text or "").replace("|", "\\|").replace("\n", " ")


def write_markdown(results: Sequence[Result], path: Path) -> None:
    out = ["# Verification ledger", "",
           "Written by `make verify` (`python -m proofs`). One row per computable claim of the "
           "paper (`paper/CLAIMS.md`, plus rows this project added). Verdicts: **holds** (printed "
           "formula = independent derivation), **corrected** (printed formula false; exact "
           "counterexample and a proved correction below), **fails** (false, no correction yet), "
           "**definition**, **evidence** (numerical support for a qualitative statement, with a "
           "control that could have failed; never counted as holds), **open** (not decided; the "
           "reason is given).", "",
           f"**{summary(results)}**", "",
           "| id | verdict | seconds | n | method | proof |", "|---|---|---|---|---|---|"]
    for r in results:
        v = r.verdict
        ns = ",".join(map(str, v.n_values))
        method = v.method if r.status != "open" else f"open: {v.notes}"
        out.append(f"| `{r.row.id}` | **{r.status}** | {r.seconds:.2f} | {ns} | {_cell(method)} "
                   f"| {r.module} |")
    findings = [r for r in results if r.status in ("corrected", "fails", "error")]
    out += ["", "## Findings in the paper", ""]
    if not findings:
        out.append("None so far.")
    for r in findings:
        out += _finding(r)
    parted = [r for r in results if r.verdict.parts]
    if parted:
        out += ["", "## Rows made of parts", ""]
        for r in parted:
            out += [f"### `{r.row.id}`", "", "| part | verdict | method |", "|---|---|---|"]
            out += [f"| {_cell(p.name)} | {p.verdict} | {_cell(p.method)} |" for p in r.verdict.parts]
            out.append("")
    measured = [r for r in results if r.verdict.evidence]
    if measured:
        out += ["", "## Numerical evidence", ""]
        for r in measured:
            e = r.verdict.evidence
            out += [f"### `{r.row.id}` — {r.status}", "", f"Claim: {r.row.claim}", "",
                    f"- measured: {e['measured']}", f"- initial conditions: {e['initial_conditions']}",
                    f"- tolerance: {e['tolerance']}",
                    f"- would have contradicted it: {e['contradiction']}",
                    f"- control: {e['control']} (separates: {e['control_separates']})", ""]
    notes = [r for r in results if r.verdict.notes and r.status not in ("open",)]
    if notes:
        out += ["", "## Notes", ""]
        out += [f"- `{r.row.id}`: {r.verdict.notes}" for r in notes]
    path.write_text("\n".join(out) + "\n", encoding="utf-8")


def _finding(r: Result) -> list[str]:
    v = r.verdict
    out = [f"### `{r.row.id}` — {r.status}", "", f"Claim: {r.row.claim}", ""]
    if r.error:
        return out + ["```", r.error.strip(), "```", ""]
    if v.printed_latex:
        out += ["As printed:", "", "$$", v.printed_latex, "$$", ""]
    if v.counterexample:
        out += [f"Counterexample (exact): {v.counterexample}", ""]
    if v.counterexample_latex:
        out += ["$$", v.counterexample_latex, "$$", ""]
    if v.correction_latex:
        out += ["Corrected (proved):", "", "$$", v.correction_latex, "$$", ""]
    for p in v.parts:
        if p.verdict in ("corrected", "fails"):
            out += [f"- part **{p.name}**: {p.verdict}. {p.counterexample or ''}"]
            if p.printed_latex:
                out += ["", "  printed: $$" + p.printed_latex + "$$"]
            if p.correction_latex:
                out += ["", "  corrected: $$" + p.correction_latex + "$$"]
    if v.notes:
        out += [f"Notes: {v.notes}", ""]
    return out + [f"Method: {v.method}", ""]
