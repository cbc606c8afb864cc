r"""eq:inverse-Leg — $(\xi, \eta)$ as functions of $(k, u, q, x)$.

**Claim (lines 804-805).**

.. math::
    \xi = \frac{b(2+b)(1-x^2)+\Delta}{(a+b+2)\Delta}u - \frac{b(2+b)\langle u,q\rangle}{(a+b+2)\Delta}q
          - \frac{bx}{\Delta}k\times q, \qquad
    \eta = \frac{a+2+bx^2}{\Delta}k + \frac{(a+2)b\langle k,q\rangle}{2\Delta}q + \frac{bx}{\Delta}u\times q.

In our words: the inverse of $L_\gamma$ in block notation, including the factor $\tfrac12$ in the
$\langle k,q\rangle q$ term of $\eta$ (it is right: for $k \parallel q$, $u = 0$ one has $\eta = k/2$).

**Uses** eq:M-O-axi-symm, eq:Delta, S5:ku. **Proves**, by three independent routes: (1) the
derived inverse (:func:`symbolic.fourd.inverse_coefficients`, an exact linear solve of the
equivariant ansatz) satisfies $L_\gamma(\xi,\eta) = (k,u)$ on $S^3$ (sparse polynomial identity);
(2) printed = derived, exact identity modulo $\lVert\gamma\rVert^2 = 1$; (3) printed = the exact
$6\times6$ solve of eq:M-O (:func:`symbolic.model.angular_velocity`) at 8 seeded rational points.
$n = 4$.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.proofs.s5_common import on_P, phase_point, ring_on_P
from chaplygin_nd.symbolic import fourd
from chaplygin_nd.symbolic.exact.identity import zero_at_points
from chaplygin_nd.symbolic.model import angular_velocity
from chaplygin_nd.symbolic.printed import section5 as printed

a, b, x, k, u, q = fourd.a, fourd.b, fourd.x, fourd.k, fourd.u, fourd.q
R = fourd.RV


def _six_by_six(pt):
    a_, b_, x_, k_, u_, q_ = (pt[n] for n in ("a", "b", "x", "k", "u", "q"))
    M = sp.Matrix(fourd.block(tuple(k_), tuple(u_)))
    gamma = sp.Matrix([*q_, x_])
    J = sp.eye(4) + a_ * sp.diag(0, 0, 0, 1)
    Om = angular_velocity(M, gamma, J, b_)
    eta_s, xi_s = fourd.unblock(Om.tolist())
    return [*(printed.xi_of(k_, u_, q_, x_, a_, b_) - sp.Matrix(xi_s)),
            *(printed.eta_of(k_, u_, q_, x_, a_, b_) - sp.Matrix(eta_s))]


@claim("eq:inverse-Leg", uses=("eq:M-O-axi-symm", "eq:Delta", "S5:ku"))
def inverse_leg() -> Verdict:
    Nxi, Neta = fourd.xi_eta_numerators()
    kk, uu = fourd.L_blocks(Neta, Nxi)
    residues = [p - fourd.D * v for p, v in zip(kk + uu, R["k"] + R["u"], strict=False)]
    checks = [ring_on_P(r, f"inverse-Leg L(inv) {i}") for i, r in enumerate(residues)]
    inverts = next((c for c in checks if not c), checks[0])
    Dx = fourd.D.as_expr()
    xi_res = printed.xi_of(k, u, q, x, a, b) * Dx - sp.Matrix([c.as_expr() for c in Nxi])
    eta_res = printed.eta_of(k, u, q, x, a, b) * Dx - sp.Matrix([c.as_expr() for c in Neta])
    return Verdict.of_parts([
        Verdict.all_of([("L(xi, eta) = (k, u)", inverts)], n_values=(4,)).as_part(
            "derived inverse inverts L_gamma"),
        Verdict.decide(on_P(xi_res, "inverse-Leg xi"), n_values=(4,)).as_part("xi"),
        Verdict.decide(on_P(eta_res, "inverse-Leg eta"), n_values=(4,)).as_part("eta"),
        Verdict.all_of([("6x6 solve", zero_at_points(
            _six_by_six, phase_point, count=8, label="inverse-Leg 6x6",
            describe="P with a in [-1,1], b > 0"))], n_values=(4,)).as_part(
            "printed = exact 6x6 solve of eq:M-O"),
    ], n_values=(4,))
