r"""$L_\gamma^{-1}$ for the axisymmetric sphere, derived by an equivariant ansatz (P:inversion).

The stabiliser of $(\gamma, E_n)$ in $O(n)$ commutes with $L_\gamma$ (eq:action), so $L_\gamma^{-1}$
lies in the span of the natural linear maps $\mathfrak{so}(n) \to \mathfrak{so}(n)$ built from
$\gamma$ and $E_n$:

.. math::
    T_0 = M,\; T_1 = (M\gamma)\wedge\gamma,\; T_2 = (ME_n)\wedge E_n,\; T_3 = (M\gamma)\wedge E_n,\;
    T_4 = (ME_n)\wedge\gamma,\; T_5 = \langle M\gamma, E_n\rangle\, \gamma\wedge E_n.

We solve $L_\gamma\big(\sum_k c_k T_k(M)\big) = M$ for all $M$ for unknown $c_k \in \mathbb{Q}(a, b, x)$
by exact linear algebra in $\mathfrak{so}(4)$ with $\gamma = (0, 0, s, x)$, $s^2 = 1 - x^2$
(:func:`inverse_coefficients`). The identity for every $n$ and every $\gamma \in S^{n-1}$ is then
*proved* in proofs/s4_inversion.py (symbolic $n = 3, 4, 5$ plus the reduction argument).
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp
from chaplygin_nd.symbolic.algebra import skew_symbols, wedge
from chaplygin_nd.symbolic.axisymmetric import Delta, E_n, L_gamma_axisym, a, b, x

__all__ = ["ansatz_terms", "inverse_coefficients", "inverse_closed_form", "inverse_denominator",
           "inverse_numerator", "TERM_NAMES"]

#: LaTeX names of the ansatz terms, in order.
TERM_NAMES = (r"M", r"(M\gamma)\wedge\gamma", r"(ME_n)\wedge E_n", r"(M\gamma)\wedge E_n",
              r"(ME_n)\wedge\gamma", r"\langle M\gamma, E_n\rangle\,\gamma\wedge E_n")


def ansatz_terms(M: sp.Matrix, gamma: sp.Matrix) -> list[sp.Matrix]:
    r"""The six equivariant maps $T_0(M), \dots, T_5(M)$ of the ansatz for $L_\gamma^{-1}$ (P:inversion);
    $M \in \mathfrak{so}(n)$, $\gamma \in \mathbb{R}^n$, any $n \ge 3$."""
    e = E_n(M.rows)
    Mg, Me = M * gamma, M * e
    return [M, wedge(Mg, gamma), wedge(Me, e), wedge(Mg, e), wedge(Me, gamma),
            (e.T * Mg)[0, 0] * wedge(gamma, e)]


@lru_cache(maxsize=1)
def inverse_coefficients() -> tuple[sp.Expr, ...]:
    r"""The unique $c_0, \dots, c_5 \in \mathbb{Q}(a, b, x)$ with $L_\gamma(\sum c_k T_k(M)) = M$ in
    $\mathfrak{so}(4)$ at $\gamma = (0, 0, s, x)$, $s^2 = 1 - x^2$ (P:inversion). Factored rational
    functions of the symbols ``a, b, x`` of :mod:`symbolic.axisymmetric`."""
    s = sp.Symbol("s", positive=True)
    n = 4
    M = skew_symbols("m", n)
    gamma = sp.Matrix([0, 0, s, x])
    cs = sp.symbols("c0:6")
    Omega = sum((c * T for c, T in zip(cs, ansatz_terms(M, gamma), strict=True)), sp.zeros(n, n))
    residual = L_gamma_axisym(Omega, gamma, a, b) - M
    m_syms = sorted(M.free_symbols, key=sp.default_sort_key)
    equations = []
    for entry in residual:
        poly = sp.Poly(sp.expand(entry), *m_syms, s)
        # reduce modulo s^2 = 1 - x^2: collect the coefficients of s^0 and s^1 for each m-monomial
        reduced: dict[tuple, sp.Expr] = {}
        for (*mon, ks), coeff in poly.terms():
            key = (tuple(mon), ks % 2)
            reduced[key] = reduced.get(key, 0) + coeff * (1 - x**2) ** (ks // 2)
        equations += [sp.expand(v) for v in reduced.values()]
    equations = [e for e in equations if e != 0]
    A, rhs = sp.linear_eq_to_matrix(equations, cs)
    from sympy.polys.matrices import DomainMatrix

    dA = DomainMatrix.from_Matrix(A.row_join(rhs)).to_field()
    rref, pivots = dA.rref()
    if tuple(pivots) != tuple(range(len(cs))):
        raise ArithmeticError("the ansatz does not determine L_gamma^{-1} uniquely")
    sol = rref.to_Matrix()[: len(cs), -1]
    return tuple(sp.factor(c) for c in sol)


def inverse_closed_form(M: sp.Matrix, gamma: sp.Matrix, a_=a, b_=b) -> sp.Matrix:
    r"""$\Omega = L_\gamma^{-1}(M) = \sum_k c_k(a, b, x)\, T_k(M)$ (P:inversion), $x = \gamma_n$;
    valid for $\gamma \in S^{n-1}$ with $\Delta(x)(2+a+b) \neq 0$, any $n \ge 3$."""
    xval = gamma[gamma.rows - 1]
    sub = {a: a_, b: b_, x: xval}
    # xreplace: the simultaneous replacement of the three symbols, as subs(..., simultaneous=True)
    # gives, without subs's pattern machinery (30x faster; a fifth of the Th:Re rows' time)
    coeffs = [c.xreplace(sub) for c in inverse_coefficients()]
    terms = ansatz_terms(M, gamma)
    return sum((c * T for c, T in zip(coeffs, terms, strict=True)), sp.zeros(M.rows, M.rows))


def inverse_denominator(a_=a, b_=b, x_=x) -> sp.Expr:
    r"""$D = 2\Delta(x)(2+a+b)$: a common denominator of the coefficients $c_k$ (P:inversion)."""
    return 2 * Delta(x_, a_, b_) * (2 + a_ + b_)


@lru_cache(maxsize=1)
def _numerator_coefficients() -> tuple[sp.Expr, ...]:
    D = inverse_denominator()
    out = tuple(sp.factor(sp.cancel(c * D)) for c in inverse_coefficients())
    for c in out:
        sp.Poly(c, a, b, x)  # raises PolynomialError unless D cleared every denominator
    return out


def inverse_numerator(M: sp.Matrix, gamma: sp.Matrix, a_=a, b_=b) -> sp.Matrix:
    r"""$D\,L_\gamma^{-1}(M) = \sum_k (D c_k)\, T_k(M)$ with $D$ of :func:`inverse_denominator` at
    $x = \gamma_n$: polynomial in $M, \gamma, a, b$ (for fast exact identities, P:inversion)."""
    sub = {a: a_, b: b_, x: gamma[gamma.rows - 1]}
    coeffs = [sp.expand(c.xreplace(sub)) for c in _numerator_coefficients()]
    terms = ansatz_terms(M, gamma)
    return sum((c * T for c, T in zip(coeffs, terms, strict=True)), sp.zeros(M.rows, M.rows)).applyfunc(sp.expand)
