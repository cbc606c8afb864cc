"""The second exact engine (symbolic/exact/flint_engine.py, symbolic/flint_model.py): FLINT reads SymPy's
expressions by a tree walk, decides the same zero tests as SymPy, disagreements raise, the
FLINT-only mode decides alone, and the FLINT point routes give SymPy's exact values."""

import os
import subprocess
import sys

import pytest
import sympy as sp
from chaplygin_nd.symbolic.algebra import skew_symbols
from chaplygin_nd.symbolic.axisymmetric import mass_tensor
from chaplygin_nd.symbolic.exact import flint_engine, identity, points
from chaplygin_nd.symbolic.exact.flint_engine import EngineDisagreement, FlintRing, use_engine
from chaplygin_nd.symbolic.exact.identity import rational_identity, zero_at_points
from chaplygin_nd.symbolic.flint_model import divergence_at_fmpq
from chaplygin_nd.symbolic.measure import chaplygin_divergence_at
from chaplygin_nd.symbolic.model import angular_velocity

g1, g2, g3, a, b = sp.symbols("g1 g2 g3 a b")
SPHERE = (g1, g2, g3)


def test_tree_walk_gives_the_value_of_the_expression():
    expr = (a * g1 + 1) ** 3 / (2 + b * g2**2) - sp.Rational(3, 7) * g3 / (a - g1) + b**-2
    ring = FlintRing([g1, g2, g3, a, b])
    num, den = ring.fraction(expr)
    point = {g1: sp.Rational(1, 3), g2: sp.Rational(-2, 5), g3: sp.Rational(7, 2),
             a: sp.Rational(5, 4), b: sp.Rational(-3, 2)}
    value = ring.value(num, den, point)
    assert sp.Rational(int(value.p), int(value.q)) == expr.xreplace(point)


def test_non_rational_expressions_are_refused():
    ring = FlintRing([g1])
    for bad in (sp.sqrt(g1), sp.Float(0.5) * g1, sp.sin(g1), sp.pi * g1):
        with pytest.raises(ValueError):
            ring.fraction(bad)


def test_normal_form_modulo_the_sphere_decides_like_sympy():
    true_on_sphere = [(g1**2 + g2**2 + g3**2 - 1) * (a * g1 - b * g3**3),
                      g1**4 - (1 - g2**2 - g3**2) ** 2,
                      (g1**2 - 1 + g2**2 + g3**2) / (1 + a**2)]
    false_on_sphere = [g1**2 + g2**2 + g3**2, g1**3 - g1 * (1 - g2**2), g3**2 - 1 + g1**2]
    for expr in true_on_sphere:
        assert rational_identity(expr, sphere=SPHERE)
    for expr in false_on_sphere:
        chk = rational_identity(expr, sphere=SPHERE, label="nf")
        assert not chk and chk.counterexample is not None
        pt = dict(chk.counterexample.point)
        assert sum(pt[str(s)] ** 2 for s in SPHERE) == 1
        assert expr.xreplace({s: pt[str(s)] for s in expr.free_symbols}) == chk.counterexample.residual


def test_both_engines_are_named_in_the_check():
    chk = rational_identity((g1 + a) ** 2 - g1**2 - 2 * a * g1 - a**2)
    assert chk and chk.engines == "SymPy+FLINT"


def test_flint_alone_decides_and_finds_the_same_counterexample(monkeypatch):
    expr = a * g1**2 + b * g2 - g3 * (1 - g1**2 - g2**2)
    both = rational_identity(expr, sphere=SPHERE, label="alone")
    monkeypatch.setenv(flint_engine.ENGINES_ENV, "flint")
    alone = rational_identity(expr, sphere=SPHERE, label="alone")
    assert not both and not alone and alone.engines == "FLINT"
    assert alone.counterexample.point == both.counterexample.point
    assert alone.counterexample.residual == both.counterexample.residual
    assert rational_identity(g1**2 - (1 - g2**2 - g3**2), sphere=SPHERE).engines == "FLINT"


def test_a_disagreement_is_an_error_not_a_verdict(monkeypatch):
    true = (g1**2 + g2**2 + g3**2 - 1) * a
    real_decide = FlintRing.decide

    def lying(self, num, den):  # a FLINT that says "non-zero" where the identity holds
        return real_decide(self, num, den) + self.vars[0]

    monkeypatch.setattr(FlintRing, "decide", lying)
    with pytest.raises(EngineDisagreement):
        rational_identity(true, sphere=SPHERE)


def test_points_run_the_linear_algebra_in_each_engine_and_compare_values():
    seen = []

    def residual(p):
        seen.append(flint_engine.current_engine())
        A = p["A"]
        x = flint_engine.solve(A, p["y"])
        return A * x - p["y"]

    def sample(rng):
        A = sp.Matrix(4, 4, points.rationals(rng, 16)) + 10 * sp.eye(4)
        return {"A": A, "y": sp.Matrix(points.rationals(rng, 4))}

    chk = zero_at_points(residual, sample, count=3, label="solve")
    assert chk and chk.engines == "SymPy+FLINT" and seen == ["sympy", "flint"] * 3
    seen.clear()
    assert zero_at_points(residual, sample, count=2, label="solve", engines=("flint",))
    assert seen == ["flint", "flint"]


def test_points_whose_values_differ_between_engines_raise():
    def residual(p):  # a FLINT side that computes a different value
        shift = sp.Rational(1, 9) if flint_engine.current_engine() == "flint" else 0
        return flint_engine.det(sp.eye(2)) - 1 + shift

    with pytest.raises(EngineDisagreement):
        zero_at_points(residual, lambda rng: {"n": 3}, count=1, label="differ")


def test_flint_linear_algebra_equals_sympy():
    rng = points.generator(7, "linalg")
    A = sp.Matrix(5, 5, points.rationals(rng, 25))
    A[4, :] = A[0, :] + A[1, :]
    B = sp.Matrix(5, 5, points.rationals(rng, 25)) + 7 * sp.eye(5)
    out = {}
    for engine in ("sympy", "flint"):
        with use_engine(engine):
            out[engine] = (flint_engine.rank(A), flint_engine.det(B), flint_engine.inverse(B),
                           flint_engine.det(A))
    assert out["sympy"] == out["flint"]
    assert out["flint"][0] == 4 and out["flint"][3] == 0 and out["flint"][1] == B.det()


@pytest.mark.parametrize("n", [3, 4, 6])
def test_flint_model_routes_give_sympy_values(n):
    rng = points.generator(11, "model", n)
    J = sp.diag(*[points.rational(rng, 1, 3, 4) for _ in range(n)])
    bb = points.rational(rng, 0, 3, 4, open_lo=True)
    gamma, M = points.sphere_point(rng, n), points.skew_matrix(rng, n)
    with use_engine("flint"):
        flint_general = angular_velocity(M, gamma, J, bb)
        flint_values = chaplygin_divergence_at(M, gamma, J, bb)
    assert flint_general == angular_velocity(M, gamma, J, bb)
    sympy_values = chaplygin_divergence_at(M, gamma, J, bb)
    assert flint_values == divergence_at_fmpq(M, gamma, J, bb)
    for key in ("div", "gamma_dot", "Omega", "dlogdet"):
        assert flint_values[key] == sympy_values[key], key
    with use_engine("flint"):
        flint_omega = angular_velocity(M, gamma, mass_tensor(n, sp.Rational(1, 2)), bb)
    assert flint_omega == angular_velocity(M, gamma, mass_tensor(n, sp.Rational(1, 2)), bb)


def test_generic_symbolic_identity_both_engines():
    M = skew_symbols("m", 4)
    assert rational_identity(list(M + M.T)).engines == "SymPy+FLINT"


def test_engine_note_names_the_engines():
    note = identity.engine_note({("identity", "SymPy+FLINT"): 3, ("points", "FLINT"): 2})
    assert "identities SymPy+FLINT x3" in note and "points FLINT x2" in note


def test_sympy_ground_types_are_gmpy_so_the_engines_share_no_code():
    env = {k: v for k, v in os.environ.items() if k != "SYMPY_GROUND_TYPES"}
    code = ("import chaplygin_nd, sympy; from sympy.external.gmpy import GROUND_TYPES; "
            "from chaplygin_nd.symbolic.exact.flint_engine import engine_label; "
            "print(GROUND_TYPES, engine_label(('sympy', 'flint')))")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                         check=True).stdout.split()
    assert out == ["gmpy", "SymPy+FLINT"]
