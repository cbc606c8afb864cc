"""S5:H-linear-nD in the simulator: the closed form for horizontal momentum in any n matches the
full system, and its generated kernel matches a 50-digit evaluation of the definitions."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import mpmath
import numpy as np
import pytest
from chaplygin_nd.simulate.dynamics.closed_forms import horizontal_invariants
from chaplygin_nd.simulate.kernels import active
from chaplygin_nd.simulate.scene.outputs import collect
from chaplygin_nd.simulate.scene.planner import plan
from chaplygin_nd.simulate.scene.run import execute
from chaplygin_nd.simulate.scene.spec import load, loads

ROOT = Path(__file__).resolve().parent.parent


def _scene(n):
    if n == 6:
        scene = load(ROOT / "scenes/horizontal6d.toml")
    else:
        scene = loads(f'n = {n}\na = 0.7\nb = 0.4\n[initial]\nfamily = "horizontal"\nseed = 3\n'
                      'count = 2\n[times]\nt_end = 40.0\nsamples = 81\n[outputs]\n'
                      'want = ["x", "horizontal"]\n[accuracy]\ntarget = 1e-10\n')
    return dataclasses.replace(scene, t=np.linspace(0.0, 20.0, 41))


@pytest.mark.parametrize("n", (5, 6))
def test_horizontal_closed_form_matches_full_system_at_target(n):
    """The planner picks the closed form, and it agrees with DOP853 on the full system (run at the
    scene's own tolerance rule, rtol = target/100) to the scene's target, x and (x, G, A, B)."""
    scene = _scene(n)
    p = plan(scene)
    assert p.model == "horizontal", p.describe()
    closed = collect(scene, execute(scene, p, progress=False))
    full_scene = dataclasses.replace(scene, method="dop853")
    full = collect(full_scene, execute(full_scene, plan(full_scene), progress=False))
    assert set(closed) == set(full) == {"t", "x", "horizontal"}
    for key in ("x", "horizontal"):
        assert np.max(np.abs(closed[key] - full[key])) < scene.target, key
    # and the motion is not trivial: x really moves
    assert np.ptp(closed["x"]) > 0.1


def test_horizontal_blocks_kernel_against_mpmath():
    """horizontal_blocks (S5:H-linear-nD) against A, B from the definitions at 50 digits, on
    seeded points of H (M = v ^ gamma) for n = 3..8, to a few ulps of F2."""
    mpmath.mp.dps = 50
    rng = np.random.default_rng(11)
    blocks = active().require("horizontal_blocks")
    for n in range(3, 9):
        for _ in range(5):
            g = rng.standard_normal(n)
            g /= np.linalg.norm(g)
            v = rng.standard_normal(n)
            M = np.outer(v, g) - np.outer(g, v)
            x, G, A, B = horizontal_invariants(M, g)
            F2 = A + B
            Mm = mpmath.matrix(M.tolist())
            col = [Mm[i, n - 1] for i in range(n)]
            B_ref = sum(c * c for c in col)
            A_ref = sum(Mm[i, j] ** 2 for i in range(n - 1) for j in range(i + 1, n - 1))
            got = blocks(x, G, F2)
            scale = F2 * np.finfo(float).eps
            assert abs(got[0] - float(A_ref)) < 16 * scale
            assert abs(got[1] - float(B_ref)) < 16 * scale
