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
    serves the axisymmetric and the control systems). $\Omega = L_\gamma^{-1}M$ by an $LDL^T$
    factorisation written as expressions: in the Killing-orthonormal basis $E_i\wedge E_j$ the matrix
    $L[(kl), (ij)] = (J_i + J_j)\delta_{(kl),(ij)} + b\,(w_k\gamma_l - \gamma_kw_l)$, $w = E_i\gamma_j -
    E_j\gamma_i$ (eq:M-O, eq:Inertia) is symmetric positive definite for $J_i > 0$, $b > 0$,
    $\|\gamma\| = 1$, so the factorisation needs no pivoting. Nothing derived is typed by hand.
    Domain: $J_i > 0$, $b > 0$, $\gamma \in S^{n-1}$."""
    from chaplygin_nd.simulate.integrators.heyoka_systems import System

    J = tuple(float(j) for j in J)
    n = len(J)
    idx = [(i, j) for i in range(n) for j in range(i + 1, n)]
    N = len(idx)
    names = tuple(f"M{i + 1}_{j + 1}" for i, j in idx) + tuple(f"gamma{i + 1}" for i in range(n))

    def build(v, p, ops):
        m, g = v[:N], v[N:N + n]
        b = p[1]
        L = [[None] * N for _ in range(N)]
        for c, (i, j) in enumerate(idx):
            w = [0] * n
            w[i], w[j] = g[j], -g[i]
            for r, (k, l) in enumerate(idx):
                terms = []
                if not _zero(w[k]):
                    terms.append(w[k] * g[l])
                if not _zero(w[l]):
                    terms.append(-(g[k] * w[l]))
                entry = b * sum(terms[1:], terms[0]) if terms else None
                if r == c:
                    const = ops.hy.expression(J[i] + J[j])
                    entry = const if entry is None else const + entry
                L[r][c] = entry
        # LDL^T: L = T D T^T, T unit lower triangular; solve T D T^T w = m
        T = [[None] * N for _ in range(N)]
        D = [None] * N
        for r in range(N):
            acc = L[r][r]
            for k in range(r):
                if T[r][k] is not None:
                    acc = acc - T[r][k] * T[r][k] * D[k]
            D[r] = acc
            for q in range(r + 1, N):
                acc = L[q][r]
                for k in range(r):
                    if T[q][k] is not None and T[r][k] is not None:
                        term = T[q][k] * T[r][k] * D[k]
                        acc = term * -1.0 if acc is None else acc - term
                T[q][r] = None if acc is None else acc / D[r]
        z = []
        for r in range(N):
            acc = m[r]
            for k in range(r):
                if T[r][k] is not None:
                    acc = acc - T[r][k] * z[k]
            z.append(acc)
        y = [z[r] / D[r] for r in range(N)]
        w_ = [None] * N
        for r in reversed(range(N)):
            acc = y[r]
            for k in range(r + 1, N):
                if T[k][r] is not None:
                    acc = acc - T[k][r] * w_[k]
            w_[r] = acc
        Om = [[0] * n for _ in range(n)]
        Mm = [[0] * n for _ in range(n)]
        for c, (i, j) in enumerate(idx):
            Om[i][j], Om[j][i] = w_[c], -w_[c]
            Mm[i][j], Mm[j][i] = m[c], -m[c]

        def prod(A, B, i, j):
            terms = [A[i][k] * B[k][j] for k in range(n)
                     if not _zero(A[i][k]) and not _zero(B[k][j])]
            return sum(terms[1:], terms[0])

        out = [prod(Mm, Om, i, j) - prod(Om, Mm, i, j) for i, j in idx]
        out += [-sum((Om[i][k] * g[k] for k in range(n) if k != i), ops.hy.expression(0.0))
                for i in range(n)]
        return out

    return System(f"control general J = diag{J}", names, ("a", "b"), build)
