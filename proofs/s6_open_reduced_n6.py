r"""Beyond the paper: its second open problem, measured for $n = 6$ (row S6:open-reduced-n6).

The same measurement and the same rule as row S6:open-reduced-n5 (:func:`proofs.s6_open_reduced_n5.open_problem_verdict`,
one mechanism for every $n$), in dimension 6.

**What integrability would predict (derived, exactly, at a seeded rational point).** $P = \mathfrak{so}(6)
\times S^5$ has dimension 20; the $SO(5)$-orbits have dimension 10, so $\dim P/SO(5) = 10$. The
non-constant coefficients of $p(\lambda, \sigma)$ ($\lambda^4, \lambda^2, \lambda^0, \sigma\lambda^3,
\sigma\lambda^1$) and $H$ are 6 invariant integrals of rank 6 on $TP$: regular reduced level sets of
dimension 4. If the reduced system were integrable (quasi-periodic on tori filling or foliating
the level sets): at most 4 reduced frequencies, at most $4 + \operatorname{rank}SO(5) = 6$ on $P$.
The issue's conjecture (tori of dimension $\lfloor n/2\rfloor = 3$, as at $a = 0$) needs
$10 - 3 = 7$ integrals: one more than known.

**Measured** on ``OPEN_COUNTS[6]`` = 16 drawn orbits (the draw ``S6:open-reduced-n6``; the same
$(a, b)$, energies, $T = 4096$, $dt = 1/2$, tolerance as $n = 5$) and 4 orbits of the non-symmetric
sphere ``CHAOTIC_J[6]``; the $n = 4$ control is the 200 orbits of S5:reconstruction. Fewer orbits than
$n = 5$ (100) to keep the row's cold cost near 30 s; the counts are stated in the row.

**Rule** (that of S6:open-reduced-n5, fixed before this run; an 8-orbit timing pilot of the $n = 6$
draw had been seen, and the control tensor was chosen by the rule of
:data:`simulate.analysis.control.CANDIDATE_J` on its own pilot draw): ``evidence`` iff at most 2 % of the
orbits are MEGNO-chaotic, at least 90 % MEGNO-regular, at most 2 % of the resolved orbits exceed the
bounds above, and both controls separate; otherwise ``open`` with the numbers. Never ``holds``.
"""

from __future__ import annotations

from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.proofs.s6_open_reduced_n5 import SECTION, open_problem_verdict


@claim("S6:open-reduced-n6", uses=("eq:pol-first-integrals", "P:Measure", "eq:action",
                                    "S5:EJ-tori", "S5:reconstruction"),
       adds=(SECTION, "the paper's second open problem measured for n = 6 (the rule of "
                      "S6:open-reduced-n5): frequency count, diffusion and MEGNO on 16 drawn orbits, "
                      "with the integrable n = 4 sphere and a non-symmetric n = 6 sphere as controls"))
def s6_open_reduced_n6() -> Verdict:
    return open_problem_verdict(6)
