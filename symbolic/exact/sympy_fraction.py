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
    ``ValueError``, as does a power with a negative exponent of zero.

    A node is a pair (numerator, denominator) with ``None`` for the denominator 1 (no product by
    one); a sum of polynomials is accumulated in one dictionary (``+`` copies its left operand,
    quadratic in the number of terms); the rational factors of a product are multiplied as
    numbers and applied once (``mul_ground``)."""
    R = K.ring
    dom = R.domain
    index = {s: i for i, s in enumerate(R.symbols)}
    memo: dict = {}

    def total(polys):
        if len(polys) == 1:
            return polys[0]
        p = R.zero                            # a fresh element: accumulated in place
        get, zero = p.get, dom.zero
        for q in polys:
            for k, v in q.items():
                v = get(k, zero) + v
                if v:
                    p[k] = v
                else:
                    p.pop(k, None)
        return p

    def add(terms):
        polys, groups = [], []                # groups: [denominator, [numerators]]
        for n, d in terms:
            if d is None:
                polys.append(n)
                continue
            for group in groups:
                if group[0] == d:
                    group[1].append(n)
                    break
            else:
                groups.append([d, [n]])
        if not groups:
            return total(polys), None
        den = groups[0][0]
        for d, _ in groups[1:]:
            den = den * d.exquo(den.gcd(d))   # lcm, by exact division
        parts = [total(polys) * den] if polys else []
        for d, ns in groups:
            q = den.exquo(d)
            parts.append(total(ns) * q if q != R.one else total(ns))
        return total(parts), den

    def product(polys):
        out = polys[0]
        for p in polys[1:]:
            out = out * p
        return out

    def walk(e):
        hit = memo.get(e)
        if hit is not None:
            return hit
        if e.is_Symbol:
            if e not in index:
                raise ValueError(f"symbol {e} is not one of the generators")
            out = (R.gens[index[e]], None)
        elif e.is_Rational:
            out = (R(e), None)
        elif e.is_Add:
            out = add([walk(t) for t in e.args])
        elif e.is_Mul:
            coeff, nums, dens = dom.one, [], []
            for t in e.args:
                if t.is_Rational:
                    coeff *= dom.from_sympy(t)
                    continue
                n, d = walk(t)
                nums.append(n)
                if d is not None:
                    dens.append(d)
            num = product(nums) if nums else R.one
            if coeff != dom.one:
                num = num.mul_ground(coeff)
            out = (num, product(dens) if dens else None)
        elif e.is_Pow and e.exp.is_Integer:
            n, d = walk(e.base)
            k = int(e.exp)
            if k < 0:
                if not n:
                    raise ValueError(f"division by zero in {e}")
                n, d, k = (R.one if d is None else d), n, -k
            out = (n ** k, None if d is None else d ** k)
        else:
            raise ValueError(f"not a rational function over Q: {type(e).__name__} in {e}")
        memo[e] = out
        return out

    num, den = walk(sp.sympify(expr))
    return K.new(num, R.one if den is None else den)
