r"""S5:SO3-action and eq:PrincMinors — the $SO(3)$ symmetry and the invariants.

**Claims (lines 816-842).** $h\cdot(k,u,(q,x)) = (hk, hu, (hq, x))$, $h\in SO(3)$; by eq:inverse-Leg
$(\xi,\eta)\mapsto(h\xi,h\eta)$, so eq:motion-n4 is equivariant; "points where $k, u, q$ are
parallel have a one-dimensional isotropy subgroup isomorphic to $SO(2)$". The invariants satisfy
$\delta^2 = \det\Lambda$ and $AB - F_1^2 \ge 0$, $B(1-x^2) - G^2 \ge 0$, $A(1-x^2) - E^2 \ge 0$.

In our words: equivariance holds (printed inverse at rational rotations; derived field
infinitesimally, which suffices as $SO(3)$ is connected). The isotropy statement misses one
stratum: at $k = u = 0$, $q = 0$ (so $x = \pm1$: $M = 0$, $\gamma = \pm E_4$) the three vectors are
(trivially) parallel and the isotropy is all of $SO(3)$. Corrected: the isotropy algebra is
$\ker[\hat k;\hat u;\hat q]$, of dimension 3, 1, 0 when $\dim\operatorname{span}\{k,u,q\}$ is 0, 1,
$\ge 2$; the isotropy group is $SO(3)$, $SO(2)$ (rotations about the common line), trivial.
The inequalities are Lagrange identities: the three minors equal $\lVert k\times u\rVert^2$,
$\lVert u\times q\rVert^2$, $\lVert k\times q\rVert^2$ on $S^3$. (With $A, B, 1-x^2 \ge 0$ and
$\det\Lambda = \delta^2 \ge 0$ these are all principal minors, so $\Lambda \succeq 0$ and every point
of $\mathcal{R}$ is the image of some $(k,u,q,x)$, the sign of $\delta$ fixing the orientation.)

**Uses** eq:action, eq:inverse-Leg, eq:motion-n4. **Proves** exact identities (for 3 seeded
rational rotations, symbolic in $k,u,q,x$; infinitesimal generators for the derived field);
isotropy dimensions exactly at explicit and seeded points of each stratum. $n = 4$.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.proofs.s5_common import exact, on_P
from chaplygin_nd.symbolic import fourd
from chaplygin_nd.symbolic.algebra import hat
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.exact.identity import Check, Counterexample
from chaplygin_nd.symbolic.printed import section5 as printed

a, b, x, k, u, q = fourd.a, fourd.b, fourd.x, fourd.k, fourd.u, fourd.q
R = fourd.RV


EPS = sp.Symbol("epsilon")


STATE = (*k, *u, *q, x)
VELOCITY = (*fourd.xi, *fourd.eta)


def _generator(e) -> tuple[sp.Matrix, sp.Matrix]:
    r"""The infinitesimal printed action of $\hat e \in \mathfrak{so}(3)$: the $10\times10$ matrix of
    $\frac{d}{d\epsilon}$ of line 819 on $(k, u, q, x)$ and the $6\times6$ one of lines 821-822 on
    $(\xi, \eta)$, at $h = 1 + \epsilon\hat e$ (first order is all a generator needs)."""
    h = sp.eye(3) + EPS * hat(list(e))
    moved = sp.Matrix([c for m in printed.action(h, k, u, q, x) for c in sp.Matrix([m])])
    moved_v = sp.Matrix([c for m in printed.velocity_action(h, fourd.xi, fourd.eta) for c in m])
    Y = moved.diff(EPS).subs(EPS, 0).jacobian(STATE)
    Yv = moved_v.diff(EPS).subs(EPS, 0).jacobian(VELOCITY)
    return Y, Yv


def _generator_checks():
    """dN[Y_e] = Y_e N for the derived (xi, eta) and the derived field, e = E1, E2, E3, with Y_e
    the generator of the printed action (a linear map; the field transforms by its differential)."""
    Nxi, Neta = fourd.xi_eta_numerators()
    kd, ud, qd, xd = fourd.field_numerators()
    field = [*kd, *ud, *qd, xd]
    velocity = [*Nxi, *Neta]
    ring_state = [*R["k"], *R["u"], *R["q"], R["x"]]
    residues = []
    for i in range(3):
        Y, Yv = _generator([1 if j == i else 0 for j in range(3)])
        if Y.free_symbols or Yv.free_symbols:
            return Check(False, "the printed action is not linear in (k, u, q, x) / (xi, eta)",
                         Counterexample((("e", i + 1),), sp.Matrix.vstack(Y, Yv)[0], "generator"))
        tangent = [sum(fourd.RING(Y[r, c]) * ring_state[c] for c in range(10)) for r in range(10)]

        def d(f, tangent=tangent):
            return sum(f.diff(z) * t for z, t in zip(ring_state, tangent, strict=False))

        residues += [d(field[r]) - sum(fourd.RING(Y[r, c]) * field[c] for c in range(10))
                     for r in range(10)]
        residues += [d(velocity[r]) - sum(fourd.RING(Yv[r, c]) * velocity[c] for c in range(6))
                     for r in range(6)]
    bad = [r for r in residues if r]
    return Check(not bad, "exact sparse-polynomial identities dN[Y_e] = Y_e N for the generators "
                          "Y_e of the printed action (lines 819, 821) (xi, eta and all 10 field "
                          "components)")


def _isotropy_dim(kk, uu, qq, xx):
    """3 - rank of the infinitesimal printed action X -> d/de h.(k, u, q, x) at h = 1 + e X."""
    cols = []
    for i in range(3):
        e = [1 if j == i else 0 for j in range(3)]
        h = sp.eye(3) + EPS * hat(e)
        moved = printed.action(h, kk, uu, qq, xx)
        cols.append([sp.diff(c, EPS).subs(EPS, 0) for m in moved for c in sp.Matrix([m])])
    return 3 - sp.Matrix(cols).T.rank()


def _strata_points(rng):
    """Exact points of the three strata: (point, dim span{k,u,q})."""
    v = sp.Matrix(points.rationals(rng, 3, 1, 3))
    g = points.sphere_point(rng, 4)
    w = sp.Matrix(points.rationals(rng, 3, -3, 3))
    line = g[:3, 0] if g[:3, 0] != sp.zeros(3, 1) else v
    return [((sp.zeros(3, 1), sp.zeros(3, 1), sp.zeros(3, 1), 1), 0),
            ((2 * line, -line / 3, line, g[3]), 1),
            ((v, 2 * v, sp.zeros(3, 1), -1), 1),
            ((w, v, g[:3, 0], g[3]), 2),
            # span of dimension 2 with two of the three parallel (each pair in turn)
            ((w, 2 * line, line, g[3]), 2), ((2 * line, w, line, g[3]), 2),
            ((v, 2 * v, line, g[3]), 2)]


def _isotropy(printed_rule: bool) -> Check:
    """Compare the isotropy dimension with the printed rule (or our correction) at every point;
    the residual lists the difference at all of them, so any change of the rule shows."""
    corrected = {0: 3, 1: 1, 2: 0}   # our correction: dim span{k,u,q} -> dim isotropy
    diffs, first = [], None
    for seed in range(3):
        for (kk, uu, qq, xx), r in _strata_points(points.generator(points.ledger_seed(), "iso", seed)):
            got = _isotropy_dim(kk, uu, qq, xx)
            want = printed.isotropy_dimension(kk, uu, qq, xx) if printed_rule else corrected[r]
            diffs.append(sp.Integer(got - want))
            if got != want and first is None:
                first = (("k", kk.T), ("u", uu.T), ("q", qq.T), ("x", xx))
    how = ("exact rank of the infinitesimal printed action at the pole (M=0, gamma=E_4) and at 3 "
           "seeded points of each stratum dim span{k,u,q} = 0, 1, 2 (for 2: also with each pair "
           "of k, u, q parallel)")
    if first is not None:
        return Check(False, how, Counterexample(first, sp.Matrix([diffs]).T,
                                                f"dim isotropy - claimed dim at all {len(diffs)} points"))
    return Check(True, how)


@claim("S5:SO3-action", uses=("eq:action", "eq:inverse-Leg", "eq:motion-n4"))
def so3_action() -> Verdict:
    rot = []
    for i in range(3):
        h = points.rational_rotation(points.generator(points.ledger_seed(), "S5 rot", i), 3)
        hk, hu, hq, hx = printed.action(h, k, u, q, x)
        xi0 = printed.xi_of(k, u, q, x, a, b)
        eta0 = printed.eta_of(k, u, q, x, a, b)
        hxi, heta = printed.velocity_action(h, xi0, eta0)
        res = [printed.xi_of(hk, hu, hq, hx, a, b) - hxi, printed.eta_of(hk, hu, hq, hx, a, b) - heta]
        rot.append(exact(sp.Matrix.vstack(*res), f"SO3 rot {i}"))
    rot_check = next((c for c in rot if not c), rot[0])
    isotropy = Verdict.decide(
        _isotropy(printed_rule=True), n_values=(4,), corrected=_isotropy(printed_rule=False),
        kind="scope", remark="The printed rule (k, u, q parallel => isotropy SO(2)) holds except at the two points k = u = q = 0 (M = 0, gamma = +-E_4), which it does not exclude; there the isotropy is all of SO(3).",
        printed_latex=r"k, u, q \text{ parallel} \Rightarrow \text{isotropy} \cong SO(2)",
        correction_latex=(r"\operatorname{iso}(k,u,q,x) \cong \begin{cases} SO(3) & k = u = q = 0 "
                          r"\ (M = 0,\ \gamma = \pm E_4)\\ SO(2) & \dim\operatorname{span}\{k,u,q\} = 1"
                          r"\\ \{1\} & \text{otherwise}\end{cases}"))
    return Verdict.of_parts([
        Verdict.all_of([("printed (xi, eta) at 3 rational rotations", rot_check)],
                       n_values=(4,)).as_part("(xi, eta) -> (h xi, h eta) from eq:inverse-Leg"),
        Verdict.all_of([("infinitesimal", _generator_checks())], n_values=(4,)).as_part(
            "equations equivariant (derived field)"),
        isotropy.as_part("isotropy"),
    ], n_values=(4,))


@claim("eq:PrincMinors", uses=("S5:SO3-action",))
def princ_minors() -> Verdict:
    dot = lambda p, r: (p.T * r)[0, 0]  # noqa: E731
    A, B, E, G, F1 = dot(k, k), dot(u, u), dot(k, q), dot(u, q), dot(k, u)
    delta = dot(q, k.cross(u))
    m1, m2, m3 = printed.princ_minors(A, B, E, G, F1, x)
    sq = lambda v: dot(v, v)  # noqa: E731
    return Verdict.all_of([
        ("delta^2 = det Lambda", on_P(delta**2 - printed.Lambda(A, B, E, G, F1, x).det(), "PM det")),
        ("AB - F1^2 = |k x u|^2", exact(m1 - sq(k.cross(u)), "PM 1")),
        ("B(1-x^2) - G^2 = |u x q|^2", on_P(m2 - sq(u.cross(q)), "PM 2")),
        ("A(1-x^2) - E^2 = |k x q|^2", on_P(m3 - sq(k.cross(q)), "PM 3")),
    ], n_values=(4,), method="exact polynomial identities in (k,u,q,x) modulo |gamma|^2 = 1 "
                             "(Lagrange identities: the minors are sums of squares)")
