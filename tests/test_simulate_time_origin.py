"""Every model starts at the scene's t[0] and agrees there; the planner's membership tests cannot
be loosened by a scene; --cross-check judges."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from chaplygin_nd.simulate.dynamics.field import FullField
from chaplygin_nd.simulate.dynamics.so import reduced_invariants
from chaplygin_nd.simulate.scene import cli
from chaplygin_nd.simulate.scene.crosscheck import cross_check
from chaplygin_nd.simulate.scene.outputs import collect
from chaplygin_nd.simulate.scene.planner import APPLIES, plan
from chaplygin_nd.simulate.scene.run import execute
from chaplygin_nd.simulate.scene.spec import find, loads
from scipy.integrate import solve_ivp

T = np.linspace(3.0, 5.0, 9)  # t[0] = 3
#: built-in scene -> the model the planner must choose for it (one scene per model)
MODEL_OF = {"steady4d": "constant-Omega", "spherical6d": "constant-Omega",
            "vertical5d": "vertical", "horizontal4d": "horizontal-4D",
            "reduced4d": "reduced-7D", "generic4d": "full", "explicit4d": "full"}


def _late(name):
    return dataclasses.replace(find(name), t=T)


def _independent(scene):
    """(M, gamma) at T by SciPy's DOP853 on eq:motion-general from (M0, gamma0) at t = 3, written
    here without simulate.scene.run (tight tolerance)."""
    f = FullField(scene.n, scene.a, scene.b)
    y0 = f.pack(scene.M0, scene.gamma0)
    shape = y0.shape
    sol = solve_ivp(lambda s, y: f(s, y.reshape(shape)).ravel(), (T[0], T[-1]), y0.ravel(),
                    method="DOP853", t_eval=T, rtol=1e-13, atol=1e-13)
    assert sol.success
    return f.unpack(sol.y.T.reshape((len(T),) + shape))[:2]


@pytest.mark.parametrize("name", sorted(MODEL_OF))
def test_every_model_starts_at_t0_and_follows_the_flow(name):
    scene = _late(name)
    p = plan(scene)
    assert p.model == MODEL_OF[name], p.describe()
    arrays = collect(scene, execute(scene, p, progress=False))
    M, gamma = _independent(scene)
    expected = {"M": M, "gamma": gamma, "x": gamma[..., -1],
                "reduced": reduced_invariants(M, gamma) if scene.n == 4 else None}
    compared = 0
    for key, want in expected.items():
        if key in arrays:
            got = arrays[key]
            assert np.max(np.abs(got[0] - want[0])) < 1e-14, (key, "differs at t[0]")
            assert np.max(np.abs(got - want)) < 1e-9, (p.model, key)
            compared += 1
    assert compared >= 2


@pytest.mark.parametrize("name", sorted(MODEL_OF))
def test_cross_check_passes_with_t0_3(name):
    scene = _late(name)
    p = plan(scene)
    arrays = collect(scene, execute(scene, p, progress=False))
    check = cross_check(scene, p, arrays, progress=False)
    assert check.passed, check.describe()
    assert check.describe().endswith("cross-check: pass")
    # the reference is another integrator or precision (simulate/scene/crosscheck.py)
    assert p.accuracy is None or p.accuracy.describe() not in check.against


def test_full_model_is_compared_with_another_integrator_not_itself():
    scene = _late("generic4d")
    p = plan(scene)
    arrays = collect(scene, execute(scene, p, progress=False))
    check = cross_check(scene, p, arrays, progress=False)
    assert p.model == "full"
    assert p.accuracy.describe() not in check.against  # not the run's own settings
    assert max(d for _, d, _, _ in check.rows) > 0  # a run compared with itself gives exactly 0
    for key, _, bound, ref in check.rows:  # bound = accuracy.target x the size of the output
        assert bound == pytest.approx(scene.target * np.max(np.abs(arrays[key])), rel=1e-6)
        assert ref <= bound / 100 * (1 + 1e-9)  # the reference is 100x more accurate


SCENE = """n = 4
a = 0.5
b = 1.0
[initial]
family = "generic"
seed = 7
{extra}
[times]
t = [3.0, 3.5, 4.0]
[outputs]
want = ["M", "gamma"]
[accuracy]
{accuracy}
"""


def test_cli_cross_check_fail_exits_1(tmp_path, capsys, monkeypatch):
    """A Lie-group run at a step too coarse for target = 1e-12 (the calibration is falsified here
    so that the step stays 0.5) is judged off: FAIL naming the run, exit 1."""
    from chaplygin_nd.simulate.scene import accuracy

    monkeypatch.setitem(accuracy.MEASURED, "lie", 1e-30)
    path = tmp_path / "coarse.toml"
    path.write_text(SCENE.format(extra="", accuracy='method = "lie"\nstep = 0.5\ntarget = 1e-12'))
    assert cli.main([str(path), "--out", str(tmp_path / "o"), "--cross-check", "--no-plots"]) == 1
    out = capsys.readouterr().out
    assert "cross-check: FAIL — the run is off" in out and " > " in out


def test_cli_cross_check_pass_exits_0(tmp_path, capsys):
    path = tmp_path / "fine.toml"
    path.write_text(SCENE.format(extra="", accuracy="target = 1e-10"))
    assert cli.main([str(path), "--out", str(tmp_path / "o"), "--cross-check", "--no-plots"]) == 0
    assert "cross-check: pass" in capsys.readouterr().out


def test_a_loose_scene_tolerance_does_not_make_a_generic_point_steady():
    scene = loads(SCENE.format(extra="tolerance = 0.9", accuracy=""))
    p = plan(scene)
    assert p.model == "full"
    text = p.describe()
    assert f"> {APPLIES:.0e}" in text and "eta0 x xi0" in text  # says what was tested


def test_a_scene_may_tighten_the_membership_test():
    base = find("vertical5d")
    assert plan(base).model == "vertical"
    assert f"<= {APPLIES:.0e}" in plan(base).describe()
    strict = dataclasses.replace(base, tolerance=1e-30)
    p = plan(strict)
    assert p.model == "full" and "> 1e-30" in p.describe()
