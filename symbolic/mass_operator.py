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
    that arithmetic's). Domain: any $\gamma\in\mathbb{R}^n$, diagonal $\mathbb{J}$, any $b$.

    The entry in row $(k, l)$, column $(i, j)$ of the rolling term is the coordinate $(k, l)$ of
    $((E_i\wedge E_j)\gamma)\wedge\gamma = \gamma_j E_i\wedge\gamma - \gamma_i E_j\wedge\gamma$,
    $\gamma_j(\delta_{ki}\gamma_l - \delta_{li}\gamma_k) - \gamma_i(\delta_{kj}\gamma_l - \delta_{lj}\gamma_k)$:
    every term carries a Kronecker delta between $\{k, l\}$ and $\{i, j\}$, so the entries of
    disjoint pairs are $b \cdot 0$ (computed once); the others are written with the deltas
    resolved ($\delta\,t$ is ``t`` or ``zero``, exactly $1 \cdot t$ or $0 \cdot t$ in each arithmetic)."""
    n = len(gamma)
    pairs = _pairs(n)

    def g(p):  # gamma_p, or its derivative d gamma_p / d gamma_m
        return gamma[p] if derivative is None else (one if p == derivative else zero)

    def dt(p, q, t):  # delta_pq * t
        return t if p == q else zero * t

    disjoint = b * (zero * zero - zero * zero)
    rows = []
    for k, l in pairs:
        row = []
        for i, j in pairs:
            if k != i and k != j and l != i and l != j:
                row.append(disjoint)
                continue
            # coordinate (k, l) of ((E_i ^ E_j) gamma) ^ gamma = gamma_j E_i^gamma - gamma_i E_j^gamma
            if derivative is None:
                entry = gamma[j] * (dt(k, i, gamma[l]) - dt(l, i, gamma[k])) \
                    - gamma[i] * (dt(k, j, gamma[l]) - dt(l, j, gamma[k]))
            else:  # product rule on the two gamma factors
                entry = g(j) * (dt(k, i, gamma[l]) - dt(l, i, gamma[k])) \
                    + gamma[j] * (dt(k, i, g(l)) - dt(l, i, g(k))) \
                    - g(i) * (dt(k, j, gamma[l]) - dt(l, j, gamma[k])) \
                    - gamma[i] * (dt(k, j, g(l)) - dt(l, j, g(k)))
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
