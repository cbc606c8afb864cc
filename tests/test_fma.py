"""Frequency maps (simulate/analysis/fma.py, simulate/scene/frequency_map.py): the control's compiled field
solves the definition, the axisymmetric case of it is the derived field, the vectorised NAFF
finds the lines PyNAFF finds, a 2-worker local Dask cluster gives the same map as one process,
and the scene runs end to end (small grids, short orbits: seconds)."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from chaplygin_nd.simulate.analysis import fma, naff
from chaplygin_nd.simulate.analysis.control import general_inertia_kernels
from chaplygin_nd.simulate.dynamics import families, so
from chaplygin_nd.simulate.integrators import heyoka_systems, heyoka_taylor

pytest.importorskip("heyoka")

ROOT = Path(__file__).resolve().parent.parent
SMALL = fma.MapSpec(a=-0.5, b=0.5, h=0.5, size=6, samples=256, dt=0.5, chunk=8)


def test_control_omega_solves_the_definition():
    M, g = families.draw("generic", 4, -0.5, 0.5, seed=5, count=4)
    for J in ((1.0, 1.3, 0.75, 0.5), (1.0, 1.0, 1.0, 0.5), (0.3, 2.0, 1.1, 0.9)):
        ref = general_inertia_kernels(J, 0.5).angular_velocity(M, g, None, None)
        for k in range(len(M)):
            w = fma.control_omega(list(so.vec(M[k])), list(g[k]), list(J), 0.5)
            assert np.max(np.abs(np.array(w) - so.vec(ref[k]))) < 1e-13


def test_the_control_field_at_the_axisymmetric_tensor_is_the_derived_field():
    a, b = -0.5, 0.5
    M, g = families.draw("generic", 4, a, b, seed=2, count=4)
    y0 = np.concatenate([so.vec(M), g], -1)
    t = np.linspace(0.0, 20.0, 41)
    derived = heyoka_taylor.integrate(heyoka_systems.full(4), y0, t, tol=1e-13, pars=[a, b])
    control = heyoka_taylor.integrate(fma.control_system(4), y0, t, tol=1e-13,
                                      pars=[1.0, 1.0, 1.0, 1.0 + a, b])
    assert np.max(np.abs(derived.y - control.y)) < 1e-10


def test_vectorised_fundamental_agrees_with_pynaff():
    dt, t = 0.5, np.arange(1024) * 0.5
    rng = np.random.default_rng(4)
    f1, f2 = rng.uniform(0.4, 1.5, 6), rng.uniform(0.05, 0.2, 6)
    z = (np.exp(1j * f1[:, None] * t) + 0.4 * np.exp(1j * f2[:, None] * t + 0.3j)
         + 0.1 * np.exp(-1j * (f1 + f2)[:, None] * t))
    nu = naff.fundamental_frequencies(z, dt)
    ref = np.array([naff.spectral_lines(row, dt, terms=3)[0][0] for row in z])
    assert np.max(np.abs(nu - ref)) < 1e-9
    assert np.max(np.abs(nu - f1)) < 1e-5          # the first NAFF step, other lines leak
    assert naff.fundamental_frequencies(np.ones((2, 64)), dt).tolist() == [0.0, 0.0]


def test_initial_conditions_lie_on_the_energy_level_set():
    for spec in (SMALL, replace(SMALL, J=(1.0, 1.3, 0.75, 0.5))):
        y0, x0, phi = fma.initial_conditions(spec)
        M, g = so.unvec(y0[:, :6], 4), y0[:, 6:]
        Om = general_inertia_kernels(spec.mass_tensor, spec.b).angular_velocity(M, g, None, None)
        H = 0.5 * np.einsum("...i,...i->...", so.vec(M), so.vec(Om))
        assert np.max(np.abs(H - spec.h)) < 1e-13
        assert np.max(np.abs(np.linalg.norm(g, axis=1) - 1)) < 1e-15
        assert np.allclose(g[:6, 3], x0)


def _hold_port(port: int):
    """A listening socket on `port` of every interface, or None when another program holds it
    already (then the port is taken either way)."""
    import socket

    sock = socket.socket()
    try:
        sock.bind(("0.0.0.0", port))
        sock.listen()
    except OSError:
        sock.close()
        return None
    return sock


def test_a_local_dask_cluster_gives_the_map_of_one_process():
    """Also with Dask's default HTTP port taken (by another cluster, a test beside this one on
    the other xdist worker, any program): CI failed on that once."""
    pytest.importorskip("distributed")
    here = fma.run_map(SMALL, workers=1)
    held = _hold_port(8787)
    try:
        cluster = fma.run_map(SMALL, workers=2, scheduler="local")
    finally:
        if held is not None:
            held.close()
    assert here.shape == (6, 6) and np.all(np.isfinite(here))
    assert np.array_equal(here, cluster)


def test_the_symmetric_map_is_regular_where_the_control_diffuses():
    """The rule of the scene's summary (fixed before the maps were drawn): regular D < -6,
    chaotic D > -4. On a small grid (T = 1024) most axisymmetric orbits are regular and no
    control orbit is."""
    spec = replace(SMALL, size=4, samples=1024)
    sym = fma.run_map(spec, workers=1)
    ctl = fma.run_map(replace(spec, J=(1.0, 1.3, 0.75, 0.5)), workers=1)
    assert np.mean(sym < -6) >= 0.5, sym
    assert np.all(ctl > -6), ctl
    assert np.median(ctl) > np.median(sym) + 2


def test_the_scene_validates_and_runs(tmp_path):
    from chaplygin_nd.simulate.scene.cli import main
    from chaplygin_nd.simulate.scene.frequency_map import FrequencyMapScene
    from chaplygin_nd.simulate.scene.spec import SceneError, load, loads

    scene = load(ROOT / "scenes" / "fma4d.toml")
    assert isinstance(scene, FrequencyMapScene) and scene.spec.size >= 200
    assert scene.control.J and not scene.spec.J
    text = (ROOT / "scenes" / "fma4d.toml").read_text()
    for old, new, where in (("grid = 200", "grid = 1", "fma.grid"),
                            ("n = 4", "n = 5", "n"),
                            ("energy = 0.5", "energy = -1", "fma.energy"),
                            ("x_range = [-0.9, 0.9]", "x_range = [0.5, 0.2]", "fma.x_range"),
                            ("control_J = [1.0, 1.3, 0.75, 0.5]", "control_J = [1, 0]", "fma.control_J"),
                            ("seed = 1", "seed = 1\nspeed = 2", "fma.speed")):
        with pytest.raises(SceneError) as err:
            loads(text.replace(old, new))
        assert err.value.field == where
    small = (text.replace("grid = 200", "grid = 3").replace("samples = 2048", "samples = 128")
             .replace("dt = 1.0", "dt = 0.5"))
    path = tmp_path / "tiny.toml"
    path.write_text(small)
    out = tmp_path / "out"
    assert main([str(path), "--out", str(out), "--workers", "1"]) == 0
    names = sorted(p.name for p in out.iterdir() if not p.name.startswith("."))
    assert names == ["fma.npz", "fma_axisymmetric.png", "fma_control.png", "summary.txt"]
    with np.load(out / "fma.npz") as d:
        assert d["D_axisymmetric"].shape == d["D_control"].shape == (3, 3)


def test_no_plots_writes_no_map_figure(tmp_path):
    """--no-plots covers the frequency-map scenes too (a new user's trial found
    fma_*.png written under --no-plots): the arrays and the summary, no PNG."""
    from chaplygin_nd.simulate.scene.cli import main

    text = (ROOT / "scenes" / "fma4d.toml").read_text()
    small = (text.replace("grid = 200", "grid = 2").replace("samples = 2048", "samples = 64")
             .replace("dt = 1.0", "dt = 0.5"))
    path = tmp_path / "tiny.toml"
    path.write_text(small)
    out = tmp_path / "out"
    assert main([str(path), "--out", str(out), "--workers", "1", "--no-plots"]) == 0
    names = sorted(p.name for p in out.iterdir() if not p.name.startswith("."))
    assert names == ["fma.npz", "summary.txt"]


def test_without_heyoka_a_map_stops_before_its_plan_with_one_line(tmp_path, monkeypatch, capsys):
    """A new user's trial: without heyoka, fma4d printed its plan line, then the error."""
    from chaplygin_nd.simulate.integrators import heyoka_taylor
    from chaplygin_nd.simulate.scene.cli import main

    monkeypatch.setattr(heyoka_taylor, "available", lambda: False)
    out = tmp_path / "fma"
    assert main(["fma4d", "--out", str(out), "--no-plots"]) == 2
    got = capsys.readouterr()
    assert "plan" not in got.out
    assert got.err.strip().splitlines() == [
        "error: frequency maps need heyoka: pip install 'chaplygin-nd[fast]'"]
    assert not out.exists()


def test_the_plan_says_how_many_processes_run_the_orbits():
    """A new user's trial: the plan said "all worker process(es)"."""
    import os

    cores = os.cpu_count() or 1
    assert fma.where(None, None) == ("this process" if cores == 1 else f"{cores} worker processes")
    assert fma.where(1, None) == "this process"
    assert fma.where(2, "local") == "a local Dask cluster of 2 processes"
    assert fma.where(None, "tcp://10.0.0.1:8786") == "Dask scheduler tcp://10.0.0.1:8786"
