"""The list of ledger rows: every id of ``paper/CLAIMS.md`` plus the rows proofs add.

A row is declared once: a row of the paper in the table of ``paper/CLAIMS.md``, a row of the
project (a stable kernel form, a physical ball, an open problem, a labelled equation CLAIMS.md
lacks) by ``@claim(ID, adds=(SECTION, statement))`` in the proof script that decides it.

``paper/CLAIMS.md`` and ``paper/chaplygin-sphere-nd.tex`` are copies of the shared originals
(a test keeps them identical when ``../shared`` is present). They ship inside the package as
package data of :mod:`chaplygin_nd.paper` (the folder ``paper/``), read through
:mod:`importlib.resources`, so an installed wheel finds them. A CLAIMS.md cell such as
``eq:motion-general, eq:M-O, eq:Inertia`` or ``eq:Manakov / eq:itildendim`` yields one row per id.
"""

from __future__ import annotations

import importlib
import pkgutil
import re
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

#: The folder above the packages: the repository root in a checkout, site-packages when installed.
ROOT = Path(__file__).resolve().parent.parent
_PAPER = resources.files("chaplygin_nd.paper")
CLAIMS_PATH = Path(str(_PAPER / "CLAIMS.md"))
PAPER_PATH = Path(str(_PAPER / "chaplygin-sphere-nd.tex"))


def is_checkout() -> bool:
    """True when running from the source repository (not from an installed wheel)."""
    return (ROOT / "pyproject.toml").is_file() and (ROOT / "ledger" / "catalog.py").is_file()


@dataclass(frozen=True)
class Row:
    id: str
    section: str
    claim: str


def _split_ids(cell: str) -> list[str]:
    return [part.strip() for part in re.split(r",|/", cell) if part.strip()]


def claims_rows(path: Path = CLAIMS_PATH) -> list[Row]:
    """The rows of CLAIMS.md in document order."""
    rows: list[Row] = []
    section = ""
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("## "):
            section = line[3:].strip()
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if not line.startswith("|") or len(cells) < 2 or cells[0] in ("id", "") \
                or set(cells[0]) <= set("-: "):
            continue
        rows.extend(Row(i, section, cells[1]) for i in _split_ids(cells[0]))
    return rows


def all_rows() -> list[Row]:
    """The ledger: the rows of CLAIMS.md in document order, then the rows registered proofs add
    (``@claim(..., adds=(section, claim))``, the one place a row of the project is declared).
    An added row whose id is a ``\\label`` of the paper (a labelled equation CLAIMS.md has no row
    for, e.g. eq:vert-3D) goes after the last row of its section, where the paper states it; the
    others follow at the end, in id order. A row declared twice (in CLAIMS.md and by ``adds=``)
    raises ``ValueError`` naming both places. Call :func:`discover` first."""
    from chaplygin_nd.ledger.registry import registry

    rows = claims_rows()
    paper = {r.id: r for r in rows}
    added = sorted((s for s in registry().values() if s.adds), key=lambda s: s.id)
    twice = [f"{s.id} (paper/CLAIMS.md, {paper[s.id].section!r}; and @claim(adds=...) in "
             f"{s.module})" for s in added if s.id in paper]
    if twice:
        raise ValueError("ledger row declared twice: " + "; ".join(twice)
                         + "; keep the CLAIMS.md row and drop adds=, or rename the added row")
    labels = set(paper_labels())
    tail = []
    for spec in added:
        section, statement = spec.adds or ("", "")
        row = Row(spec.id, section, statement)
        if spec.id in labels:
            last = max((i for i, r in enumerate(rows) if r.section == row.section),
                       default=len(rows) - 1)
            rows.insert(last + 1, row)
        else:
            tail.append(row)
    rows += tail
    ids = [r.id for r in rows]
    duplicates = {i for i in ids if ids.count(i) > 1}
    if duplicates:
        raise ValueError(f"duplicate ledger ids: {sorted(duplicates)}")
    return rows


def paper_labels(path: Path = PAPER_PATH) -> list[str]:
    r"""Every ``\label{...}`` of the paper, in order."""
    return re.findall(r"\\label\{([^}]*)\}", path.read_text(encoding="utf-8"))


def discover() -> list[str]:
    """Import every module of the ``proofs`` package (registering its claims): it holds only the
    claim scripts and their shared helpers, so nothing is excluded."""
    from chaplygin_nd import proofs

    names = []
    for info in sorted(pkgutil.iter_modules(proofs.__path__), key=lambda i: i.name):
        importlib.import_module(f"chaplygin_nd.proofs.{info.name}")
        names.append(info.name)
    return names


def _declared_ids() -> set[str]:
    """Every ledger id, read without importing a proof: CLAIMS.md and the ``@claim("ID", ...)``
    lines of the proof scripts (the rows they add)."""
    ids = {r.id for r in claims_rows()}
    folder = Path(str(resources.files("chaplygin_nd.proofs")))
    for script in folder.glob("*.py"):
        ids.update(re.findall(r"@claim\(\s*[\"']([^\"']+)[\"']",
                              script.read_text(encoding="utf-8")))
    return ids


#: Unknown ids an error describes; the rest are counted.
SHOWN = 5


def resolve(ids: list[str]) -> list[str]:
    """The ledger ids named by ``ids`` (surrounding blanks stripped; each once, in the order first
    named), checked before any proof is imported; an unknown one raises ``KeyError`` with one line naming the nearest ids
    ("did you mean"), case-insensitively."""
    import difflib

    known = _declared_ids()
    lower: dict[str, list[str]] = {}
    for i in sorted(known):
        lower.setdefault(i.lower(), []).append(i)
    from chaplygin_nd.console import shortlist

    out: list[str] = []
    bad: list[str] = []
    for raw in ids:
        name = raw.strip()
        if name in known:
            if name not in out:
                out.append(name)
            continue
        if len(bad) >= SHOWN:  # counted, not described: the message stays one short line
            bad.append(raw)
            continue
        near = lower.get(name.lower(), []) or [
            i for k in difflib.get_close_matches(name.lower()[:200], list(lower), n=3, cutoff=0.6)
            for i in lower[k]]
        shown = repr(raw) if len(raw) <= 60 else repr(raw[:57]) + "..."
        bad.append(shown + (f" (did you mean {', '.join(near[:3])}?)" if near else ""))
    if bad:
        raise KeyError(f"unknown ledger id {shortlist(bad, SHOWN, width=200)}; "
                       "`chaplygin prove --list` lists them")
    return out
