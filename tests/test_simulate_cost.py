"""The cost model of the planner (simulate/scene/cost.py) and the run budget (simulate/scene/budget.py):
the cheapest predicted candidate is chosen, a scene may still name its method, and on a fresh
machine (empty caches) a long scene is not refused because of the compile time before its run."""

from __future__ import annotations

from pathlib import Path

import pytest
from chaplygin_nd.runtime import jit_cache
from chaplygin_nd.simulate.integrators import heyoka_taylor
from chaplygin_nd.simulate.scene import budget, cost
from chaplygin_nd.simulate.scene.planner import plan
from chaplygin_nd.simulate.scene.run import execute
from chaplygin_nd.simulate.scene.spec import load, loads

ROOT = Path(__file__).resolve().parents[1]
heyoka_only = pytest.mark.skipif(not heyoka_taylor.available(), reason="heyoka not installed")


def test_choose_takes_the_least_total_and_describes_all():
    cands = [cost.Candidate("dop853", None, 0.0, 2.0),
             cost.Candidate("heyoka", True, 1.0, 0.1, "cold"),
             cost.Candidate("heyoka", False, 0.03, 0.05, "on disk")]
    best = cost.choose(cands)
    assert best is cands[2]
    text = cost.describe(cands, best)
    assert text.startswith("predicted heyoka unrolled") and "DOP853" in text and "compact" in text


def test_decomposition_size_is_quadratic_for_the_full_field():
    for n in (8, 16, 32):
        assert heyoka_taylor.decomposition_size(f"full n={n}", n) <= 30 * n * n


def test_a_named_method_is_kept():
    text = (ROOT / "scenes/generic4d.toml").read_text().replace("target = 1e-12",
                                                                 'target = 1e-12\nmethod = "dop853"')
    p = plan(loads(text))
    assert p.method == "dop853" and "cost: predicted DOP853" in p.describe()
    assert "heyoka" not in p.describe().split("cost:")[1]


@heyoka_only
@pytest.mark.parametrize("variant", ["generic4d t_end 2000", "generic4d t_end 2000 heyoka", "tori4d"])
def test_fresh_machine_long_scenes_are_not_refused(tmp_path, monkeypatch, variant):
    """Empty caches (ours and heyoka's folder variable) and a budget that decides at the first
    step: compile time inside the run's clock, scaled by T/t1, would refuse these runs."""
    monkeypatch.setenv(jit_cache.ENV, str(tmp_path / "cache"))
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    monkeypatch.setattr(budget, "PILOT_SECONDS", 0.0)
    jit_cache.forget_memory()
    if variant == "tori4d":
        scene = load(ROOT / "scenes/tori4d.toml")
    else:
        text = (ROOT / "scenes/generic4d.toml").read_text().replace("t_end = 100.0", "t_end = 2000.0")
        if variant.endswith("heyoka"):
            text = text.replace("target = 1e-12", 'target = 1e-12\nmethod = "heyoka"')
        scene = loads(text)
    p = plan(scene)
    assert "cost: predicted" in p.describe()
    traj = execute(scene, p, progress=False, force=False)
    assert traj.t[-1] == scene.t[-1]
    if p.method == "heyoka":
        assert traj.compile_seconds > 0  # compiled here (cold), outside the budget's clock
    jit_cache.forget_memory()
