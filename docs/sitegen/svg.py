"""A row's ancestor subgraph as inline SVG (no matplotlib, no Graphviz): the rows it uses,
directly or not, laid out by :func:`chaplygin_nd.ledger.graph.positions` (the same layers as the
full claim graph), coloured like it, every node a link to its page."""

from __future__ import annotations

import html
from collections.abc import Callable, Sequence

from chaplygin_nd.ledger import graph

_CHAR, _H, _GAP_X, _GAP_Y, _PAD = 7.2, 22, 14, 46, 8


def ancestors(claim_id: str, uses: dict[str, Sequence[str]]) -> list[str]:
    """``claim_id`` and every row it uses directly or not (each once)."""
    seen, stack = [], [claim_id]
    while stack:
        v = stack.pop()
        if v in seen or v not in uses:
            continue
        seen.append(v)
        stack.extend(uses[v])
    return seen


def subgraph(claim_id: str, order: Sequence[str], uses: dict[str, Sequence[str]],
             fill: dict[str, str], href: Callable[[str], str]) -> str:
    """SVG of the ancestors of ``claim_id`` (kept in ledger ``order``); arrows from a used row to
    the row that uses it; ``claim_id`` drawn with a thick border."""
    keep = set(ancestors(claim_id, uses))
    ids = [i for i in order if i in keep]
    acyclic, back = graph.split_cycles(ids, {i: [u for u in uses[i] if u in keep] for i in ids})
    pos = graph.positions(ids, acyclic)
    width = {i: len(i) * _CHAR + 2 * _PAD for i in ids}
    layers: dict[int, list[str]] = {}
    for i in sorted(ids, key=lambda i: pos[i]):
        layers.setdefault(pos[i][0], []).append(i)
    span = {k: sum(width[i] for i in row) + _GAP_X * (len(row) - 1) for k, row in layers.items()}
    total_w = max(span.values()) + 2 * _PAD
    xy = {}
    for k, row in layers.items():
        x = (total_w - span[k]) / 2
        for i in row:
            xy[i] = (x, _PAD + k * (_H + _GAP_Y))
            x += width[i] + _GAP_X
    total_h = _PAD * 2 + len(layers) * _H + (len(layers) - 1) * _GAP_Y
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" class="ancestor-graph" width="{total_w:.0f}" '
           f'height="{total_h:.0f}" viewBox="0 0 {total_w:.0f} {total_h:.0f}" role="img" '
           f'aria-label="rows used by {html.escape(claim_id)}">',
           '<defs><marker id="arrow" viewBox="0 0 10 10" refX="10" refY="5" markerWidth="6" '
           'markerHeight="6" orient="auto-start-reverse"><path d="M0,0 L10,5 L0,10 z" '
           'fill="#8c8c8c"/></marker></defs>']
    edges = [(i, u, False) for i in ids for u in acyclic[i]] + [(i, u, True) for i, u in back]
    for i, u, cycle in edges:
        (x0, y0), (x1, y1) = xy[u], xy[i]
        a = (x0 + width[u] / 2, y0 + _H if y0 < y1 else y0)
        b = (x1 + width[i] / 2, y1 if y0 < y1 else y1 + _H)
        dash = ' stroke-dasharray="4 3"' if cycle else ""
        out.append(f'<line x1="{a[0]:.1f}" y1="{a[1]:.1f}" x2="{b[0]:.1f}" y2="{b[1]:.1f}" '
                   f'stroke="#8c8c8c" stroke-width="1"{dash} marker-end="url(#arrow)"/>')
    for i in ids:
        x, y = xy[i]
        me = i == claim_id
        bold = ' font-weight="bold"' if me else ""
        out.append(f'<a href="{html.escape(href(i))}"><title>{html.escape(i)}</title>'
                   f'<rect x="{x:.1f}" y="{y:.1f}" width="{width[i]:.1f}" height="{_H}" rx="4" '
                   f'fill="{fill[i]}" stroke="#303030" stroke-width="{2.5 if me else 0.8}"/>'
                   f'<text x="{x + width[i] / 2:.1f}" y="{y + _H / 2 + 4:.1f}" '
                   f'text-anchor="middle" font-family="monospace" font-size="12"'
                   f'{bold}>{html.escape(i)}</text></a>')
    out.append("</svg>")
    return "".join(out)
