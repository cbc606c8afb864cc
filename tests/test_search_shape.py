"""The shape of the exact searches (symbolic/search/box_search.py): a back end is one file
(symbolic/search/backend_numpy.py, selected by name, shares no code with FLINT) and gives the same
results as FLINT; the base owns the degree -> box rule."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from chaplygin_nd.symbolic.search import backend, box_search, integral_search, sampled_field

A, B = sp.Rational(-1, 3), sp.Rational(3, 2)
GENERIC3 = sampled_field.general((1, sp.Rational(3, 2), sp.Rational(7, 3)), sp.Rational(1, 2))


@pytest.mark.parametrize("model, box", [
    (GENERIC3, (2, 4, 1)),
    (sampled_field.axisymmetric(4, A, B), (2, 4, 1)),
    (sampled_field.axisymmetric(5, A, B), (2, 4, 1)),
])
def test_a_second_back_end_gives_the_same_box(model, box):
    flint_r = integral_search.search_degree(model, *box)
    numpy_r = integral_search.search_degree(model, *box, backend="numpy")
    assert numpy_r == flint_r
    assert flint_r.settled and flint_r.found > 0


def test_the_back_ends_agree_on_rank_nullspace_rref():
    p = backend.PRIMES[0]
    rng = np.random.default_rng(5)
    A = rng.integers(0, p, size=(7, 4)) @ np.diag([1, 1, 0, 1]) % p       # rank 3
    A = np.concatenate([A, A[:, :1]], axis=1) % p                          # a dependent column
    f, n = backend.get("flint"), backend.get("numpy")
    assert f.rank(A, p) == n.rank(A, p) == 3
    assert (f.rref(A, p) == n.rref(A, p)).all()
    for la in (f, n):
        N = la.nullspace(A, p)
        assert N.shape == (2, 5) and la.rank(N, p) == 2
        assert not la.matmul(A, N.T, p).any()


def test_an_unknown_back_end_is_one_clear_error():
    with pytest.raises(ValueError, match="unknown linear-algebra back end 'nosuch'.*flint"):
        backend.get("nosuch")


def test_the_degree_to_box_rule():
    assert box_search.box_for(4, 1) == (4, 6, 1)
    assert box_search.box_for(6, 2, 6) == (6, 6, 2)
    assert box_search.box_for(3, 0) == (3, 3, 0)
    with pytest.raises(ValueError):
        box_search.box_for(0, 1)


def test_the_lifting_to_rationals_checks_with_one_more_prime():
    q = [sp.Rational(-7, 3), sp.Rational(5, 11)]

    def at(i):
        p = backend.PRIMES[i]
        return np.array([[int(x.p) * pow(int(x.q), -1, p) % p for x in q]], dtype=np.int64)

    assert box_search.BoxSearch(None).rational_kernel(at, 3) == [q]

    def wrong(i):
        return at(i) if i < 2 else (at(i) + 1) % backend.PRIMES[i]

    with pytest.raises(ArithmeticError, match="check prime"):
        box_search.BoxSearch(None).rational_kernel(wrong, 3)
