r"""The $SO(4)$-reduced axisymmetric $n = 5$ sphere (row S6:reduced-n5, the paper's open problem, first half).

Derived as :mod:`symbolic.reduction.reduced_n4` derives eq:red-system for $n = 4$: each generator
$f \in \{x, A_\pm, B, G, E_\pm, S_{uu}, S_{uq}, S_{qq}\}$ of :mod:`symbolic.reduction.invariants_n5` is
differentiated along the field on $P = \mathfrak{so}(5)\times S^4$,

.. math::
    D\dot M = [M, D\Omega], \qquad D\dot\gamma = -(D\Omega)\gamma, \qquad
    D\Omega = D\,L_\gamma^{-1}(M) \ \text{(P:inversion, derived: :func:`symbolic.axisym_inverse.inverse_numerator`)},

with $D = 2(2+a+b)\Delta(x)$ (eq:Delta): $D\dot f = \sum_z \partial_z f\, D\dot z$ is an $SO(4)$-invariant
polynomial in $(K, u, q)$ with coefficients in $\mathbb{Q}[a, b, x]$, written in the generators by
:func:`symbolic.reduction.invariants_n5.in_generators` (ansatz over all products of the tridegree, exact
rref over $\mathbb{Q}$), then $s = \lVert q\rVert^2 \to 1 - x^2$. The result is a polynomial vector field
on $\mathbb{R}^{10} \ni r = (x, A_+, A_-, B, G, E_+, E_-, S_{uu}, S_{uq}, S_{qq})$ over $D$; its restriction
to the reduced space (the image of $P$, cut out by the relations $R_1, R_2$ of
:func:`symbolic.reduction.invariants_n5.relations`, with $s = 1 - x^2$) is the reduced dynamics.
"""

from __future__ import annotations

from functools import cache

import sympy as sp
from chaplygin_nd.symbolic.axisym_inverse import inverse_numerator
from chaplygin_nd.symbolic.axisymmetric import a, b, x
from chaplygin_nd.symbolic.reduction import invariants_n5 as ri5

__all__ = ["COORDS", "SYMBOLS", "D", "phase_field_numerators", "raw_derivatives",
           "field_numerators", "field", "relations_on_P"]

#: Coordinates of the ambient $\mathbb{R}^{10}$, in this order.
COORDS = ("x", "Ap", "Am", "B", "G", "Ep", "Em", "Suu", "Suq", "Sqq")
SYMBOLS = {"x": x, **{n: ri5.SYMBOLS[n] for n in COORDS[1:]}}
Delta = (2 + a) * (2 + b) - a * b * x**2
#: The common denominator $D = 2(2+a+b)\Delta(x)$ of $L_\gamma^{-1}$ (P:inversion).
D = 2 * (2 + a + b) * Delta


@cache
def phase_field_numerators():
    r"""$(D\dot M_{ij})_{i<j}$ and $D\dot\gamma$ as elements of :data:`symbolic.reduction.invariants_n5.RING`
    (eq:motion-general with the derived inverse, $n = 5$; valid on $S^4$)."""
    R = ri5.RING
    DO = inverse_numerator(ri5.M, ri5.gamma)          # expanded entries
    W = [[R(DO[i, j]) for j in range(5)] for i in range(5)]
    M = [[R(ri5.M[i, j]) for j in range(5)] for i in range(5)]
    g = [R(v) for v in ri5.gamma]
    Mdot = {(i, j): sum((M[i][k] * W[k][j] - W[i][k] * M[k][j] for k in range(5)), R(0))
            for i in range(5) for j in range(i + 1, 5)}
    gdot = [-sum((W[i][k] * g[k] for k in range(5)), R(0)) for i in range(5)]
    return Mdot, gdot


@cache
def raw_derivatives() -> dict:
    r"""$D\dot f$ for each $f$ of :data:`COORDS`, straight from the field on $P$ (ring elements):
    $D\dot f = \sum_{i<j}\partial_{M_{ij}}f\,D\dot M_{ij} + \sum_k \partial_{q_k}f\,D\dot q_k$, and
    $D\dot x = D\dot\gamma_5$."""
    Mdot, gdot = phase_field_numerators()
    R = ri5.RING
    gens = R.gens
    g = ri5.generator_polys()
    out = {"x": gdot[4]}
    for name in COORDS[1:]:
        f = g[name]
        tot = R(0)
        for k, pair in enumerate((i, j) for i in range(5) for j in range(i + 1, 5)):
            d = f.diff(gens[3 + k])
            if d:
                tot += d * Mdot[pair]
        for k in range(4):
            d = f.diff(gens[13 + k])
            if d:
                tot += d * gdot[k]
        out[name] = tot
    return out


@cache
def field_numerators() -> dict:
    r"""$D\dot f$ for $f$ in :data:`COORDS` in the generators, $s = 1 - x^2$: elements of
    :data:`symbolic.reduction.invariants_n5.INV_RING` (S6:reduced-n5, derived)."""
    return {n: ri5.on_sphere(ri5.in_generators(N)) for n, N in raw_derivatives().items()}


def field() -> dict:
    r"""The reduced field on $\mathbb{R}^{10}$ (S6:reduced-n5): coordinate name -> SymPy rational
    expression in $a, b$ and the coordinates (denominator $D$)."""
    return {n: p.as_expr() / D for n, p in field_numerators().items()}


def relations_on_P() -> list:
    r"""The two relations $R_1$ (tridegree $(2,2,2)$) and $R_2$ ($(4,2,2)$) with $s = 1 - x^2$, as
    SymPy expressions in the coordinates: the reduced space lies in $\{R_1 = R_2 = 0\}$ (S6:reduced-n5)."""
    rel = ri5.relations()
    r1 = rel[(2, 2, 2)][0]
    # the (4,2,2) relation that is not a multiple of R1: the one without A_p*R1 / A_m*R1 shape
    r2 = [r for r in rel[(4, 2, 2)] if ri5.INV_RING(r1.as_expr() * ri5.SYMBOLS["Ap"]) != r
          and ri5.INV_RING(r1.as_expr() * ri5.SYMBOLS["Am"]) != r]
    if len(r2) != 1:
        raise ArithmeticError("expected one new relation in tridegree (4,2,2)")
    return [ri5.on_sphere(r1).as_expr(), ri5.on_sphere(r2[0]).as_expr()]


#: The known integrals (eq:pol-first-integrals, H) by name: the non-constant coefficients of
#: $p(\lambda, \sigma) = \det(M + \sigma\gamma\gamma^T - \lambda)$ and the energy.
INTEGRAL_NAMES = ("c_lambda3", "c_lambda1", "c_sigma_lambda2", "c_sigma_lambda0", "H")


@cache
def _integral_numerators() -> dict:
    from sympy.polys.matrices import DomainMatrix

    lam, sig = sp.symbols("lambda sigma")
    A = DomainMatrix.from_Matrix(ri5.M + sig * ri5.gamma * ri5.gamma.T - lam * sp.eye(5))
    p = sp.Poly(A.domain.to_sympy(A.det()), lam, sig)     # fraction-free det over ZZ[...]
    R = ri5.RING
    out = {}
    for name, mon in zip(INTEGRAL_NAMES[:4], ((3, 0), (1, 0), (2, 1), (0, 1)), strict=True):
        out[name] = ri5.on_sphere(ri5.in_generators(R(p.coeff_monomial(lam**mon[0] * sig**mon[1]))))
    DO = inverse_numerator(ri5.M, ri5.gamma)
    twoDH = sum((ri5.M[i, j] * DO[i, j] for i in range(5) for j in range(i + 1, 5)), sp.Integer(0))
    out["H"] = ri5.on_sphere(ri5.in_generators(R(sp.expand(twoDH))))   # 2 D H
    return out


def integrals() -> dict:
    r"""The five known integrals in the reduced coordinates (S6:reduced-n5): the coefficients of
    $\lambda^3, \lambda^1, \sigma\lambda^2, \sigma\lambda^0$ of $p(\lambda,\sigma)$ (eq:pol-first-integrals;
    $s \to 1 - x^2$) and $H = \tfrac12\langle M, L_\gamma^{-1}M\rangle_\kappa$ (over $2D$); name -> SymPy
    expression in $a, b$ and the coordinates."""
    num = _integral_numerators()
    return {n: (num[n].as_expr() / (2 * D) if n == "H" else num[n].as_expr()) for n in INTEGRAL_NAMES}


__all__ += ["INTEGRAL_NAMES", "integrals"]
