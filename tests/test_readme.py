"""The README stays a screen or two (issue 26: at most 12 KB) and every manual page it links to
exists and is built into the site (docs/build_pages.py MANUAL): one copy of each text, no dead link."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
README = ROOT / "README.md"


def test_readme_fits_on_a_screen_or_two():
    assert len(README.read_bytes()) <= 12 * 1024


def test_every_manual_page_the_readme_links_exists_and_is_on_the_site():
    links = re.findall(r"\]\((docs/pages/[\w.-]+\.md)\)", README.read_text(encoding="utf-8"))
    assert links, "the README links the manual"
    site = (ROOT / "docs" / "build_pages.py").read_text(encoding="utf-8")
    missing = [p for p in links if not (ROOT / p).is_file()]
    unbuilt = [p for p in links if f'"pages/{Path(p).stem}"' not in site]
    assert missing == [] and unbuilt == []
