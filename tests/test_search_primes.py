"""Several primes of a search box (symbolic/search/multimodular.py): the combined sandwich, and the
same table whether the primes run here or on a local Dask cluster."""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.symbolic.search import invariant_search, multimodular, sampled_field

MODEL = sampled_field.axisymmetric(5, sp.Rational(-1, 3), sp.Rational(3, 2))
BOXES = [(2, 4, 1), (4, 4, 1)]


def test_the_combined_sandwich_takes_the_tightest_ends():
    a = {"n": 5, "kind": "axisymmetric", "d": 4, "d_gamma": 4, "k": 1, "unknowns": 9, "prime": 3,
         "found": 5, "known": 3, "recovered": True}
    b = {**a, "prime": 7, "found": 4, "known": 4}
    r = multimodular.combine([a, b])
    assert (r["found"], r["known"], r["settled"], r["primes"]) == (4, 4, True, [3, 7])


def test_primes_here_and_on_a_local_dask_cluster_give_the_same_table():
    here = multimodular.run(MODEL, "invariant", BOXES, primes=2)
    dask = multimodular.run(MODEL, "invariant", BOXES, primes=2, scheduler="local", workers=2)
    assert here == dask
    assert all(r["settled"] and len(r["primes"]) == 2 for r in here)
    single = [invariant_search.InvariantRingSearch(MODEL).run_box(b) for b in BOXES]
    assert [r["found"] for r in here] == [s.found for s in single]   # both primes settle alike
