"""What a user meets at the edges of the commands and the notebook API, one test each:
``verify --report-dir`` never replaces report files it did not write, ``mutate --compare`` reads
its file before the run, worker counts must be positive, the notebook API refuses complex,
non-finite and n < 3 input, and ``chaplygin docs -h`` is help, not a report path."""

from __future__ import annotations

import json
import os

import numpy as np
import pytest
from chaplygin_nd.ledger.__main__ import _report_paths
from cli_helpers import exit_code, one_error_line

from chaplygin_nd import api, cli


# verify --report-dir: a file the program did not write is refused before any proof runs
@pytest.mark.parametrize("name, text", [
    ("VERIFICATION.md", "my own notes\n"),
    ("verification.json", '{"mine": 1}'),
    ("verification.json", "not json"),
    ("claim-graph.svg", "<svg/>"),           # no verification.json of ours beside it
])
def test_report_dir_refuses_files_it_did_not_write(tmp_path, capsys, name, text):
    (tmp_path / name).write_text(text)
    assert exit_code(cli.main, ["verify", "--report-dir", str(tmp_path)]) == 2
    line = one_error_line(capsys)
    assert name in line and "not written by `chaplygin verify`" in line, line
    assert (tmp_path / name).read_text() == text
    assert sorted(p.name for p in tmp_path.iterdir()) == [name]


def test_report_dir_refuses_a_symlink(tmp_path, capsys):
    other = tmp_path / "elsewhere.md"
    other.write_text("keep")
    folder = tmp_path / "reports"
    folder.mkdir()
    (folder / "VERIFICATION.md").symlink_to(other)
    assert _report_paths(str(folder), whole=True) == 2
    assert "VERIFICATION.md" in one_error_line(capsys)
    assert (folder / "VERIFICATION.md").is_symlink() and other.read_text() == "keep"


def test_report_dir_accepts_its_own_earlier_reports(tmp_path):
    (tmp_path / "VERIFICATION.md").write_text("# Verification ledger\n\nWritten by ...\n")
    (tmp_path / "verification.json").write_text(json.dumps({"generation": "x", "rows": []}))
    (tmp_path / "claim-graph.svg").write_text("<svg/>")
    md, js, svg = _report_paths(str(tmp_path), whole=True)
    assert (md.name, js.name, svg.name) == ("VERIFICATION.md", "verification.json",
                                            "claim-graph.svg")
    assert _report_paths(str(tmp_path / "new"), whole=True)[0].parent == tmp_path / "new"


# the notebook API: input outside the domain raises ValueError naming it, never a silent answer
def _state(n, seed=0):
    rng = np.random.default_rng(seed)
    A = rng.normal(size=(n, n))
    gamma = rng.normal(size=n)
    return A - A.T, gamma / np.linalg.norm(gamma)


@pytest.mark.parametrize("kernel", [api.angular_velocity, api.L_gamma, api.vector_field,
                                    api.energy])
def test_the_api_refuses_complex_input(kernel):
    M, gamma = _state(4)
    for args, name in [((M * (1 + 1j), gamma, 0.5, 1.0), "M"),
                       ((M, gamma * 1j, 0.5, 1.0), "gamma"),
                       ((M, gamma, 0.5 + 1j, 1.0), "a"),
                       ((M, gamma, 0.5, np.complex128(1.0)), "b")]:
        with pytest.raises(ValueError, match=f"^{name}" if name != "M" else "^(M|Omega) is complex"):
            kernel(*args)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_the_api_refuses_non_finite_M_and_gamma(bad):
    M, gamma = _state(4)
    gamma[1] = bad
    with pytest.raises(ValueError, match="^gamma has a non-finite entry"):
        api.angular_velocity(M, gamma, 0.5, 1.0)
    M, gamma = _state(4)
    M[0, 1], M[1, 0] = bad, -bad
    with pytest.raises(ValueError, match="^M has a non-finite entry"):
        api.energy(M, gamma, 0.5, 1.0)


@pytest.mark.parametrize("n", [0, 1, 2])
def test_the_api_refuses_n_below_3(n):
    M, gamma = np.zeros((n, n)), np.ones(n)
    for kernel in (api.angular_velocity, api.L_gamma, api.energy, api.zeta):
        with pytest.raises(ValueError, match=r"n >= 3"):
            kernel(M, gamma, 0.5, 1.0)


def test_the_api_still_takes_real_lists_and_integers():
    M = [[0, 1, 0], [-1, 0, 0], [0, 0, 0]]
    Omega = api.angular_velocity(M, [0, 0, 1], 0.5, 1)
    assert np.allclose(api.L_gamma(Omega, [0, 0, 1], 0.5, 1), M, rtol=0, atol=1e-14)


# mutate --compare: a file that cannot be read is refused before the (long) run, not after it
def test_mutate_reads_compare_before_the_run(tmp_path, monkeypatch, capsys):
    from chaplygin_nd.ledger.mutation import printed as mutate

    monkeypatch.setattr(mutate, "baseline", lambda *a, **k: pytest.fail("the run started"))
    out = tmp_path / "m.json"
    bad = tmp_path / "bad.json"
    bad.write_text('{"summary": "x"}')
    for compare, why in [(tmp_path / "missing.json", "cannot read it"),
                         (bad, "not a mutation.json")]:
        argv = ["mutate", "--function", "section3.H_nd", "--compare", str(compare), "--out", str(out)]
        assert exit_code(cli.main, argv) == 2
        line = one_error_line(capsys)
        assert f"--compare {compare}" in line and why in line, line
    assert not out.exists() and bad.read_text() == '{"summary": "x"}'
    good = tmp_path / "good.json"
    good.write_text(json.dumps({"mutants": [{"function": "f", "mutation": "m", "outcome": "killed"}]}))
    theirs = mutate.compared_outcomes(good)
    assert mutate._compare([{"function": "f", "mutation": "m", "outcome": "survived"}], theirs) \
        == ["f m: killed there, survived here"]


# counts must be positive: --jobs 0 meant "one per core" and --jobs -3 one worker, silently
@pytest.mark.parametrize("argv", [
    ["verify", "--jobs", "0"], ["prove", "eq:invL3D", "--jobs", "-3"], ["verify", "-j", "two"],
    ["mutate", "--jobs", "0"], ["mutate", "--per-function", "0"], ["mutate", "--sample", "-1"],
])
def test_counts_must_be_positive(argv, capsys):
    assert exit_code(cli.main, argv) == 2
    line = one_error_line(capsys)
    assert any(o in line for o in ("--jobs", "-j", "--per-function", "--sample")), line


# chaplygin docs: -h is help (it was taken for a report path), a bad report is one line
def test_docs_help_and_extra_arguments(capsys):
    assert exit_code(cli.main, ["docs", "-h"]) == 0
    assert capsys.readouterr().out.startswith("usage: chaplygin docs")
    assert exit_code(cli.main, ["docs", "a.json", "b.json"]) == 2
    assert "unrecognized arguments" in one_error_line(capsys)


@pytest.mark.parametrize("text", ["not json", "{}", '{"rows": 3}', "[]"])
def test_docs_pages_refuse_a_report_that_is_not_ours(tmp_path, monkeypatch, capsys, text):
    import importlib

    from chaplygin_nd.ledger.catalog import ROOT

    monkeypatch.syspath_prepend(str(ROOT / "docs"))
    build_pages = importlib.import_module("build_pages")
    report = tmp_path / "verification.json"
    report.write_text(text)
    out = tmp_path / "src"
    assert build_pages.main(["--report", str(report), "--out", str(out)]) == 2
    line = one_error_line(capsys)
    assert "is not a verification.json" in line, line
    assert not out.exists()


# an empty scene name is not the current folder
@pytest.mark.parametrize("name", ["", "  "])
def test_an_empty_scene_name_is_refused(name, tmp_path, monkeypatch, capsys):
    from chaplygin_nd.simulate.scene.spec import SceneError

    monkeypatch.chdir(tmp_path)
    assert exit_code(cli.main, ["simulate", name, "--out", str(tmp_path / "o")]) == 2
    line = one_error_line(capsys)
    assert "an empty scene name" in line and "steady4d" in line, line
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(SceneError, match="an empty scene name"):
        api.simulate(name)


# an open evidence row names the part of the rule fixed beforehand that failed, with its numbers
def _orbits(spec: dict):
    from chaplygin_nd.simulate.analysis.drawn_evidence import OrbitResult

    out = []
    for (cls, mcls), k in spec.items():
        out += [OrbitResult(0.5, 0.5, 1.0, 2, [0.1, 0.3], 1e-9, 2.0, 0.0, cls, mcls, drift=1e-10)] * k
    return out


def test_unmet_names_each_failed_part_of_the_rule():
    from chaplygin_nd.proofs import drawn_common as dc

    good = _orbits({("predicted", "regular"): 150, ("unresolved", "regular"): 50})
    assert dc.supported(good) and dc.unmet(good) == []
    edge = _orbits({("predicted", "regular"): 196, ("excess", "regular"): 4})  # exactly 2 %
    assert dc.supported(edge) and dc.unmet(edge) == []
    excess = _orbits({("predicted", "regular"): 195, ("excess", "regular"): 5})
    assert dc.unmet(excess) == ["frequencies: 5 of 200 orbits have a line no combination |c| <= 12 "
                                "explains (excess, contradict): 2.5 %, more than the rule's 2 %"]
    undecided = _orbits({("predicted", "regular"): 138, ("unresolved", "undecided"): 62})
    assert dc.unmet(undecided) == ["chaos: 138 of 200 orbits are regular by the MEGNO ladder: 69 %, "
                                   "fewer than the rule's 90 %"]
    few = _orbits({("predicted", "regular"): 30, ("unresolved", "regular"): 170})
    assert dc.unmet(few) == ["frequencies: 30 of 200 orbits show exactly the predicted count: 15 %, "
                             "fewer than the rule's 20 %"]
    # chaos and excess each within 2 %, together beyond: the combined part names both
    both = _orbits({("predicted", "regular"): 194, ("excess", "regular"): 3,
                    ("predicted", "chaotic"): 3})
    assert dc.unmet(both) == ["chaos and frequencies: 6 of 200 orbits are chaotic or excess "
                              "(contradict): 3 %, more than the rule's 2 %"]
    for results in (excess, undecided, few):
        assert not dc.supported(results)


# cn.decide: the same "did you mean" as chaplygin prove; a list is a TypeError that says so
def test_decide_names_the_nearest_id():
    with pytest.raises(KeyError, match="did you mean P:inversion"):
        api.decide("p:inversion")
    with pytest.raises(TypeError, match="one ledger id"):
        api.decide(["P:inversion"])


# mutate --out: never replaces a file it did not write, never writes into an installed package
def test_mutate_out_refuses_a_foreign_file_and_an_installed_package(tmp_path, monkeypatch, capsys):
    from chaplygin_nd.ledger.mutation import printed as mutate

    monkeypatch.setattr(mutate, "baseline", lambda *a, **k: pytest.fail("the run started"))
    mine = tmp_path / "notes.json"
    mine.write_text('{"my": "notes"}')
    assert exit_code(cli.main, ["mutate", "--function", "section3.H_nd", "--out", str(mine)]) == 2
    assert "is not a mutation.json this program wrote" in one_error_line(capsys)
    assert mine.read_text() == '{"my": "notes"}'
    monkeypatch.setattr(mutate, "is_checkout", lambda: False)
    assert exit_code(cli.main, ["mutate", "--function", "section3.H_nd"]) == 2
    assert "give --out FILE" in one_error_line(capsys)


# without heyoka (a wheel installed without the `fast` extra) the evidence rows are open with a
# reason, and they still read the printed predictions: `verify` then exits 0 (it exited 1 with
# "printed function section5.so3_rank is reached by no ledger row", four times)
def test_evidence_rows_without_heyoka_still_reach_their_printed_functions(monkeypatch):
    from chaplygin_nd.ledger.runner import run, select
    from chaplygin_nd.simulate.integrators import heyoka_taylor

    monkeypatch.setattr(heyoka_taylor, "available", lambda: False)
    ids = ["S5:EJ-tori", "S5:reconstruction", "Th:Re-tori:frequencies", "S6:open-reduced-n5"]
    results = run(select(ids), jobs=1)
    assert [r.status for r in results] == ["open"] * 4
    assert all("heyoka, which is not installed" in r.verdict.notes for r in results)
    # the open problem's exact part needs no heyoka: it is computed and said
    assert "so dim P/SO(4) = 14 - 6 = 8" in results[3].verdict.notes
    reached = {f for r in results for f in r.printed}
    assert {"section5.euler_jacobi_torus_dimension", "section5.reconstruction_statement",
            "section5.so3_rank", "section4.vertical_torus_dimension"} <= reached, reached


# bench --out: an existing file is one line (it was a FileExistsError traceback); a folder of
# someone else's files is refused (throughput.md was replaced, --cold emptied cache/ folders)
def test_bench_out_refuses_files_it_did_not_write(tmp_path, monkeypatch, capsys):
    import importlib

    bench_main = importlib.import_module("chaplygin_nd.bench.__main__")
    monkeypatch.setattr(bench_main, "_run", lambda names, args: 0)
    monkeypatch.setattr(bench_main, "_own_caches", lambda root, cold: None)
    a_file = tmp_path / "a_file"
    a_file.write_text("mine")
    theirs = tmp_path / "theirs"
    theirs.mkdir()
    (theirs / "throughput.md").write_text("mine")
    for out, why in [(a_file, "exists and is not a folder"), (theirs, "did not write")]:
        assert exit_code(cli.main, ["bench", "throughput", "--out", str(out)]) == 2
        assert why in one_error_line(capsys)
    assert a_file.read_text() == "mine" and sorted(os.listdir(theirs)) == ["throughput.md"]
    new = tmp_path / "new"
    assert exit_code(cli.main, ["bench", "throughput", "--out", str(new)]) == 0
    assert (new / bench_main.MARKER).is_file()
    (new / "throughput.md").write_text("an earlier run")   # its own folder is taken again
    assert exit_code(cli.main, ["bench", "throughput", "--out", str(new)]) == 0


def test_simulate_workers_must_be_positive(tmp_path, capsys):
    for bad in ("0", "-2"):
        argv = ["simulate", "fma4d", "--workers", bad, "--out", str(tmp_path / "o")]
        assert exit_code(cli.main, argv) == 2
        line = one_error_line(capsys)
        assert line.count("--workers") == 1 and "not a positive integer" in line, line
    assert not (tmp_path / "o").exists()


def test_mutate_help_is_plain_text(capsys):
    assert exit_code(cli.main, ["mutate", "-h"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("usage: chaplygin mutate") and "``" not in out and "ledger.mutate" not in out


def test_simulate_takes_a_scene_file_whose_name_has_an_equals_sign(tmp_path):
    from chaplygin_nd.ledger.catalog import ROOT

    path = tmp_path / "a=0.5.toml"
    path.write_text((ROOT / "scenes" / "steady4d.toml").read_text())
    run = api.simulate(str(path))     # it was read as TOML text: "not valid TOML"
    assert run.plan.model == "constant-Omega"


def test_a_folder_named_like_a_built_in_scene_does_not_hide_it(tmp_path, monkeypatch):
    """An earlier run's output folder `tori4d` in the working folder: the name still finds the
    built-in scene (a folder is not a scene file)."""
    from chaplygin_nd.simulate.scene.spec import find

    (tmp_path / "vertical5d").mkdir()
    monkeypatch.chdir(tmp_path)
    scene = find("vertical5d")
    assert scene.name == "vertical5d" and scene.n == 5
