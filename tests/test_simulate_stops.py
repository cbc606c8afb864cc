"""Runs that cannot be right stop at once with one line and exit 2; costly runs say so and are
refused unless --force; bad inputs get a message, not a traceback."""

from __future__ import annotations

import hashlib
import subprocess
import sys
import time
from pathlib import Path

import pytest
from chaplygin_nd.simulate.scene import cli

ROOT = Path(__file__).resolve().parent.parent


def _scene(b="1.0", initial='family = "generic"\nseed = 7', times="t_end = 10.0",
           want='["M", "gamma"]'):
    return (f"n = 4\na = 0.5\nb = {b}\n[initial]\n{initial}\n[times]\n{times}\n"
            f"[outputs]\nwant = {want}\n")


def _run(capsys, tmp_path, text: bytes | str, *extra):
    """Run the command line on a scene file (in this process: warnings are errors under
    pytest, so a warning would surface as a failure); (code, stdout, stderr, seconds)."""
    path = tmp_path / "scene.toml"
    path.write_bytes(text if isinstance(text, bytes) else text.encode())
    out = tmp_path / "out"
    start = time.perf_counter()
    code = cli.main([str(path), "--out", str(out), "--no-plots", *extra])
    captured = capsys.readouterr()
    return code, captured.out, captured.err, time.perf_counter() - start


def _one_line_error(code, err, *words):
    assert code == 2, err
    assert "Traceback" not in err and "np.float64" not in err and "Warning" not in err, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), err
    for w in words:
        assert w in lines[0], err


def test_b_1e300_stops_within_seconds(capsys, tmp_path):
    code, _, err, seconds = _run(capsys, tmp_path, _scene(b="1e300"))
    _one_line_error(code, err, "Omega", "not finite", "t = 0")
    assert seconds < 10
    assert not (tmp_path / "out").exists()


def test_scale_1e300_stops_within_seconds(capsys, tmp_path):
    code, _, err, seconds = _run(capsys, tmp_path, _scene(initial='family = "generic"\nseed = 7\n'
                                                  "scale = 1e300"))
    _one_line_error(code, err, "not finite", "t = 0", "M")
    assert seconds < 10


def test_non_finite_sample_names_field_and_time():
    import numpy as np
    from chaplygin_nd.simulate.integrators.stops import NonFinite, check_finite

    values = np.ones((5, 2))
    values[3, 1] = np.inf
    with pytest.raises(NonFinite, match=r"^gamma is not finite at t = 1\.5 "):
        check_finite("gamma", values, np.linspace(0.0, 2.0, 5))


def test_long_horizon_is_refused_after_a_short_pilot(capsys, tmp_path):
    code, _, err, seconds = _run(capsys, tmp_path, _scene(times="t_end = 1e12"))
    _one_line_error(code, err, "estimated", " s ", "limit", "--force")
    assert seconds < 15
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("times,initial,field", [
    ("t_end = 1.0\nsamples = 100000000", 'family = "generic"\nseed = 7', "times.samples"),
    ("t_end = 1.0", 'family = "generic"\nseed = 7\ncount = 1000000', "initial.count")])
def test_huge_arrays_are_refused_before_they_are_made(capsys, tmp_path, times, initial, field):
    code, _, err, seconds = _run(capsys, tmp_path, _scene(times=times, initial=initial))
    _one_line_error(code, err, field, "memory", "GB", "--force")
    assert seconds < 10


def test_force_lifts_the_memory_limit(monkeypatch):
    from chaplygin_nd.simulate.scene import budget
    from chaplygin_nd.simulate.scene.spec import SceneError, loads

    text = _scene(times="t_end = 1.0\nsamples = 1000")
    need = budget.memory_bytes(4, 1, 1000, ["M", "gamma"])
    monkeypatch.setattr(budget, "memory_limit", lambda: need // 2)
    with pytest.raises(SceneError, match="memory"):
        loads(text)
    assert len(loads(text, force=True).t) == 1000


@pytest.mark.parametrize("initial,words", [
    ('family = "generic"\nseed = -3', ("initial.seed", "negative")),
    ('gamma = [0.0, 0.0, 0.0, 0.0]\nM = [[0.0, 1.0, 0.0, 0.0], [-1.0, 0.0, 0.0, 0.0], '
     '[0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0]]', ("initial.gamma", "unit vector")),
    ('gamma = [0.0, 0.0, 0.0, 2.0]\nM = [[0.0, 1.0, 0.0, 0.0], [-1.0, 0.0, 0.0, 0.0], '
     '[0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0]]', ("|gamma| = 2 ", "gamma / 2"))])
def test_bad_initial_conditions_get_a_message(capsys, tmp_path, initial, words):
    code, _, err, _ = _run(capsys, tmp_path, _scene(initial=initial))
    _one_line_error(code, err, *words)
    assert "/ 0" not in err


@pytest.mark.parametrize("content,words", [
    (b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\xff\xfe", ("not UTF-8",)),
    ("title = 'caf\u00e9'\n".encode("latin-1"), ("not UTF-8",)),
    (b"n = 4\x00\x00", ("TOML",))])
def test_binary_and_non_utf8_scene_files(capsys, tmp_path, content, words):
    code, _, err, _ = _run(capsys, tmp_path, content)
    _one_line_error(code, err, *words)


def test_out_dot_and_out_under_a_file(tmp_path, capsys, monkeypatch):
    scene = tmp_path / "s.toml"
    scene.write_text(_scene())
    monkeypatch.chdir(tmp_path)
    assert cli.main([str(scene), "--out", "."]) == 2
    assert cli.main([str(scene), "--out", str(scene / "x")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 2 and all(e.startswith("error: --out") for e in err)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.toml"]


def test_unknown_scene_names_the_built_in_ones(capsys):
    assert cli.main(["no-such-scene"]) == 2
    err = capsys.readouterr().err
    assert "generic4d" in err and "Traceback" not in err


def test_codegen_help_prints_usage_and_writes_nothing():
    def digest():
        return {p.name: hashlib.sha256(p.read_bytes()).hexdigest()
                for p in sorted((ROOT / "generated").glob("*.py"))}

    before = digest()
    mtimes = {p.name: p.stat().st_mtime_ns for p in (ROOT / "generated").glob("*.py")}
    r = subprocess.run([sys.executable, "-m", "chaplygin_nd.symbolic.codegen.kernels", "-h"], capture_output=True,
                       text=True, cwd=ROOT, timeout=60)
    assert r.returncode == 0 and r.stdout.startswith("usage:") and "wrote" not in r.stdout
    assert digest() == before
    assert {p.name: p.stat().st_mtime_ns for p in (ROOT / "generated").glob("*.py")} == mtimes


def test_progress_counts_from_t0_and_stops_on_a_nan_time():
    import io

    from chaplygin_nd.simulate.integrators.stops import NonFinite
    from chaplygin_nd.simulate.scene.run import Progress

    stream = io.StringIO()
    bar = Progress(5.0, "late", after=0.0, stream=stream, t0=3.0)
    bar.last -= 2.0
    bar(4.0)
    assert "50.0%" in stream.getvalue()
    with pytest.raises(NonFinite, match="not finite"):
        bar(float("nan"))
