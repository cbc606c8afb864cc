"""The notebook API (chaplygin_nd.api): its doctests run here, importing the package stays light,
and a scene given by name, by path or as TOML text gives the same arrays."""

from __future__ import annotations

import doctest
import subprocess
import sys

import numpy as np
import pytest
from chaplygin_nd.simulate.scene.spec import builtin_scenes

import chaplygin_nd
import chaplygin_nd.api as api


def test_the_doctests_of_the_api_pass():
    result = doctest.testmod(api, optionflags=doctest.ELLIPSIS, verbose=False)
    assert result.attempted >= 30 and result.failed == 0, result
    documented = [f for f in api.__all__ if f != "Simulation"]
    assert all(">>> " in getattr(api, f).__doc__ for f in documented)


def test_import_loads_neither_sympy_nor_numpy():
    code = ("import sys, chaplygin_nd; "
            "print(sorted({m.split('.')[0] for m in sys.modules} & {'sympy', 'numpy'}))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert r.stdout.strip() == "[]"


def test_the_api_is_reexported():
    for name in api.__all__:
        assert getattr(chaplygin_nd, name) is getattr(api, name) or name == "simulate"
    assert set(api.__all__) <= set(dir(chaplygin_nd))


def test_simulate_is_the_subpackage_and_the_function():
    import chaplygin_nd.simulate.scene.spec as scene_module  # the subpackage is imported first

    assert chaplygin_nd.simulate.scene.spec is scene_module
    by_name = chaplygin_nd.simulate("steady4d")
    assert isinstance(by_name, api.Simulation)


def test_a_frequency_map_is_refused_with_one_clear_error():
    from chaplygin_nd.simulate.scene.spec import SceneError

    with pytest.raises(SceneError, match="a frequency map has no single trajectory"):
        chaplygin_nd.simulate("fma4d")


def test_help_shows_the_function_and_the_reprs_are_short():
    import pydoc

    text = pydoc.render_doc(chaplygin_nd.simulate, renderer=pydoc.plaintext)
    assert "function simulate" in text and "Plan and run ``scene``" in text
    assert "Four subpackages and one binding" not in text  # not the subpackage's docstring
    run = chaplygin_nd.simulate("steady4d")
    shown = repr(run)
    assert shown.startswith("<Simulation") and shown.count("\n") <= 4 and len(shown) < 600
    assert "constant-Omega" in shown and "M (301, 1, 4, 4)" in shown
    result = api.decide("eq:invL3D")
    assert repr(result).startswith("<Result eq:invL3D: holds") and len(repr(result)) < 120


def test_a_scene_by_name_path_or_text_gives_the_same_arrays(tmp_path):
    assert "steady4d" in builtin_scenes()
    from importlib import resources
    text = (resources.files("chaplygin_nd.scenes") / "steady4d.toml").read_text()
    path = tmp_path / "mine.toml"
    path.write_text(text)
    runs = [api.simulate("steady4d"), api.simulate(path), api.simulate(text)]
    for run in runs[1:]:
        assert run.plan.model == runs[0].plan.model
        assert sorted(run.outputs) == sorted(runs[0].outputs)
        for key, v in run.outputs.items():
            np.testing.assert_array_equal(v, runs[0].outputs[key])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["mine.toml"]  # nothing written
    assert "model: constant-Omega" in runs[0].summary()


def test_an_unknown_row_is_a_key_error():
    with pytest.raises(KeyError):
        api.decide("no:such-row")
