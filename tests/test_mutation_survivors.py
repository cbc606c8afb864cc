"""Properties of derivations that the rows only use through zero tests (every mutant
of ``make mutate-derivations`` that no check killed gets a test or an equivalence argument).

Each test asserts a correct property of the function on inputs where it is not zero, so that a
mutant that agrees with it only at zero (e.g. the normal form negated) is told apart.
"""

from __future__ import annotations

from chaplygin_nd.symbolic import fourd


def test_sphere_normal_form_reduces_x_squared_to_one_minus_q_squared():
    """On S^3, x^2 = 1 - |q|^2: the normal form of x^3 a is x a (1 - |q|^2), of degree < 2 in x, and
    a polynomial of degree < 2 in x is its own normal form."""
    x, q, a = fourd.RV["x"], fourd.RV["q"], fourd.RV["a"]
    qq = fourd.dot(q, q)
    assert fourd.sphere_normal_form(x**3 * a) == x * a * (1 - qq)
    assert fourd.sphere_normal_form(x * qq + a) == x * qq + a
    assert fourd.sphere_normal_form(x**2 + qq) == 1


# The runtime evaluates batches ``(..., n, n)`` of any batch shape. The tests of the runtime used
# flat batches (or none), where ``M.shape[1]`` happens to be n: a mutant reading the size there
# instead of ``M.shape[-1]`` was bit-for-bit the original at every call they made.

def _batch(n, shape=(2, 3), seed=7):
    import numpy as np

    rng = np.random.default_rng(seed)
    A = rng.standard_normal(shape + (n, n))
    M = A - np.swapaxes(A, -1, -2)
    gamma = rng.standard_normal(shape + (n,))
    gamma /= np.linalg.norm(gamma, axis=-1, keepdims=True)
    return M, gamma


def _each(f, *batched):
    """f applied sample by sample over the batch shape (2, 3)."""
    import numpy as np

    return np.array([[f(*(x[i, j] for x in batched)) for j in range(3)] for i in range(2)])


def test_runtime_functions_broadcast_over_a_two_dimensional_batch():
    import numpy as np
    from chaplygin_nd.runtime import axisym

    a, b = 0.3, 0.7
    for n in (4, 5):
        M, gamma = _batch(n)
        for method in ("auto", "matrix"):
            Omega = axisym.angular_velocity(M, gamma, a, b, method)
            assert Omega.shape == M.shape
            assert np.allclose(Omega, _each(lambda m, g, k=method: axisym.angular_velocity(
                m, g, a, b, k), M, gamma), rtol=1e-12, atol=1e-12)
            Mdot, gdot = axisym.vector_field(M, gamma, a, b, method)
            one = [[axisym.vector_field(M[i, j], gamma[i, j], a, b, method) for j in range(3)]
                   for i in range(2)]
            assert np.allclose(Mdot, np.array([[o[0] for o in r] for r in one]), atol=1e-12)
            assert np.allclose(gdot, np.array([[o[1] for o in r] for r in one]), atol=1e-12)
        assert np.allclose(axisym.L_gamma(M, gamma, a, b),
                           _each(lambda m, g: axisym.L_gamma(m, g, a, b), M, gamma), atol=1e-12)
        assert np.allclose(axisym.chi(M, a, b), _each(lambda m: axisym.chi(m, a, b), M),
                           atol=1e-12)
        assert np.allclose(axisym.p_coefficients(M, gamma),
                           _each(axisym.p_coefficients, M, gamma), atol=1e-10)


def test_expm_skew_of_the_one_by_one_zero_matrix_is_one():
    """so(1) = {0} and e^0 = 1 (the n = 1 case that vertical_solution reaches for n = 2)."""
    import numpy as np
    from chaplygin_nd.runtime import axisym

    assert np.array_equal(axisym.expm_skew(np.zeros((1, 1))), np.ones((1, 1)))
    assert np.array_equal(axisym.expm_skew(np.zeros((4, 1, 1))), np.ones((4, 1, 1)))


def test_vector_field_broadcasts_one_matrix_against_a_batch_of_gamma():
    import numpy as np
    from chaplygin_nd.runtime import axisym

    M, gamma = _batch(5)
    Mdot, gdot = axisym.vector_field(M[0, 0], gamma, 0.3, 0.7)
    assert Mdot.shape == (2, 3, 5, 5) and gdot.shape == (2, 3, 5)
    for i in range(2):
        for j in range(3):
            want = axisym.vector_field(M[0, 0], gamma[i, j], 0.3, 0.7)
            assert np.allclose(Mdot[i, j], want[0], atol=1e-12)
            assert np.allclose(gdot[i, j], want[1], atol=1e-12)


def test_compiled_angular_velocity_broadcasts_every_leading_axis():
    """runtime.compiled.angular_velocity: a (2, 3) batch of (M, gamma), and one (M, gamma) against
    a (2, 3) batch of a, equal the NumPy runtime to 16 ulps of max |Omega| (as tests/test_heyoka)."""
    import numpy as np
    import pytest

    pytest.importorskip("heyoka")
    from chaplygin_nd.runtime import axisym, compiled

    eps = np.finfo(float).eps
    M, gamma = _batch(4)
    want = axisym.angular_velocity(M, gamma, 0.3, 0.7, "matrix")
    got = compiled.angular_velocity(M, gamma, 0.3, 0.7)
    assert got.shape == want.shape
    assert np.max(np.abs(got - want)) <= 16 * eps * np.max(np.abs(want))
    a = np.linspace(-0.9, 0.9, 6).reshape(2, 3)
    got = compiled.angular_velocity(M[0, 0], gamma[0, 0], a, 0.7)
    want = axisym.angular_velocity(M[0, 0], gamma[0, 0], a, 0.7, "matrix")
    assert got.shape == want.shape == (2, 3, 4, 4)
    assert np.max(np.abs(got - want)) <= 16 * eps * np.max(np.abs(want))


def test_the_compiled_angular_velocity_records_the_hash_of_its_expressions(tmp_path, monkeypatch):
    """runtime.jit_cache stores beside a compiled object the SHA-256 of its expressions' text
    ("source", for the record): for the angular-velocity cfunc, the text of its outputs."""
    import hashlib
    import pickle

    import pytest

    pytest.importorskip("heyoka")
    from chaplygin_nd.runtime import compiled, jit_cache

    monkeypatch.setenv("CHAPLYGIN_ND_CACHE", str(tmp_path))
    jit_cache.forget_memory()
    try:
        cf, _, how = compiled.angular_velocity_function(3)
        assert how == "cold compile"
        (entry_path,) = jit_cache.cache_dir().glob("*.pkl")
        with entry_path.open("rb") as fh:
            entry = pickle.load(fh)
        assert entry["source"] == hashlib.sha256("\n".join(map(str, cf.fn)).encode()).hexdigest()
    finally:
        jit_cache.forget_memory()


def test_expression_vector_field_with_attitude_appends_g_omega_and_the_centre_velocity():
    """runtime.expressions.vector_field with the attitude g (the full system): after the reduced
    field come vec(g Omega) row-major and r g Omega gamma (Omega = L_gamma^{-1} M), here built
    with float arithmetic and compared with the NumPy runtime."""
    import math

    import numpy as np
    from chaplygin_nd.runtime import axisym, expressions

    class FloatOps:
        sqrt = staticmethod(math.sqrt)

        @staticmethod
        def rational(p, q):
            return p / q

    n, a, b, r = 4, 0.3, 0.7, 1.5
    M, gamma = _batch(n, shape=(1,))
    M, gamma = M[0], gamma[0]
    g = np.linalg.qr(np.random.default_rng(3).standard_normal((n, n)))[0]
    out = expressions.vector_field(list(axisym.vec(M)), list(gamma), a, b, FloatOps,
                                   g=[list(row) for row in g], radius=r)
    Omega = axisym.angular_velocity(M, gamma, a, b, "matrix")
    d = n * (n - 1) // 2
    assert len(out) == d + n + n * n + n
    assert np.allclose(out[d + n:d + n + n * n], (g @ Omega).ravel(), atol=1e-12)
    assert np.allclose(out[d + n + n * n:], r * g @ Omega @ gamma, atol=1e-12)


def test_parse_model_builds_the_model_the_user_gave():
    """chaplygin first-integrals: a and b (or J and b) reach the model in their places (eq:axisymm:
    J = Id + a E_n E_n^T; eq:Inertia: J = diag(J)); the search's tests only used a = b."""
    import sympy as sp
    from chaplygin_nd.symbolic.search import command

    m = command.parse_model(4, "1/2", "3", None)
    assert (m.n, m.J, m.b) == (4, (1, 1, 1, sp.Rational(3, 2)), 3)
    g = command.parse_model(3, None, "2", "1,2,3")
    assert (g.n, g.J, g.b, g.kind) == (3, (1, 2, 3), 2, "general")
