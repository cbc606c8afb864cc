r"""The runtime on batches: every batch entry against its own 50-digit mpmath reference.

``runtime.axisym.vertical_solution`` is promised for batches (``(..., n, n)``, ``t`` and ``a``
broadcast) but was tested on one matrix only, so a transpose that is right for one matrix and
wrong for a stack (``R.T`` for ``swapaxes(R, -1, -2)``) survived. Here a batch of ``n`` points
(so that such a transpose still has a valid shape and gives a wrong value, not an error) and a
2-D batch are compared entry by entry with $e^{\zeta t}$ from ``mpmath.expm`` at 50 digits.

``runtime.compiled.angular_velocity`` broadcasts every leading axis; the path where $\gamma$
alone carries the batch (one $M$, scalar $a, b$) is compared with an mpmath LU solve of the
matrix of $L_\gamma$ assembled from eq:M-O, point by point.
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
from chaplygin_nd.runtime import axisym

EPS = np.finfo(float).eps


def _vertical_batch(rng, n: int, shape: tuple[int, ...]):
    """A batch of points of V (M0 gamma0 = 0, |gamma0| = 1), float, of batch ``shape``."""
    gamma = rng.standard_normal(shape + (n,))
    gamma /= np.linalg.norm(gamma, axis=-1, keepdims=True)
    A = rng.standard_normal(shape + (n, n))
    P = np.eye(n) - gamma[..., :, None] * gamma[..., None, :]
    M0 = P @ (A - np.swapaxes(A, -1, -2)) @ P
    return M0, gamma


def _expm_reference(M0, gamma, t, a, b):
    """(M(t), gamma(t)) for one point: zeta of the runtime at that single point (the batch path is
    what is under test), exponentiated by mpmath.expm at 50 digits."""
    n = M0.shape[-1]
    Z = mpmath.matrix(axisym.zeta(M0, gamma, a, b).tolist()) * mpmath.mpf(float(t))
    R = mpmath.expm(Z)
    return R * mpmath.matrix(M0.tolist()) * R.T, R * mpmath.matrix(gamma.tolist()), n


def _max_error(Mt, gt, ref) -> float:
    Mt_ref, gt_ref, n = ref
    return max(max(float(abs(mpmath.mpf(float(Mt[i, j])) - Mt_ref[i, j]))
                   for i in range(n) for j in range(n)),
               max(float(abs(mpmath.mpf(float(gt[i])) - gt_ref[i])) for i in range(n)))


@pytest.mark.parametrize("n", [3, 4, 5])
@pytest.mark.parametrize("shape", [None, (2, 3)], ids=["n points", "2x3 batch"])
def test_vertical_solution_on_a_batch_against_mpmath(n, shape):
    """Th:Re closed form on a batch, with t and a varying along the batch: each entry within
    8 n eps (|M0| + 1) of mpmath.expm(zeta t) applied to its M0, gamma0."""
    mpmath.mp.dps = 50
    shape = shape or (n,)
    rng = np.random.default_rng([n, len(shape), 1717])
    M0, gamma = _vertical_batch(rng, n, shape)
    t = rng.uniform(0.5, 3.0, shape)
    a = rng.uniform(-1.0, 1.0, shape)
    b = 1.3
    Mt, gt = axisym.vertical_solution(M0, gamma, t, a, b)
    assert Mt.shape == shape + (n, n) and gt.shape == shape + (n,)
    for idx in np.ndindex(*shape):
        ref = _expm_reference(M0[idx], gamma[idx], t[idx], a[idx], b)
        scale = 1 + float(np.linalg.norm(M0[idx]))
        err = _max_error(Mt[idx], gt[idx], ref)
        assert err <= 8 * n * EPS * scale, (idx, err / (EPS * scale))


def _mp_L(gamma, a, b):
    """The matrix of L_gamma (eq:M-O, J = Id + a E_n E_n^T) at 50 digits in the basis E_p ^ E_r
    (p < r), assembled from the definition; and the pairs (p, r)."""
    n = len(gamma)
    pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]
    J = [1] * (n - 1) + [1 + mpmath.mpf(float(a))]
    g = [mpmath.mpf(float(c)) for c in gamma]
    cols = []
    for p, r in pairs:
        Og = [0] * n
        Og[p], Og[r] = g[r], -g[p]   # (E_p ^ E_r) gamma
        cols.append([(J[i] + J[j]) * (1 if (i, j) == (p, r) else 0)
                     + mpmath.mpf(float(b)) * (Og[i] * g[j] - g[i] * Og[j]) for i, j in pairs])
    return mpmath.matrix([[cols[c][k] for c in range(len(pairs))] for k in range(len(pairs))]), pairs


def _mp_angular_velocity(M, gamma, a, b):
    """Omega = L_gamma^{-1} M by an mpmath LU solve (upper entries of Omega)."""
    L, pairs = _mp_L(gamma, a, b)
    return list(mpmath.lu_solve(L, mpmath.matrix([mpmath.mpf(float(M[i, j])) for i, j in pairs])))


@pytest.mark.parametrize("n", [3, 4, 5])
def test_L_gamma_on_a_batch_against_mpmath(n):
    """runtime.axisym.L_gamma (the forward map Omega -> M of eq:M-O) on a batch with a, b varying
    along it: each entry equals the matrix of L_gamma from the definition applied at 50 digits,
    within 8 eps (1 + |a| + |b|) |Omega|."""
    mpmath.mp.dps = 50
    rng = np.random.default_rng([n, 7])
    A = rng.standard_normal((4, n, n))
    Omega = A - np.swapaxes(A, -1, -2)
    gamma = rng.standard_normal((4, n))
    gamma /= np.linalg.norm(gamma, axis=-1, keepdims=True)
    a, b = rng.uniform(-1, 1, 4), rng.uniform(0.1, 3, 4)
    M = axisym.L_gamma(Omega, gamma, a, b)
    i, j = np.triu_indices(n, 1)
    for k in range(4):
        L, pairs = _mp_L(gamma[k], a[k], b[k])
        ref = L * mpmath.matrix([mpmath.mpf(float(Omega[k][p, r])) for p, r in pairs])
        err = max(float(abs(mpmath.mpf(float(v)) - r)) for v, r in zip(M[k][i, j], ref))
        scale = (1 + abs(a[k]) + b[k]) * float(np.linalg.norm(Omega[k]))
        assert err <= 8 * EPS * scale, (k, err / (EPS * scale))
        assert np.array_equal(M[k], -M[k].T)


@pytest.mark.parametrize("n", [3, 4, 5])
def test_chi_on_a_batch_against_the_derived_expression(n):
    """runtime.axisym.chi (eq:solManakov) on a batch with a varying along it: each entry equals the
    derived chi of symbolic.vertical evaluated exactly at the float inputs (as rationals), within
    8 eps (1 + |chi|)."""
    import sympy as sp
    from chaplygin_nd.symbolic.vertical import chi as chi_exact

    rng = np.random.default_rng([n, 8])
    A = rng.standard_normal((3, n, n))
    Omega0 = A - np.swapaxes(A, -1, -2)
    a, b = rng.uniform(-1, 1, 3), 1.25
    got = axisym.chi(Omega0, a, b)
    assert got.shape == (3, n, n)
    for k in range(3):
        W = sp.Matrix(n, n, [sp.Rational(float(v)) for v in Omega0[k].ravel()])
        ref = np.array(chi_exact(W, sp.Rational(float(a[k])), sp.Rational(b)).evalf(30).tolist(),
                       dtype=float)
        assert np.max(np.abs(got[k] - ref)) <= 8 * EPS * (1 + np.max(np.abs(ref))), k


@pytest.mark.parametrize("n", [3, 4, 6])
def test_compiled_with_gamma_alone_batched(n):
    """runtime.compiled.angular_velocity with one M (n, n), gamma (count, n), scalar a, b (the
    broadcast path): each row equals the mpmath solve for that gamma within 16 eps |L^-1| |M|."""
    pytest.importorskip("heyoka")
    from chaplygin_nd.runtime import compiled

    mpmath.mp.dps = 50
    rng = np.random.default_rng([n, 99])
    A = rng.standard_normal((n, n))
    M = A - A.T
    gamma = rng.standard_normal((7, n))
    gamma /= np.linalg.norm(gamma, axis=-1, keepdims=True)
    a, b = 0.4, 1.6
    Omega = compiled.angular_velocity(M, gamma, a, b)
    assert Omega.shape == (7, n, n)
    i, j = np.triu_indices(n, 1)
    for k in range(7):
        ref = _mp_angular_velocity(M, gamma[k], a, b)
        err = max(float(abs(mpmath.mpf(float(v)) - r)) for v, r in zip(Omega[k][i, j], ref))
        scale = float(np.linalg.norm(M)) * 4  # |L^-1| <= 1/min(2, 2+a) at these a, b
        assert err <= 16 * EPS * scale, (k, err / (EPS * scale))
        assert np.array_equal(Omega[k], -Omega[k].T)


@pytest.mark.parametrize("n", [3, 4, 6])
def test_vec_and_unvec_are_inverse_on_skew_matrices(n):
    """unvec returns skew matrices (both triangles: a mutant writing +c below the diagonal had
    passed every runtime test, which read results through vec), and vec/unvec invert each other."""
    rng = np.random.default_rng(n)
    c = rng.standard_normal((5, 2, n * (n - 1) // 2))
    A = axisym.unvec(c, n)
    assert A.shape == (5, 2, n, n)
    assert np.array_equal(A, -np.swapaxes(A, -1, -2))
    assert np.array_equal(axisym.vec(A), c)
    assert np.array_equal(axisym.unvec(axisym.vec(A), n), A)
    M = axisym.unvec(c[0, 0], n)
    gamma = rng.standard_normal(n)
    gamma /= np.linalg.norm(gamma)
    Omega = axisym.angular_velocity(M, gamma, 0.3, 1.2)
    assert np.array_equal(Omega, -Omega.T)  # the result is a skew matrix, not only its upper half


@pytest.mark.parametrize("n", [3, 5])
def test_expression_builder_angular_velocity_is_the_whole_skew_matrix(n):
    """runtime.expressions.angular_velocity (the builder the compiled cfunc is made from), called
    with float arithmetic, returns the whole skew Omega = L^{-1} M (zero diagonal, lower triangle
    the negated upper): the cfunc reads only i < j, so a mutant filling the diagonal with 1, or
    writing the lower triangle into M, had passed every test. Compared with the NumPy runtime."""
    from chaplygin_nd.runtime import expressions as rx

    rng = np.random.default_rng([n, 5])
    A = rng.standard_normal((n, n))
    M = A - A.T
    gamma = rng.standard_normal(n)
    gamma /= np.linalg.norm(gamma)
    M_list = [list(map(float, row)) for row in M]
    Omega = np.array(rx.angular_velocity(M_list, list(map(float, gamma)), 0.4, 1.6,
                                         axisym._NumpyOps), dtype=float)
    assert np.array_equal(np.array(M_list), M)  # the input is not written to
    assert np.array_equal(Omega, -Omega.T)
    want = axisym.angular_velocity(M, gamma, 0.4, 1.6, method="matrix")
    assert np.max(np.abs(Omega - want)) <= 64 * EPS * np.max(np.abs(want))
