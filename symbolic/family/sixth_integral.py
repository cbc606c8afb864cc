r"""A sixth first integral of the axisymmetric $n = 5$ sphere (row S6:sixth-integral-n5, beyond the paper).

Found by the numerical guide (:mod:`simulate.analysis.integral_guide`: an orbit-constant
combination of $M$-degree 4 over $\Delta$ beyond the products of the known integrals), then fixed by
exact linear algebra over $\mathbb{Q}(a, b)$ in the reduced coordinates of :mod:`symbolic.reduction.reduced_n5` and
written with $\mathfrak{so}(5)$ operations:

.. math::
    w = \star(M\wedge M)/2 \in \mathbb{R}^5,\quad w_i = (-1)^{i-1}\operatorname{Pf}(M_{\hat\imath\hat\imath})
    \ (\text{so } Mw = 0),\qquad B = aE_5E_5^T + b\gamma\gamma^T,

.. math::
    F = \frac{\langle w, B(2 + B)w\rangle}{\Delta(x)}
      = \frac{a(a+2)\langle w, E_5\rangle^2 + 2ab\,x\,\langle w, E_5\rangle\langle w, \gamma\rangle
              + b(b+2)\langle w, \gamma\rangle^2}{(2+a)(2+b) - abx^2}\quad (\lVert\gamma\rVert = 1).

$\Delta(x) = \det(2 + B)/2^{n-2}$ (P:Measure), and $L_\gamma(\Omega) = 2\Omega + B\Omega + \Omega B$. The known
integrals in the same objects: $\lVert w\rVert^2 = -c_{\lambda^1}$ and $\langle w, \gamma\rangle^2 = c_{\sigma\lambda^0}$
(eq:pol-first-integrals). In the reduced coordinates $\langle w, E_5\rangle = \operatorname{Pf}K = (A_+ - A_-)/4$ and
$\langle w,\gamma\rangle = \pm L$, $L = (E_+ - E_-)/2 - x(A_+ - A_-)/4$ (up to the sign convention of $w$).
"""

from __future__ import annotations

from functools import cache

import sympy as sp
from chaplygin_nd.symbolic.reduction import invariants_n5 as ri5

__all__ = ["pfaffian_vector", "numerator_ring", "Delta_ring", "numerator_expr", "integral_text",
           "numerator_in_invariants"]

_PAIRS = [(i, j) for i in range(5) for j in range(i + 1, 5)]


def pfaffian_vector(M):
    r"""$w_i = (-1)^{i}\operatorname{Pf}(M$ without row and column $i)$ (0-based $i$) of a $5\times5$ skew
    ``M`` (list of lists, any ring); $Mw = 0$. S6:sixth-integral-n5."""
    def pf4(idx):
        p, q, r, s = idx
        return M[p][q] * M[r][s] - M[p][r] * M[q][s] + M[p][s] * M[q][r]
    return [(-1) ** i * pf4([j for j in range(5) if j != i]) for i in range(5)]


def _numerator(M, gamma, a, b, x):
    w = pfaffian_vector(M)
    oE = w[4]
    og = sum((w[i] * gamma[i] for i in range(1, 5)), w[0] * gamma[0])
    return a * (a + 2) * oE**2 + 2 * a * b * x * oE * og + b * (b + 2) * og**2


@cache
def numerator_ring():
    r"""$N_F = \Delta F$ as an element of :data:`symbolic.reduction.invariants_n5.RING` (S6:sixth-integral-n5)."""
    R = ri5.RING
    g = R.gens
    M = [[R(0)] * 5 for _ in range(5)]
    for k, (i, j) in enumerate(_PAIRS):
        M[i][j], M[j][i] = g[3 + k], -g[3 + k]
    gamma = [g[13 + i] for i in range(4)] + [g[2]]
    return _numerator(M, gamma, g[0], g[1], g[2])


def Delta_ring():
    r"""$\Delta(x) = (2+a)(2+b) - abx^2$ (eq:Delta) in :data:`symbolic.reduction.invariants_n5.RING`."""
    a, b, x = ri5.RING.gens[:3]
    return (2 + a) * (2 + b) - a * b * x**2


def numerator_expr(M, gamma, a, b):
    r"""$N_F$ for a SymPy $5\times5$ skew ``M`` and ``gamma`` (length 5): the same formula on expressions."""
    Ml = [[M[i, j] for j in range(5)] for i in range(5)]
    return _numerator(Ml, list(gamma), a, b, gamma[4])


def integral_text() -> str:
    r"""$F$ as text SymPy parses, in the symbols ``M_ij`` ($i < j$, 1-based), ``gamma_i``, ``a``, ``b``
    (the form of the formula, not expanded). S6:sixth-integral-n5."""
    Ms = {(i, j): sp.Symbol(f"M_{i + 1}{j + 1}") for i, j in _PAIRS}
    M = sp.zeros(5, 5)
    for (i, j), s in Ms.items():
        M[i, j], M[j, i] = s, -s
    gam = sp.symbols("gamma_1:6")
    a, b = sp.symbols("a b")
    N = numerator_expr(M, gam, a, b)
    return f"({sp.sstr(N)})/((2 + a)*(2 + b) - a*b*gamma_5**2)"


@cache
def numerator_in_invariants():
    r"""$N_F$ in the reduced coordinates of :mod:`symbolic.reduction.reduced_n5` ($s \to 1 - x^2$), element of
    :data:`symbolic.reduction.invariants_n5.INV_RING` (S6:sixth-integral-n5)."""
    return ri5.on_sphere(ri5.in_generators(numerator_ring()))
