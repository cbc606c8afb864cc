r"""Power of the evidence rows on planted defects: the rows run on a *wrong* field must
not say ``evidence``.

Each defect is one textual edit of ``generated/expression_builders.py`` in a temporary copy of the
package (laid out as pyproject's ``package-dir``; the tree is never touched), run in a subprocess
(``python -I -B``, the copy first on ``sys.path``, an empty result cache):

* ``coefficient`` — the weight of $M^2E_n\wedge E_n$ in $\dot M$ of the structured field
  (S4:structured-field, the form heyoka integrates) times 1.01: one coefficient of the full field
  eq:motion-general off by 1 %;
* ``sign`` — the sign of the $ME_n$ term of $\dot\gamma$ flipped;
* ``reduced-coefficient`` / ``reduced-sign`` — the same in eq:red-system (the field of S5:EJ-tori):
  $\dot E$ times 1.01; the sign of the $ab\,x^2G$ term of $\dot x$.

Only the heyoka field is edited; the integrals are evaluated by the (correct) NumPy kernels, so the
drift of $H$ and $p(\lambda, \sigma)$ (or $F_1..F_3, H$) along the orbits shows whether the planted
field is a defect at all. Per defect and row: the verdict, which parts of the rule failed
(integrals, frequencies, chaos indicator) and the numbers.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tempfile
import tomllib
from pathlib import Path

from chaplygin_nd import processes

ROOT = Path(__file__).resolve().parent.parent

#: (name, the unique original text, its replacement, the rows it is run against)
DEFECTS = (
    ("coefficient", "        _t8,\n        _t10*_t9,\n", "        _t8,\n        1.01*_t10*_t9,\n",
     ("S5:reconstruction", "Th:Re-tori:frequencies", "S6:open-reduced-n5")),
    ("sign", "        _t10*_t16*x,\n", "        -_t10*_t16*x,\n",
     ("S5:reconstruction", "Th:Re-tori:frequencies", "S6:open-reduced-n5")),
    ("reduced-coefficient", "        _t15*(-E*G*_t16 - F1*_t14*x),",
     "        1.01*_t15*(-E*G*_t16 - F1*_t14*x),", ("S5:EJ-tori",)),
    ("reduced-sign", "        _t15*(G*_t26 - _t11*_t25),", "        _t15*(G*_t26 + _t11*_t25),",
     ("S5:EJ-tori",)),
)

_RUN = """
import json, sys
sys.path.insert(0, {pkg!r})
from chaplygin_nd.ledger.catalog import discover
from chaplygin_nd.ledger.registry import registry
discover()
out = {{}}
for row in {rows!r}:
    v = registry()[row].run()
    data = v.evidence or {{}}
    drifts = [o.get("drift") for o in data.get("orbits", []) if o.get("drift") is not None]
    n = v.notes or ""
    why = (n[:n.index(")") + 1] if n.startswith("the measurement does not support") and ")" in n
           else n.split(": ", 1)[0])
    out[row] = {{"verdict": v.verdict, "unmet": [why] if v.verdict == "open" else [],
                "control_separates": data.get("control_separates"),
                "drift_max": max(drifts) if drifts else None,
                "drift_median": sorted(drifts)[len(drifts) // 2] if drifts else None,
                "parts": data.get("parts", {{}})}}
print("RESULT " + json.dumps(out))
"""


def copy_package(dest: Path) -> Path:
    """The project's packages under ``dest/chaplygin_nd`` as pyproject maps them (symbolic links
    to the paper and scenes resolved)."""
    mapping = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["package-dir"]
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc")
    for package, folder in sorted(mapping.items()):
        shutil.copytree(ROOT / folder, dest.joinpath(*package.split(".")), ignore=ignore,
                        dirs_exist_ok=True, symlinks=False)
    return dest


def plant(pkg: Path, old: str, new: str) -> None:
    """Replace the unique ``old`` by ``new`` in the copy's generated/expression_builders.py."""
    path = pkg / "chaplygin_nd" / "generated" / "expression_builders.py"
    text = path.read_text()
    if text.count(old) != 1:
        raise ValueError(f"the planted edit does not match once: {old!r}")
    path.write_text(text.replace(old, new))


def run_rows(pkg: Path, rows, timeout: float = 1200.0) -> dict:
    """Run ``rows`` in the copy ``pkg`` (fresh result cache); ``{row: {...}}``."""
    with tempfile.TemporaryDirectory(prefix="planted-cache-") as cache:
        env = {k: v for k, v in os.environ.items() if not k.startswith("PYTHON")}
        env["CHAPLYGIN_ND_CACHE"] = cache
        r = subprocess.run([sys.executable, "-I", "-B", "-c", _RUN.format(pkg=str(pkg), rows=list(rows))],
                           env=env, capture_output=True, text=True, timeout=timeout,
                           **processes.popen_kwargs())  # the child dies with this process
    line = [x for x in r.stdout.splitlines() if x.startswith("RESULT ")]
    if r.returncode != 0 or not line:
        return {row: {"verdict": "error", "unmet": [r.stderr.strip().splitlines()[-1:]]} for row in rows}
    return json.loads(line[-1][len("RESULT "):])


def run(defects=DEFECTS) -> list[dict]:
    """Every defect against its rows; one record per (defect, row)."""
    out = []
    for name, old, new, rows in defects:
        with tempfile.TemporaryDirectory(prefix="planted-") as tmp:
            pkg = copy_package(Path(tmp) / "site")
            plant(pkg, old, new)
            res = run_rows(Path(tmp) / "site", rows)
        for row in rows:
            out.append({"defect": name, "row": row, **res[row]})
            print(f"planted {name}: {row} -> {res[row]['verdict']}", flush=True)
    return out


def markdown(records) -> str:
    """The planted-defect table: per (defect, row) the verdict, the drift of the integrals and
    which parts of the row's rule held (yes) or caught the defect (CAUGHT)."""
    lines = ["## Planted defects (bench/planted.py)", "",
             "Which part of each row's rule caught the defect: CAUGHT = failed on the planted field.", "",
             "| defect | row | verdict | max / median drift of the integrals | integrals | chaos "
             "indicator | frequencies | control separates |", "|---|---|---|---|---|---|---|---|"]
    for r in records:
        parts = r.get("parts") or {}
        cells = [("CAUGHT" if parts.get(k) is False else "yes" if parts.get(k) else "-")
                 for k in ("integrals", "chaos", "frequencies")]
        drift = (f"{r['drift_max']:.1e} / {r['drift_median']:.1e}" if r.get("drift_max") is not None
                 else "-")
        verdict = r["verdict"] if r["verdict"] != "error" else (
            "error: " + " ".join(str(u) for u in r.get("unmet", [])).replace("|", "/")[:120])
        sep = {True: "yes", False: "no"}.get(r.get("control_separates"), "-")
        lines.append(f"| {r['defect']} | {r['row']} | {verdict} | {drift} | " + " | ".join(cells)
                     + f" | {sep} |")
    return "\n".join(lines) + "\n"
