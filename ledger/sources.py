r"""Where each ledger row lives in the code, recorded by the run for the reading site.

``chaplygin verify`` writes, per row of ``verification.json``, a ``sources`` record (:func:`collect`):

* ``proof``: the claim script's module, its path, the line span of the ``@claim`` function
  (decorator included), that source text and the module's docstring;
* ``printed``: for each function of ``symbolic/printed`` the row called (the run's ``printed``
  list), its path, line span and source (the literal transcription);
* ``paper_lines``: the lines of the .tex that ``symbolic/printed`` says it transcribed for the row
  (``SOURCE`` tables and ``ID (lines a-b)`` in its text);
* ``kernels``: the ``module.function`` of ``generated/`` whose docstring's ``Claims:`` line names it;
* ``tests``: the ``tests/file::test`` functions whose source names the row in quotes (a checkout
  only: an installed wheel has no tests, the list is then empty).

The site (``docs/build_pages.py``) reads this record and the paper and nothing else of the code:
no import of proofs or printed modules, no scan of generated/ or tests/ at site-build time.
Row ids beyond the paper and ids in SOURCE tables are read as text; nothing here decides a verdict.
"""

from __future__ import annotations

import ast
import importlib
import inspect
import re
from collections.abc import Iterable, Sequence
from pathlib import Path

from chaplygin_nd.ledger.catalog import ROOT
from chaplygin_nd.ledger.registry import ClaimSpec

__all__ = ["collect", "proof_source", "printed_source", "paper_lines", "kernels_by_claim",
           "tests_by_claim"]

#: A ``ID (lines a-b)`` reference longer than this is not a transcription of one statement.
_MAX_LINES = 40


def _relative(path: str | Path) -> str:
    """``path`` relative to the package root (``proofs/x.py``), or as given when outside it."""
    p = Path(path).resolve()
    try:
        return p.relative_to(ROOT).as_posix()
    except ValueError:
        return p.as_posix()


def _span(obj) -> dict:
    """Path, 1-based inclusive line span and source text of a function (decorators included)."""
    lines, first = inspect.getsourcelines(obj)
    return {"path": _relative(inspect.getsourcefile(obj) or ""),
            "lines": [first, first + len(lines) - 1], "source": "".join(lines)}


def proof_source(spec: ClaimSpec) -> dict:
    """The ``@claim`` function deciding a row: module, path, line span, source, module docstring."""
    module = inspect.getmodule(spec.run)
    return {"module": spec.module, **_span(spec.run), "doc": inspect.getdoc(module) or ""}


def printed_source(name: str) -> dict:
    """``module.function`` of ``symbolic/printed``: path, line span and source (``{"name": name}``
    alone when it cannot be found)."""
    module, _, func = name.partition(".")
    try:
        obj = getattr(importlib.import_module(f"chaplygin_nd.symbolic.printed.{module}"), func)
        return {"name": name, **_span(obj)}
    except (ImportError, AttributeError, TypeError, OSError):
        return {"name": name}


def paper_lines(printed_dir: Path) -> dict[str, list[int]]:
    """claim id -> the .tex lines ``symbolic/printed`` says it transcribed (SOURCE tables and
    ``ID (lines a-b)`` / ``ID (line a)`` / ``lines a and b`` in its docstrings and comments)."""
    found: dict[str, set[int]] = {}
    for path in sorted(printed_dir.glob("section*.py")):
        text = path.read_text(encoding="utf-8")
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, ast.Assign) and any(getattr(t, "id", "") == "SOURCE"
                                                     for t in node.targets):
                for cid, lines in ast.literal_eval(node.value).items():
                    found.setdefault(cid, set()).update(lines)
        for m in re.finditer(r"([A-Za-z0-9]+:[\w:.-]+)\s*\(lines?\s+(\d+)(?:\s*(?:-|–|and)\s*(\d+))?",
                             text):
            cid, a, b = m.group(1), int(m.group(2)), int(m.group(3) or m.group(2))
            if b >= a and b - a < _MAX_LINES:
                found.setdefault(cid, set()).update(range(a, b + 1))
    return {cid: sorted(lines) for cid, lines in found.items()}


def kernels_by_claim(generated: Path) -> dict[str, list[str]]:
    """claim id -> ``module.function`` of generated/ whose docstring's ``Claims:`` line names it."""
    out: dict[str, list[str]] = {}
    for path in sorted(generated.glob("*.py")):
        for node in ast.parse(path.read_text(encoding="utf-8")).body:
            if isinstance(node, ast.FunctionDef) and not node.name.startswith("_"):
                doc = ast.get_docstring(node) or ""
                m = re.search(r"Claims:\s*([^\n]*?)\.?(?:\s+Operations|\n|$)", doc)
                for cid in (c.strip() for c in (m.group(1).split(",") if m else [])):
                    out.setdefault(cid, []).append(f"{path.stem}.{node.name}")
    return out


def tests_by_claim(tests: Path, ids: Iterable[str]) -> dict[str, list[str]]:
    """claim id -> ``tests/file::test`` of every test function whose source has the id in quotes
    (``{}`` when ``tests`` is not a folder, as in an installed wheel)."""
    out: dict[str, list[str]] = {}
    ids = list(ids)
    for path in sorted(tests.glob("test_*.py")) if tests.is_dir() else []:
        text = path.read_text(encoding="utf-8")
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, ast.FunctionDef) and node.name.startswith("test"):
                body = ast.get_source_segment(text, node) or ""
                for cid in ids:
                    if f'"{cid}"' in body or f"'{cid}'" in body:
                        out.setdefault(cid, []).append(f"tests/{path.name}::{node.name}")
    return out


def collect(rows: Sequence[tuple[str, tuple[str, ...]]], specs: dict[str, ClaimSpec]
            ) -> dict[str, dict]:
    """row id -> its ``sources`` record (see the module docstring), for ``rows`` given as
    ``(id, printed functions called)``; ``specs``: the registered proofs."""
    lines = paper_lines(ROOT / "symbolic" / "printed")
    kernels = kernels_by_claim(ROOT / "generated")
    tests = tests_by_claim(ROOT / "tests", [cid for cid, _ in rows])
    out = {}
    for cid, printed in rows:
        spec = specs.get(cid)
        out[cid] = {"proof": proof_source(spec) if spec is not None else None,
                    "printed": [printed_source(name) for name in printed],
                    "paper_lines": lines.get(cid, []), "kernels": kernels.get(cid, []),
                    "tests": tests.get(cid, [])}
    return out
