"""Small defects a new user met , each as the user sees it: the usage line of
``chaplygin prove``, empty path options, ``--report-dir`` with ids, the plan printed once, cache
warnings in one line, ``mutate --function`` validated, the notebook API's domain checks, and a
clean ``dir(chaplygin_nd)``. Every error is one line on stderr and exit 2, with nothing written."""

from __future__ import annotations

import os
import subprocess
import sys
import warnings

import numpy as np
import pytest
from chaplygin_nd.ledger.__main__ import _report_paths
from chaplygin_nd.ledger.mutation import command as mutate_derivations
from chaplygin_nd.ledger.mutation import printed as mutate
from chaplygin_nd.runtime import jit_cache
from chaplygin_nd.simulate.analysis import result_cache
from chaplygin_nd.simulate.scene import cli as simulate_cli
from cli_helpers import exit_code, one_error_line

import chaplygin_nd
from chaplygin_nd import api, cli, console
from chaplygin_nd import cache as project_cache


# 1. the usage line names the command the user typed
@pytest.mark.parametrize("command", ["prove", "verify"])
def test_help_names_the_command(command, capsys):
    assert exit_code(cli.main, [command, "-h"]) == 0
    out = capsys.readouterr().out
    assert out.startswith(f"usage: chaplygin {command} "), out
    other = {"prove": "verify", "verify": "prove"}[command]
    assert f"usage: chaplygin {other}" not in out


def test_prove_help_does_not_offer_report_dir(capsys):
    assert exit_code(cli.main, ["prove", "-h"]) == 0
    assert "--report-dir" not in capsys.readouterr().out


# 2. an empty path is an error, never the default folder or the current one
@pytest.mark.parametrize("argv", [
    ["simulate", "steady4d", "--out", ""],
    ["simulate", "steady4d", "--out", "  "],
    ["verify", "--report-dir", ""],
    ["mutate", "--out", ""],
])
def test_an_empty_path_option_is_one_line_and_writes_nothing(argv, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert exit_code(cli.main, argv) == 2
    line = one_error_line(capsys)
    assert f"{argv[-2]}: an empty path" in line, line
    assert list(tmp_path.iterdir()) == []


def test_bench_refuses_an_empty_out(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert exit_code(cli.main, ["bench", "--quick", "--out", ""]) == 2
    assert "--out: an empty path" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


# 3. --report-dir with ids is refused before any proof runs; nothing is created or replaced
def test_report_dir_with_ids_is_refused(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    target = tmp_path / "reports"
    assert exit_code(cli.main, ["prove", "eq:invL3D", "--report-dir", str(target)]) == 2
    line = one_error_line(capsys)
    assert "--report-dir" in line and "chaplygin verify --report-dir DIR" in line, line
    assert not target.exists()
    # a folder holding a whole report keeps it byte for byte
    target.mkdir()
    (target / "VERIFICATION.md").write_text("the whole ledger")
    assert _report_paths(str(target), whole=False) == 2
    assert (target / "VERIFICATION.md").read_text() == "the whole ledger"
    assert _report_paths(None, whole=False) == ()   # ids without --report-dir: no report


# 4. the plan line is printed once: scene and plan before the run, the rest after
def test_simulate_prints_each_summary_line_once(tmp_path, capsys):
    out = tmp_path / "o"
    assert simulate_cli.main(["steady4d", "--out", str(out), "--no-plots"]) == 0
    printed = capsys.readouterr().out.splitlines()
    assert sum(line.startswith("model: ") for line in printed) == 1, printed
    assert sum(line.startswith("scene ") for line in printed) == 1, printed
    written = (out / "summary.txt").read_text(encoding="utf-8").splitlines()
    # the screen shows the whole summary, in its order, once; the file adds the scene's remarks
    # (steady4d: b = 0.5 < n + a, no ball of matter; simulate.scene.spec._body says why)
    body = [line for line in written if line.startswith("  body: ")]
    assert len(body) == 1 and "no ball of matter" in body[0], written
    assert printed == [line for line in written if line not in body]


# 5. cache warnings: one line "warning: ..." on stderr, still warnings
def test_cache_warnings_are_one_line_and_still_warnings(tmp_path):
    shared = tmp_path / "shared"
    shared.mkdir()
    shared.chmod(0o777)
    code = ("from chaplygin_nd.simulate.analysis import result_cache as rc\n"
            "assert rc.private_folder('evidence') is None\n")
    env = {**os.environ, project_cache.ENV: str(shared)}
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env,
                       timeout=120, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    lines = r.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("warning: the cache folder "), lines
    assert "writable by group or others" in lines[0] and project_cache.ENV in lines[0]
    strict = subprocess.run([sys.executable, "-W", "error", "-c", code], capture_output=True,
                            text=True, env=env, timeout=120, cwd=tmp_path)
    assert strict.returncode != 0 and "ResultCacheWarning" in strict.stderr  # -W error applies


def test_only_the_projects_warnings_change_format():
    for category in (result_cache.ResultCacheWarning, jit_cache.CacheWarning):
        assert issubclass(category, project_cache.CacheWarning)
        assert warnings.formatwarning("bad\nentry", category, "f.py", 3) == "warning: bad entry\n"
    assert issubclass(project_cache.CacheWarning, console.OneLineWarning)
    assert warnings.formatwarning("x", UserWarning, "f.py", 3).startswith("f.py:3: UserWarning: x")
    with pytest.warns(result_cache.ResultCacheWarning, match="recorded"):
        warnings.warn("recorded", result_cache.ResultCacheWarning, stacklevel=1)


# 6. mutate --function: an unknown name is one line, before the baseline, with how to list them
def test_mutate_refuses_an_unknown_function(tmp_path, capsys):
    out = tmp_path / "m.json"
    assert mutate.main(["--function", "section4.k", "--function", "nope", "--out", str(out)]) == 2
    line = one_error_line(capsys)
    assert "'section4.k' (did you mean section4.K?)" in line and "'nope'" in line, line
    assert "`chaplygin mutate --list`" in line
    assert not out.exists()
    assert mutate.main(["--list"]) == 0
    listed = capsys.readouterr().out.split()
    assert "section4.K" in listed and "nope" not in listed


def test_mutate_derivations_refuses_an_unknown_function(tmp_path, capsys):
    out = tmp_path / "m.json"
    argv = ["--target", "runtime", "--function", "runtime.axisym.zetaa", "--out", str(out)]
    assert mutate_derivations.main(argv) == 2
    line = one_error_line(capsys)
    assert "did you mean runtime.axisym.zeta?" in line and "--target runtime --list" in line, line
    assert not out.exists()


def test_mutate_derivations_never_replaces_a_foreign_file_and_reads_rerun_first(tmp_path, capsys):
    mine = tmp_path / "mine.json"
    mine.write_text('{"mine": 1}')
    argv = ["--target", "runtime", "--function", "runtime.axisym.vec", "--out", str(mine)]
    assert mutate_derivations.main(argv) == 2
    assert "exists and is not a mutation JSON" in one_error_line(capsys)
    assert mine.read_text() == '{"mine": 1}'
    out = tmp_path / "m.json"
    argv = ["--target", "runtime", "--function", "runtime.axisym.vec", "--out", str(out),
            "--rerun", str(tmp_path / "missing.json")]
    assert mutate_derivations.main(argv) == 2
    assert one_error_line(capsys).startswith("error: --rerun ")
    assert not out.exists()


def test_main_in_process_leaves_the_signal_handlers_as_it_found_them(capsys):
    """cli.main called in-process (a test, a mutant's test run) must not ignore SIGINT/SIGTERM
    after its command: a SIGTERM to a mutation worker running such a test was lost."""
    import signal

    before = {sig: signal.getsignal(sig) for sig in (signal.SIGINT, signal.SIGTERM)}
    assert exit_code(cli.main, ["prove", "-h"]) == 0
    assert cli.main(["--version"]) == 0
    assert {sig: signal.getsignal(sig) for sig in before} == before
    capsys.readouterr()


def test_mutate_derivations_is_a_chaplygin_command(capsys):
    """`chaplygin mutate-derivations` (what make mutate-derivations runs): the program's signal
    handling (one line on Ctrl-C or SIGTERM), not a bare `python -m` traceback."""
    assert "mutate-derivations" in cli.COMMANDS
    assert exit_code(cli.main, ["mutate-derivations", "-h"]) == 0
    assert "--target" in capsys.readouterr().out


def test_mutate_derivations_checks_the_out_folder_before_the_run(tmp_path, capsys):
    """An --out in a folder that does not exist is refused before any mutant runs (the trial of
    once, the whole run ran, then the atomic write failed with a traceback)."""
    out = tmp_path / "missing" / "m.json"
    argv = ["--target", "runtime", "--function", "runtime.axisym.vec", "--out", str(out)]
    assert mutate_derivations.main(argv) == 2
    assert "no such folder" in one_error_line(capsys)
    assert not out.parent.exists()


@pytest.mark.parametrize("module", ["printed", "command"])
def test_mutation_tools_refuse_an_out_folder_they_cannot_write_even_as_root(module, capsys):
    """/proc accepts no new file, whatever os.access says to root: both tools refuse it before
    any mutant runs."""
    import importlib

    tool = importlib.import_module(f"chaplygin_nd.ledger.mutation.{module}")
    argv = ["--out", "/proc/chaplygin-m.json"]
    if module == "command":
        argv += ["--target", "runtime", "--function", "runtime.axisym.vec"]
    assert tool.main(argv) == 2
    assert "cannot write in /proc" in one_error_line(capsys)

# 7. the notebook API checks the domain it documents
def _state(n=4, seed=5):
    rng = np.random.default_rng(seed)
    A = rng.normal(size=(n, n))
    gamma = rng.normal(size=n)
    return A - A.T, gamma / np.linalg.norm(gamma)


@pytest.mark.parametrize("kernel", [api.angular_velocity, api.vector_field, api.energy])
def test_the_api_refuses_a_non_skew_M(kernel):
    M, gamma = _state()
    with pytest.raises(ValueError, match=r"^M is not skew-symmetric .*so\(n\)"):
        kernel(M + np.eye(4) * 1e-3, gamma, 0.5, 0.5)
    with pytest.raises(ValueError, match=r"^M has shape \(4,\)"):
        kernel(gamma, gamma, 0.5, 0.5)


@pytest.mark.parametrize("kernel", [api.angular_velocity, api.L_gamma, api.vector_field,
                                    api.energy])
@pytest.mark.parametrize(("a", "b", "name"), [(-1.5, 0.5, "a"), (np.array([0.2, -2.0]), 0.5, "a"),
                                              (0.5, 0.0, "b"), (0.5, -1.0, "b"),
                                              (float("nan"), 0.5, "a"), (0.5, float("inf"), "b")])
def test_the_api_refuses_a_and_b_outside_the_papers_domain(kernel, a, b, name):
    M, gamma = _state()
    with pytest.raises(ValueError, match=rf"^{name} = \S+ is outside the domain: a finite {name} "):
        kernel(M, gamma, a, b)


def test_the_api_accepts_the_edges_of_the_domain():
    M, gamma = _state()
    for a in (-1.0, 1.0, 3.0):  # a = -1 (the paper's edge); a > 1, a prolate body
        Omega = api.angular_velocity(M, gamma, a, 0.5)
        assert np.allclose(api.L_gamma(Omega, gamma, a, 0.5), M, rtol=1e-12, atol=1e-12)
    with pytest.raises(ValueError, match=r"^Omega is not skew-symmetric"):
        api.L_gamma(np.ones((4, 4)), gamma, 0.5, 0.5)


def test_zeta_refuses_a_state_off_the_vertical_set():
    M, gamma = _state()
    with pytest.raises(ValueError, match=r"^M0 gamma0 != 0 .*vertical set V"):
        api.zeta(M, gamma, 0.5, 0.5)


# 8. the package namespace: public names only, lazy imports intact
def test_dir_of_the_package_is_clean():
    code = "import chaplygin_nd, sys; print(' '.join(dir(chaplygin_nd)))"
    names = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                           check=True, timeout=120).stdout.split()
    assert not {"importlib", "os", "sys", "types"} & set(names), names
    assert [n for n in names if n.startswith("_") and not n.endswith("__")] == [], names
    assert set(chaplygin_nd.__all__) <= set(names)
    assert chaplygin_nd.energy is api.energy and callable(chaplygin_nd.simulate)


@pytest.mark.parametrize("module, argv", [
    ("command", ["--target", "derivations", "--function", "search.sampled_field.mod"]),
    ("command", ["--sample", "5"]),
    ("printed", ["--function", "section4.K"]),
])
def test_a_partial_mutation_run_never_replaces_the_full_record(module, argv, capsys):
    """A new user's trial: `chaplygin mutate-derivations --function X` in the checkout replaced the
    checked-in record of the full run (856 mutants) by its 7. A partial run needs --out."""
    import importlib

    from chaplygin_nd.ledger.catalog import ROOT

    record = ROOT / ("mutation.json" if module == "printed" else "mutation-derivations.json")
    before = record.read_bytes() if record.exists() else None
    tool = importlib.import_module(f"chaplygin_nd.ledger.mutation.{module}")
    assert tool.main(argv) == 2
    assert "give --out FILE: a partial run would replace" in one_error_line(capsys)
    assert (record.read_bytes() if record.exists() else None) == before


def test_simulate_help_names_every_built_in_scene(capsys):
    from chaplygin_nd.simulate.scene.spec import builtin_scenes
    with pytest.raises(SystemExit) as stop:
        simulate_cli.main(["--help"])
    assert stop.value.code == 0
    shown = " ".join(capsys.readouterr().out.split())
    names = list(builtin_scenes())
    assert names and all(name in shown for name in names), (names, shown)
