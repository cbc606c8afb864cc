r"""A Jacobi exclusion of the Hamiltonisation search (symbolic/search/poisson.py) carried from one
rational $(a_0, b_0)$ to every $(a, b)$ off an explicit algebraic curve, by a certificate checked
exactly over $\mathbb{Q}(a, b)$.

**The sample points.** Every condition is sampled at $(M, \gamma) = (L_\gamma\Omega, \gamma)$ for
seeded rational $(\Omega, \gamma)$. There $dH = (\Omega, -\tfrac12\langle\Omega,
\partial_{\gamma_k}L_\gamma\Omega\rangle)$, $X$, $\Delta(\gamma_n)$ and every basis bivector of the
box with its first derivatives are *polynomials* in $(a, b)$ ($L_\gamma$ is affine in $(a, b)$), so
the sampled conditions live in $\mathbb{Q}[a, b]$ (symbolic/search/generic_extension.py, the same
points for the linear stage). Wherever $L_\gamma$ is invertible at the sample points these are
points of $P$ and a true Hamiltonisation satisfies every sampled condition.

**Step 1, the linear stage over $\mathbb{Q}(a, b)$.** $Ac = h$ with $A = A_0 + aA_1 + bA_2$ and
$h = \Delta^e X$ is solved by fraction-free Gauss–Jordan elimination over $\mathbb{Q}[a, b]$ on
$r$ rows and pivot columns whose $r \times r$ minor $\mu$ is nonzero at $(a_0, b_0)$ ($r$ the rank
there). The result, $\mu c = n_0 + \sum_f t_f\, n_f$ ($t_f$ the free columns), is *checked* on every
sampled row as a polynomial identity, so for every $(a, b)$ with $\mu(a, b) \ne 0$ the solutions
of the sampled linear stage are exactly $c = (n_0 + \sum_f t_f\, n_f)/\mu$ (the $n_f$ are independent,
the identity block, and the rank is $r$ there). Common factors are divided out: $n_0 = g\,n_0'$,
$n_f = g_f\,n_f'$, $g, g_f \mid \mu$.

**Step 2, the Jacobi stage.** With $P = s_0\,n_0' + \sum_f t_f\, n_f'$ the sampled Jacobi condition of
symbolic/search/poisson.py is a homogeneous quadratic in $(s_0, t)$, linear in $\sigma$; a solution
with $s_0 = \mu/g \ne 0$ rescales to $s_0 = 1$. So the equations $f_k(t, \sigma) \in
\mathbb{Q}[a, b][t, \sigma]$ are those of $P = n_0' + \sum_f t_f n_f'$.

**Step 3, the certificate.** At $(a_0, b_0)$, $1$ is in the $\mathbb{Q}$-span of the sampled
Jacobi equations (in every Jacobi box measured; otherwise no certificate, said so); $S$ is the
support of that combination within a basis of the equations there, and
$\sum_{k\in S}\lambda_k f_k = \nu$ is solved by fraction-free elimination over $\mathbb{Q}[a, b]$
($\lambda_k, \nu \in \mathbb{Q}[a, b]$, $\nu(a_0, b_0) \ne 0$) and *checked* as a polynomial
identity in $\mathbb{Q}[a, b, t, \sigma]$. Where $\mu\nu \ne 0$ no $(t, \sigma)$ solves the sampled
Jacobi equations: the box holds no Hamiltonisation for every $(a, b)$ off
$\{\mu\nu = 0\}$ and the $(a, b)$ where $L_\gamma$ is singular or $\Delta$ vanishes at a sample
point ($\mu\nu \ne 0$ at $(a_0, b_0)$, checked).

**Step 4, two certificates** (:func:`generic_exclusion`) from independent sample points: the box
is empty off the common factors $g$ of the two curves $\mu\nu\prod(\det L_\gamma\,\Delta) = 0$
and the finitely many points where their coprime rests meet; a factor of $g$ with coefficients of
one sign and a nonzero constant in $(a + 1, b)$ has no zero on the domain $a \ge -1$, $b \ge 0$.

A box that has solutions at $(a_0, b_0)$ (the controls: Borisov–Mamaev at $n = 3$, the homogeneous
ball $a = 0$ at $n = 4$) gets no certificate: Step 3 finds no combination, or Step 1's check
fails (a special point), and :func:`jacobi_certificate` says so.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import flint
import sympy as sp
from chaplygin_nd.symbolic.search.box_columns import jacobi_values
from chaplygin_nd.symbolic.search.polys_ab import (
    AB,
    ab_ctx,
    det_L,
    factor_set,
    factored,
    ff_gauss_jordan,
    no_zero_in_domain,
    point_rank_profile,
    poly_text,
    primitive,
)

__all__ = ["JacobiCertificate", "generic_kernel", "jacobi_polys", "jacobi_certificate",
           "generic_exclusion", "AB", "ff_gauss_jordan", "no_zero_in_domain", "poly_text"]

#: where the certificate is computed (the ledger rows compute it under make verify-deep)
WHERE = "symbolic/search/jacobi_generic.py, make verify-deep"
#: per n, the largest number of unknowns t after the linear stage for which the certificate is
#: attempted by the rows (measured at n = 4: 8 and 12 unknowns, 27 and 89 CPU s for both
#: certificates; n = 5 with 9 unknowns had not finished one after ~240 CPU s: not attempted)
MAX_FREE = {3: 12, 4: 12}


@dataclass
class JacobiCertificate:
    """One Jacobi box carried to generic (a, b), or why not: sizes, the exceptional polynomials
    and the certificate as text (module docstring)."""

    n: int
    degree: int
    e: int
    a0: object
    b0: object
    proved: bool = False
    reason: str = ""
    free: int = -1              # unknowns t after the linear stage over Q(a, b)
    rank: int = 0
    equations: int = 0          # sampled Jacobi equations (nonzero)
    support: int = 0            # equations used by the certificate
    mu: str = ""                # the pivot minor (factored)
    nu: str = ""                # the certificate's denominator (factored)
    short: tuple = ("", "")     # mu and nu with long factors named by their degrees
    factors: list = field(default_factory=list)  # of mu, nu and det L_gamma at the points
    stages: dict = field(default_factory=dict)
    seconds: float = 0.0
    text: dict = field(default_factory=dict)

    def as_dict(self) -> dict:
        return {"n": self.n, "degree": self.degree, "e": self.e, "a0": str(self.a0), "b0": str(self.b0),
                "proved": self.proved, "reason": self.reason, "free": self.free, "rank": self.rank,
                "equations": self.equations, "support": self.support, "mu": self.mu, "nu": self.nu,
                "seconds": round(self.seconds, 2), "text": self.text}

    def statement(self) -> str:
        if not self.proved:
            return f"only at (a, b) = ({self.a0}, {self.b0}) ({self.reason})"
        return (f"generic (a, b): no solution off mu * nu = 0 and the (a, b) where L_gamma is singular "
                f"at a sample point, with mu = {self.short[0]} (the linear stage's pivot minor) and "
                f"nu = {self.short[1]} (c a rational constant; every factor in full in the "
                f"certificate): 1 = sum of {self.support} of the {self.equations} sampled Jacobi "
                f"equations times polynomials over nu, checked over Q[a, b, t, sigma] in FLINT and SymPy "
                f"({self.free} unknowns t and sigma)")


def _linear_system(n: int, e: int, fb: list, cols: list, points: list):
    """A (rows of fmpq_mpoly in a, b) and h = Delta^e X of the linear stage at the points
    (L_gamma Omega, gamma): generic_extension.omega_rows at three (a, b), affinity checked at a
    fourth."""
    from chaplygin_nd.symbolic.search import generic_extension as ge

    ctx = ab_ctx()
    a, b = ctx.gens()
    (A0, X0), (A1, X1), (A2, X2), (A3, X3) = (ge.omega_rows(n, x, y, 0, fb, cols, points)
                                              for x, y in ((0, 0), (1, 0), (0, 1), (2, 3)))
    A = [[u + (v - u) * a + (w - u) * b for u, v, w in zip(r0, r1, r2, strict=True)]
         for r0, r1, r2 in zip(A0, A1, A2, strict=True)]
    X = [u + (v - u) * a + (w - u) * b for u, v, w in zip(X0, X1, X2, strict=True)]
    if any(p(2, 3) != q for r, s in zip(A, A3, strict=True) for p, q in zip(r, s, strict=True)) \
            or any(p(2, 3) != q for p, q in zip(X, X3, strict=True)):
        raise ArithmeticError("the sampled linear conditions are not affine in (a, b)")
    per = len(A) // len(points)
    h = []
    for i, x in enumerate(X):
        g = points[i // per][1]
        xn = flint.fmpq(int(sp.Rational(g[n - 1]).p), int(sp.Rational(g[n - 1]).q))
        D = 4 + 2 * a + 2 * b + a * b * (1 - xn**2)
        h.append(x * D**e if e >= 0 else None)
    if any(v is None for v in h):
        raise ValueError("e < 0: the right-hand side is not polynomial (not needed by any Jacobi box)")
    return A, h


def generic_kernel(A: list, h: list, at: tuple):
    r"""Step 1 of the module docstring: (mu, n0, [n_f], free columns), with $\mu c = n_0 +
    \sum_f t_f n_f$ checked on every row of $Ac = h$; otherwise a string saying why not ($Ac = h$
    inconsistent at ``at``, or the point is special: the check fails)."""
    aug = [r + [v] for r, v in zip(A, h, strict=True)]
    C, R = point_rank_profile(A, at)
    Caug, _ = point_rank_profile(aug, at)
    if len(A[0]) in Caug:
        return "the linear stage is inconsistent at the point: not a Jacobi box"
    k = len(A[0])
    E, solved, mu = ff_gauss_jordan([aug[i] for i in R], C)
    free = [j for j in range(k) if j not in set(C)]
    zero = mu - mu
    n0 = [zero] * k
    for i, c in enumerate(solved):
        n0[c] = E[i][k]
    kern = []
    for f in free:
        v = [zero] * k
        v[f] = mu
        for i, c in enumerate(solved):
            v[c] = -E[i][f]
        kern.append(v)
    for row, hv in zip(A, h, strict=True):   # the check that makes the parametrisation exact
        if sum((x * y for x, y in zip(row, n0, strict=True)), zero) != mu * hv or \
                any(sum((x * y for x, y in zip(row, v, strict=True)), zero) != 0 for v in kern):
            return ("the solution over Q(a, b) from the point's pivots fails a sampled row: the point "
                    "is special (a rank there is below its generic value)")
    return mu, n0, kern, free


def jacobi_polys(n: int, fb: list, cols: list, P0: list, Ks: list, points: list):
    r"""Step 2: the sampled Jacobi condition of symbolic/search/poisson.py,
    $\Delta[P,P]_{ijk} + \sigma\sum_{\mathrm{cyc}}P_{jk}(P\,d\Delta)_i$, for
    $P = \sum_u (P_0 + \sum_f t_f K_f)_u B_u$ at the points $(L_\gamma\Omega, \gamma)$: a list of
    (label, fmpq_mpoly in $a, b, t_1.., \sigma$), and the context."""
    from chaplygin_nd.symbolic.algebra import vec
    from chaplygin_nd.symbolic.mass_operator import L_entries

    names = AB + tuple(f"t{i + 1}" for i in range(len(Ks))) + ("sigma",)
    ctx = flint.fmpq_mpoly_ctx.get(names, "lex")
    gens = ctx.gens()
    a, b, ts, s = gens[0], gens[1], gens[2:-1], gens[-1]
    m = n * (n - 1) // 2
    N = m + n

    def lift(p):   # a polynomial in (a, b) into the full ring
        return p.compose(a, b, ctx=ctx)

    coef = [lift(c) + sum((t * lift(K[u]) for t, K in zip(ts, Ks, strict=True)), ctx.from_dict({}))
            for u, c in enumerate(P0)]
    zero, one = ctx.from_dict({}), ctx.from_dict({(0,) * len(names): 1})
    out = []
    for pi, (Om, g) in enumerate(points):
        w = [one * flint.fmpq(int(sp.Rational(v).p), int(sp.Rational(v).q)) for v in vec(Om)]
        gq = [one * flint.fmpq(int(sp.Rational(v).p), int(sp.Rational(v).q)) for v in g]
        L = L_entries(gq, [one] * (n - 1) + [one + a], b, zero, one)
        Mv = [sum((L[r][c] * w[c] for c in range(m)), zero) for r in range(m)]
        pt = Mv + gq
        x = gq[n - 1]
        D = 4 + 2 * a + 2 * b + a * b * (1 - x * x)
        dD = -2 * a * b * x
        V = [[zero] * N for _ in range(N)]
        dV = [[[zero] * N for _ in range(N)] for _ in range(N)]
        for u, cu in zip(cols, coef, strict=True):
            if cu.is_zero():
                continue
            for (i, j), f in fb[u].items():
                val = cu * f.compose(*pt, ctx=ctx)
                V[i][j] += val
                V[j][i] -= val
                for l in range(N):
                    df = f.derivative(l)
                    if not df.is_zero():
                        dv = cu * df.compose(*pt, ctx=ctx)
                        dV[l][i][j] += dv
                        dV[l][j][i] -= dv
        out += [((pi, *ijk), val) for ijk, val in jacobi_values(V, dV, D, dD, s, zero)]
    return out, ctx


def _coefficients(eqs: list, nab: int = 2) -> tuple[list, list]:
    """The sampled equations as rows of coefficients (fmpq_mpoly in a, b) over the monomials in
    (t, sigma), the constant monomial first."""
    actx = ab_ctx()
    rows: list = []
    monos: dict = {}
    for _, f in eqs:
        row: dict = {}
        for exps, c in zip(f.monoms(), f.coeffs(), strict=True):
            key = tuple(exps[nab:])
            row.setdefault(key, {})[tuple(exps[:nab])] = c
            monos.setdefault(key, None)
        rows.append({k: actx.from_dict(v) for k, v in row.items()})
    order = sorted(monos, key=lambda k: (sum(k), k))
    return rows, order


def _fmpq(v) -> flint.fmpq:
    v = sp.Rational(v)
    return flint.fmpq(int(v.p), int(v.q))


def small_points(n: int, count: int, seed: int, label: str, den: int) -> list:
    """Seeded (Omega, gamma) with small heights (denominators <= ``den``; gamma by inverse
    stereographic projection, symbolic/exact/points.py): the certificate's size grows with them."""
    from chaplygin_nd.symbolic.exact.points import generator, skew_matrix, sphere_point

    rng = generator(seed, "jacobi-generic", label, n, den)
    return [(skew_matrix(rng, n, -3, 3, den), sphere_point(rng, n, den)) for _ in range(count)]


def jacobi_certificate(n: int, degree: int, e: int, a0, b0, *, seed: int, den: int = 1,
                       label: str = "") -> JacobiCertificate:
    """Steps 1-3 of the module docstring for the box (n, degree, e) from the point (a0, b0)."""
    from chaplygin_nd.symbolic.search import bivector_ansatz as ba
    from chaplygin_nd.symbolic.search import box_columns as bc
    from chaplygin_nd.symbolic.search.cost import StageClock

    t0 = time.perf_counter()
    a0, b0 = sp.Rational(a0), sp.Rational(b0)
    out = JacobiCertificate(n, degree, e, a0, b0)
    clock = StageClock(out.stages)
    at = (flint.fmpq(int(a0.p), int(a0.q)), flint.fmpq(int(b0.p), int(b0.q)))
    ans = ba.ansatz(n, degree)
    fb = bc.flint_bivectors(ans)
    cols, _ = bc.independent_columns(ans, fb, seed)
    N = len(ans.coords)
    lin_pts = small_points(n, 2 * (len(cols) // N) + 6, seed, "omega-linear" + label, den)
    A, h = _linear_system(n, e, fb, cols, lin_pts)
    clock("linear conditions")
    gk = generic_kernel(A, h, at)
    clock("kernel over Q(a, b)")
    if isinstance(gk, str):
        out.reason = gk
        out.seconds = time.perf_counter() - t0
        return out
    mu, n0, kern, free = gk
    out.free, out.rank = len(kern), len(cols) - len(kern)
    P0, Ks = primitive(n0), [primitive(v) for v in kern]
    jac_pts = small_points(n, 3 + len(Ks) // 4, seed, "omega-jacobi" + label, den)
    eqs, ctx = jacobi_polys(n, fb, cols, P0, Ks, jac_pts)
    out.equations = len(eqs)
    clock("jacobi equations over Q[a, b]")
    rows, monos = _coefficients(eqs)
    const = tuple([0] * (len(Ks) + 1))
    if not rows or monos[0] != const:
        out.reason = "no sampled Jacobi equation has a constant term"
        out.seconds = time.perf_counter() - t0
        return out
    actx = ab_ctx()
    zero = actx.from_dict({})
    vals = flint.fmpq_mat(len(rows), len(monos),
                          [r.get(k, zero)(*at) for r in rows for k in monos])
    _, rk = vals.rref()
    sub = flint.fmpq_mat(len(rows), len(monos) - 1,
                         [vals[i, j] for i in range(len(rows)) for j in range(1, len(monos))])
    if sub.rref()[1] == rk:
        out.reason = ("1 is not in the span of the sampled Jacobi equations at the point (the box has "
                      "solutions there, or needs a Groebner basis beyond a linear step)")
        out.seconds = time.perf_counter() - t0
        return out
    # a basis of the rows at the point, then the unique combination giving the constant 1
    from chaplygin_nd.symbolic.search.generic_extension import _pivots

    Rt, r = vals.transpose().rref()
    basis = _pivots(Rt, r, len(rows))
    Bm = flint.fmpq_mat(len(monos), len(basis) + 1,
                        [x for j in range(len(monos))
                         for x in [vals[i, j] for i in basis] + [flint.fmpq(int(j == 0))]])
    Rb, _ = Bm.rref()
    lam = [Rb[i, len(basis)] for i in range(len(basis))]
    S = [basis[i] for i, v in enumerate(lam) if v != 0]
    out.support = len(S)
    clock("support at the point")
    sv = flint.fmpq_mat(len(S), len(monos), [vals[i, j] for i in S for j in range(len(monos))])
    Rs, rs = sv.rref()
    Q = _pivots(Rs, rs, len(monos))
    if Q[0] != 0 or rs != len(S):
        raise ArithmeticError("the certificate's support is not independent at the point")
    one = actx.from_dict({(0, 0): 1})
    system = [[rows[S[i]].get(monos[q], zero) for i in range(len(S))] + [one if q == 0 else zero]
              for q in Q]
    E, solved, nu = ff_gauss_jordan(system, list(range(len(S))))
    lam_num: list = [None] * len(S)
    for i, c in enumerate(solved):
        lam_num[c] = E[i][len(S)]
    g = nu
    for lv in lam_num:   # the common factor of the certificate
        g = g.gcd(lv)
    nu = nu / g
    lam_num = [lv / g for lv in lam_num]
    clock("certificate over Q(a, b)")

    def lift(p):
        g = ctx.gens()
        return p.compose(g[0], g[1], ctx=ctx)

    total = sum((lift(lv) * eqs[k][1] for lv, k in zip(lam_num, S, strict=True)), ctx.from_dict({}))
    if total != lift(nu):
        raise ArithmeticError("the certificate sum lambda_k f_k = nu fails over Q[a, b, t, sigma]")
    if not _sympy_agrees([lift(lv) for lv in lam_num], [eqs[k][1] for k in S], lift(nu), ctx):
        raise ArithmeticError("SymPy's ring disagrees: sum lambda_k f_k != nu over Q[a, b, t, sigma]")
    clock("certificate check (FLINT and SymPy)")
    out.proved = True
    if mu(*at) == 0 or nu(*at) == 0:
        raise ArithmeticError("the certificate's curve passes through its own point")
    (out.mu, smu), (out.nu, snu) = factored(mu), factored(nu)
    out.short = (smu, snu)
    actx_a, actx_b = actx.gens()
    deltas = [4 + 2 * actx_a + 2 * actx_b + actx_a * actx_b * (1 - _fmpq(g[n - 1]) ** 2)
              for _, g in lin_pts + jac_pts]
    out.factors = factor_set([mu, nu] + [det_L(n, g) for _, g in lin_pts + jac_pts] + deltas)
    clock("factors")
    out.text = {"points": "(M, gamma) = (L_gamma Omega, gamma) at these (Omega, gamma): linear stage "
                          + str([[str(list(O)), str(list(g))] for O, g in lin_pts]) + "; Jacobi "
                          + str([[str(list(O)), str(list(g))] for O, g in jac_pts]),
                "columns": [int(u) for u in cols],
                "P0": [poly_text(p) for p in P0], "K": [[poly_text(p) for p in v] for v in Ks],
                "mu": out.mu, "nu": out.nu,
                "lambda": {str(eqs[k][0]): poly_text(lv) for lv, k in zip(lam_num, S, strict=True)}}
    out.seconds = time.perf_counter() - t0
    return out


def _sympy_agrees(lams: list, fs: list, nu, ctx) -> bool:
    r"""The certificate identity $\sum_k \lambda_k f_k = \nu$ recomputed in SymPy's sparse ring over
    $\mathbb{Q}$ from the FLINT polynomials' terms (the second engine on what a row claims)."""
    R = sp.ring([str(v) for v in ctx.names()], sp.QQ)[0]

    def conv(p):
        return R.from_dict({m: sp.QQ(int(c.p), int(c.q)) for m, c in p.to_dict().items()})

    return sum((conv(lv) * conv(f) for lv, f in zip(lams, fs, strict=True)), R.zero) == conv(nu)


def generic_exclusion(n: int, degree: int, e: int, a0, b0, *, seed: int) -> tuple[bool, str, dict]:
    r"""Two certificates (:func:`jacobi_certificate`) from independent sample points: the box is
    empty off the zero set of each one's $\mu\nu\prod\det L_\gamma$, hence off their common
    factors $g$ and the finitely many points where the two coprime remainders meet. Returns
    (proved, statement, both certificates and $g$ as text)."""
    certs = [jacobi_certificate(n, degree, e, a0, b0, seed=seed, label=lab) for lab in ("", "-2")]
    data: dict = {"certificates": [c.as_dict() for c in certs]}
    if not all(c.proved for c in certs):
        return False, certs[0].statement() if not certs[0].proved else certs[1].statement(), data
    common = [f for f in certs[0].factors if any(f == g or f == -g for g in certs[1].factors)]
    g = " * ".join(f"({poly_text(f)})" for f in common) or "1"
    inside = [f for f in common if not no_zero_in_domain(f)]
    dom = " * ".join(f"({poly_text(f)})" for f in inside) or "1"
    data["common_factors"], data["in_domain"] = g, dom
    cpu = sum(sum(c.stages.values()) for c in certs)
    return True, (f"generic (a, b): off the curve {g} = 0 and finitely many points; in the domain "
                  f"a >= -1, b >= 0 off {dom} = 0 and finitely many points (the other factors have "
                  f"coefficients of one sign and a nonzero constant in (a + 1, b)). Two certificates "
                  f"over Q(a, b) from independent sample points, each excluding the box off its curve "
                  f"mu * nu * prod (det L_gamma * Delta) = 0; g = their common factors; {cpu:.0f} s CPU. "
                  f"First: {certs[0].statement()[len('generic (a, b): '):]}"), data

