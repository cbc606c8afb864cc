r"""SymPy's reading of an expression into $\mathbb{Q}(x_1,\dots,x_m)$, in lowest terms (route 1 of
:mod:`symbolic.exact.identity`, the SymPy engine).

``FracField.from_expr`` builds the fraction node by node and cancels (a polynomial gcd) after
every addition and multiplication; on the residuals of the ledger's identities that was most of
the SymPy engine's time (P:Measure, S4:structured-field, Th:Re: 3-14x the CPU of the walk below,
measured per call over the whole ledger). :func:`reduced_fraction` instead
walks the expression tree once with SymPy's sparse polynomials (``PolyElement`` over QQ), keeping
each node as an uncancelled numerator/denominator pair (sums over the lcm of their denominators),
and cancels once at the end with the field's own constructor. A fraction in lowest terms is
unique up to a unit and ``FracField.new`` normalises that unit, so the result is the element
``from_expr`` returns (the same numerator and denominator: compared on every call of every ledger
row when this was introduced; tests/test_sympy_fraction.py checks it on its own cases). The
arithmetic stays SymPy's; the FLINT engine (:mod:`symbolic.exact.flint_engine`) still decides
independently.
"""

from __future__ import annotations

import sympy as sp

__all__ = ["reduced_fraction"]


def reduced_fraction(K, expr):
    r"""``expr`` (a SymPy expression) as an element of the fraction field ``K`` (SymPy ``field``
    over QQ; its generators are the symbols ``expr`` may contain), in lowest terms: equal to
    ``K.from_expr(expr)``. Domain: rational functions over $\mathbb{Q}$ of ``K``'s generators
    (rational numbers, the generators, sums, products, integer powers); anything else raises
    ``ValueError``, as does a power with a negative exponent of zero."""
    R = K.ring
    index = {s: i for i, s in enumerate(R.symbols)}
    memo: dict = {}

    def add(terms):
        poly, groups = R.zero, []             # groups: [denominator, numerator sum]
        for n, d in terms:
            if d == R.one:
                poly += n
                continue
            for group in groups:
                if group[0] == d:
                    group[1] += n
                    break
            else:
                groups.append([d, n])
        if not groups:
            return poly, R.one
        den = groups[0][0]
        for d, _ in groups[1:]:
            den = den * d.exquo(den.gcd(d))   # lcm, by exact division
        num = poly * den
        for d, n in groups:
            num += n * den.exquo(d)
        return num, den

    def walk(e):
        hit = memo.get(e)
        if hit is not None:
            return hit
        if e.is_Symbol:
            if e not in index:
                raise ValueError(f"symbol {e} is not one of the generators")
            out = (R.gens[index[e]], R.one)
        elif e.is_Rational:
            out = (R(e), R.one)
        elif e.is_Add:
            out = add([walk(t) for t in e.args])
        elif e.is_Mul:
            num, den = R.one, R.one
            for t in e.args:
                n, d = walk(t)
                num, den = num * n, den * d
            out = (num, den)
        elif e.is_Pow and e.exp.is_Integer:
            n, d = walk(e.base)
            k = int(e.exp)
            if k < 0:
                if not n:
                    raise ValueError(f"division by zero in {e}")
                n, d, k = d, n, -k
            out = (n ** k, d ** k)
        else:
            raise ValueError(f"not a rational function over Q: {type(e).__name__} in {e}")
        memo[e] = out
        return out

    num, den = walk(sp.sympify(expr))
    return K.new(num, den)
