"""Bad input gets one line, never a traceback: each case as a user meets it — an
explicit family without its point, a damaged evidence cache entry, gamma off the unit sphere in
the notebook API, more workers than cores, --workers/--scheduler on a scene that is not a
frequency map, escape sequences in a title, a UTF-8 byte-order mark."""

from __future__ import annotations

import numpy as np
import pytest
from chaplygin_nd.simulate.analysis import result_cache
from chaplygin_nd.simulate.scene import cli as simulate_cli
from chaplygin_nd.simulate.scene import frequency_map
from chaplygin_nd.simulate.scene.spec import SceneError, loads
from cli_helpers import exit_code, one_error_line

import chaplygin_nd as cn

SCENE = """title = "t"
n = 4
a = 0.5
b = 1.0
[initial]
{initial}
[times]
t_end = 1.0
samples = 11
[outputs]
want = ["M", "gamma"]
"""


def _simulate(tmp_path, text: str, *options: str, name: str = "s.toml") -> list[str]:
    scene = tmp_path / name
    scene.write_bytes(text.encode("utf-8") if isinstance(text, str) else text)
    return [str(scene), "--out", str(tmp_path / "out"), "--no-plots", *options]


def test_explicit_family_without_its_point_is_one_line(tmp_path, capsys):
    argv = _simulate(tmp_path, SCENE.format(initial='family = "explicit"\nseed = 1'))
    assert exit_code(simulate_cli.main, argv) == 2
    line = one_error_line(capsys)
    assert 'family = "explicit" needs the initial condition itself' in line and "give M" in line
    assert not (tmp_path / "out").exists()


def test_a_byte_order_mark_is_named(tmp_path, capsys):
    text = b"\xef\xbb\xbf" + SCENE.format(initial='family = "generic"\nseed = 1').encode()
    assert exit_code(simulate_cli.main, _simulate(tmp_path, text)) == 2
    line = one_error_line(capsys)
    assert "byte-order mark" in line and "BOM" in line and "without a BOM" in line


@pytest.mark.parametrize("title", ["a\x1b[31mred\x1b[0m", "two\nlines", "bell\x07", "c1\x9b2J"])
def test_a_title_with_control_characters_is_refused(title):
    text = SCENE.format(initial='family = "generic"\nseed = 1').replace(
        'title = "t"', "title = " + repr(title).replace("'", '"').replace("\\x", "\\u00"))
    with pytest.raises(SceneError) as exc:
        loads(text)
    assert "control character" in str(exc.value) and "\n" not in str(exc.value)
    assert "\x1b" not in str(exc.value)  # the error itself does not echo the escape
    assert loads(text.replace(text.split("\n")[0], 'title = "plain — ünïcode ok"')).title \
        == "plain — ünïcode ok"


@pytest.mark.parametrize("option", [["--scheduler", "local"], ["--workers", "2"]])
def test_pool_options_on_a_scene_without_a_frequency_map_are_refused(tmp_path, capsys, option):
    argv = _simulate(tmp_path, SCENE.format(initial='family = "generic"\nseed = 1'), *option)
    assert exit_code(simulate_cli.main, argv) == 2
    line = one_error_line(capsys)
    assert option[0] in line and "[fma]" in line
    assert not (tmp_path / "out").exists()


def test_more_workers_than_cores_are_bounded_and_said(tmp_path, capsys, monkeypatch):
    seen = {}

    def run(scene, workers=None, scheduler=None):  # the map itself is not run here
        seen["workers"] = workers
        return {}, "summary"

    monkeypatch.setattr(frequency_map, "run", run)
    monkeypatch.setattr(simulate_cli.os, "cpu_count", lambda: 2)
    argv = ["fma4d", "--out", str(tmp_path / "out"), "--workers", "100000"]
    assert exit_code(simulate_cli.main, argv) == 0
    out = capsys.readouterr().out
    assert seen["workers"] == 2
    assert "--workers 100000 is more than the 2 cores of this machine: running 2" in out


def test_gamma_off_the_unit_sphere_is_refused():
    M = np.zeros((4, 4))
    M[0, 1], M[1, 0] = 0.3, -0.3
    for gamma in ([0.0, 0.0, 0.0, 2.0], [0.0, 0.0, 0.0, 1.0 + 1e-6], [0.0, 0.0, 0.0, 0.5]):
        for call in (cn.angular_velocity, cn.energy, cn.vector_field):
            with pytest.raises(ValueError, match=r"gamma is off the unit sphere .* \|gamma\| = 1"):
                call(M, np.array(gamma), 0.5, 1.0)
    # within the stated tolerance (api.TOLERANCE) a float gamma is accepted
    Omega = cn.angular_velocity(M, np.array([0.0, 0.0, 0.0, 1.0 + 1e-13]), 0.5, 1.0)
    assert np.allclose(cn.L_gamma(Omega, np.array([0.0, 0.0, 0.0, 1.0]), 0.5, 1.0), M)
    cn.L_gamma(Omega, np.array([0.0, 0.0, 0.0, 2.0]), 0.5, 1.0)  # L_gamma: any gamma in R^n


@pytest.mark.parametrize("damage", ["", "[{\"a\": 1", "not json", "[{\"unknown\": 1}]", "\xff"])
def test_a_damaged_cache_entry_is_a_miss_with_one_warning(tmp_path, damage):
    from chaplygin_nd.simulate.analysis.drawn_evidence import OrbitResult

    entry = tmp_path / "drawn-x.json"
    entry.write_text(damage, encoding="latin-1")
    with pytest.warns(result_cache.ResultCacheWarning, match="is damaged"):
        found = result_cache.read_entry(entry, lambda text: [OrbitResult(**d)
                                                             for d in __import__("json").loads(text)])
    assert found is None


def test_a_reader_that_stops_reading_is_not_a_traceback():
    """`chaplygin --help | head -1`: the pipe's reader is gone before the program writes (its end
    is closed here before the interpreter has even started), so every write fails with EPIPE. The
    program says nothing and exits 141, as a process killed by SIGPIPE does in the shell."""
    import subprocess
    import sys

    with subprocess.Popen([sys.executable, "-m", "chaplygin_nd", "--help"],
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE) as proc:
        proc.stdout.close()             # no reader from here on
        err = proc.stderr.read().decode()
        status = proc.wait(timeout=120)
    assert status == 141 and err == ""
