r"""Section 3 of the paper (vertical and horizontal momentum), as printed (DESIGN rule 1).

Sets are transcribed as their defining functions (the set is where all of them vanish) together
with the stated dimensions; proof steps as the equalities they assert.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.symbolic.algebra import wedge


def _dot(u: sp.Matrix, v: sp.Matrix) -> sp.Expr:
    return (u.T * v)[0]


def V_3d(M, gamma) -> sp.Matrix:
    r"""eq:VHgeneraln (line 286): ``\mathcal{V} = \{ (M,\gamma) \in P \, : \, M\times \gamma =0\}``."""
    return M.cross(gamma)


def H_3d(M, gamma) -> dict[str, sp.Expr]:
    r"""eq:VHgeneraln (lines 286-287): ``\mathcal{H} = \{ (M,\gamma) \in P \, : \, f_2=\langle M,
    \gamma \rangle=0\}`` — the printed condition names the integral $f_2$ and equates it with
    $\langle M,\gamma\rangle$. Returned: both expressions the line writes equal to zero, with
    $f_2 = \lVert M\rVert^2$ as defined on line 185."""
    return {"f_2": _dot(M, M), "<M,gamma>": _dot(M, gamma)}


def dimensions_3d() -> dict[str, int]:
    r"""eq:VHgeneraln (lines 289-290): ``These are submanifolds of $P$, of dimension 3 and 4
    respectively`` (V then H); and $\mathcal{V}\cap\mathcal{H} = \{M = 0\}$ (line 291)."""
    return {"V": 3, "H": 4, "V∩H": 2}


def euler_top_lambda_step(lam) -> dict[str, sp.Expr]:
    r"""P:EulerTop, proof (line 316): ``$M(t)=\lambda \gamma(t)$ for a scalar $\lambda$ that is
    necessarily constant since it satisfies $f_1(M_0,\gamma_0)=f_1(M(t),\gamma (t))=\lambda^2$``.
    Returned: the value the proof assigns to $f_1$ on $M = \lambda\gamma$."""
    return {"f_1": lam**2}


def euler_top_energy_step(lam, Omega, gamma) -> sp.Expr:
    r"""P:EulerTop, proof (line 316): ``$2H=\lambda \langle \Omega (t), \gamma (t) \rangle$``."""
    return lam * _dot(Omega, gamma)


def vert_3d_residual(Omega, Omega_dot, tilde_inertia) -> sp.Matrix:
    r"""eq:vert-3D (line 310): ``{\tilde \I} \dot \Omega = ({\tilde \I}\Omega) \times \Omega.``"""
    return tilde_inertia * Omega_dot - (tilde_inertia * Omega).cross(Omega)


def V_nd(M, gamma) -> sp.Matrix:
    r"""eq:def-H-V (line 329): ``\mathcal{V} = \{(M,\gamma)\in P \, : \ M\gamma =0 \}``."""
    return M * gamma


def H_nd(M, gamma) -> sp.Matrix:
    r"""eq:def-H-V (line 329): ``\mathcal{H} = \{(M,\gamma)\in P \, : \, M-(M\gamma)\wedge \gamma =0 \}``."""
    return M - wedge(M * gamma, gamma)


def space_forms(n: int) -> dict[str, sp.Matrix]:
    r"""eq:def-H-V (lines 335-337): the space representation of $M$ on $\mathcal{V}$ and on
    $\mathcal{H}$: ``\begin{pmatrix} \so(n-1) & {\bf 0} \\ {\bf 0} & 0 \end{pmatrix}`` and
    ``\begin{pmatrix} {\bf 0}_{(n-1)\times (n-1)} & \R^{n-1} \\ -(\R^{n-1} )^T  & 0 \end{pmatrix}``
    (with $e_n$ the normal). Returned as 0/1 masks: 1 where an entry may be non-zero."""
    V = sp.zeros(n, n)
    V[: n - 1, : n - 1] = sp.ones(n - 1, n - 1) - sp.eye(n - 1)
    H = sp.zeros(n, n)
    H[: n - 1, n - 1] = sp.ones(n - 1, 1)
    H[n - 1, : n - 1] = sp.ones(1, n - 1)
    return {"V": V, "H": H}


def dimensions_nd(n: int) -> dict[str, int]:
    r"""eq:def-H-V (line 340): ``the dimension of $\mathcal{V}$ is $\frac{n(n-1)}{2}$  whereas that
    of $\mathcal{H}$ is $2(n-1)$``."""
    return {"V": n * (n - 1) // 2, "H": 2 * (n - 1)}
