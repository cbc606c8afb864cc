r"""The axisymmetric sphere for any $n$, on batches of matrices (runtime around ``generated.axisym``).

Arrays: $M, \Omega \in \mathfrak{so}(n)$ as ``(..., n, n)``, $\gamma$ as ``(..., n)``, parameters
$a, b$ scalars or batch arrays; every leading axis broadcasts. $E_n$ is the last basis vector and
$x = \gamma_n$. $u\wedge v = uv^T - vu^T$.

* :func:`angular_velocity` — $\Omega = L_\gamma^{-1}M = \sum_k c_k T_k(M)$ (P:inversion) with
  $T = (M, (M\gamma)\wedge\gamma, (ME_n)\wedge E_n, (M\gamma)\wedge E_n, (ME_n)\wedge\gamma,
  \langle M\gamma, E_n\rangle\gamma\wedge E_n)$ and $c_k$ from the generated coefficient kernel;
  for $n = 3, 4$ the generated component kernels (faster) unless ``method="matrix"``.
* :func:`vertical_solution` — Th:Re: $M(t) = e^{\zeta t}M_0e^{-\zeta t}$, $\gamma(t) = e^{\zeta t}\gamma_0$,
  with :func:`expm_skew` on $\mathfrak{so}(n-1)$ (Rodrigues in the stable form of row K:rodrigues
  for $n = 4$, a plane rotation for $n = 3$, a Hermitian eigendecomposition for $n \ge 5$).
"""

from __future__ import annotations

import numpy as np
from chaplygin_nd.generated import axisym as g
from chaplygin_nd.generated import expression_builders as eb

__all__ = ["vec", "unvec", "L_gamma", "angular_velocity", "vector_field", "energy", "p_coefficients",
           "zeta", "chi",
           "expm_skew", "vertical_solution"]


def _pairs(n: int):
    return np.triu_indices(n, 1)


def vec(A: np.ndarray) -> np.ndarray:
    """Coordinates $A_{ij}$, $i<j$ (lexicographic) of ``(..., n, n)`` skew matrices (symbolic.algebra.vec)."""
    A = np.asarray(A, dtype=float)
    i, j = _pairs(A.shape[-1])
    return A[..., i, j]


def unvec(c: np.ndarray, n: int) -> np.ndarray:
    """The skew ``(..., n, n)`` matrices with coordinates ``c`` (inverse of :func:`vec`)."""
    c = np.asarray(c, dtype=float)
    i, j = _pairs(n)
    A = np.zeros(c.shape[:-1] + (n, n))
    A[..., i, j] = c
    A[..., j, i] = -c
    return A


def _wedge(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    return u[..., :, None] * v[..., None, :] - v[..., :, None] * u[..., None, :]


def _scalar(p) -> np.ndarray:
    """A parameter as an array broadcasting against ``(..., n, n)``."""
    return np.asarray(p, dtype=float)[..., None, None]


def L_gamma(Omega, gamma, a, b) -> np.ndarray:
    r"""$L_\gamma(\Omega) = \mathbb{J}\Omega + \Omega\mathbb{J} + b(\Omega\gamma)\wedge\gamma$, $\mathbb{J} =
    \mathrm{Id} + aE_nE_n^T$ (eq:M-O, eq:axisymm) $= 2\Omega + a(\Omega E_n)\wedge E_n + b(\Omega\gamma)\wedge\gamma$.
    Any $\gamma \in \mathbb{R}^n$."""
    Omega, gamma = np.asarray(Omega, dtype=float), np.asarray(gamma, dtype=float)
    n = Omega.shape[-1]
    e = np.zeros(n)
    e[-1] = 1.0
    Og = np.einsum("...ij,...j->...i", Omega, gamma)
    return 2 * Omega + _scalar(a) * _wedge(Omega[..., :, -1], e) + _scalar(b) * _wedge(Og, gamma)


def _terms_apply(c: np.ndarray, M: np.ndarray, gamma: np.ndarray) -> np.ndarray:
    r"""$\sum_k c_k T_k(M)$ with the six ansatz terms of symbolic.axisym_inverse (broadcast)."""
    n = M.shape[-1]
    e = np.zeros(n)
    e[-1] = 1.0
    Mg = np.einsum("...ij,...j->...i", M, gamma)
    Me = M[..., :, -1]
    C = [c[..., k][..., None, None] for k in range(6)]
    return (C[0] * M + C[1] * _wedge(Mg, gamma) + C[2] * _wedge(Me, e)
            + C[3] * _wedge(Mg, e) + C[4] * _wedge(Me, gamma)
            + C[5] * Mg[..., -1][..., None, None] * _wedge(gamma, e))


def angular_velocity(M, gamma, a, b, method: str = "auto") -> np.ndarray:
    r"""$\Omega = L_\gamma^{-1}(M)$ (P:inversion), ``(..., n, n)``. Domain: $\gamma \in S^{n-1}$,
    $\Delta(x) \ne 0 \ne 2+a+b$ (e.g. $|a| \le 1$, $b > 0$). ``method``: ``"auto"`` (component
    kernel for $n = 3, 4$), ``"matrix"`` (coefficient kernel + einsum, any $n \ge 3$)."""
    M, gamma = np.asarray(M, dtype=float), np.asarray(gamma, dtype=float)
    n = M.shape[-1]
    if method == "auto" and n in (3, 4):
        kernel = g.angular_velocity_axisym_3d if n == 3 else g.angular_velocity_axisym_4d
        return unvec(kernel(vec(M), gamma, a, b), n)
    c = g.inverse_coefficients(gamma[..., -1], a, b)
    return _terms_apply(c, M, gamma)


class _NumpyOps:
    """``ops`` of the generated expression builders for float arrays."""

    sqrt = staticmethod(np.sqrt)

    @staticmethod
    def rational(p: int, q: int) -> float:
        return p / q


#: The pairs of the structured field's weights (order of ``structured_field_weights``).
_STRUCTURED_PAIRS = [(i, j) for i in range(6) for j in range(i + 1, 6)]


def _matvec(M: np.ndarray, v: np.ndarray) -> np.ndarray:
    return np.einsum("...ij,...j->...i", M, v)


def vector_field(M, gamma, a, b, method: str = "auto") -> tuple[np.ndarray, np.ndarray]:
    r"""$(\dot M, \dot\gamma) = ([M, \Omega], -\Omega\gamma)$, $\Omega = L_\gamma^{-1}M$ (eq:motion-general);
    domain as :func:`angular_velocity`. ``method``: ``"auto"`` — the structured $O(n^2)$ form of row
    S4:structured-field, $\dot M = \sum w_{ij}V_i\wedge V_j$, $\dot\gamma = \sum u_iV_i$ over
    $V = (M^2\gamma, M^2E_n, M\gamma, ME_n, \gamma, E_n)$ with the generated weights (structural
    zeros skipped); ``"matrix"`` — $M\Omega - \Omega M$ with the matrix $\Omega$ (for comparisons)."""
    M, gamma = np.asarray(M, dtype=float), np.asarray(gamma, dtype=float)
    if method == "matrix":
        Omega = angular_velocity(M, gamma, a, b, method)
        return M @ Omega - Omega @ M, -_matvec(Omega, gamma)
    n = M.shape[-1]
    e = np.zeros(n)
    e[-1] = 1.0
    Mg = _matvec(M, gamma)
    Me = M[..., :, -1]
    V = [_matvec(M, Mg), _matvec(M, Me), Mg, Me, gamma, e]
    weights = eb.structured_field_weights(gamma[..., -1], Mg[..., -1],
                                          np.einsum("...i,...i->...", gamma, gamma),
                                          np.asarray(a, dtype=float), np.asarray(b, dtype=float),
                                          _NumpyOps)
    w, u = weights[:len(_STRUCTURED_PAIRS)], weights[len(_STRUCTURED_PAIRS):]
    A: dict[int, np.ndarray] = {}
    for (i, j), wij in zip(_STRUCTURED_PAIRS, w):
        if not (isinstance(wij, int) and wij == 0):
            A[j] = A.get(j, 0) + np.asarray(wij)[..., None] * V[i]
    Mdot = sum(_wedge(Aj, V[j]) for j, Aj in A.items())
    gdot = sum(np.asarray(ui)[..., None] * Vi for ui, Vi in zip(u, V)
               if not (isinstance(ui, int) and ui == 0))
    shape = np.broadcast_shapes(M.shape, gamma.shape[:-1] + (n, n))
    return np.broadcast_to(Mdot, shape).copy(), np.broadcast_to(gdot, shape[:-1]).copy()


def energy(M, gamma, a, b, method: str = "auto") -> np.ndarray:
    r"""$H = \tfrac12\langle M, \Omega\rangle_\kappa = \tfrac12\sum_{i<j} M_{ij}\Omega_{ij}$ (S2.2:energy);
    domain as :func:`angular_velocity`."""
    M = np.asarray(M, dtype=float)
    Omega = angular_velocity(M, gamma, a, b, method)
    return 0.5 * np.sum(vec(M) * vec(Omega), axis=-1)


def _poly_from_roots(roots: np.ndarray) -> np.ndarray:
    """Coefficients (highest power first) of prod_k (lambda - roots[..., k]), vectorised over the
    batch (what numpy.poly does for one set of roots)."""
    c = np.zeros(roots.shape[:-1] + (roots.shape[-1] + 1,), dtype=complex)
    c[..., 0] = 1.0
    for k in range(roots.shape[-1]):
        c[..., 1:k + 2] = c[..., 1:k + 2] - roots[..., k:k + 1] * c[..., 0:k + 1]
    return c


def p_coefficients(M, gamma) -> np.ndarray:
    r"""Coefficients of $p(\lambda,\sigma) = \det(M + \sigma\gamma\gamma^T - \lambda\,\mathrm{Id})$
    (eq:pol-first-integrals), ``out[..., i, j]`` multiplying $\lambda^i\sigma^j$, shape ``(..., n+1, 2)``;
    $M$ ``(..., n, n)``, $\gamma$ ``(..., n)``, any $n$. For $n = 3, 4$ the generated kernels (the
    expanded determinant, emitted from the derived expression); otherwise, since $p$ is affine in
    $\sigma$, $p = \det(M - \lambda) + \sigma(\det(M + \gamma\gamma^T - \lambda) - \det(M - \lambda))$
    from batched eigenvalues (one LAPACK call for the whole batch, no Python loop)."""
    M, gamma = np.asarray(M, dtype=float), np.asarray(gamma, dtype=float)
    n = M.shape[-1]
    if n in (3, 4):
        kernel = g.p_coefficients_3d if n == 3 else g.p_coefficients_4d
        return kernel(vec(M), gamma)
    shape = np.broadcast_shapes(M.shape[:-2], gamma.shape[:-1])
    M = np.broadcast_to(M, shape + (n, n))
    G = M + gamma[..., :, None] * gamma[..., None, :]
    c0 = np.real(_poly_from_roots(np.linalg.eigvals(M)))
    c1 = np.real(_poly_from_roots(np.linalg.eigvals(G)))
    sign = (-1.0) ** n  # det(M - lambda) = (-1)^n det(lambda - M)
    return np.stack([sign * c0[..., ::-1], sign * (c1 - c0)[..., ::-1]], axis=-1)


def zeta(M0, gamma0, a, b) -> np.ndarray:
    r"""$\zeta = \kappa(x_0)M_0 - L_{\gamma_0}^{-1}M_0 \in \mathfrak{so}(n-1)$ (Th:Re, derived);
    domain: $(M_0, \gamma_0) \in \mathcal{V}$ ($M_0\gamma_0 = 0$, $\gamma_0 \in S^{n-1}$)."""
    M0, gamma0 = np.asarray(M0, dtype=float), np.asarray(gamma0, dtype=float)
    kappa = g.vertical_coefficients(gamma0[..., -1], a, b)[..., 0]
    return _scalar(kappa) * M0 - angular_velocity(M0, gamma0, a, b, "matrix")


def chi(Omega0, a, b) -> np.ndarray:
    r"""$\chi = \tilde\kappa\,\tilde{\mathbb{I}}(\Omega_0) - \Omega_0$, $\tilde{\mathbb{I}}(\Omega) =
    (2+b)\Omega + a(\Omega E_n)\wedge E_n$ (eq:solManakov, eq:itildendim); any $\Omega_0$."""
    Omega0 = np.asarray(Omega0, dtype=float)
    n = Omega0.shape[-1]
    e = np.zeros(n)
    e[-1] = 1.0
    kappa_t = g.vertical_coefficients(0.0, a, b)[..., 1]
    It = (2 + _scalar(b)) * Omega0 + _scalar(a) * _wedge(Omega0[..., :, -1], e)
    return _scalar(kappa_t) * It - Omega0


def _rodrigues(Z: np.ndarray) -> np.ndarray:
    r"""$e^Z = I + \operatorname{sinc}\theta\, Z + \tfrac12\operatorname{sinc}^2(\theta/2)\,Z^2$ for
    $3\times3$ skew $Z$, $\theta = \lVert z\rVert$ (row K:rodrigues: no $0/0$ as $\theta \to 0$)."""
    theta = np.sqrt(Z[..., 2, 1] ** 2 + Z[..., 0, 2] ** 2 + Z[..., 1, 0] ** 2)
    s1 = np.sinc(theta / np.pi)[..., None, None]
    s2 = 0.5 * np.sinc(theta / (2 * np.pi))[..., None, None] ** 2
    return np.eye(3) + s1 * Z + s2 * (Z @ Z)


def expm_skew(Z) -> np.ndarray:
    r"""$e^Z \in SO(n)$ for skew ``(..., n, n)`` $Z$: a plane rotation for $n = 2$, Rodrigues in the
    stable form of K:rodrigues for $n = 3$, else $e^Z = V e^{-i\Lambda} V^*$ from the Hermitian
    eigendecomposition $iZ = V\Lambda V^*$ (backward stable)."""
    Z = np.asarray(Z, dtype=float)
    n = Z.shape[-1]
    if n == 1:
        return np.ones(Z.shape)
    if n == 2:
        w = Z[..., 1, 0]
        c, s = np.cos(w), np.sin(w)
        return np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)
    if n == 3:
        return _rodrigues(Z)
    lam, V = np.linalg.eigh(1j * Z)
    return np.real(np.einsum("...ik,...k,...jk->...ij", V, np.exp(-1j * lam), V.conj()))


def vertical_solution(M0, gamma0, t, a, b) -> tuple[np.ndarray, np.ndarray]:
    r"""Th:Re: $(M(t), \gamma(t)) = (e^{\zeta t}M_0e^{-\zeta t}, e^{\zeta t}\gamma_0)$ for $(M_0, \gamma_0) \in
    \mathcal{V}$; ``t`` a scalar or batch array (broadcast against the batch of $M_0$)."""
    M0, gamma0 = np.asarray(M0, dtype=float), np.asarray(gamma0, dtype=float)
    Z = zeta(M0, gamma0, a, b)[..., :-1, :-1]  # zeta E_n = 0: zeta lies in so(n-1)
    Zt = _scalar(t) * Z
    n = M0.shape[-1]
    R = np.zeros(Zt.shape[:-2] + (n, n))
    R[..., :-1, :-1] = expm_skew(Zt)
    R[..., -1, -1] = 1.0
    return R @ M0 @ np.swapaxes(R, -1, -2), np.einsum("...ij,...j->...i", R, gamma0)
