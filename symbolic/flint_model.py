r"""The model's exact computations at one rational point, in FLINT (``fmpq``, ``fmpq_mat``).

The FLINT engine's side of the heavy point steps of the all-$n$ rows: $L_\gamma$ (eq:M-O) as an
``fmpq_mat``, $\Omega = L_\gamma^{-1}M$, and the ingredients of the ambient divergence of
eq:motion-general (eq:invmeasuredet). :func:`symbolic.model.angular_velocity` and
:func:`symbolic.measure.chaplygin_divergence_at` call these when the current engine is FLINT
(:func:`symbolic.exact.flint_engine.use_engine`); their SymPy side is unchanged, and
:func:`symbolic.exact.identity.zero_at_points` requires the two values to be equal wherever both run.

The divergence is computed here by a different route from the SymPy side (which inverts
$L_\gamma$ and forms every $\partial_{\gamma_k}L_\gamma$ as a matrix): one exact solve with $n + 1$
right-hand sides and the trace identities of :func:`divergence_at_fmpq` (symmetry of $L_\gamma$,
$\partial_{\gamma_k}L_\gamma = b(P_k + P_k^T)$ of rank $\le 2(n-1)$).
Domain: any $n \ge 2$, rational $\gamma$ (not necessarily unit), diagonal rational $\mathbb{J}$,
rational $b$ with $L_\gamma$ invertible.
"""

from __future__ import annotations

import flint
import sympy as sp
from chaplygin_nd.symbolic.exact.flint_engine import (
    current_engine,
    note_call,
    to_fmpq,
    to_sympy_matrix,
)
from chaplygin_nd.symbolic.mass_operator import L_entries, L_matrix_qq

__all__ = ["L_matrix_fmpq", "L_matrix_at", "angular_velocity_fmpq", "divergence_at_fmpq"]

_ZERO, _ONE = flint.fmpq(0), flint.fmpq(1)


def _pairs(n: int) -> list[tuple[int, int]]:
    return [(i, j) for i in range(n) for j in range(i + 1, n)]


def L_matrix_fmpq(gamma, J: sp.Matrix, b) -> flint.fmpq_mat:
    r"""The matrix of $L_\gamma$ (eq:M-O) in the basis $E_i\wedge E_j$, entries in ``fmpq``."""
    rows = L_entries([to_fmpq(v) for v in gamma], [to_fmpq(v) for v in J.diagonal()],
                      to_fmpq(b), _ZERO, _ONE)
    return flint.fmpq_mat(rows)


def L_matrix_at(gamma: sp.Matrix, J: sp.Matrix, b):
    r"""$L_\gamma$ (eq:M-O) at a rational point in the current engine's own matrix type:
    ``fmpq_mat`` (FLINT) or a sparse ``DomainMatrix`` over QQ (SymPy, ``mass_operator.L_matrix_qq``)."""
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


def divergence_at_fmpq(M: sp.Matrix, gamma: sp.Matrix, J: sp.Matrix, b) -> dict:
    r"""The same exact quantities as :func:`symbolic.measure.chaplygin_divergence_at` (``div``,
    ``gamma_dot``, ``Omega``, ``dlogdet``: the ambient divergence of eq:motion-general,
    $\dot\gamma$, $\Omega$ and $\partial_{\gamma_k}\log\det L_\gamma$), computed in FLINT with
    **one** exact solve $L_\gamma[\,\Omega \mid Y_1 \cdots Y_n] = [\,M \mid e_1\wedge\gamma \cdots
    e_n\wedge\gamma]$ instead of the full inverse (2.3 s of the 2.7 s at $n = 24$).

    In the Killing-orthonormal coordinates of :func:`symbolic.algebra.vec`, with
    $\langle u\wedge v, Y\rangle = u^TYv$, the matrix of $L_\gamma$ is symmetric (eq:M-O; checked
    exactly here, else ``ArithmeticError``), hence so is $L_\gamma^{-1}$, and:

    * $\operatorname{div}_M = \sum_a\langle B_a, [B_a,\Omega]\rangle + \operatorname{tr}(\mathrm{ad}_M
      L_\gamma^{-1})$; the first sum is computed, the trace is $0$ ($\mathrm{ad}_M$ is skew-adjoint,
      $L_\gamma^{-1}$ self-adjoint);
    * $\operatorname{div}_\gamma = -\sum_k[(\partial_k\Omega)\gamma]_k - \Omega_{kk}$ with
      $\partial_k\Omega = -L_\gamma^{-1}c_k$, $c_k = (\partial_kL_\gamma)\Omega = b[(\Omega e_k)\wedge
      \gamma + (\Omega\gamma)\wedge e_k]$: $-[(\partial_k\Omega)\gamma]_k = \langle e_k\wedge\gamma,
      L_\gamma^{-1}c_k\rangle = \langle Y_k, c_k\rangle$;
    * $\partial_k L_\gamma = b(P_k + P_k^T)$ with $P_k X = (Xe_k)\wedge\gamma$ (so $P_k^TX = (X\gamma)
      \wedge e_k$), hence $\operatorname{tr}(L_\gamma^{-1}\partial_kL_\gamma) = 2b\operatorname{tr}
      (L_\gamma^{-1}P_k) = 2b\sum_r (Y_r)_{rk}$.

    Wherever both engines run, :func:`symbolic.exact.identity.zero_at_points` requires these values to
    equal SymPy's, which forms the full inverse and every $\partial_kL_\gamma$ (no shortcut).
    """
    n = gamma.rows
    pairs = _pairs(n)
    g = [to_fmpq(v) for v in gamma]
    bq = to_fmpq(b)
    L = L_matrix_fmpq(gamma, J, b)
    if L != L.transpose():
        raise ArithmeticError("the matrix of L_gamma is not symmetric: the trace identities of "
                              "divergence_at_fmpq do not apply")
    # columns: vec(M), then vec(e_r ^ gamma) (entry (i, j): delta_ri gamma_j - gamma_i delta_rj)
    rhs = [[to_fmpq(M[i, j])] + [(g[j] if r == i else _ZERO) - (g[i] if r == j else _ZERO)
                                  for r in range(n)] for i, j in pairs]
    X = L.solve(flint.fmpq_mat(rhs))
    Om = _skew(n, [X[a, 0] for a in range(len(pairs))])
    Y = [_skew(n, [X[a, 1 + r] for a in range(len(pairs))]) for r in range(n)]
    # <B_a, [B_a, Omega]> = ([B_a, Omega])_ij = Omega_jj - Omega_ii for B_a = E_i ^ E_j
    div_M = sum((Om[j][j] - Om[i][i] for i, j in pairs), _ZERO)
    Om_g = [sum((Om[i][k] * g[k] for k in range(n)), _ZERO) for i in range(n)]
    gamma_dot = [-v for v in Om_g]
    div_gamma = _ZERO
    dlogdet = []
    for k in range(n):
        Yk, Om_ek = Y[k], [Om[i][k] for i in range(n)]
        # <Y_k, c_k> = b [ (Omega e_k)^T Y_k gamma + (Omega gamma)^T Y_k e_k ]
        Yk_g = [sum((Yk[i][j] * g[j] for j in range(n)), _ZERO) for i in range(n)]
        div_gamma += bq * (sum((Om_ek[i] * Yk_g[i] for i in range(n)), _ZERO)
                           + sum((Om_g[i] * Yk[i][k] for i in range(n)), _ZERO)) - Om[k][k]
        dlogdet.append(2 * bq * sum((Y[r][r][k] for r in range(n)), _ZERO))
    rational = _sympy_rational
    return {"div": rational(div_M + div_gamma),
            "gamma_dot": sp.Matrix([rational(v) for v in gamma_dot]),
            "Omega": to_sympy_matrix(flint.fmpq_mat(Om)),
            "dlogdet": [rational(v) for v in dlogdet]}


def _sympy_rational(v: flint.fmpq) -> sp.Rational:
    return sp.Rational(int(v.p), int(v.q))
