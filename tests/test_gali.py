"""GALI_k (simulate/analysis/gali.py): the volume on exact configurations, the projection
transverse to the SO(n-1) orbits, the rule on series of known shape, and the rule on systems whose
torus dimension is known (uncoupled pendula, the standard map), quick versions of the validation
study (simulate/analysis/gali_study.py)."""

from __future__ import annotations

import numpy as np
import pytest
from chaplygin_nd.simulate.analysis import gali as gl
from chaplygin_nd.simulate.analysis import gali_study
from chaplygin_nd.simulate.dynamics import so


def test_volume_of_known_configurations():
    e = np.eye(4)
    assert np.allclose(gl.gali(e[:3]), [1.0, 1.0, 1.0])
    theta = 0.3
    u = np.array([[1.0, 0.0, 0.0], [np.cos(theta), np.sin(theta), 0.0], [0.0, 0.0, 5.0]])
    assert np.allclose(gl.gali(u), [1.0, np.sin(theta), np.sin(theta)])
    parallel = np.array([[1.0, 2.0, 0.0], [-2.0, -4.0, 0.0]])
    assert gl.gali(parallel)[1] < 1e-15


def test_projection_is_transverse_to_the_group_and_tangent_to_P():
    rng = np.random.default_rng(5)
    n = 5
    M = so.unvec(rng.standard_normal(so.so_dim(n)), n)
    g = rng.standard_normal(n)
    g /= np.linalg.norm(g)
    y = np.concatenate([so.vec(M), g])
    u = gl.project(rng.standard_normal((3, len(y))), y, n)
    Q = gl.group_directions(y, n)
    assert Q.shape[1] == so.so_dim(n - 1) + 1          # 6 group directions and the normal
    assert np.max(np.abs(u @ Q)) < 1e-12
    assert np.max(np.abs(u[:, so.so_dim(n):] @ g)) < 1e-12
    # a vector that already is transverse is kept
    assert np.allclose(gl.project(u, y, n), u)


def _series(T, shapes):
    t = np.linspace(0.0, T, 2049)
    tt = np.maximum(t, 1.0)
    return t, np.stack([f(tt) for f in shapes], -1)


def test_rule_on_series_of_known_shape():
    one = lambda t: np.ones_like(t)                      # noqa: E731
    flat = lambda t: 0.3 + 0.1 * np.sin(t)               # noqa: E731
    t, g = _series(4096.0, [one, flat, flat, lambda t: 0.2 / t])
    r = gl.verdict(t, g)
    assert (r.cls, r.dimension) == ("regular", 3)
    t, g = _series(4096.0, [one, flat, lambda t: 5.0 / t ** 2])
    assert (gl.verdict(t, g).cls, gl.verdict(t, g).dimension) == ("regular", 2)
    t, g = _series(4096.0, [one, flat, flat])
    assert gl.verdict(t, g).dimension == 3               # reported as >= K
    t, g = _series(4096.0, [one, lambda t: np.exp(-0.01 * t)])
    assert gl.verdict(t, g).cls == "chaotic"
    t, g = _series(4096.0, [one, lambda t: np.full_like(t, 1e-16)])   # collapsed before W_1
    assert gl.verdict(t, g).cls == "chaotic"


def test_standard_map_chaotic_and_twist():
    chaotic = gali_study.standard_map(10.0, 16, steps=1024)
    assert all(r.cls == "chaotic" for r in chaotic)
    twist = gali_study.standard_map(0.0, 16, steps=1024)
    assert all(r.cls == "regular" and r.dimension == 1 for r in twist)


@pytest.mark.parametrize("m", [2, 3])
def test_uncoupled_pendula_read_their_dimension(m):
    pytest.importorskip("heyoka")
    from chaplygin_nd.simulate.analysis import gali_runs

    y0, pars = gali_study._pendula_orbits(m, 8, 11)
    out = gali_runs.integrate(gali_study.pendula(m), y0, pars, K=m + 1, T=2048.0, dt=0.5, seed=3,
                              stride=8)
    dims = [r.dimension for r in out["gali"] if r.cls == "regular"]
    assert len(dims) == 8
    assert sum(d == m for d in dims) >= 7                   # the study's rate: 1 miss in 104
    assert all(d <= m for d in dims)


def test_sphere_quotient_reads_two():
    """The n = 4 sphere on P/SO(3) (Euler-Jacobi: 2-tori); chaos is read on the standard map
    above (the non-symmetric sphere is a mixed system: a single orbit's truth is unknown)."""
    pytest.importorskip("heyoka")
    from chaplygin_nd.simulate.analysis import draws, gali_runs
    from chaplygin_nd.simulate.integrators import heyoka_systems as hs

    ens = draws.draw("test-gali", "generic", 4, 4, 7)
    y0 = np.concatenate([so.vec(ens.M0), ens.gamma0], -1)
    pars = np.stack([ens.a, ens.b])
    out = gali_runs.integrate(hs.full(4), y0, pars, K=3, T=2048.0, dt=0.5, seed=7,
                              time_factor=ens.time_factor, n=4, stride=8)
    assert [(r.cls, r.dimension) for r in out["gali"]].count(("regular", 2)) >= 3
    assert all(r.cls == "regular" and r.dimension <= 2 for r in out["gali"])


def test_group_directions_stay_group_directions():
    """The flow is SO(n-1)-equivariant, so a deviation along the group orbit stays along it: its
    projection (what GALI on the quotient reads) stays zero (simulate/analysis/gali.py)."""
    pytest.importorskip("heyoka")
    from chaplygin_nd.simulate.integrators import heyoka_systems as hs
    from chaplygin_nd.simulate.integrators.heyoka_taylor import compiled_integrator

    n = 4
    rng = np.random.default_rng(9)
    M = so.unvec(rng.standard_normal(so.so_dim(n)), n)
    g = rng.standard_normal(n)
    g /= np.linalg.norm(g)
    y = np.concatenate([so.vec(M), g])
    X = np.zeros((n, n))
    X[0, 2], X[2, 0] = 1.0, -1.0                     # a generator of SO(3) = {h : h E_4 = E_4}
    u = np.concatenate([so.vec(X @ M - M @ X), X @ g])
    u /= np.linalg.norm(u)
    ta, _, _ = compiled_integrator(gl.deviation_system(hs.full(n), 1), "double", 1e-12,
                                   compact=True, cache=False)
    ta.state[:] = np.concatenate([y, u])
    ta.pars[:] = [0.5, 2.0]
    ta.propagate_until(40.0)
    d = len(y)
    yT, uT = ta.state[:d], ta.state[d:]
    assert abs(np.linalg.norm(uT) - 1.0) < 1e-9
    assert np.linalg.norm(gl.project(uT[None], yT, n)) < 1e-8
    # a generic vector does not stay there (the check can fail)
    v = gl.initial_deviations(y[None], 1, 3, n)[0, 0]
    ta.state[:] = np.concatenate([y, v])
    ta.time = 0.0
    ta.propagate_until(40.0)
    assert np.linalg.norm(gl.project(ta.state[d:][None], ta.state[:d], n)) > 1e-3


def test_torus_orbit_resolution_follows_the_drawn_rows():
    """An ambiguous line unresolves an orbit whose count is within the prediction, never an
    excess (simulate/analysis/torus_rows.py, as simulate/analysis/drawn_evidence.classify)."""
    from chaplygin_nd.simulate.analysis.torus_rows import TorusOrbit

    def orbit(count, diffusion, ambiguous):
        return TorusOrbit(0.5, 2.0, 1.0, {"cls": "regular", "dimension": 3}, count, [], diffusion,
                          0.0, "", {"ambiguous": ambiguous, "expected": 3})

    assert orbit(3, 1e-7, 0).resolved
    assert not orbit(3, 1e-7, 2).resolved
    assert orbit(4, 1e-7, 2).resolved                    # an excess stays one
    assert not orbit(3, 1e-3, 0).resolved


def _einsum_group_matrix(y, n, symmetric=True):
    """The earlier columns of ``group_directions``: products with the matrix X (the reference)."""
    N = so.so_dim(n)
    M, g = so.unvec(y[..., :N], n), y[..., N:N + n]
    cols = []
    if symmetric:
        for i in range(n - 1):
            for j in range(i + 1, n - 1):
                X = np.zeros((n, n))
                X[i, j], X[j, i] = 1.0, -1.0
                XM = np.einsum("ij,...jk->...ik", X, M) - np.einsum("...ij,jk->...ik", M, X)
                cols.append(np.concatenate([so.vec(XM), np.einsum("ij,...j->...i", X, g)], -1))
    cols.append(np.concatenate([np.zeros(y.shape[:-1] + (N,)), g], -1))
    return np.stack(cols, -1)


@pytest.mark.parametrize("n", [4, 5, 6, 7, 8])
@pytest.mark.parametrize("symmetric", [True, False])
def test_group_columns_are_the_bits_of_the_products(n, symmetric):
    """The copied columns equal the einsum products bit for bit, zeros of either sign included,
    so the orthonormal directions (one QR of the same matrix) are the same bits too."""
    rng = np.random.default_rng(n)
    y = rng.standard_normal((40, 3, so.so_dim(n) + n))
    y[::3, :, :4] = 0.0
    y[1::3, :, 2:7] = -0.0
    new, old = gl._group_matrix(y, n, symmetric), _einsum_group_matrix(y, n, symmetric)
    assert new.shape == old.shape and new.tobytes() == old.tobytes()
    Q_old, _ = np.linalg.qr(old)
    assert gl.group_directions(y, n, symmetric).tobytes() == Q_old.tobytes()
