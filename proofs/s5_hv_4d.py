r"""S5:HV4D — the horizontal and vertical sets in block notation, and their dimension.

**Claim (lines 783-789).** $\mathcal{H} = \{x^2k + \langle k,q\rangle q - xq\times u = 0,\ (1-x^2)u - xk\times q
- \langle u,q\rangle q = 0\}$ and $\mathcal{V} = \{\langle u,q\rangle = 0,\ k\times q + xu = 0\}$ are
the sets $M - (M\gamma)\wedge\gamma = 0$ and $M\gamma = 0$ of eq:def-H-V; both are 6-dimensional
(and invariant).

In our words: the blocks of $M - (M\gamma)\wedge\gamma$ are exactly the two printed vectors (on
$S^3$), and $M\gamma = (k\times q + xu, -\langle u,q\rangle)$. Dimension: since
$\langle q, x^2k + Eq - xq\times u\rangle = E$ on $S^3$, the first equation says $E = 0$ and
$x(xk - q\times u) = 0$; for $x\ne0$ it is $k = q\times u/x$, which makes the second equation an
identity on $S^3$. So $\mathcal{H}\cap\{x\ne0\}$ is the graph of $k = q\times u/x$ over
$\{(u,q,x)\}\cong\mathbb{R}^3\times(S^3\setminus\{x=0\})$: dimension 6. Likewise
$\mathcal{V}\cap\{x\ne0\}$ is the graph of $u = -k\times q/x$ (then $\langle u, q\rangle = 0$
automatically): dimension 6. The slices $x = 0$ are of lower dimension.

**Uses** eq:def-H-V, eq:motion-n4, eq:inverse-Leg (derived field, for invariance). **Proves** the
identities exactly (modulo $\lVert\gamma\rVert^2=1$); invariance exactly at 6 seeded rational points of
each set (the derived field evaluated exactly). $n = 4$.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.proofs.s5_common import exact, horizontal_point, on_P, phase_point, subs_point
from chaplygin_nd.symbolic import fourd
from chaplygin_nd.symbolic.algebra import wedge
from chaplygin_nd.symbolic.exact.identity import zero_at_points
from chaplygin_nd.symbolic.printed import section5 as printed

a, b, x, k, u, q = fourd.a, fourd.b, fourd.x, fourd.k, fourd.u, fourd.q
Z = (*k, *u, *q, x)


def _d(p, r):
    return (p.T * r)[0, 0]


def _vertical_point(rng):
    while True:
        pt = phase_point(rng)
        if pt["x"] != 0:
            pt["u"] = -pt["k"].cross(pt["q"]) / pt["x"]
            return pt


def _invariance(constraints, point, label):
    """X(c) = 0 at exact points of the set, for each constraint component c."""
    field = fourd.field()
    cs = [c for group in constraints for c in (group if isinstance(group, sp.MatrixBase)
                                               else [group])]
    grads = [[sp.diff(c, z) for z in Z] for c in cs]

    def residual(pt):
        sub = subs_point(pt)
        X = [f.xreplace(sub) for f in field]
        return [sp.expand(sum(g.xreplace(sub) * Xz for g, Xz in zip(row, X, strict=False))) for row in grads]
    return zero_at_points(residual, point, count=6, label=label, describe="the set, x != 0")


@claim("S5:HV4D", uses=("eq:def-H-V", "eq:motion-n4", "eq:inverse-Leg"))
def s5_hv4d() -> Verdict:
    M = sp.Matrix(fourd.block(tuple(k), tuple(u)))
    g = sp.Matrix([*q, x])
    W = M - wedge(M * g, g)
    (v1, v2, v3), w = fourd.unblock(W.tolist())
    Mg = M * g
    h1, h2 = printed.H_set(k, u, q, x)
    c1, c2 = printed.V_set(k, u, q, x)
    E = _d(k, q)
    qxu = q.cross(u)
    return Verdict.all_of([
        ("H eq. 1 = hat-block of M - (M g)^g", on_P(h1 - sp.Matrix([v1, v2, v3]), "HV H1")),
        ("H eq. 2 = column block", on_P(h2 - sp.Matrix(w), "HV H2")),
        ("V: <u,q> = -(M g)_4", exact(c1 + Mg[3], "HV V1")),
        ("V: k x q + x u = (M g)_{1..3}", exact(c2 - Mg[:3, 0], "HV V2")),
        ("<q, H eq. 1> = E on S^3", on_P(_d(q, h1) - E, "HV dim1")),
        ("H eq. 1 = x (x k - q x u) + E q", exact(h1 - x * (x * k - qxu) - E * q, "HV dim2")),
        ("H eq. 2 vanishes where x k = q x u", on_P(
            (1 - x**2) * u - qxu.cross(q) - _d(u, q) * q, "HV dim3")),
        ("V: <k x q, q> = 0", exact(_d(k.cross(q), q), "HV dim4")),
        ("H invariant", _invariance((h1, h2), horizontal_point, "HV inv H")),
        ("V invariant", _invariance((c1, c2), _vertical_point, "HV inv V")),
    ], n_values=(4,), method=(
        "exact identities modulo |gamma|^2 = 1 (blocks of M - (M gamma)^gamma and M gamma; graph "
        "description k = q x u/x, u = -k x q/x giving dimension 6); invariance exact at 6 seeded "
        "rational points of each set"))
