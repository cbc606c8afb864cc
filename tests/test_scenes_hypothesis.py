"""Property: any scene file gives exit 0 with outputs, or exit 2 with one line and nothing written —
never a traceback, a hang or a write outside ``--out``.

Scene files are generated from a small valid scene by replacing, deleting or adding keys with wrong
types, NaN/inf, extreme magnitudes, empty or mismatched arrays, deep nesting and unicode. The CLI
runs in-process (with the memory and time limits of simulate.scene.budget lowered so that a costly scene
is refused at once, which is the path under test); a few cases run as a subprocess for the real
exit status and stderr. Fixed CI profile: derandomized, no deadline.
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import shutil
import signal
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest
from chaplygin_nd.simulate.scene import budget, cli
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

settings.register_profile("ci", max_examples=120, deadline=None, derandomize=True,
                          suppress_health_check=[HealthCheck.too_slow,
                                                 HealthCheck.function_scoped_fixture])
CI = settings.get_profile("ci")

BASE = {"title": "small", "n": 3, "a": 0.5, "b": 1.0,
        "initial": {"family": "generic", "seed": 1},
        "times": {"t_end": 1.0, "samples": 5},
        "outputs": {"want": ["x"]},
        "accuracy": {"target": 1e-8, "method": "dop853"}}
KEYS = [("n",), ("a",), ("b",), ("radius",), ("title",),
        ("initial", "family"), ("initial", "seed"), ("initial", "count"), ("initial", "scale"),
        ("initial", "members"), ("initial", "M"), ("initial", "Omega"), ("initial", "gamma"),
        ("initial", "tolerance"), ("times", "t_end"), ("times", "samples"), ("times", "t"),
        ("outputs", "want"), ("accuracy", "target"), ("accuracy", "method"), ("accuracy", "dps"),
        ("accuracy", "step"), ("ball", "mass"), ("ball", "inertia"), ("extra",),
        ("initial", "extra"), ("outputs", "extra")]
NAMES = ["M", "Omega", "gamma", "x", "integrals", "zeta", "reduced", "horizontal", "orientation",
         "contact_path", "frequencies", "poincare", "", "ü", "X"]

numbers = st.one_of(
    st.sampled_from([0, 1, -1, 3, 4, 2**62, -(2**63), 0.0, -0.0, 0.5, 1e-300, 5e-324, 1e308,
                     -1e308, math.nan, math.inf, -math.inf, 1e-12, 100.0, 10**9]),
    st.integers(-5, 10), st.floats(allow_nan=True, allow_infinity=True))
scalars = st.one_of(numbers, st.booleans(), st.text(max_size=8),
                    st.sampled_from(["generic", "vertical", "horizontal", "steady-rotation",
                                     "explicit", "auto", "lie", "heyoka", "reference", "x", "π"]))
arrays = st.one_of(
    st.lists(numbers, max_size=5),
    st.lists(st.lists(numbers, min_size=0, max_size=4), max_size=4),
    st.lists(st.sampled_from(NAMES), max_size=4),
    st.just([]), st.just([[]]),
    st.integers(1, 40).map(lambda d: _nest(d)))
values = st.one_of(scalars, arrays, st.dictionaries(st.sampled_from(["a", "b", "x"]), scalars,
                                                    max_size=2))


def _nest(depth):
    v = [1.0]
    for _ in range(depth):
        v = [v]
    return v


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return "nan" if math.isnan(v) else ("inf" if v > 0 else "-inf") if math.isinf(v) else repr(v)
    if isinstance(v, str):
        return json.dumps(v)  # a TOML basic string
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    return "{" + ", ".join(f"{k} = {_toml_value(x)}" for k, x in v.items()) + "}"


def toml_text(scene: dict) -> str:
    """A small TOML writer (top-level keys, then one [table] per dict)."""
    top = [f"{k} = {_toml_value(v)}" for k, v in scene.items() if not isinstance(v, dict)]
    tables = [f"[{k}]\n" + "\n".join(f"{kk} = {_toml_value(vv)}" for kk, vv in v.items())
              for k, v in scene.items() if isinstance(v, dict)]
    return "\n".join(top + tables) + "\n"


@st.composite
def scenes(draw):
    scene = json.loads(json.dumps(BASE))
    for _ in range(draw(st.integers(1, 4))):
        key = draw(st.sampled_from(KEYS))
        table = scene
        for part in key[:-1]:
            table = table.setdefault(part, {})
            if not isinstance(table, dict):
                break
        else:
            if draw(st.booleans()) and key[-1] in table:
                del table[key[-1]]
            else:
                table[key[-1]] = draw(values)
    return toml_text(scene)


@contextlib.contextmanager
def _alarm(seconds: int):
    def on_alarm(signum, frame):
        raise TimeoutError(f"the run took more than {seconds} s (a hang)")
    old = signal.signal(signal.SIGALRM, on_alarm)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


def _check_one(text: str, monkeypatch) -> None:
    root = Path(tempfile.mkdtemp(prefix="scene-prop-"))
    try:
        scene, out = root / "s.toml", root / "out"
        scene.write_text(text, encoding="utf-8")
        stdout, stderr = io.StringIO(), io.StringIO()
        with monkeypatch.context() as m:
            m.setattr(budget, "memory_limit", lambda: 64 << 20)
            m.setattr(budget, "LIMIT_SECONDS", 4.0)
            m.chdir(root)
            with _alarm(60), contextlib.redirect_stdout(stdout), contextlib.redirect_stderr(stderr):
                code = cli.main([str(scene), "--out", str(out), "--no-plots"])
        err = [line for line in stderr.getvalue().splitlines() if not line.startswith("cost:")]
        assert sorted(p.name for p in root.iterdir()) in (["s.toml"], ["out", "s.toml"]), text
        if code == 0:
            assert (out / "summary.txt").is_file() and (out / "outputs.npz").is_file(), text
        else:
            assert code == 2, (code, text, stderr.getvalue())
            assert len(err) == 1 and err[0].startswith("error: "), (text, stderr.getvalue())
            assert not out.exists(), text
    finally:
        shutil.rmtree(root, ignore_errors=True)


@CI
@given(scenes())
def test_any_scene_runs_or_is_refused_with_one_line(monkeypatch, text):
    _check_one(text, monkeypatch)


@pytest.mark.parametrize("text", [
    toml_text(BASE),
    toml_text({**BASE, "a": math.nan}),
    "n = 3\na = 0.5\nb = 1.0\n[initial]\ngamma = " + "[" * 5000 + "]" * 5000 + "\n",
    toml_text({**BASE, "title": "ünïcødé — ∞", "times": {"t_end": 5e-324, "samples": 5}}),
])
def test_subprocess_exit_status_and_one_line(tmp_path, text):
    scene = tmp_path / "s.toml"
    scene.write_text(text, encoding="utf-8")
    r = subprocess.run([sys.executable, "-m", "chaplygin_nd", "simulate", str(scene), "--out",
                        str(tmp_path / "o"), "--no-plots"], capture_output=True, text=True,
                       timeout=300, env={**_env(), "PYTHONIOENCODING": "ascii"})
    assert "Traceback" not in r.stderr
    if r.returncode == 0:
        assert (tmp_path / "o" / "summary.txt").is_file()
    else:
        assert r.returncode == 2 and r.stderr.count("\n") == 1, r.stderr
        assert not (tmp_path / "o").exists()


def _env():
    import os

    return dict(os.environ)
