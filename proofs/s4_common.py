r"""Shared machinery of the Section 4 proofs (registers no ledger row).

* symbolic points: generic $M \in \mathfrak{so}(n)$, $\gamma$ with symbolic entries (identities are
  proved modulo $\lVert\gamma\rVert^2 = 1$), generic points of $\mathcal{V}$ ($M = PAP$);
* seeded exact rational points: $\gamma \in S^{n-1}$ by inverse stereographic projection,
  $a \in [-1, 1]$, $b > 0$;
* :func:`combine` — several :class:`~symbolic.exact.identity.Check` s as one (holds iff all hold).

The reduction argument used by most Section 4 rows
---------------------------------------------------
Every formula of Section 4 is built from $M$ (or $\Omega$), $\gamma$, $E_n$ with matrix-vector
products, $u \wedge v$, inner products and scalar functions of $x = \langle\gamma, E_n\rangle$. Such
a formula $F$ is *natural*: for a linear isometry $\iota: \mathbb{R}^k \to \mathbb{R}^n$ with
$\iota E_k = E_n$, $F(\iota M' \iota^T, \iota\gamma') = \iota F(M', \gamma')\iota^T$, and $F(M, \gamma)$
lies in $\Lambda^2 S$ when $M \in \Lambda^2 S$ and $S \ni \gamma, E_n$. An identity $F \equiv 0$ that
is *linear* in $M$ needs checking only on $M = u\wedge v$ for $u, v$ in an orthonormal basis
(of $\mathbb{R}^n$, or of $\gamma^\perp$ for identities on $\mathcal{V} = \Lambda^2\gamma^\perp$); then
$S = \operatorname{span}\{E_n, \gamma, u, v\}$ has dimension $\le 4$, and (enlarging $S$ to dimension
4 when $n \ge 4$) the identity in $\mathbb{R}^n$ is the pull-back of the same identity in
$\mathbb{R}^4$ at $(M', \gamma')$. Hence **the exact symbolic check for $n = 4$ (every $M$, every
$\gamma \in S^3$) proves a linear identity for every $n \ge 4$**, and $n = 3$ is checked on its own.
Bilinear identities need $\dim S \le 6$, i.e. the symbolic check at $n = 6$.

The frame. The same naturality, with $h \in SO(n-1)$ ($hE_n = E_n$), moves any $\gamma$ to
$(0, \dots, 0, s, x)$ with $s \ge 0$; an identity in $M$ holding for all $M$ at every such
$\gamma$ holds at every $\gamma$. So for $n \ge 4$ the symbolic checks take $\gamma$ in this frame
(modulo $s^2 + x^2 = 1$), which keeps them fast; $n = 3$ uses a fully generic $\gamma$. The
equivariance itself (eq:action) is proved with fully generic $\gamma$.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence

import sympy as sp
from chaplygin_nd.symbolic.algebra import skew_symbols, vector_symbols, wedge
from chaplygin_nd.symbolic.axisymmetric import a, b
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.exact.identity import (
    Check,
    point_engines,
    rational_identity,
    zero_at_points,
)
from chaplygin_nd.symbolic.vertical import vertical_point

__all__ = [
    "a", "b", "SAMPLERS", "FRAME", "gamma_symbols", "frame_gamma", "sphere_symbols", "generic",
    "generic_vertical", "sym_gamma", "sym_checks",
    "random_point", "random_vertical_point", "point_checks", "combine", "fact", "REDUCTION",
]

#: Counterexample samplers keeping the paper's domain $a \in [-1, 1]$, $b > 0$.
SAMPLERS = {a: lambda r: points.rational(r, -1, 1, 8, nonzero=True),
            b: lambda r: points.rational(r, 0, 4, 8, open_lo=True)}

FRAME = (" (generic gamma for n = 3; for n >= 4 gamma = (0,..,0,s,x), no loss by "
         "SO(n-1)-naturality)")

FRAME_ALL = " (gamma = (0,..,0,s,x), no loss by SO(n-1)-naturality)"

REDUCTION = ("reduction argument (linear in M; operators act on span{E_n, gamma, u, v}, "
             "proofs/s4_common.py) covering all n >= 4 from the symbolic n = 4 check")


def gamma_symbols(n: int) -> sp.Matrix:
    r"""$\gamma = (g_1, \dots, g_n)^T$ with real symbols; identities are taken modulo $\sum g_i^2 = 1$."""
    return vector_symbols("g", n)


def frame_gamma(n: int) -> sp.Matrix:
    r"""$\gamma = (0, \dots, 0, g_{n-1}, g_n)^T$: every $\gamma \in \mathbb{R}^n$ is $h$ of such a vector
    for some $h \in SO(n-1)$ ($hE_n = E_n$), so natural identities need only this frame."""
    g = gamma_symbols(n)
    return sp.Matrix([0] * (n - 2) + [g[n - 2], g[n - 1]])


def sphere_symbols(n: int) -> tuple:
    """The symbols of the gamma used at this n: generic for n = 3, the frame for n >= 4."""
    g = gamma_symbols(n)
    return tuple(g) if n == 3 else (g[n - 2], g[n - 1])


def generic(n: int) -> tuple[sp.Matrix, sp.Matrix]:
    r"""A generic $M \in \mathfrak{so}(n)$ (symbols ``m..``) and $\gamma$: fully generic for $n = 3$,
    :func:`frame_gamma` for $n \ge 4$ (see FRAME)."""
    return skew_symbols("m", n), (gamma_symbols(n) if n == 3 else frame_gamma(n))


def sym_gamma(n: int) -> sp.Matrix:
    """The symbolic gamma of :func:`sym_checks` at this n (generic for n = 3, the frame for n >= 4)."""
    return gamma_symbols(n) if n == 3 else frame_gamma(n)


def generic_vertical(n: int, frame: bool = False) -> tuple[sp.Matrix, sp.Matrix]:
    r"""A generic point of $\mathcal{V} = \Lambda^2\gamma^\perp$: for $n = 3$, $M_0 = PAP$
    (:func:`~symbolic.vertical.vertical_point`) with generic $\gamma$; for $n \ge 4$, with $\gamma$ in
    the frame, $M_0 = \sum_{i<j} A_{ij} f_i\wedge f_j$ over the basis $f = (E_1, \dots, E_{n-2},
    (0, \dots, 0, g_n, -g_{n-1}))$ of $\gamma^\perp$ (also for $n = 3$ when ``frame``)."""
    if n == 3 and not frame:
        g = gamma_symbols(n)
        return vertical_point(skew_symbols("A", n), g).applyfunc(sp.expand), g
    g = frame_gamma(n)
    f = [sp.eye(n)[:, i] for i in range(n - 2)]
    f.append(sp.Matrix([0] * (n - 2) + [g[n - 1], -g[n - 2]]))
    A = skew_symbols("A", n - 1)
    M0 = sp.zeros(n, n)
    for i in range(n - 1):
        for j in range(i + 1, n - 1):
            M0 += A[i, j] * wedge(f[i], f[j])
    return M0, g


def sym_checks(residual: Callable[[int], object], ns: Sequence[int], *, sphere: bool = True,
               label: str, uses_gamma: bool | None = None, frame_n3: bool = False,
               generic_gamma: bool = False) -> Check:
    r"""``rational_identity(residual(n))`` modulo $\lVert\gamma\rVert^2 = 1$ for each $n$ in ``ns``
    (a square matrix residual on its entries $i \le j$, see :func:`_upper`). ``frame_n3``: the
    residual uses the frame $\gamma$ also for $n = 3$; ``generic_gamma``: it uses the fully generic
    :func:`gamma_symbols` for every $n$."""
    checks = []
    for n in ns:
        if not sphere:
            sph = None
        elif generic_gamma:
            sph = tuple(gamma_symbols(n))
        elif frame_n3 and n == 3:
            sph = tuple(frame_gamma(3)[1:])
        else:
            sph = sphere_symbols(n)
        chk = rational_identity(_upper(residual(n)), sphere=sph, samplers=SAMPLERS,
                                label=f"{label}-n{n}")
        checks.append((n, chk))
    return combine([c for _, c in checks],
                   method=f"exact symbolic identity for n in {{{', '.join(str(n) for n in ns)}}}"
                          + (" modulo ||gamma||^2 = 1" if sphere else "")
                          + (" (fully generic gamma)" if generic_gamma else
                             (FRAME_ALL if frame_n3 else FRAME)
                             if (sphere if uses_gamma is None else uses_gamma) else ""))


def _upper(residual):
    """A square matrix residual in so(n) is checked on its entries i <= j (both sides are skew by
    construction; the seeded point checks compare full matrices)."""
    if isinstance(residual, sp.MatrixBase) and residual.is_square and residual.rows > 1:
        n = residual.rows
        return [residual[i, j] for i in range(n) for j in range(i, n)]
    return residual


def random_point(rng, n: int, *, vertical: bool = False) -> dict:
    r"""Exact rational point: $a \in [-1,1]$, $b > 0$, $\gamma \in S^{n-1}$, $M \in \mathfrak{so}(n)$
    (in $\mathcal{V}$ when ``vertical``)."""
    pt = points.axisymmetric_parameters(rng)
    gamma = points.sphere_point(rng, n)
    M = points.skew_matrix(rng, n)
    if vertical:
        M = vertical_point(M, gamma)
    pt.update({"n": n, "gamma": gamma, "M": M})
    return pt


def random_vertical_point(rng, n: int) -> dict:
    """:func:`random_point` on $\\mathcal{V}$."""
    return random_point(rng, n, vertical=True)


def point_checks(residual: Callable[[dict], object], ns: Iterable[int], *, count: int = 1,
                 vertical: bool = False, label: str, sympy_max: int | None = None) -> Check:
    """``zero_at_points`` at ``count`` seeded rational points for each n in ``ns``; SymPy and
    FLINT up to ``sympy_max`` (default ``exact.SYMPY_POINT_MAX_N``), FLINT alone above."""
    ns = list(ns)
    checks = []
    for n in ns:
        def sample(r, n=n):
            return random_point(r, n, vertical=vertical)

        checks.append(zero_at_points(residual, sample, count=count, label=f"{label}-n{n}",
                                     describe="V" if vertical else "so(n) x S^{n-1}",
                                     engines=point_engines(n, sympy_max)))
    return combine(checks, method=f"exact at {count} seeded rational point(s) "
                                  f"{'of V ' if vertical else ''}for each n in "
                                  f"{points.n_text(ns)} (seed {points.ledger_seed()})")


def combine(checks: Sequence[Check], *, method: str = "") -> Check:
    """One :class:`Check` that holds iff all do; the first failure's counterexample is kept.
    No checks: ``ValueError`` (an empty conjunction would hold vacuously and prove nothing)."""
    checks = list(checks)
    if not checks:
        raise ValueError("combine needs at least one check: an empty list proves nothing")
    seconds = sum(c.seconds for c in checks)
    how = method or "; ".join(dict.fromkeys(c.method for c in checks))
    for c in checks:
        if not c.ok:
            return Check(False, f"{how} [failed: {c.method}]", c.counterexample, seconds)
    return Check(True, how, None, seconds)


def fact(ok: bool, method: str, counterexample=None) -> Check:
    """A :class:`Check` from an exact computation done in the proof itself (e.g. an explicit
    point where a quantity is non-zero)."""
    return Check(bool(ok), method, counterexample)
