r"""eq:V-velocity — the vertical space in terms of the angular velocity.

Claim (lines 512-518): on $S^{n-1}$,

.. math::
    \mathcal{V} = \{M\gamma = 0\} = \{(\Omega, \gamma) : (2+b)\Omega\gamma + ax\Omega E_n = 0
    \ \text{and}\ \langle\Omega\gamma, E_n\rangle = 0\}, \qquad M = L_\gamma(\Omega).

How. We prove the identity (modulo $\lVert\gamma\rVert^2 = 1$, every $\Omega$)

.. math::
    L_\gamma(\Omega)\gamma = \big[(2+b)\Omega\gamma + ax\Omega E_n\big] + a\langle\Omega\gamma, E_n\rangle E_n,
    \qquad \big\langle (2+b)\Omega\gamma + ax\Omega E_n, E_n\big\rangle = (2+b)\langle\Omega\gamma, E_n\rangle .

If both printed conditions hold, the first identity gives $M\gamma = 0$. Conversely, if
$M\gamma = 0$, pairing the first identity with $E_n$ and using the second gives
$(2+a+b)\langle\Omega\gamma, E_n\rangle = 0$, so both conditions hold (this is eq:aux-inversion).
The second identity also shows that the second printed condition is implied by the first
(for $b \ne -2$): it is redundant, though not wrong. Both identities are linear in $\Omega$:
symbolic $n = 3, 4$ and the reduction argument cover every $n$; seeded exact points of both
descriptions ($n \le 12$) are checked as well.

Uses: eq:M-O-axi-symm, eq:aux-inversion, eq:def-H-V.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.proofs.s4_common import (
    REDUCTION,
    a,
    b,
    combine,
    random_point,
    sym_checks,
    sym_gamma,
)
from chaplygin_nd.symbolic.algebra import skew_symbols
from chaplygin_nd.symbolic.axisym_inverse import inverse_closed_form
from chaplygin_nd.symbolic.axisymmetric import E_n, L_gamma_axisym
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.exact.identity import point_engines, zero_at_points
from chaplygin_nd.symbolic.printed import section4 as printed


def _identity(n: int):
    Omega, g = skew_symbols("w", n), sym_gamma(n)
    c1, c2 = printed.V_velocity(Omega, g, a, b)
    e = E_n(n)
    return list(L_gamma_axisym(Omega, g) * g - (c1 + a * c2 * e)) + [(e.T * c1)[0, 0] - (2 + b) * c2]


def _V_to_velocity(p: dict):
    Om = inverse_closed_form(p["M"], p["gamma"], p["a"], p["b"])
    c1, c2 = printed.V_velocity(Om, p["gamma"], p["a"], p["b"])
    return list(c1) + [c2]


def _velocity_point(rng, n: int) -> dict:
    """Omega annihilating u = (2+b) gamma + a x E_n: Omega = P_u A P_u; both printed conditions hold."""
    p = random_point(rng, n)
    g, e = p["gamma"], E_n(n)
    u = (2 + p["b"]) * g + p["a"] * g[n - 1] * e
    P = sp.eye(n) - u * u.T / (u.T * u)[0, 0]
    p["Omega"] = P * p["M"] * P
    return p


def _velocity_to_V(p: dict):
    c1, c2 = printed.V_velocity(p["Omega"], p["gamma"], p["a"], p["b"])
    M = L_gamma_axisym(p["Omega"], p["gamma"], p["a"], p["b"])
    return list(c1) + [c2] + list(M * p["gamma"])


@claim("eq:V-velocity", uses=("eq:M-O-axi-symm", "eq:aux-inversion", "eq:def-H-V"))
def eq_v_velocity() -> Verdict:
    ident = sym_checks(_identity, (3, 4), label="Vvel")
    pts = combine(
        [zero_at_points(_V_to_velocity, lambda r, n=n: random_point(r, n, vertical=True), count=1,
                        label=f"V->vel-{n}", engines=point_engines(n)) for n in points.all_n(3)]
        + [zero_at_points(_velocity_to_V, lambda r, n=n: _velocity_point(r, n), count=1,
                          label=f"vel->V-{n}", engines=point_engines(n)) for n in points.all_n(3)],
        method=f"exact at seeded rational points of each description, n = {points.n_text(points.all_n(3))}")
    return Verdict.of_parts([
        Verdict.decide(ident, method=ident.method + "; " + REDUCTION).as_part(
            "M gamma = [(2+b) Omega gamma + a x Omega E_n] + a <Omega gamma, E_n> E_n"),
        Verdict.decide(pts).as_part("both inclusions at exact points"),
    ], n_values=(3, 4, points.ALL_N_MAX), notes="The second condition <Omega gamma, E_n> = 0 is implied by the "
                                  "first (its E_n-component is (2+b)<Omega gamma, E_n>): redundant.")
