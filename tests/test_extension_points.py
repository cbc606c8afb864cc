"""Adding a scene output, an evidence rule or an integrator is one registration: the scene check,
the planner, the collection, the figures, the verdict's reasons and the calibration tables read
the registries (simulate/scene/output_registry.py, simulate/analysis/rules.py,
simulate/integrators/registry.py), so an entry added in a test is seen everywhere at once."""

from __future__ import annotations

import numpy as np
import pytest
from chaplygin_nd.simulate.analysis import rules
from chaplygin_nd.simulate.integrators import registry, settings
from chaplygin_nd.simulate.scene import figures, output_registry, spec
from chaplygin_nd.simulate.scene.outputs import collect
from chaplygin_nd.simulate.scene.planner import plan
from chaplygin_nd.simulate.scene.run import execute

SCENE = """
n = 4
a = 0.5
b = 1.0
[initial]
family = "generic"
seed = 3
[times]
t_end = 0.5
samples = 6
[outputs]
want = [{want}]
[accuracy]
method = "dop853"
"""


@pytest.fixture
def added(request):
    """Register ``request.param`` (a registry and an entry) for one test, then remove it."""
    reg, entry = request.param
    reg.register(entry)
    try:
        yield entry
    finally:
        del reg._entries[reg.key(entry)]


def _norm(scene, d):
    return {"norm": np.linalg.norm(d["M"], axis=(-2, -1))}


NORM = output_registry.Output("norm", _norm)
ONLY5 = output_registry.Output("only5", _norm, only_n=5)


@pytest.mark.parametrize("added", [(output_registry._REGISTRY, NORM)], indirect=True)
def test_a_registered_output_is_validated_planned_collected_and_drawn(added):
    scene = spec.loads(SCENE.format(want='"norm", "x"'))
    assert "norm" in spec.OUTPUTS and scene.outputs == ("norm", "x")
    p = plan(scene)
    arrays = collect(scene, execute(scene, p, progress=False))
    assert arrays["norm"].shape == (6, 1) and np.all(arrays["norm"] > 0)
    assert output_registry.drawing("norm", figures.series) is figures.series
    assert "norm" not in output_registry.where("reduced")   # it declared no reduced model


@pytest.mark.parametrize("added", [(output_registry._REGISTRY, ONLY5)], indirect=True)
def test_a_registered_outputs_conditions_are_checked_by_the_scene(added):
    with pytest.raises(spec.SceneError, match="only5.*n = 5"):
        spec.loads(SCENE.format(want='"only5"'))


def test_an_unregistered_output_is_refused():
    with pytest.raises(spec.SceneError, match="unknown output 'norm'"):
        spec.loads(SCENE.format(want='"norm"'))


class _Orbit:
    def __init__(self, cls, megno_cls="regular", drift=0.0, diffusion=1e-9):
        self.cls, self.megno_cls, self.drift, self.diffusion = cls, megno_cls, drift, diffusion


PLANTED = rules.Rule("planted", "cls", (rules.Criterion(
    "are resonant", lambda r: r.cls == "resonant", 0.5, at_least=False),))


@pytest.mark.parametrize("added", [(rules._REGISTRY, PLANTED)], indirect=True)
def test_a_registered_evidence_rule_decides_with_the_others(added):
    orbits = [_Orbit("resonant")] * 6 + [_Orbit("predicted")] * 4
    assert rules.unmet(orbits) == [
        "planted: 6 of 10 orbits are resonant: 60 %, more than the rule's 50 %"]
    assert rules.unmet([_Orbit("predicted")] * 10) == []
    assert len(rules.separates(orbits, orbits)) == 2       # the planted rule has no control test


def test_the_tables_of_the_integrators_are_their_entries():
    assert spec.METHODS == ("auto", *registry.named())
    for entry in registry.entries():
        for key, calibration in entry.calibration:
            assert settings.MEASURED[key] == calibration.measured
            assert settings.ROUNDING[key] == calibration.rounding
            if calibration.floor is not None:
                assert settings.FLOORS[key] == calibration.floor
    assert all(e.cost is not None for e in registry.entries() if e.costed)
