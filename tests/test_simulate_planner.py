"""The planner's choice for every example scene, and its rules on hand-made scenes."""

from __future__ import annotations

from pathlib import Path

import pytest
from chaplygin_nd.simulate.kernels import active
from chaplygin_nd.simulate.scene.planner import MODELS, plan
from chaplygin_nd.simulate.scene.spec import load, loads

ROOT = Path(__file__).resolve().parent.parent


def _expected(stem: str) -> str:
    k = active()
    reduced = "reduced-7D" if k.has("reduced_field") else "full"
    return {
        "generic4d": "full",            # M, Omega, gamma are not SO(3)-invariant
        "vertical5d": "vertical" if k.has("zeta") else "full",
        "steady4d": "constant-Omega",   # P:steady-rot
        "spherical6d": "constant-Omega",  # a = 0
        "horizontal4d": "horizontal-4D" if k.has("horizontal") and k.has("horizontal_A")
        and k.has("reduced_integrals") else reduced,
        "horizontal6d": "horizontal" if k.has("horizontal") and k.has("horizontal_blocks")
        else "full",                    # S5:H-linear-nD: any n
        "reduced4d": reduced,
        "ensemble3d": "full",
        "long4d": "full",               # method = "lie" asks for the full system
        "explicit4d": "full",
        "reference4d": "full",
        "prolate_ball3d": "full",       # a physical ball (S4:physical-ball), a = 4
        "tori4d": "full",               # frequencies on P need the full system
    }[stem]


SCENES = sorted(p.stem for p in (ROOT / "scenes").glob("*.toml")  # not frequency maps (test_fma)
                if "\n[fma]" not in p.read_text(encoding="utf-8"))


def test_every_scene_has_an_expectation():
    assert SCENES and all(_expected(s) in MODELS for s in SCENES)


@pytest.mark.parametrize("stem", SCENES)
def test_planner_choice_for_example_scene(stem):
    scene = load(ROOT / "scenes" / f"{stem}.toml")
    p = plan(scene)
    assert p.model == _expected(stem), p.describe()
    assert p.reconstruct == bool({"orientation", "contact_path"} & set(scene.outputs))
    assert p.reason
    if p.model == "full" and stem in ("horizontal4d", "reduced4d", "vertical5d"):
        assert "not in generated/" in p.describe()  # a skipped model says why


def test_method_of_example_scenes():
    assert plan(load(ROOT / "scenes/long4d.toml")).method == "lie"
    assert plan(load(ROOT / "scenes/reference4d.toml")).method == "reference"
    from chaplygin_nd.simulate.integrators import heyoka_taylor

    generic = plan(load(ROOT / "scenes/generic4d.toml"))
    if heyoka_taylor.available():  # auto: the honouring candidate of least predicted cost
        assert generic.method == "heyoka"  # DOP853 cannot honour 1e-12 (simulate/scene/accuracy.py)
        assert "cost: predicted" in generic.describe()  # every prediction in the plan line
        tol = generic.accuracy.tol  # calibrated for target 1e-12
        assert f"heyoka Taylor, tol {tol:.3g}; calibrated for relative error <= 1e-12" \
            in generic.describe()
    else:  # DOP853 cannot honour 1e-12: the mpmath Taylor method does
        assert generic.method == "reference" and "mpmath Taylor" in generic.describe()
    assert plan(load(ROOT / "scenes/steady4d.toml")).method == "closed form"


def _scene(initial, n=4, a=0.5, want='["M", "gamma"]'):
    return loads(f'n = {n}\na = {a}\nb = 1.0\n[initial]\n{initial}\n[times]\nt_end = 1.0\n'
                 f'[outputs]\nwant = {want}\n')


def test_unclaimed_vertical_point_is_detected():
    """An explicit initial condition in V (not a steady rotation) gets the closed form of Th:Re
    without being labelled; a point in V that is also a steady rotation gets the cheaper one."""
    from chaplygin_nd.simulate.dynamics import families
    M0, g0 = families.draw("vertical", 4, 0.5, 1.0, seed=12)
    s = _scene(f"M = {M0[0].tolist()}\ngamma = {g0[0].tolist()}")
    assert s.family == "explicit"
    assert plan(s).model == ("vertical" if active().has("zeta") else "full")
    steady = _scene('M = [[0.0, 1.0, 0.0, 0.0], [-1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0], '
                    '[0.0, 0.0, 0.0, 0.0]]\ngamma = [0.0, 0.0, 0.6, 0.8]')
    assert plan(steady).model == "constant-Omega"


def test_spherical_inertia_beats_everything():
    s = _scene('family = "vertical"\nseed = 2', n=5, a=0.0)
    assert plan(s).model == "constant-Omega"


def test_reconstruction_only_when_asked():
    base = 'family = "generic"\nseed = 4'
    assert not plan(_scene(base)).reconstruct
    assert plan(_scene(base, want='["contact_path"]')).reconstruct
    assert plan(_scene(base, want='["orientation"]')).reconstruct


def test_orientation_rules_out_the_reduced_models():
    p = plan(_scene('family = "horizontal"\nseed = 4', want='["reduced", "orientation"]'))
    assert p.model == "full"
    assert "not SO(3)-invariant" in p.describe()


def test_force_full():
    s = load(ROOT / "scenes/steady4d.toml")
    assert plan(s, force_full=True).model == "full"
