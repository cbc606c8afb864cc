r"""The full field in $O(n^2)$: $\dot M = [M, \Omega]$ and $\dot\gamma = -\Omega\gamma$ without the matrix $\Omega$.

The derived inverse (P:inversion, :mod:`symbolic.axisym_inverse`) is a sum of rank-2 terms,

.. math::
    \Omega = c_0M + \sum_{k=1}^{5} f_k\, c_k\; u_k\wedge v_k, \qquad
    (u_k, v_k) = (M\gamma, \gamma), (ME_n, E_n), (M\gamma, E_n), (ME_n, \gamma), (\gamma, E_n),

with $f_5 = s := \langle M\gamma, E_n\rangle$ and $f_k = 1$ otherwise. For skew $M$, $[M, M] = 0$ and

.. math::
    [M, u\wedge v] = (Mu)\wedge v + u\wedge(Mv), \qquad (u\wedge v)w = u\langle v, w\rangle - v\langle u, w\rangle,

and the inner products that occur are $\langle\gamma, \gamma\rangle =: g$, $\langle E_n, \gamma\rangle = x$,
$\langle M\gamma, \gamma\rangle = 0$, $\langle ME_n, \gamma\rangle = -s$. So the field is a combination of
wedges and of vectors from the six vectors

.. math::
    V = (M^2\gamma,\ M^2E_n,\ M\gamma,\ ME_n,\ \gamma,\ E_n):\qquad
    \dot M = \sum_{i<j} w_{ij}\, V_i\wedge V_j, \qquad \dot\gamma = \sum_i u_i V_i,

with scalar weights $w_{ij}, u_i \in \mathbb{Q}(a, b, x)[s, g]$. Forming $V$ costs three
matrix-vector products; every wedge $O(n^2)$ — about $7.5n^2$ operations against $2n^3$ for the
matrix products $M\Omega - \Omega M$. :func:`structured_weights` *derives* the weights from the
derived coefficients by the two rules above (no weight is typed by hand; the combination
$c_3 - c_4$ of $(M\gamma)\wedge(ME_n)$ is computed and found to vanish); proofs/s4_structured_field.py
proves the result equal to the derived field exactly (row S4:structured-field).
"""

from __future__ import annotations

from functools import cache

import sympy as sp
from chaplygin_nd.symbolic.algebra import wedge
from chaplygin_nd.symbolic.axisym_inverse import inverse_coefficients
from chaplygin_nd.symbolic.axisymmetric import E_n, x

__all__ = ["VECTORS", "PAIRS", "s", "g", "structured_weights", "structured_field", "vectors"]

#: Names of the vectors $V$, in the order of the weights (see the module docstring).
VECTORS = ("MMgamma", "MME", "Mgamma", "ME", "gamma", "E")
#: The pairs $(i, j)$, $i < j$, of :data:`VECTORS` whose wedges carry the weights $w_{ij}$ (lexicographic).
PAIRS = tuple((i, j) for i in range(len(VECTORS)) for j in range(i + 1, len(VECTORS)))

#: $s = \langle M\gamma, E_n\rangle$ and $g = \langle\gamma, \gamma\rangle$ (symbols of the weights).
s = sp.Symbol("s", real=True)
g = sp.Symbol("gg", positive=True)

# M applied to a named vector, and the inner products <v, gamma> of the named vectors; both are
# exact facts for skew M (<M gamma, gamma> = 0, <M E, gamma> = -<E, M gamma> = -s), checked in
# the ledger row through the final identity.
_APPLY_M = {"gamma": "Mgamma", "E": "ME", "Mgamma": "MMgamma", "ME": "MME"}
_WITH_GAMMA = {"gamma": g, "E": x, "Mgamma": sp.Integer(0), "ME": -s}


def _terms():
    """The rank-2 terms of the derived $\\Omega$ (c_1..c_5 of :mod:`symbolic.axisym_inverse`):
    (coefficient, u, v) with $\\Omega = c_0M + \\sum \\text{coefficient}\\; u\\wedge v$."""
    c = inverse_coefficients()
    return c[0], [(c[1], "Mgamma", "gamma"), (c[2], "ME", "E"), (c[3], "Mgamma", "E"),
                  (c[4], "ME", "gamma"), (s * c[5], "gamma", "E")]


def _simplify(w: sp.Expr) -> sp.Expr:
    return sp.factor(sp.together(w))


@cache
def structured_weights() -> tuple[tuple[sp.Expr, ...], tuple[sp.Expr, ...]]:
    r"""``(w, u)``: the weights $w_{ij}$ (in the order of :data:`PAIRS`) and $u_i$ (order of
    :data:`VECTORS`) of $\dot M = \sum w_{ij} V_i\wedge V_j$, $\dot\gamma = \sum u_i V_i$
    (eq:motion-general with P:inversion), rational functions of $a, b, x$ times polynomials in $s, g$.
    Derived by the commutator rule; valid for any $n \ge 3$, $\Delta(x)(2+a+b) \ne 0$."""
    c0, terms = _terms()
    index = {name: i for i, name in enumerate(VECTORS)}
    pair_w: dict[tuple[int, int], sp.Expr] = {}

    def add_wedge(coef, p, q):
        i, j = index[p], index[q]
        if i == j:
            return  # p ^ p = 0
        key, sign = ((i, j), 1) if i < j else ((j, i), -1)
        pair_w[key] = pair_w.get(key, 0) + sign * coef

    for coef, u, v in terms:  # [M, u ^ v] = (M u) ^ v + u ^ (M v);  [M, c0 M] = 0
        add_wedge(coef, _APPLY_M[u], v)
        add_wedge(coef, u, _APPLY_M[v])
    vec_w: dict[int, sp.Expr] = {index["Mgamma"]: -c0}  # -Omega gamma = -c0 M gamma - ...
    for coef, u, v in terms:  # (u ^ v) gamma = u <v, gamma> - v <u, gamma>
        vec_w[index[u]] = vec_w.get(index[u], 0) - coef * _WITH_GAMMA[v]
        vec_w[index[v]] = vec_w.get(index[v], 0) + coef * _WITH_GAMMA[u]
    w = tuple(_simplify(pair_w.get(p, 0)) for p in PAIRS)
    u = tuple(_simplify(vec_w.get(i, 0)) for i in range(len(VECTORS)))
    return w, u


def vectors(M: sp.Matrix, gamma: sp.Matrix) -> list[sp.Matrix]:
    r"""The vectors $V = (M^2\gamma, M^2E_n, M\gamma, ME_n, \gamma, E_n)$ (three matrix-vector products)."""
    e = E_n(M.rows)
    Mg, Me = M * gamma, M * e
    return [M * Mg, M * Me, Mg, Me, gamma, e]


def structured_field(M: sp.Matrix, gamma: sp.Matrix, a_=None, b_=None) -> tuple[sp.Matrix, sp.Matrix]:
    r"""$(\dot M, \dot\gamma)$ of eq:motion-general in the structured form (S4:structured-field):
    $\sum w_{ij}V_i\wedge V_j$, $\sum u_iV_i$ with the weights of :func:`structured_weights` at
    $x = \gamma_n$, $s = (M\gamma)_n$, $g = \lVert\gamma\rVert^2$. $M$ skew, any $n \ge 3$; ``a_, b_``
    substitute the parameters (default: the symbols)."""
    from chaplygin_nd.symbolic.axisymmetric import a, b

    n = M.rows
    V = vectors(M, gamma)
    sub = {x: gamma[n - 1], s: V[2][n - 1], g: (gamma.T * gamma)[0, 0]}
    if a_ is not None:
        sub[a] = a_
    if b_ is not None:
        sub[b] = b_
    w, u = structured_weights()
    Mdot = sp.zeros(n, n)
    for (i, j), wij in zip(PAIRS, w):
        if wij != 0:
            Mdot += wij.xreplace(sub) * wedge(V[i], V[j])   # = subs(sub, simultaneous=True)
    gdot = sp.zeros(n, 1)
    for ui, v in zip(u, V):
        if ui != 0:
            gdot += ui.xreplace(sub) * v
    return Mdot, gdot
