r"""From one $(a, b)$ to generic ones: the semicontinuity of the nullity (row S6:first-integrals).

**Statement.** Let a box $S$ (of either strategy) be settled at $(a_0, b_0)$: $\dim V(a_0, b_0) =
\dim K(a_0, b_0)$, $V$ the integrals in $S$ and $K \subseteq V$ the span of the known products.
Then $V(a, b) = K(a, b)$ and $\dim V(a, b) = \dim V(a_0, b_0)$ for every $(a, b)$ outside a proper
algebraic subset of the parameter plane (for **generic** $(a, b)$).

**Argument.** (i) $F = P/D^k$ with $P \in S$ is an integral iff $\Delta\,X_N(P) - kP\,X_N(\Delta)
\equiv 0$ modulo $\lVert\gamma\rVert^2 - 1$, with $X_N$ the field with $\Omega$ replaced by its
numerator $N = 2(2+a+b)\Delta\,L_\gamma^{-1}(M)$ (P:inversion). If the entries of $N$ are
polynomials in $(a, b)$ (checked below), the matrix $L(a, b)$ of this linear map, in the fixed
bases of $S$ and of the standard monomials, has entries in $\mathbb{Q}[a, b]$, and
$\dim V(a, b) = \dim S - \mathrm{rank}\,L(a, b)$. A minor of $L$ that is non-zero at
$(a_0, b_0)$ is a non-zero polynomial, so non-zero outside its zero set: $\mathrm{rank}\,L(a, b) \ge
\mathrm{rank}\,L(a_0, b_0)$, i.e. $\dim V(a, b) \le \dim V(a_0, b_0)$ generically (the nullity is
upper semicontinuous). (ii) Likewise the known products: their numerators, scaled by non-zero
constants in the point ($2 + a + b$ for $H$), are polynomials in $(a, b)$ (checked below), so the rank
of their coefficient matrix is at least its value at $(a_0, b_0)$ generically:
$\dim K(a, b) \ge \dim K(a_0, b_0)$. (iii) Hence generically $\dim V(a, b) \le \dim V(a_0, b_0) =
\dim K(a_0, b_0) \le \dim K(a, b) \le \dim V(a, b)$: equality throughout. A finite union of proper
algebraic subsets is one: the statement holds for all the boxes of a table at once.

It says nothing about the excluded set (e.g. $a = 0$, where the field has more symmetry): a
statement at a particular $(a, b)$ needs its own run. A second run at another $(a, b)$ that finds
the same numbers is consistent with (iii), not a proof of it; the proof is (i)–(ii).
"""

from __future__ import annotations

import sympy as sp

__all__ = ["polynomial_in_parameters"]


def polynomial_in_parameters(n: int) -> dict:
    r"""The checks (i)–(ii) of the module docstring at dimension $n$ (axisymmetric sphere),
    exactly in SymPy with symbolic $a, b$, $M$, $\gamma$: the entries of $N$, $\Delta$, the numerator
    $\tfrac12\langle M, N\rangle$ of $H$ (times the point-independent $2(2+a+b)$), and for odd $n$
    the numerators of $F$ and $F_2$ are polynomials in $(a, b)$. Returns the names checked and
    ``ok``."""
    from chaplygin_nd.symbolic.algebra import skew_symbols, vector_symbols
    from chaplygin_nd.symbolic.axisym_inverse import inverse_numerator
    from chaplygin_nd.symbolic.search import found_integral

    a, b = sp.symbols("a b")
    M, g = skew_symbols("m", n), sp.Matrix(vector_symbols("g", n))
    N = inverse_numerator(M, g, a, b)
    checks = {"N = 2(2+a+b) Delta L^-1(M)": all(sp.expand(e).is_polynomial(a, b) for e in N),
              "Delta": found_integral.denominator(g, a, b).is_polynomial(a, b),
              "2 D H = <M, N>": sp.expand(sum(M[i, j] * N[i, j] for i in range(n)
                                              for j in range(i + 1, n))).is_polynomial(a, b)}
    if n % 2:
        num, _ = found_integral.new_integral(M, g, a, b)
        checks["numerator of F"] = num.is_polynomial(a, b)
        v = found_integral.pfaffian_vector(M)
        vg = (v.T * g)[0, 0]
        x = g[n - 1]
        num2 = a * (a + 2) * v[n - 1] ** 2 + 2 * a * b * x * v[n - 1] * vg + b * (b + 2) * vg**2
        checks["numerator of F2"] = sp.expand(num2).is_polynomial(a, b)
    return {"checked": sorted(checks), "ok": all(checks.values()), "n": n}
