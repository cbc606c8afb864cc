r"""Emit verified SymPy expressions as *expression builders*: straight-line Python over any arithmetic.

The NumPy kernels of ``generated/`` evaluate a derived formula on float arrays. A JIT such as
heyoka (Taylor integrators and compiled functions, LLVM) needs the same formula as an expression
graph of its own. ``generated/expression_builders.py`` holds, for each selected kernel, one function

.. code-block:: python

    def reduced_field(r, a, b, ops):
        A, B, E, G, F1, x, delta = r
        _t0 = ...            # the common subexpressions of sympy.cse, in canonical order
        return [...]         # the outputs, row-major

that uses only ``+ - * /``, integer literals and ``ops.rational(p, q)`` (exact rational constants;
a float literal would be rounded to double before a multiprecision integrator sees it),
``ops.sqrt``. Called with heyoka expressions it builds heyoka expressions; called with floats or
mpmath numbers it evaluates (the tests use this to check the builders against the NumPy kernels
without heyoka). The file imports nothing, so ``generated/`` imports without heyoka installed.

The expressions are the *derived* ones the NumPy kernels are emitted from (the same ``Kernel``
objects of :mod:`symbolic.codegen.emit`), never printed formulas. Output is deterministic, with a banner
(producer, claims, SHA-256 of the inputs, operation counts) and the stale check of ``make verify``.
"""

from __future__ import annotations

import hashlib

import sympy as sp
from sympy.printing.str import StrPrinter

__all__ = ["BUILDERS", "render_builders", "BuilderPrinter"]

#: (producer "module:function" returning Kernel objects, names of the kernels to emit as builders).
BUILDERS: tuple[tuple[str, tuple[str, ...]], ...] = (
    ("chaplygin_nd.symbolic.codegen.emit.axisym:kernels", ("inverse_coefficients", "Delta", "structured_field_weights",
                                                                "vector_field_axisym_4d",
                                      "energy_axisym_4d")),
    ("chaplygin_nd.symbolic.codegen.emit.reduced:kernels", ("reduced_field", "reduced_integrals")),
    ("chaplygin_nd.symbolic.codegen.emit.reduced5:kernels", ("reduced5_field",)),
    ("chaplygin_nd.symbolic.codegen.emit.sphere3d:kernels", ("vector_field_3d", "integrals_3d")),
)

STEM = "expression_builders"

#: Builders whose outputs are emitted with each numerator collected over the monomials of the state
#: (the first argument), coefficients polynomials in the parameters: fewer nonlinear terms for a
#: Taylor integrator, where a product of two series costs O(order) per order and a product with a
#: parameter O(1). Measured on the reduced field (tol 1e-13, T = 50): heyoka decomposition 217 -> 121
#: terms, run 0.26 -> 0.17 ms. An identity of rational functions (numerator expanded and regrouped).
COLLECT = frozenset({"reduced_field", "reduced5_field"})


def collected(expr: sp.Expr, symbols) -> sp.Expr:
    """``expr`` = N/D with N regrouped as a sum over monomials of ``symbols`` (coefficients
    polynomials in the other symbols), D as ``sympy.together`` gives it (the same rational function)."""
    num, den = sp.fraction(sp.together(expr))
    if num == 0:
        return sp.Integer(0)
    poly = sp.Poly(sp.expand(num), *symbols)
    regrouped = sp.Add(*[c * sp.Mul(*[s**e for s, e in zip(symbols, m)]) for m, c in poly.terms()])
    return regrouped / den  # no sp.factor: on the 3D determinant it runs for minutes


class BuilderPrinter(StrPrinter):
    """Plain Python arithmetic: integer powers as products or ``1/(...)``, rationals as
    ``ops.rational(p, q)``, square roots as ``ops.sqrt``; anything else is refused."""

    def _print_Rational(self, expr):
        return f"ops.rational({expr.p}, {expr.q})"

    def _print_Integer(self, expr):
        return str(expr.p)

    def _print_Float(self, expr):  # pragma: no cover - the derived fields are exact
        raise TypeError(f"float constant {expr} in a derived expression")

    def _print_Pow(self, expr, rational=False):
        base, exp = expr.as_base_exp()
        b = self.parenthesize(base, sp.printing.precedence.PRECEDENCE["Pow"])
        if exp == sp.Rational(1, 2):
            return f"ops.sqrt({self._print(base)})"
        if exp.is_Integer and 1 < int(exp) <= 8:
            return "*".join([b] * int(exp))
        if exp.is_Integer and int(exp) < 0:
            return f"1/({self._print(base ** (-exp))})"
        raise TypeError(f"power {expr} is not supported by the builders")

    def _print_Function(self, expr):  # pragma: no cover - the derived fields are rational
        raise TypeError(f"function {expr.func} is not supported by the builders")


def _emit(k) -> tuple[str, int]:
    printer = BuilderPrinter()
    outputs = list(k.outputs)
    if k.name in COLLECT:
        outputs = [collected(e, k.arguments[0].symbols) for e in outputs]
    replacements, reduced = sp.cse(outputs, symbols=sp.numbered_symbols("_t"), order="canonical")
    ops = sum(sp.count_ops(e) for _, e in replacements) + sum(sp.count_ops(e) for e in reduced)
    args = ", ".join(a.name for a in k.arguments)
    lines = [f"def {k.name}({args}, ops):",
             f'    r"""{k.doc.strip()}',
             "",
             "    Builder: arguments as objects with + - * / (components of an array argument as a",
             f"    sequence), ``ops`` with ``rational(p, q)`` and ``sqrt``; returns the {len(outputs)} outputs",
             f"    row-major, shape {k.shape!r}. Claims: {', '.join(k.claims)}. Operations after CSE: {ops}.",
             '    """']
    for a in k.arguments:
        if not a.scalar:
            lines.append(f"    {', '.join(s.name for s in a.symbols)}, = {a.name}")
        elif a.symbols[0].name != a.name:
            lines.append(f"    {a.symbols[0].name} = {a.name}")
    for sym, expr in replacements:
        lines.append(f"    {sym} = {printer.doprint(expr)}")
    lines.append("    return [")
    lines += [f"        {printer.doprint(e)}," for e in reduced]
    lines.append("    ]")
    return "\n".join(lines) + "\n", ops


HEADER = '''r"""Expression builders of the derived fields, for JIT back ends (heyoka) and exact evaluation.

GENERATED by symbolic/codegen/builders.py (codegen version {version}) -- DO NOT EDIT BY HAND.
Regenerate with `make generate`; `make verify` fails when this file is stale.
Producers: {producers}
Claims: {claims}
Source hash (sha256 of the kernel inputs): {digest}
Operation counts after CSE: {counts}

Each function is straight-line Python over any arithmetic (see symbolic/codegen/builders.py):
heyoka expressions build a heyoka expression graph, floats or mpmath numbers evaluate. This file
imports nothing.
"""
'''


def render_builders(kernels_of, version: str) -> str:
    """The text of ``generated/expression_builders.py``; ``kernels_of(producer)`` returns the
    Kernel list of a producer (shared with the NumPy emission, so each is derived once)."""
    bodies, counts, fingerprints, claims = [], [], [version, repr(sorted(COLLECT))], set()
    for producer, names in BUILDERS:
        chosen = {k.name: k for k in kernels_of(producer)}
        for name in names:
            k = chosen[name]
            body, ops = _emit(k)
            bodies.append(body)
            counts.append(f"{name}={ops}")
            fingerprints.append(k.fingerprint())
            claims.update(k.claims)
    digest = hashlib.sha256("\n\n".join(fingerprints).encode()).hexdigest()
    head = HEADER.format(version=version, producers=", ".join(p for p, _ in BUILDERS),
                         claims=", ".join(sorted(claims)), digest=digest, counts=", ".join(counts))
    return head + "\n\n" + "\n\n".join(bodies)
