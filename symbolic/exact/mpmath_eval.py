r"""High-precision references for the generated kernels: SymPy expressions evaluated in mpmath.

``lambdify(..., "mpmath")`` is not used: it may round float literals to double and leave
rationals as Python floats, so a "50-digit" reference silently runs at 16 digits. Here the
expression tree is walked directly: integers and rationals become exact ``mpf(p)/q`` at the
working precision, a ``Float`` is rejected (derived expressions are exact), and every symbol takes
an ``mpf`` value (a float input converts exactly: ``mpf(float)`` is exact).

:func:`mp_abs_eval` evaluates the same tree with every sum replaced by the sum of the absolute
values of its terms: the componentwise condition scale $\lvert f\rvert_{\mathrm{abs}}$ of the
formula, with which a straight-line float evaluation has error $\le c\,u\,\lvert f\rvert_{\mathrm{abs}}$
($u$ the unit roundoff, $c$ ~ the depth of the expression; Higham, *Accuracy and Stability of
Numerical Algorithms*, 2nd ed., §3.1). The tests state their bounds in units of machine epsilon
times this scale, or times a condition number of the problem where one applies.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import mpmath
import sympy as sp

__all__ = ["mp_eval", "mp_abs_eval", "to_mpf"]

_FUNCS = {sp.sin: mpmath.sin, sp.cos: mpmath.cos, sp.exp: mpmath.exp, sp.sqrt: mpmath.sqrt,
          sp.sinc: lambda z: mpmath.sinc(z), sp.Abs: abs}


def to_mpf(value) -> mpmath.mpf:
    """An exact ``mpf`` from a float, int or SymPy rational (rationals rounded at working precision)."""
    if isinstance(value, sp.Rational):
        return mpmath.mpf(int(value.p)) / int(value.q)
    if isinstance(value, sp.Basic):
        raise TypeError(f"not an exact number: {value!r}")
    return mpmath.mpf(value)


def _walk(expr: sp.Expr, values: Mapping[sp.Symbol, mpmath.mpf], absolute: bool, memo: dict):
    hit = memo.get(expr)
    if hit is not None:
        return hit
    if expr.is_Symbol:
        v = values[expr]
        out = abs(v) if absolute else v
    elif expr.is_Rational:
        out = to_mpf(expr)
        out = abs(out) if absolute else out
    elif expr.is_Float:
        raise TypeError(f"float literal {expr} in a derived expression")
    elif expr.is_Add:
        out = mpmath.fsum(_walk(a, values, absolute, memo) for a in expr.args)
    elif expr.is_Mul:
        out = mpmath.fprod(_walk(a, values, absolute, memo) for a in expr.args)
    elif expr.is_Pow and absolute and expr.exp.is_Integer and expr.exp < 0:
        # |1/d|_abs = |1/d| * (|d|_abs/|d|): the division amplifies the relative error of d.
        true = abs(_walk(expr.base, values, False, {}))
        out = (_walk(expr.base, values, True, memo) / true**2) ** int(-expr.exp)
    elif expr.is_Pow:
        base = _walk(expr.base, values, absolute, memo)
        e = expr.exp
        if e.is_Integer:
            out = base ** int(e)
        elif e.is_Rational:
            out = base ** (mpmath.mpf(int(e.p)) / int(e.q))
        else:
            out = base ** _walk(e, values, absolute, memo)
    elif expr.func in _FUNCS:
        args = [_walk(a, values, False, memo if not absolute else {}) for a in expr.args]
        out = _FUNCS[expr.func](*args)
        out = abs(out) if absolute else out
    else:
        raise TypeError(f"no mpmath rule for {expr.func}")
    memo[expr] = out
    return out


def mp_eval(exprs: Sequence[sp.Expr], values: Mapping[sp.Symbol, object]) -> list[mpmath.mpf]:
    """Each expression at ``values`` (symbol -> float/int/Rational/mpf) in mpmath at the current
    precision, with exact constants."""
    vals = {s: to_mpf(v) if not isinstance(v, mpmath.mpf) else v for s, v in values.items()}
    memo: dict = {}
    return [_walk(sp.sympify(e), vals, False, memo) for e in exprs]


def mp_abs_eval(exprs: Sequence[sp.Expr], values: Mapping[sp.Symbol, object]) -> list[mpmath.mpf]:
    """The absolute-value evaluation $\\lvert f\\rvert_{\\mathrm{abs}}$ of each expression (see the
    module docstring): the condition scale of evaluating that formula in floating point."""
    vals = {s: to_mpf(v) if not isinstance(v, mpmath.mpf) else v for s, v in values.items()}
    memo: dict = {}
    return [_walk(sp.sympify(e), vals, True, memo) for e in exprs]


# ---------------------------------------------------------------------------------------------
# Independent references from the definitions (no derived formula): L_gamma by eq:M-O with
# J = Id + a E_n E_n^T (eq:axisymm), Omega by an mpmath LU solve, block notation of S:4D.
# ---------------------------------------------------------------------------------------------

def mp_pairs(n: int) -> list[tuple[int, int]]:
    """Index pairs i < j (lexicographic): the coordinates ``vec`` of symbolic.algebra."""
    return [(i, j) for i in range(n) for j in range(i + 1, n)]


def mp_unvec(v, n: int) -> mpmath.matrix:
    """The skew n x n mpmath matrix with coordinates ``v``."""
    A = mpmath.zeros(n, n)
    for (i, j), c in zip(mp_pairs(n), v):
        A[i, j], A[j, i] = c, -c
    return A


def mp_vec(A, n: int) -> list:
    """Coordinates A_ij, i < j."""
    return [A[i, j] for i, j in mp_pairs(n)]


def mp_L_matrix(gamma, a, b) -> mpmath.matrix:
    r"""Matrix of $L_\gamma(\Omega) = \mathbb{J}\Omega + \Omega\mathbb{J} + b(\Omega\gamma)\wedge\gamma$,
    $\mathbb{J} = \mathrm{Id} + aE_nE_n^T$ (eq:M-O, eq:axisymm), in the basis $E_i\wedge E_j$; any $\gamma$."""
    n = len(gamma)
    J = [mpmath.mpf(1)] * (n - 1) + [1 + mpmath.mpf(a)]
    pairs = mp_pairs(n)
    L = mpmath.zeros(len(pairs), len(pairs))
    for c in range(len(pairs)):
        Om = mp_unvec([1 if q == c else 0 for q in range(len(pairs))], n)
        Og = [mpmath.fsum(Om[i, k] * gamma[k] for k in range(n)) for i in range(n)]
        for row, (i, j) in enumerate(pairs):
            L[row, c] = (J[i] + J[j]) * Om[i, j] + b * (Og[i] * gamma[j] - gamma[i] * Og[j])
    return L


def mp_Omega(M, gamma, a, b) -> mpmath.matrix:
    r"""$\Omega = L_\gamma^{-1}M$ by an mpmath LU solve of :func:`mp_L_matrix` (``M`` an n x n matrix)."""
    n = len(gamma)
    sol = mpmath.lu_solve(mp_L_matrix(gamma, a, b), mpmath.matrix(mp_vec(M, n)))
    return mp_unvec([sol[i] for i in range(sol.rows)], n)


def mp_block(v, w) -> mpmath.matrix:
    r"""$\begin{pmatrix}\hat v & w\\ -w^T & 0\end{pmatrix}$ (S:4D notation)."""
    return mpmath.matrix([[0, -v[2], v[1], w[0]], [v[2], 0, -v[0], w[1]],
                          [-v[1], v[0], 0, w[2]], [-w[0], -w[1], -w[2], 0]])


def mp_unblock(W) -> tuple[list, list]:
    """$(v, w)$ with ``W`` = :func:`mp_block` (v, w)."""
    return [W[2, 1], W[0, 2], W[1, 0]], [W[0, 3], W[1, 3], W[2, 3]]
