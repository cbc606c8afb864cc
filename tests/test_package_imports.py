"""The package root has no import circle: ``chaplygin_nd/__init__`` re-exports the notebook API
(:mod:`chaplygin_nd.api`), the command line (:mod:`chaplygin_nd.cli`) imports the package for its
version, so the notebook API must not import a command line (it once reached ``chaplygin_nd.cli``
through the scene command for the summary text). Read from the source, every import at any depth
of the code (deferred ones too), over every module of the installed namespace."""

from __future__ import annotations

import ast
import functools
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
#: The folders mapped into the namespace (pyproject.toml's package-dir) that hold Python code.
FOLDERS = {"chaplygin_nd": "chaplygin_nd", "symbolic": "chaplygin_nd.symbolic",
           "proofs": "chaplygin_nd.proofs", "ledger": "chaplygin_nd.ledger",
           "generated": "chaplygin_nd.generated", "runtime": "chaplygin_nd.runtime",
           "simulate": "chaplygin_nd.simulate", "bench": "chaplygin_nd.bench"}


def _name(path: Path) -> str:
    folder, *rest = path.relative_to(ROOT).with_suffix("").parts
    return ".".join([FOLDERS[folder], *(p for p in rest if p != "__init__")])


MODULES = {_name(p): p for folder in FOLDERS for p in (ROOT / folder).rglob("*.py")
           if p.name != "__main__.py"}


def _targets(path: Path) -> set[str]:
    """The project modules ``path`` imports: ``from pkg import mod`` names ``pkg.mod`` when that is
    a module (the parent package is loaded by then; only a name read from ``pkg`` is an arrow to
    ``pkg``)."""
    out: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            out.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            for a in node.names:
                sub = f"{node.module}.{a.name}"
                out.add(sub if sub in MODULES else node.module)
    return {m for m in out if m in MODULES}


@functools.cache
def _graph() -> dict[str, set[str]]:
    """Module -> the project modules it imports (read when a test first asks, not at collection:
    both xdist workers collect this file)."""
    return {m: _targets(p) for m, p in MODULES.items()}


def _circle_through(start: str) -> list[str] | None:
    """A shortest import path from ``start`` back to itself, or None."""
    parent: dict[str, str] = {}
    frontier = [start]
    while frontier:
        nxt = []
        for m in frontier:
            for t in sorted(_graph()[m]):
                if t == start:
                    path = [m]
                    while path[-1] != start:
                        path.append(parent[path[-1]])
                    return [*reversed(path), start]
                if t not in parent and t != start:
                    parent[t] = m
                    nxt.append(t)
        frontier = nxt
    return None


#: The modules of the package root: the namespace itself, the notebook API and the command line.
ROOT_MODULES = ("chaplygin_nd", "chaplygin_nd.api", "chaplygin_nd.cli")


def test_the_graph_is_read():
    assert "chaplygin_nd.api" in _graph()["chaplygin_nd"]          # the deferred re-export
    assert "chaplygin_nd" in _graph()["chaplygin_nd.cli"]          # the version
    assert "chaplygin_nd.simulate.scene.planner" in _graph()["chaplygin_nd.api"]


def test_no_circle_through_the_package_root():
    circles = {m: _circle_through(m) for m in ROOT_MODULES}
    assert {m: " -> ".join(c) for m, c in circles.items() if c} == {}


def test_the_notebook_api_imports_no_command_line():
    reached, todo = set(), ["chaplygin_nd.api"]
    while todo:
        m = todo.pop()
        for t in _graph()[m]:
            if t not in reached:
                reached.add(t)
                todo.append(t)
    assert sorted(m for m in reached if m.endswith(".cli")) == []
