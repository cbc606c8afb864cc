r"""The invariant measure of the reduced $n = 5$ sphere in a chart of the quotient, and the
push-forward of the measure of $P$ (row S6:euler-jacobi-n5).

$Z = \{R_1 = R_2 = 0\} \subset \mathbb{R}^{10}$ (S6:reduced-n5) is, where $J = \det\partial(R_1, R_2)/\partial(y, y') \ne 0$,
the graph of $(y, y') = \phi(z)$ over the chart $z = r \setminus \{y, y'\} \in \mathbb{R}^8$; here
$(y, y') = (S_{qq}, A_+)$, so $J = B\,(A_-(B(x^2-1) + G^2) + E_-^2)$. On $Z$ the reduced field is $X = N/D$
(it is tangent to $Z$), and in the chart its components are $X_i$, $i \in z$.

**Liouville in the chart** (no lemma on residues). The density $\tilde\rho = \Delta^{-3/2}/J$ on the chart
is invariant iff $\sum_{i\in z}\frac{d}{dz_i}(\tilde\rho X_i) = 0$ on $Z$, where $\frac{d}{dz_i}h = \partial_ih - (\partial_yh, \partial_{y'}h)
\,J_{yy'}^{-1}(\partial_iR_1, \partial_iR_2)^T$ is the derivative along $Z$ (implicit functions). Writing
$\frac{d}{dz_i}(\Delta^{-3/2}g) = \Delta^{-3/2}(\frac{d}{dz_i}g - \tfrac32 g\,\partial_i\Delta/\Delta)$ and clearing denominators,
this is the polynomial identity :func:`chart_divergence` $= q_1R_1 + q_2R_2$, checked exactly
(symbolic $a, b$) by the row — in this chart and in every other pair $(y, y')$ with $J_{yy'} \ne 0$
(:func:`charts`, 44 pairs), which together cover the regular part of $Z$; the densities $\Delta^{-3/2}/\lvert J_{yy'}\rvert$ agree on
every overlap (:func:`chart_transition_residuals`, checked by the row), so they are one density on the regular part of $Z$.

**Push-forward.** The measure of $P$ is $\Delta^{-3/2}\,dM\,d\gamma$ (P:Measure, $n = 5$), the volume of the
Euclidean metric in $((M_{ij})_{i<j}, \gamma)$ restricted to $P$, times $\Delta^{-3/2}$. By the coarea formula its
push-forward under $z\circ\pi : P \to \mathbb{R}^8$ has, on the principal stratum, the density
$\Delta^{-3/2}\,\operatorname{vol}(SO(4)\cdot p)/J_\pi$ with $J_\pi^2 = \det(dz\,\Pi\,dz^T)$ ($\Pi$ the projection on $TP$)
and $\operatorname{vol}(SO(4)\cdot p)^2 = c\,\det\operatorname{Gram}(Y_{12}, \dots, Y_{34})$, $Y_{ij}$ the generators of the
action at $p$ ($c$ a constant: the volume of $SO(4)$ and the order of the isotropy, constant on the
principal stratum). :func:`pushforward_ratio` returns $\det\operatorname{Gram}\cdot J^2/\det(dz\,\Pi\,dz^T)$ at a point
of $P$: it is the same number at every point iff the push-forward *is* $\tilde\rho$ up to a constant,
the fibre-volume factor included.
"""

from __future__ import annotations

from functools import cache

from chaplygin_nd.symbolic.family import euler_jacobi_n5 as ej

__all__ = ["CHART_OUT", "chart_jacobian", "chart_divergence", "relation_s_polynomial", "charts",
           "chart_transition_residuals", "pushforward_ratio"]

#: The two coordinates solved for on $Z$: $(y, y') = (S_{qq}, A_+)$.
CHART_OUT = ("Sqq", "Ap")


def _d(h, name):
    return h.diff(ej.coordinates()[name])


@cache
def chart_jacobian(out: tuple[str, str] = CHART_OUT):
    r"""$J = \det\partial(R_1, R_2)/\partial(y, y')$ for the pair ``out`` $= (y, y')$ of reduced coordinates, and the
    $2\times2$ matrix (ring elements)."""
    R1, R2 = ej.relations()
    y, yp = out
    mat = [[_d(R1, y), _d(R1, yp)], [_d(R2, y), _d(R2, yp)]]
    return mat[0][0] * mat[1][1] - mat[0][1] * mat[1][0], mat


@cache
def chart_divergence(out: tuple[str, str] = CHART_OUT):
    r"""$T = 2J^3D^2\Delta^{5/2}\sum_{i\in z}\frac{d}{dz_i}(\Delta^{-3/2}X_i/J)$ as a polynomial of
    :data:`symbolic.reduction.invariants_n5.INV_RING` (module docstring): zero on $Z$ iff the chart
    density $\Delta^{-3/2}/J$ is invariant. Returns ``(T, (q1, q2), remainder)`` with $T = q_1R_1 + q_2R_2 +$
    remainder (multivariate division by $R_1, R_2$ and :func:`relation_s_polynomial`, its quotient on $g_3$ carried back
    to $R_1, R_2$)."""
    N, D = ej.field()
    R1, R2 = ej.relations()
    J, (r1, r2) = chart_jacobian(out)
    y, yp = out
    adj = [[r2[1], -r1[1]], [-r2[0], r1[0]]]   # adjugate of [[dR1/dy, dR1/dy'], [dR2/dy, dR2/dy']]
    Dl = ej._Delta()
    DJ = D * J
    zero = R1 * 0
    z = [i for i in ej.r5.COORDS if i not in out]
    # c[s][i] = (adj(dR/d(y, y')) dR/dz_i)_s: J times d/dz_i = J d_i - d_y c[0][i] - d_y' c[1][i]
    dR = {i: (_d(R1, i), _d(R2, i)) for i in z}
    c = [{i: adj[s][0] * dR[i][0] + adj[s][1] * dR[i][1] for i in z} for s in range(2)]
    V = [sum((N[i] * c[s][i] for i in z), zero) for s in range(2)]

    def N_Jd(h):
        """sum_i N_i J d/dz_i h over the chart, with the two corrections summed before the product."""
        return J * sum((N[i] * _d(h, i) for i in z), zero) - _d(h, y) * V[0] - _d(h, yp) * V[1]

    # sum_i [(Jd(N_i) DJ - N_i Jd(DJ)) 2 Delta - 3 N_i DJ Jd(Delta)], each sum over i taken before its
    # products with DJ and Delta (the same polynomial, a few large products instead of 8 per coordinate)
    div_N = sum((J * _d(N[i], i) - _d(N[i], y) * c[0][i] - _d(N[i], yp) * c[1][i] for i in z), zero)
    T = (div_N * DJ - N_Jd(DJ)) * Dl * 2 - 3 * DJ * N_Jd(Dl)
    if T == 0:
        return T, (R1 * 0, R1 * 0), T
    g3, (u, v) = relation_s_polynomial()
    (h1, h2, h3), rem = T.div([R1, R2, g3])
    return T, (h1 + h3 * u, h2 + h3 * v), rem


@cache
def relation_s_polynomial():
    r"""$(g_3, (u, v))$ with $g_3 = uR_1 + vR_2$: the S-polynomial of $R_1, R_2$ in the lex order of
    :data:`symbolic.reduction.invariants_n5.INV_RING`, reduced by them (the quotients tracked). Dividing by
    $(R_1, R_2, g_3)$ instead of $(R_1, R_2)$ alone leaves remainder 0 for the divergence in every chart (a plain division
    by $R_1, R_2$ does not for the charts that solve for $x$); the cofactors it gives are checked as an identity by the row."""
    R1, R2 = ej.relations()
    (m1, c1), (m2, c2) = R1.LT, R2.LT
    lcm = tuple(max(i, j) for i, j in zip(m1, m2, strict=True))
    ring = R1.ring
    t1 = ring({tuple(l - i for l, i in zip(lcm, m1, strict=True)): 1 / c1})
    t2 = ring({tuple(l - i for l, i in zip(lcm, m2, strict=True)): 1 / c2})
    (h1, h2), g3 = (t1 * R1 - t2 * R2).div([R1, R2])
    return g3, (t1 - h1, -t2 - h2)


@cache
def charts() -> tuple:
    r"""Every pair $(y, y')$ of reduced coordinates with $J_{yy'} = \det\partial(R_1, R_2)/\partial(y, y') \ne 0$ as a polynomial
    (44 of the 45: $\partial(R_1, R_2)/\partial(A_+, A_-)$ vanishes identically). Where $dR_1 \wedge dR_2 \ne 0$ some $J_{yy'}$ is
    non-zero (they are its coefficients), so these charts cover the regular part of $Z$ (implicit functions)."""
    import itertools

    return tuple(out for out in itertools.combinations(ej.r5.COORDS, 2) if chart_jacobian(out)[0] != 0)



def chart_transition_residuals() -> list:
    r"""For every unordered pair of charts $c = (y, y')$, $c' = (u, u')$ of :func:`charts`: the residual of
    $J_c^k\det\partial z'/\partial z = \pm J_c^{k-1}J_{c'}$, $k = \lvert c\setminus c'\rvert$ (the sign that makes it smaller),
    as polynomials (ring elements). On $Z$, $z' = r \setminus c'$ is a function of $z = r \setminus c$ whose
    Jacobian is the identity on the shared coordinates and $\partial\phi_r/\partial z_s$ ($r \in c\setminus c'$,
    $s \in c'\setminus c$) elsewhere, with $J_c\,\partial\phi/\partial z_s = -\operatorname{adj}(\partial R/\partial c)\,\partial R/\partial z_s$
    (implicit functions). All residuals zero means $\lvert\det\partial z'/\partial z\rvert = \lvert J_{c'}/J_c\rvert$
    wherever both charts are defined: the chart densities $\Delta^{-3/2}/\lvert J_c\rvert$ are one density on the
    regular part of $Z$. Domain: the relations of S6:reduced-n5."""
    import itertools

    R1, R2 = ej.relations()
    out = []
    for c, cp in itertools.combinations(charts(), 2):
        J, m = chart_jacobian(c)
        Jp, _ = chart_jacobian(cp)
        adj = [[m[1][1], -m[0][1]], [-m[1][0], m[0][0]]]
        rows = [c.index(r) for r in c if r not in cp]
        cols = [s for s in cp if s not in c]

        def scaled(r, s, adj=adj):   # J_c times d(phi_r)/d(z_s)
            dR = (_d(R1, s), _d(R2, s))
            return -(adj[r][0] * dR[0] + adj[r][1] * dR[1])

        if len(rows) == 1:
            lhs, rhs = scaled(rows[0], cols[0]), Jp
        else:
            lhs = scaled(rows[0], cols[0]) * scaled(rows[1], cols[1]) - scaled(rows[0], cols[1]) * scaled(rows[1], cols[0])
            rhs = J * Jp
        difference = lhs - rhs   # the identity holds up to the sign of the orientation: lhs = +rhs or -rhs
        out.append(difference if difference == 0 else lhs + rhs)
    return out

def _det(rows, engine):
    n = len(rows)
    if engine == "flint":
        import flint
        return flint.fmpq_mat(n, n, [v for r in rows for v in r]).det()
    import sympy as sp
    from sympy.polys.matrices import DomainMatrix
    return DomainMatrix([list(r) for r in rows], (n, n), sp.QQ).det()


def pushforward_ratio(M, gamma, engine: str = "sympy"):
    r"""$\det\operatorname{Gram}(Y_{ij})\cdot J^2/\det(dz\,\Pi\,dz^T)$ at the point $(M, \gamma)$ of $P$ (module
    docstring), exactly, every step in ``engine``'s numbers (``sympy``: ``QQ``; ``flint``: ``fmpq``)."""
    from chaplygin_nd.symbolic.family import wedge_integrals as wi
    from chaplygin_nd.symbolic.reduction import invariants_n5 as ri5

    num, zero, one = wi.numbers(engine)
    n = 5
    pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]
    Mq = [[num(M[i, j]) for j in range(n)] for i in range(n)]
    g = [num(v) for v in gamma]
    # generators Y_ij = ([e_ij, M], e_ij gamma) of so(4) (i < j < 5), in the coordinates (M_ij (i<j), gamma)
    gens = []
    for i, j in [(r, c) for r in range(4) for c in range(r + 1, 4)]:
        X = [[zero] * n for _ in range(n)]
        X[i][j], X[j][i] = one, -one
        XM = [[sum((X[r][t] * Mq[t][c] - Mq[r][t] * X[t][c] for t in range(n)), zero) for c in range(n)]
              for r in range(n)]
        gens.append([XM[r][c] for r, c in pairs] + [sum((X[r][t] * g[t] for t in range(n)), zero)
                                                  for r in range(n)])
    gram = [[sum((u * v for u, v in zip(Y, Z, strict=True)), zero) for Z in gens] for Y in gens]
    # gradients of the chart coordinates z (as polynomials in M_ij, gamma) at the point
    polys = ri5.generator_polys()
    R = ri5.RING
    phase = {"x": R.gens[2], **{k: v for k, v in polys.items() if k != "s"}}
    var_idx = [3 + k for k in range(len(pairs))] + list(range(13, 17)) + [2]   # M_ij, q1..q4, x
    at = [zero, zero, g[4]] + [Mq[i][j] for i, j in pairs] + g[:4]

    def ev(p):
        return sum((num(c) * _monomial(m, at, one) for m, c in p.terms()), zero)
    rows = []
    for name in ej.r5.COORDS:
        if name in CHART_OUT:
            continue
        p = phase[name]
        rows.append([ev(p.diff(R.gens[v])) for v in var_idx])
    tang = [row[:len(pairs)] + [row[len(pairs) + s] - g[s] * sum((row[len(pairs) + t] * g[t] for t in range(n)), zero)
                                for s in range(n)] for row in rows]
    gz = [[sum((u * v for u, v in zip(r1, r2, strict=True)), zero) for r2 in tang] for r1 in tang]
    vals = ej.quotient_point(M, gamma)
    J, _ = chart_jacobian()
    Jv = ev_inv(J, vals, num, zero, one)
    return _det(gram, engine) * Jv * Jv / _det(gz, engine)


def _monomial(m, at, one):
    out = one
    for v, e in zip(at, m, strict=True):
        if e:
            out *= v**e
    return out


def ev_inv(p, vals: dict, num, zero, one):
    """Evaluate an element of INV_RING at reduced coordinates ``vals`` (a, b unused by J)."""
    from chaplygin_nd.symbolic.reduction import invariants_n5 as ri5
    names = [str(s) for s in ri5.INV_RING.symbols]
    at = [num(vals[n]) if n in vals else zero for n in names]
    return sum((num(c) * _monomial(m, at, one) for m, c in p.terms()), zero)
