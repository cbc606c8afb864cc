r"""The equilibria of the reduced $n = 5$ sphere and the critical set of its six integrals
(row S6:euler-jacobi-n5).

On the principal stratum of $P/SO(4)$ the reduced field vanishes at $\pi(p)$ iff the field on $P$ is tangent to
the orbit there: $X(p) = Y_\xi(p)$ for some $\xi \in \mathfrak{so}(4)$, where $Y_\zeta(M, \gamma) = ([\zeta, M], \zeta\gamma)$. As
$X(p) = -Y_\Omega(p)$, this says that $\eta = \Omega + \xi$ fixes $p$: $Y_\eta(p) = 0$ (i.e. $[\eta, M] = 0$, $\eta\gamma = 0$) with
$(\eta - \Omega)E_5 = 0$. Two kinds:

* $\eta = 0$, i.e. $\Omega E_5 = 0$ (a four-parameter family in the quotient). For $\zeta = w\wedge E_5$ the
  collapse identity of S6:wedge-integrals ($k = 1$) gives $dH(Y_\zeta) \propto a\langle\Omega E_5, \Omega\zeta E_5\rangle = 0$, and the
  coefficients $c_i$ of $p(\lambda, \sigma)$ are $SO(5)$-invariant, so $dc_i(Y_\zeta) = 0$: five of the six integrals vanish
  on the images of $Y_{w\wedge E_5}$, $w \perp E_5$, a 4-dimensional subspace of $T Z$ when the $SO(5)$-orbit of $p$ has
  dimension 10. Hence their rank on $TZ$ is at most $8 - 4 = 4$, and the six have rank $\le 5 < 6$.
* $\eta \ne 0$: $p$ is fixed by $\eta$, so (up to $SO(5)$) it lies in the family of :func:`isotropy_family_matrix`,
  where the four $SO(5)$-invariant coefficients $c$ of $p(\lambda, \sigma)$ have rank $\le 3$ (exact, over
  $\mathbb{Q}(\mu, m_1, m_2, m_3)$); with $H$ and $F$ the six have rank $\le 5 < 6$. (The same holds in the first kind
  when the $SO(5)$-orbit has dimension $< 10$: then some $\eta \ne 0$ fixes $p$.)

:func:`eta_point` builds exact rational points of the second kind ($\eta$ of rank 2: $\gamma \perp$ its plane, $M$ in
its centraliser, the linear equations $(L_\gamma^{-1}M - \eta)E_5 = 0$ solved exactly, free unknowns drawn), and
:func:`orbit_checks` the exact facts used for the first kind at a point.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.symbolic import algebra, model
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.family import independence as ind
from chaplygin_nd.symbolic.family import wedge_integrals as wi

__all__ = ["eta_point", "orbit_checks", "fixed_by", "isotropy_family_matrix"]


def _wedge(u, v):
    return u * v.T - v * u.T


def eta_point(rng, a, b):
    r"""An exact point $(M, \gamma, \eta)$ of $P$ with $Y_\eta(p) = 0$, $(\Omega - \eta)E_5 = 0$, $\eta E_5 \ne 0$ (module
    docstring), or ``None`` when the drawn linear system has no solution. $\eta = \theta\,v_1\wedge v_2$ with $v_1 = e_1$,
    $v_2 = c\,e_2 + s\,e_5$ ($c^2 + s^2 = 1$, $s \ne 0$), $\gamma$ a rational unit vector of the plane's complement, $M =
    \mu\,v_1\wedge v_2 + M'$ with $M' \in \mathfrak{so}$ of the complement."""
    e = [sp.Matrix([1 if i == j else 0 for i in range(5)]) for j in range(5)]
    t = points.rational(rng, 1, 3, nonzero=True)
    c, s = (1 - t**2) / (1 + t**2), 2 * t / (1 + t**2)
    v1, v2 = e[0], c * e[1] + s * e[4]
    w = [e[2], e[3], -s * e[1] + c * e[4]]                 # orthonormal basis of the complement
    gw = points.sphere_point(rng, 3)
    gamma = sum((gw[i] * w[i] for i in range(3)), sp.zeros(5, 1))
    theta = points.rational(rng, 1, 2, nonzero=True)
    eta = theta * _wedge(v1, v2)
    unknowns = sp.symbols("mu m1:4")
    M = unknowns[0] * _wedge(v1, v2) + unknowns[1] * _wedge(w[0], w[1]) + unknowns[2] * _wedge(w[0], w[2]) \
        + unknowns[3] * _wedge(w[1], w[2])
    L = model.L_matrix(gamma, sp.diag(1, 1, 1, 1, 1 + a), b)
    Om = algebra.unvec(list(L.LUsolve(sp.Matrix(algebra.vec(M)))), 5)
    A, rhs = sp.linear_eq_to_matrix([sp.expand(v) for v in (Om - eta) * e[4]], unknowns)
    try:
        sol, free = A.gauss_jordan_solve(rhs)
    except ValueError:   # inconsistent for this draw
        return None
    sol = sol.subs({f: points.rational(rng, -2, 2) for f in free})
    return M.subs(dict(zip(unknowns, sol, strict=True))), gamma, eta


def fixed_by(M, gamma, eta) -> bool:
    """$[\\eta, M] = 0$ and $\\eta\\gamma = 0$ exactly."""
    return (eta * M - M * eta).is_zero_matrix and (eta * gamma).is_zero_matrix


def orbit_checks(M, gamma, a, b, engine: str = "sympy") -> dict:
    r"""At a point of $P$: the rank of the $SO(5)$ generators $Y_{e_i\wedge e_j}$ (10 when the isotropy is finite), of the
    $SO(4)$ ones (6 on the principal stratum), and
    the values of $dc_i$ and $dH$ on $Y_{e_m\wedge E_5}$, $m \le 4$ (all zero when $\Omega E_5 = 0$), each in ``engine``'s
    numbers."""
    num, zero, one = wi.numbers(engine)
    n = 5
    pairs = wi.subsets(n, 2)
    Mq = [[num(M[i, j]) for j in range(n)] for i in range(n)]
    g = [num(v) for v in gamma]

    def Y(i, j):
        X = [[zero] * n for _ in range(n)]
        X[i][j], X[j][i] = one, -one
        XM = [[sum((X[r][t] * Mq[t][c] - Mq[r][t] * X[t][c] for t in range(n)), zero) for c in range(n)]
              for r in range(n)]
        return [XM[r][c] for r, c in pairs] + [sum((X[r][t] * g[t] for t in range(n)), zero) for r in range(n)]
    gens = [Y(i, j) for i, j in pairs]
    _, cgrads = ind.coefficient_gradients(M, gamma, engine)
    hgrad = wi.gradient(M, gamma, a, b, 1, engine)
    vals = [sum((x * y for x, y in zip(grad, Y(m, 4), strict=True)), zero)
            for grad in [*cgrads, hgrad] for m in range(4)]
    so4 = [Y(i, j) for i, j in pairs if j < 4]
    return {"orbit_rank": ind._rank(gens, engine), "so4_rank": ind._rank(so4, engine), "values": vals}


def isotropy_family_matrix():
    r"""The differentials on $TP$ of the four non-constant coefficients $c$ of $p(\lambda, \sigma) = \det(M + \sigma\gamma\gamma^T - \lambda)$
    (:math:`\lambda^3, \lambda, \sigma\lambda^2, \sigma`) along the family $M = \mu\,e_1\wedge e_2 + M'$, $M' \in \mathfrak{so}(\operatorname{span}\{e_3, e_4, e_5\})$
    ($M'_{34} = m_1$, $M'_{35} = m_2$, $M'_{45} = m_3$), $\gamma = e_5$: a $4\times14$ matrix over $\mathbb{Q}[\mu, m_1, m_2, m_3]$ (the
    column of $\gamma_5$, normal to the sphere, dropped). Every point of $P$ fixed by some $\eta \ne 0$ is, up to
    $SO(5)$ (which keeps the rank of $dc$), in this family: if $\eta$ has rank 2, $\eta = \theta\,v_1\wedge v_2$ fixes $(M, \gamma)$ iff
    $\gamma \perp v_1, v_2$ and $M \in \mathfrak{so}(\Pi)\oplus\mathfrak{so}(\Pi^\perp)$; if it has rank 4, $\gamma$ spans $\ker\eta$ and $M \in \mathfrak{so}(\gamma^\perp)$,
    which a plane of $M$'s normal form fixes with rank 2. Returns (matrix, symbols)."""
    n = 5
    pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]
    Ms = sp.symbols("M12 M13 M14 M15 M23 M24 M25 M34 M35 M45")
    g = sp.symbols("g1:6")
    lam, sig = sp.symbols("lambda sigma")
    mu, m1, m2, m3 = sp.symbols("mu m1 m2 m3")
    from sympy.polys.matrices import DomainMatrix
    from sympy.polys.rings import ring

    # the determinant, its coefficients, their derivatives and the restriction to the family are all
    # formed in QQ[M, g, lambda, sigma] (ring arithmetic; the same polynomials as with expressions)
    R, *gens = ring((*Ms, *g, lam, sig), sp.QQ)
    Mr, gr, L, S = gens[:10], gens[10:15], gens[15], gens[16]
    mat = [[S * gr[i] * gr[j] - (L if i == j else 0) for j in range(n)] for i in range(n)]
    for (i, j), v in zip(pairs, Mr, strict=True):
        mat[i][j], mat[j][i] = mat[i][j] + v, mat[j][i] - v
    det = DomainMatrix([[R(e) for e in row] for row in mat], (n, n), R.to_domain()).det()

    def coeff(i, j):   # the coefficient of lambda^i sigma^j, an element of R free of lambda, sigma
        return R({m[:15] + (0, 0): c for m, c in det.terms() if m[15:] == (i, j)})
    coeffs = [coeff(i, j) for i, j in ((3, 0), (1, 0), (2, 1), (0, 1))]
    F, *fam = ring((mu, m1, m2, m3), sp.QQ)
    # M = mu e_12 + m1 e_34 + m2 e_35 + m3 e_45, gamma = e_5: the images of M12..M45, g1..g5
    image = (fam[0], 0, 0, 0, 0, 0, 0, fam[1], fam[2], fam[3], 0, 0, 0, 0, 1)

    def on_family(p):
        out = F(0)
        for m, c in p.terms():
            term = F(c)
            for v, e in zip(image, m[:15], strict=True):
                if e:
                    term *= v**e
            out += term
        return out.as_expr()
    rows = [[on_family(c.diff(v)) for v in (*Mr, *gr[:4])] for c in coeffs]
    return sp.Matrix(rows), (mu, m1, m2, m3)
