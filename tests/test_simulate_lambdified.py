"""An independent NumPy route to the kernels :mod:`simulate` uses, built at import by ``lambdify``
from the *definitions* in :mod:`symbolic.model` (eq:M-O with eq:Inertia and eq:axisymm): the matrix
of $L_\\gamma$ is lambdified and inverted by ``numpy.linalg.solve``. Tests use it (a) to check the
generated kernels that :mod:`simulate` binds to and (b) as a second route in cross-checks."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from chaplygin_nd.simulate.dynamics import so
from chaplygin_nd.simulate.kernels import Kernels, active
from chaplygin_nd.symbolic.algebra import vector_symbols
from chaplygin_nd.symbolic.model import L_matrix

_a, _b = sp.symbols("a b", real=True)
_L = {}


def _L_fn(n):
    if n not in _L:
        gamma = vector_symbols("g", n)
        J = sp.diag(*([1] * (n - 1) + [1 + _a]))
        _L[n] = sp.lambdify((list(gamma), _a, _b), L_matrix(gamma, J, _b), "numpy", cse=True)
    return _L[n]


def _L_batch(gamma, a, b):
    gamma = np.asarray(gamma, dtype=float)
    n = gamma.shape[-1]
    flat = gamma.reshape(-1, n)
    mats = np.array([np.array(_L_fn(n)(list(g), a, b), dtype=float) for g in flat])
    return mats.reshape(gamma.shape[:-1] + mats.shape[-2:])


def L_gamma(Omega, gamma, a, b):
    """eq:M-O-axi-symm through the lambdified matrix of $L_\\gamma$."""
    n = gamma.shape[-1]
    return so.unvec(np.einsum("...ij,...j->...i", _L_batch(gamma, a, b), so.vec(Omega)), n)


def angular_velocity(M, gamma, a, b):
    """$L_\\gamma^{-1}(M)$ by a batched linear solve of the lambdified matrix."""
    n = gamma.shape[-1]
    L = _L_batch(gamma, a, b)
    return so.unvec(np.linalg.solve(L, so.vec(M)[..., None])[..., 0], n)


def lambdified_kernels() -> Kernels:
    """The independent kernel set (no zeta, no reduced field: those must come from generated/)."""
    return Kernels(name="lambdified symbolic.model", L_gamma=L_gamma,
                   angular_velocity=angular_velocity, note="test route")


@pytest.mark.parametrize("n", [3, 4, 5, 6])
def test_generated_inverse_matches_definition(n):
    """The generated $L_\\gamma^{-1}$ (P:inversion) inverts the definition eq:M-O-axi-symm."""
    rng = np.random.default_rng([6, n])
    g = rng.standard_normal((20, n))
    gamma = g / np.linalg.norm(g, axis=-1, keepdims=True)
    M = so.unvec(rng.standard_normal((20, so.so_dim(n))), n)
    for a, b in [(0.5, 1.0), (-1.0, 0.1), (1.0, 5.0), (0.0, 2.0)]:
        Omega = active().require("angular_velocity")(M, gamma, a, b)
        assert np.allclose(L_gamma(Omega, gamma, a, b), M, rtol=0, atol=1e-13)
        assert np.allclose(active().require("L_gamma")(Omega, gamma, a, b), M, rtol=0, atol=1e-13)


def test_one_point_fast_path_equals_the_public_kernels():
    """simulate's one-point path (generated blocks on floats) returns what the public, batched
    generated kernels return, for L_gamma^{-1}, L_gamma, zeta and the reduced field/integrals:
    the same expressions, so at most rounding-level differences (Python floats vs NumPy)."""

    def same(x, y):
        return np.allclose(x, y, rtol=1e-15, atol=1e-15)

    import chaplygin_nd.generated.axisym as g
    import chaplygin_nd.generated.reduced as red
    from chaplygin_nd.simulate.dynamics import families
    from chaplygin_nd.simulate.dynamics.so import reduced_invariants

    k = active()
    for n in (3, 4):
        M, gamma = families.draw("vertical", n, 0.4, 1.3, seed=n)
        one = k.angular_velocity(M, gamma, 0.4, 1.3)
        public = getattr(g, f"angular_velocity_axisym_{n}d")(so.vec(M), gamma, 0.4, 1.3)
        assert same(so.vec(one), public)
        z = getattr(g, f"zeta_{n}d")(so.vec(M), gamma, 0.4, 1.3)
        assert same(so.vec(k.zeta(M, gamma, 0.4, 1.3)), z)
        assert np.allclose(k.L_gamma(one, gamma, 0.4, 1.3), M, rtol=0, atol=1e-14)
    M, gamma = families.draw("generic", 4, -0.4, 0.7, seed=21)
    r = reduced_invariants(M, gamma)
    assert same(k.reduced_field(r, -0.4, 0.7), red.reduced_field(r, -0.4, 0.7))
    assert same(k.reduced_integrals(r, -0.4, 0.7), red.reduced_integrals(r, -0.4, 0.7))
