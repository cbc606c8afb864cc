"""The code generator: a hand edit of generated/ is caught, and output is deterministic.

The stale check is :func:`symbolic.codegen.kernels.stale_report`, called by ``make verify``
(``chaplygin verify --check-generated``). These tests edit a *temporary copy* of generated/, never
the real files.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from chaplygin_nd.symbolic.codegen import kernels


@pytest.fixture(scope="module")
def fresh(tmp_path_factory) -> Path:
    """generated/ regenerated once into a temporary folder."""
    out = tmp_path_factory.mktemp("fresh")
    kernels.write(out)
    return out


def test_checked_in_generated_is_current(fresh):
    """generated/ in the repository equals what symbolic/ produces now (else: `make generate`)."""
    assert kernels.diff_report(kernels.GENERATED, fresh) == ""


def test_hand_edit_is_detected_with_diff_and_fix(fresh, tmp_path):
    """Editing one generated line makes the stale report non-empty, show the line and the fix."""
    copy = tmp_path / "generated"
    shutil.copytree(kernels.GENERATED, copy)
    target = copy / "axisym.py"
    text = target.read_text()
    line = next(li for li in text.splitlines() if li.strip().startswith("out[0] = "))
    target.write_text(text.replace(line, line + " * 1.0000001", 1))
    report = kernels.stale_report(copy)
    assert "generated/ is stale" in report
    shown = report.splitlines()
    assert "-" + line + " * 1.0000001" in shown and "+" + line in shown  # the edit, and what is due
    assert "make generate" in report
    # a deleted file and an extra file are stale too
    target.write_text(text)  # restored: no difference (diff_report is stale_report's comparison)
    assert kernels.diff_report(copy, fresh) == ""
    (copy / "reduced.py").unlink()
    assert "reduced.py" in kernels.diff_report(copy, fresh)


def test_banner(fresh):
    """Every generated module names its producer, claims, input hash, 'do not edit' and op counts,
    and imports NumPy only."""
    for stem, producer in kernels.MODULES:
        text = (fresh / f"{stem}.py").read_text()
        head = text[:3000]
        assert producer in head and "DO NOT EDIT" in head and "Source hash (sha256" in head
        assert "Operation counts after CSE:" in head and "Claims:" in head
        imports = {li.strip() for li in text.splitlines() if li.startswith(("import ", "from "))}
        assert imports == {"import numpy", "import numpy as np", "from chaplygin_nd.generated._batching import _run"}
    runtime = (fresh / "_batching.py").read_text()
    assert "DO NOT EDIT" in runtime
    assert {li.strip() for li in runtime.splitlines() if li.startswith(("import ", "from "))} \
        == {"import numpy as np"}


@pytest.mark.slow  # derives every kernel again in a fresh process (~6 CPU-s): make test-slow
def test_deterministic_across_hash_seeds(fresh, tmp_path):
    """Same input => byte-identical files, whatever PYTHONHASHSEED the generating process has."""
    out = tmp_path / "seeded"
    code = f"from pathlib import Path; from symbolic.codegen.kernels import write; write(Path({str(out)!r}))"
    env = dict(os.environ, PYTHONHASHSEED="12345")
    subprocess.run([sys.executable, "-c", code], check=True, env=env, cwd=kernels.ROOT, timeout=120)
    assert kernels.diff_report(out, fresh) == ""


def test_expression_builders_are_stamped_import_nothing_and_are_stale_checked(fresh, tmp_path):
    """generated/expression_builders.py (the heyoka builders) has the banner, imports nothing (so
    generated/ imports without heyoka), and a hand edit of it is caught like any kernel's."""
    text = (fresh / "expression_builders.py").read_text()
    head = text[:3000]
    assert "DO NOT EDIT" in head and "Source hash (sha256" in head and "Operation counts after CSE:" in head
    assert not [li for li in text.splitlines() if li.startswith(("import ", "from "))]
    copy = tmp_path / "generated"
    shutil.copytree(fresh, copy)
    target = copy / "expression_builders.py"
    target.write_text(text.replace("ops.rational(1, 2)", "ops.rational(1, 3)", 1))
    assert "expression_builders.py" in kernels.diff_report(copy, fresh)


def test_the_regeneration_beside_the_rows_records_the_emitted_derivations():
    """verify's task beside the rows regenerates generated/ and records the derivations it calls:
    the same list as emitted_derivations (which verify no longer derives a second time)."""
    from chaplygin_nd.ledger import reach

    text, emitted = reach.regenerated_and_emitted()
    assert text == ""
    assert emitted and emitted == reach.emitted_derivations()
