"""One import namespace: every folder of Python code is a subpackage of
``chaplygin_nd`` in pyproject.toml, and no module imports a project folder by its bare name (which
would work in a checkout by accident and break in a wheel, or clobber another distribution)."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CONFIG = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["tool"]["setuptools"]
FOLDERS = {pkg: ROOT / folder for pkg, folder in CONFIG["package-dir"].items()}


def _python_folders() -> dict[str, Path]:
    """Every folder below a mapped folder that holds Python modules, by its dotted package name."""
    found = {}
    for pkg, folder in FOLDERS.items():
        for init in folder.rglob("__init__.py"):
            rel = init.parent.relative_to(folder)
            found[".".join((pkg, *rel.parts))] = init.parent
    return found


def test_every_python_folder_is_a_listed_package():
    assert set(_python_folders()) == set(CONFIG["packages"])
    for folder in FOLDERS.values():  # no module outside a package
        for module in folder.rglob("*.py"):
            assert (module.parent / "__init__.py").is_file(), f"{module} is in no package"


def test_no_bare_project_imports():
    names = "symbolic|proofs|ledger|generated|runtime|simulate|bench"
    bare = re.compile(rf"^\s*(?:from\s+(?:{names})(?:\.[\w.]+)?\s+import\b|import\s+(?:{names})\b)", re.M)
    offenders = [f"{p.relative_to(ROOT)}: {m.group(0).strip()}"
                 for folder in [*FOLDERS.values(), ROOT / "tests", ROOT / "docs"]
                 for p in folder.rglob("*.py") for m in bare.finditer(p.read_text(encoding="utf-8"))]
    assert offenders == []
