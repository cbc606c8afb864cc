"""simulate/ imports no SymPy (DESIGN: a user who only simulates pays no SymPy import), and
long runs report progress on stderr."""

from __future__ import annotations

import io
import subprocess
import sys
from pathlib import Path

from chaplygin_nd.simulate.scene.run import Progress

ROOT = Path(__file__).resolve().parent.parent


def test_simulate_imports_no_sympy():
    modules = sorted(".".join(p.relative_to(ROOT / "simulate").with_suffix("").parts)
                     for p in (ROOT / "simulate").rglob("*.py") if p.stem not in ("__main__", "__init__"))
    code = ("import sys\n" + "".join(f"import chaplygin_nd.simulate.{m}\n" for m in modules)
            + "import chaplygin_nd.simulate.integrators.dop853, chaplygin_nd.simulate.integrators.lie, "
              "chaplygin_nd.simulate.integrators.taylor, chaplygin_nd.simulate.integrators.heyoka_taylor, "
              "chaplygin_nd.simulate.integrators.heyoka_systems, chaplygin_nd.runtime.compiled, "
              "chaplygin_nd.runtime.expressions\n"
            + "assert 'heyoka' not in sys.modules  # imported only when a heyoka run starts\n"
            + "from chaplygin_nd.simulate.kernels import active\nactive()\n"
            + "assert 'sympy' not in sys.modules, sorted(m for m in sys.modules if 'sympy' in m)\n"
            + "print('ok')\n")
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True)
    assert out.returncode == 0 and out.stdout.strip() == "ok", out.stderr


def test_progress_reports_on_stderr_only_for_long_runs():
    stream = io.StringIO()
    quick = Progress(10.0, "quick", after=3600.0, stream=stream)
    quick(5.0)
    quick.done()
    assert stream.getvalue() == ""
    slow = Progress(10.0, "slow", after=0.0, stream=stream)
    slow.last -= 2.0  # pretend the last report is older than a second
    slow(5.0)
    slow.done()
    text = stream.getvalue()
    assert "slow: t = 5 / 10" in text and "50.0%" in text and text.endswith("\n")
