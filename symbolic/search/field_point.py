r"""The field $X$ of eq:motion-general and its Jacobian at a rational point of
$P = \mathfrak{so}(n)\times S^{n-1}$, exact in FLINT's ``fmpq`` (for the symmetry-field search,
symbolic/search/symmetry_fields.py): $\Omega = L_\gamma^{-1}M$, $\dot M = [M, \Omega]$,
$\dot\gamma = -\Omega\gamma$, and $\partial\Omega = L_\gamma^{-1}(\partial M -
\partial L_\gamma\,\Omega)$."""

from __future__ import annotations

import flint
from chaplygin_nd.symbolic.algebra import so_basis, vec
from chaplygin_nd.symbolic.axisymmetric import mass_tensor
from chaplygin_nd.symbolic.model import L_matrix, L_matrix_derivative
from chaplygin_nd.symbolic.search.point_values import fq as _fq

__all__ = ["field_and_jacobian"]


def field_and_jacobian(n, a, b, M, gamma):
    r"""$X$ (eq:motion-general, $J = \mathrm{Id} + aE_nE_n^T$, $L_\gamma$ with $b$) and its exact Jacobian at the
    rational point $(M, \gamma)$, $\gamma$ on the sphere: (values, columns $\partial X/\partial z_l$), coordinates
    $z$ = the upper triangle of $M$ then $\gamma$."""
    J = mass_tensor(n, a)
    L = flint.fmpq_mat([[_fq(v) for v in row] for row in L_matrix(gamma, J, b).tolist()])
    Li = L.inv()
    mv = flint.fmpq_mat([[_fq(v)] for v in vec(M)])
    w = Li * mv
    m = len(so_basis(n))
    Om = _unvec([w[i, 0] for i in range(m)], n)
    Mq = _unvec([_fq(v) for v in vec(M)], n)
    gq = [_fq(v) for v in gamma]
    X = _field(Mq, Om, gq, n)
    cols = []
    for l in range(m + n):
        if l < m:
            dM = [flint.fmpq(0)] * m
            dM[l] = flint.fmpq(1)
            dw = Li * flint.fmpq_mat([[v] for v in dM])
            dg = [flint.fmpq(0)] * n
        else:
            k = l - m
            dL = flint.fmpq_mat([[_fq(v) for v in row] for row in L_matrix_derivative(gamma, b, k).tolist()])
            dw = -(Li * (dL * w))
            dM = [flint.fmpq(0)] * m
            dg = [flint.fmpq(0)] * n
            dg[k] = flint.fmpq(1)
        dOm = _unvec([dw[i, 0] for i in range(m)], n)
        dMm = _unvec(dM, n)
        top = _vecq(_mm(dMm, Om, n), n, sub=_mm(Om, dMm, n))
        top2 = _vecq(_mm(Mq, dOm, n), n, sub=_mm(dOm, Mq, n))
        bot = [-(sum((dOm[i][j] * gq[j] for j in range(n)), flint.fmpq(0))
                 + sum((Om[i][j] * dg[j] for j in range(n)), flint.fmpq(0))) for i in range(n)]
        cols.append([u + v for u, v in zip(top, top2, strict=True)] + bot)
    return X, cols


def _unvec(c, n):
    A = [[flint.fmpq(0)] * n for _ in range(n)]
    idx = 0
    for i in range(n):
        for j in range(i + 1, n):
            A[i][j], A[j][i] = c[idx], -c[idx]
            idx += 1
    return A


def _mm(A, B, n):
    return [[sum((A[i][k] * B[k][j] for k in range(n)), flint.fmpq(0)) for j in range(n)] for i in range(n)]


def _vecq(A, n, sub):
    return [A[i][j] - sub[i][j] for i in range(n) for j in range(i + 1, n)]


def _field(Mq, Om, gq, n):
    top = _vecq(_mm(Mq, Om, n), n, sub=_mm(Om, Mq, n))
    bot = [-sum((Om[i][j] * gq[j] for j in range(n)), flint.fmpq(0)) for i in range(n)]
    return top + bot
