"""Targets are kept or refused (simulate/scene/accuracy.py), and the cross-check can judge every built-in
scene on both installs: with heyoka and without it (CHAPLYGIN_ND_WITHOUT_HEYOKA=1, the base install).

The longest cross-checks (long4d, tori4d; and on the base install the scenes whose reference is the
mpmath Taylor method on an ensemble or in n = 5, 6) run in ``chaplygin bench calibration``, which
also measures the constants (bench/out/calibration.md)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from chaplygin_nd.simulate.integrators import heyoka_taylor
from chaplygin_nd.simulate.scene import accuracy, cli
from chaplygin_nd.simulate.scene.crosscheck import MARGIN, cross_check, reference_settings
from chaplygin_nd.simulate.scene.frequency_map import FrequencyMapScene
from chaplygin_nd.simulate.scene.outputs import collect
from chaplygin_nd.simulate.scene.planner import plan
from chaplygin_nd.simulate.scene.run import execute
from chaplygin_nd.simulate.scene.spec import builtin_scenes, find, loads

#: minutes: cross-checked by ``chaplygin bench calibration`` (bench/out/calibration.md)
LONGEST = {"long4d", "tori4d"}
#: on the base install their reference is the mpmath Taylor method on an ensemble or in n = 5, 6
#: (1-4 minutes each under load): also in the bench only
LONG_ON_BASE = {"horizontal6d", "ensemble3d", "vertical5d", "spherical6d"}
#: with heyoka the reference of these is the mpmath Taylor method on 64 members or in n = 5
#: (2-6 minutes under load): in the bench
LONG_ON_FAST = {"ensemble3d", "vertical5d"}
#: with heyoka these take 20-50 s each with both cores busy (pytest --durations): in
#: make test-slow (CI runs it), so that make test stays within its time; horizontal6d's
#: reference is the mpmath Taylor method in n = 6 (an mpmath inverse of the 15 x 15 L_gamma at
#: every step, 1200 steps): ~38 CPU-s, a quarter of make test's wall time on 2 cores by itself;
#: spherical6d (n = 6, ~7 CPU-s, the costliest of the rest) too
SLOW_ON_FAST = {"generic4d", "prolate_ball3d", "explicit4d", "horizontal6d", "spherical6d"}
#: a frequency map is a grid of orbits, not one trajectory: tests/test_fma.py checks it
MAPS = {name for name in builtin_scenes() if isinstance(find(name), FrequencyMapScene)}
CASES = [pytest.param(name, install, marks=pytest.mark.slow
                      if install == "base" or name in SLOW_ON_FAST else ())
         for name in sorted(set(builtin_scenes()) - LONGEST - MAPS)
         for install in ["base"] + (["fast"] if heyoka_taylor.available() else [])
         if name not in (LONG_ON_BASE if install == "base" else LONG_ON_FAST)]


@pytest.mark.parametrize("name,install", CASES)
def test_every_builtin_scene_passes_its_own_cross_check(name, install, monkeypatch):
    monkeypatch.setenv(accuracy.WITHOUT_HEYOKA, "1" if install == "base" else "0")
    scene = find(name)
    p = plan(scene)
    if p.accuracy is not None:
        assert p.accuracy.honoured, p.describe()
        if install == "base":
            assert p.method != "heyoka", p.describe()
        elif scene.method == "auto" and p.model in ("full", "reduced-7D"):
            # among the methods that honour the target, the one of least predicted cost
            assert p.method in ("heyoka", "dop853") and "cost: predicted" in p.describe(), \
                p.describe()
    traj = execute(scene, p, progress=False)
    arrays = collect(scene, traj)
    check = cross_check(scene, p, arrays, progress=False)
    assert check.passed, check.describe()
    ref = reference_settings(scene, p)
    promised = p.accuracy.promised if p.accuracy else scene.target
    assert ref.promised <= promised / MARGIN * (1 + 1e-9)
    if p.accuracy is not None:  # a different integrator or precision
        assert _setting(ref) != _setting(p.accuracy)


def _setting(s) -> dict:
    """The integrator, its precision and its typed setting (tol, h or dps)."""
    import dataclasses

    return {f.name: getattr(s, f.name) for f in dataclasses.fields(s)
            if f.name not in ("promised", "honoured")}


def test_dop853_cannot_honour_a_target_below_its_floor():
    s = accuracy.choose("dop853", 1e-13, 10.0)
    assert not s.honoured and s.tol == accuracy.FLOORS["dop853"] and s.promised > 1e-13
    assert "CANNOT honour" in s.describe()
    assert accuracy.choose("dop853", 1e-8, 10.0).honoured


def test_auto_falls_back_to_the_taylor_method_without_heyoka(monkeypatch):
    monkeypatch.setenv(accuracy.WITHOUT_HEYOKA, "1")
    s = accuracy.automatic(1e-12, 100.0, 30, reduced=False)
    assert s.method == "reference" and s.honoured and s.dps >= 18
    assert accuracy.automatic(1e-8, 100.0, 30, reduced=False).method == "dop853"
    with pytest.raises(accuracy.Unattainable, match="cannot be honoured"):
        accuracy.automatic(1e-13, 100.0, 30, reduced=True)


def _scene(extra):
    return ('n = 4\na = 0.5\nb = 1.0\n[initial]\nfamily = "generic"\nseed = 7\n[times]\n'
            f't_end = 1.0\nsamples = 5\n[outputs]\nwant = ["x"]\n[accuracy]\n{extra}\n')


def test_a_named_method_runs_and_says_it_cannot(tmp_path, capsys):
    path = tmp_path / "named.toml"
    path.write_text(_scene('target = 1e-13\nmethod = "dop853"'))
    assert cli.main([str(path), "--out", str(tmp_path / "o"), "--no-plots"]) == 0
    assert "CANNOT honour the target" in capsys.readouterr().out


def test_an_unattainable_automatic_target_is_refused_with_one_line(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv(accuracy.WITHOUT_HEYOKA, "1")
    text = _scene("target = 1e-13").replace('want = ["x"]', 'want = ["reduced"]')
    path = tmp_path / "tight.toml"
    path.write_text(text)
    assert cli.main([str(path), "--out", str(tmp_path / "o"), "--no-plots"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "cannot be honoured" in err[0]
    assert not (tmp_path / "o").exists()


def test_the_lie_step_follows_the_target():
    s = accuracy.choose("lie", 1e-8, 100.0, step=0.05)
    assert s.honoured and s.h < 0.05
    assert accuracy.SAFETY * accuracy.estimated_error(s, 100.0) <= 1e-8 * (1 + 1e-9)


def test_a_fail_says_which_side_is_off():
    scene = loads(_scene("target = 1e-8").replace('want = ["x"]', 'want = ["M", "gamma"]'))
    p = plan(dataclasses.replace(scene, method="dop853"))
    arrays = collect(scene, execute(scene, p, progress=False))
    arrays["M"] = arrays["M"] + 1e-5 * np.max(np.abs(arrays["M"]))
    check = cross_check(scene, p, arrays, progress=False)
    assert not check.passed
    assert "the run is off: its error in M" in check.describe()
