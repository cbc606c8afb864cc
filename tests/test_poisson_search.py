"""The exact Hamiltonisation search (rows S7:poisson-controls, -n4, -n5): the ansatz spans every
equivariant bivector of its weight, the controls are recovered by the same code (Borisov-Mamaev for
n = 3, the e(4) Lie-Poisson bracket at b = 0), mutated structures are refuted, an n = 4 box is
excluded exactly, and the command's bad input gives one line."""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.symbolic.algebra import so_basis
from chaplygin_nd.symbolic.search import bivector_ansatz as ba
from chaplygin_nd.symbolic.search import box_columns as bc
from chaplygin_nd.symbolic.search import poisson as ps
from chaplygin_nd.symbolic.search import poisson_proof as pp
from chaplygin_nd.symbolic.search.poisson_command import main
from cli_helpers import exit_code, one_error_line

A, B = sp.Rational(1, 3), sp.Rational(2, 5)
a, b = sp.symbols("a b", real=True)


def test_blocks_span_every_equivariant_bivector_of_weight_minus_one():
    """At a slice point the blocks reach the dimension of the stabiliser-invariant tensors."""
    for n in (3, 4):
        c = ba.completeness(n)
        assert c["mm_rank"] == c["mm_invariant"] > 0 and c["mg_rank"] == c["mg_invariant"] == 4


def test_the_field_conserves_H_at_a_point():
    """dH(X) = 0 exactly (S2.2:energy): the data the linear stage is built from is consistent."""
    from chaplygin_nd.symbolic.exact.points import generator, skew_matrix, sphere_point
    rng = generator(3, "poisson-test")
    for n in (3, 4, 5):
        fd = ps.field_data(n, A, B, skew_matrix(rng, n), sphere_point(rng, n))
        assert sum(u * v for u, v in zip(fd["dH"], fd["X"], strict=True)) == 0
        assert any(v != 0 for v in fd["X"])


def test_n3_control_recovers_borisov_mamaev_uniquely():
    """Box (2, 1): one solution, sigma = -1/2, equal to the closed form, and exactly proved."""
    r = ps.search_box(3, 2, 1, A, B, seed=11)
    vals = pp.solution_values(r)
    assert r.outcome == "solutions" and vals["free"] == [] and vals[ps.sigma] == sp.Rational(-1, 2)
    P = pp.structure_matrix(r, vals)
    gam = list(ba.coordinates(3)[1])
    diff = (pp.borisov_mamaev(A, B) - P).applyfunc(sp.expand)
    assert all(bc.sphere_reduce(v, gam) == 0 for v in diff if v != 0)
    assert any(v != 0 for v in P)
    assert all(bool(c) for c in pp.prove_structure(3, P, sp.Rational(-1, 2), 1, A, B).values())


def test_n3_closed_form_holds_for_symbolic_parameters_and_mutants_fail():
    """The closed form is a Hamiltonisation for symbolic a, b; a wrong conformal exponent breaks
    Jacobi, a wrong multiplier breaks Pi dH = rho X, a changed coefficient breaks both."""
    P = pp.borisov_mamaev(a, b)
    assert all(bool(c) for c in pp.prove_structure(3, P, sp.Rational(-1, 2), 1, a, b).values())
    assert not pp.prove_structure(3, P, 0, 1, A, B)["jacobi"]
    assert not pp.prove_structure(3, P, sp.Rational(-1, 2), 0, A, B, jacobi=False)["hamilton"]
    M, g, _ = ba.coordinates(3)
    bad = pp.borisov_mamaev(A, B) + ba.block_bivectors(3, M, g)[1]
    assert not pp.prove_structure(3, bad, sp.Rational(-1, 2), 1, A, B, jacobi=False)["hamilton"]


def test_free_body_control_is_the_lie_poisson_bracket_of_e4():
    """b = 0: the degree-0 box gives {M_xi, M_eta} = -<M, [xi, eta]>, {M_xi, gamma} = xi gamma
    (built here from commutators), nothing else."""
    n = 4
    r = ps.search_box(n, 0, 0, A, 0, seed=5)
    vals = pp.solution_values(r)
    P = pp.structure_matrix(r, vals)
    M, g, _ = ba.coordinates(n)
    basis = so_basis(n)
    m = len(basis)
    LP = sp.zeros(m + n, m + n)
    for p, xi in enumerate(basis):
        for q, eta in enumerate(basis):
            br = xi * eta - eta * xi
            LP[p, q] = -sum(M[i, j] * br[i, j] for i in range(n) for j in range(i + 1, n))
        for k in range(n):
            LP[p, m + k], LP[m + k, p] = (xi * g)[k], -(xi * g)[k]
    assert (P - LP).applyfunc(sp.expand) == sp.zeros(m + n, m + n)


def test_n4_boxes_are_excluded_exactly():
    """n = 4: box (1, 1) has no solution of the linear stage; box (2, 1) has an affine space of
    candidates that the Jacobi stage excludes (Groebner basis {1})."""
    r = ps.search_box(4, 1, 1, A, B, seed=5)
    assert r.outcome == "excluded (linear)" and r.unknowns > r.independent > 0
    r = ps.search_box(4, 2, 1, A, B, seed=5)
    assert r.free > 0 and r.jacobi_equations > 0 and r.groebner == [1]
    assert r.outcome == "excluded (Jacobi)"


def test_command_bad_input_gives_one_line(capsys):
    for argv in (["2", "1"], ["4", "1", "--e", "x"], ["4", "1", "--a", "-2"], ["4", "2", "--from", "3"]):
        assert exit_code(main, argv) == 2
        one_error_line(capsys)


def test_command_prints_one_line_per_box(capsys):
    assert main(["3", "0", "--e", "1"]) == 0
    out = capsys.readouterr().out.strip().splitlines()
    assert len(out) == 1 and "n=3 d=0 e=1" in out[0] and "excluded (linear)" in out[0]
