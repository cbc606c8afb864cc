r"""Exact search for commuting symmetry fields of eq:motion-general (row S7:symmetry-fields):
$O(n-1)$-equivariant vector fields $Y = \Delta^s Q$ on $P$ with

.. math::
    [\Delta^\tau X, \Delta^s Q] \equiv 0 \ \text{modulo the } \mathfrak{so}(n-1)\text{ directions},
    \qquad Q(F_j) = 0, \qquad \langle Q^\gamma, \gamma\rangle = 0,

$F_j$ the coefficients of $p(\lambda, \sigma)$ and $H$ (eq:pol-first-integrals, S2.2:energy).
Divided by $\Delta^{\tau + s}$ the first condition is linear in $Q$ for fixed $(s, \tau)$:
$C(Q) = [X, Q] + s\,\tfrac{X(\Delta)}{\Delta} Q - \tau\,\tfrac{Q(\Delta)}{\Delta} X \in
T_p(SO(n-1)\cdot p)$ at every point. Bogoyavlenskij's theorem on $P/SO(n-1)$ needs
$\lfloor n/2\rfloor - 1$ such fields independent of $X$ modulo the orbits.

**The box** (weight 1: $Q^M$ quadratic in $M$, $Q^\gamma$ linear — the weight of $X$ and of the
Hamiltonian fields of quadratic integrals), coefficients polynomials of degree $\le d$ in
$x = \gamma_n$, spanned by: the orbit fields $\zeta_A = ([A, M], A\gamma)$ with $A = \pi T_j(M)$
($\pi$ the projection to $\mathfrak{so}(n-1)$, $T_j$ of symbolic/axisym_inverse.py); the field
$DX$ ($D = 2(2+a+b)\Delta$, polynomial); and the blocks of :func:`field_blocks`. The orbit fields
solve the conditions exactly (equivariance of $X$, invariance of the $F_j$ and of $\Delta$), and
$DX$ does when $s = \tau - 1$ (it is then $\Delta^\tau X$ up to a constant). These are the
*trivial* solutions.

**Exactness.** The conditions are evaluated at seeded rational points (exact $DX$ at a point:
$\partial\Omega = L_\gamma^{-1}(\partial M - \partial L_\gamma\,\Omega)$). The sampled solution space
contains the true one; trivial solutions lie in the true one. When the two dimensions agree, the
box holds exactly no field beyond the trivial ones; otherwise the seeded points are extended
(doubled, up to :data:`_MAX_DOUBLINGS` times) and the count redone, and what excess remains is an
upper bound, reported as candidates (a candidate still needs an exact proof before it is claimed).
Column syzygies suggested by the points are each proved (vanishing modulo the sphere,
symbolic/search/orbit_fields.py) before a column is dropped; the column sample is extended the
same way when one is not an identity.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import flint
import sympy as sp
from chaplygin_nd.symbolic.algebra import so_basis, vec, wedge
from chaplygin_nd.symbolic.axisym_inverse import ansatz_terms, inverse_numerator
from chaplygin_nd.symbolic.axisymmetric import Delta
from chaplygin_nd.symbolic.search import bivector_ansatz as ba
from chaplygin_nd.symbolic.search.box_columns import mpoly_context as _ctx
from chaplygin_nd.symbolic.search.box_columns import rref_solve as _rref_solve
from chaplygin_nd.symbolic.search.box_columns import sample_points as _points
from chaplygin_nd.symbolic.search.cost import StageClock
from chaplygin_nd.symbolic.search.field_point import field_and_jacobian
from chaplygin_nd.symbolic.search.orbit_fields import (
    invariants,
    orbit_fields,
    rho_x_combination,
    vanishes_on_sphere,
)
from chaplygin_nd.symbolic.search.point_values import fq as _fq

__all__ = ["field_blocks", "FieldBox", "search_fields", "estimate", "invariants"]


#: how often the column sample is doubled before a syzygy that is not an identity is an error
_MAX_DOUBLINGS = 2


def _E(n):
    e = sp.zeros(n, 1)
    e[n - 1] = 1
    return e


def _pi(A: sp.Matrix) -> sp.Matrix:
    B = A.copy()
    n = A.rows
    for i in range(n):
        B[n - 1, i] = B[i, n - 1] = 0
    return B


def field_blocks(n: int, M, gamma, a, b) -> tuple[list, list[str], int]:
    r"""The fields of the box at $(M, \gamma)$ as $(Q^M, Q^\gamma)$: first the six orbit fields
    $\zeta_{\pi T_j(M)}$, then $DX$, then the equivariant blocks (module docstring). Returns the
    list, their names and the number of trivial columns (orbit fields and $DX$)."""
    E = _E(n)
    T = ansatz_terms(M, gamma)
    zero_m, zero_v = sp.zeros(n, n), sp.zeros(n, 1)
    out, names = [], []
    for j, t in enumerate(T):
        A = _pi(t)
        out.append((A * M - M * A, A * gamma))
        names.append(f"orbit(pi T{j})")
    DO = inverse_numerator(M, gamma, a, b)
    out.append((M * DO - DO * M, -DO * gamma))
    names.append("D X")
    trivial = len(out)
    s = (M * gamma).T * E
    s = s[0, 0]
    Mg, ME = M * gamma, M * E
    for j in range(1, 6):
        out.append((M * T[j] - T[j] * M, zero_v))
        names.append(f"[M, T{j}]")
    for j in range(6):
        out.append((s * T[j], zero_v))
        names.append(f"<Mg,E> T{j}")
    for u, v, nm in ((Mg, ME, "Mg^ME"), (M * Mg, gamma, "MMg^g"), (M * Mg, E, "MMg^E"),
                     (M * ME, gamma, "MME^g"), (M * ME, E, "MME^E")):
        out.append((wedge(u, v), zero_v))
        names.append(nm)
    gE = wedge(gamma, E)
    kil = lambda A, B: sum(A[i, j] * B[i, j] for i in range(n) for j in range(i + 1, n))  # noqa: E731
    for sc, nm in ((kil(M, M), "|M|^2"), ((Mg.T * Mg)[0, 0], "|Mg|^2"), ((ME.T * ME)[0, 0], "|ME|^2"),
                   ((Mg.T * ME)[0, 0], "<Mg,ME>"), (s * s, "<Mg,E>^2")):
        out.append((sc * gE, zero_v))
        names.append(f"{nm} g^E")
    out.append((M * gE * M, zero_v))
    names.append("M (g^E) M")
    out.append((M * M * gE + gE * M * M, zero_v))
    names.append("{M^2, g^E}")
    for v, nm in ((Mg, "Mg"), (ME, "ME"), (s * gamma, "<Mg,E> g"), (s * E, "<Mg,E> E")):
        out.append((zero_m, v))
        names.append(nm)
    return out, names, trivial


def estimate(n: int, degree: int) -> str:
    """A one-line size and CPU-time estimate of a box, stage by stage (symbolic/search/fields_cost.py)."""
    from chaplygin_nd.symbolic.search.fields_cost import field_cost

    return field_cost(n, degree).line()


@dataclass
class FieldBox:
    """One box (n, d, s, tau) at (a, b): sizes and the outcome."""

    n: int
    degree: int
    s: object
    tau: object
    independent: int = 0
    trivial: int = 0
    solutions: int = 0
    excess: int = 0
    orbit_proved: int = 0
    points: int = 0             # sample points of the conditions (extended while candidates remain)
    column_points: int = 0      # sample points of the column rank (extended while a syzygy fails)
    rho_x: bool = False         # Delta^tau X written in the box (s = tau - 1 - k, k >= 1) and counted
    outcome: str = ""
    generic: str = ""           # over which (a, b) the count holds (generic_extension.py)
    kernel: list | None = None
    columns: list | None = None
    seconds: float = 0.0
    stages: dict = field(default_factory=dict)  # CPU seconds per stage (fields_cost.STAGES)

    def as_dict(self) -> dict:
        return {"n": self.n, "degree": self.degree, "s": str(self.s), "tau": str(self.tau),
                "independent": self.independent, "trivial": self.trivial,
                "solutions": self.solutions, "orbit_proved": self.orbit_proved, "points": self.points,
                "column_points": self.column_points, "rho_x": self.rho_x,
                "excess": self.excess, "outcome": self.outcome, "generic": self.generic,
                "seconds": round(self.seconds, 2)}


def _columns(n: int, degree: int, a, b):
    M, gamma, z = ba.coordinates(n)
    fields, names, trivial = field_blocks(n, M, gamma, a, b)
    ctx = _ctx(z)
    xf = ctx.gens()[len(z) - 1]
    cols, labels, triv = [], [], []
    for f_i, (YM, Yg) in enumerate(fields):
        base = []   # the field's components in FLINT, expanded once; x^k times them below
        for c in list(vec(YM)) + list(Yg):
            e = sp.expand(c)
            base.append(ctx.from_dict({m: _fq(v) for m, v in sp.Poly(e, *z).as_dict().items()})
                        if e != 0 else None)
        for k in range(degree + 1):
            if f_i == trivial - 1 and k > 0:
                continue  # D X itself only
            cols.append([p * xf**k if p is not None else None for p in base])
            labels.append((names[f_i], k))
            triv.append(f_i < trivial)
    return z, cols, labels, triv


def search_fields(n: int, degree: int, s, tau, a, b, *, seed: int) -> FieldBox:
    """Decide one box exactly (module docstring)."""
    from chaplygin_nd.symbolic.search import sampled_field

    t0 = time.perf_counter()
    a, b, s, tau = sp.Rational(a), sp.Rational(b), sp.Rational(s), sp.Rational(tau)
    res = FieldBox(n, degree, s, tau)
    clock = StageClock(res.stages)
    z, cols, labels, triv = _columns(n, degree, a, b)
    N = len(z)
    model = sampled_field.axisymmetric(n, a, b)
    clock("columns")
    # independent columns (syzygies proved exactly, trivial columns kept first as pivots)
    keep, dx_syzygy, res.column_points = _independent(z, cols, seed, n, labels, clock)
    cols = [cols[u] for u in keep]
    triv = [triv[u] for u in keep]
    res.independent = len(cols)
    rho = None  # Delta^tau X written in the box, when s = tau - 1 - k for an integer k >= 1
    k = tau - 1 - s
    if k.is_integer and k >= 1:
        dx = next(u for u in range(len(cols)) if labels[keep[u]][0] == "D X")
        rho = rho_x_combination(n, z, cols, dx, int(k), a, b, seed)
    res.rho_x = rho is not None
    count, done, rows = 2 * len(cols) // (N - 1) + 4, 0, []
    for attempt in range(_MAX_DOUBLINGS + 1):
        # the sampled conditions: the same seeded points, extended while candidates remain
        for M, g in _points(n, count, seed, "fields")[done:]:
            rows += _condition_rows(n, a, b, s, tau, cols, model, M, g)
        done = count
        clock("conditions")
        _, kernel = _rref_solve(rows, [flint.fmpq(0)] * len(rows))
        clock("kernel")
        counted = [u for u, t in enumerate(triv) if t and (labels[keep[u]][0] != "D X" or s == tau - 1)]
        if any(row[u] != 0 for row in rows for u in counted):
            raise ArithmeticError("a trivial field fails a sampled condition: the conditions are wrong")
        others = [v for v in kernel if not _is_trivial_unit(v, triv)]
        proved = orbit_fields(n, z, cols, others, seed) if others else []
        clock("orbit proofs")
        exact = _rank_of_trivial(len(cols), counted, [coef for _, coef in proved], rho, rows)
        if len(kernel) == exact or attempt == _MAX_DOUBLINGS:
            break
        count *= 2
    res.points = done
    res.solutions = len(kernel)
    res.kernel, res.columns = kernel, [(labels[u], cols[i]) for i, u in enumerate(keep)]
    res.orbit_proved = len(proved)
    res.trivial = exact
    res.excess = res.solutions - res.trivial
    res.outcome = ("no field beyond the trivial ones" if res.excess == 0
                   else f"{res.excess} candidate(s) beyond the trivial ones (upper bound)")
    if res.excess < 0:
        raise ArithmeticError("fewer sampled solutions than exact ones: a bug")
    if res.excess == 0 and res.rho_x:
        res.generic = (f"only at (a, b) = ({a}, {b}) (Delta^tau X is written in the box there with "
                       "coefficients that depend on a, b)")
    elif res.excess == 0:
        from chaplygin_nd.symbolic.search.generic_extension import fields_generic

        res.generic = fields_generic(rows, res.solutions, res.trivial, f"(a, b) = ({a}, {b})", dx_syzygy,
                                     [labels[keep[u]][0] == "D X" for u in range(len(cols))],
                                     [coef for _, coef in proved])
    clock("generic")
    res.seconds = time.perf_counter() - t0
    return res


def _condition_rows(n, a, b, s, tau, cols, model, M, g) -> list[list]:
    r"""The sampled conditions of the module docstring at the rational point $(M, \gamma)$, one row
    per condition, one entry per column: $C(Q)$ paired with a basis of the annihilator of the
    orbit directions, $\langle Q^\gamma, \gamma\rangle$, and $Q(F_j)$, $Q(H)$."""
    from chaplygin_nd.symbolic.search.known_integrals import gradients_at

    N = n * (n - 1) // 2 + n
    m = N - n
    xs = sp.Symbol("x")
    Dx = Delta(xs, a, b)
    basis = [A for A in so_basis(n) if all(A[i, n - 1] == 0 for i in range(n))]
    pt = [_fq(v) for v in list(vec(M)) + list(g)]
    X, dX = field_and_jacobian(n, a, b, M, g)
    D, dD = _fq(Dx.subs(xs, g[n - 1])), _fq(sp.diff(Dx, xs).subs(xs, g[n - 1]))
    XD = dD * X[N - 1] / D
    grads = gradients_at(model, M, g)
    zetas = [list(vec(A * M - M * A)) + list(A * g) for A in basis]
    _, ann = _rref_solve([[_fq(v) for v in zt] for zt in zetas], [flint.fmpq(0)] * len(zetas))
    vals, ders = [], []
    for polys in cols:
        vals.append([p(*pt) if p is not None else flint.fmpq(0) for p in polys])
        ders.append([[p.derivative(l)(*pt) if p is not None else flint.fmpq(0) for l in range(N)]
                     for p in polys])
    Cs = []
    for Q, DQ in zip(vals, ders, strict=True):
        QD = dD * Q[N - 1] / D
        C = []
        for i in range(N):
            v = sum((DQ[i][l] * X[l] for l in range(N)), flint.fmpq(0))
            v -= sum((dX[l][i] * Q[l] for l in range(N)), flint.fmpq(0))
            C.append(v + _fq(s) * XD * Q[i] - _fq(tau) * QD * X[i])
        Cs.append(C)
    rows = [[sum((w[i] * C[i] for i in range(N)), flint.fmpq(0)) for C in Cs] for w in ann]
    rows.append([sum((Q[m + k] * _fq(g[k]) for k in range(n)), flint.fmpq(0)) for Q in vals])
    for r in range(grads.rows):
        gr = [_fq(v) for v in grads.row(r)]
        rows.append([sum((gr[i] * Q[i] for i in range(N)), flint.fmpq(0)) for Q in vals])
    return rows


def _independent(z, cols, seed, n, labels=None, clock=None) -> tuple[list[int], bool, int]:
    """Indices of columns independent as functions on P (syzygies proved modulo the sphere),
    whether a proved syzygy involves the column D X (which depends on a, b), and the points used. The sampled syzygies
    contain the true ones; when one of them is not an identity the sample was too small, and the
    same seeded points are extended (doubled) until every sampled syzygy is proved."""
    N = len(z)
    count = 2 * (len(cols) // N) + 6
    zero = _ctx(z).from_dict({})
    for _ in range(_MAX_DOUBLINGS + 1):
        rows = []
        for M, g in _points(n, count, seed, "field-columns"):
            pt = [_fq(v) for v in list(vec(M)) + list(g)]
            vals = [[p(*pt) if p is not None else flint.fmpq(0) for p in polys] for polys in cols]
            for i in range(N):
                rows.append([v[i] for v in vals])
        _, kernel = _rref_solve(rows, [flint.fmpq(0)] * len(rows))
        if clock:
            clock("column rank")
        proved = all(vanishes_on_sphere(sum((c * cols[u][i] for u, c in enumerate(v)
                                             if c != 0 and cols[u][i] is not None), zero), n)
                     for v in kernel for i in range(N))
        if clock:
            clock("syzygy proofs")
        if proved:
            break
        count *= 2
    else:
        raise ArithmeticError(f"a sampled syzygy of the field box is not an identity at {count // 2} points")
    dropped = {max(u for u, c in enumerate(v) if c != 0) for v in kernel}
    dx = bool(labels) and any(c != 0 and labels[u][0] == "D X" for v in kernel for u, c in enumerate(v))
    return [u for u in range(len(cols)) if u not in dropped], dx, count


def _rank_of_trivial(C: int, counted: list, proved: list, rho, rows) -> int:
    """How many independent exact solutions are known: the counted trivial columns, the proved
    orbit-direction fields and Delta^tau X written in the box (each checked against the sampled
    conditions, which every true solution satisfies)."""
    vecs = [[flint.fmpq(1) if w == u else flint.fmpq(0) for w in range(C)] for u in counted] + list(proved)
    if rho is not None:
        if any(sum((r[u] * rho[u] for u in range(C)), flint.fmpq(0)) != 0 for r in rows):
            raise ArithmeticError("Delta^tau X fails a sampled condition: the conditions are wrong")
        vecs.append(rho)
    if not vecs:
        return 0
    return flint.fmpq_mat(len(vecs), C, [v for row in vecs for v in row]).rref()[1]


def _is_trivial_unit(v, triv) -> bool:
    nz = [u for u, c in enumerate(v) if c != 0]
    return len(nz) == 1 and triv[nz[0]]
