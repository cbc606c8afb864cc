r"""What a Hamiltonisation box will cost, said before it runs (``chaplygin poisson``,
symbolic/search/poisson.py).

CPU time (``time.process_time``) stage by stage, from the sizes the box fixes: $N = n(n-1)/2 + n$
coordinates, $U = 24(d+1)$ columns (the blocks of symbolic/search/bivector_ansatz.py times $x^k$,
$k \le d$; the independent ones are at most $U$) and $P = 2\lfloor U/N\rfloor + 6$ sample points.
The growth laws, constants fitted by CPU time on boxes $n = 3..5$, $d \le 5$:

* building the columns (the ansatz in SymPy, then FLINT polynomials), once per $(n, d)$ for all
  $e$: $c_0 + c_1 U N^2$;
* the column rank and the exact proofs of its syzygies (SymPy, modulo the sphere): $c_2 U N^2$;
* the linear conditions at the points ($P\,dH = \Delta^e X$, tangency): $P(c_3 N + c_4 U N^2)$,
  the per-point part ($X$, $dH$, $\Delta$ at a point, SymPy) dominating small boxes;
* the kernel over $\mathbb{Q}$: milliseconds at every box measured (not modelled);
* the carry to generic $(a, b)$ of a linear exclusion (symbolic/search/generic_extension.py):
  $c_5 U N^2$;
* only when the linear stage leaves an affine space: the Jacobi equations at the points (the
  $\binom{N}{3}$ Jacobiator entries as polynomials in the free unknowns) and their Gröbner basis
  over $\mathbb{Q}$: $c_6 U^3 (N/10)^4$, from $n = 4$, $d = 2..5$ (cubic in $U$ to within 10 %)
  and $n = 5$. The dimension of that space is known only after the kernel, so the estimate states
  this stage beside the sure part. A Gröbner basis can grow far beyond any such law; it is the
  one stage the estimate cannot bound.

A guide within a factor of a few, never a verdict.
"""

from __future__ import annotations

from dataclasses import dataclass

from chaplygin_nd.symbolic.search.cost import duration
from chaplygin_nd.symbolic.search.fields_cost import wall_factor

__all__ = ["PoissonCost", "poisson_cost", "STAGES", "BLOCKS"]

#: the equivariant bivector blocks of one degree (bivector_ansatz.MM_NAMES + MG_NAMES)
BLOCKS = 24
#: the stages of poisson.search_box, as its BoxResult.stages names them
STAGES = ("columns", "column rank and syzygy proofs", "conditions", "kernel", "jacobi equations",
          "groebner", "generic")
C_FIXED, C_COL = 0.05, 6e-5
C_SYZ = 2e-5
C_POINT, C_COND = 1e-3, 1.2e-6
C_GENERIC = 1e-4
C_JACOBI = 1.1e-6


@dataclass(frozen=True)
class PoissonCost:
    """The estimate of one box for one exponent e: sizes and CPU seconds per stage (keys of
    :data:`STAGES`); ``jacobi`` is the Jacobi stage's part, run only if the linear stage leaves
    solutions."""

    n: int
    degree: int
    coordinates: int
    columns: int
    points: int
    stages: dict
    jacobi: float

    @property
    def sure(self) -> float:
        """CPU seconds of the linear stage and its carry to generic (a, b)."""
        return sum(v for k, v in self.stages.items() if k not in ("jacobi equations", "groebner"))

    def cpu(self) -> float:
        """CPU seconds with the Jacobi stage."""
        return self.sure + self.jacobi

    def line(self) -> str:
        """One line: sizes, the CPU estimate without and with the Jacobi stage, the wall bound."""
        f, load = wall_factor()
        return (f"n={self.n} degree={self.degree}: at most {self.columns} unknowns, {self.coordinates} "
                f"coordinates, {self.points} points; CPU about {duration(self.sure)} "
                f"+ {duration(self.jacobi)} if the linear stage leaves solutions (Jacobi, Groebner; "
                f"wall up to {f:.1f}x at load {load:.1f})")


def poisson_cost(n: int, degree: int) -> PoissonCost:
    """The :class:`PoissonCost` of the Hamiltonisation box (n, d), one exponent e (module
    docstring's laws)."""
    if n < 3 or degree < 0:
        raise ValueError(f"(n, d) = ({n}, {degree}): need n >= 3, d >= 0")
    N = n * (n - 1) // 2 + n
    U = BLOCKS * (degree + 1)
    P = 2 * (U // N) + 6
    jac = C_JACOBI * U**3 * (N / 10) ** 4
    stages = {
        "columns": C_FIXED + C_COL * U * N * N,
        "column rank and syzygy proofs": C_SYZ * U * N * N,
        "conditions": P * (C_POINT * N + C_COND * U * N * N),
        "kernel": 0.0,
        "jacobi equations": jac,
        "groebner": 0.0,
        "generic": C_GENERIC * U * N * N,
    }
    return PoissonCost(n, degree, N, U, P, stages, jac)
