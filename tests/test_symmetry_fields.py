"""The exact search for commuting symmetry fields (row S7:symmetry-fields): the trivial solutions
(orbit fields, Delta^tau X) are recovered and only they; Delta X stops being one when s != tau - 1;
the n = 3 Hamiltonian field of Borisov-Mamaev's structure is exactly trivial; bad input."""

from __future__ import annotations

import pytest
import sympy as sp
from chaplygin_nd.symbolic.search import symmetry_fields as sf
from chaplygin_nd.symbolic.search.fields_command import main
from cli_helpers import exit_code, one_error_line

A, B = sp.Rational(1, 3), sp.Rational(2, 5)


def test_trivial_fields_are_the_solutions_and_delta_x_needs_the_matching_exponent():
    half = sp.Rational(1, 2)
    r1 = sf.search_fields(3, 1, -half, half, A, B, seed=2)
    r2 = sf.search_fields(3, 1, 0, half, A, B, seed=2)
    assert r1.excess == 0 and r2.excess == 0 and r1.solutions > 0
    assert r1.solutions == r2.solutions + 1  # Delta X solves exactly when s = tau - 1


def test_the_n3_hamiltonian_field_of_borisov_mamaev_is_delta_x_plus_orbit_fields():
    from chaplygin_nd.proofs.s7_hamiltonisation import _bm_field_is_trivial
    part = _bm_field_is_trivial()
    assert part.verdict == "holds" and "D X" in part.method


def test_invariants_are_invariant_under_a_rational_rotation_fixing_E_n():
    from chaplygin_nd.symbolic.exact.points import (
        generator,
        rational_rotation,
        skew_matrix,
        sphere_point,
    )
    from chaplygin_nd.symbolic.search import bivector_ansatz as ba
    n = 4
    M, g, z = ba.coordinates(n)
    inv = sf.invariants(n, M, g)
    rng = generator(4, "inv")
    R3 = rational_rotation(rng, n - 1)
    R = sp.diag(R3, sp.Integer(1))
    Mv, gv = skew_matrix(rng, n), sphere_point(rng, n)
    sub = dict(zip(list(z), [Mv[i, j] for i in range(n) for j in range(i + 1, n)] + list(gv)))
    Mr, gr = R * Mv * R.T, R * gv
    subr = dict(zip(list(z), [Mr[i, j] for i in range(n) for j in range(i + 1, n)] + list(gr)))
    assert len(inv) > 5 and all(e.xreplace(sub) == e.xreplace(subr) for e in inv)


def test_command_bad_input_gives_one_line(capsys):
    for argv in (["2", "0"], ["3", "0", "--pairs", "x"], ["3", "0", "--b", "0"], ["3", "-1"]):
        assert exit_code(main, argv) == 2
        one_error_line(capsys)


def test_a_count_is_carried_to_generic_parameters_unless_delta_x_enters_a_syzygy():
    """n = 3, d = 0: one minor of the sampled conditions, nonzero at (1/3, 2/5), carries the count
    to generic (a, b); at d = 1 a proved column syzygy involves D X (which depends on a, b), so the
    count is stated at the point only."""
    half = sp.Rational(1, 2)
    r0 = sf.search_fields(3, 0, -half, half, A, B, seed=2)
    assert r0.excess == 0 and r0.generic.startswith("generic (a, b)") and "!= 0" in r0.generic
    r1 = sf.search_fields(3, 1, -half, half, A, B, seed=2)
    assert r1.excess == 0 and r1.generic.startswith("only at") and "D X" in r1.generic


def test_vanishing_on_the_sphere_agrees_between_flint_division_and_the_sympy_normal_form():
    """Both engines on the identities the search proves (the n = 4, d = 1 orbit-direction field
    against every invariant) and on polynomials that do not vanish (the field D X against x and
    |M|^2 ... one more term than the sphere allows)."""
    from chaplygin_nd.symbolic.search import bivector_ansatz as ba
    from chaplygin_nd.symbolic.search import orbit_fields as of
    from chaplygin_nd.symbolic.search.point_values import fq
    from chaplygin_nd.symbolic.search.poisson import _ctx

    n = 4
    r = sf.search_fields(n, 1, 0, 1, A, B, seed=2)
    assert r.orbit_proved == 1
    M, g, z = ba.coordinates(n)
    ctx = _ctx(z)
    zero = ctx.from_dict({})
    N = len(z)
    polys = [p for _, p in r.columns]
    labels = [lab for lab, _ in r.columns]
    others = [v for v in r.kernel if sum(1 for c in v if c != 0) > 1]
    assert others
    inv = [ctx.from_dict({m: fq(c) for m, c in sp.Poly(e, *z).as_dict().items()}) for e in of.invariants(n, M, g)]
    sphere = sum(v**2 for v in g) - 1
    checked = 0
    for v in others:
        Q = [sum((c * polys[u][i] for u, c in enumerate(v) if c != 0 and polys[u][i] is not None), zero)
             for i in range(N)]
        for f in inv:
            e = sum((Q[i] * f.derivative(i) for i in range(N)), zero)
            flint_says = of.vanishes_on_sphere(e, n)
            sympy_says = of.sphere_normal_form(of.to_sympy(e, z), list(g)) == 0
            assert flint_says == sympy_says
            checked += flint_says
    assert checked > 0
    dx = next(i for i, lab in enumerate(labels) if lab == ("D X", 0))
    xq = polys[dx][N - 1]  # (D X)(gamma_n): not zero on the sphere
    for e in (xq, xq * inv[1], xq + ctx.from_dict({m: fq(c) for m, c in sp.Poly(sp.expand(sphere), *z).as_dict().items()})):
        assert not of.vanishes_on_sphere(e, n)
        assert of.sphere_normal_form(of.to_sympy(e, z), list(g)) != 0
    mult = ctx.from_dict({m: fq(c) for m, c in sp.Poly(sp.expand(sphere * z[0] * z[-1]), *z).as_dict().items()})
    assert of.vanishes_on_sphere(mult * xq, n) and of.sphere_normal_form(of.to_sympy(mult * xq, z), list(g)) == 0
    assert sp.expand(of.to_sympy(xq, z) - sp.Poly(of.to_sympy(xq, z), *z).as_expr()) == 0


@pytest.mark.slow
def test_n6_degree2_needs_a_larger_column_sample_and_recovers_the_trivial_fields():
    """At n = 6, d = 2 the first column sample suggests a syzygy that is not an identity; the
    extended sample proves every one, and the box holds the trivial fields (the orbit fields, Delta^tau
    X, one orbit-direction field proved exactly) and nothing else (several CPU seconds: slow)."""
    r = sf.search_fields(6, 2, 1, 2, A, B, seed=2)
    assert r.column_points > 2 * (100 // 21) + 6  # the first sample (C = 100 columns, N = 21) was extended
    assert r.excess == 0 and r.orbit_proved == 1 and r.solutions == r.trivial > 1
