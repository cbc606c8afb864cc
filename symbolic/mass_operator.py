r"""The matrix of $L_\gamma$ (eq:M-O) entry by entry, in whatever arithmetic its inputs are.

One assembly serves the SymPy model (:mod:`symbolic.model`), exact $\mathbb{Q}$ linear algebra
(``DomainMatrix``) and the FLINT engine (:mod:`symbolic.flint_model`), so that neither of the
last two needs the other: the assembly is written once, below both.
"""

from __future__ import annotations

import sympy as sp
from sympy.polys.domains import QQ
from sympy.polys.matrices import DomainMatrix

__all__ = ["L_entries", "L_matrix_qq"]


def _pairs(n: int) -> list[tuple[int, int]]:
    return [(i, j) for i in range(n) for j in range(i + 1, n)]


def L_entries(gamma, Jdiag, b, zero, one, derivative: int | None = None):
    r"""Rows of the matrix of $L_\gamma$ (eq:M-O; or of $\partial L_\gamma/\partial\gamma_m$ for
    ``derivative = m``) in the basis $E_i\wedge E_j$, $i<j$, with entries computed in the
    arithmetic of the inputs (SymPy expressions, QQ or ``fmpq`` elements; ``zero`` and ``one`` are
    that arithmetic's). Domain: any $\gamma\in\mathbb{R}^n$, diagonal $\mathbb{J}$, any $b$."""
    n = len(gamma)
    pairs = _pairs(n)

    def d(p, q):  # Kronecker delta in the input arithmetic
        return one if p == q else zero

    def g(p):  # gamma_p, or its derivative d gamma_p / d gamma_m
        return gamma[p] if derivative is None else d(p, derivative)

    rows = []
    for k, l in pairs:
        row = []
        for i, j in pairs:
            # coordinate (k, l) of ((E_i ^ E_j) gamma) ^ gamma = gamma_j E_i^gamma - gamma_i E_j^gamma
            if derivative is None:
                entry = gamma[j] * (d(k, i) * gamma[l] - d(l, i) * gamma[k]) \
                    - gamma[i] * (d(k, j) * gamma[l] - d(l, j) * gamma[k])
            else:  # product rule on the two gamma factors
                entry = g(j) * (d(k, i) * gamma[l] - d(l, i) * gamma[k]) \
                    + gamma[j] * (d(k, i) * g(l) - d(l, i) * g(k)) \
                    - g(i) * (d(k, j) * gamma[l] - d(l, j) * gamma[k]) \
                    - gamma[i] * (d(k, j) * g(l) - d(l, j) * g(k))
            entry = b * entry
            if derivative is None and (k, l) == (i, j):
                entry = entry + Jdiag[i] + Jdiag[j]
            row.append(entry)
        rows.append(row)
    return rows


def L_matrix_qq(gamma: sp.Matrix, J: sp.Matrix, b, derivative: int | None = None) -> DomainMatrix:
    r"""``L_matrix`` (or ``L_matrix_derivative`` for ``derivative = k``) at an exact rational point,
    as a ``DomainMatrix`` over $\mathbb{Q}$ (fast exact linear algebra for large $n$)."""
    conv = QQ.from_sympy
    rows = L_entries([conv(sp.Rational(x)) for x in gamma],
                      [conv(sp.Rational(x)) for x in J.diagonal()], conv(sp.Rational(b)),
                      QQ.zero, QQ.one, derivative)
    return DomainMatrix(rows, (len(rows), len(rows)), QQ).to_sparse()
