"""The layers of simulate/ (DESIGN: arrows go one way): scene -> analysis -> integrators -> dynamics
-> kernels -> generated/. Read from the source (every import, lazy ones included), so a new module
that imports against the arrows, or closes a circle, fails here with the offending edge; and
simulate/kernels.py is the one module of simulate/ that reaches generated/ and the kernels'
assembly in runtime/ (the heyoka integrator modules use runtime's expression graphs and JIT cache,
which are not kernels but the machinery that compiles them)."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
SIMULATE = ROOT / "simulate"
#: Each layer may import only the layers after it (and itself).
LAYERS = ("scene", "analysis", "integrators", "dynamics", "kernels")
#: The so(n) algebra (vec/unvec, wedge, the SO(n) invariants) imports nothing of simulate, so every
#: layer may use it, the binding included (it reshapes kernel arguments with vec/unvec).
LEAVES = {"chaplygin_nd.simulate.dynamics.so"}


def _module_name(path: Path) -> str:
    parts = path.relative_to(SIMULATE).with_suffix("").parts
    return ".".join(("chaplygin_nd.simulate",) + tuple(p for p in parts if p != "__init__"))


def _imports(path: Path) -> set[str]:
    """Every ``chaplygin_nd.simulate...`` module that ``path`` imports, at any depth of the code."""
    out: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            out.update(a.name for a in node.names if a.name.startswith("chaplygin_nd.simulate"))
        elif isinstance(node, ast.ImportFrom) and (node.module or "").startswith("chaplygin_nd.simulate"):
            for a in node.names:  # ``from pkg import module`` names a module when one exists
                sub = f"{node.module}.{a.name}"
                known = (SIMULATE / Path(*sub.split(".")[2:])).with_suffix(".py")
                out.add(sub if known.exists() or known.with_suffix("").is_dir() else node.module)
    return out


def _layer(module: str) -> str | None:
    parts = module.split(".")
    return parts[2] if len(parts) > 2 and parts[2] in LAYERS else None


GRAPH = {_module_name(p): _imports(p) for p in SIMULATE.rglob("*.py") if p.name != "__main__.py"}


def test_every_module_belongs_to_a_layer():
    assert [m for m in GRAPH if m != "chaplygin_nd.simulate" and _layer(m) is None] == []


@pytest.mark.parametrize("module", sorted(GRAPH))
def test_imports_follow_the_arrows(module):
    here = _layer(module)
    if here is None:
        return  # the package's own __init__ imports nothing (checked by the empty set below)
    against = sorted(t for t in GRAPH[module]
                     if t not in LEAVES and _layer(t) is not None
                     and LAYERS.index(_layer(t)) < LAYERS.index(here))
    assert against == [], f"{module} imports against the arrows: {against}"


def test_the_leaves_import_nothing_of_simulate():
    assert {m: GRAPH[m] for m in LEAVES if GRAPH[m]} == {}


def test_package_init_imports_nothing():
    assert GRAPH["chaplygin_nd.simulate"] == set()


def test_no_import_circle():
    seen: dict[str, int] = {}  # 1 = on the current path, 2 = done

    def visit(m: str, path: list[str]) -> None:
        seen[m] = 1
        for t in sorted(GRAPH.get(m, ())):
            if t not in GRAPH:
                continue
            if seen.get(t) == 1:
                raise AssertionError(" -> ".join(path[path.index(t):] + [t]) if t in path else t)
            if t not in seen:
                visit(t, path + [t])
        seen[m] = 2

    for m in sorted(GRAPH):
        if m not in seen:
            visit(m, [m])


def test_nothing_outside_the_scene_product_imports_the_scene_command():
    users = sorted(str(p.relative_to(ROOT)) for folder in ("simulate", "proofs", "bench", "ledger",
                                                            "symbolic", "runtime", "generated",
                                                            "chaplygin_nd")
                   for p in (ROOT / folder).rglob("*.py") if p.name != "__main__.py"
                   if "chaplygin_nd.simulate.scene.cli" in _imports_any(p)
                   and not str(p.relative_to(ROOT)).startswith("simulate/scene/"))
    assert users == []


def test_proofs_import_analysis_never_the_reverse():
    back = sorted(m for m, targets in GRAPH.items()
                  if any(t.startswith(("chaplygin_nd.proofs", "chaplygin_nd.ledger")) for t in targets))
    assert back == []


def _imports_any(path: Path) -> set[str]:
    out: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            out.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module:
            out.add(node.module)
            out.update(f"{node.module}.{a.name}" for a in node.names)
    return out


#: The one binding of simulate/ to generated/ and to runtime's assembly of the kernels.
BINDING = "simulate/kernels.py"
#: runtime/ modules that are heyoka machinery, not kernels, and the modules of simulate/ that use it.
HEYOKA_RUNTIME = ("chaplygin_nd.runtime.expressions", "chaplygin_nd.runtime.jit_cache")
HEYOKA_MODULES = ("simulate/integrators/heyoka_taylor.py", "simulate/integrators/heyoka_systems.py")


def _reaches(path: Path) -> set[str]:
    """The modules of generated/ and runtime/ that ``path`` imports, at any depth of the code."""
    return {m for m in _imports_any(path)
            if m.startswith(("chaplygin_nd.generated", "chaplygin_nd.runtime"))
            and m not in ("chaplygin_nd.generated", "chaplygin_nd.runtime")}


def test_generated_and_runtime_only_through_the_binding():
    around = {}
    for p in SIMULATE.rglob("*.py"):
        rel = str(p.relative_to(ROOT))
        if rel == BINDING:
            continue
        allowed = HEYOKA_RUNTIME if rel in HEYOKA_MODULES else ()
        bad = sorted(m for m in _reaches(p) if not m.startswith(allowed or ("\0",)))
        if bad:
            around[rel] = bad
    assert around == {}, f"imports of generated/ or runtime/ that go around {BINDING}: {around}"


def test_the_binding_reaches_generated():
    """The rule above is not vacuous: the binding itself imports generated/ and runtime/."""
    text = (ROOT / BINDING).read_text(encoding="utf-8")
    assert "chaplygin_nd.generated." in text and "chaplygin_nd.runtime." in text
