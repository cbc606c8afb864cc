r"""eq:motion-n4 and S5:ku — the 4D equations and $(k, u)$ in block notation.

**Claims.** With $M = \begin{pmatrix}\hat k & u\\ -u^T & 0\end{pmatrix}$,
$\Omega = \begin{pmatrix}\hat\eta & \xi\\ -\xi^T & 0\end{pmatrix}$, $\gamma = (q, x)$:

* eq:motion-n4 — $\dot M = [M,\Omega]$, $\dot\gamma = -\Omega\gamma$ read
  $\dot k = k\times\eta + u\times\xi$, $\dot u = k\times\xi + u\times\eta$, $\dot q = q\times\eta - x\xi$,
  $\dot x = \langle q, \xi\rangle$.
* S5:ku — eq:M-O-axi-symm reads $k = 2\eta + bq\times(\eta\times q) - bx\,\xi\times q$,
  $u = (2+a+b)\xi - bq\times(\xi\times q) + bx\,\eta\times q$.

In our words: the block form of the commutator and of $L_\gamma$ is what the paper prints. The
$k$-formula holds for every $\gamma\in\mathbb{R}^4$; the $u$-formula uses $\lVert q\rVert^2 = 1 - x^2$
(the exact image has $(2+a+bx^2)\xi + b\langle\xi,q\rangle q$), so it holds on $S^3$.

**Uses** eq:motion-general, eq:M-O-axi-symm. **Proves** both by exact polynomial identities
(:func:`symbolic.fourd.motion_blocks`, :func:`symbolic.fourd.L_blocks`: $4\times4$ matrix products),
the second modulo $\lVert\gamma\rVert^2 = 1$. $n = 4$.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.proofs.s5_common import exact, on_P
from chaplygin_nd.symbolic import fourd
from chaplygin_nd.symbolic.printed import section5 as printed

a, b, x, k, u, q, eta, xi = (fourd.a, fourd.b, fourd.x, fourd.k, fourd.u, fourd.q, fourd.eta,
                             fourd.xi)
R = fourd.RV


def _expr(vecs):
    return [sp.Matrix([c.as_expr() for c in v]) if isinstance(v, tuple) else v.as_expr()
            for v in vecs]


@claim("eq:motion-n4", uses=("eq:motion-general",))
def motion_n4() -> Verdict:
    derived = _expr(fourd.motion_blocks(R["k"], R["u"], R["eta"], R["xi"]))
    shown = printed.motion_n4(k, u, q, x, xi, eta)
    names = ("k_dot", "u_dot", "q_dot", "x_dot")
    checks = [(n, exact(sp.Matrix([p - d]) if not isinstance(p, sp.MatrixBase) else p - d,
                        f"motion-n4 {n}")) for n, p, d in zip(names, shown, derived, strict=False)]
    return Verdict.all_of(checks, n_values=(4,), method="exact polynomial identity in "
                          "(k, u, q, x, xi, eta) against [M, Omega] and -Omega gamma in 4x4 blocks")


@claim("S5:ku", uses=("eq:M-O-axi-symm",))
def s5_ku() -> Verdict:
    kd, ud = _expr(fourd.L_blocks(R["eta"], R["xi"]))
    return Verdict.all_of([
        ("k (any gamma)", exact(printed.k_of(eta, xi, q, x, a, b) - kd, "ku k")),
        ("u (on S^3)", on_P(printed.u_of(eta, xi, q, x, a, b) - ud, "ku u")),
    ], n_values=(4,), method="exact polynomial identities against L_gamma(Omega) computed with 4x4 "
                             "matrices; u modulo |q|^2 + x^2 = 1")
