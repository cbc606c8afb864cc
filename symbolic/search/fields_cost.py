r"""What a symmetry-field box will cost, said before it runs (``chaplygin symmetry-fields``,
symbolic/search/symmetry_fields.py).

The estimate is CPU time (``time.process_time``), stage by stage, from the sizes the box fixes
before anything is built: $N = n(n-1)/2 + n$ coordinates, $C = 34(d+1) - d$ columns (the 34 fields
of :func:`~chaplygin_nd.symbolic.search.symmetry_fields.field_blocks` times $x^k$, $k \le d$, $DX$
once; the independent ones are at most $C$, so $C$ bounds them), $P = \lfloor 2C/(N-1)\rfloor + 4$
sample points and at most $R = P(N + n)$ condition rows. The growth laws, with constants and
exponents fitted by least squares on $\log$ CPU time over the boxes $n = 3..6$, $d \le 3$ and
$n = 5$, $d = 4$ (one process, boxes in order of $n$ then $d$, $s = \tau - 1$; the largest ratio
of measured to fitted time in brackets):

* building the columns (the 34 fields expanded in SymPy once, converted to FLINT, their $x^k$
  multiples FLINT products): $c_0 + c_1 N^{2.2}$, fitted on each $n$'s first box (the later boxes
  of a process reuse SymPy's caches and cost a quarter of it) [2];
* the column rank over $\mathbb{Q}$: $c_2 C^{1.4} N^{0.9}$ [1.4];
* the exact proofs of its syzygies (FLINT division by $\|\gamma\|^2 - 1$,
  symbolic/search/orbit_fields.py): $c_3 C N$ (hundredths of a second);
* the conditions at the sample points (values and first derivatives of every column, $[X, Q]$
  at a point): $c_4 C N^{1.1}$ [1.3];
* the kernel over $\mathbb{Q}$ (FLINT ``fmpq_mat.rref``): $c_5 C^2 N$ (hundredths of a second);
* the exact orbit-direction proofs, one per kernel vector that is not a trivial column: $Q(I)$
  for the 21 :func:`~chaplygin_nd.symbolic.search.orbit_fields.invariants`, each divided by
  $\|\gamma\|^2 - 1$ in FLINT, so one candidate costs $c_6 (N/10)^{p}$, $p = 3$ fitted on
  $n = 4, 5, 6$ ($d = 1$, one candidate each, each $n$'s first; later ones reuse SymPy's
  conversion of the invariants and cost a fifth; the candidate does not grow with $d$). From
  $n = 7$ on the invariants reach degree $n - 1$ in $M$ and one candidate cost about 250 s at
  $n = 7$, $d = 1$ (load 10–17); beyond it the growth $(N/28)^8$ is a guess from that one point,
  chosen steep so that a box is refused rather than started. Their number is
  known only after the kernel (one in every box with a candidate measured), so the estimate gives
  the cost of one beside the sure part. The same proof through SymPy (the terms converted by
  repeated addition, quadratic in their number, then reduced modulo the sphere) costs about
  $16.3\,(N/10)^{8.4}$ s: 8 min at $n = 5$, 2.3 h at $n = 6$.

When candidates remain after the first sample, the points are doubled and the conditions, kernel
and orbit proofs redone (symbolic/search/symmetry_fields.py); the estimate is for one sample (no
box measured needed a second).

The wall time is the CPU time divided by the share of a core the process gets: at most
$(L + 1)/c$ times longer on $c$ cores at 1-minute load $L$ (``os.getloadavg``), the bound printed.
A guide within a factor of a few, never a verdict.
"""

from __future__ import annotations

import os
from dataclasses import dataclass

from chaplygin_nd.symbolic.search.cost import duration

__all__ = ["FieldCost", "field_cost", "wall_factor", "STAGES", "FIELDS"]

#: the fields of one degree in the box (symbolic_fields.field_blocks: 6 orbit fields, DX, 27 more)
FIELDS = 34
#: the stages of symmetry_fields.search_fields, in order, as its FieldBox.stages names them
STAGES = ("columns", "column rank", "syzygy proofs", "conditions", "kernel", "orbit proofs", "generic")
#: CPU seconds (fitted as the module docstring says): fixed, and per N^COL_POWER, of the columns;
#: per C^1.4 N^0.9 of the column rank; per C N of the syzygy proofs; per C N^1.1 of the
#: conditions; per C^2 N of the kernel; one orbit-direction candidate at N = 10, and its growth
#: exponent in N
C_FIXED, C_COL, COL_POWER = 0.3, 2.7e-3, 2.2
C_RANK = 1.2e-5
C_SYZ = 6.8e-6
C_COND = 6.7e-4
C_KERNEL = 3.9e-8
C_CANDIDATE = 0.35
CANDIDATE_POWER = 3.0
#: from n = 7 on the invariants reach degree n - 1 (orbit_fields.invariants): one candidate measured
#: at n = 7 (N = 28), and a growth exponent that is a guess, not a fit (one point), chosen steep
C_CANDIDATE_7, CANDIDATE_POWER_7 = 250.0, 8.0


@dataclass(frozen=True)
class FieldCost:
    """The estimate of one box: its sizes and CPU seconds per stage (``stages``, keys of
    :data:`STAGES`; ``orbit proofs`` is the cost of one candidate, ``candidate``)."""

    n: int
    degree: int
    coordinates: int
    columns: int
    points: int
    rows: int
    stages: dict
    candidate: float

    @property
    def sure(self) -> float:
        """CPU seconds of the stages every box runs (all but the orbit-direction proofs)."""
        return sum(v for k, v in self.stages.items() if k != "orbit proofs")

    def cpu(self, candidates: int = 1) -> float:
        """CPU seconds with ``candidates`` orbit-direction proofs."""
        return self.sure + candidates * self.candidate

    def line(self) -> str:
        """One line: sizes, the CPU estimate with one candidate and without, the wall bound."""
        f, load = wall_factor()
        return (f"n={self.n} degree={self.degree}: at most {self.columns} unknowns, {self.coordinates} "
                f"coordinates, {self.points} points; CPU about {duration(self.sure)} "
                f"+ {duration(self.candidate)} per orbit-direction candidate (CPU {duration(self.cpu())} "
                f"with one; wall up to {f:.1f}x that at load {load:.1f})")


def wall_factor() -> tuple[float, float]:
    """How much longer than its CPU time a single-threaded run may take now, at most: (L + 1)/c on
    c cores at 1-minute load L (1 where the load is unknown), and L."""
    try:
        load = os.getloadavg()[0]
    except OSError:
        return 1.0, 0.0
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    return max(1.0, (load + 1) / cores), load


def field_cost(n: int, degree: int) -> FieldCost:
    """The :class:`FieldCost` of the symmetry-field box (n, d) (module docstring's laws)."""
    if n < 3 or degree < 0:
        raise ValueError(f"(n, d) = ({n}, {degree}): need n >= 3, d >= 0")
    N = n * (n - 1) // 2 + n
    C = FIELDS * (degree + 1) - degree
    P = 2 * C // (N - 1) + 4
    R = P * (N + n)
    stages = {
        "columns": C_FIXED + C_COL * N**COL_POWER,
        "column rank": C_RANK * C**1.4 * N**0.9,
        "syzygy proofs": C_SYZ * C * N,
        "conditions": C_COND * C * N**1.1,
        "kernel": C_KERNEL * C * C * N,
        "generic": 0.0,
    }
    candidate = (C_CANDIDATE * (N / 10) ** CANDIDATE_POWER if n <= 6
                 else C_CANDIDATE_7 * (N / 28) ** CANDIDATE_POWER_7)
    stages["orbit proofs"] = candidate
    return FieldCost(n, degree, N, C, P, R, stages, candidate)
