r"""eq:SOnminus1 and eq:action — the extra $SO(n-1)$ symmetry of the axisymmetric sphere.

Claims (Section 4.1, lines 486-500):

.. math::
    SO(n-1) = \{h \in SO(n) : hE_n = E_n\} \ \text{(eq:SOnminus1)}, \qquad
    h\cdot(M, \gamma) = (hMh^{-1}, h\gamma) \ \text{(eq:action)},

$\Omega \mapsto h\Omega h^{-1}$ under the action, and eq:motion-general is $SO(n-1)$-equivariant.

In our words: rotations about the symmetry axis commute with $L_\gamma$, hence with
$L_\gamma^{-1}$, and therefore map solutions to solutions.

What is proved. (i) $L_{h\gamma}(h\Omega h^{-1}) = hL_\gamma(\Omega)h^{-1}$ exactly for a *symbolic*
$h$ — the Cayley transform $h = (I - S)^{-1}(I + S)$ of a generic $S \in \mathfrak{so}(n-1)$ (which
covers every rotation without eigenvalue $-1$, a dense set) — for $n = 3$; its infinitesimal form
$L_\gamma([S, \Omega]) + \partial_\gamma L_\gamma(S\gamma)(\Omega) = [S, L_\gamma(\Omega)]$ for generic
$S \in \mathfrak{so}(n-1)$ (which integrates to the connected group) for $n = 3, 4, 5$; and for every $n$ by
naturality (each term of $L_\gamma$ is built from $\Omega$, $\gamma$, $E_n$ with products and wedges,
and $hE_n = E_n$); since $L_\gamma$ is invertible (P:Measure), $L^{-1}_{h\gamma}(hMh^{-1}) =
hL^{-1}_\gamma(M)h^{-1}$. (ii) The same for the derived closed form of $L_\gamma^{-1}$ and for the
vector field $X(M,\gamma) = ([M,\Omega], -\Omega\gamma)$: exact at seeded rational rotations of
$SO(n-1)$ (Cayley of rational skew matrices), $n = 3..12, 16, 20, 24$.

Uses: eq:M-O-axi-symm, P:Measure, P:inversion, eq:motion-general.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.proofs.s4_common import combine, gamma_symbols, random_point, sym_checks
from chaplygin_nd.symbolic.algebra import commutator, skew_symbols
from chaplygin_nd.symbolic.axisym_inverse import inverse_closed_form
from chaplygin_nd.symbolic.axisymmetric import E_n, L_gamma_axisym
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.exact.identity import point_engines, zero_at_points
from chaplygin_nd.symbolic.printed import section4 as printed


def _cayley(S: sp.Matrix) -> sp.Matrix:
    eye = sp.eye(S.rows)
    return (eye - S).inv() * (eye + S)


def _embed(h_small: sp.Matrix, n: int) -> sp.Matrix:
    """h in SO(n-1) acting on the first n-1 coordinates, fixing E_n."""
    h = sp.eye(n)
    h[: n - 1, : n - 1] = h_small
    return h


def _symbolic_h(n: int) -> sp.Matrix:
    return _embed(_cayley(skew_symbols("s", n - 1)), n)


def _rotation_point(rng, n: int) -> dict:
    pt = random_point(rng, n)
    pt["h"] = _embed(points.rational_rotation(rng, n - 1), n)
    return pt


@claim("eq:SOnminus1", uses=(),
       adds=("Section 4 — the axisymmetric sphere",
             "SO(n−1) = {h ∈ SO(n): h Eₙ = Eₙ}; definition used by eq:action"))
def eq_sonminus1() -> Verdict:
    def fixes_axis(p):
        return p["h"] * E_n(p["n"]) - E_n(p["n"])

    def is_rotation(p):
        h = p["h"]
        return list(h.T * h - sp.eye(p["n"])) + [h.det() - 1]

    checks = []
    for n in range(3, 9):
        for fn, lab in ((fixes_axis, "fix"), (is_rotation, "rot")):
            checks.append(zero_at_points(fn, lambda r, n=n: _rotation_point(r, n), count=1,
                                         label=f"SOn1-{lab}-{n}"))
    return Verdict.definition(
        "SO(n-1) = {h in SO(n): h E_n = E_n}; its Lie algebra is {zeta in so(n): zeta E_n = 0}",
        n_values=tuple(range(3, 9)),
        consistency=[("the sampled rotations used by eq:action lie in SO(n-1)",
                      combine(checks, method="exact at seeded Cayley rotations, n = 3..8"))])


def _L_equivariance(n: int):
    h = _symbolic_h(n)
    Omega, g = skew_symbols("w", n), gamma_symbols(n)
    return L_gamma_axisym(h * Omega * h.T, h * g) - h * L_gamma_axisym(Omega, g) * h.T


def _L_infinitesimal(n: int):
    r"""$\frac{d}{dt}\big|_0 \big(L_{e^{tS}\gamma}(e^{tS}\Omega e^{-tS}) - e^{tS}L_\gamma(\Omega)e^{-tS}\big)$
    for a generic $S \in \mathfrak{so}(n-1)$: zero for all $S$ iff $L$ is equivariant under the
    connected group $SO(n-1)$."""
    S = sp.zeros(n, n)
    S[: n - 1, : n - 1] = skew_symbols("s", n - 1)
    Omega, g = skew_symbols("w", n), gamma_symbols(n)
    t = sp.Symbol("t")
    moved = L_gamma_axisym(Omega + t * commutator(S, Omega), g + t * S * g)
    # not expanded: the exact engines read the residual as polynomials
    return moved.diff(t).subs(t, 0) - commutator(S, L_gamma_axisym(Omega, g))


def _inverse_equivariance(p: dict):
    h, M, g, av, bv = p["h"], p["M"], p["gamma"], p["a"], p["b"]
    hM, hg = printed.action(h, M, g)
    return inverse_closed_form(hM, hg, av, bv) - h * inverse_closed_form(M, g, av, bv) * h.T


def _field_equivariance(p: dict):
    h, M, g, av, bv = p["h"], p["M"], p["gamma"], p["a"], p["b"]
    hM, hg = printed.action(h, M, g)
    Om, hOm = inverse_closed_form(M, g, av, bv), inverse_closed_form(hM, hg, av, bv)
    dM, dg = commutator(M, Om), -Om * g
    return list(commutator(hM, hOm) - h * dM * h.T) + list(-hOm * hg - h * dg)


@claim("eq:action", uses=("eq:SOnminus1", "eq:M-O-axi-symm", "P:Measure", "P:inversion",
                          "eq:motion-general"))
def eq_action() -> Verdict:
    L_eq = combine([sym_checks(_L_equivariance, (3,), sphere=False, label="L-equiv"),
                    sym_checks(_L_infinitesimal, (3, 4, 5), sphere=False, label="L-inf")],
                   method="exact symbolic: finite (Cayley h of a generic S) for n = 3; "
                          "infinitesimal (generic S in so(n-1), generic gamma) for n = 3, 4, 5")
    inv_eq = combine([zero_at_points(_inverse_equivariance, lambda r, n=n: _rotation_point(r, n),
                                     count=1, label=f"inv-equiv-{n}", engines=point_engines(n)) for n in points.all_n(3)],
                     method=f"exact at seeded rational (M, gamma, h in SO(n-1)), n = {points.n_text(points.all_n(3))}")
    X_eq = combine([zero_at_points(_field_equivariance, lambda r, n=n: _rotation_point(r, n),
                                   count=1, label=f"X-equiv-{n}", engines=point_engines(n)) for n in points.all_n(3)],
                   method=f"exact at seeded rational (M, gamma, h in SO(n-1)), n = {points.n_text(points.all_n(3))}")
    return Verdict.of_parts([
        Verdict.decide(L_eq, method=L_eq.method + "; naturality covers all n").as_part(
            "L_gamma is SO(n-1)-equivariant"),
        Verdict.decide(inv_eq).as_part("Omega -> h Omega h^{-1}"),
        Verdict.decide(X_eq).as_part("eq:motion-general is equivariant"),
    ], n_values=(3, 4, points.ALL_N_MAX))


