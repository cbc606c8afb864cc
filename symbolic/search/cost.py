r"""What a search box will cost, said before it runs (``chaplygin first-integrals``).

Per box: the unknowns and blocks (exact for the invariant ring and for the weight-zero space at
$n \le$ :data:`EXACT_COUNT_MAX_N`, by a count over torus weights that builds nothing; above it the
number of all standard monomials, an upper bound), and estimates of seconds and peak bytes from
the structure of the computation with constants measured on this machine's kind
(bench/bench_first_integrals.py, 2 cores, idle; the estimate is a guide within a factor of a few,
never a verdict):

* building the conditions: one value per (row, monomial): $\sim$ :data:`SECONDS_PER_ENTRY` each;
* the rank mod $p$ of a block of $b$ unknowns: $\sim$ :data:`SECONDS_PER_CUBE` $\cdot\, b^3$;
* the weight-zero space's split by the $2^n$ characters of the reflections: $2^n$ passes over its
  orbits (this is what makes $n = 100$ impossible);
* memory: the condition matrices ($8(b + 24)b$ bytes per block), the transient conversion of the
  largest block to FLINT ($\sim 40 b^2$ bytes), the chunk of monomial values and, for the
  weight-zero space, the enumerated monomials of $M$-degree $d$ (one tuple of all coordinates each).
"""

from __future__ import annotations

import os
import time
from collections import Counter
from dataclasses import dataclass
from math import comb

__all__ = ["Estimate", "estimate", "available_bytes", "duration", "weight_zero_count", "EXACT_COUNT_MAX_N",
           "StageClock"]

#: seconds per entry of the condition values, per unit b^3 of a block's rank, per (character x
#: orbit) of the weight-zero split, and the fixed cost of a box (idle 2-core machine)
SECONDS_PER_ENTRY = 1.5e-7
SECONDS_PER_CUBE = 2e-10
SECONDS_PER_SPLIT = 2e-6
SECONDS_FIXED = 0.3
BASE_BYTES = 150 * 2**20        #: the process with NumPy, SymPy and FLINT loaded
EXACT_COUNT_MAX_N = 9


@dataclass(frozen=True)
class Estimate:
    box: tuple
    unknowns: int
    exact: bool              # False: unknowns is an upper bound (all standard monomials)
    largest: int             # the largest block (estimated for the weight-zero space)
    seconds: float
    bytes: int
    split_seconds: float = 0.0   # the part of ``seconds`` spent splitting by characters

    def line(self) -> str:
        d, dg, k = self.box
        u = f"{self.unknowns}" if self.exact else f"at most {self.unknowns}"
        bound = "" if self.exact else " (from that bound)"
        return (f"box (M-degree {d}, gamma-degree <= {dg}, D^{k}): {u} unknowns, largest block "
                f"~{self.largest}, estimated {duration(self.seconds)} and {_size(self.bytes)}{bound}")


class StageClock:
    """Adds the CPU time since the previous call to ``stages[name]`` (``time.process_time``: CPU,
    not wall, so a stage's figure holds on a loaded machine); what a search's estimate is fitted
    to."""

    def __init__(self, stages: dict):
        self.stages, self.t = stages, time.process_time()

    def __call__(self, name: str) -> None:
        t = time.process_time()
        self.stages[name] = self.stages.get(name, 0.0) + t - self.t
        self.t = t


def duration(s: float) -> str:
    """A duration for a person: seconds, minutes, hours or years."""
    if s < 120:
        return f"{s:.1f} s"
    if s < 7200:
        return f"{s / 60:.0f} min"
    if s < 86400 * 365:
        return f"{s / 3600:.1f} h"
    return f"{s / 3.15e7:.1e} years"


def _size(b: float) -> str:
    return f"{b / 2**30:.3g} GB" if b >= 2**30 else f"{b / 2**20:.0f} MB"


def available_bytes() -> int:
    """Memory the machine has available now (MemAvailable of /proc/meminfo; total RAM elsewhere)."""
    try:
        with open("/proc/meminfo", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")


def _weights(n: int, planes: int):
    """Torus weights of the M and gamma coordinates (candidate_basis.coordinates, without building
    its matrices): basis vectors z_j, zb_j (weights +-e_j) and e_k (0)."""
    vecs = [tuple((s if t == j else 0) for t in range(planes)) for j in range(planes) for s in (1, -1)]
    vecs += [(0,) * planes] * (n - 2 * planes)
    m = [tuple(a + b for a, b in zip(vecs[i], vecs[j])) for i in range(n) for j in range(i + 1, n)]
    return m, vecs[:-1], vecs[-1]           # M coordinates, gamma_1..n-1, gamma_n (weight 0)


def _sym_counts(weights, d: int) -> Counter:
    dp: list[Counter] = [Counter() for _ in range(d + 1)]
    dp[0][(0,) * len(weights[0]) if weights and weights[0] else ()] = 1
    for w in weights:
        for k in range(1, d + 1):      # multiset counts: add w any number of times, in place
            for key, c in list(dp[k - 1].items()):
                dp[k][tuple(a + b for a, b in zip(key, w))] += c
    return dp[d]


def weight_zero_count(n: int, planes: int, d: int, d_gamma: int) -> int:
    """The number of weight-zero standard monomials of S(d, d_gamma) (candidate_basis.basis), by
    counting over weights."""
    m, g, _gn = _weights(n, planes)
    if planes == 0:
        return comb(len(m) + d - 1, d) * _gamma_total(n, d_gamma)
    cm = _sym_counts(m, d)
    total = 0
    for e in range(d_gamma + 1):
        cg = _sym_counts(g, e)
        if e:
            cg = cg + _sym_counts(g, e - 1)      # times gamma_n (weight 0, exponent <= 1)
        total += sum(c * cg.get(tuple(-x for x in w), 0) for w, c in cm.items())
    return total


def _gamma_total(n: int, d_gamma: int) -> int:
    return sum(comb(n - 2 + e, e) + (comb(n - 3 + e, e - 1) if e else 0) for e in range(d_gamma + 1))


def estimate(search, box: tuple) -> Estimate:
    """The :class:`Estimate` of ``box`` for a strategy of symbolic/search/box_search.py."""
    from chaplygin_nd.symbolic.search.box_search import MARGIN
    from chaplygin_nd.symbolic.search.invariant_search import InvariantRingSearch

    d, dg, _k = box
    model = search.model
    n = model.n
    if isinstance(search, InvariantRingSearch):
        blocks = search.unknown_counts(box)
        unknowns, exact = sum(blocks), True
        largest = max(blocks) if blocks else 0
        split, enum_bytes, width = 0.0, 0, len(search.ring.names) + 1
    else:
        planes = model.planes
        nm = n * (n - 1) // 2
        if n <= EXACT_COUNT_MAX_N:
            unknowns, exact = weight_zero_count(n, planes, d, dg), True
        else:
            unknowns, exact = comb(nm + d - 1, d) * _gamma_total(n, dg), False
        share = 1.5 / 2 ** (min(planes, 4) + 1) if planes else 1.5 / 2 ** min(n, 5)
        largest = max(1, min(unknowns, int(unknowns * share)))
        split = SECONDS_PER_SPLIT * 2.0 ** n * unknowns
        enum_bytes = comb(nm + d - 1, d) * (8 * nm + 64)
        width = nm + n
    rows = largest + MARGIN
    blocks_n = max(1, -(-unknowns // max(1, largest)))
    seconds = (SECONDS_FIXED + SECONDS_PER_ENTRY * rows * unknowns + split
               + SECONDS_PER_CUBE * blocks_n * float(largest) ** 3 + 2e-6 * unknowns * width)
    chunk = min(rows * unknowns, 4_000_000)
    nbytes = (BASE_BYTES + enum_bytes + 8 * width * unknowns * 3 + 40 * chunk
              + 8 * rows * unknowns + 40 * largest * largest)
    return Estimate(tuple(box), unknowns, exact, largest, seconds, int(nbytes), split)
