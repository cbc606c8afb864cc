r"""The control system of the frequency evidence: the $n$-dimensional Chaplygin sphere with a
*generic* (non-axisymmetric) diagonal mass tensor $\mathbb{J} = \mathrm{diag}(J_1, \dots, J_n)$.

Same equations eq:motion-general, same inertia operator eq:Inertia $\mathbb{I}(\Omega) = \mathbb{J}\Omega +
\Omega\mathbb{J}$ and the same $L_\gamma(\Omega) = \mathbb{I}(\Omega) + b(\Omega\gamma)\wedge\gamma$ (eq:M-O) as
the axisymmetric sphere; only $\mathbb{J}$ differs. Why it is a control. For $n = 4$ the phase space
$\mathfrak{so}(4)\times S^3$ has dimension 9; the known integrals are $H$ and the coefficients of
$p(\lambda, \sigma)$ (eq:pol-first-integrals: $F_1, F_2, F_3$), 4 in all, plus the invariant measure
(eq:invmeasuredet). The Euler–Jacobi theorem would need 7. The axisymmetric case gets its
integrability from the $SO(3)$ symmetry, which a generic $\mathbb{J}$ destroys, and no further
integral is known. So the level sets have dimension 5 and nothing forces quasi-periodicity. (For
$n = 3$ the general-$\mathbb{J}$ sphere is Chaplygin's integrable case: not a control.) Whether its
orbits are actually irregular is *measured* (frequency diffusion), not assumed.

$L_\gamma^{-1}$ has no closed form here; it is a batched linear solve of the matrix of $L_\gamma$ in the
basis $e_{ij} = E_i\wedge E_j$ ($i < j$), assembled from the definition above. Nothing derived is
written by hand.
"""

from __future__ import annotations

import numpy as np
from chaplygin_nd.simulate.dynamics import so
from chaplygin_nd.simulate.kernels import Kernels

__all__ = ["general_inertia_kernels", "L_gamma_general", "general_system", "CHAOTIC_J",
           "CANDIDATE_J"]

#: Candidate mass tensors, least asymmetric first, and the rule that chose the control,
#: fixed before any frequency result of the drawn ensembles was seen: the first candidate for which
#: at least 7 of 8 pilot orbits (``simulate.analysis.draws.draw("pilot-control", "generic", n, 8, seed=777)``,
#: a draw of its own, not the ledger's) have MEGNO <Y>(4096) >= 4 (:mod:`simulate.analysis.chaos`). Measured
#: (MEGNO only; heyoka tol 1e-10): n = 4 — diag(1, 1.3, 0.75, 0.5), the first control of the frequency experiment: 5 of
#: 8 (1.97 11.1 1.98 1.99 13.6 13.8 13.8 17.9); diag(1, 2, 0.5, 0.25): 7 of 8 (9.5 20.4 1.96 7.0
#: 32.3 32.6 32.9 29.1) -> chosen then. n = 5 — diag(1, 1.3, 0.75, 0.5, 1.1): 3 of 8; diag(1, 2, 0.5,
#: 0.25, 1.5): 8 of 8 (4.5 5.6 22.5 12.1 35.7 25.4 27.1 40.9) -> chosen. n = 6 (the
#: same rule; the n = 5 choice extended by 0.75): diag(1, 2, 0.5, 0.25, 1.5, 0.75): 8 of 8 (24.2 27.0
#: 29.3 16.9 36.2 30.1 21.9 39.5) -> chosen.
#:
#: The drawn rows ask more of a control: chaotic by the MEGNO horizon ladder on >= 90 % of its orbits.
#: The validation study (bench/bench_evidence.py) found diag(1, 2, 0.5, 0.25) a mixed system: 23 of
#: 32 drawn orbits chaotic at T = 4096 (8 regular, <Y> ~ 2), 26 of 32 at T = 8192. Pilot (32 orbits,
#: ``draw("pilot-control-24", "generic", 4, 32, 777)``, T = 4096, the ladder rule): diag(1, 4, 0.25,
#: 0.1): 27 of 32; diag(1, 8, 0.125, 0.05): 21; diag(1, 16, 0.1, 0.02): 15; diag(0.5, 2, 0.125,
#: 0.05) (the second one halved, i.e. b doubled relative to J): 31 of 32 (1 undecided) -> the n = 4
#: control of the drawn rows. n = 5 kept: 29 of 32 chaotic in the study.
CANDIDATE_J = {4: ((1.0, 1.3, 0.75, 0.5), (1.0, 2.0, 0.5, 0.25), (1.0, 4.0, 0.25, 0.1),
                   (1.0, 8.0, 0.125, 0.05), (1.0, 16.0, 0.1, 0.02), (0.5, 2.0, 0.125, 0.05)),
               5: ((1.0, 1.3, 0.75, 0.5, 1.1), (1.0, 2.0, 0.5, 0.25, 1.5)),
               6: ((1.0, 2.0, 0.5, 0.25, 1.5, 0.75),)}
CHAOTIC_J = {4: (0.5, 2.0, 0.125, 0.05), 5: (1.0, 2.0, 0.5, 0.25, 1.5),
             6: (1.0, 2.0, 0.5, 0.25, 1.5, 0.75)}


def L_gamma_general(Omega: np.ndarray, gamma: np.ndarray, J: np.ndarray, b: float) -> np.ndarray:
    r"""$L_\gamma(\Omega) = \mathbb{J}\Omega + \Omega\mathbb{J} + b(\Omega\gamma)\wedge\gamma$ (eq:M-O, eq:Inertia),
    batched; ``J`` the diagonal of $\mathbb{J}$. Domain: $\Omega$ skew, any $\gamma$."""
    Jm = np.diag(np.asarray(J, dtype=float))
    Og = np.einsum("...ij,...j->...i", Omega, gamma)
    return Jm @ Omega + Omega @ Jm + b * so.wedge(Og, gamma)


def general_inertia_kernels(J, b: float) -> Kernels:
    r"""A :class:`simulate.kernels.Kernels` whose ``angular_velocity(M, gamma, a, b)`` solves
    $L_\gamma(\Omega) = M$ for the diagonal mass tensor ``J`` (the ``a`` argument is ignored: $\mathbb{J}$
    is fixed here). Domain: $J_i > 0$, $b > 0$, $\|\gamma\| = 1$ ($L_\gamma$ is then positive definite)."""
    J = np.asarray(J, dtype=float)
    n = len(J)
    basis = so.unvec(np.eye(so.so_dim(n)), n)  # (N, n, n)

    def angular_velocity(M, gamma, a_ignored, b_ignored):
        lead = M.shape[:-2]
        gs = gamma.reshape(-1, 1, n)
        cols = L_gamma_general(basis[None], gs, J, b)          # (count, N, n, n)
        L = np.swapaxes(so.vec(cols), -1, -2)                  # columns = images of e_ij
        w = np.linalg.solve(L, so.vec(M.reshape(-1, n, n))[..., None])[..., 0]
        return so.unvec(w, n).reshape(lead + (n, n))

    return Kernels(name=f"general J = diag{tuple(float(j) for j in J)} (control)",
                   angular_velocity=angular_velocity, note="linear solve of eq:M-O")


def _zero(v) -> bool:
    return isinstance(v, int) and v == 0


def general_system(J):
    r"""eq:motion-general for the diagonal mass tensor ``J`` as a heyoka system
    (:class:`simulate.integrators.heyoka_systems.System`; state $(\mathrm{vec}\,M, \gamma)$ as
    :class:`simulate.dynamics.field.FullField`; parameters $(a, b)$, $a$ unused so that one parameter layout
    serves the axisymmetric and the control systems). $\dot M = [M, \Omega]$, $\dot\gamma = -\Omega\gamma$.

    $\Omega = L_\gamma^{-1}M$ through an $n\times n$ solve, not the $\binom n2\times\binom n2$ matrix of
    $L_\gamma$. By eq:M-O and eq:Inertia, $L_\gamma(\Omega) = \mathbb{J}\Omega + \Omega\mathbb{J} + b\,v\wedge\gamma$
    with $v = \Omega\gamma$, whose $(i, j)$ entry is $(J_i + J_j)\Omega_{ij} + b(v_i\gamma_j - \gamma_iv_j)$. So
    $L_\gamma(\Omega) = M$ iff

    .. math::
        \Omega_{ij} = c_{ij}\,(M_{ij} - b(v_i\gamma_j - \gamma_iv_j)), \qquad c_{ij} = 1/(J_i + J_j),

    and $v = \Omega\gamma$ then solves $Av = r$, $r_i = \sum_j c_{ij}M_{ij}\gamma_j$, $A = I + bG$,
    $G_{ii} = \sum_{k\ne i}c_{ik}\gamma_k^2$, $G_{ij} = -c_{ij}\gamma_i\gamma_j$ ($i \ne j$; the $k = i$ terms
    cancel). $A$ is symmetric positive definite for $b \ge 0$: $x^TGx = \frac12\sum_{i,k}c_{ik}(x_i\gamma_k -
    x_k\gamma_i)^2 \ge 0$, so its $LDL^T$ factorisation, written as expressions, needs no pivoting, and
    $\dot\gamma = -v$. It costs $O(n^3/6)$ operations instead of $O(n^6/48)$: the tangent system of
    $n = 5$ decomposes into 1671 operations instead of 3579 and steps 3x faster (the same steps;
    the orbits agree to rounding, tests/test_chaos.py checks the field against the NumPy linear
    solve of :func:`general_inertia_kernels`). Nothing derived is typed by hand.
    Domain: $J_i > 0$, $b > 0$, $\gamma \in S^{n-1}$."""
    from chaplygin_nd.simulate.integrators.heyoka_systems import System

    J = tuple(float(j) for j in J)
    n = len(J)
    idx = [(i, j) for i in range(n) for j in range(i + 1, n)]
    N = len(idx)
    names = tuple(f"M{i + 1}_{j + 1}" for i, j in idx) + tuple(f"gamma{i + 1}" for i in range(n))
    c = [[1.0 / (J[i] + J[j]) for j in range(n)] for i in range(n)]

    def build(v, p, ops):
        hy = ops.hy
        m, g = v[:N], v[N:N + n]
        b = p[1]
        Mm: list[list] = [[0] * n for _ in range(n)]
        for k, (i, j) in enumerate(idx):
            Mm[i][j], Mm[j][i] = m[k], -m[k]
        r = [hy.sum([hy.expression(c[i][j]) * (Mm[i][j] * g[j]) for j in range(n) if j != i])
             for i in range(n)]
        A: list[list] = [[None] * n for _ in range(n)]
        for i in range(n):
            A[i][i] = hy.expression(1.0) + b * hy.sum([hy.expression(c[i][k]) * (g[k] * g[k])
                                                       for k in range(n) if k != i])
            for j in range(i + 1, n):
                A[i][j] = A[j][i] = -(b * (hy.expression(c[i][j]) * (g[i] * g[j])))
        # LDL^T: A = T D T^T, T unit lower triangular; then T D T^T v = r
        T: list[list] = [[None] * n for _ in range(n)]
        D: list = [None] * n
        for q in range(n):
            acc = A[q][q]
            for k in range(q):
                acc = acc - T[q][k] * T[q][k] * D[k]
            D[q] = acc
            for s in range(q + 1, n):
                acc = A[s][q]
                for k in range(q):
                    acc = acc - T[s][k] * T[q][k] * D[k]
                T[s][q] = acc / D[q]
        z: list = []
        for q in range(n):
            acc = r[q]
            for k in range(q):
                acc = acc - T[q][k] * z[k]
            z.append(acc)
        w: list = [None] * n
        for q in reversed(range(n)):
            acc = z[q] / D[q]
            for k in range(q + 1, n):
                acc = acc - T[k][q] * w[k]
            w[q] = acc                                   # w = v = Omega gamma
        Om: list[list] = [[0] * n for _ in range(n)]
        for k, (i, j) in enumerate(idx):
            Om[i][j] = hy.expression(c[i][j]) * (m[k] - b * (w[i] * g[j] - g[i] * w[j]))
            Om[j][i] = -Om[i][j]

        def prod(X, Y, i, j):
            return hy.sum([X[i][k] * Y[k][j] for k in range(n)
                           if not _zero(X[i][k]) and not _zero(Y[k][j])])

        out = [prod(Mm, Om, i, j) - prod(Om, Mm, i, j) for i, j in idx]
        return out + [-w[i] for i in range(n)]

    return System(f"control general J = diag{J}", names, ("a", "b"), build)
