r"""The exceptional $b$ of the independence bound at one point, as a polynomial in $b$ (row S6:wedge-independence).

On the $SO(n)$-orbit of $p = (M, \gamma)$ the integrals $h = (H_1, \dots, H_K)$, $K = \lceil n/2\rceil - 1$, become
$\varphi_k(e) = \langle W_k, (2 + D_{B(e)})^{-1}W_k\rangle$, $W_k = M^{\wedge k}$, $B(e) = a\,ee^T + b\gamma\gamma^T$
(:mod:`symbolic.family.independence_all_n`, step (ii)). Differentiating the resolvent, with $Y_k = (2 + D_B)^{-1}W_k$
at $e = E_n$ and $D_{ve^T + ev^T} = \varepsilon_v\iota_e + \varepsilon_e\iota_v$,

.. math::
    d\varphi_k(v) = -a\langle Y_k, D_{vE_n^T + E_nv^T}Y_k\rangle = -2a\,\langle\iota_vY_k, \iota_{E_n}Y_k\rangle, \qquad v \perp E_n .

Here $b$ is a symbol: the entries of $2 + D_B$ are polynomials of degree $\le 1$ in $b$, the solve is exact over
$\mathbb{Q}(b)$, and every $K\times K$ minor of $\Phi_{ki} = \langle\iota_{E_i}Y_k, \iota_{E_n}Y_k\rangle$ ($i < n$; the factor $-2a$ dropped,
$a \ne 0$) is a rational function of $b$. Its denominator divides a power of the eigenvalue factors of $2 + D_B$,
none zero where $L_\gamma$ is invertible; so the rank of $d\varphi$ at $p$ is below $K$ exactly at the common roots of the
numerators, the roots of their greatest common divisor $G(b)$. The point has $\gamma \in \operatorname{span}\{E_{n-1}, E_n\}$ (every
point is one after a rotation in $SO(n-1)$, which fixes $E_n$ and every $H_k$), so $2 + D_B$ is block diagonal
with blocks of size $\le 2$ in the basis $e_I$.

Two engines, independently: SymPy's field ``QQ.frac_field(b)`` with its ``count_roots`` (Sturm), and FLINT
``fmpq_poly`` pairs (numerator, denominator) with a Sturm sequence written here. The number of positive roots
counts distinct roots.
"""

from __future__ import annotations

import itertools

import flint
import sympy as sp
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.family import wedge_integrals as wi
from sympy.polys.matrices import DomainMatrix

__all__ = ["adapted_frame_point", "phi_matrix", "exceptional_record", "common", "positive_roots_sturm"]

_b = sp.Symbol("b")
_FIELD = sp.QQ.frac_field(_b)


class _Frac:
    """A rational function of $b$ over FLINT: a pair of ``fmpq_poly`` (numerator, denominator), reduced."""

    __slots__ = ("p", "q")

    def __init__(self, p, q=None):
        p = p if isinstance(p, flint.fmpq_poly) else flint.fmpq_poly([p])
        q = flint.fmpq_poly([1]) if q is None else q
        if p.is_zero():
            self.p, self.q = p, flint.fmpq_poly([1])
            return
        g = p.gcd(q)
        p, q = p / g if g.degree() > 0 else p, q / g if g.degree() > 0 else q
        c = q.leading_coefficient()
        self.p, self.q = p / c, q / c

    @staticmethod
    def _of(o):
        return o if isinstance(o, _Frac) else _Frac(flint.fmpq_poly([o]))

    def __add__(self, o):
        o = self._of(o)
        return _Frac(self.p * o.q + o.p * self.q, self.q * o.q)

    __radd__ = __add__

    def __neg__(self):
        return _Frac(-self.p, self.q)

    def __sub__(self, o):
        return self + (-self._of(o))

    def __rsub__(self, o):
        return self._of(o) - self

    def __mul__(self, o):
        o = self._of(o)
        return _Frac(self.p * o.p, self.q * o.q)

    __rmul__ = __mul__

    def __truediv__(self, o):
        o = self._of(o)
        if o.p.is_zero():
            raise ZeroDivisionError("division by the zero rational function")
        return _Frac(self.p * o.q, self.q * o.p)

    def __eq__(self, o):
        o = self._of(o)
        return self.p == o.p and self.q == o.q

    def __ne__(self, o):
        return not self == o

    __hash__ = None  # type: ignore[assignment]


def _engine(engine: str):
    """(convert a rational, the symbol b, zero, one) in the engine's field $\\mathbb{Q}(b)$."""
    if engine == "flint":
        def num(v):
            r = sp.Rational(v)
            return _Frac(flint.fmpq_poly([flint.fmpq(int(r.p), int(r.q))]))
        return num, _Frac(flint.fmpq_poly([0, 1])), _Frac(0), _Frac(1)
    if engine != "sympy":
        raise ValueError(f"unknown engine {engine!r} (sympy or flint)")
    return (lambda v: _FIELD.convert(sp.Rational(v))), _FIELD.gens[0], _FIELD.zero, _FIELD.one


def adapted_frame_point(rng, n: int):
    r"""$(M, \gamma, f, \theta)$: $M = \sum_j\theta_jf_{2j-1}\wedge f_{2j}$ in a random rational orthonormal frame $f$ with distinct
    non-zero $\theta_j$ (as :func:`symbolic.family.independence_all_n.frame_point`), $\gamma$ a random rational point of
    the unit circle of $\operatorname{span}\{E_{n-1}, E_n\}$."""
    f = points.rational_rotation(rng, n)
    theta: list = []
    while len(theta) < n // 2:
        v = points.rational(rng, 1, 4, nonzero=True)
        if v not in theta:
            theta.append(v)
    M = sp.zeros(n, n)
    for j, t in enumerate(theta):
        u, v = f[:, 2 * j], f[:, 2 * j + 1]
        M += t * (u * v.T - v * u.T)
    gamma = sp.Matrix([0] * (n - 2) + list(points.sphere_point(rng, 2)))
    return M, gamma, f, theta


def _solve_dense(A, y, zero):
    """Gaussian elimination over a field (any element type with ``+ - * /`` and ``== 0``)."""
    n = len(y)
    R = [list(row) + [v] for row, v in zip(A, y, strict=True)]
    for c in range(n):
        piv = next(r for r in range(c, n) if R[r][c] != 0)
        R[c], R[piv] = R[piv], R[c]
        for r in range(n):
            if r != c and R[r][c] != 0:
                m = R[r][c] / R[c][c]
                R[r] = [x - m * z for x, z in zip(R[r], R[c], strict=True)]
    return [R[i][n] / R[i][i] for i in range(n)]


def _det(A, zero, one):
    """The determinant over a field by elimination."""
    A = [list(r) for r in A]
    n, d = len(A), one
    for c in range(n):
        piv = next((r for r in range(c, n) if A[r][c] != 0), None)
        if piv is None:
            return zero
        if piv != c:
            A[c], A[piv], d = A[piv], A[c], -d
        d = d * A[c][c]
        for r in range(c + 1, n):
            if A[r][c] != 0:
                m = A[r][c] / A[c][c]
                A[r] = [x - m * z for x, z in zip(A[r], A[c], strict=True)]
    return d


def phi_matrix(M, gamma, a, engine: str = "sympy") -> list[list]:
    r"""$\Phi_{ki} = \langle\iota_{E_i}Y_k, \iota_{E_n}Y_k\rangle$, $k = 1..K$, $i = 1..n-1$, over $\mathbb{Q}(b)$ (module docstring;
    $d\varphi_k(E_i) = -2a\Phi_{ki}$), with $Y_k = (2 + D_B)^{-1}M^{\wedge k}$ solved block by block."""
    num, b, zero, one = _engine(engine)
    n = M.rows
    Mq = [[num(M[i, j]) for j in range(n)] for i in range(n)]
    g = [num(v) for v in gamma]
    B = [[(num(a) if i == j == n - 1 else zero) + b * g[i] * g[j] for j in range(n)] for i in range(n)]
    En = [one if i == n - 1 else zero for i in range(n)]
    out = []
    for k in range(1, (n + 1) // 2):
        basis = wi.subsets(n, 2 * k)
        W = wi.wedge_power(Mq, n, k, zero, one)
        A = wi.shifted(B, n, 2 * k, zero)
        Yv = [zero] * len(W)
        for block in wi._components(A, len(W)):
            pos = {c: t for t, c in enumerate(block)}
            dense = [[zero] * len(block) for _ in block]
            for r in block:
                for c, v in A.get(r, {}).items():
                    dense[pos[r]][pos[c]] = v
            for r, v in zip(block, _solve_dense(dense, [W[r] for r in block], zero), strict=True):
                Yv[r] = v
        Y = dict(zip(basis, Yv, strict=True))
        Z = wi.interior(En, Y, zero)
        out.append([wi.inner(wi.interior([one if t == i else zero for t in range(n)], Y, zero), Z, zero)
                    for i in range(n - 1)])
    return out


def positive_roots_sturm(p) -> int:
    """The number of distinct roots in $b > 0$ of a non-zero ``fmpq_poly`` ``p``, by a Sturm sequence:
    $V(0^+) - V(+\\infty)$ after dividing out the power of $b$ (so $p(0) \\ne 0$)."""
    if p.is_zero():
        raise ValueError("the zero polynomial has every b as a root")
    while p.coeffs()[0] == 0:
        p = p.right_shift(1)
    seq = [p, p.derivative()]
    while not seq[-1].is_zero():
        seq.append(-(seq[-2] % seq[-1]))
    seq = [s for s in seq if not s.is_zero()]

    def changes(signs):
        s = [v for v in signs if v != 0]
        return sum(1 for x, y in zip(s, s[1:], strict=False) if (x > 0) != (y > 0))
    return changes([s.coeffs()[0] for s in seq]) - changes([s.leading_coefficient() for s in seq])


def _gcd(polys: list, engine: str):
    """The monic gcd of the engine's polynomials (the zero polynomial if all are zero)."""
    if engine == "flint":
        G = flint.fmpq_poly([0])
        for q in polys:
            if not q.is_zero():
                G = q if G.is_zero() else G.gcd(q)
        return G / G.leading_coefficient() if not G.is_zero() else G
    G = sp.Poly(0, _b, domain=sp.QQ)
    for q in polys:
        G = sp.gcd(G, q)
    return G.monic() if not G.is_zero else G


def _positive_roots(G, engine: str) -> int:
    """Distinct roots of the non-zero polynomial ``G`` in $b > 0$: FLINT by :func:`positive_roots_sturm`,
    SymPy by ``count_roots`` on $[0, \\infty)$ less the root $0$."""
    if engine == "flint":
        return positive_roots_sturm(G)
    return int(G.count_roots(0, None)) - (1 if G.eval(0) == 0 else 0)


def _as_text(G, engine: str) -> str:
    if engine == "flint":
        coeffs = [sp.Rational(int(c.p), int(c.q)) for c in G.coeffs()]
        return str(sp.Poly(list(reversed(coeffs)), _b, domain=sp.QQ).as_expr()) if coeffs else "0"
    return str(G.as_expr())


def _rational_roots(G, engine: str) -> list:
    """The rational roots $b > 0$ of ``G`` (``sympy.Rational``), from the engine's factorisation."""
    if engine == "flint":
        out = []
        for fac, _ in G.factor()[1]:
            if fac.degree() == 1:
                c0, c1 = fac.coeffs()
                out.append(sp.Rational(int((-c0 / c1).p), int((-c0 / c1).q)))
    else:
        out = [r for r in sp.roots(G, filter="Q")]
    return sorted(r for r in out if r > 0)


def _at_zero(x, engine: str):
    """A reduced element of $\\mathbb{Q}(b)$ at $b = 0$ (its denominator is non-zero there: $L_\\gamma$ at $b = 0$)."""
    if engine == "flint":
        p = x.p.coeffs()[0] if x.p.length() else flint.fmpq(0)
        return p / x.q.coeffs()[0]
    return sp.QQ.convert(sp.Rational(x.numer.as_expr().subs(_b, 0) / x.denom.as_expr().subs(_b, 0)))


def exceptional_record(M, gamma, a, engine: str = "sympy") -> dict:
    r"""At the point, in one engine's arithmetic throughout: the gcd $G(b)$ of the numerators of the $K\times K$
    minors of $\Phi$ (``poly``: the engine's monic polynomial; ``gcd``: as text), its degree, the number of its
    distinct roots in $b > 0$ and its rational roots there, the number of minors, the rank of $\Phi$ at $b = 0$, and
    the number of distinct roots in $b > 0$ of the lcm of the minors' denominators (``pole_positive_roots``: zero
    means every minor is defined for every $b > 0$, so the rank falls exactly at the roots of $G$).
    Raises ``ValueError`` if every minor is zero (the point is not in general position)."""
    n = M.rows
    K = (n + 1) // 2 - 1
    _, _, zero, one = _engine(engine)
    Phi = phi_matrix(M, gamma, a, engine)
    minors = [_det([[Phi[k][i] for i in cols] for k in range(K)], zero, one)
              for cols in itertools.combinations(range(n - 1), K)]
    nums = [m.p if engine == "flint" else sp.Poly(m.numer.as_expr(), _b, domain=sp.QQ) for m in minors]
    G = _gcd(nums, engine)
    if (G.is_zero() if engine == "flint" else G.is_zero):
        raise ValueError("every minor of d(phi) vanishes identically in b at this point")
    dens = [m.q if engine == "flint" else sp.Poly(m.denom.as_expr(), _b, domain=sp.QQ) for m in minors]
    L = dens[0]
    for d in dens[1:]:
        g = _gcd([L, d], engine)
        L = L * d / g if engine == "flint" else sp.quo(L * d, g)
    Phi0 = [[_at_zero(x, engine) for x in row] for row in Phi]
    if engine == "flint":
        rank0 = flint.fmpq_mat(len(Phi0), n - 1, [v for r in Phi0 for v in r]).rank()
    else:
        rank0 = DomainMatrix([list(r) for r in Phi0], (len(Phi0), n - 1), sp.QQ).rank()
    return {"poly": G, "gcd": _as_text(G, engine), "degree": int(G.degree()), "positive_roots": _positive_roots(G, engine),
            "rational_positive_roots": _rational_roots(G, engine), "minors": len(minors), "rank_at_0": rank0,
            "pole_positive_roots": _positive_roots(L, engine)}


def common(polys: list, engine: str) -> tuple[str, int, int]:
    r"""The gcd of the $G(b)$ of several points (the $b$ at which the bound fails at every one of them), in the
    engine: (text, degree, distinct roots in $b > 0$)."""
    G = _gcd(polys, engine)
    return _as_text(G, engine), int(G.degree()), _positive_roots(G, engine)
