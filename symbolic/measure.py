r"""Invariant measures as divergence identities, with the sphere handled exactly.

A measure $\rho\, dM\, d\gamma$ on $P = V \times S^{n-1}$ is invariant under a vector field $X$
iff $\operatorname{div}(\rho X) = 0$ on $P$. We never use coordinates on the sphere. Instead:

* the equations are extended to the ambient space $V \times \mathbb{R}^n$ by the same formulas
  (here $\dot\gamma = -\Omega\gamma$ with $\Omega = L_\gamma^{-1}M$ for any $\gamma$); the extension
  $X$ is tangent to every level set of $\phi = \lVert\gamma\rVert^2$ because $X(\phi) = -2\gamma^T\Omega
  \gamma = 0$;
* on a level set the *Leray form* $\nu$ with $dV\!\wedge\! d\gamma = d\phi \wedge \nu$ restricts to
  $\tfrac{1}{2}$ times the round measure of $S^{n-1}$ when $\phi = 1$ (as $d\phi = 2\,dr$ there);
* since $X(\phi) = 0$, $\mathcal{L}_X(\rho\,dV d\gamma) = d\phi \wedge \mathcal{L}_X(\rho\nu)$ and
  therefore $\mathcal{L}_X(\rho\nu)|_{\phi=1} = \operatorname{div}(\rho X)|_{\phi=1}\; \rho\nu|_{\phi=1}$.

So $\rho\,dM\,d\gamma$ (meaning $\rho$ times the product of $dM$ with the round measure) is
invariant on $P$ **iff the ambient divergence $\operatorname{div}(\rho X)$ vanishes at the points
with $\lVert\gamma\rVert = 1$** — an identity modulo $\lVert\gamma\rVert^2 - 1$, which the engine
decides exactly. With $\rho = \prod_i D_i^{p_i}$ the identity divided by $\rho$ is
$\operatorname{div} X + \sum_i p_i\, X(D_i)/D_i = 0$, a rational-function identity.
"""

from __future__ import annotations

from collections.abc import Sequence

import sympy as sp
from chaplygin_nd.symbolic.algebra import commutator, so_basis, unvec, vec
from chaplygin_nd.symbolic.mass_operator import L_matrix_qq
from sympy.polys.domains import QQ
from sympy.polys.matrices import DomainMatrix

__all__ = ["divergence", "measure_residual", "chaplygin_divergence_at"]


def divergence(field: Sequence[sp.Expr], coords: Sequence[sp.Symbol]) -> sp.Expr:
    r"""$\operatorname{div} X = \sum_i \partial X_i / \partial x_i$ in the coordinates ``coords``."""
    if len(field) != len(coords):
        raise ValueError(f"{len(field)} components for {len(coords)} coordinates")
    return sp.Add(*[sp.diff(f, c) for f, c in zip(field, coords)])


def measure_residual(field: Sequence[sp.Expr], coords: Sequence[sp.Symbol],
                     density: Sequence[tuple[sp.Expr, sp.Rational]]) -> sp.Expr:
    r"""$\operatorname{div}(\rho X)/\rho$ for $\rho = \prod_i D_i^{p_i}$ given as pairs $(D_i, p_i)$:
    $\operatorname{div} X + \sum_i p_i X(D_i)/D_i$. Zero (modulo the sphere) iff $\rho$ is invariant."""
    total = divergence(field, coords)
    for base, power in density:
        derivative = sp.Add(*[f * sp.diff(base, c) for f, c in zip(field, coords)])
        total += sp.Rational(power) * derivative / base
    return total


def _dm(matrix: sp.Matrix) -> DomainMatrix:
    return DomainMatrix.from_Matrix(matrix).convert_to(QQ)


def chaplygin_divergence_at(M: sp.Matrix, gamma: sp.Matrix, J: sp.Matrix, b) -> dict:
    r"""Exact ingredients of the divergence of eq:motion-general at one rational point.

    For $X(M, \gamma) = ([M, \Omega], -\Omega\gamma)$ with $\Omega = L_\gamma^{-1}M$ (eq:M-O, any
    diagonal $\mathbb{J}$, any $n$), returns exact rationals:

    * ``div``: the ambient divergence $\operatorname{div}_M + \operatorname{div}_\gamma$ of $X$, using
      $\partial_{m_a}\Omega = L_\gamma^{-1}B_a$ and $\partial_{\gamma_k}\Omega = -L_\gamma^{-1}
      (\partial_k L_\gamma) L_\gamma^{-1} M$;
    * ``gamma_dot``: $\dot\gamma$; ``Omega``: $\Omega$;
    * ``dlogdet``: $\partial_{\gamma_k}\log\det L_\gamma = \operatorname{tr}(L_\gamma^{-1}\partial_k L_\gamma)$ (Jacobi).

    Then $\operatorname{div}(\rho X)/\rho = \texttt{div} + \sum_k \dot\gamma_k\,\partial_k\log\rho$ for
    any density $\rho(\gamma)$; e.g. $\rho = (\det L_\gamma)^{-1/2}$ (eq:invmeasuredet).
    """
    from chaplygin_nd.symbolic.exact import flint_engine  # the engine of this evaluation
    flint_engine.note_call()
    if flint_engine.current_engine() == "flint":
        from chaplygin_nd.symbolic.flint_model import divergence_at_fmpq
        return divergence_at_fmpq(M, gamma, J, b)
    n = gamma.rows
    basis = so_basis(n)
    L = L_matrix_qq(gamma, J, b)
    L_inv = L.inv()
    Omega = unvec((L_inv * _dm(vec(M))).to_Matrix(), n)
    L_inv_sp = L_inv.to_Matrix()
    # div_M: sum_a < B_a, [B_a, Omega] + [M, L^{-1} B_a] >  (coordinates are Killing-orthonormal)
    div_M = sp.Integer(0)
    for a, B in enumerate(basis):
        dOmega = unvec(L_inv_sp[:, a], n)
        div_M += vec(commutator(B, Omega) + commutator(M, dOmega))[a]
    vec_Omega = _dm(vec(Omega))
    L_inv_rows = L_inv.to_list()
    div_gamma = sp.Integer(0)
    dlogdet = []
    for k in range(n):
        dL = L_matrix_qq(gamma, J, b, derivative=k)
        dOmega = unvec((-(L_inv * (dL * vec_Omega))).to_Matrix(), n)
        div_gamma -= (dOmega * gamma)[k] + Omega[k, k]
        # tr(L^{-1} dL) from the non-zero entries of the sparse dL only.
        trace = sum((L_inv_rows[i][j] * v for (j, i), v in dL.to_dok().items()), QQ.zero)
        dlogdet.append(QQ.to_sympy(trace))
    return {"div": sp.Rational(div_M + div_gamma), "gamma_dot": -Omega * gamma,
            "Omega": Omega, "dlogdet": dlogdet}
