r"""The Lie algebra $\mathfrak{so}(n)$ as the paper uses it (Section 2).

* wedge: $u \wedge v = u v^T - v u^T$ (footnote to eq:M-O);
* hat map $\hat{}: \mathbb{R}^3 \to \mathfrak{so}(3)$, $\hat u v = u \times v$ (Section 4, eq:xiV3D);
* commutator $[A, B] = AB - BA$ (eq:motion-general);
* Killing metric $\langle A, B\rangle_\kappa = -\tfrac12 \operatorname{tr}(AB)$ (S2.2:energy);
* the basis $e_{ij} = E_i \wedge E_j$ ($i < j$) of $\mathfrak{so}(n)$, orthonormal for
  $\langle\cdot,\cdot\rangle_\kappa$, and the coordinates ``vec``/``unvec`` in that basis.

Every function works on SymPy matrices with any entries (symbols or exact rationals).
"""

from __future__ import annotations

from collections.abc import Sequence

import sympy as sp

__all__ = [
    "wedge", "hat", "unhat", "commutator", "killing", "so_basis", "so_dim", "vec", "unvec",
    "skew_symbols", "vector_symbols", "column", "basis_vector",
]


def column(entries: Sequence) -> sp.Matrix:
    """A column vector (SymPy ``Matrix`` of shape (n, 1)) from a sequence of entries."""
    return sp.Matrix(list(entries))


def basis_vector(n: int, i: int) -> sp.Matrix:
    r"""$E_{i+1} \in \mathbb{R}^n$ (0-based ``i``); ``basis_vector(n, n - 1)`` is $E_n$ (eq:axisymm)."""
    if not 0 <= i < n:
        raise ValueError(f"index {i} outside 0..{n - 1}")
    e = sp.zeros(n, 1)
    e[i] = 1
    return e


def wedge(u: sp.Matrix, v: sp.Matrix) -> sp.Matrix:
    r"""$u \wedge v = u v^T - v u^T \in \mathfrak{so}(n)$ (footnote to eq:M-O); any $u, v \in \mathbb{R}^n$."""
    return u * v.T - v * u.T


def hat(w: Sequence) -> sp.Matrix:
    r"""The hat map $\mathbb{R}^3 \to \mathfrak{so}(3)$ with $\hat w v = w \times v$ (eq:xiV3D)."""
    w1, w2, w3 = list(w)
    return sp.Matrix([[0, -w3, w2], [w3, 0, -w1], [-w2, w1, 0]])


def unhat(W: sp.Matrix) -> sp.Matrix:
    r"""Inverse of :func:`hat` on $\mathfrak{so}(3)$: the vector $w$ with $\hat w = W$."""
    if W.shape != (3, 3):
        raise ValueError(f"unhat needs a 3x3 matrix, got {W.shape}")
    return sp.Matrix([W[2, 1], W[0, 2], W[1, 0]])


def commutator(A: sp.Matrix, B: sp.Matrix) -> sp.Matrix:
    r"""$[A, B] = AB - BA$ (eq:motion-general)."""
    return A * B - B * A


def killing(A: sp.Matrix, B: sp.Matrix) -> sp.Expr:
    r"""Killing metric $\langle A, B\rangle_\kappa = -\tfrac12 \operatorname{tr}(AB)$ on $\mathfrak{so}(n)$
    (Section 2.2, S2.2:energy). For skew $A, B$ it equals $\sum_{i<j} A_{ij} B_{ij}$."""
    return -sp.Rational(1, 2) * (A * B).trace()


def so_dim(n: int) -> int:
    r"""$\dim \mathfrak{so}(n) = n(n-1)/2$."""
    return n * (n - 1) // 2


def _pairs(n: int) -> list[tuple[int, int]]:
    return [(i, j) for i in range(n) for j in range(i + 1, n)]


def so_basis(n: int) -> list[sp.Matrix]:
    r"""The basis $E_i \wedge E_j$, $i < j$ (lexicographic), of $\mathfrak{so}(n)$; orthonormal for
    the Killing metric. Coordinates in it are the upper-triangular entries (:func:`vec`)."""
    return [wedge(basis_vector(n, i), basis_vector(n, j)) for i, j in _pairs(n)]


def vec(A: sp.Matrix) -> sp.Matrix:
    r"""Coordinates of $A \in \mathfrak{so}(n)$ in :func:`so_basis`: the entries $A_{ij}$, $i<j$."""
    n = A.shape[0]
    return sp.Matrix([A[i, j] for i, j in _pairs(n)])


def unvec(coords: Sequence, n: int) -> sp.Matrix:
    r"""The element of $\mathfrak{so}(n)$ with coordinates ``coords`` in :func:`so_basis`."""
    coords = list(coords)
    if len(coords) != so_dim(n):
        raise ValueError(f"so({n}) has dimension {so_dim(n)}, got {len(coords)} coordinates")
    A = sp.zeros(n, n)
    for (i, j), c in zip(_pairs(n), coords):
        A[i, j] = c
        A[j, i] = -c
    return A


def skew_symbols(name: str, n: int) -> sp.Matrix:
    r"""A generic element of $\mathfrak{so}(n)$ with real symbols ``{name}{i}{j}`` ($1 \le i < j \le n$)
    above the diagonal. For $n \ge 10$ the indices are separated by an underscore."""
    sep = "_" if n >= 10 else ""
    coords = [sp.Symbol(f"{name}{i + 1}{sep}{j + 1}", real=True) for i, j in _pairs(n)]
    return unvec(coords, n)


def vector_symbols(name: str, n: int) -> sp.Matrix:
    r"""A generic column vector of $\mathbb{R}^n$ with real symbols ``{name}1 .. {name}n``."""
    return column(sp.symbols(f"{name}1:{n + 1}", real=True))
