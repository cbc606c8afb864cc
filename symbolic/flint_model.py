r"""The model's exact computations at one rational point, in FLINT (``fmpq``, ``fmpq_mat``).

The FLINT engine's side of the heavy point steps of the all-$n$ rows: $L_\gamma$ (eq:M-O) as an
``fmpq_mat``, $\Omega = L_\gamma^{-1}M$, and the ingredients of the ambient divergence of
eq:motion-general (eq:invmeasuredet). :func:`symbolic.model.angular_velocity` and
:func:`symbolic.measure.chaplygin_divergence_at` call these when the current engine is FLINT
(:func:`symbolic.flint_engine.use_engine`); their SymPy side is unchanged, and
:func:`symbolic.exact.zero_at_points` requires the two values to be equal wherever both run.

The divergence is computed here by a different route from the SymPy side (which forms every
$\partial_{\gamma_k}L_\gamma$ as a matrix): $\partial_{\gamma_k}L_\gamma(X) = b\,[(Xe_k)\wedge\gamma
+ (X\gamma)\wedge e_k]$ is applied to the basis elements directly, $O(n^3)$ instead of $O(n^5)$.
Domain: any $n \ge 2$, rational $\gamma$ (not necessarily unit), diagonal rational $\mathbb{J}$,
rational $b$ with $L_\gamma$ invertible.
"""

from __future__ import annotations

import flint
import sympy as sp
from chaplygin_nd.symbolic.flint_engine import current_engine, note_call, to_fmpq, to_sympy_matrix
from chaplygin_nd.symbolic.model import L_matrix_qq, _L_entries

__all__ = ["L_matrix_fmpq", "L_matrix_at", "angular_velocity_fmpq", "divergence_at_fmpq"]

_ZERO, _ONE = flint.fmpq(0), flint.fmpq(1)


def _pairs(n: int) -> list[tuple[int, int]]:
    return [(i, j) for i in range(n) for j in range(i + 1, n)]


def L_matrix_fmpq(gamma, J: sp.Matrix, b) -> flint.fmpq_mat:
    r"""The matrix of $L_\gamma$ (eq:M-O) in the basis $E_i\wedge E_j$, entries in ``fmpq``."""
    rows = _L_entries([to_fmpq(v) for v in gamma], [to_fmpq(v) for v in J.diagonal()],
                      to_fmpq(b), _ZERO, _ONE)
    return flint.fmpq_mat(rows)


def L_matrix_at(gamma: sp.Matrix, J: sp.Matrix, b):
    r"""$L_\gamma$ (eq:M-O) at a rational point in the current engine's own matrix type:
    ``fmpq_mat`` (FLINT) or a sparse ``DomainMatrix`` over QQ (SymPy, ``model.L_matrix_qq``)."""
    note_call()
    if current_engine() == "flint":
        return L_matrix_fmpq(gamma, J, b)
    return L_matrix_qq(gamma, J, b)


def angular_velocity_fmpq(M: sp.Matrix, gamma: sp.Matrix, J: sp.Matrix, b) -> sp.Matrix:
    r"""$\Omega = L_\gamma^{-1}M$ (inverse of eq:M-O) by ``fmpq_mat.solve``; returned as a SymPy
    matrix of rationals. Raises ``ZeroDivisionError`` if $L_\gamma$ is singular."""
    n = gamma.rows
    rhs = flint.fmpq_mat([[to_fmpq(M[i, j])] for i, j in _pairs(n)])
    coords = L_matrix_fmpq(gamma, J, b).solve(rhs)
    return _skew(n, [coords[a, 0] for a in range(coords.nrows())], sympy=True)


def _skew(n: int, coords, sympy: bool = False):
    A = [[_ZERO] * n for _ in range(n)]
    for (i, j), c in zip(_pairs(n), coords):
        A[i][j], A[j][i] = c, -c
    return to_sympy_matrix(flint.fmpq_mat(A)) if sympy else A


def _commutator_entry(A, C, i: int, j: int):
    """Entry (i, j) of AC - CA for dense list matrices."""
    n = len(A)
    return sum((A[i][k] * C[k][j] - C[i][k] * A[k][j] for k in range(n)), _ZERO)


def divergence_at_fmpq(M: sp.Matrix, gamma: sp.Matrix, J: sp.Matrix, b) -> dict:
    r"""The same exact quantities as :func:`symbolic.measure.chaplygin_divergence_at` (``div``,
    ``gamma_dot``, ``Omega``, ``dlogdet``: the ambient divergence of eq:motion-general,
    $\dot\gamma$, $\Omega$ and $\partial_{\gamma_k}\log\det L_\gamma$), computed in FLINT."""
    n = gamma.rows
    pairs = _pairs(n)
    index = {p: a for a, p in enumerate(pairs)}
    g = [to_fmpq(v) for v in gamma]
    bq = to_fmpq(b)
    L = L_matrix_fmpq(gamma, J, b)
    L_inv = L.inv()
    m = flint.fmpq_mat([[to_fmpq(M[i, j])] for i, j in pairs])
    om = L.solve(m)
    Om = _skew(n, [om[a, 0] for a in range(len(pairs))])
    Mq = [[to_fmpq(M[i, j]) for j in range(n)] for i in range(n)]
    # div_M = sum_a < B_a, [B_a, Omega] + [M, L^{-1} B_a] >, B_a = E_i ^ E_j, <B_a, X> = X_ij
    div_M = _ZERO
    for a, (i, j) in enumerate(pairs):
        B = [[_ZERO] * n for _ in range(n)]
        B[i][j], B[j][i] = _ONE, -_ONE
        dOm = _skew(n, [L_inv[c, a] for c in range(len(pairs))])
        div_M += _commutator_entry(B, Om, i, j) + _commutator_entry(Mq, dOm, i, j)
    Om_g = [sum((Om[i][k] * g[k] for k in range(n)), _ZERO) for i in range(n)]
    gamma_dot = [-v for v in Om_g]
    # d_k L (Omega) = b[(Omega e_k) ^ gamma + (Omega gamma) ^ e_k], one column per k; one solve
    cols = [[bq * (Om[i][k] * g[j] - Om[j][k] * g[i] + Om_g[i] * (_ONE if j == k else _ZERO)
                   - Om_g[j] * (_ONE if i == k else _ZERO)) for k in range(n)] for i, j in pairs]
    d_oms = -L.solve(flint.fmpq_mat(cols))
    div_gamma = _ZERO
    dlogdet = []
    for k in range(n):
        dOm = _skew(n, [d_oms[a, k] for a in range(len(pairs))])
        div_gamma -= sum((dOm[k][l] * g[l] for l in range(n)), _ZERO) + Om[k][k]
        # tr(L^-1 d_k L) = sum_a (L^-1 vec(d_k L(B_a)))_a, d_k L(B_a) sparse
        trace = _ZERO
        for a, (i, j) in enumerate(pairs):
            image: dict[int, flint.fmpq] = {}
            # (B_a e_k) ^ gamma: B_a e_k = delta_jk e_i - delta_ik e_j
            for s, (p, q) in ((1, (i, j)), (-1, (j, i))):
                if q == k:
                    for r in range(n):
                        if r != p:
                            _add_wedge(image, index, p, r, s * g[r] * bq)
            # (B_a gamma) ^ e_k = (gamma_j e_i - gamma_i e_j) ^ e_k
            if i != k:
                _add_wedge(image, index, i, k, g[j] * bq)
            if j != k:
                _add_wedge(image, index, j, k, -g[i] * bq)
            trace += sum((L_inv[a, c] * v for c, v in image.items()), _ZERO)
        dlogdet.append(trace)
    rational = _sympy_rational
    return {"div": rational(div_M + div_gamma),
            "gamma_dot": sp.Matrix([rational(v) for v in gamma_dot]),
            "Omega": to_sympy_matrix(flint.fmpq_mat(Om)),
            "dlogdet": [rational(v) for v in dlogdet]}


def _add_wedge(image: dict, index: dict, p: int, r: int, coeff) -> None:
    """image += coeff * (e_p ^ e_r) in coordinates (e_p ^ e_r = -e_r ^ e_p)."""
    if p < r:
        image[index[(p, r)]] = image.get(index[(p, r)], _ZERO) + coeff
    else:
        image[index[(r, p)]] = image.get(index[(r, p)], _ZERO) - coeff


def _sympy_rational(v: flint.fmpq) -> sp.Rational:
    return sp.Rational(int(v.p), int(v.q))
