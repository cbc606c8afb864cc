"""Bounded before it starts, and smaller cases: each is one line
and exit 2 before any computation (or the fix), never a traceback or a hang."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest
from chaplygin_nd.simulate.scene import cli

SMALL = """n = 3
a = 0.5
b = 1.0
[initial]
family = "generic"
seed = 1
{initial}
[times]
{times}
[outputs]
want = [{want}]
"""


def _scene(tmp_path, initial="", times="t_end = 1.0\nsamples = 5", want='"x"'):
    path = tmp_path / "s.toml"
    path.write_text(SMALL.format(initial=initial, times=times, want=want))
    return path


def _one_line(capsys, argv, *words):
    assert cli.main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: "), err
    for w in words:
        assert w in err[0], err[0]


def test_scene_files_must_be_small_regular_files(tmp_path, capsys):
    _one_line(capsys, ["/dev/zero"], "not a regular file")
    fifo = tmp_path / "fifo.toml"
    os.mkfifo(fifo)
    _one_line(capsys, [str(fifo)], "not a regular file")  # returns: the open does not block
    big = tmp_path / "big.toml"
    big.write_bytes(b"#" * ((1 << 20) + 1))
    _one_line(capsys, [str(big)], "larger than 1 MiB")


def test_members_asked_for_count_in_the_size_check(tmp_path, capsys):
    path = _scene(tmp_path, initial="members = [1000000000]")
    _one_line(capsys, [str(path), "--out", str(tmp_path / "o")], "initial.members")
    assert not (tmp_path / "o").exists()


def test_a_time_grid_float64_cannot_hold(tmp_path, capsys):
    path = _scene(tmp_path, times="t_end = 5e-324")
    _one_line(capsys, [str(path), "--out", str(tmp_path / "o")], "not distinct")


def test_spectral_outputs_of_a_short_run_are_refused_before_it(tmp_path, capsys):
    text = SMALL.replace("n = 3", "n = 4").format(initial="", times="t_end = 3.0\nsamples = 20",
                                                  want='"frequencies"')
    path = tmp_path / "short.toml"
    path.write_text(text)
    _one_line(capsys, [str(path), "--out", str(tmp_path / "o")], "at least 64")


def test_deep_nesting_is_one_line(tmp_path, capsys):
    path = tmp_path / "deep.toml"
    path.write_text("n = 3\na = 0.5\nb = 1.0\n[initial]\ngamma = " + "[" * 5000 + "]" * 5000 + "\n")
    _one_line(capsys, [str(path)], "nested too deeply")


def test_an_out_name_too_long_for_the_file_system_is_refused_first(tmp_path, capsys):
    path = _scene(tmp_path)
    _one_line(capsys, [str(path), "--out", str(tmp_path / ("x" * 250))], "longer than")


@pytest.mark.parametrize("inertia,ok", [("[0.15, 0.1 + 0.2]", True), ("[0.15, 0.30000000000000004]", True),
                                        ("[0.15, 0.3001]", False)])
def test_a_flat_disc_and_a_full_shell_get_the_same_tolerance(tmp_path, capsys, inertia, ok):
    inertia = inertia.replace("0.1 + 0.2", repr(0.1 + 0.2))
    path = tmp_path / "disc.toml"
    path.write_text(f"n = 3\n[ball]\nmass = 1.0\nradius = 1.0\ninertia = {inertia}\n[initial]\n"
                    'family = "generic"\nseed = 1\n[times]\nt_end = 1.0\nsamples = 5\n'
                    '[outputs]\nwant = ["x"]\n')
    code = cli.main([str(path), "--out", str(tmp_path / "o"), "--no-plots"])
    assert code == (0 if ok else 2), capsys.readouterr().err


def _run(args, tmp_path, **env):
    return subprocess.run([sys.executable, "-m", "chaplygin_nd", "simulate", *args],
                          capture_output=True, text=True, timeout=300, cwd=tmp_path,
                          env={**os.environ, **env})


def test_ascii_stdout_bogus_backend_and_a_closed_pipe(tmp_path):
    r = _run(["steady4d", "--out", "a"], tmp_path, PYTHONIOENCODING="ascii", MPLBACKEND="bogus")
    assert r.returncode == 0 and "Traceback" not in r.stderr, r.stderr
    assert " - " in r.stdout and "warning: MPLBACKEND='bogus'" in r.stderr
    assert (tmp_path / "a" / "M.png").is_file()
    # | head -1: stdout closed after the first line; the run still writes its files, quietly
    p = subprocess.Popen([sys.executable, "-m", "chaplygin_nd", "simulate", "steady4d", "--out",
                          "b", "--no-plots"], cwd=tmp_path, stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    p.stdout.readline()
    p.stdout.close()
    err = p.stderr.read()
    p.stderr.close()
    assert p.wait(timeout=300) == 0 and "Broken pipe" not in err and "Traceback" not in err, err
    assert (tmp_path / "b" / "summary.txt").is_file()
