r"""The claim graph, drawn: every ledger row a node, every ``uses=`` an arrow from what is used to
what uses it (as in a Lean blueprint), nodes coloured by verdict and, for a finding, by its kind.

A row that *rests on an erratum* — it uses, directly or through other rows, a row whose kind is an
erratum (``formula`` or ``proof``) — gets a dashed border in that colour, so a reader sees at a
glance which results depend on a corrected formula.

Every node is a link (an SVG ``<a>``, matplotlib's ``set_url``) to the row's page of the reading
site (``make docs``): ``claims/<page_name(id)>.html``. The graph ``make verify`` writes to
``docs/claim-graph.svg`` links into ``docs/_build/html/``, so after ``make docs`` its nodes open
the pages; the site's index draws it again with links relative to the index.

Layout (no graphviz, so CI needs nothing installed by hand): a layered drawing. A row's column is
the length of the longest chain of rows it uses (the rows that use nothing are column 0); inside a
column rows are ordered by the mean position of the rows they use (barycentre sweeps), starting
from ledger order. Drawn with matplotlib into a deterministic SVG (fixed hash salt, no date), so
an unchanged ledger rewrites the same bytes.
"""

from __future__ import annotations

import contextlib
import re
import threading
from collections.abc import Callable, Sequence
from pathlib import Path

from chaplygin_nd.ledger.registry import ERRATA_KINDS, KINDS, VERDICTS
from chaplygin_nd.ledger.runner import Result

#: Fill colour of a node by verdict; a finding is coloured by its kind instead (KIND_COLOUR).
VERDICT_COLOUR = {
    "holds": "#b7e1b0", "definition": "#d9d9d9", "evidence": "#a6d8e6", "corrected": "#f4a582",
    "open": "#ffffff", "fails": "#b2182b", "error": "#404040",
}
KIND_COLOUR = {"formula": "#e34a33", "proof": "#fdae61", "scope": "#fee08b", "reading": "#c2a5cf"}
ERRATUM_EDGE = "#b2182b"

#: Where the nodes of docs/claim-graph.svg link: the site's pages, relative to docs/.
SITE_FROM_DOCS = "_build/html/"


def page_name(claim_id: str) -> str:
    """The stable file name (without ``.html``) of a row's page on the reading site: the label
    with every character outside ``[A-Za-z0-9._-]`` replaced by ``-`` (``P:inversion`` ->
    ``P-inversion``). The site's builder fails if two rows get the same name."""
    return re.sub(r"[^A-Za-z0-9._-]", "-", claim_id)


def site_link(claim_id: str, prefix: str = SITE_FROM_DOCS) -> str:
    """The link of a node: ``prefix`` + ``claims/<page_name>.html``."""
    return f"{prefix}claims/{page_name(claim_id)}.html"


_LAYER_HEIGHT, _BOX_HEIGHT, _GAP = 0.62, 0.26, 0.22  # inches
_FONT_SIZE = 7.5
_CHAR_WIDTH = 0.6 * _FONT_SIZE / 72  # inches per character of the monospace label


def split_cycles(ids: Sequence[str], uses: dict[str, Sequence[str]]):
    """``(acyclic, back)``: the ``uses`` relation without the edges that close a cycle, and those
    edges ``(row, used)``. Uses of an earlier ledger row are kept; a use of a later row is kept
    unless it closes a cycle. A cycle means two rows each use part of the other (e.g. a closed form
    and the definition it inverts); it is drawn dashed and listed in the report."""
    index = {i: k for k, i in enumerate(ids)}
    acyclic: dict[str, list[str]] = {i: [u for u in uses.get(i, ()) if u in index
                                         and index[u] < index[i]] for i in ids}

    def reaches(start: str, goal: str) -> bool:
        seen, stack = set(), [start]
        while stack:
            v = stack.pop()
            if v == goal:
                return True
            if v not in seen:
                seen.add(v)
                stack.extend(acyclic[v])
        return False

    back: list[tuple[str, str]] = []
    for i in ids:
        for u in uses.get(i, ()):
            if u in index and index[u] > index[i]:
                if reaches(u, i):
                    back.append((i, u))
                else:
                    acyclic[i].append(u)
    return acyclic, back


def layers(ids: Sequence[str], uses: dict[str, Sequence[str]]) -> dict[str, int]:
    """Column of each row: 0 if it uses nothing, else 1 + the largest column of what it uses
    (``uses`` must be acyclic: see :func:`split_cycles`)."""
    column: dict[str, int] = {}
    known = set(ids)

    def depth(i: str) -> int:
        if i not in column:
            column[i] = 1 + max((depth(u) for u in uses.get(i, ()) if u in known), default=-1)
        return column[i]

    for i in ids:
        depth(i)
    return column


def positions(ids: Sequence[str], uses: dict[str, Sequence[str]], sweeps: int = 4):
    """(column, row) of every node: columns from :func:`layers`, rows by barycentre sweeps.
    ``uses`` must be acyclic (see :func:`split_cycles`)."""
    column = layers(ids, uses)
    users: dict[str, list[str]] = {i: [] for i in ids}
    for i in ids:
        for u in uses.get(i, ()):
            if u in users:
                users[u].append(i)
    order = {c: [i for i in ids if column[i] == c] for c in sorted(set(column.values()))}
    rank = {i: k for c in order for k, i in enumerate(order[c])}

    def resort(c: int, neighbours) -> None:
        def key(i: str):
            near = [rank[j] for j in neighbours(i)]
            return (sum(near) / len(near) if near else rank[i], rank[i])
        order[c].sort(key=key)
        rank.update({i: k for k, i in enumerate(order[c])})

    for _ in range(sweeps):
        for c in list(order)[1:]:
            resort(c, lambda i: [u for u in uses.get(i, ()) if u in rank])
        for c in list(order)[-2::-1]:
            resort(c, lambda i: users[i])
    return {i: (column[i], rank[i]) for i in ids}


def rests_on_erratum(results: Sequence[Result]) -> dict[str, str]:
    """Rows that use, directly or not, a row whose kind is an erratum -> that kind (the most
    serious one if several)."""
    kind = {r.row.id: r.verdict.kind for r in results}
    uses = {r.row.id: r.uses for r in results}
    found: dict[str, str] = {}
    for r in results:
        seen, stack = set(), list(uses[r.row.id])
        while stack:
            u = stack.pop()
            if u in seen:
                continue
            seen.add(u)
            if kind.get(u) in ERRATA_KINDS:
                prev = found.get(r.row.id)
                here = kind[u]
                if here is not None and (prev is None or KINDS.index(here) < KINDS.index(prev)):
                    found[r.row.id] = here
            stack.extend(uses.get(u, ()))
    return found


def fill(result: Result) -> str:
    """The node colour: the kind's colour for a finding, else the verdict's."""
    if result.verdict.kind:
        return KIND_COLOUR[result.verdict.kind]
    return VERDICT_COLOUR.get(result.status, "#ffffff")


def draw(results: Sequence[Result], link: Callable[[str], str | None] = site_link):
    """The claim graph as a matplotlib figure: layers top to bottom, what is used above its users;
    node ``i`` links to ``link(i)`` (no link when it returns ``None``)."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib import pyplot as plt
    from matplotlib.artist import Artist
    from matplotlib.lines import Line2D
    from matplotlib.patches import FancyBboxPatch, Patch

    ids = [r.row.id for r in results]
    by_id = {r.row.id: r for r in results}
    uses, back = split_cycles(ids, {r.row.id: r.uses for r in results})
    pos = positions(ids, uses)
    resting = rests_on_erratum(results)
    width = {i: len(i) * _CHAR_WIDTH + 0.14 for i in ids}
    layer_of: dict[int, list[str]] = {}
    for i in sorted(ids, key=lambda i: pos[i]):
        layer_of.setdefault(pos[i][0], []).append(i)
    span = {k: sum(width[i] for i in row) + _GAP * (len(row) - 1) for k, row in layer_of.items()}
    widest = max(span.values())
    xy = {}
    for k, row in layer_of.items():
        x = (widest - span[k]) / 2
        for i in row:
            xy[i] = (x, -k * _LAYER_HEIGHT)
            x += width[i] + _GAP

    legend_height = 1.2
    fig_w, fig_h = widest + 0.4, len(layer_of) * _LAYER_HEIGHT + legend_height
    fig = plt.figure(figsize=(fig_w, fig_h))
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_xlim(-0.2, widest + 0.2)
    ax.set_ylim(-(len(layer_of) - 0.5) * _LAYER_HEIGHT, legend_height + 0.5 * _LAYER_HEIGHT - 0.2)
    ax.axis("off")

    edges = [(i, u, False) for i in ids for u in uses[i]] + [(i, u, True) for i, u in back]
    for i, u, closes_cycle in edges:
        (x0, y0), (x1, y1) = xy[u], xy[i]
        bad = by_id[u].verdict.kind in ERRATA_KINDS
        down = y0 > y1
        start = (x0 + width[u] / 2, y0 + (-1 if down else 1) * _BOX_HEIGHT / 2)
        end = (x1 + width[i] / 2, y1 + (1 if down else -1) * _BOX_HEIGHT / 2)
        ax.annotate("", xy=end, xytext=start,
                    arrowprops=dict(arrowstyle="-|>", lw=1.2 if bad else 0.45, mutation_scale=7,
                                    color=ERRATUM_EDGE if bad else "#8c8c8c",
                                    alpha=1.0 if bad else 0.7,
                                    linestyle=(0, (3, 2)) if closes_cycle else "solid",
                                    shrinkA=0, shrinkB=0,
                                    connectionstyle="arc3,rad=0.3" if closes_cycle else "arc3"),
                    zorder=3 if bad else 1)
    for i in ids:
        x, y = xy[i]
        rests = i in resting
        box = ax.add_patch(FancyBboxPatch(
            (x, y - _BOX_HEIGHT / 2), width[i], _BOX_HEIGHT,
            boxstyle="round,pad=0,rounding_size=0.05", facecolor=fill(by_id[i]),
            edgecolor=KIND_COLOUR[resting[i]] if rests else "#303030",
            linewidth=2.0 if rests else 0.6, linestyle=(0, (3, 1.5)) if rests else "solid",
            zorder=4))
        label = ax.text(x + width[i] / 2, y, i, va="center", ha="center", fontsize=_FONT_SIZE,
                        family="monospace", zorder=5,
                        color="#ffffff" if by_id[i].status in ("fails", "error") else "#000000")
        url = link(i)
        if url:
            box.set_url(url)
            label.set_url(url)

    present = {r.status for r in results}
    handles: list[Artist] = [Patch(facecolor=VERDICT_COLOUR.get(v, "#ffffff"), edgecolor="#303030", label=v)
               for v in VERDICTS if v in present and v not in ("corrected", "fails")]
    handles += [Patch(facecolor=KIND_COLOUR[k], edgecolor="#303030",
                      label=f"{k} ({'erratum' if k in ERRATA_KINDS else 'remark'})") for k in KINDS]
    handles += [Patch(facecolor="#ffffff", edgecolor=KIND_COLOUR["formula"], linestyle=(0, (3, 1.5)),
                      linewidth=2.0, label="rests on an erratum (border: its kind)"),
                Line2D([], [], color=ERRATUM_EDGE, lw=1.2, label="uses an erratum row"),
                Line2D([], [], color="#8c8c8c", lw=0.8, linestyle=(0, (3, 2)),
                       label="use that closes a cycle")]
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, 1.0), ncol=4,
              fontsize=8, frameon=False, title="Claim graph of the ledger: an arrow goes from a "
              "row to a row that uses it;\ncolour = verdict, or the kind of a finding",
              title_fontsize=9)
    return fig


def import_beside() -> threading.Thread:
    """Import matplotlib (about 1 s) in a daemon thread of this process, while the ledger's
    workers decide the rows: :func:`render` needs it only after the last row, where the import was
    part of ``verify``'s serial tail. The parent only waits for its workers meanwhile; the import
    lock makes :func:`render`'s own import wait for this one if it is still running."""
    def work() -> None:
        with contextlib.suppress(Exception):   # render imports again and reports any error
            import matplotlib

            matplotlib.use("Agg")
            from matplotlib import pyplot  # noqa: F401

    thread = threading.Thread(target=work, name="import-matplotlib", daemon=True)
    thread.start()
    return thread


def render(results: Sequence[Result], link: Callable[[str], str | None] = site_link) -> str:
    """The claim graph as SVG text (deterministic: fixed hash salt, no date)."""
    import matplotlib

    matplotlib.use("Agg")
    import io

    from matplotlib import pyplot as plt

    with matplotlib.rc_context({"svg.hashsalt": "chaplygin-nd claim graph", "svg.fonttype": "none"}):
        fig = draw(results, link)
        buffer = io.StringIO()
        fig.savefig(buffer, format="svg", metadata={"Date": None, "Creator": None})
        plt.close(fig)
    # matplotlib opens every link in a new window; a node should open its page in place
    return buffer.getvalue().replace(' target="_blank"', "")


def write(results: Sequence[Result], path: Path,
          link: Callable[[str], str | None] = site_link) -> bool:
    """Write the claim graph as SVG to ``path`` (atomically, a unique temporary name); True if
    its content changed."""
    from chaplygin_nd.ledger.report import write_files

    text = render(results, link)
    old = path.read_text(encoding="utf-8") if path.exists() else None
    if old == text:
        return False
    write_files({Path(path): text})
    return True
