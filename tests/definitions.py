"""Definitions the tests compare the toolkit's functions with, written from the textbook
formula and nothing else (no toolkit code)."""

from __future__ import annotations

import itertools
from math import factorial

import sympy as sp
from sympy.combinatorics import Permutation


def pfaffian(A: sp.Matrix) -> sp.Expr:
    """Pf(A) = 1/(2^m m!) sum over permutations s of sgn(s) prod_i A[s(2i), s(2i+1)] (size 2m);
    0 for an odd size (a skew matrix of odd size is singular, and no pairing exists)."""
    size = A.rows
    if size % 2:
        return sp.Integer(0)
    total = sp.Integer(0)
    for perm in itertools.permutations(range(size)):
        total += Permutation(list(perm)).signature() * sp.prod(
            A[perm[2 * i], perm[2 * i + 1]] for i in range(size // 2))
    return total / (2 ** (size // 2) * factorial(size // 2))
