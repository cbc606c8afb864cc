"""A Jacobi exclusion carried to generic (a, b) by a certificate over Q(a, b): the fraction-free
solve, the controls (boxes with solutions are never excluded), and the n = 4 certificate with
its prediction at another (a, b)."""

import flint
import pytest
import sympy as sp
from chaplygin_nd.symbolic.search import jacobi_generic as jg
from chaplygin_nd.symbolic.search import poisson as ps

SEED = 20261121


def test_the_fraction_free_solve_is_cramer_over_q_a_b():
    ctx = flint.fmpq_mpoly_ctx.get(jg.AB, "lex")
    a, b = ctx.gens()
    one = ctx.from_dict({(0, 0): 1})
    rows = [[a + 1, 2 * one, b, one], [3 * one, a * b, a - 2, b], [one - b, a, 5 * one, 2 * a]]
    E, solved, mu = jg.ff_gauss_jordan(rows, [0, 1, 2])
    sa, sb = sp.symbols("a b")
    to_sp = lambda p: sp.sympify(jg.poly_text(p), locals={"a": sa, "b": sb})  # noqa: E731
    M = sp.Matrix(3, 4, lambda i, j: to_sp(rows[i][j]))
    x = M[:, :3].LUsolve(M[:, 3])
    assert sp.expand(to_sp(mu) - M[:, :3].det()) == 0 or sp.expand(to_sp(mu) + M[:, :3].det()) == 0
    for i, c in enumerate(solved):
        assert sp.cancel(to_sp(E[i][3]) / to_sp(mu) - x[c]) == 0
        assert all(E[i][j].is_zero() for j in range(3) if j != c)


def test_control_borisov_mamaev_box_is_not_excluded():
    # n = 3, box (2, 1) holds Borisov-Mamaev's Hamiltonisation for every (a, b)
    cert = jg.jacobi_certificate(3, 2, 1, sp.Rational(1, 3), sp.Rational(2, 5), seed=SEED)
    assert not cert.proved and "not in the span" in cert.reason
    assert cert.statement().startswith("only at")


@pytest.mark.slow
def test_control_homogeneous_ball_is_not_excluded():
    # n = 4, a = 0: the box (2, 0) holds a Hamiltonisation (S7:poisson-controls); from that point
    # the procedure must not produce an exclusion
    cert = jg.jacobi_certificate(4, 2, 0, 0, sp.Rational(2, 5), seed=SEED)
    assert not cert.proved and "special" in cert.reason


@pytest.mark.slow
def test_n4_jacobi_box_is_excluded_off_a_curve_that_holds_the_known_structures():
    a0, b0 = sp.Rational(1, 3), sp.Rational(2, 5)
    ok, statement, data = jg.generic_exclusion(4, 2, 1, a0, b0, seed=SEED)
    assert ok and statement.startswith("generic (a, b): off the curve")
    sa, sb = sp.symbols("a b")
    first = data["certificates"][0]
    mu = sp.sympify(first["mu"], locals={"a": sa, "b": sb})
    nu = sp.sympify(first["nu"], locals={"a": sa, "b": sb})
    assert mu.subs({sa: a0, sb: b0}) != 0 and nu.subs({sa: a0, sb: b0}) != 0
    for v in first["text"]["lambda"].values():    # the certificate is text SymPy can parse
        assert sp.sympify(v, locals={"a": sa, "b": sb}).free_symbols <= {sa, sb}
    # control: at a = 0 (Delta constant: the homogeneous ball) and b = 0 (the free body) the box
    # has solutions, so the exceptional curve must hold both lines; in the domain it is just them
    inside = sp.factor_list(sp.sympify(data["in_domain"], locals={"a": sa, "b": sb}))[1]
    assert sorted(str(f) for f, _ in inside) == ["a", "b"]
    assert ps.search_box(4, 2, 1, 0, b0, seed=SEED).outcome == "solutions"
    assert ps.search_box(4, 2, 1, a0, 0, seed=SEED).outcome == "solutions"
    # and off the curve the point search agrees: an exclusion at another (a, b)
    a1, b1 = sp.Rational(-2, 7), sp.Rational(5, 3)
    assert (mu * nu).subs({sa: a1, sb: b1}) != 0
    assert ps.search_box(4, 2, 1, a1, b1, seed=SEED).outcome.startswith("excluded")


@pytest.mark.slow
def test_command_carries_a_jacobi_box_with_its_certificate(capsys, tmp_path):
    import json

    from chaplygin_nd.symbolic.search.poisson_command import main

    out = tmp_path / "box.json"
    assert main(["4", "2", "--from", "2", "--e", "1", "--jacobi-generic", "--seed", str(SEED),
                 "--json", str(out)]) == 0
    line = capsys.readouterr().out.strip().splitlines()
    assert len(line) == 1 and "excluded (Jacobi) for generic (a, b)" in line[0]
    box = json.loads(out.read_text())[0]
    assert all(c["proved"] for c in box["certificate"]["certificates"])
    assert box["generic"].startswith("generic (a, b): off the curve")


def test_a_factor_is_called_zero_free_on_the_domain_only_when_it_is():
    ctx = flint.fmpq_mpoly_ctx.get(jg.AB, "lex")
    a, b = ctx.gens()
    delta = 4 + 2 * a + 2 * b + a * b * (1 - flint.fmpq(2, 7) ** 2)   # Delta(x), |x| < 1
    for f in (a + 2, b + 2, a + b + 2, delta):
        assert jg.no_zero_in_domain(f)
    # a = 0, b = 0, a curve through (1, 27/...) and a = -1 all meet a >= -1, b >= 0
    for f in (a, b, 25 * a * b + 54 * a - 4 * b, a + 1, a - b):
        assert not jg.no_zero_in_domain(f)


def test_the_second_engine_recomputes_the_certificate_identity():
    """_sympy_agrees recomputes sum lambda_k f_k = nu in SymPy's ring from FLINT's terms: a true identity
    agrees, one with nu off by a term does not."""
    import flint

    ctx = flint.fmpq_mpoly_ctx.get(("a", "b", "t0", "sigma"), "lex")
    a, b, t, s = ctx.gens()
    lams, fs = [a + 1, flint.fmpq(1, 3) * b], [t * s - 2, t + a]
    nu = sum((lv * f for lv, f in zip(lams, fs)), ctx.from_dict({}))
    assert jg._sympy_agrees(lams, fs, nu, ctx)
    assert not jg._sympy_agrees(lams, fs, nu + flint.fmpq(1, 7) * s, ctx)
