"""The import graph of symbolic/ has no circle (DESIGN: arrows go one way). Read from the source,
every import at any depth of the code (deferred ones inside functions too), so a module that
closes a circle fails here with the circle it closes."""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SYMBOLIC = ROOT / "symbolic"
PREFIX = "chaplygin_nd.symbolic"


def _module_name(path: Path) -> str:
    parts = path.relative_to(SYMBOLIC).with_suffix("").parts
    return ".".join((PREFIX,) + tuple(p for p in parts if p != "__init__"))


def _is_module(name: str) -> bool:
    rel = Path(*name.split(".")[2:]) if name != PREFIX else Path()
    return (SYMBOLIC / rel).with_suffix(".py").exists() or (SYMBOLIC / rel / "__init__.py").exists()


def _imports(path: Path) -> set[str]:
    """Every ``chaplygin_nd.symbolic...`` module that ``path`` imports, at any depth of the code
    (``from pkg import name`` counts the module ``pkg.name`` when it exists, else ``pkg``)."""
    out: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            out.update(a.name for a in node.names if a.name.startswith(PREFIX))
        elif isinstance(node, ast.ImportFrom) and (node.module or "").startswith(PREFIX):
            for a in node.names:
                sub = f"{node.module}.{a.name}"
                out.add(sub if _is_module(sub) else node.module)
    return out


GRAPH = {_module_name(p): _imports(p) for p in SYMBOLIC.rglob("*.py")}


def _circles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components with more than one module, or a module importing itself
    (Tarjan's algorithm, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []
    counter = 0
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph.get(root, ()))))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on.add(root)
        while work:
            v, it = work[-1]
            for w in it:
                if w not in graph:
                    continue
                if w not in index:
                    index[w] = low[w] = counter
                    counter += 1
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(graph.get(w, ())))))
                    break
                if w in on:
                    low[v] = min(low[v], index[w])
            else:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[v])
                if low[v] == index[v]:
                    comp = []
                    while True:
                        w = stack.pop()
                        on.discard(w)
                        comp.append(w)
                        if w == v:
                            break
                    if len(comp) > 1 or v in graph.get(v, ()):
                        out.append(sorted(comp))
    return out


def test_the_reader_sees_a_circle_closed_by_a_deferred_import():
    """The check itself: a circle through an import inside a function is found."""
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}, "e": {"e"}}
    assert _circles(graph) == [["a", "b", "c"], ["e"]]
    tree = ast.parse("def f():\n    from chaplygin_nd.symbolic.search import backend\n")
    found = [n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)]
    assert found == ["chaplygin_nd.symbolic.search"]


def test_the_graph_holds_the_search_modules():
    search = {m for m in GRAPH if m.startswith(f"{PREFIX}.search.")}
    assert f"{PREFIX}.search.box_search" in search and f"{PREFIX}.search.backend" in search
    assert f"{PREFIX}.search.backend" in GRAPH[f"{PREFIX}.search.box_search"]


def test_no_import_circle_in_symbolic():
    assert _circles(GRAPH) == []
