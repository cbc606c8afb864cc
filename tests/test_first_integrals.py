"""The exact first-integral search (row S6:first-integrals): controls, the exactness bounds on a
planted case, the field modulo p, reconstruction over QQ, the new n = 5 integral, bad input."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from chaplygin_nd.symbolic.search import (
    candidate_basis,
    found_integral,
    known_integrals,
    reconstruction,
    sampled_field,
)
from chaplygin_nd.symbolic.search import integral_search as fi
from chaplygin_nd.symbolic.search.command import main
from cli_helpers import exit_code, one_error_line

A, B = sp.Rational(-1, 3), sp.Rational(3, 2)


def test_axisymmetric_field_equals_the_solve_of_the_definition():
    """The derived inverse (P:inversion) and the mod-p solve of eq:M-O give the same field."""
    p = sampled_field.PRIMES[0]
    m1 = sampled_field.axisymmetric(5, A, B)
    s = sampled_field.sample(m1, 40, p, np.random.default_rng(3))
    f2 = sampled_field.field_at(sampled_field.general(m1.J, m1.b), s["z"], p)
    assert f2["ok"].all() and (s["zdot"] == f2["zdot"]).all()


@pytest.mark.parametrize("n, box, found", [
    (3, (1, 2, 0), 1),           # <M, gamma> (generic J)
    (3, (2, 4, 1), 3),           # |M|^2, <M, gamma>^2, H
    (4, (2, 4, 1), 4),           # F1, F2, F3, H (eq:motion-n4)
    (5, (2, 4, 1), 4),           # two coefficients of p, <v, gamma>, H
    (5, (3, 5, 1), 0),
])
def test_controls_recover_the_known_integrals_and_nothing_more(n, box, found):
    model = (sampled_field.general((1, sp.Rational(3, 2), sp.Rational(7, 3)), sp.Rational(1, 2))
             if n == 3 else sampled_field.axisymmetric(n, A, B))
    r = fi.search_degree(model, *box)
    assert (r.found, r.known, r.settled) == (found, found, True)
    assert r.recovered is not False


def test_exactness_bounds_on_the_planted_n5_integral():
    """Without F among the known integrals the search shows exactly one more (the upper bound
    exceeds the lower bound by one); with F the bounds meet."""
    model = sampled_field.axisymmetric(5, A, B)
    with_f = fi.search_degree(model, 4, 4, 1)
    paper = sum(fi.known_ranks(model, 4, 4, 1, False).values())
    assert with_f.settled and with_f.found == with_f.known == paper + 1
    for blk in with_f.blocks:
        assert blk.nullity >= blk.known_rank      # the exact inequality, block by block


def test_reconstruction_over_qq_gives_proved_integrals():
    """n = 4, M-degree 2, Delta^1: the kernel of the trivial block over QQ, each vector proved."""
    model = sampled_field.axisymmetric(4, A, B)
    rows, B_, blk, cols = reconstruction.reconstruct(model, 2, 4, 1, 0, primes=3)
    assert len(rows) == 3                           # F2, F3, H (F1 = Pf M is odd)
    for r in rows:
        expr = reconstruction.to_expression(B_, blk, cols, r)
        assert reconstruction.prove_integral(expr, model, 1).ok


def test_new_integral_exact():
    assert found_integral.prove_symbolic(3).ok
    assert found_integral.prove_at_points(5, 1).ok
    text = found_integral.new_integral_text(5)
    assert sp.sympify(text).free_symbols >= {sp.Symbol("a"), sp.Symbol("b"), sp.Symbol("M_12")}


def test_new_integral_text_is_the_derived_integral():
    # the text writes the square unexpanded; parsed, it is new_integral's num / Delta exactly
    from chaplygin_nd.symbolic.algebra import unvec

    for n in (3, 5):
        Ms, gs = reconstruction.real_symbols(n)
        a, b = sp.symbols("a b")
        num, den = found_integral.new_integral(unvec(Ms, n), sp.Matrix(gs), a, b)
        text = sp.sympify(found_integral.new_integral_text(n))
        assert sp.expand(sp.numer(text) - num) == 0 and sp.expand(sp.denom(text) - den) == 0


def test_new_integral_6_text_is_the_derived_integral_at_a_rational_point():
    # G's text against new_integral_6 at an exact point where a, b and every coordinate differ (so
    # no exchange of two names goes unseen). The text is evaluated as Python over exact Rationals
    # (sympify takes ~45 s on its 85 kB); that is exact because no integer/integer literal occurs
    import re

    from chaplygin_nd.symbolic.algebra import unvec

    Ms, gs = reconstruction.real_symbols(6)
    a, b = sp.symbols("a b")
    values = {s: sp.Rational(k + 2, 7 + 3 * k) for k, s in enumerate([*Ms, *gs, a, b])}
    num, den = found_integral.new_integral_6(unvec(Ms, 6).xreplace(values),
                                     sp.Matrix(gs).xreplace(values), values[a], values[b])
    text = found_integral.new_integral_6_text()
    assert not re.search(r"(?<![\w.)])\d+\s*/\s*\d+", text)
    assert set(re.findall(r"[A-Za-z_]\w*", text)) <= {str(s) for s in values}
    value = eval(compile(text, "<G>", "eval"), {"__builtins__": {}},  # noqa: S307 - our own text
                 {str(s): v for s, v in values.items()})
    assert den != 0 and isinstance(value, sp.Rational) and value == num / den


def test_real_symbols_follow_the_naming_of_the_published_text():
    # the names verification.json's integrals are written in (1-based, i < j): a reader parses them
    Ms, gs = reconstruction.real_symbols(4)
    assert [str(s) for s in Ms] == ["M_12", "M_13", "M_14", "M_23", "M_24", "M_34"]
    assert [str(s) for s in gs] == ["gamma_1", "gamma_2", "gamma_3", "gamma_4"]


def test_new_integral_is_independent_for_n5_only():
    m5 = sampled_field.axisymmetric(5, A, B)
    assert known_integrals.jacobian_rank(m5, 1, include_new=True)["rank"] == 6
    m3 = sampled_field.axisymmetric(3, A, B)
    assert known_integrals.jacobian_rank(m3, 1, include_new=True)["rank"] == 3


@pytest.mark.parametrize("argv, needle", [
    (["2", "2", "--a", "0", "--b", "1"], "n >= 3"),
    (["4", "2", "--a", "-2", "--b", "1"], "a >= -1"),
    (["4", "2", "--a", "-3/2", "--b", "1"], "a = -3/2 is outside"),  # a value, not an option
    (["4", "2", "--a", "0", "--b", "-1/2"], "b = -1/2 is outside"),
    (["4", "2", "--a", "0", "--b", "-1e-3"], "is outside the domain b > 0"),
    (["4", "2", "--a", "x", "--b", "1"], "not a rational"),
    (["4", "2", "--a", "0"], "b is required"),
    (["3", "2", "--J", "1,2", "--b", "1"], "3 positive rationals"),
    (["4", "2", "--a", "0", "--J", "1,1,1,1", "--b", "1"], "not both"),
])
def test_bad_input_is_one_line(capsys, argv, needle):
    assert exit_code(main, argv) == 2
    assert needle in one_error_line(capsys)


def test_api_bad_input():
    import chaplygin_nd as cn

    with pytest.raises(ValueError, match="b > 0"):
        cn.first_integrals(4, 2, a=0, b=-1)
    with pytest.raises(ValueError, match="degree"):
        cn.first_integrals(4, 0, a=0, b=1)


def test_jacobian_mod_p_is_a_lower_bound_that_matches_the_exact_rank():
    """rank mod p <= rank over QQ; at n = 4, 5 it equals the exact rank (4, then 6 with F)."""
    for n, rank in ((4, 4), (5, 6)):
        r = known_integrals.jacobian_rank_mod_p(sampled_field.axisymmetric(n, A, B), True)
        assert r["rank_mod_p"] == rank == r["functions"]


def _unit_skew(n: int, i: int, j: int) -> sp.Matrix:
    E = sp.zeros(n, n)
    E[i, j], E[j, i] = 1, -1
    return E


def test_hodge_square_of_a_decomposable_pair_is_the_complementary_plane():
    """W = *(M^M)/8 from its definition, by hand: for M = E_12 + E_34, M^M = 2 e1^e2^e3^e4, whose
    Hodge star is 2 e5^e6; the 1/8 and the 8 signed orderings of the 4 indices give W = E_56
    exactly (so a sign, a scale or a dropped factor of the sum is caught, which G = q(W) cannot
    see: G is quadratic in W). A single plane has M^M = 0."""
    M = _unit_skew(6, 0, 1) + _unit_skew(6, 2, 3)
    assert found_integral.hodge_square(M) == _unit_skew(6, 4, 5)
    assert found_integral.hodge_square(_unit_skew(6, 1, 4)) == sp.zeros(6, 6)
    with pytest.raises(ValueError, match="n = 6"):
        found_integral.hodge_square(sp.zeros(5, 5))


def test_n6_integral_at_an_exact_point_and_counted_in_the_box():
    """G (n = 6) vanishes under X at an exact rational point (random a, b); the known ranks of
    the box (4, 4, 1) grow by one when G is counted."""
    assert found_integral.prove_at_points(6, 1, builder=found_integral.new_integral_6).ok
    m6 = sampled_field.axisymmetric(6, A, B)
    with_g = sum(fi.known_ranks(m6, 4, 4, 1, True).values())
    assert with_g == sum(fi.known_ranks(m6, 4, 4, 1, False).values()) + 1


def _orbit_values(n, builder, a, b, T=4.0):
    """F (or G) along a float orbit of eq:motion-general (DOP853, rtol 1e-12): max relative drift."""
    from scipy.integrate import solve_ivp

    pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]
    J = np.ones(n)
    J[-1] += a

    def omega(M, g):
        L = np.zeros((len(pairs), len(pairs)))
        for c, (i, j) in enumerate(pairs):
            B_ = np.zeros((n, n))
            B_[i, j], B_[j, i] = 1, -1
            Bg = B_ @ g
            img = J[:, None] * B_ + B_ * J[None, :] + b * (np.outer(Bg, g) - np.outer(g, Bg))
            L[:, c] = [img[k, l] for k, l in pairs]
        w = np.linalg.solve(L, [M[i, j] for i, j in pairs])
        Om = np.zeros((n, n))
        for c, (i, j) in enumerate(pairs):
            Om[i, j], Om[j, i] = w[c], -w[c]
        return Om

    def rhs(_, y):
        M, g = y[: n * n].reshape(n, n), y[n * n:]
        Om = omega(M, g)
        return np.concatenate([(M @ Om - Om @ M).ravel(), -Om @ g])

    rng = np.random.default_rng(0)
    M0 = rng.normal(size=(n, n))
    M0 = M0 - M0.T
    g0 = rng.normal(size=n)
    g0 /= np.linalg.norm(g0)
    sol = solve_ivp(rhs, (0, T), np.concatenate([M0.ravel(), g0]), method="DOP853",
                    rtol=1e-12, atol=1e-12, t_eval=np.linspace(0, T, 5))
    vals = []
    for y in sol.y.T:
        num, den = builder(sp.Matrix(y[: n * n].reshape(n, n)), sp.Matrix(y[n * n:]), a, b)
        vals.append(float(num) / float(den))
    vals = np.array(vals)
    return np.max(np.abs(vals - vals[0])) / abs(vals[0])


def test_new_integrals_stay_constant_along_a_float_orbit():
    """Numerical, not a verdict: F (n = 5) and G (n = 6) along an orbit, DOP853 at rtol 1e-12,
    T = 4; the relative drift stays at the integrator's level (a non-integral such as the
    numerator of F alone drifts by order one on the same orbit)."""
    assert _orbit_values(5, found_integral.new_integral, -0.4, 1.5) < 1e-8
    assert _orbit_values(6, found_integral.new_integral_6, 0.6, 0.8) < 1e-8

    def numerator_only(M, g, a, b):
        return found_integral.new_integral(M, g, a, b)[0], sp.Integer(1)

    assert _orbit_values(5, numerator_only, -0.4, 1.5) > 1e-3


@pytest.mark.parametrize("n, d, d_gamma", [(4, 2, 2), (5, 2, 2)])
def test_real_columns_are_a_real_basis_of_each_block(n, d, d_gamma):
    """Every block's real basis (reconstruction.real_columns) has as many elements as the block has
    complex columns, and its elements, written out (to_expression), are real polynomials that are
    linearly independent: none is zero (the real part of i times a real column would be), none
    repeats. This is what the reconstruction over QQ relies on."""
    B_ = candidate_basis.basis(n, d, d_gamma, sampled_field.axisymmetric(n, A, B).planes)
    for blk in B_.blocks:
        cols = reconstruction.real_columns(B_, blk)
        assert len(cols) == blk.columns
        polys = [sp.Poly(reconstruction.to_expression(B_, blk, cols, [int(i == j) for i in
                                                                         range(len(cols))]),
                         *sum(reconstruction.real_symbols(n), []))
                 for j in range(len(cols))]
        monomials = sorted({m for p in polys for m in p.as_dict()})
        matrix = sp.Matrix([[p.as_dict().get(m, 0) for m in monomials] for p in polys])
        assert matrix.rank() == len(cols), (n, blk.character)


def test_to_expression_is_the_real_part_sum_of_its_definition_in_sympy():
    """reconstruction.to_expression (FLINT complex arithmetic) against the same sum written in
    SymPy from the definitions: linear forms sum_j (re + i im)_rj x_j, monomials their products,
    a column the signed sum of its monomials, a real column Re(i^ipow * column), the result
    sum_j q_j (real column j). A run: a factor of 2 on every monomial and the linear
    forms' coefficients dropped survived the tests that compare only spans and zero-ness."""
    n = 4
    B_ = candidate_basis.basis(n, 2, 2, sampled_field.axisymmetric(n, A, B).planes)
    syms = sum(reconstruction.real_symbols(n), [])
    real = [sp.Symbol(s.name, real=True) for s in syms]
    co = B_.coords
    lin = [sum((int(co.re[r, j]) + sp.I * int(co.im[r, j])) * real[j] for j in range(len(real)))
           for r in range(len(co.names))]
    checked = 0
    for blk in B_.blocks:
        cols = reconstruction.real_columns(B_, blk)
        q = [sp.Rational(k + 2, 3) for k in range(len(cols))]

        def column(c, blk=blk):
            return sum(int(s) * sp.Mul(*[lin[r] ** int(e) for r, e in enumerate(B_.exponents[int(m)])])
                       for m, s, cc in zip(blk.monomial, blk.sign, blk.column) if cc == c)

        want = sum(qj * sum(coeff * sp.expand(sp.I ** ipow * column(c)).as_real_imag()[0]
                            for c, coeff, ipow in combo) for qj, combo in zip(q, cols))
        got = reconstruction.to_expression(B_, blk, cols, q).xreplace(dict(zip(syms, real)))
        assert sp.expand(got - want) == 0, blk.character
        checked += 1
    assert checked == len(B_.blocks) > 0


def test_a_block_without_integrals_has_an_empty_kernel_in_its_own_basis():
    """reconstruction.kernel_rref on a block whose kernel is trivial (the M-degree-1,
    gamma-degree-1 block of character 4, n = 4: no linear integral there): a 0-row matrix with one
    column per real column, and the basis and block it was asked for. The tests reached that
    branch with no such block (a mutation run found a 1-row result survived)."""
    model = sampled_field.axisymmetric(4, A, B)
    R, basis, blk, cols = reconstruction.kernel_rref(model, 1, 1, 0, 4, 0, 1)
    assert R.shape == (0, len(cols)) and len(cols) == blk.columns > 0
    assert blk.character == 4 and blk in basis.blocks
    assert basis.exponents.shape == candidate_basis.basis(4, 1, 1, model.planes).exponents.shape


def test_search_is_search_degree_over_its_boxes():
    """first_integrals.search (no row or test called it): one DegreeResult per
    box, in order, each the search_degree of that box."""
    model = sampled_field.axisymmetric(4, A, B)
    boxes = [(2, 0, 0), (1, 1, 0)]
    assert fi.search(model, boxes) == [fi.search_degree(model, d, dg, k) for d, dg, k in boxes]
