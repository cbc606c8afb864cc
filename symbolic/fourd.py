r"""The axisymmetric 4D Chaplygin sphere in block notation (Section 5), derived from the definitions.

Block notation of Section 5 (S:4D), with $\hat v w = v \times w$:

.. math::
    M = \begin{pmatrix} \hat k & u \\ -u^T & 0 \end{pmatrix}, \quad
    \Omega = \begin{pmatrix} \hat \eta & \xi \\ -\xi^T & 0 \end{pmatrix}, \quad
    \gamma = (q, x)^T, \qquad k, u, \eta, \xi, q \in \mathbb{R}^3,\ x \in [-1, 1].

Everything is obtained from eq:motion-general ($\dot M = [M,\Omega]$, $\dot\gamma = -\Omega\gamma$) and
eq:M-O-axi-symm ($M = 2\Omega + a(\Omega E_4)\wedge E_4 + b(\Omega\gamma)\wedge\gamma$) by computing with
$4\times 4$ matrices; nothing is copied from the paper.

The inverse $(\xi, \eta) = L_\gamma^{-1}(k, u)$ is *solved*: $L_\gamma$ commutes with rotations fixing
$E_4$, so it is a $2\times 2$ block matrix over the commutative algebra spanned by
$I$, $P_1 = qq^T$, $P_2 = \hat q$ (with $P_1^2 = sP_1$, $P_1P_2 = P_2P_1 = 0$, $P_2^2 = P_1 - sI$,
$s = \lVert q\rVert^2$). The ansatz $L_\gamma^{-1} = [c_0 I + c_1 P_1 + c_2 P_2]_{2\times 2}$ gives 12
linear equations for 12 unknowns, solved exactly over $\mathbb{Q}(a, b, x, s)$; as $L_\gamma$ is
invertible the solution *is* the inverse (for every $\gamma$ with $\Delta \ne 0$, not only on $S^3$).
On $S^3$ we set $s = 1 - x^2$.

Fast arithmetic: the 4D field is handled as sparse polynomials (``sympy.polys.rings``) in the ring
:data:`RING` with generators ``a, b, x, k1..k3, u1..u3, q1..q3, eta1..eta3, xi1..xi3``; rational
quantities are numerators over the common denominator
$D = 2(2+a+b)\Delta(x)$, $\Delta(x) = (2+a)(2+b) - abx^2$ (eq:Delta).
"""

from __future__ import annotations

from functools import cache

import sympy as sp
from sympy import QQ
from sympy.polys.rings import ring

__all__ = [
    "a", "b", "x", "s", "k", "u", "q", "eta", "xi", "RING", "GENS", "RV", "Delta", "D",
    "cross", "dot", "block", "unblock", "L_blocks", "motion_blocks", "inverse_coefficients",
    "inverse_apply", "xi_eta_numerators", "xi_eta", "field_numerators", "field",
    "charpoly", "F1", "F2", "F3", "energy", "integrals",
    "sphere_normal_form", "velocity_form_numerators",
]

#: Parameters, $x = \gamma_4$ and $s = \lVert q\rVert^2$ (used off the sphere only).
a, b, x, s = sp.symbols("a b x s", real=True)
k = sp.Matrix(sp.symbols("k1:4", real=True))
u = sp.Matrix(sp.symbols("u1:4", real=True))
q = sp.Matrix(sp.symbols("q1:4", real=True))
eta = sp.Matrix(sp.symbols("eta1:4", real=True))
xi = sp.Matrix(sp.symbols("xi1:4", real=True))

GENS = (a, b, x, *k, *u, *q, *eta, *xi)
RING, *_RG = ring(list(GENS), QQ)
_a, _b, _x = _RG[0:3]
_k, _u, _q, _eta, _xi = (tuple(_RG[i:i + 3]) for i in (3, 6, 9, 12, 15))
#: The generators of :data:`RING` by name: scalars ``a, b, x`` and 3-tuples ``k, u, q, eta, xi``.
RV = {"a": _a, "b": _b, "x": _x, "k": _k, "u": _u, "q": _q, "eta": _eta, "xi": _xi}

#: eq:Delta as a ring element, and the common denominator $D = 2(2+a+b)\Delta(x)$.
Delta = (2 + _a) * (2 + _b) - _a * _b * _x**2
D = 2 * (2 + _a + _b) * Delta


def cross(p, r):
    """$p \\times r$ for 3-tuples of ring elements or expressions (utility of S:4D, eq:motion-n4)."""
    return (p[1] * r[2] - p[2] * r[1], p[2] * r[0] - p[0] * r[2], p[0] * r[1] - p[1] * r[0])


def dot(p, r):
    """$\\langle p, r\\rangle$ for 3-tuples (utility of S:4D)."""
    return p[0] * r[0] + p[1] * r[1] + p[2] * r[2]


def _add(*vs):
    return tuple(sum(c) for c in zip(*vs, strict=False))


def _scale(c, v):
    return tuple(c * t for t in v)


def block(v, w):
    r"""The $4\times 4$ skew matrix $\begin{pmatrix}\hat v & w\\ -w^T & 0\end{pmatrix}$ (S:4D notation),
    as nested lists; ``v, w`` 3-tuples (ring elements or SymPy expressions)."""
    zero = v[0] * 0
    return [[zero, -v[2], v[1], w[0]], [v[2], zero, -v[0], w[1]],
            [-v[1], v[0], zero, w[2]], [-w[0], -w[1], -w[2], zero]]


def unblock(W):
    """Inverse of :func:`block` on $\\mathfrak{so}(4)$: the pair $(v, w)$."""
    return (W[2][1], W[0][2], W[1][0]), (W[0][3], W[1][3], W[2][3])


def _mm(P, Q):
    return [[sum(P[i][m] * Q[m][j] for m in range(4)) for j in range(4)] for i in range(4)]


def _mv(P, v):
    return [sum(P[i][j] * v[j] for j in range(4)) for i in range(4)]


def _wedge(v, w):
    return [[v[i] * w[j] - w[i] * v[j] for j in range(4)] for i in range(4)]


def L_blocks(eta_, xi_, q_=_q, x_=_x):
    r"""$(k, u)$ of $M = L_\gamma(\Omega) = 2\Omega + a(\Omega E_4)\wedge E_4 + b(\Omega\gamma)\wedge\gamma$
    (eq:M-O-axi-symm, $n = 4$) for $\Omega$ = block$(\eta, \xi)$, $\gamma = (q, x)$; any $\gamma \in
    \mathbb{R}^4$ (computed with $4\times4$ matrices; S5:ku derived)."""
    Om = block(eta_, xi_)
    one = _a**0
    gamma = [*q_, x_]
    E4 = [0 * one, 0 * one, 0 * one, one]
    W1 = _wedge(_mv(Om, E4), E4)
    W2 = _wedge(_mv(Om, gamma), gamma)
    return unblock([[2 * Om[i][j] + _a * W1[i][j] + _b * W2[i][j] for j in range(4)]
                    for i in range(4)])


def motion_blocks(k_, u_, eta_, xi_, q_=_q, x_=_x):
    r"""$(\dot k, \dot u, \dot q, \dot x)$ from $\dot M = [M, \Omega]$, $\dot\gamma = -\Omega\gamma$
    (eq:motion-general, $n = 4$) in block form (derives eq:motion-n4); any entries."""
    M = block(k_, u_)
    Om = block(eta_, xi_)
    P, Q = _mm(M, Om), _mm(Om, M)
    kd, ud = unblock([[P[i][j] - Q[i][j] for j in range(4)] for i in range(4)])
    gd = [-t for t in _mv(Om, [*q_, x_])]
    return kd, ud, tuple(gd[:3]), gd[3]


# ---------------------------------------------------------------------------------------------
# The inverse: an exact linear solve in the algebra span{I, qq^T, qhat}.
# ---------------------------------------------------------------------------------------------

def _amul(f, g):
    """Product in span{I, P1=qq^T, P2=qhat}: P1^2 = sP1, P1P2 = P2P1 = 0, P2^2 = P1 - sI."""
    return (f[0] * g[0] - s * f[2] * g[2],
            f[0] * g[1] + f[1] * g[0] + s * f[1] * g[1] + f[2] * g[2],
            f[0] * g[2] + f[2] * g[0])


def _L_algebra():
    r"""$L_\gamma$ as a 2x2 block matrix over the algebra, read off from :func:`L_blocks`:
    $k = (2+bs)\eta - bP_1\eta + bxP_2\xi$, $u = -bxP_2\eta + (2+a+bx^2)\xi + bP_1\xi$."""
    return [[(2 + b * s, -b, 0), (0, 0, b * x)], [(0, 0, -b * x), (2 + a + b * x**2, b, 0)]]


@cache
def inverse_coefficients(on_sphere: bool = True):
    r"""The exact inverse of $L_\gamma$ ($n = 4$, eq:M-O-axi-symm) in the algebra basis:
    ``C[i][j] = (c0, c1, c2)`` with $(\eta, \xi)^T = C\,(k, u)^T$ and each block
    $c_0 I + c_1 qq^T + c_2\hat q$. Rational functions of $a, b, x$ (and $s = \lVert q\rVert^2$ if
    ``on_sphere`` is false; on $S^3$, $s = 1 - x^2$). Solved from 12 linear equations."""
    cs = sp.symbols("c0:12")
    X = [[cs[0:3], cs[3:6]], [cs[6:9], cs[9:12]]]
    L = _L_algebra()
    eqs = []
    for i in range(2):
        for j in range(2):
            prod = [p + r for p, r in zip(_amul(L[i][0], X[0][j]), _amul(L[i][1], X[1][j]), strict=False)]
            eqs += [sp.expand(p - t) for p, t in zip(prod, (int(i == j), 0, 0), strict=False)]
    sol = sp.solve(eqs, cs, dict=True)
    if len(sol) != 1:
        raise ArithmeticError("the inverse ansatz has no unique solution")
    sub = {s: 1 - x**2} if on_sphere else {}
    return tuple(tuple(tuple(sp.factor(sol[0][c].subs(sub)) for c in X[i][j]) for j in range(2))
                 for i in range(2))


def _to_ring(expr):
    return RING(sp.expand(expr))


@cache
def _inverse_ring():
    """Coefficients of :func:`inverse_coefficients` (on the sphere) times D, as ring elements."""
    Dexpr = 2 * (2 + a + b) * ((2 + a) * (2 + b) - a * b * x**2)
    out = []
    for row in inverse_coefficients(True):
        out.append(tuple(tuple(_to_ring(sp.cancel(c * Dexpr)) for c in blk) for blk in row))
    return tuple(out)


def inverse_apply(kv, uv, q_=_q):
    r"""$D\cdot L_\gamma^{-1}(kv, uv) = (D\xi, D\eta)$ on $S^3$ for any 3-tuples ``kv, uv`` of ring
    elements (eq:inverse-Leg derived; valid where $\lVert q\rVert^2 + x^2 = 1$)."""
    C = _inverse_ring()

    def ap(c, v):
        return _add(_scale(c[0], v), _scale(c[1] * dot(q_, v), q_), _scale(c[2], cross(q_, v)))
    N_eta = _add(ap(C[0][0], kv), ap(C[0][1], uv))
    N_xi = _add(ap(C[1][0], kv), ap(C[1][1], uv))
    return N_xi, N_eta


@cache
def xi_eta_numerators():
    r"""$(D\xi, D\eta)$ as functions of $(k, u, q, x)$ on $S^3$ (eq:inverse-Leg derived), ring elements."""
    return inverse_apply(_k, _u)


def xi_eta():
    r"""$(\xi, \eta)$ as SymPy column vectors in $a, b, k, u, q, x$, on $S^3$ (eq:inverse-Leg derived);
    domain $\lVert q\rVert^2 + x^2 = 1$, $\Delta(x) \neq 0$."""
    Nxi, Neta = xi_eta_numerators()
    Dx = D.as_expr()
    return (sp.Matrix([c.as_expr() / Dx for c in Nxi]), sp.Matrix([c.as_expr() / Dx for c in Neta]))


@cache
def field_numerators():
    r"""$D\cdot(\dot k, \dot u, \dot q, \dot x)$: the explicit 4D field (eq:motion-n4 with eq:inverse-Leg,
    both derived) as ring elements in $a, b, k, u, q, x$; valid on $S^3$."""
    Nxi, Neta = xi_eta_numerators()
    return motion_blocks(_k, _u, Neta, Nxi)


def field():
    r"""The explicit 4D field $(\dot k_1..\dot k_3, \dot u_1..\dot u_3, \dot q_1..\dot q_3, \dot x)$ as a
    list of 10 SymPy rational expressions in $a, b, k, u, q, x$ (eq:motion-n4 + eq:inverse-Leg,
    derived); domain $P = \mathbb{R}^3\times\mathbb{R}^3\times S^3$."""
    kd, ud, qd, xd = field_numerators()
    Dx = D.as_expr()
    return [c.as_expr() / Dx for c in (*kd, *ud, *qd, xd)]


def sphere_normal_form(p):
    r"""Normal form of a ring element modulo $\lVert q\rVert^2 + x^2 - 1$ ($x^2 \to 1 - \lVert q\rVert^2$);
    zero iff ``p`` vanishes on $S^3$ (single generator = Gröbner basis)."""
    return p.rem(_x**2 + dot(_q, _q) - 1)


# ---------------------------------------------------------------------------------------------
# Integrals (S5:F123, S5:H4D) computed from their definitions.
# ---------------------------------------------------------------------------------------------

def charpoly(lam, sig):
    r"""$p(\lambda, \sigma) = \det(M + \sigma\gamma\gamma^T - \lambda\,\mathrm{Id}_4)$ (eq:pol-first-integrals,
    $n = 4$) as an expanded SymPy expression in $\lambda, \sigma, k, u, q, x$ (any $\gamma$)."""
    M = sp.Matrix(block(tuple(k), tuple(u)))
    g = sp.Matrix([*q, x])
    return sp.expand((M + sig * g * g.T - lam * sp.eye(4)).det(method="berkowitz"))


def F1():
    r"""$F_1 = \langle k, u\rangle$; $F_1^2 = \det M$ is the constant term of $p$ (S5:F123). Ring element."""
    return dot(_k, _u)


def F2():
    r"""$F_2 = \lVert k\rVert^2 + \lVert u\rVert^2$, the $\lambda^2$ coefficient of $p$ (S5:F123)."""
    return dot(_k, _k) + dot(_u, _u)


@cache
def F3():
    r"""$F_3 := -[\lambda\sigma]\,p(\lambda,\sigma)$, read off from the determinant (S5:F123, derived):
    ring element in $k, u, q, x$ (any $\gamma$)."""
    lam, sig = sp.symbols("lambda sigma")
    coeff = sp.Poly(charpoly(lam, sig), lam, sig).coeff_monomial(lam * sig)
    return -_to_ring(coeff)


@cache
def energy():
    r"""$(2D)\cdot H$ with $H = \tfrac12\langle M, \Omega\rangle_\kappa = -\tfrac14\operatorname{tr}(M\Omega)$
    (S2.2:energy, $n = 4$) and $\Omega = L_\gamma^{-1}M$ derived; ring element, valid on $S^3$."""
    Nxi, Neta = xi_eta_numerators()
    MO = _mm(block(_k, _u), block(Neta, Nxi))
    return -sum(MO[i][i] for i in range(4)) / 2  # -(1/4) tr(M D Omega) * 2


def integrals():
    r"""The polynomial first integrals of the 4D field as SymPy expressions in $k, u$ (S5:F123,
    derived): ``F1``, ``F2``, ``F3`` ($= -[\lambda\sigma]p$). (The energy is :func:`energy`, over
    $2D$; an ``H`` entry here was read by nothing, so nothing checked it: mutation testing found it.)"""
    return {"F1": F1().as_expr(), "F2": F2().as_expr(), "F3": F3().as_expr()}


@cache
def velocity_form_numerators():
    r"""$D\cdot(\dot\xi, \dot\eta)$ as functions of $(\xi, \eta, q, x)$ on $S^3$ (derives
    eq:Motion-Velocity): from $\dot M = L_\gamma(\dot\Omega) + b(\Omega\dot\gamma)\wedge\gamma +
    b(\Omega\gamma)\wedge\dot\gamma = [M, \Omega]$ with $M = L_\gamma(\Omega)$, $\dot\gamma = -\Omega\gamma$:
    $\dot\Omega = L_\gamma^{-1}\big([M,\Omega] - b(\Omega\dot\gamma)\wedge\gamma - b(\Omega\gamma)\wedge\dot\gamma\big)$."""
    kM, uM = L_blocks(_eta, _xi)
    kd, ud, qd, xd = motion_blocks(kM, uM, _eta, _xi)
    Om = block(_eta, _xi)
    g, gd = [*_q, _x], [*qd, xd]
    W = [[_b * (p + r) for p, r in zip(r1, r2, strict=False)]
         for r1, r2 in zip(_wedge(_mv(Om, gd), g), _wedge(_mv(Om, g), gd), strict=False)]
    wk, wu = unblock(W)
    return inverse_apply(_add(kd, _scale(-1, wk)), _add(ud, _scale(-1, wu)))
