"""symbolic.exact.sympy_fraction: the SymPy engine's one-cancellation reading of an expression equals
``FracField.from_expr`` (numerator and denominator), and refuses what is not a rational function."""

import pytest
import sympy as sp
from chaplygin_nd.symbolic.exact import identity
from chaplygin_nd.symbolic.exact.sympy_fraction import reduced_fraction
from sympy.polys.fields import field
from sympy.polys.orderings import lex

x, y, z, a = sp.symbols("x y z a")
GENS = [z, y, x, a]

CASES = [
    sp.Integer(0),
    sp.Rational(-3, 7),
    x,
    (x**2 - y**2) / (x - y),                                   # cancels to x + y
    1 / (x - y) + 1 / (y - x),                                 # zero
    x / (a + 1) - (x * a + x) / (a + 1) ** 2,                  # zero after cancelling a + 1
    (1 / x + 1 / y) / (x + y),                                 # = 1/(x y)
    sp.Rational(2, 3) * (x + 1) ** 3 / (3 * (x + 1) * y) - (x + 1) ** 2 / (sp.Rational(9, 2) * y),
    -(x - y) ** -2 * (y - x) ** 3,                             # negative powers, sign
    ((x + y) / (x - z)) ** 3 + a / (z - x) ** 2 + sp.Rational(5, 4),
    (a * x + a * y) / (2 * a * z) - (x + y) / (2 * z) + x**2 * y / (x * y),
]


@pytest.mark.parametrize("expr", CASES, ids=range(len(CASES)))
def test_equals_from_expr(expr):
    K, *_ = field(GENS, sp.QQ, lex)
    mine, theirs = reduced_fraction(K, expr), K.from_expr(expr)
    assert (mine.numer, mine.denom) == (theirs.numer, theirs.denom)


@pytest.mark.parametrize("expr", [x + sp.Float(0.5), sp.sqrt(x), sp.sin(x), x**y, x + sp.Symbol("w"),
                                  sp.I * x])
def test_not_a_rational_function(expr):
    K, *_ = field(GENS, sp.QQ, lex)
    with pytest.raises(ValueError):
        reduced_fraction(K, expr)


def test_negative_power_of_zero():
    K, *_ = field(GENS, sp.QQ, lex)
    with pytest.raises(ValueError, match="division by zero"):
        reduced_fraction(K, sp.Pow(sp.Add(x, -x, evaluate=False), -1, evaluate=False))


def test_numerator_polynomial_on_the_sphere():
    """The engine's entry point: an identity on the circle (numerator in the ideal) and one off."""
    g1, g2 = sp.symbols("g1 g2")
    gens = [g2, g1, a]
    num, den = identity.numerator_polynomial((g1**2 + g2**2 - 1) * a / (a + 1), gens, (g1, g2))
    assert not num
    num, den = identity.numerator_polynomial(g1**2 / (a + 1), gens, (g1, g2))
    assert num and den == den.ring(a + 1)
