r"""S5:measure4D — the invariant measure of the explicit 4D equations.

**Claim (line 811).** $\mu = dk\,du\,dq\,dx/\Delta(x)$ is invariant.

In our words, and which coordinates: $dq\,dx$ stands for the round (rotation-invariant) volume
$d\sigma$ of $S^3 \ni (q, x)$ — the $d\gamma$ of eq:invmeasuredet; in the chart $(k, u, q)$ of the
hemisphere $x > 0$ the density is $1/(\Delta(x)\,x)$ because $d\sigma = dq/|x|$ there. It is the
$n = 4$ case of P:Measure ($\Delta^{-(n-2)/2}$ with $dM = dk\,du$).

**Method.** The derived field (:func:`symbolic.fourd.field_numerators`, $X = N/D$) is defined on
$\mathbb{R}^3\times\mathbb{R}^3\times\mathbb{R}^4$ and tangent to every sphere $\lVert\gamma\rVert = r$
(because $\dot q = q\times\eta - x\xi$, $\dot x = \langle q,\xi\rangle$ give
$\tfrac{d}{dt}(\lVert q\rVert^2 + x^2) = 0$ for any $\xi, \eta$). Then, as explained in
:mod:`symbolic.measure`, $\rho\,dk\,du\,d\sigma$ is invariant iff the ambient divergence
$\operatorname{div}(\rho X)$ vanishes on $\lVert\gamma\rVert = 1$. With $\rho/D = f(x)$:
$\operatorname{div}(\rho X) = f\operatorname{div}N + f'(x)N_x$, so the residual is
$\operatorname{den}\cdot\operatorname{div}N + \operatorname{num}\cdot N_x$ where $f'/f = \operatorname{num}/
\operatorname{den}$ — a polynomial identity modulo the sphere.

**Uses** eq:motion-n4, eq:inverse-Leg, P:Measure. **Proves** it exactly for $n = 4$ (and, as a
control, that $\rho = 1$ and $\rho = \Delta^{-2}$ are *not* invariant).
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.proofs.s5_common import ring_on_P
from chaplygin_nd.symbolic import fourd
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.exact.identity import Check, Counterexample
from chaplygin_nd.symbolic.printed import section5 as printed

a, b, x = fourd.a, fourd.b, fourd.x
R = fourd.RV
_Z = (*R["k"], *R["u"], *R["q"], R["x"])


def divergence_residual(rho):
    r"""Numerator of $\operatorname{div}(\rho X)$ for a density $\rho(x)$, as a ring element."""
    kd, ud, qd, xd = fourd.field_numerators()
    N = (*kd, *ud, *qd, xd)
    divN = sum(Nz.diff(z) for z, Nz in zip(_Z, N, strict=False))
    f = rho / fourd.D.as_expr()
    num, den = sp.fraction(sp.cancel(sp.diff(f, x) / f))
    return fourd.RING(sp.expand(den)) * divN + fourd.RING(sp.expand(num)) * xd


@claim("S5:measure4D", uses=("eq:motion-n4", "eq:inverse-Leg", "P:Measure"))
def s5_measure4d() -> Verdict:
    shown = ring_on_P(divergence_residual(printed.measure_density(a, b, x)), "measure4D")
    Delta = printed.Delta(a, b, x)
    # Controls: the same test must reject densities that are not invariant, or it proves nothing.
    controls = []
    for i, (name, r) in enumerate((("rho = 1", sp.Integer(1)), ("rho = Delta^-2", Delta**-2))):
        chk = ring_on_P(divergence_residual(r), f"measure4D control {i}")
        controls.append((f"control: {name} is not invariant",
                         Check(not chk.ok, f"{name}: div(rho X) != 0 ({chk.method})")))
    # A density, not a signed form: positive at seeded exact (x, a, b) in the domain.
    values = []
    for i in range(6):
        rng = points.generator(points.ledger_seed(), "measure4D positive", i)
        par = points.axisymmetric_parameters(rng)
        values.append(printed.measure_density(par["a"], par["b"], points.rational(rng, -1, 1, 8)))
    bad = [v for v in values if not v.is_positive]
    positive = Check(not bad, "exact sign at 6 seeded (x, a, b) in [-1,1] x [-1,1] x (0,4]",
                     Counterexample((("values", tuple(values)),), bad[0], "density <= 0")
                     if bad else None)
    return Verdict.of_parts([
        Verdict.all_of([("1/Delta > 0", positive)], n_values=(4,)).as_part("a positive density"),
        Verdict.decide(shown, n_values=(4,), method=(
            "exact: ambient divergence of rho X (field tangent to all spheres) vanishes modulo "
            "|gamma|^2 = 1; sparse-polynomial normal form")).as_part("1/Delta(x) invariant"),
        Verdict.all_of(controls, n_values=(4,)).as_part("controls (the test rejects rho = 1, "
                                                          "Delta^-2)"),
    ], n_values=(4,), notes="dq dx = round measure of S^3 (chart (k,u,q), x>0: density "
                            "1/(Delta(x) x))")
