"""The identity engine proves true identities and refutes false ones with exact counterexamples."""

import random

import pytest
import sympy as sp
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.exact.identity import exact_zero, rational_identity, zero_at_points

g = sp.symbols("g1:4", real=True)
a, b, x = sp.symbols("a b x")


def test_true_identity_modulo_sphere():
    assert rational_identity((g[0] ** 2 + g[1] ** 2) * a - a * (1 - g[2] ** 2), sphere=g)


def test_rational_function_identity_clears_denominators():
    lhs = 1 / (a + 1) + 1 / (a - 1)
    assert rational_identity(lhs - 2 * a / (a**2 - 1))


def test_false_identity_gives_exact_counterexample_on_sphere():
    check = rational_identity(g[0] ** 2 + g[1] ** 2 - 1, sphere=g)
    assert not check
    point = dict(check.counterexample.point)
    values = [point[str(s)] for s in g]
    assert all(isinstance(v, sp.Rational) for v in values)
    assert sum(v**2 for v in values) == 1                        # on the sphere, exactly
    value = (g[0] ** 2 + g[1] ** 2 - 1).subs(dict(zip(g, values)))
    assert value == check.counterexample.residual != 0           # the recorded value is true


def test_counterexample_respects_parameter_domain():
    sampler = {b: lambda r: points.rational(r, 0, 4, 6, open_lo=True),
               a: lambda r: points.rational(r, -1, 1, 6)}
    check = rational_identity(sp.Matrix([0, a * b + b]), samplers=sampler)
    assert not check
    point = dict(check.counterexample.point)
    assert 0 < point["b"] <= 4 and -1 <= point["a"] <= 1
    assert check.counterexample.where == "entry (2, 1)"


def test_identity_that_needs_the_sphere_is_refuted_without_it():
    expr = g[0] ** 2 + g[1] ** 2 + g[2] ** 2 - 1
    assert rational_identity(expr, sphere=g)
    assert not rational_identity(expr)


def test_non_rational_input_is_an_error_not_a_verdict():
    with pytest.raises(ValueError):
        rational_identity(sp.sqrt(a) - 1)


def test_zero_at_points_finds_a_nonzero_point_and_rejects_floats():
    check = zero_at_points(lambda p: p["x"] ** 2 - p["x"], lambda r: {"x": points.rational(r, 2, 5)},
                           count=3, label="t")
    assert not check and check.counterexample.residual != 0
    with pytest.raises(TypeError):
        exact_zero(sp.Float(0.5) - sp.Rational(1, 2) + sp.Float(1e-30))


def test_points_are_exact_and_reproducible():
    r1, r2 = points.generator(7, "x"), points.generator(7, "x")
    p1, p2 = points.sphere_point(r1, 5), points.sphere_point(r2, 5)
    assert p1 == p2 and (p1.T * p1)[0] == 1
    R = points.rational_rotation(points.generator(3), 4)
    assert R.T * R == sp.eye(4) and R.det() == 1
    assert points.generator(1, "a").random() != points.generator(1, "b").random()


def test_rational_respects_open_ends():
    rng = random.Random(0)
    values = {points.rational(rng, 0, 1, 2, open_lo=True, open_hi=True) for _ in range(50)}
    assert values == {sp.Rational(1, 2)}


def test_sparse_polynomials_are_decided_in_their_own_ring():
    from sympy.polys.rings import ring

    R, X, Y, Z, A = ring("x y z a", sp.QQ)
    x_, y_, z_, a_ = sp.symbols("x y z a")
    assert rational_identity([(X**2 + Y**2 + Z**2 - 1) * A], sphere=(x_, y_, z_))
    check = rational_identity([X**2 + Y**2 - 1], sphere=(x_, y_, z_),
                              samplers={a_: lambda r: sp.Rational(1, 2)})
    assert not check
    point = dict(check.counterexample.point)
    assert point["x"] ** 2 + point["y"] ** 2 + point["z"] ** 2 == 1
    assert check.counterexample.residual == point["x"] ** 2 + point["y"] ** 2 - 1 != 0
