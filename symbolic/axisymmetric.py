r"""The axisymmetric sphere (Section 4): mass tensor, $L_\gamma$, the block $C$, $\Delta$, $\det L_\gamma$.

Everything here is *derived* from the definitions of Section 2 (:mod:`symbolic.model`):

.. math::
    \mathbb{J} = \mathrm{Id}_n + a E_n E_n^T \ \text{(eq:axisymm)}, \qquad
    \mathbb{I}(\Omega) = \mathbb{J}\Omega + \Omega\mathbb{J}, \qquad
    L_\gamma(\Omega) = \mathbb{I}(\Omega) + b(\Omega\gamma)\wedge\gamma \ \text{(eq:M-O)}.

Adapted frame (used in P:Measure). For $\gamma \in S^{n-1}$ not parallel to $E_n$ and
$w \perp \gamma, E_n$, the operator $L_\gamma$ maps the plane $\operatorname{span}\{E_n\wedge w,
\gamma\wedge w\}$ to itself, with matrix $C$ (columns = images); it multiplies $E_n \wedge\gamma$
by a scalar $c_0$ and $w_i\wedge w_j$ by a scalar $c_2$. All three are *computed* here by applying
$L_\gamma$ to a concrete frame in $\mathbb{R}^4$ (:func:`frame_coefficients`), never copied from
the paper. $\Delta := \det C$ and $\det L_\gamma = c_0\, c_2^{(n-2)(n-3)/2}\,\Delta^{n-2}$.

$\Omega = L_\gamma^{-1}(M)$ in closed form lives in :mod:`symbolic.axisym_inverse`.
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp
from chaplygin_nd.symbolic.algebra import basis_vector, wedge
from chaplygin_nd.symbolic.model import L_gamma, L_matrix, inertia_operator

__all__ = [
    "a", "b", "x", "E_n", "mass_tensor", "inertia_axisym", "L_gamma_axisym", "L_matrix_axisym",
    "frame_coefficients", "block_C", "Delta", "det_L_axisym",
]

#: The parameters of eq:axisymm / eq:M-O and $x = \langle\gamma, E_n\rangle$, as SymPy symbols.
a, b, x = sp.symbols("a b x", real=True)


def E_n(n: int) -> sp.Matrix:
    r"""The symmetry axis $E_n = (0, \dots, 0, 1)^T \in \mathbb{R}^n$ (eq:axisymm)."""
    return basis_vector(n, n - 1)


def mass_tensor(n: int, a=a) -> sp.Matrix:
    r"""$\mathbb{J} = \mathrm{Id}_n + a E_n E_n^T$ (eq:axisymm); any $n \ge 2$, any $a$."""
    e = E_n(n)
    return sp.eye(n) + a * e * e.T


def inertia_axisym(Omega: sp.Matrix, a=a) -> sp.Matrix:
    r"""$\mathbb{I}(\Omega) = \mathbb{J}\Omega + \Omega\mathbb{J}$ with $\mathbb{J}$ of eq:axisymm
    (definition eq:Inertia, not the simplified form printed in eq:M-O-axi-symm); $\Omega \in \mathfrak{so}(n)$."""
    return inertia_operator(Omega, mass_tensor(Omega.rows, a))


def L_gamma_axisym(Omega: sp.Matrix, gamma: sp.Matrix, a=a, b=b) -> sp.Matrix:
    r"""$M = L_\gamma(\Omega) = \mathbb{J}\Omega + \Omega\mathbb{J} + b(\Omega\gamma)\wedge\gamma$,
    $\mathbb{J}$ of eq:axisymm (eq:M-O, the object of eq:M-O-axi-symm); any $\gamma \in \mathbb{R}^n$."""
    return L_gamma(Omega, gamma, mass_tensor(Omega.rows, a), b)


def L_matrix_axisym(gamma: sp.Matrix, a=a, b=b) -> sp.Matrix:
    r"""Matrix of $L_\gamma$ (eq:M-O with eq:axisymm) in the basis $E_i \wedge E_j$ of $\mathfrak{so}(n)$."""
    return L_matrix(gamma, mass_tensor(gamma.rows, a), b)


def _coords_in(target: sp.Matrix, spanning: list[sp.Matrix], reduce_rule: dict) -> list[sp.Expr]:
    """Coefficients c with target = sum c_k spanning_k (exact linear solve on the entries)."""
    cs = sp.symbols(f"c0:{len(spanning)}")
    eqs = [sp.expand((target - sum((c * S for c, S in zip(cs, spanning, strict=True)), sp.zeros(*target.shape)))[i])
           for i in range(len(target))]
    eqs = [sp.expand(e.subs(reduce_rule)) for e in eqs]
    sol = sp.solve([e for e in eqs if e != 0], cs, dict=True)
    if len(sol) != 1 or set(sol[0]) != set(cs):
        raise ArithmeticError("image not in the expected span")
    return [sp.factor(sol[0][c].subs(reduce_rule)) for c in cs]


@lru_cache(maxsize=1)
def frame_coefficients() -> dict[str, sp.Expr]:
    r"""Images of the adapted basis under $L_\gamma$ (P:Measure), computed in $\mathbb{R}^4$ with
    $E = E_4$, $\gamma = (0, 0, s, x)$, $s^2 = 1 - x^2$, $s \neq 0$, $w_1 = E_1$, $w_2 = E_2$.

    Returns ``C`` (2x2, columns are the coordinates of $L_\gamma(E_n\wedge w)$ and
    $L_\gamma(\gamma\wedge w)$ in $(E_n\wedge w, \gamma\wedge w)$), ``c0`` ($L_\gamma(E_n\wedge\gamma)
    = c_0\,E_n\wedge\gamma$) and ``c2`` ($L_\gamma(w_1\wedge w_2) = c_2\, w_1\wedge w_2$), as
    polynomials in $a, b, x$. The frame is general: any $(\gamma, E_n, w_i, w_j)$ is carried to it
    by an isometry fixing $E_n$ (see proofs/s4_measure.py for the argument)."""
    s = sp.Symbol("s", positive=True)
    rule = {s**2: 1 - x**2}
    e = E_n(4)
    g = sp.Matrix([0, 0, s, x])
    w1, w2 = basis_vector(4, 0), basis_vector(4, 1)
    L = lambda Om: L_gamma_axisym(Om, g, a, b).applyfunc(lambda t: sp.expand(t).subs(rule))  # noqa: E731
    Ew, gw = wedge(e, w1), wedge(g, w1)
    col1 = _coords_in(L(Ew), [Ew, gw], rule)
    col2 = _coords_in(L(gw), [Ew, gw], rule)
    (c0,) = _coords_in(L(wedge(e, g)), [wedge(e, g)], rule)
    (c2,) = _coords_in(L(wedge(w1, w2)), [wedge(w1, w2)], rule)
    C = sp.Matrix([[col1[0], col2[0]], [col1[1], col2[1]]])
    return {"C": C, "c0": c0, "c2": c2}


def block_C(x=x, a=a, b=b) -> sp.Matrix:
    r"""The $2\times 2$ block $C$ of $L_\gamma$ on $\operatorname{span}\{E_n\wedge w, \gamma\wedge w\}$
    (P:Measure), columns = images; $x = \langle\gamma, E_n\rangle \in [-1, 1]$."""
    C = frame_coefficients()["C"]
    return C.subs({sp.Symbol("x", real=True): x, sp.Symbol("a", real=True): a,
                   sp.Symbol("b", real=True): b}, simultaneous=True)


def Delta(x=x, a=a, b=b) -> sp.Expr:
    r"""$\Delta(x) := \det C$ (eq:Delta), derived as the determinant of the block of :func:`block_C`.
    Polynomial in $a, b, x$; positive for $x^2 \le 1$, $b > 0$, $a > -2$ (see proofs/s4_delta.py).

    At rational $(x, a, b)$ (the seeded points of the searches and point checks) the value is
    the same determinant, expanded once in $\mathbb{Q}[x, a, b]$ (:func:`_delta_polynomial`) and
    evaluated there exactly, instead of a substitution into the matrix and a determinant per call."""
    args = (x, a, b)
    if all(isinstance(v, (int, sp.Rational)) for v in args):
        R, poly = _delta_polynomial()
        conv = R.domain.from_sympy
        return R.domain.to_sympy(poly(*(conv(sp.Rational(v)) for v in args)))
    return _delta_expr(*args)


@lru_cache(maxsize=64)
def _delta_expr(x, a, b) -> sp.Expr:
    """``expand(det(block_C(x, a, b)))`` for symbolic arguments (SymPy expressions are immutable,
    so a repeated call returns the same expression)."""
    return sp.expand(block_C(x, a, b).det())


@lru_cache(maxsize=1)
def _delta_polynomial():
    r"""$\det C$ of :func:`block_C` (at the symbols $x, a, b$) as a sparse polynomial of
    $\mathbb{Q}[x, a, b]$ (through :func:`block_C`, as the symbolic route goes)."""
    R = sp.ring([x, a, b], sp.QQ)[0]
    return R, R(sp.expand(block_C().det()))


def det_L_axisym(n: int, x=x, a=a, b=b) -> sp.Expr:
    r"""$\det L_\gamma = c_0\, c_2^{(n-2)(n-3)/2}\, \Delta(x)^{n-2}$ assembled from the derived block
    form (P:Measure); $n \ge 2$, $\gamma \in S^{n-1}$ with $\langle\gamma, E_n\rangle = x$."""
    fc = frame_coefficients()
    sub = {sp.Symbol("x", real=True): x, sp.Symbol("a", real=True): a,
           sp.Symbol("b", real=True): b}
    c0 = fc["c0"].subs(sub, simultaneous=True)
    c2 = fc["c2"].subs(sub, simultaneous=True)
    return c0 * c2 ** ((n - 2) * (n - 3) // 2) * Delta(x, a, b) ** (n - 2)
