"""The Section 4 proofs have teeth: a one-symbol change to a printed formula flips its row.

Each test replaces one function of symbolic/printed/section4.py by a mutant (a sign, a factor 2,
a missing x_0 — the kind of slip a transcription or the paper could make) and re-runs the row:
it must no longer be `holds`, and it must come with an exact counterexample.
"""

from __future__ import annotations

import pytest
from chaplygin_nd.ledger.catalog import discover
from chaplygin_nd.ledger.registry import registry
from chaplygin_nd.symbolic.algebra import basis_vector, wedge
from chaplygin_nd.symbolic.printed import section4 as printed


def _run(claim_id: str):
    discover()
    return registry()[claim_id].run()


def _E(n):
    return basis_vector(n, n - 1)


def _K_sign(M, gamma, a, b):  # + abx (ME)^gamma flipped to -
    E = _E(M.rows)
    x = (gamma.T * E)[0, 0]
    return (a * b * x * wedge(M * gamma, E) - a * (2 + b) * wedge(M * E, E)
            - a * b * x * wedge(M * E, gamma) - b * (2 + a) * wedge(M * gamma, gamma)
            - a * b * (4 + a + b) * (E.T * M * gamma)[0, 0] / (2 + a + b) * wedge(gamma, E))


def _Delta_sign(x, a, b):
    return (2 + a) * (2 + b) + a * b * x**2


def _zeta_factor(M0, gamma0, a, b):  # 2 Delta -> Delta in the first term
    E = _E(M0.rows)
    x0 = (E.T * gamma0)[0, 0]
    D = printed.Delta(x0, a, b)
    return (-a * (2 + b * (1 - x0**2)) / D * M0
            + (a * (2 + b) * wedge(M0 * E, E) - a * b * x0 * wedge(M0 * E, gamma0)) / (2 * D))


def _xiVnD_no_x0(Omega0, gamma0, a, b):  # gamma_0 - x_0 E_n -> gamma_0 - E_n
    E = _E(Omega0.rows)
    x0 = (E.T * gamma0)[0, 0]
    D = printed.Delta(x0, a, b)
    return (-a * (2 + b * (1 - x0**2)) / D * (Omega0 - wedge(Omega0 * E, E))
            - a * b * x0 / D * wedge(Omega0 * E, gamma0 - E))


@pytest.mark.parametrize("claim_id, name, mutant", [
    ("P:inversion", "K", _K_sign),
    ("eq:Delta", "Delta", _Delta_sign),
    # Th:Re proves twice (~4 CPU-s, the costliest of the four): make test-slow
    pytest.param("Th:Re", "zeta_Th_Re", _zeta_factor, marks=pytest.mark.slow),
    ("eq:xiVnD", "zeta_xiVnD", _xiVnD_no_x0),
])
def test_a_mutated_printed_formula_is_caught(monkeypatch, claim_id, name, mutant):
    assert _run(claim_id).verdict == "holds"
    monkeypatch.setattr(printed, name, mutant)
    v = _run(claim_id)
    assert v.verdict == "fails"
    assert v.counterexample
