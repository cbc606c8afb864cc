r"""The ansatz of the Hamiltonisation search: $O(n-1)$-equivariant bivectors on
$P = \mathfrak{so}(n)\times S^{n-1}$ of the weight that can carry the field (row S7:poisson-search).

Coordinates $z = (M_{ij})_{i<j} \cup (\gamma_k)$, $\nabla F = \sum_{i<j} \partial_{M_{ij}}F\, E_i\wedge E_j$
(the Killing-orthonormal basis of symbolic/algebra.py). A bivector $\Pi$ is the skew matrix
$\Pi_{ab} = \{z_a, z_b\}$.

**Why this shape.** $X$ of eq:motion-general scales like $M \mapsto \lambda M$, $X \mapsto \lambda X$
($\dot M$ is quadratic in $M$, $\dot\gamma$ linear) and $H = \tfrac12\langle M, \Omega\rangle$ like
$\lambda^2$. For a multiplier $\rho(\gamma)$ the component of $\Pi$ that can satisfy $\Pi\,dH = \rho X$
is the one of weight $-1$: the $MM$ block linear in $M$, the $M\gamma$ block independent of $M$, the
$\gamma\gamma$ block zero. We search in that class (an $M$-inhomogeneous $\Pi$ is not covered).

**The building blocks.** With $E = E_n$, $x = \gamma_n$, $\xi, \eta \in \mathfrak{so}(n)$ (the two
differentials), $T_0, \dots, T_5$ the six equivariant maps of symbolic/axisym_inverse.py and
$\ell(\xi) = \langle\xi\gamma, E\rangle$:

* $MM$: $\langle T_j(M), [\xi, \eta]\rangle$; $\ell(\xi)\langle\eta, T_j(M)\rangle - (\xi\leftrightarrow\eta)$;
  $\langle M\gamma, E\rangle(\langle\xi\gamma, \eta E\rangle - \langle\eta\gamma, \xi E\rangle)$;
  $\langle\xi u, M\eta v\rangle$ skew-symmetrised for $(u, v) \in \{(\gamma,\gamma), (E,E), (\gamma,E)\}$;
  $\langle\xi u, \eta w\rangle - (\xi\leftrightarrow\eta)$ for $u \in \{\gamma, E\}$, $w \in \{M\gamma, ME\}$.
* $M\gamma$: $\xi\gamma$, $\xi E$, $\ell(\xi)\gamma$, $\ell(\xi)E$.

Every block is multiplied by $x^k$, $0 \le k \le d$ (on the sphere the $O(n-1)$-invariants of $\gamma$
are the functions of $x$). :func:`completeness` checks, at a rational point of a slice, that these
blocks span every $O(n-2)$-invariant tensor of the block's type (the stabiliser of $\gamma$): then
every $O(n-1)$-equivariant bivector of weight $-1$ is $\sum_u r_u(x) B_u$ with $r_u$ rational in $x$,
and the box "degree $\le d$" is a statement about numerators.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import sympy as sp
from chaplygin_nd.symbolic.algebra import _pairs, skew_symbols, so_basis, vector_symbols
from chaplygin_nd.symbolic.axisym_inverse import ansatz_terms

__all__ = ["Ansatz", "coordinates", "mm_blocks", "mg_blocks", "block_bivectors", "ansatz",
           "completeness", "MM_NAMES", "MG_NAMES"]


def _dot(u: sp.Matrix, v: sp.Matrix):
    return (u.T * v)[0, 0]


def _kil(A: sp.Matrix, B: sp.Matrix):
    n = A.rows
    return sum(A[i, j] * B[i, j] for i in range(n) for j in range(i + 1, n))


MM_NAMES = tuple([f"<T{j}(M),[xi,eta]>" for j in range(6)]
                 + [f"l(xi)<eta,T{j}(M)> - swap" for j in range(6)]
                 + ["<M g,E>(<xi g,eta E> - swap)", "<xi g,M eta g>", "<xi E,M eta E>",
                    "<xi g,M eta E> - swap", "<xi g,eta M g> - swap", "<xi g,eta M E> - swap",
                    "<xi E,eta M g> - swap", "<xi E,eta M E> - swap"])
MG_NAMES = ("xi g", "xi E", "l(xi) g", "l(xi) E")


def mm_blocks(xi, eta, M, gamma, E, T=None) -> list:
    r"""The skew bilinear forms $B(\xi, \eta)$, linear in $M$, of the $MM$ block (module docstring);
    exact for symbolic or rational entries, any $n \ge 3$. ``T``: ``ansatz_terms(M, gamma)`` when
    the caller has it (it does not depend on $\xi, \eta$). Products are taken vector first
    ($M(\eta\gamma)$, not $(M\eta)\gamma$): the same values, without $n\times n$ products."""
    T = ansatz_terms(M, gamma) if T is None else T
    xg, yg, xE, yE = xi * gamma, eta * gamma, xi * E, eta * E
    Mg, ME = M * gamma, M * E
    br = xi * eta - eta * xi
    lx, ly = _dot(xg, E), _dot(yg, E)
    out = [_kil(t, br) for t in T]
    out += [lx * _kil(eta, t) - ly * _kil(xi, t) for t in T]
    out.append(_dot(Mg, E) * (_dot(xg, yE) - _dot(yg, xE)))
    out.append(_dot(xg, M * yg))
    out.append(_dot(xE, M * yE))
    out.append(_dot(xg, M * yE) - _dot(yg, M * xE))
    for xu, yu in ((xg, yg), (xE, yE)):          # u = gamma, then u = E
        for w in (Mg, ME):
            out.append(_dot(xu, eta * w) - _dot(yu, xi * w))
    return out


def mg_blocks(xi, gamma, E) -> list:
    r"""The linear maps $\xi \mapsto C(\xi) \in \mathbb{R}^n$ of the $M\gamma$ block (module docstring)."""
    lx = _dot(xi * gamma, E)
    return [xi * gamma, xi * E, lx * gamma, lx * E]


def coordinates(n: int) -> tuple[sp.Matrix, sp.Matrix, list[sp.Symbol]]:
    """The symbolic point: $M$ (symbols ``M_ij``), $\\gamma$ (``gamma_k``), and the coordinate list
    $z$ in the order of the bivector's rows (the $M_{ij}$, $i<j$, then the $\\gamma_k$)."""
    M = skew_symbols("M_", n)
    gamma = vector_symbols("gamma_", n)
    z = [M[i, j] for i, j in _pairs(n)] + list(gamma)
    return M, gamma, z


def _E(n: int) -> sp.Matrix:
    e = sp.zeros(n, 1)
    e[n - 1] = 1
    return e


def block_bivectors(n: int, M, gamma) -> list[sp.Matrix]:
    r"""Each building block as an $N\times N$ skew matrix, $N = \dim\mathfrak{so}(n) + n$, at the
    point $(M, \gamma)$ (symbolic or rational): $MM$ blocks first, then $M\gamma$ blocks."""
    basis = so_basis(n)
    m, N, E = len(basis), len(basis) + n, _E(n)
    mm: list[list] = [[None] * m for _ in range(m)]
    T = ansatz_terms(M, gamma)
    for p in range(m):
        for q in range(p + 1, m):
            mm[p][q] = mm_blocks(basis[p], basis[q], M, gamma, E, T)
    out = []
    for u in range(len(MM_NAMES)):
        P = sp.zeros(N, N)
        for p in range(m):
            for q in range(p + 1, m):
                v = sp.expand(mm[p][q][u])
                P[p, q], P[q, p] = v, -v
        out.append(P)
    mg = [mg_blocks(basis[p], gamma, E) for p in range(m)]
    for u in range(len(MG_NAMES)):
        P = sp.zeros(N, N)
        for p in range(m):
            for k in range(n):
                v = sp.expand(mg[p][u][k])
                P[p, m + k], P[m + k, p] = v, -v
        out.append(P)
    return out


@dataclass(frozen=True)
class Ansatz:
    """The basis of a box: ``bivectors[u] = x^k B_j`` with ``labels[u] = (block name, k)``;
    ``coords`` the coordinate symbols; ``n``, ``degree`` d."""

    n: int
    degree: int
    coords: tuple
    labels: tuple
    bivectors: tuple


@lru_cache(maxsize=8)
def ansatz(n: int, degree: int) -> Ansatz:
    r"""Every block times $x^k$, $0 \le k \le d$ (the box of degree $d$), as symbolic bivectors."""
    _, _, z = coordinates(n)
    names = MM_NAMES + MG_NAMES
    labels, bivs = [], []
    for j in range(len(names)):
        for k in range(degree + 1):
            labels.append((names[j], k))
            bivs.append(_power_block(n, j, k))
    return Ansatz(n, degree, tuple(z), tuple(labels), tuple(bivs))


@lru_cache(maxsize=4)
def _symbolic_blocks(n: int) -> list[sp.Matrix]:
    """:func:`block_bivectors` at the symbolic point of :func:`coordinates` (one per $n$: every box
    of every degree is built from the same blocks)."""
    M, gamma, _ = coordinates(n)
    return block_bivectors(n, M, gamma)


@lru_cache(maxsize=512)
def _power_block(n: int, j: int, k: int) -> sp.Matrix:
    r"""$x^k B_j$ with $x = \gamma_n$, expanded (shared by the boxes of degree $\ge k$); not to be
    mutated (the boxes share it)."""
    B = _symbolic_blocks(n)[j]
    if k == 0:
        return B
    # expand(x^k e) by one product in Q[z] (the same expanded expression, 2.5x faster)
    R, *z = sp.ring(coordinates(n)[2], sp.QQ)
    xk = z[-1] ** k
    return B.applyfunc(lambda e: (R(e) * xk).as_expr() if e != 0 else e)


def _invariant_dimension(n: int, shape: str, gamma0: sp.Matrix) -> int:
    """dim of the O(n-2)-invariant tensors of the block type at gamma0 = (0,..,0,s,x)."""
    basis = so_basis(n)
    m = len(basis)
    # the stabiliser of gamma0 and E in O(n): rotations and one reflection of the first n-2 axes
    gens = [B for B in so_basis(n) if all(B[i, j] == 0 for i in range(n) for j in range(n)
                                          if i >= n - 2 or j >= n - 2)]
    refl = sp.eye(n)
    refl[0, 0] = -1

    def coords(A):  # so(n) coordinates
        return [A[i, j] for i, j in _pairs(n)]

    def act_so(g, A):  # Ad_g on so(n), as a matrix on coordinates (g orthogonal or generator)
        return sp.Matrix([coords(g * b * g.T) for b in basis]).T

    def ad(Y):
        return sp.Matrix([coords(Y * b - b * Y) for b in basis]).T

    idx: list[tuple]
    if shape == "mm":  # T[c, p, q], p < q: linear in M (index c), skew in (xi, eta)
        idx = [(c, p, q) for c in range(m) for p in range(m) for q in range(p + 1, m)]
    else:  # T[p, k]: so(n) -> R^n
        idx = [(p, k) for p in range(m) for k in range(n)]
    pos = {t: i for i, t in enumerate(idx)}
    unknowns = sp.symbols(f"t0:{len(idx)}")

    def tensor(key):
        if shape == "mm":
            c, p, q = key
            if p == q:
                return 0
            return unknowns[pos[(c, p, q)]] if p < q else -unknowns[pos[(c, q, p)]]
        return unknowns[pos[key]]

    eqs = []
    for kind, Y in [("lie", Y) for Y in gens] + [("group", refl)]:
        A = (ad(Y) if kind == "lie" else act_so(Y, None)).tolist()   # lists: fast entry access
        V = (Y if kind == "lie" else refl).tolist()
        nz = [[j for j in range(m) if A[i][j] != 0] for i in range(m)]
        for key in idx:
            if shape == "mm":
                c, p, q = key[0], key[1], key[2]
                # (g.T)[c,p,q] = sum A[c,c'] A[p,p'] A[q,q'] T[c',p',q'] (contragredient = same: orthogonal)
                if kind == "lie":
                    val = (sum(A[c][cc] * tensor((cc, p, q)) for cc in nz[c])
                           + sum(A[p][pp] * tensor((c, pp, q)) for pp in nz[p])
                           + sum(A[q][qq] * tensor((c, p, qq)) for qq in nz[q]))
                else:
                    val = sum(A[c][cc] * A[p][pp] * A[q][qq] * tensor((cc, pp, qq))
                              for cc in nz[c] for pp in nz[p] for qq in nz[q]) - tensor(key)
            else:
                p, k = key[0], key[1]
                if kind == "lie":
                    val = (sum(A[p][pp] * tensor((pp, k)) for pp in nz[p])
                           + sum(V[k][kk] * tensor((p, kk)) for kk in range(n) if V[k][kk] != 0))
                else:
                    val = sum(A[p][pp] * V[k][kk] * tensor((pp, kk)) for pp in nz[p]
                              for kk in range(n) if V[k][kk] != 0) - tensor(key)
            if val != 0:
                eqs.append(val)
    if not eqs:
        return len(idx)
    mat, _ = sp.linear_eq_to_matrix(eqs, unknowns)
    from sympy.polys.matrices import DomainMatrix
    return len(idx) - DomainMatrix.from_Matrix(mat).convert_to(sp.QQ).rank()


def _linear_coefficients(n: int, gamma0: sp.Matrix, E: sp.Matrix) -> dict:
    r"""``{(p, q, c): [B_u(basis[p], basis[q]) at M = basis[c] for each MM block u]}``, exact: each
    form evaluated once at the symbolic $M = \sum_c \mu_c\,\mathrm{basis}[c]$ (:func:`skew_symbols`),
    expanded in $\mathbb{Q}[\mu]$, checked homogeneous of degree 1, and its coefficient of $\mu_c$
    taken (one evaluation per $(p, q)$ instead of one per $(p, q, c)$)."""
    basis = so_basis(n)
    m = len(basis)
    Ms = skew_symbols("mu", n)
    mus = [Ms[i, j] for i, j in _pairs(n)]
    R, *gens = sp.ring(mus, sp.QQ)
    out: dict = {}
    T = ansatz_terms(Ms, gamma0)
    for p in range(m):
        for q in range(p + 1, m):
            polys = [R(sp.expand(f)) for f in mm_blocks(basis[p], basis[q], Ms, gamma0, E, T)]
            if any(sum(k) != 1 for f in polys for k in f.keys()):
                raise ArithmeticError("an MM block is not linear in M")
            for c in range(m):
                out[(p, q, c)] = [R.domain.to_sympy(f.coeff(gens[c])) for f in polys]
    return out


def completeness(n: int) -> dict:
    r"""At $\gamma_0 = (0, \dots, 0, 3/5, 4/5)$: the dimension of the $O(n-2)$-invariant tensors of
    each block type and the rank of the building blocks there (exact, over $\mathbb{Q}$). Equal
    numbers mean that the blocks span every $O(n-1)$-equivariant bivector of weight $-1$ over
    the rational functions of $x$ (an equivariant tensor field is fixed by its values on the slice)."""
    from sympy.polys.matrices import DomainMatrix

    gamma0 = sp.zeros(n, 1)
    gamma0[n - 2], gamma0[n - 1] = sp.Rational(3, 5), sp.Rational(4, 5)
    basis, E = so_basis(n), _E(n)
    m = len(basis)
    # the forms are linear in M: the coefficient of the coordinate c of M (the form at
    # M = basis[c]) is read off the form at the symbolic M, checked homogeneous linear there
    forms = _linear_coefficients(n, gamma0, E)
    rows_mm = [[forms[(p, q, c)][u] for p in range(m) for q in range(p + 1, m) for c in range(m)]
               for u in range(len(MM_NAMES))]
    rows_mg = []
    for u in range(len(MG_NAMES)):
        rows_mg.append([mg_blocks(basis[p], gamma0, E)[u][k] for p in range(m) for k in range(n)])
    rank = lambda rows: DomainMatrix.from_Matrix(sp.Matrix(rows)).convert_to(sp.QQ).rank()  # noqa: E731
    return {"n": n, "mm_invariant": _invariant_dimension(n, "mm", gamma0), "mm_rank": rank(rows_mm),
            "mg_invariant": _invariant_dimension(n, "mg", gamma0), "mg_rank": rank(rows_mg)}
