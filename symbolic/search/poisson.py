r"""Exact search for a Hamiltonisation of eq:motion-general on $P = \mathfrak{so}(n)\times S^{n-1}$
(row S7:poisson-search; the paper's first open problem).

**What is searched.** A bivector $\Pi = \Delta^\sigma P$ with $P = \sum_u c_u\, x^{k_u} B_{j_u}$ in the
box of degree $d$ of symbolic/search/bivector_ansatz.py ($O(n-1)$-equivariant, weight $-1$), and a
multiplier $\rho = \Delta^{\sigma + e}$ ($e \in \mathbb{Z}$; $\sigma$ free, half-integers included),
such that on $P$

.. math::
    P\,dH = \Delta^{e} X, \qquad P\,d\|\gamma\|^2 = 0, \qquad
    \Delta\,[P, P]_{ijk} + \sigma \textstyle\sum_{\mathrm{cyc}} P_{jk}\,(P\,d\Delta)_i = 0,

where $[P, P]_{ijk} = \sum_l P_{il}\partial_l P_{jk} + \mathrm{cyc}$ is the Jacobiator. The last
condition is Jacobi for $\Pi = \Delta^\sigma P$ (for $\phi = \Delta^\sigma$,
$[\phi P, \phi P] = \phi^2 [P, P] + \phi \sum_{\mathrm{cyc}} P_{jk} (P\,d\phi)_i$, times
$\Delta^{1-2\sigma}$). With $\Pi\,d\|\gamma\|^2 = 0$ on the sphere, $\Pi$ is tangent to $P$ and all
three conditions are identities modulo $\|\gamma\|^2 = 1$; then $\{\cdot,\cdot\}_\Pi$ is a Poisson
bracket on $P$ and $\rho X$ is its Hamiltonian field of $H$.

**Exactness (the sandwich).** Every condition is evaluated at seeded rational points of
$\mathfrak{so}(n)\times S^{n-1}$ with exact rationals (FLINT ``fmpq``), for fixed rational $a, b$.
A true solution satisfies every sampled equation, so the sampled solution set *contains* the true
one: an inconsistent sampled linear system, or a Gröbner basis $\{1\}$ of the sampled Jacobi
equations over $\mathbb{Q}$ on the sampled affine space, *proves* that the box holds no
Hamiltonisation. Block dependencies (syzygies) that the points suggest are each proved as exact
identities modulo the sphere before a column is dropped. A solution found is proved by exact
identities (symbolic/exact, SymPy and FLINT) in :func:`prove_structure`.

**Over which $(a, b)$.** A box whose linear stage is inconsistent is carried to every $(a, b)$ off
a proper algebraic subset by symbolic/search/generic_extension.py (``BoxResult.generic`` states
the argument and its minor); a box excluded by Jacobi, with ``jacobi_generic``, off an explicit
curve $\mu\nu = 0$ by the certificate of symbolic/search/jacobi_generic.py (in
``BoxResult.certificate``), otherwise at its $(a, b)$.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from functools import lru_cache

import flint
import sympy as sp
from chaplygin_nd.symbolic.algebra import vec
from chaplygin_nd.symbolic.axisymmetric import Delta, mass_tensor
from chaplygin_nd.symbolic.exact.flint_engine import use_engine
from chaplygin_nd.symbolic.model import angular_velocity
from chaplygin_nd.symbolic.search import bivector_ansatz as ba
from chaplygin_nd.symbolic.search.box_columns import flint_bivectors, jacobi_values
from chaplygin_nd.symbolic.search.box_columns import independent_columns as _independent_columns
from chaplygin_nd.symbolic.search.box_columns import mpoly_context as _ctx
from chaplygin_nd.symbolic.search.box_columns import rref_solve as _rref_solve
from chaplygin_nd.symbolic.search.box_columns import sample_points as _points
from chaplygin_nd.symbolic.search.cost import StageClock
from chaplygin_nd.symbolic.search.point_values import bivector_values as _values
from chaplygin_nd.symbolic.search.point_values import dH_gamma
from chaplygin_nd.symbolic.search.point_values import fq as _fq

__all__ = ["BoxResult", "field_data", "flint_bivectors", "search_box", "estimate", "sigma"]

#: the exponent of the conformal factor $\Delta^\sigma$, an unknown of the Jacobi stage
sigma = sp.Symbol("sigma")


#: per (n, degree, seed): the independent columns of the box; per point: their values there
_COLUMNS: dict = {}
_VALUES: dict = {}


def field_data(n: int, a, b, M: sp.Matrix, gamma: sp.Matrix) -> dict:
    r"""At a rational point of $P$: $dH$ ($\partial_{M_{ij}}H = \Omega_{ij}$,
    $\partial_{\gamma_k}H = -\tfrac12\langle\Omega, \partial_{\gamma_k}L_\gamma\,\Omega\rangle$ for the
    extension $H = \tfrac12\langle M, L_\gamma^{-1}M\rangle$ of eq:M-O to $\mathbb{R}^n$), $X$ of
    eq:motion-general ($[M, \Omega]$, $-\Omega\gamma$) and $\Delta(x)$, $\Delta'(x)$ (eq:Delta), exact."""
    with use_engine("flint"):   # the exact solve of eq:M-O in fmpq_mat (the same rationals)
        Om = angular_velocity(M, gamma, mass_tensor(n, a), b)
    w = vec(Om)
    dg = dH_gamma([_fq(v) for v in w], [_fq(v) for v in gamma], _fq(b), n)
    dH = list(w) + [_q(v) for v in dg]
    X = list(vec(M * Om - Om * M)) + list(-Om * gamma)
    x = gamma[n - 1]
    R, dD = _delta_derivative(a, b)
    return {"dH": dH, "X": X, "Delta": Delta(x, a, b),
            "dDelta": R.domain.to_sympy(dD(R.domain.from_sympy(sp.Rational(x))))}


@lru_cache(maxsize=16)
def _delta_derivative(a, b):
    r"""$\Delta'(x)$ (eq:Delta) at rational $(a, b)$, a polynomial of $\mathbb{Q}[x]$ (derived once per
    $(a, b)$ and evaluated exactly at each point of :func:`field_data`)."""
    xs = sp.Symbol("x")
    R = sp.ring([xs], sp.QQ)[0]
    return R, R(sp.diff(Delta(xs, sp.Rational(a), sp.Rational(b)), xs))


@dataclass
class BoxResult:
    """One box (n, degree d, e) at (a, b): sizes, the outcome and the seconds it took."""

    n: int
    degree: int
    e: int
    a: object
    b: object
    unknowns: int = 0
    independent: int = 0
    syzygies: int = 0
    linear: str = ""            # "inconsistent" or "affine space of dimension k"
    free: int = -1              # dimension of the sampled affine space (-1: empty)
    jacobi_equations: int = 0
    groebner: list = field(default_factory=list)
    stages: dict = field(default_factory=dict)  # CPU seconds per stage (cost.StageClock)
    outcome: str = ""           # "excluded (linear)", "excluded (Jacobi)", "solutions"
    generic: str = ""           # over which (a, b) an exclusion holds (generic_extension.py)
    certificate: dict = field(default_factory=dict)  # a Jacobi exclusion's (jacobi_generic.py)
    seconds: float = 0.0
    solution: dict | None = None

    def as_dict(self) -> dict:
        return {"n": self.n, "degree": self.degree, "e": self.e, "a": str(self.a), "b": str(self.b),
                "unknowns": self.unknowns, "independent": self.independent,
                "syzygies": self.syzygies, "linear": self.linear, "free": self.free,
                "jacobi_equations": self.jacobi_equations,
                "groebner": [str(g) for g in self.groebner][:8], "outcome": self.outcome,
                "generic": self.generic, **({"certificate": self.certificate} if self.certificate else {}),
                "seconds": round(self.seconds, 2)}


def estimate(n: int, degree: int) -> str:
    """A one-line size and CPU-time estimate of a box, stage by stage (symbolic/search/poisson_cost.py)."""
    from chaplygin_nd.symbolic.search.poisson_cost import poisson_cost

    return poisson_cost(n, degree).line()


def search_box(n: int, degree: int, e: int, a, b, *, seed: int, progress=None,
               generic: bool = True, jacobi_generic: bool = False) -> BoxResult:
    """Decide one box exactly (module docstring): the linear stage over QQ, then the Jacobi
    stage by a Gröbner basis over QQ in the remaining unknowns and sigma; with ``generic``, an
    exclusion is carried to generic (a, b) when the check of symbolic/search/generic_extension.py
    passes, a Jacobi one (``jacobi_generic``) when symbolic/search/jacobi_generic.py finds its
    certificate (``generic`` says over which (a, b) it holds)."""
    t0 = time.perf_counter()
    a, b = sp.Rational(a), sp.Rational(b)
    res = BoxResult(n, degree, e, a, b)
    clock = StageClock(res.stages)
    ans = ba.ansatz(n, degree)
    fb = flint_bivectors(ans)
    clock("columns")
    res.unknowns = len(fb)
    key = (n, degree, seed)
    if key not in _COLUMNS:     # the box's columns and their values do not depend on (a, b) or e
        _COLUMNS[key] = _independent_columns(ans, fb, seed)
    cols, res.syzygies = _COLUMNS[key]
    clock("column rank and syzygy proofs")
    res.independent = len(cols)
    N = len(ans.coords)
    m = N - n
    rows, per_point = _linear_rows(n, degree, a, b, seed, fb, cols)
    rhs = []
    for D, X in per_point:
        De = _fq(D ** e)
        rhs += [De * x for x in X] + [flint.fmpq(0)] * m
    clock("conditions")
    part, kernel = _rref_solve(rows, rhs)
    clock("kernel")
    if progress:
        progress(f"  n={n} d={degree} e={e}: linear stage done ({time.perf_counter() - t0:.1f} s)")
    ctx = _ctx(ans.coords)
    if part is None:
        res.linear, res.outcome = "inconsistent", "excluded (linear)"
        if generic:
            _generic(res, fb, cols, seed)
        clock("generic")
        res.seconds = time.perf_counter() - t0
        return res
    res.free = len(kernel)
    res.linear = f"affine space of dimension {len(kernel)}"
    P0 = _combine(fb, cols, part, ctx)
    Ks = [_combine(fb, cols, k, ctx) for k in kernel]
    eqs, ring_gens = jacobi_equations(n, a, b, P0, Ks, seed, ctx)
    res.jacobi_equations = len(eqs)
    clock("jacobi equations")
    if not eqs:
        gb = []
    else:
        gb = list(sp.groebner(eqs, *ring_gens, order="grevlex", domain=sp.QQ).exprs)
    res.groebner = gb
    clock("groebner")
    res.outcome = "excluded (Jacobi)" if gb == [1] else "solutions"
    if res.outcome == "excluded (Jacobi)" and generic:
        _generic(res, fb, cols, seed, jacobi_generic)
    if res.outcome == "solutions":
        res.solution = {"groebner": gb, "gens": ring_gens, "cols": cols, "part": part,
                        "kernel": kernel, "ansatz": ans}
    clock("generic")
    res.seconds = time.perf_counter() - t0
    return res


#: per (n, degree, seed, a, b): the rows of the linear stage and, per point, Delta and X (the
#: boxes of one degree and (a, b) differ only in e, i.e. in the right-hand side Delta^e X)
_ROWS: dict = {}


def _linear_rows(n: int, degree: int, a, b, seed: int, fb: list, cols: list) -> tuple[list, list]:
    r"""The conditions $P\,dH = \Delta^e X$ (rows $i < N$) and $P\,d\|\gamma\|^2 = 0$ (rows
    $i < m$) of :func:`search_box` at its seeded points, on the columns ``cols``: the rows (which do
    not depend on $e$) and, per point, $(\Delta, X)$, exact; kept per (n, degree, seed, a, b)."""
    key = (n, degree, seed, a, b, tuple(cols))
    if key in _ROWS:
        return _ROWS[key]
    N = n * (n - 1) // 2 + n
    m = N - n
    rows, per_point = [], []
    for M, g in _points(n, 2 * (len(cols) // N) + 6, seed, "linear"):
        fd = field_data(n, a, b, M, g)
        pt = [_fq(v) for v in list(vec(M)) + list(g)]
        dH = [_fq(v) for v in fd["dH"]]
        vkey = (n, degree, seed, tuple(pt))
        if vkey not in _VALUES:
            _VALUES[vkey] = [_values(fb[u], pt, N) for u in cols]
        Vs = _VALUES[vkey]
        for i in range(N):
            rows.append([sum((V[i][j] * dH[j] for j in range(N)), flint.fmpq(0)) for V in Vs])
        gg = [2 * _fq(v) for v in g]
        for i in range(m):
            rows.append([sum((V[i][m + k] * gg[k] for k in range(n)), flint.fmpq(0)) for V in Vs])
        per_point.append((fd["Delta"], [_fq(x) for x in fd["X"]]))
    _ROWS[key] = rows, per_point
    return rows, per_point


def _generic(res: BoxResult, fb, cols, seed: int, jacobi: bool = False) -> None:
    """Over which (a, b) an exclusion holds: a linear one for generic (a, b) when the check of
    symbolic/search/generic_extension.py passes; one decided by Jacobi off the curve of the
    certificate of symbolic/search/jacobi_generic.py (with ``jacobi``), else at its (a, b) only."""
    from chaplygin_nd.symbolic.search import generic_extension as ge
    from chaplygin_nd.symbolic.search import jacobi_generic as jg

    at = f"(a, b) = ({res.a}, {res.b})"
    if res.outcome == "excluded (Jacobi)":
        top = jg.MAX_FREE.get(res.n, 0)
        if not jacobi or res.free > top:
            why = "not computed" if not jacobi else f"not attempted at n = {res.n}: {res.free} unknowns > {top}"
            res.generic = f"only at {at} (its certificate over Q(a, b), {jg.WHERE}, {why})"
            return
        _, res.generic, res.certificate = jg.generic_exclusion(res.n, res.degree, res.e, res.a,
                                                               res.b, seed=seed)
        return
    N = res.n * (res.n - 1) // 2 + res.n
    pts = _points(res.n, 2 * (len(cols) // N) + 6, seed, "omega-linear")
    ok, text = ge.linear_generic(res.n, res.a, res.b, res.e, fb, cols, pts,
                                 key=(res.n, res.degree, tuple(cols), seed))
    res.generic = text if ok else f"only at {at} ({text})"


def _combine(fb, cols, coeffs, ctx) -> dict:
    out: dict = {}
    for u, c in zip(cols, coeffs, strict=True):
        if c == 0:
            continue
        for k, f in fb[u].items():
            out[k] = out.get(k, ctx.from_dict({})) + c * f
    return {k: f for k, f in out.items() if f != 0}


def jacobi_equations(n: int, a, b, P0: dict, Ks: list[dict], seed: int, ctx, points: int | None = None):
    r"""The Jacobi condition of the module docstring at seeded rational points of $P$, for
    $P = P_0 + \sum_i t_i K_i$: polynomials in $t_i$ and $\sigma$ over $\mathbb{Q}$ (a basis of
    their span), and the generators $(t_1, \dots, t_r, \sigma)$. The arithmetic in $t, \sigma$ is
    FLINT's ``fmpq_mpoly`` (the values at a point are ``fmpq``); the basis is read back into SymPy."""
    ts = sp.symbols(f"t1:{len(Ks) + 1}")
    gens = (*ts, sigma)
    T = flint.fmpq_mpoly_ctx.get(tuple(str(g) for g in gens), "lex")
    tg = T.gens()
    zero = T.from_dict({})
    N = ctx.nvars()
    parts = [P0, *Ks]
    coef = [T.from_dict({(0,) * len(gens): 1}), *tg[:-1]]
    s = tg[-1]
    # each part's entries and their non-zero partial derivatives, once (they do not depend on the point)
    table = [(c, [((i, j), f, [(l, d) for l in range(N) if (d := f.derivative(l)) != 0])
                  for (i, j), f in part.items()]) for part, c in zip(parts, coef, strict=True)]
    count = points if points is not None else 3 + len(Ks) // 4
    eqs = []
    for M, g in _points(n, count, seed, "jacobi"):
        pt = [_fq(v) for v in list(vec(M)) + list(g)]
        fd = field_data(n, a, b, M, g)
        D, dD = _fq(fd["Delta"]), _fq(fd["dDelta"])
        V = [[zero] * N for _ in range(N)]
        dV = [[[zero] * N for _ in range(N)] for _ in range(N)]
        for c, entries in table:
            for (i, j), f, derivatives in entries:
                v = c * f(*pt)
                V[i][j] += v
                V[j][i] -= v
                for l, d in derivatives:
                    w = c * d(*pt)
                    dV[l][i][j] += w
                    dV[l][j][i] -= w
        eqs += [val for _, val in jacobi_values(V, dV, D, dD, s, zero)]
    R = sp.ring(gens, sp.QQ)[0]
    return _span_basis(eqs, R), gens


def _q(v: flint.fmpq):
    return sp.Rational(int(v.p), int(v.q))


def _qr(R, v: flint.fmpq):
    return R(R.domain.from_sympy(_q(v)))


def _span_basis(eqs: list, R) -> list[sp.Expr]:
    """A basis (over QQ) of the span of the sampled equations (``fmpq_mpoly`` in the generators
    of the SymPy ring ``R``, in its order), as SymPy expressions: the rows of the reduced echelon
    form of their coefficient matrix (monomials in increasing exponent order)."""
    if not eqs:
        return []
    terms = [{tuple(int(k) for k in mono): c for mono, c in e.to_dict().items()} for e in eqs]
    monos = sorted({mono for t in terms for mono in t})
    pos = {mono: i for i, mono in enumerate(monos)}
    A = flint.fmpq_mat(len(eqs), len(monos))
    for r, t in enumerate(terms):
        for mono, c in t.items():
            A[r, pos[mono]] = c
    Rr, rank = A.rref()
    out = []
    for i in range(rank):
        poly = R({monos[j]: R.domain.from_sympy(sp.Rational(int(Rr[i, j].p), int(Rr[i, j].q)))
                  for j in range(len(monos)) if Rr[i, j] != 0})
        out.append(poly.as_expr())
    return out
