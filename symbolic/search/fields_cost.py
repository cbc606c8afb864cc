r"""What a symmetry-field box will cost, said before it runs (``chaplygin symmetry-fields``,
symbolic/search/symmetry_fields.py).

The estimate is CPU time (``time.process_time``), stage by stage, from the sizes the box fixes
before anything is built: $N = n(n-1)/2 + n$ coordinates, $C = 34(d+1) - d$ columns (the 34 fields
of :func:`~chaplygin_nd.symbolic.search.symmetry_fields.field_blocks` times $x^k$, $k \le d$, $DX$
once; the independent ones are at most $C$, so $C$ bounds them), $P = \lfloor 2C/(N-1)\rfloor + 4$
sample points and at most $R = P(N + n)$ condition rows. The growth laws, with constants fitted
by CPU time on boxes $n = 3..6$, $d \le 3$:

* building the columns (SymPy expansion of the fields): $c_0 + c_1 N^2 + c_2 C N$;
* the column rank and the exact proofs of its syzygies (SymPy, modulo the sphere): $c_3 C N^2$;
* the conditions at the sample points (values and first derivatives of every column,
  $[X, Q]$ at a point; $P$ points, but at these sizes each point's fixed part dominates):
  $c_4 C N^{3/2}$;
* the kernel over $\mathbb{Q}$ (FLINT ``fmpq_mat.rref`` of $R \approx 2C$ rows, entries growing
  with $N$): $c_5 C^2 N$ (milliseconds at every box measured);
* the exact orbit-direction proofs, one per kernel vector that is not a trivial column: each
  converts $Q(I)$ for the 21 :func:`invariants` to SymPy and reduces it modulo the sphere. One
  candidate's $Q(I)$ have $T \approx 4300\,(N/10)^{4.2}$ terms in all (counted at $n = 4, 5, 6$,
  $d = 1$, and the same at $n = 4$, $d = 1..3$: the candidate does not grow with $d$), and each
  check costs about the square of its terms (SymPy builds the sum by repeated addition: measured
  $T^{2.1}$ for the conversion, $T^{1.7}$ for the reduction), so one candidate costs
  $c_6 (N/10)^{8.4}$, $c_6$ fitted at $n = 4$. Their number is known only after the kernel
  (one in every box with a candidate measured), so the estimate gives the cost of one beside the
  sure part; this stage dominates every box with a candidate from $n = 4$ on.

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
#: CPU seconds: fixed, per N^2 and per C N of the columns; per C N^2 of the syzygy proofs; per
#: C N^1.5 of the conditions; per C^2 N of the kernel; one orbit-direction candidate at N = 10, and
#: its growth exponent in N (fitted on n = 3..6, d <= 3, see the module docstring)
C_FIXED, C_COL_N2, C_COL_CN = 0.2, 4.4e-3, 2.9e-4
C_SYZ = 3.5e-5
C_COND = 3e-4
C_KERNEL = 1e-7
C_CANDIDATE = 16.3
CANDIDATE_POWER = 8.4


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
        "columns": C_FIXED + C_COL_N2 * N * N + C_COL_CN * C * N,
        "column rank": 0.0,
        "syzygy proofs": C_SYZ * C * N * N,
        "conditions": C_COND * C * N**1.5,
        "kernel": C_KERNEL * C * C * N,
        "generic": 0.0,
    }
    candidate = C_CANDIDATE * (N / 10) ** CANDIDATE_POWER
    stages["orbit proofs"] = candidate
    return FieldCost(n, degree, N, C, P, R, stages, candidate)
