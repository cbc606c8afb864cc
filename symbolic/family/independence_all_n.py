r"""Independence of the $2n - 2 - \lfloor n/2\rfloor$ invariant integrals for every $n$: the finite identities of
the argument (row S6:wedge-independence).

**The argument.** Let $c$ be the $n - 1$ non-constant coefficients of $p(\lambda, \sigma)$ and $h = (H_1, \dots, H_K)$,
$K = \lceil n/2\rceil - 1$. (i) The $c_i$ are invariant under all of $SO(n)$, so $dc$ vanishes on the tangent of the
orbit $O = SO(n)\cdot p$ and $\operatorname{rank}(dc, dh)_p \ge \operatorname{rank} dc_p + \operatorname{rank}(dh_p|_{T_pO})$. (ii) $h(g\cdot p) =
\varphi(g^{-1}E_n)$ with $\varphi_k(e) = \langle M^{\wedge k}, (2 + D_{a ee^T + b\gamma\gamma^T})^{-1}M^{\wedge k}\rangle$ at the fixed $p = (M, \gamma)$
($D$ is equivariant and the inner product invariant), and $g \mapsto g^{-1}E_n$ is a submersion onto $S^{n-1}$, so
$\operatorname{rank}(dh_p|_{T_pO}) = \operatorname{rank} d\varphi_{E_n}$ on $T_{E_n}S^{n-1}$ (for finite isotropy). (iii) At $b = 0$,
$D_{ee^T} = e\wedge\iota_e$ is a projection, so $(2 + aD_{ee^T})^{-1} = \tfrac12 + (\tfrac1{2+a} - \tfrac12)\,e\wedge\iota_e$ and
$\varphi_k(e) = \tfrac12\lVert W\rVert^2 - \tfrac{a}{2(2+a)}\lVert\iota_eW\rVert^2$, $W = M^{\wedge k}$ (coefficients $\operatorname{Pf}M_{II}$). For
$M = \sum_j\theta_j f_{2j-1}\wedge f_{2j}$ (an orthonormal frame $f$, $t_j = \theta_j^2$, $r_j(e)^2 = (f_{2j-1}\cdot e)^2 + (f_{2j}\cdot e)^2$):

.. math::
    \varphi_k(e) = \tfrac12 e_k(t) - \tfrac{a}{2(2+a)}\sum_j t_j\,e_{k-1}(t_{\ne j})\,r_j(e)^2

(:func:`closed_form_residual`). (iv) The $K\times\lfloor n/2\rfloor$ matrix $A_{kj} = t_je_{k-1}(t_{\ne j})$ has full rank on the
tangent of $\{\sum_j r_j^2 (+ r_0^2) = 1\}$: for odd $n$ it is $A = V\operatorname{diag}(t)$ with $V_{kj} = e_{k-1}(t_{\ne j})$ square, for
even $n$ its missing last row is $e_{n/2}(t)(1, \dots, 1)$, so the condition is again $\det V \ne 0$; and
$\det V \ne 0$ for distinct $t_j$ because the polynomials $\prod_{i\ne j}(1 + t_iy) = \sum_k V_{kj}y^{k-1}$ are independent
(at $y = -1/t_l$ only the $l$-th is non-zero). So $\operatorname{rank} d\varphi = K$ where every $r_j \ne 0$ (and $r_0 \ne 0$ for odd $n$).
(v) $\operatorname{rank} dc = n - 1$ at such a point with $\gamma$ generic (partial fractions:
$p = \det(M - \lambda)(1 + \sigma\gamma^T(M - \lambda)^{-1}\gamma)$ gives the $t_j$ and the weights $\lVert\gamma_j\rVert^2$, $n - 1$ independent
functions). Hence the rank is $(n - 1) + K = 2n - 2 - \lfloor n/2\rfloor$ at $b = 0$, every $a \notin \{0, -2\}$. For fixed $a$ and $p$
the minors of $d\varphi$ are rational functions of $b$, regular where $L_\gamma$ is invertible, and one is non-zero at
$b = 0$: it has finitely many zeros, so the rank is full for every such $a$ and all but finitely many $b$ (depending
on $a$), on an open dense set of $P$ (:mod:`symbolic.family.exceptional_b` computes those $b$ at a point).

Computed here, at exact points, every step in one engine's numbers: (iii) for every $k$, (iv)
as the rank of $d\varphi_{E_n}$ from the closed form, (v) as the rank of $dc$; with $b = 0$ the operator $2 + D_B$
is diagonal, so this is cheap to $n = 16$ and beyond.
"""

from __future__ import annotations

import itertools

import sympy as sp
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.family import independence as ind
from chaplygin_nd.symbolic.family import wedge_integrals as wi

__all__ = ["frame_point", "elementary", "closed_form_residual", "phi_rank", "c_tangent_rows", "c_rank"]


def frame_point(rng, n: int):
    r"""$(M, \gamma, f, \theta)$: $M = \sum_j\theta_jf_{2j-1}\wedge f_{2j}$ in a random rational orthonormal frame $f$ (the
    columns of a Cayley rotation) with distinct non-zero rational $\theta_j$, and a random $\gamma \in S^{n-1}$."""
    f = points.rational_rotation(rng, n)
    m = n // 2
    theta: list = []
    while len(theta) < m:
        v = points.rational(rng, 1, 4, nonzero=True)
        if v not in theta:
            theta.append(v)
    M = sp.zeros(n, n)
    for j in range(m):
        u, v = f[:, 2 * j], f[:, 2 * j + 1]
        M += theta[j] * (u * v.T - v * u.T)
    return M, points.sphere_point(rng, n), f, theta


def elementary(t: list, k: int, zero, one):
    """$e_k(t)$, the elementary symmetric polynomial (any numbers)."""
    if k < 0:
        return zero
    out = zero
    for S in itertools.combinations(range(len(t)), k):
        term = one
        for i in S:
            term = term * t[i]
        out = out + term
    return out


def _frame_data(f, theta, num, one):
    n = f.rows
    t = [num(v) ** 2 for v in theta]
    # r_j(E_n)^2 and the gradients of r_j(e)^2 at e = E_n along e_1..e_{n-1}
    r2 = [num(f[n - 1, 2 * j]) ** 2 + num(f[n - 1, 2 * j + 1]) ** 2 for j in range(len(t))]
    dr2 = [[2 * (num(f[i, 2 * j]) * num(f[n - 1, 2 * j]) + num(f[i, 2 * j + 1]) * num(f[n - 1, 2 * j + 1]))
            for i in range(n - 1)] for j in range(len(t))]
    return t, r2, dr2


def closed_form_residual(M, gamma, f, theta, a, k: int, engine: str = "sympy"):
    r"""$H_k - \big(\tfrac12e_k(t) - \tfrac{a}{2(2+a)}\sum_jt_je_{k-1}(t_{\ne j})r_j(E_n)^2\big)$ at $b = 0$ (module docstring, (iii)):
    zero. $H_k$ by :func:`symbolic.family.wedge_integrals.value` (the resolvent solved, not the closed form)."""
    num, zero, one = wi.numbers(engine)
    t, r2, _ = _frame_data(f, theta, num, one)
    a_ = num(a)
    closed = elementary(t, k, zero, one) / 2
    closed -= a_ / (2 * (2 + a_)) * sum((t[j] * elementary(t[:j] + t[j + 1:], k - 1, zero, one) * r2[j]
                                         for j in range(len(t))), zero)
    return wi.value(M, gamma, a, 0, k, engine) - closed


def phi_rank(f, theta, engine: str = "sympy") -> int:
    r"""The rank of $(d\varphi_1, \dots, d\varphi_K)$ at $e = E_n$ on $T_{E_n}S^{n-1} = \operatorname{span}(e_1..e_{n-1})$ from the closed
    form (the common factor $-a/(2(2+a))$ dropped): rows $\sum_jt_je_{k-1}(t_{\ne j})\,\partial_i r_j^2$, $k = 1..K$."""
    num, zero, one = wi.numbers(engine)
    n = f.rows
    t, _, dr2 = _frame_data(f, theta, num, one)
    K = (n + 1) // 2 - 1
    rows = [[sum((t[j] * elementary(t[:j] + t[j + 1:], k - 1, zero, one) * dr2[j][i] for j in range(len(t))), zero)
             for i in range(n - 1)] for k in range(1, K + 1)]
    return ind._rank(rows, engine)


def c_tangent_rows(M, gamma, engine: str = "sympy") -> list[list]:
    r"""The differentials of the $n - 1$ coefficients of $p(\lambda, \sigma)$ at $(M, \gamma)$ restricted to $TP$:
    each gradient in $((M_{ij})_{i<j}, \gamma)$ with its $\gamma$ part projected on $\gamma^\perp$
    ($v \mapsto v - \langle v, \gamma\rangle\gamma$; domain $\lVert\gamma\rVert = 1$)."""
    num, zero, _ = wi.numbers(engine)
    n = M.rows
    _, grads = ind.coefficient_gradients(M, gamma, engine)
    g = [num(v) for v in gamma]
    N = n * (n - 1) // 2
    return [row[:N] + [row[N + i] - g[i] * sum((row[N + s] * g[s] for s in range(n)), zero) for i in range(n)]
            for row in grads]


def c_rank(M, gamma, engine: str = "sympy") -> int:
    """The rank on $TP$ of the differentials of the $n - 1$ coefficients of $p(\\lambda, \\sigma)$ at $(M, \\gamma)$
    (:func:`c_tangent_rows`)."""
    return ind._rank(c_tangent_rows(M, gamma, engine), engine)
