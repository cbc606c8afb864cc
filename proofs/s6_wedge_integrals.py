r"""Beyond the paper: a family of first integrals for every $n$, and the count of the tori (row S6:wedge-integrals).

**Claim.** For the axisymmetric sphere with $B = aE_nE_n^T + b\gamma\gamma^T$ (so $L_\gamma = 2 + D_B$ on
$\Lambda^2 = \mathfrak{so}(n)$) and $D_B$ the derivation extension of $B$ to $\Lambda^{2k}$,

.. math::
    H_k = \langle M^{\wedge k}, (2 + D_B)^{-1} M^{\wedge k}\rangle, \qquad 1 \le k \le \lfloor n/2\rfloor,

are first integrals of eq:motion-general ($H_1 = 2H$; $H_{n/2} = \operatorname{Pf}(M)^2/(2+a+b)$ for even $n$).
With the $n$ known integrals (the non-constant coefficients of $p(\lambda, \sigma)$ and $H$), the new
ones $H_2, \dots, H_{\lceil n/2\rceil - 1}$ (that is $\lceil n/2\rceil - 2$ of them) give
$2n - 2 - \lfloor n/2\rfloor$ independent $SO(n-1)$-invariant integrals: exactly the number a flow on
$\lfloor n/2\rfloor$-tori in the $(2n-2)$-dimensional $P/SO(n-1)$ needs.

**Checked here.** (1) $\dot H_k = 0$ exactly at a seeded rational point of $P$ with random rational
$a \in [-1, 1]\setminus\{0\}$, $b \in [1, 3]$, for every $k$ and $n = 4, \dots, 9$ ($\Omega$ by an exact solve of the
definition eq:M-O-axi-symm, :mod:`symbolic.family.wedge_integrals`; SymPy ``DomainMatrix`` and FLINT
``fmpq_mat``, which must agree): Schwartz–Zippel evidence of the identity for those $n$, the method the
ledger uses for all-$n$ rows up to $n = 12$ (here to 9 for cost). (2) At a seeded rational point, the
differentials on $TP$ of the $n$ known integrals and $H_2..H_{\lceil n/2\rceil-1}$ have rank
$2n - 2 - \lfloor n/2\rfloor$ and vanish on the generators of $SO(n-1)$, $n = 5, \dots, 8$ (SymPy and
FLINT ranks, exact zeros). For $n = 6$, $\dot H_2 = 0$ is also checked as an identity in symbolic $a, b$
beside the ledger (:mod:`symbolic.family.wedge_n6`, ``tests/test_wedge_n6.py``: FLINT reduction of the
164 220-term residual modulo $\lVert\gamma\rVert^2 = 1$, 40 s; SymPy's reduction agreed in a 600 s run).
For $n = 5$ the symbolic proof is row S6:sixth-integral-n5 ($H_2$ and its $F$
is $(\lVert w\rVert^2 + F)/(2+a+b)$; tests/test_reduced5.py).

**Not proved.** The identity for every $n$ (no reduction argument yet); and what the count gives for
$n \ge 6$: Euler–Jacobi needs $m - 2$ integrals and yields 2-tori, but here the expected tori have
dimension $\lfloor n/2\rfloor \ge 3$; quasi-periodicity on $k$-tori needs, besides $m - k$ integrals,
$k$ independent commuting vector fields preserving them (Bogoyavlenskij's broad integrability) or a
Hamiltonisation (the paper's first open problem). Those are not established here.

**Uses** eq:motion-general, eq:M-O-axi-symm, eq:pol-first-integrals, eq:action.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.proofs.s6_open_reduced_n5 import _generators, _integral_gradients
from chaplygin_nd.symbolic.exact import flint_engine, points
from chaplygin_nd.symbolic.exact.identity import Check
from chaplygin_nd.symbolic.exact.points import ledger_seed
from chaplygin_nd.symbolic.family import wedge_integrals as wi

SECTION = "Conclusions — open problems (beyond the paper)"
RATE_N = (4, 5, 6, 7, 8, 9)
RANK_N = (5, 6, 7, 8)


def _point(n: int, what: str):
    rng = points.generator(ledger_seed(), "S6:wedge-integrals", what, n)
    M = points.skew_matrix(rng, n)
    gamma = points.sphere_point(rng, n)
    a = sp.Integer(0)
    while a == 0:   # a = 0 is the spherical tensor (Omega constant): a special stratum, not generic
        a = points.rational(rng, -1, 1)
    return M, gamma, a, points.rational(rng, 1, 3)


def conservation(n: int) -> Check:
    r"""Part (1) in dimension ``n``: $\dot H_k = 0$ at a seeded rational point, both engines, every $k$."""
    M, g, a, b = _point(n, "rate")
    bad = []
    for k in range(1, n // 2 + 1):
        rs, rf = wi.rate(M, g, a, b, k, "sympy"), wi.rate(M, g, a, b, k, "flint")
        if sp.Rational(int(rf.p), int(rf.q)) != rs:
            raise flint_engine.EngineDisagreement(f"dH_{k}/dt at n = {n}: SymPy {rs}, FLINT {rf}")
        if rs != 0:
            bad.append((k, rs))
    return Check(not bad, f"n = {n}: dH_k/dt = 0 exactly for k = 1..{n // 2} at a = {a}, b = {b} "
                          "(SymPy DomainMatrix and FLINT fmpq_mat)" + (f"; non-zero: {bad}" if bad else ""))


def independence(n: int) -> tuple[Check, int]:
    """Part (2) in dimension ``n``: the rank on $TP$ of the known and the new integrals, invariance."""
    M, g, a, b = _point(n, "rank")
    _, G = _integral_gradients(M, g, a, b)
    rows = [wi.gradient(M, g, a, b, k, "sympy") for k in range(2, (n + 1) // 2)]
    J = G.col_join(sp.Matrix(rows)) if rows else G
    N = n * (n - 1) // 2
    JT = J * sp.diag(sp.eye(N), sp.eye(n) - g * g.T)
    r_sympy = JT.rank()
    with flint_engine.use_engine("flint"):
        r_flint = flint_engine.rank(JT)
    invariant = all(v == 0 for v in J * _generators(M, g).T)
    need = 2 * n - 2 - n // 2
    return (Check(r_sympy == r_flint == need and invariant,
                  f"n = {n}: rank {r_sympy} (SymPy), {r_flint} (FLINT) of {J.rows} integrals "
                  f"({n} known + {len(rows)} new), needed 2n - 2 - floor(n/2) = {need}; "
                  f"SO({n - 1})-invariant: {invariant}"), r_sympy)


@claim("S6:wedge-integrals", uses=("eq:motion-general", "eq:M-O-axi-symm", "eq:pol-first-integrals",
                                    "eq:action", "S6:sixth-integral-n5"),
       adds=(SECTION, "first integrals H_k = <M^k, (2 + D_B)^{-1} M^k> of the axisymmetric sphere "
                      "(B = a E_n E_n^T + b gamma gamma^T); with the n known ones they give "
                      "2n - 2 - floor(n/2) independent invariant integrals (n = 5..8 exact at seeded "
                      "points; conservation exact at seeded points for n = 4..9)"))
def s6_wedge_integrals() -> Verdict:
    parts = [Verdict.all_of([(f"n = {n}", conservation(n))], n_values=(n,)).as_part(f"conserved, n = {n}")
             for n in RATE_N]
    ranks = {}
    for n in RANK_N:
        chk, r = independence(n)
        ranks[n] = r
        parts.append(Verdict.all_of([(f"n = {n}", chk)], n_values=(n,)).as_part(f"independent, n = {n}"))
    notes = ("independent invariant integrals (known n + new ceil(n/2) - 2): "
             + ", ".join(f"n = {n}: {r}" for n, r in ranks.items())
             + "; for every n this is 2n - 2 - floor(n/2), the count of quasi-periodic motion on "
             "floor(n/2)-tori in P/SO(n-1); all n: conjecture (no reduction argument); n >= 6: a torus "
             "theorem beyond Euler-Jacobi is needed and not established")
    return Verdict.of_parts(parts, n_values=tuple(sorted(set(RATE_N) | set(RANK_N))), notes=notes, method=(
        "exact at seeded rational points (Schwartz-Zippel): dH_k/dt by exact solves of L_gamma and of "
        "2 + D_B on the wedge powers, SymPy and FLINT; exact Jacobian ranks (SymPy and FLINT)"))
