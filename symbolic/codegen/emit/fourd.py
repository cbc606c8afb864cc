r"""Kernels of the axisymmetric 4D sphere in block notation $(k, u, q, x)$ (Section 5, S:4D).

Sources (derived, never printed): :mod:`symbolic.fourd` — the solved inverse $(\xi, \eta)$ of
$(k, u)$ (eq:inverse-Leg derived), the explicit field (eq:motion-n4 + eq:inverse-Leg), the
integrals $F_1, F_2, F_3$ (read off $p(\lambda,\sigma)$) and $H$, the measure density $1/\Delta$
(S5:measure4D) and the velocity form (eq:Motion-Velocity derived). Each rational quantity there is
a numerator over $D = 2(2+a+b)\Delta(x)$; here $\Delta$ is emitted in the stable form of row K:Delta.

Arguments: ``k, u, q`` arrays ``(..., 3)``, ``x`` ``(...)``; domain $\lVert q\rVert^2 + x^2 = 1$,
$|a| \le 1$, $b > 0$ (the derived forms used $\lVert q\rVert^2 = 1 - x^2$).
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.symbolic import fourd
from chaplygin_nd.symbolic.codegen.emit.axisym import stable_Delta
from chaplygin_nd.symbolic.codegen.kernels import Argument, Kernel

__all__ = ["kernels", "stable_D"]

a, b, x = fourd.a, fourd.b, fourd.x


def stable_D() -> sp.Expr:
    r"""$D = 2(2+a+b)\Delta(x)$ with $\Delta$ in the stable form (row K:Delta)."""
    return 2 * (2 + a + b) * stable_Delta(x, a, b)


def _over_D(ring_elements) -> sp.Matrix:
    D = stable_D()
    return sp.Matrix([p.as_expr() / D for p in ring_elements])


def kernels() -> list[Kernel]:
    """The kernel list of ``generated/fourd.py``."""
    K, U, Q = (Argument(name, tuple(v)) for name, v in (("k", fourd.k), ("u", fourd.u), ("q", fourd.q)))
    X, A_, B_ = Argument("x", (x,), True), Argument("a", (a,), True), Argument("b", (b,), True)
    XI, ETA = Argument("xi", tuple(fourd.xi)), Argument("eta", tuple(fourd.eta))
    Nxi, Neta = fourd.xi_eta_numerators()
    xi_, eta_ = _over_D(Nxi), _over_D(Neta)
    # The field and H composed exactly as symbolic.fourd composes them (motion_blocks of (k, u) and
    # the solved (eta, xi); -1/4 tr(M Omega)), but on (xi, eta) kept as common subexpressions:
    # 1565 -> ~400 operations against the expanded numerators of fourd.field_numerators().
    kv, uv, qv = tuple(fourd.k), tuple(fourd.u), tuple(fourd.q)
    kd, ud, qd, xd = fourd.motion_blocks(kv, uv, tuple(eta_), tuple(xi_), qv, x)
    MO = fourd._mm(fourd.block(kv, uv), fourd.block(tuple(eta_), tuple(xi_)))
    H = -sum(MO[i][i] for i in range(4)) / 4
    I = fourd.integrals()
    Nxid, Netad = fourd.velocity_form_numerators()
    return [
        Kernel("xi_eta_4d", ("eq:inverse-Leg", "K:Delta"),
               "(xi, eta) = L_gamma^{-1}(k, u) in block notation (eq:inverse-Leg, derived in\n"
               "    symbolic.fourd); shape (..., 6). Domain |q|^2 + x^2 = 1.",
               (K, U, Q, X, A_, B_), _over_D([*Nxi, *Neta]), (6,)),
        Kernel("field_4d", ("eq:motion-n4", "eq:inverse-Leg", "K:Delta"),
               "(dk, du, dq, dx)/dt of the explicit 4D field (eq:motion-n4 with eq:inverse-Leg, derived);\n"
               "    shape (..., 10). Domain |q|^2 + x^2 = 1.",
               (K, U, Q, X, A_, B_), sp.Matrix([*kd, *ud, *qd, xd]), (10,)),
        Kernel("integrals_4d", ("S5:F123", "S5:H4D", "K:Delta"),
               "(F1, F2, F3, H): F1 = <k,u>, F2 = |k|^2+|u|^2, F3 = -[lambda sigma] p(lambda, sigma),\n"
               "    H = 1/2 <M, Omega>_kappa (S5:F123, S5:H4D, derived). Domain |q|^2 + x^2 = 1 (for H).",
               (K, U, Q, X, A_, B_),
               sp.Matrix([I["F1"], I["F2"], I["F3"], H]), (4,)),
        Kernel("measure_density_4d", ("S5:measure4D", "K:Delta"),
               "1/Delta(x): density of the invariant measure w.r.t. dk du dsigma_{S^3} (S5:measure4D).",
               (X, A_, B_), sp.Matrix([1 / stable_Delta(x, a, b)]), (1,)),
        Kernel("velocity_form_4d", ("eq:Motion-Velocity", "K:Delta"),
               "(dxi/dt, deta/dt) as functions of (xi, eta, q, x) (eq:Motion-Velocity, derived);\n"
               "    shape (..., 6). Domain |q|^2 + x^2 = 1.",
               (XI, ETA, Q, X, A_, B_), _over_D([*Nxid, *Netad]), (6,)),
    ]
