"""The exact search for commuting symmetry fields (row S7:symmetry-fields): the trivial solutions
(orbit fields, Delta^tau X) are recovered and only they; Delta X stops being one when s != tau - 1;
the n = 3 Hamiltonian field of Borisov-Mamaev's structure is exactly trivial; bad input."""

from __future__ import annotations

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
