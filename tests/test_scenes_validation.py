"""Bad scenes get one clear error naming the field and the fix; nothing runs, nothing is written."""

from __future__ import annotations

import textwrap
from pathlib import Path

import numpy as np
import pytest
from chaplygin_nd.simulate.scene import cli
from chaplygin_nd.simulate.scene.spec import OUTPUTS, SceneError, load, loads

# trajectory scenes; frequency-map scenes ([fma], tests/test_fma.py) have no initial condition
SCENES = sorted(p for p in Path(__file__).resolve().parent.parent.glob("scenes/*.toml")
                if "\n[fma]" not in p.read_text(encoding="utf-8"))

BASE = """
n = 4
a = 0.5
b = 1.0
{extra}
[initial]
{initial}
[times]
{times}
[outputs]
want = {want}
[accuracy]
{accuracy}
"""


def scene_text(extra="", initial='family = "generic"\nseed = 1', times="t_end = 1.0",
               want='["M", "gamma"]', accuracy="", **replace):
    text = BASE.format(extra=extra, initial=initial, times=times, want=want, accuracy=accuracy)
    for key, value in replace.items():
        text = text.replace(f"{key} = ", f"__{key} = ", 1).replace(f"__{key} = ", value, 1) \
            if value is not None else text
    return text


def test_example_scenes_load():
    """Every shipped scene is valid."""
    assert len(SCENES) >= 8
    for path in SCENES:
        scene = load(path)
        assert scene.M0.shape == (scene.count, scene.n, scene.n)
        assert np.allclose(np.linalg.norm(scene.gamma0, axis=-1), 1.0, atol=1e-14)
        assert set(scene.outputs) <= set(OUTPUTS)


def test_the_base_scene_is_valid():
    assert loads(scene_text()).n == 4


VERTICAL_BROKEN = """M = [[0.0, 1.0, 0.0, 0.0], [-1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0]]
gamma = [0.6, 0.0, 0.0, 0.8]
family = "vertical"
"""
HORIZONTAL_BROKEN = VERTICAL_BROKEN.replace('"vertical"', '"horizontal"')
STEADY_BROKEN = """Omega = [[0.0, -0.3, 0.0, 1.0], [0.3, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0], [-1.0, 0.0, 0.0, 0.0]]
gamma = [0.0, 0.0, 0.6, 0.8]
family = "steady-rotation"
"""
EXPLICIT = """M = [[0.0, 1.0, 0.0, 0.0], [-1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0]]
gamma = {gamma}
"""
BAD = {
    # a > 1 (a prolate ball) is accepted with a note: tests/test_physical_ball.py
    "a below -1": (dict(a="a = -1.0001\n#"), "a", "a >= -1"),
    "b zero": (dict(b="b = 0.0\n#"), "b", "b > 0"),
    "b negative": (dict(b="b = -2.0\n#"), "b", "b > 0"),
    "n too small": (dict(n="n = 2\n#"), "n", "n >= 3"),
    "n not integer": (dict(n="n = 4.5\n#"), "n", "integer"),
    "gamma not unit": (dict(initial=EXPLICIT.format(gamma="[0.0, 0.0, 0.6, 0.81]")),
                       "initial.gamma", "normalise"),
    "gamma wrong length": (dict(initial=EXPLICIT.format(gamma="[0.6, 0.8]")),
                           "initial.gamma", "shape (4,)"),
    "M not skew": (dict(initial=EXPLICIT.format(gamma="[0.0, 0.0, 0.6, 0.8]").replace(
        "[-1.0, 0.0", "[1.0, 0.0")), "initial.M", "X[j][i] = -X[i][j]"),
    "M wrong shape": (dict(initial='M = [[0.0, 1.0], [-1.0, 0.0]]\ngamma = [0.0, 0.0, 0.6, 0.8]'),
                      "initial.M", "shape (4, 4)"),
    "M not rectangular": (dict(initial='M = [[0.0, 1.0], [-1.0]]\ngamma = [0.0, 0.0, 0.6, 0.8]'),
                          "initial.M", "array of shape"),
    "vertical claim false": (dict(initial=VERTICAL_BROKEN), "initial.family", "M0 gamma0 = 0"),
    "horizontal claim false": (dict(initial=HORIZONTAL_BROKEN), "initial.family",
                               "(M0 gamma0) ^ gamma0"),
    "steady claim false": (dict(initial=STEADY_BROKEN), "initial.family", "eta0 parallel"),
    "steady in 5D": (dict(n="n = 5\n#", initial='family = "steady-rotation"\nseed = 1'),
                     "initial.family", "n = 4"),
    "both M and Omega": (dict(initial=EXPLICIT.format(gamma="[0.0, 0.0, 0.6, 0.8]")
                              + "Omega = [[0.0]]"), "initial", "one of them"),
    "family without seed": (dict(initial='family = "vertical"'), "initial.seed", "seed"),
    "unknown family": (dict(initial='family = "diagonal"\nseed = 1'), "initial.family",
                       "generic"),
    "unknown output": (dict(want='["M", "spin"]'), "outputs.want", "Omega"),
    "outputs not a list": (dict(want='"M"'), "outputs.want", "list"),
    "zeta for a generic scene": (dict(want='["zeta"]'), "outputs.want", "vertical"),
    "reduced in 5D": (dict(n="n = 5\n#", want='["reduced"]'), "outputs.want", "n = 4"),
    "unknown key": (dict(extra="colour = 3"), "colour", "use only"),
    "unknown initial key": (dict(initial='family = "generic"\nseed = 1\nsed = 2'),
                            "initial.sed", "use only"),
    "negative t_end": (dict(times="t_end = -1.0"), "times.t_end", "t_end > 0"),
    "times not increasing": (dict(times="t = [0.0, 2.0, 1.0]"), "times.t", "increasing"),
    "times not a list": (dict(times="t = 3.0"), "times.t", "t = [0.0"),
    "both t and t_end": (dict(times="t = [0.0, 1.0]\nt_end = 2.0"), "times", "one of them"),
    "samples too few": (dict(times="t_end = 1.0\nsamples = 1"), "times.samples", "samples >= 2"),
    "dps out of range": (dict(accuracy="dps = 5"), "accuracy.dps", "15 <= dps"),
    "step not positive": (dict(accuracy="step = 0.0"), "accuracy.step", "0.01"),
    "count with explicit point": (dict(initial=EXPLICIT.format(gamma="[0.0, 0.0, 0.6, 0.8]")
                                       + "count = 3"), "initial.count", "drop count"),
    "gamma missing": (dict(initial="M = [[0.0]]"), "initial.gamma", "|gamma| = 1"),
    "radius not positive": (dict(extra="radius = 0.0"), "radius", "radius > 0"),
    "target out of range": (dict(accuracy="target = 2.0"), "accuracy.target", "1e-10"),
    "unknown method": (dict(accuracy='method = "euler"'), "accuracy.method", "dop853"),
    "not TOML": (dict(extra="= = ="), "TOML", "syntax"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_scene_error_names_field_and_fix(case):
    kwargs, field, fix = BAD[case]
    with pytest.raises(SceneError) as info:
        loads(scene_text(**kwargs), source="bad.toml")
    message = str(info.value)
    assert info.value.field == field, message
    assert message.startswith(f"bad.toml: {field}: "), message
    assert "Fix: " in message and fix in message, message


def test_family_claim_that_holds_is_accepted():
    ok = """M = [[0.0, 1.0, 0.0, 0.0], [-1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0]]
gamma = [0.0, 0.0, 0.6, 0.8]
family = "vertical"
"""
    scene = loads(scene_text(initial=ok))
    assert scene.family == "vertical" and scene.claimed


def test_bad_scene_runs_nothing_and_writes_nothing(tmp_path, capsys):
    """The CLI prints one error line, exits 2 and leaves no output folder (nor a temp folder)."""
    path = tmp_path / "bad.toml"
    path.write_text(scene_text(b="b = -1.0\n#"))
    out = tmp_path / "out"
    assert cli.main([str(path), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "b:" in err[0] and "Fix:" in err[0]
    assert not out.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.toml"]


def test_missing_file_is_a_scene_error(tmp_path):
    with pytest.raises(SceneError) as info:
        load(tmp_path / "nowhere.toml")
    assert info.value.field == "file"
    assert str(info.value).startswith(f"{tmp_path / 'nowhere.toml'}: cannot read it")


def test_a_misspelt_built_in_scene_gets_the_closest_name():
    """A new user's trial: ``chaplygin simulate stedy4d`` listed the scenes but did not say which one
    was meant, and said ``file:`` as if it were a field of the scene."""
    from chaplygin_nd.simulate.scene.spec import find

    with pytest.raises(SceneError) as info:
        find("stedy4d")
    assert str(info.value).startswith("stedy4d: no such scene file or built-in scene "
                                      "(did you mean steady4d?). Fix: ")
    with pytest.raises(SceneError) as info:
        find("zzzz")
    assert "did you mean" not in str(info.value)


def test_dedent_helper_keeps_toml_valid():
    assert loads(textwrap.dedent(scene_text())).outputs == ("M", "gamma")
