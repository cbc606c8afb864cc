r"""Beyond the paper: its second open problem, measured for $n = 6$ (row S6:open-reduced-n6).

The torus dimension of the reduced motion on $P/SO(5)$ ($\dim = 10$, 7 independent invariant
integrals with $H_2, H_3$ of S6:wedge-integrals, independent by S6:wedge-independence: level sets of dimension 3), read by GALI on the
quotient and the NAFF count on the $SO(5)$-invariant signals, with the rule and the control of
:func:`proofs.s6_torus_dimension.torus_verdict` (one mechanism for $n = 6, 7, 8$; its docstring says
why the rule of S6:open-reduced-n5 left this row ``open``: its control did not separate on the
diffusion on $P$).
"""

from __future__ import annotations

from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.proofs.s6_open_reduced_n5 import SECTION
from chaplygin_nd.proofs.s6_torus_dimension import USES, torus_verdict


@claim("S6:open-reduced-n6", uses=USES,
       adds=(SECTION, "the paper's second open problem measured for n = 6: the torus dimension of "
                      "the reduced motion (floor(n/2) = 3 predicted) by GALI on the quotient and the "
                      "NAFF count on drawn orbits, with a chaotic control that separates on both"))
def s6_open_reduced_n6() -> Verdict:
    return torus_verdict(6)
