"""The rows grouped as the paper is: by the sections of ``paper/CLAIMS.md``, in its order, then the
rows whose section is not one of the paper's (the project's own: stable kernel rewrites, physical
balls, the open problems) under *Beyond the paper*, each under its own section.

Nothing here names a row id: a row belongs where its ``section`` (from the report) says.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

#: The heading of the group of sections that are not the paper's.
BEYOND = "Beyond the paper"


@dataclass
class Section:
    """One section of the site: its heading and its rows (dicts of verification.json)."""

    title: str
    rows: list[dict] = field(default_factory=list)
    beyond: bool = False

    @property
    def anchor(self) -> str:
        """A stable HTML id for the section's heading."""
        return "sec-" + re.sub(r"[^a-z0-9]+", "-", self.title.lower()).strip("-")


def paper_sections(claims_md: str) -> list[str]:
    """The ``## `` headings of CLAIMS.md, in order: the paper's sections."""
    return [line[3:].strip() for line in claims_md.splitlines() if line.startswith("## ")]


def group(rows: list[dict], paper: list[str]) -> list[Section]:
    """The paper's sections (in CLAIMS.md order, each with its rows in ledger order), then every
    other section (in order of first appearance) marked ``beyond``. Empty sections are dropped."""
    sections = {title: Section(title) for title in paper}
    for row in rows:
        if row["section"] not in sections:
            sections[row["section"]] = Section(row["section"], beyond=True)
        sections[row["section"]].rows.append(row)
    return [s for s in sections.values() if s.rows]


def short_title(claim: str, limit: int = 56) -> str:
    """A few words for the sidebar: the claim's first clause (up to ``;`` or `` — ``), cut at a
    word boundary near ``limit`` characters."""
    text = re.split(r";| — |: (?=[a-z])", claim.strip(), maxsplit=1)[0].strip().rstrip(".,")
    if len(text) <= limit:
        return text
    cut = text[:limit].rsplit(" ", 1)[0].rstrip(",;:(")
    return cut + " …"
