"""Heavier exact confirmations of Section 4 beyond what the ledger budget allows.

The ledger proves the linear identities with symbolic n = 3 (generic gamma) and n = 4 (gamma in
the SO(n-1) frame) plus the reduction argument. Here the same identities are re-proved with a
*fully generic* symbolic gamma at n = 4 and n = 5, where the frame argument is not needed.
"""

from __future__ import annotations

import pytest
import sympy as sp
from chaplygin_nd.proofs.s4_common import a, b, gamma_symbols
from chaplygin_nd.symbolic.algebra import skew_symbols
from chaplygin_nd.symbolic.axisym_inverse import (
    inverse_closed_form,
    inverse_denominator,
    inverse_numerator,
)
from chaplygin_nd.symbolic.axisymmetric import E_n, L_gamma_axisym
from chaplygin_nd.symbolic.exact.identity import rational_identity
from chaplygin_nd.symbolic.printed import section4 as printed
from chaplygin_nd.symbolic.vertical import vertical_point, zeta


def _upper(R: sp.Matrix) -> list:
    n = R.rows
    return [R[i, j] for i in range(n) for j in range(i, n)]


@pytest.mark.slow
@pytest.mark.parametrize("n", (4, 5))
def test_derived_inverse_solves_L_with_generic_gamma(n):
    M, g = skew_symbols("m", n), gamma_symbols(n)
    R = L_gamma_axisym(inverse_numerator(M, g), g) - inverse_denominator(x_=g[n - 1]) * M
    assert rational_identity(_upper(R.applyfunc(sp.expand)), sphere=tuple(g))


@pytest.mark.slow
@pytest.mark.parametrize("n", (4, 5))
def test_printed_inverse_with_generic_gamma(n):
    M, g = skew_symbols("m", n), gamma_symbols(n)
    R = printed.Omega_inverse(M, g, a, b) - inverse_closed_form(M, g)
    assert rational_identity(_upper(R), sphere=tuple(g))


@pytest.mark.slow
def test_theorem_zeta_with_generic_gamma_n4():
    g = gamma_symbols(4)
    M0 = vertical_point(skew_symbols("A", 4), g).applyfunc(sp.expand)
    z = printed.zeta_Th_Re(M0, g, a, b)
    assert rational_identity(_upper(z - zeta(M0, g)), sphere=tuple(g))
    assert rational_identity(list(z * E_n(4)), sphere=tuple(g))
