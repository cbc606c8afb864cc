"""S5:H-linear-nD beyond the ledger budget: the symbolic identities for n = 5, 6 (frame gamma) and
with a fully generic gamma at n = 3 (the base case of the reduction, without the frame argument).
The ledger row proves n = 3, 4 symbolically plus the reduction argument, and n = 3..12 at seeded
exact points."""

from __future__ import annotations

import pytest
from chaplygin_nd.proofs import s5_horizontal_nd as row
from chaplygin_nd.proofs.s4_common import SAMPLERS
from chaplygin_nd.symbolic.exact.identity import rational_identity

CHECKED = [i for i in range(len(row.NAMES)) if i != row.CONSERVATION]


@pytest.mark.slow
@pytest.mark.parametrize(("n", "generic_gamma"), [(5, False), (6, False), (3, True)])
def test_horizontal_nd_identities_symbolic(n, generic_gamma):
    res, sphere = row._symbolic(n, generic_gamma)
    check = rational_identity([res[i] for i in CHECKED], sphere=sphere, samplers=SAMPLERS,
                              label=f"HnD-slow-n{n}")
    assert check.ok, check.counterexample.text()


def test_horizontal_nd_refutes_a_perturbed_system():
    """Control: G_dot = -omega^2 x + x/7 is refuted by the same engine, with an exact point."""
    res, sphere = row._symbolic(3)
    check = rational_identity([res[1] + sphere[-1] / 7], sphere=sphere, samplers=SAMPLERS,
                              label="HnD-control")
    assert not check.ok and check.counterexample is not None
