"""Closed forms and reconstruction agree with the full system; outputs are written atomically."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest
from chaplygin_nd.simulate.dynamics import so
from chaplygin_nd.simulate.scene import cli
from chaplygin_nd.simulate.scene.crosscheck import cross_check
from chaplygin_nd.simulate.scene.outdir import MANIFEST, claim
from chaplygin_nd.simulate.scene.outputs import collect, write
from chaplygin_nd.simulate.scene.planner import plan
from chaplygin_nd.simulate.scene.run import execute
from chaplygin_nd.simulate.scene.spec import load

ROOT = Path(__file__).resolve().parent.parent


def _short(stem, t_end=6.0, samples=13):
    scene = load(ROOT / "scenes" / f"{stem}.toml")
    return dataclasses.replace(scene, t=np.linspace(0.0, t_end, samples))


@pytest.mark.parametrize("stem", ["steady4d", "vertical5d", "spherical6d", "horizontal4d",
                                  "reduced4d", "explicit4d"])
def test_cross_check_agreement(stem):
    """Every output of the planned model equals an independent full run to 1e-10
    (outputs are O(1); horizons are short), and the cross-check judges it a pass."""
    scene = _short(stem)
    p = plan(scene)
    arrays = collect(scene, execute(scene, p, progress=False))
    check = cross_check(scene, p, arrays, progress=False)
    diffs = {k: d for k, d, _, _ in check.rows}
    assert set(diffs) == {k for k in arrays if k != "t" and k != "zeta"
                          and not k.startswith("drift.")}
    assert max(diffs.values()) < 1e-10, (p.model, diffs)
    assert check.passed and check.describe().endswith("cross-check: pass")


def test_vertical_closed_form_keeps_x_and_zeta_fixes_E_n():
    """Th:Re: x(t) = x0, zeta E_n = 0, zeta gamma0 = -Omega0 gamma0 (on the vertical scene)."""
    scene = _short("vertical5d")
    p = plan(scene)
    arrays = collect(scene, execute(scene, p, progress=False))
    if p.model != "vertical":
        pytest.fail(f"zeta kernel missing: {p.describe()}")
    zeta = arrays["zeta"][0]
    assert np.max(np.abs(arrays["x"] - arrays["x"][0])) < 1e-13
    assert np.max(np.abs(zeta[:, -1])) < 1e-14
    Og = p.Omega0[0] @ scene.gamma0[0]
    assert np.max(np.abs(zeta @ scene.gamma0[0] + Og)) < 1e-13


@pytest.mark.parametrize("stem,method", [("explicit4d", "lie"), ("steady4d", "auto"),
                                         ("vertical5d", "auto")])
def test_reconstruction_is_consistent(stem, method):
    """g in SO(n), g^T E_n = gamma (the convention gamma = g^T E_n), and the centre stays at height
    c_n = 0 (the contact point moves in the plane) — to rounding for the closed forms and the
    Lie-group integrator, whose updates are orthogonal (DOP853 keeps them only to its tolerance;
    its reconstruction is compared in test_cross_check_agreement)."""
    scene = dataclasses.replace(_short(stem), method=method)
    traj = execute(scene, plan(scene), progress=False)
    g, gamma, c = traj.data["g"], traj.data["gamma"], traj.data["c"]
    n = scene.n
    assert np.max(np.abs(g @ np.swapaxes(g, -1, -2) - np.eye(n))) < 1e-12
    assert np.allclose(np.linalg.det(g), 1.0, atol=1e-12)
    assert np.max(np.abs(g[..., -1, :] - gamma)) < 1e-10
    assert np.max(np.abs(c[..., -1])) < 1e-10


def test_contact_path_of_a_steady_rotation_is_a_straight_line():
    scene = _short("steady4d")
    c = execute(scene, plan(scene), progress=False).data["c"][:, 0, :-1]
    v = c[-1] - c[0]
    off = c - c[0] - np.outer((c - c[0]) @ v / (v @ v), v)
    assert np.linalg.norm(v) > 0.1 and np.max(np.abs(off)) < 1e-12


def test_cli_writes_outputs_and_summary(tmp_path, capsys):
    src = (ROOT / "scenes/steady4d.toml").read_text().replace("t_end = 30.0", "t_end = 3.0")
    path = tmp_path / "steady.toml"
    path.write_text(src)
    out = tmp_path / "result"
    assert cli.main([str(path), "--out", str(out), "--cross-check"]) == 0
    text = capsys.readouterr().out
    assert "model: constant-Omega" in text and "cross-check" in text and "drift" in text
    with np.load(out / "outputs.npz") as data:  # closed: an open npz is a ResourceWarning (error)
        assert data["M"].shape == (301, 1, 4, 4) and data["contact_path"].shape == (301, 1, 3)
    for name in ("M", "Omega", "gamma", "orientation", "contact_path", "drift.energy"):
        assert (out / f"{name}.csv").stat().st_size > 0
        assert (out / f"{name}.png").read_bytes()[:4] == b"\x89PNG"
    assert "constant-Omega" in (out / "summary.txt").read_text()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["result", "steady.toml"]
    assert "cross-check: pass" in text


def test_failed_write_leaves_no_partial_file(tmp_path):
    """Each file is written atomically: a failure mid-way leaves the files of the first run
    (summary.txt untouched), no temporary file, and a manifest that still owns every file."""
    out = tmp_path / "o"
    write(claim(out, "s"), {"t": np.arange(3.0), "x": np.zeros((3, 1))}, "first", plots=False)
    bad = {"t": np.arange(3.0), "x": np.zeros((3, 1)), "M": np.array([object()] * 3)}
    with pytest.raises(TypeError):
        write(claim(out, "s"), bad, "second", plots=False)
    assert (out / "summary.txt").read_text() == "first\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["o"]
    names = {p.name for p in out.iterdir()}
    assert not [n for n in names if ".tmp" in n]
    owned = set(json.loads((out / MANIFEST).read_text())["files"])
    assert names - {MANIFEST} <= owned


def test_rotation_to_maps_E_n_to_gamma():
    rng = np.random.default_rng(5)
    for n in (3, 4, 7):
        for _ in range(5):
            gamma = rng.standard_normal(n)
            gamma /= np.linalg.norm(gamma)
            g0 = so.rotation_to(gamma)
            assert np.allclose(g0.T[:, -1], gamma, atol=1e-15)
            assert np.isclose(np.linalg.det(g0), 1.0)


def test_reduced_invariants_are_SO3_invariant_and_satisfy_the_syzygy():
    """r = (A, B, E, G, F1, x, delta) (Section 5, eq:red-system order) is unchanged by
    h.(k, u, q, x) = (hk, hu, hq, x), and delta^2 = det Lambda."""
    from chaplygin_nd.simulate.dynamics import families
    from chaplygin_nd.simulate.dynamics.so import reduced_invariants

    M, gamma = families.draw("generic", 4, 0.5, 1.0, seed=8, count=6)
    r = reduced_invariants(M, gamma)
    h = np.eye(4)
    h[:3, :3] = so.expm_skew_t(so.hat(np.array([0.3, -1.1, 0.7])), np.array([1.0]))[0]
    r_h = reduced_invariants(h @ M @ h.T, gamma @ h.T)
    assert np.max(np.abs(r - r_h)) < 1e-14
    A, B, E, G, F1, x, delta = np.moveaxis(r, -1, 0)
    Lam = np.stack([np.stack([A, F1, E], -1), np.stack([F1, B, G], -1),
                    np.stack([E, G, 1 - x**2], -1)], -2)
    assert np.max(np.abs(delta**2 - np.linalg.det(Lam))) < 1e-14
    k, u = so.split4(M)
    assert np.allclose(A, np.sum(k * k, -1)) and np.allclose(F1, np.sum(k * u, -1))
