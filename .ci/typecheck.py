"""mypy over the package as Python imports it (``make typecheck``; CI runs it).

The repository keeps its folders at the root and pyproject.toml maps them into ``chaplygin_nd``
(``symbolic/`` is ``chaplygin_nd.symbolic``, ...); mypy cannot follow that mapping, so this
script assembles the namespace in a temporary folder (links to the real folders, outside the
tree) and runs ``mypy -p chaplygin_nd`` there with the settings of ``[tool.mypy]``. The errors
name the real files. Exit status: mypy's.
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def main() -> int:
    config = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    mapping = config["tool"]["setuptools"]["package-dir"]
    with tempfile.TemporaryDirectory(prefix="chaplygin-typecheck-") as tmp:
        top = Path(tmp) / "chaplygin_nd"
        top.mkdir()
        for entry in (ROOT / mapping["chaplygin_nd"]).iterdir():
            (top / entry.name).symlink_to(entry)
        for package, folder in mapping.items():
            if package != "chaplygin_nd":
                (top / package.split(".", 1)[1]).symlink_to(ROOT / folder)
        cmd = [sys.executable, "-m", "mypy", "--config-file", str(ROOT / "pyproject.toml"),
               "--cache-dir", str(ROOT / ".venv" / "mypy-cache"), "-p", "chaplygin_nd"]
        r = subprocess.run(cmd, cwd=tmp, capture_output=True, text=True)
    # the subpackages' folders have their names, so dropping the prefix names the real files
    sys.stdout.write((r.stdout + r.stderr).replace("chaplygin_nd/", ""))
    return r.returncode


if __name__ == "__main__":
    sys.exit(main())
