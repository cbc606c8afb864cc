r"""A Hamiltonisation found by symbolic/search/poisson.py, made explicit and proved exactly
(row S7:poisson-controls).

From a box with solutions: the Gröbner basis is read as rational values of the remaining
unknowns $t_i$ and of $\sigma$ (unknowns left free by it are set to $0$, stated), the bivector
$P = \sum_u c_u x^{k_u} B_{j_u}$ is assembled symbolically, and :func:`prove_structure` proves on
$P = \mathfrak{so}(n)\times S^{n-1}$, as exact identities modulo $\|\gamma\|^2 = 1$ (SymPy and
FLINT, symbolic/exact/identity.py):

.. math::
    P\,d\|\gamma\|^2 = 0, \qquad P\,dH - \Delta^e X = 0, \qquad
    \Delta\,[P, P] + \sigma \textstyle\sum_{\mathrm{cyc}} P_{jk}(P\,d\Delta)_i = 0,

with $dH$ from the derived inverse $L_\gamma^{-1}$ (symbolic/axisym_inverse.py) and
$\partial_{\gamma_k} H = -\tfrac12\langle\Omega, \partial_{\gamma_k}L_\gamma\Omega\rangle$.
:func:`lift_symbolic` re-solves the linear stage over $\mathbb{Q}(a, b)$ with the same free columns
set to zero, so that the structure can be proved for symbolic $a, b$.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.symbolic.algebra import vec
from chaplygin_nd.symbolic.axisym_inverse import inverse_closed_form
from chaplygin_nd.symbolic.axisymmetric import Delta
from chaplygin_nd.symbolic.exact.identity import rational_identity
from chaplygin_nd.symbolic.model import L_matrix_derivative
from chaplygin_nd.symbolic.search import bivector_ansatz as ba
from chaplygin_nd.symbolic.search.poisson import BoxResult, sigma

__all__ = ["solution_values", "structure_matrix", "lift_symbolic", "prove_structure", "borisov_mamaev",
           "structure_text", "symbolic_field", "jacobi_residual"]


def solution_values(res: BoxResult) -> dict | None:
    """Rational values of (t_i, sigma) solving the box's Gröbner basis, the unknowns it leaves
    free set to 0; None when the basis is not linear (then the solution set is not read off)."""
    sol = res.solution
    if sol is None:
        return None
    gb, gens = sol["groebner"], sol["gens"]
    if any(sp.Poly(g, *gens).total_degree() > 1 for g in gb):
        return None
    free = [v for v in gens if v not in set().union(*(sp.sympify(g).free_symbols for g in gb))]
    eqs = list(gb) + [v for v in free if v != sigma]
    sol = sp.solve(eqs, gens, dict=True)
    if len(sol) != 1:
        return None
    vals = {v: sol[0].get(v, sp.Integer(0)) for v in gens}
    if sigma in free:
        vals[sigma] = sp.Integer(0)
    vals["free"] = [str(v) for v in free]
    return vals


def structure_matrix(res: BoxResult, values: dict) -> sp.Matrix:
    """The symbolic bivector P of the solution (entries polynomial in the coordinates)."""
    s = res.solution
    if s is None:
        raise ValueError("the box has no solution to assemble")
    ans: ba.Ansatz = s["ansatz"]
    ts = [v for v in s["gens"] if v != sigma]
    coeffs = [sp.Rational(int(c.p), int(c.q)) for c in s["part"]]
    for t, k in zip(ts, s["kernel"], strict=True):
        coeffs = [c + values[t] * sp.Rational(int(v.p), int(v.q)) for c, v in zip(coeffs, k, strict=True)]
    N = len(ans.coords)
    P = sp.zeros(N, N)
    for u, c in zip(s["cols"], coeffs, strict=True):
        if c != 0:
            P += c * ans.bivectors[u]
    return P.applyfunc(sp.expand)


def symbolic_field(n: int, a, b) -> tuple[sp.Matrix, sp.Matrix, list, list, sp.Expr]:
    r"""Symbolic $M, \gamma$, $dH$ and $X$ on the sphere (derived inverse, eq:M-O) and $\Delta(\gamma_n)$."""
    M, gamma, _ = ba.coordinates(n)
    Om = inverse_closed_form(M, gamma, a, b)
    w = vec(Om)
    dH = list(w) + [-(w.T * L_matrix_derivative(gamma, b, k) * w)[0, 0] / 2 for k in range(n)]
    X = list(vec(M * Om - Om * M)) + list(-Om * gamma)
    return M, gamma, dH, X, Delta(gamma[n - 1], a, b)


def lift_symbolic(res: BoxResult, values: dict, a=None, b=None) -> sp.Matrix:
    r"""The same solution over $\mathbb{Q}(a, b)$: the linear stage re-solved with symbolic $a, b$
    (free columns of the rational solve, and the kernel directions, fixed as in ``values``) by an
    exact solve on the coefficients of the sampled equations. Returns P (entries in
    $\mathbb{Q}(a,b)[M, \gamma]$); its correctness is what :func:`prove_structure` decides."""
    from chaplygin_nd.symbolic.axisymmetric import a as sa
    from chaplygin_nd.symbolic.axisymmetric import b as sb
    from chaplygin_nd.symbolic.exact.points import generator, skew_matrix, sphere_point

    a = sa if a is None else a
    b = sb if b is None else b
    s = res.solution
    if s is None:
        raise ValueError("the box has no solution to lift")
    ans: ba.Ansatz = s["ansatz"]
    n, N = res.n, len(ans.coords)
    cols = s["cols"]
    ts = [v for v in s["gens"] if v != sigma]
    # the coordinates pinned by the rational solution: the free columns of its rref
    free_cols = [max(j for j, v in enumerate(k) if v != 0) for k in s["kernel"]]
    pinned = {j: values[t] for j, t in zip(free_cols, ts, strict=True)}
    unknown = [j for j in range(len(cols)) if j not in pinned]
    M, gamma, dH, X, D = symbolic_field(n, a, b)
    coords = ans.coords
    rng = generator(0, "poisson-lift", n)
    rows, rhs = [], []
    for _ in range(2 * len(cols) // N + 6):
        Mv, gv = skew_matrix(rng, n), sphere_point(rng, n)
        sub = dict(zip(coords, list(vec(Mv)) + list(gv), strict=True))
        dHv = [sp.cancel(e.xreplace(sub)) for e in dH]
        Xv = [sp.cancel(e.xreplace(sub)) for e in X]
        De = D.xreplace(sub) ** res.e
        Bs = [ans.bivectors[u].xreplace(sub) for u in cols]
        for i in range(N):
            coeff = [sum(B[i, j] * dHv[j] for j in range(N)) for B in Bs]
            rows.append([coeff[j] for j in unknown])
            rhs.append(De * Xv[i] - sum(coeff[j] * v for j, v in pinned.items()))
        for i in range(N - n):
            coeff = [sum(B[i, N - n + k] * 2 * gv[k] for k in range(n)) for B in Bs]
            rows.append([coeff[j] for j in unknown])
            rhs.append(-sum(coeff[j] * v for j, v in pinned.items()))
    from sympy.polys.matrices import DomainMatrix

    K = sp.QQ.frac_field(a, b) if isinstance(a, sp.Symbol) else sp.QQ
    A = DomainMatrix.from_list_sympy(len(rows), len(unknown) + 1,
                                     [r + [h] for r, h in zip(rows, rhs, strict=True)]).convert_to(K)
    R, piv = A.rref()
    if len(unknown) in piv or len(piv) != len(unknown):
        raise ArithmeticError("the symbolic linear stage does not determine the solution")
    Rm = R.to_Matrix()
    sol = dict(pinned)
    for i, j in enumerate(piv):
        sol[unknown[j]] = sp.factor(Rm[i, len(unknown)])
    P = sp.zeros(N, N)
    for j, u in enumerate(cols):
        if sol[j] != 0:
            P += sol[j] * ans.bivectors[u]
    return P


def prove_structure(n: int, P: sp.Matrix, sig, e: int, a, b, *, jacobi: bool = True) -> dict:
    r"""Decide the three identities of the module docstring exactly (SymPy and FLINT): returns
    ``{"casimir": Check, "hamilton": Check, "jacobi": Check}``. $a, b$ symbolic or rational."""
    M, gamma, dH, X, D = symbolic_field(n, a, b)
    N = P.rows
    m = N - n
    coords = [M[i, j] for i in range(n) for j in range(i + 1, n)] + list(gamma)
    casimir = [sum(P[i, m + k] * 2 * gamma[k] for k in range(n)) for i in range(m)]
    hamilton = [sum(P[i, j] * dH[j] for j in range(N)) - D**e * X[i] for i in range(N)]
    out = {"casimir": rational_identity(casimir, sphere=list(gamma), label="poisson casimir"),
           "hamilton": rational_identity(hamilton, sphere=list(gamma), label="poisson hamilton")}
    if jacobi:
        out["jacobi"] = rational_identity(jacobi_residual(P, coords, n, a, b, sig),
                                          sphere=list(gamma), label="poisson jacobi")
    return out


def structure_text(P: sp.Matrix, n: int, sig, e: int) -> dict:
    """The structure as text SymPy can parse: {"{z_i, z_j}": "...", ...} for the nonzero brackets
    of Pi = Delta^sigma P (coordinates M_<i><j>, gamma_<k>, 1-based; a, b symbolic), with
    Delta, sigma and the multiplier rho = Delta^(sigma + e)."""
    _, _, coords = ba.coordinates(n)
    x = coords[-1]
    brackets = {f"{{{coords[i]}, {coords[j]}}}": str(sp.factor(P[i, j]))
                for i in range(P.rows) for j in range(i + 1, P.cols) if P[i, j] != 0}
    from chaplygin_nd.symbolic.axisymmetric import a as sa
    from chaplygin_nd.symbolic.axisymmetric import b as sb
    return {"Delta": str(Delta(x, sa, sb)), "sigma": str(sig), "multiplier": f"Delta**({sp.Rational(sig) + e})",
            "bracket": "Delta**sigma * P", "P": brackets}


def borisov_mamaev(a, b) -> sp.Matrix:
    r"""The $n = 3$ structure the search finds (box $(d, e) = (2, 1)$, unique there, $\sigma = -1/2$),
    read off in the blocks of symbolic/search/bivector_ansatz.py by an exact fit over
    $\mathbb{Q}(a, b)$ and proved for symbolic $a, b$ by :func:`prove_structure`:

    .. math::
        \{M_\xi, M_\eta\}_P = -\langle (4 + 2a + ab - b^2 - 2abx^2)M + b(b+2)(M\gamma)\wedge\gamma
        + abx\,(M\gamma)\wedge E_3,\ [\xi, \eta]\rangle, \qquad \{M_\xi, \gamma\}_P = \Delta\,\xi\gamma,

    $\Pi = \Delta^{-1/2}P$, multiplier $\rho = \Delta^{1/2}$: Borisov–Mamaev's Hamiltonisation of the
    Chaplygin ball, in the variables of the paper."""
    M, gamma, _ = ba.coordinates(3)
    B = ba.block_bivectors(3, M, gamma)
    x = gamma[2]
    mm = [-(4 + 2 * a + a * b - b**2 - 2 * a * b * x**2), -b * (b + 2), 0, -a * b * x, 0, 0]
    P = sum((c * B[j] for j, c in enumerate(mm) if c != 0), sp.zeros(6, 6))
    P += Delta(x, a, b) * B[len(ba.MM_NAMES)]
    return P.applyfunc(sp.expand)


def jacobi_residual(Pmat: sp.Matrix, coords, n: int, a, b, sig) -> list[sp.Expr]:
    r"""The Jacobi condition of the module docstring for a symbolic bivector $P$ (entries
    polynomial in the coordinates): $\Delta[P,P]_{ijk} + \sigma\sum_{\mathrm{cyc}}P_{jk}(P\,d\Delta)_i$,
    one polynomial per triple $i<j<k$ (an identity modulo the sphere when $\Pi$ is Poisson).

    When every entry is a polynomial over $\mathbb{Q}$ (in the coordinates and the symbols $a, b$,
    $\sigma$ may carry) the arithmetic runs in SymPy's sparse polynomials and each residual is
    returned expanded (:func:`_jacobi_residual_ring`); otherwise with expressions, as below."""
    fast = _jacobi_residual_ring(Pmat, coords, a, b, sig)
    return fast if fast is not None else _jacobi_residual_expr(Pmat, coords, a, b, sig)


def _jacobi_residual_expr(Pmat: sp.Matrix, coords, a, b, sig) -> list[sp.Expr]:
    """:func:`jacobi_residual` with SymPy expressions (any entries rational in a, b)."""
    N = len(coords)
    x = coords[-1]
    D = Delta(x, a, b)
    dD = sp.diff(D, x)
    dP = [[[sp.diff(Pmat[j, k], coords[l]) for k in range(N)] for j in range(N)] for l in range(N)]
    out = []
    for i in range(N):
        for j in range(i + 1, N):
            for k in range(j + 1, N):
                jac = 0
                for (p, q, r) in ((i, j, k), (j, k, i), (k, i, j)):
                    jac += sum(Pmat[p, l] * dP[l][q][r] for l in range(N))
                extra = (Pmat[j, k] * Pmat[i, N - 1] + Pmat[k, i] * Pmat[j, N - 1]
                         + Pmat[i, j] * Pmat[k, N - 1]) * dD
                out.append(sp.expand(D * jac + sig * extra))
    return out


def _jacobi_residual_ring(Pmat: sp.Matrix, coords, a, b, sig) -> list[sp.Expr] | None:
    r""":func:`jacobi_residual` in $\mathbb{Q}[\text{coords}, \text{parameters}]$ (``PolyElement``
    products and derivatives instead of expression trees), the same polynomials as expanded
    expressions; None when an entry is not a polynomial there (a denominator in $a, b$)."""
    N = len(coords)
    x = coords[-1]
    D = Delta(x, a, b)
    dD = sp.diff(D, x)
    entries = [Pmat[i, j] for i in range(N) for j in range(N)]
    params = set().union(*(sp.sympify(e).free_symbols for e in (*entries, D, sig))) - set(coords)
    R, *gens = sp.ring(list(coords) + sorted(params, key=sp.default_sort_key), sp.QQ)
    try:
        P = [[R(sp.sympify(Pmat[i, j])) for j in range(N)] for i in range(N)]
        RD, RdD, Rsig = R(D), R(dD), R(sp.sympify(sig))
    except Exception:  # CoercionFailed / ValueError: not a polynomial over QQ in these generators
        return None
    dP = [[[P[j][k].diff(gens[l]) for k in range(N)] for j in range(N)] for l in range(N)]
    out = []
    for i in range(N):
        for j in range(i + 1, N):
            for k in range(j + 1, N):
                jac = R.zero
                for (p, q, r) in ((i, j, k), (j, k, i), (k, i, j)):
                    for l in range(N):
                        if P[p][l] and dP[l][q][r]:
                            jac += P[p][l] * dP[l][q][r]
                extra = (P[j][k] * P[i][N - 1] + P[k][i] * P[j][N - 1] + P[i][j] * P[k][N - 1]) * RdD
                out.append((RD * jac + Rsig * extra).as_expr())
    return out
