"""The bench's plumbing, not its speed: ``chaplygin bench -h`` prints usage, an unknown name is a
usage error (exit 2), outputs are written atomically as JSON rows, target lines say MET or NOT MET,
and the drift-growth fit used to extrapolate the long run recovers a known exponent."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent


def _bench(*args):
    return subprocess.run([sys.executable, "-m", "chaplygin_nd.bench", *args], cwd=ROOT, capture_output=True,
                          text=True, timeout=120)


def test_help_and_unknown_name():
    ok = _bench("-h")
    assert ok.returncode == 0 and "usage: chaplygin bench" in ok.stdout
    assert "work_precision" in ok.stdout and "throughput" in ok.stdout
    bad = _bench("no_such_bench")
    assert bad.returncode == 2 and "unknown benchmark no_such_bench" in bad.stderr
    assert bad.stdout == ""


def test_rows_written_atomically_and_targets_worded(tmp_path):
    sys.path.insert(0, str(ROOT))
    from chaplygin_nd.bench.report import target, write_rows

    path = tmp_path / "rows.json"
    path.write_text("old")
    write_rows(path, [{"backend": "copy", "seconds": np.float64(0.5), "error": float("nan")}])
    assert json.loads(path.read_text()) == [{"backend": "copy", "seconds": 0.5, "error": None}]
    assert [p.name for p in tmp_path.iterdir()] == ["rows.json"]  # no temporary left behind
    assert target("x", True, "d") == "- x: MET — d"
    assert target("x", False, "d") == "- x: NOT MET — d"


def test_drift_growth_fit_recovers_exponent():
    sys.path.insert(0, str(ROOT))
    from chaplygin_nd.bench.sections_models import growth

    steps = np.arange(0, 20001, 200, dtype=float)
    for alpha in (0.5, 1.0):
        alpha_fit, c = growth(steps, 3e-17 * steps ** alpha)
        assert abs(alpha_fit - alpha) < 1e-9 and abs(c / 3e-17 - 1) < 1e-6
    assert np.isnan(growth(steps, np.zeros_like(steps))[0])
