"""The first-integral search in the invariant ring (symbolic/search/invariant_search.py): its
unknowns are a proved basis of the invariants of each bidegree, its generators are those of
S6:reduced-n5, and the same controls as the weight-zero search come out."""

from __future__ import annotations

import random
from fractions import Fraction

import numpy as np
import pytest
import sympy as sp
from chaplygin_nd.symbolic.reduction import invariants_n5
from chaplygin_nd.symbolic.search import (
    genericity,
    integral_search,
    invariant_rings,
    invariant_search,
    known_integrals,
    sampled_field,
)

A, B = sp.Rational(-1, 3), sp.Rational(3, 2)
GENERIC3 = sampled_field.general((1, sp.Rational(3, 2), sp.Rational(7, 3)), sp.Rational(1, 2))
P = 268435361


def test_the_derivative_weights_are_exact_to_their_degree():
    """h'(0) = sum_t w_t h(t) for h = t^j, j = 0..D; for D = 4 the classical five-point weights."""
    for D in range(1, 9):
        nodes = invariant_search.derivative_nodes(D)
        for j in range(D + 1):
            assert sum(w * t**j for t, w in nodes) == (1 if j == 1 else 0), (D, j)
    assert [w for _t, w in invariant_search.derivative_nodes(4)] == [
        Fraction(-25, 12), 4, -3, Fraction(4, 3), Fraction(-1, 4)]


def test_the_so4_generators_mod_p_are_those_of_the_reduction():
    """The vectorised mod-p values equal invariants_n5.generators_from (exact integers) at an
    integer point, in the combinations A+ +- A-, E+ +- E-."""
    rng = random.Random(3)
    Mm = [[0] * 5 for _ in range(5)]
    z = []
    for i in range(5):
        for j in range(i + 1, 5):
            v = rng.randrange(-50, 50)
            Mm[i][j], Mm[j][i] = v, -v
            z.append(v)
    q = [rng.randrange(-50, 50) for _ in range(4)]
    z += q + [7]
    want = invariants_n5.generators_from(Mm, q)
    exact = [want["Ap"] + want["Am"], want["Ap"] - want["Am"], want["B"], want["G"],
             want["Ep"] + want["Em"], want["Ep"] - want["Em"], want["Suu"], want["Suq"], want["Sqq"],
             want["s"]]
    got = invariant_rings.ring_for(5, "axisymmetric").values(np.array([z], dtype=np.int64), P)[0]
    assert [int(g) for g in got] == [e % P for e in exact]


@pytest.mark.parametrize("model, box", [(GENERIC3, (2, 4, 1)), (GENERIC3, (3, 4, 1)),
                                        (sampled_field.axisymmetric(4, A, B), (2, 4, 1)),
                                        (sampled_field.axisymmetric(5, A, B), (2, 4, 1))])
def test_controls_recover_exactly_the_known_integrals(model, box):
    r = invariant_search.InvariantRingSearch(model).run_box(box)
    paper = sum(invariant_search.InvariantRingSearch(model, include_new=False).known_ranks(box).values())
    assert r.settled and r.recovered and r.found == paper > 0
    if model.kind == "general":   # no symmetry: the same space as the weight-zero search
        old = integral_search.search_degree(model, *box)
        assert (r.unknowns, r.found, r.known) == (old.unknowns, old.found, old.known)


def test_the_invariant_ring_finds_F_beyond_the_paper():
    model = sampled_field.axisymmetric(5, A, B)
    r = invariant_search.InvariantRingSearch(model).run_box((4, 4, 1))
    paper = sum(invariant_search.InvariantRingSearch(model, include_new=False).known_ranks((4, 4, 1)).values())
    assert r.settled and r.recovered and r.found == paper + 1


def test_the_box_6_6_2_settles_only_with_the_lowest_degree_form_of_F(monkeypatch):
    model = sampled_field.axisymmetric(5, A, B)
    r = invariant_search.InvariantRingSearch(model).run_box((6, 6, 2))
    assert r.settled and r.recovered is not False and r.unknowns < 1000
    full = known_integrals.generators

    def without_f2(model, include_new=False):
        return [g for g in full(model, include_new) if g.name != "F2"]

    monkeypatch.setattr(known_integrals, "generators", without_f2)
    short = invariant_search.InvariantRingSearch(model).run_box((6, 6, 2))
    assert short.found == r.found and short.known < r.known and not short.settled


def test_a_missing_generator_is_caught_by_the_dimension(monkeypatch):
    """Drop S_qq: the products no longer reach the dimension of some bidegree; the basis refuses."""
    ring = invariant_rings.ring_for(5, "axisymmetric")
    keep = [i for i, n in enumerate(ring.names) if n != "Sqq"]
    short = invariant_rings.Ring("SO4-short", 5, "SO(4)", tuple(ring.names[i] for i in keep),
                                 tuple(ring.m_degree[i] for i in keep), tuple(ring.q_degree[i] for i in keep),
                                 lambda z, p: ring.values(z, p)[:, keep], ring.dimension, ring.reflections)
    monkeypatch.setattr(invariant_rings, "ring_for", lambda n, kind: short)
    invariant_search.basis.cache_clear()
    try:
        with pytest.raises(ArithmeticError, match="span"):
            invariant_search.basis(5, "axisymmetric", 2, 2)
    finally:
        invariant_search.basis.cache_clear()


def test_no_invariant_ring_for_n_without_generators():
    with pytest.raises(ValueError, match="no invariant generators"):
        invariant_rings.ring_for(9, "axisymmetric")


def test_the_parameters_enter_polynomially():
    r = genericity.polynomial_in_parameters(3)
    assert r["ok"] and "numerator of F2" in r["checked"]


def test_the_weyl_dimension_agrees_with_the_su2_counts():
    """orthogonal_invariants.dimension (Weyl's formula for SO(m)) against the independent counts:
    SU(2) x SU(2) for SO(4) (invariants_n5, by tridegree) and SU(2) for SO(3)."""
    from chaplygin_nd.symbolic.search import orthogonal_invariants as oi

    for d in range(5):
        for l in range(4):
            assert oi.dimension(4, d, l) == sum(invariants_n5.invariant_dimension(i, d - i, l)
                                                for i in range(d + 1))
            assert oi.dimension(3, d, l) == invariant_rings.ring_for(4, "axisymmetric").dimension(d, l)
    assert oi.dimension(5, 2, 0) == 2 and oi.dimension(6, 3, 0) == 1   # |K|^2, |u|^2; Pf K


def test_n6_invariant_ring_finds_G_beyond_the_paper():
    model = sampled_field.axisymmetric(6, A, B)
    r = invariant_search.InvariantRingSearch(model).run_box((4, 6, 1))
    paper = sum(invariant_search.InvariantRingSearch(model, include_new=False).known_ranks((4, 6, 1)).values())
    assert r.settled and r.recovered and r.found == paper + 1


def test_a_ring_refuses_reflections_that_are_not_coordinate_indices():
    ring = invariant_rings.ring_for(4, "axisymmetric")
    fields = {f: getattr(ring, f) for f in ring.__dataclass_fields__}
    for bad in ((0, 4), (0, 0), (-1, 3)):
        with pytest.raises(ValueError, match="reflections"):
            invariant_rings.Ring(**{**fields, "reflections": bad})
    with pytest.raises(ValueError, match="generators"):
        invariant_rings.Ring(**{**fields, "m_degree": fields["m_degree"][:-1]})
