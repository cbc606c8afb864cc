r"""Weight multiplicities of torus representations, for the character dimensions of invariant rings.

A representation of a torus is its list of weights (integer tuples). Its $d$-th symmetric power and
the tensor product of two representations are again weight multiplicities (``Counter``); the
dimension of the invariants is then read off by Weyl's character formula
(:mod:`symbolic.search.invariant_rings` for $SO(3)$, :mod:`symbolic.search.orthogonal_invariants`
for $SO(m)$, $m \ge 5$).
"""

from __future__ import annotations

from collections import Counter

__all__ = ["symmetric_power", "tensor_product"]


def symmetric_power(weights, d: int) -> Counter:
    r"""Weight multiplicities of $S^d V$ for $V$ with the given weights (one tuple per basis
    vector; $d \ge 0$): every multiset of $d$ basis vectors contributes the sum of their weights."""
    dp: list[Counter] = [Counter() for _ in range(d + 1)]
    dp[0][(0,) * len(weights[0])] = 1
    for w in weights:
        new: list[Counter] = [Counter() for _ in range(d + 1)]
        for k in range(d + 1):
            for key, c in dp[k].items():
                for t in range(d - k + 1):
                    new[k + t][tuple(a + t * b for a, b in zip(key, w))] += c
        dp = new
    return dp[d]


def tensor_product(c1: Counter, c2: Counter) -> Counter:
    r"""Weight multiplicities of $V_1 \otimes V_2$: weights add, multiplicities multiply."""
    out: Counter = Counter()
    for k1, v1 in c1.items():
        for k2, v2 in c2.items():
            out[tuple(a + b for a, b in zip(k1, k2))] += v1 * v2
    return out
