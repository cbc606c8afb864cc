"""Every internal link of the built site resolves (``make docs`` runs this after the build):
each ``href``, ``src`` and ``xlink:href`` of every HTML page (and of every inline SVG in it)
that is not external, a ``mailto:`` or a pure ``#fragment`` must name a file of the build, and a
``#fragment`` must be an ``id`` of that page. Sphinx's own ``linkcheck`` needs the network.

    python docs/check_links.py [docs/_build/html]       exit 1 and a list when a link is broken
"""

from __future__ import annotations

import re
import sys
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

ATTRS = ("href", "src", "xlink:href")


class _Links(HTMLParser):
    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.links: list[str] = []
        self.ids: set[str] = set()

    def handle_starttag(self, tag, attrs):
        for name, value in attrs:
            if name in ATTRS and value:
                self.links.append(value)
            if name in ("id", "name") and value:
                self.ids.add(value)

    handle_startendtag = handle_starttag


def _parse(page: Path) -> _Links:
    parser = _Links()
    parser.feed(page.read_text(encoding="utf-8"))
    return parser


def broken_links(site: Path) -> list[str]:
    """``page: link`` for every internal link that does not resolve."""
    site = site.resolve()
    parsed = {p: _parse(p) for p in sorted(site.rglob("*.html"))}
    bad = []
    for page, links in parsed.items():
        for link in links.links:
            parts = urlsplit(link)
            if parts.scheme or link.startswith("//") or re.match(r"(mailto|data|javascript):", link):
                continue
            target = (page.parent / unquote(parts.path)).resolve() if parts.path else page
            if target.is_dir():
                target = target / "index.html"
            if not target.is_file() or not target.is_relative_to(site.resolve()):
                bad.append(f"{page.relative_to(site)}: {link}")
            elif parts.fragment and target.suffix == ".html":
                ids = parsed.get(target, None) or _parse(target)
                if unquote(parts.fragment) not in ids.ids:
                    bad.append(f"{page.relative_to(site)}: {link} (no such anchor)")
    return bad


def main(argv: list[str] | None = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    site = Path(args[0] if args else Path(__file__).resolve().parent / "_build" / "html")
    pages = list(site.rglob("*.html"))
    if not pages:
        print(f"error: no HTML pages under {site}: run `make docs` first", file=sys.stderr)
        return 2
    bad = broken_links(site)
    for line in bad:
        print(f"broken link: {line}", file=sys.stderr)
    print(f"{len(pages)} pages, {len(bad)} broken internal link(s)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
