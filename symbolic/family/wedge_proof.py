r"""The identities of the all-$n$ proof that every $H_k$ is a first integral (row S6:wedge-integrals).

The proof (proofs/s6_wedge_integrals.py states it in full) has two steps.

**Collapse.** For *any* skew $\Omega$, along $\dot M = [M, \Omega]$, $\dot\gamma = -\Omega\gamma$ (so $\dot M^{\wedge k} = -D_\Omega M^{\wedge k}$
and $\dot B = -[\Omega, B] + a[\Omega, EE^T]$),

.. math::  \dot H_k = 2a\langle D_\Omega Y, D_{EE^T}Y\rangle = -2a\,\langle\iota_E Y, \iota_{\Omega E}Y\rangle, \qquad Y = (2 + D_B)^{-1}M^{\wedge k}.

**Vanishing.** Let $V \ni E, \gamma$ be a 2-plane, $e = E$, $f \perp e$ in $V$, $U = V^\perp$ (so $BU = 0$, $BV \subset V$),
$M = m_0 + e\wedge p + f\wedge q + \mu\, e\wedge f$ ($m_0 \in \Lambda^2U$, $p, q \in U$), $m^{(j)} = m_0^{\wedge j}/j!$,
$C = (2 + B|_V)^{-1}$, $c = 2 + \operatorname{tr}B|_V$, $\omega_e = C_{ee}p + C_{ef}q$, $\omega_f = C_{fe}p + C_{ff}q$. Then
$M^{\wedge k}/k! = m^{(k)} + e\wedge p\wedge m^{(k-1)} + f\wedge q\wedge m^{(k-1)} + e\wedge f\wedge(\mu m^{(k-1)} - p\wedge q\wedge m^{(k-2)})$ and

.. math::
    Y = \tfrac12 m^{(k)} + e\wedge\omega_e\wedge A + f\wedge\omega_f\wedge A + \tfrac1c\,e\wedge f\wedge(\mu A - p\wedge q\wedge A'),\quad
    A = m^{(k-1)},\ A' = m^{(k-2)},

$\Omega = L_\gamma^{-1}M$ is the case $k = 1$, $u = \Omega e = -\omega_e - \tfrac{\mu}{c} f$, and
$\langle\iota_eY, \iota_uY\rangle = T_1 + T_2 + T_3$ with
$T_1 = -\tfrac12\langle\omega_e\wedge A, \iota_{\omega_e}m^{(k)}\rangle = -\tfrac12\langle\omega_e\wedge\omega_e\wedge A, m^{(k)}\rangle = 0$,
$T_2 = \tfrac{\mu}{c}\big(\langle A, \iota_{\omega_e}(\omega_f\wedge A)\rangle - \langle\omega_e\wedge A, \omega_f\wedge A\rangle\big) = 0$ and
$T_3 = -\tfrac1c\langle p\wedge q\wedge A', \iota_{\omega_e}(\omega_f\wedge A)\rangle = -\tfrac1c\langle\omega_e\wedge p\wedge q\wedge A', \omega_f\wedge A\rangle = 0$
($\iota_x$ is the adjoint of $x\wedge$, $x\wedge x = 0$, $\omega_e \in \operatorname{span}\{p, q\}$).

This module computes each side of each equality at an exact point, in either engine's rationals, in
coordinates where $e = E_n$, $f = E_{n-1}$ (0-based indices $n-1$, $n-2$) and $U$ is spanned by the others;
$B$ is any symmetric matrix supported on $V$ (the axisymmetric $B$ with $\gamma \in V$ is one of them,
and every point of $P$ is moved to such a $\gamma$ by $SO(n-1)$, eq:action).
"""

from __future__ import annotations

import functools

from chaplygin_nd.symbolic.family import wedge_integrals as wi

__all__ = ["wedge", "form", "collapse_residual", "vanishing_terms"]


def wedge(X: dict, Y: dict, zero) -> dict:
    r"""$X\wedge Y$ of forms (dicts $I \mapsto$ coefficient, $I$ sorted) in the basis $e_I$."""
    out: dict = {}
    for I, x in X.items():
        if x == 0:
            continue
        for J, y in Y.items():
            if y == 0:
                continue
            shuffle = _shuffle(I, J)
            if shuffle is None:
                continue
            K, even = shuffle
            out[K] = out.get(K, zero) + (x * y if even else -(x * y))
    return out


@functools.lru_cache(maxsize=1 << 16)
def _shuffle(I: tuple, J: tuple):
    """(sorted I + J, whether the shuffle that sorts I + J is even), or None when I and J meet."""
    if set(I) & set(J):
        return None
    # sign of the shuffle that sorts I + J: count pairs (i in I, j in J) with i > j
    inv = sum(1 for i in I for j in J if i > j)
    return tuple(sorted(I + J)), inv % 2 == 0


def form(values: list, basis: list) -> dict:
    """A form from its coefficients in ``basis`` (the order of :func:`wedge_integrals.subsets`)."""
    return dict(zip(basis, values, strict=True))


def _scale(X: dict, s) -> dict:
    return {I: s * v for I, v in X.items()}


def _add(*forms: dict) -> dict:
    out: dict = {}
    for X in forms:
        for I, v in X.items():
            out[I] = out[I] + v if I in out else v
    return out


def _same(X: dict, Y: dict, zero) -> bool:
    return all(X.get(I, zero) == Y.get(I, zero) for I in set(X) | set(Y))


def _resolvent(Mq, B, n, k, engine, zero, one):
    basis = wi.subsets(n, 2 * k)
    W = wi.wedge_power(Mq, n, k, zero, one)
    return form(W, basis), form(wi.solve(wi.shifted(B, n, 2 * k, zero), W, engine, zero), basis)


def collapse_residual(M, gamma, a, b, k: int, Omega, engine: str = "sympy"):
    r"""$\dot H_k + 2a\langle\iota_EY, \iota_{\Omega E}Y\rangle$ along $\dot M = [M, \Omega]$, $\dot\gamma = -\Omega\gamma$ for the
    given skew ``Omega`` (any rotation rate, not only $L_\gamma^{-1}M$): zero by the collapse step
    (module docstring). The rate is :func:`wedge_integrals.rate`, the other side is computed here."""
    num, zero, one = wi.numbers(engine)
    n = M.rows
    Mq, g, _, _, B, _, _ = wi.point_fields(M, gamma, a, b, engine, Omega)
    _, Y = _resolvent(Mq, B, n, k, engine, zero, one)
    E = [zero] * (n - 1) + [one]
    u = [sum((num(Omega[i, j]) * E[j] for j in range(n)), zero) for i in range(n)]
    lhs = wi.rate(M, gamma, a, b, k, engine, Omega)
    return lhs + 2 * num(a) * wi.inner(wi.interior(E, Y, zero), wi.interior(u, Y, zero), zero)


def vanishing_terms(M, BV, k: int, engine: str = "sympy") -> dict[str, object]:
    r"""The equalities of the vanishing step (module docstring) at an exact point: ``M`` a SymPy skew
    $n\times n$ matrix, ``BV`` a symmetric $2\times2$ (rows/columns $f, e$) giving $B$ supported on
    $V = \operatorname{span}\{E_{n-1}, E_n\}$. Returns residuals (each must be zero) named by the step:
    the splitting of $M$, $Y$ against its closed form, $u = \Omega e$, $\langle\iota_eY, \iota_uY\rangle - (T_1 + T_2 + T_3)$,
    and $T_1, T_2, T_3$ in both forms (before and after moving $\iota$ across)."""
    num, zero, one = wi.numbers(engine)
    n = M.rows
    if n < 4:
        raise ValueError("the vanishing step needs n >= 4 (dim U >= 2)")
    e, f = n - 1, n - 2
    Mq = [[num(M[i, j]) for j in range(n)] for i in range(n)]
    B = [[zero] * n for _ in range(n)]
    for r, i in enumerate((f, e)):
        for s, j in enumerate((f, e)):
            B[i][j] = num(BV[r][s])
    U = range(n - 2)
    m0 = {(i, j): Mq[i][j] for i in U for j in U if i < j}
    p = {(i,): -Mq[i][e] for i in U}
    q = {(i,): -Mq[i][f] for i in U}
    mu = Mq[e][f]
    ve, vf = {(e,): one}, {(f,): one}
    res: dict[str, object] = {}
    rebuilt = _add(m0, wedge(ve, p, zero), wedge(vf, q, zero), _scale(wedge(ve, vf, zero), mu))
    res["M = m0 + e^p + f^q + mu e^f"] = int(not _same(rebuilt, {(i, j): Mq[i][j] for i, j in wi.subsets(n, 2)}, zero))
    # C = (2 + B_V)^{-1} in the basis (e, f), c = 2 + tr B_V
    bee, bef, bff = B[e][e], B[e][f], B[f][f]
    det = (2 + bee) * (2 + bff) - bef * bef
    Cee, Cef, Cff = (2 + bff) / det, -bef / det, (2 + bee) / det
    c = 2 + bee + bff
    om_e = _add(_scale(p, Cee), _scale(q, Cef))
    om_f = _add(_scale(p, Cef), _scale(q, Cff))

    def power(j):   # m^{(j)}: the Pfaffians of the U-block
        if j < 0:
            return {}
        memo: dict = {}
        return {I: wi.pfaffian(Mq, I, zero, one, memo) for I in wi.subsets(n - 2, 2 * j)}
    mk, A, A2 = power(k), power(k - 1), power(k - 2)
    pq = wedge(p, q, zero)
    tail = _add(_scale(A, mu), _scale(wedge(pq, A2, zero), -one))
    Y_closed = _add(_scale(mk, one / 2), wedge(ve, wedge(om_e, A, zero), zero),
                    wedge(vf, wedge(om_f, A, zero), zero),
                    _scale(wedge(wedge(ve, vf, zero), tail, zero), one / c))
    _, Y = _resolvent(Mq, B, n, k, engine, zero, one)
    res["Y = (2 + D_B)^{-1} M^k against its closed form"] = int(not _same(Y, Y_closed, zero))
    pairs = wi.subsets(n, 2)
    om = wi.solve(wi.shifted(B, n, 2, zero), [Mq[i][j] for i, j in pairs], engine, zero)
    Om = [[zero] * n for _ in range(n)]
    for (i, j), v in zip(pairs, om, strict=True):
        Om[i][j], Om[j][i] = v, -v
    u = [Om[i][e] for i in range(n)]
    u_closed = [-om_e.get((i,), zero) for i in range(n)]
    u_closed[f] = u_closed[f] - mu / c
    res["u = Omega e = -omega_e - (mu/c) f"] = int(u != u_closed)
    Ev = [one if i == e else zero for i in range(n)]
    total = wi.inner(wi.interior(Ev, Y, zero), wi.interior(u, Y, zero), zero)
    oe = [om_e.get((i,), zero) for i in range(n)]
    ofA = wedge(om_f, A, zero)
    T1 = -wi.inner(wedge(om_e, A, zero), wi.interior(oe, mk, zero), zero) / 2
    T2 = mu / c * (wi.inner(A, wi.interior(oe, ofA, zero), zero)
                   - wi.inner(wedge(om_e, A, zero), ofA, zero))
    T3 = -wi.inner(wedge(pq, A2, zero), wi.interior(oe, ofA, zero), zero) / c
    res["<i_e Y, i_u Y> - (T1 + T2 + T3)"] = total - (T1 + T2 + T3)
    res["T1"] = T1
    res["T1 moved: <omega_e^omega_e^A, m^(k)>"] = wi.inner(wedge(om_e, wedge(om_e, A, zero), zero), mk, zero)
    res["T2"] = T2
    res["T3"] = T3
    res["T3 moved: <omega_e^p^q^A', omega_f^A>"] = wi.inner(wedge(om_e, wedge(pq, A2, zero), zero), ofA, zero)
    res["<i_e Y, i_u Y>"] = total
    return res
