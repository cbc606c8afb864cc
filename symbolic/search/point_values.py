r"""Exact values at a rational point of $P$ shared by the searches (symbolic/search/poisson.py,
symbolic/search/generic_extension.py): rationals as FLINT ``fmpq``, a bivector's matrix from its
upper-triangle polynomials, and $\partial_\gamma H$."""

from __future__ import annotations

import flint
import sympy as sp

__all__ = ["fq", "bivector_values", "dH_gamma"]


def fq(v) -> flint.fmpq:
    """A rational (SymPy, int or str) as ``fmpq``."""
    v = sp.Rational(v)
    return flint.fmpq(int(v.p), int(v.q))


def bivector_values(entries: dict, pt: list, N: int) -> list[list]:
    """The skew N x N matrix of a bivector {(i, j): fmpq_mpoly, i < j} at the point ``pt`` (fmpq)."""
    V = [[flint.fmpq(0)] * N for _ in range(N)]
    for (i, j), f in entries.items():
        v = f(*pt)
        V[i][j], V[j][i] = v, -v
    return V


def dH_gamma(w: list, gamma: list, b, n: int) -> list:
    r"""$\partial_{\gamma_k}H = -\tfrac12\langle\Omega, \partial_{\gamma_k}L_\gamma\,\Omega\rangle$,
    $k = 1..n$, for $\Omega$ with coordinates ``w`` (``fmpq``), exact in FLINT's ``fmpq`` (the entries
    of $\partial L_\gamma$ from symbolic/mass_operator.py, in that arithmetic)."""
    from chaplygin_nd.symbolic.mass_operator import L_entries

    zero, one = flint.fmpq(0), flint.fmpq(1)
    out = []
    for k in range(n):
        D = L_entries(gamma, [zero] * n, b, zero, one, k)
        out.append(-sum((w[r] * sum((D[r][c] * w[c] for c in range(len(w)) if D[r][c] != 0), zero)
                         for r in range(len(w))), zero) / 2)
    return out
