r"""The linear-algebra back end of the exact searches: dense matrices over $\mathbb{F}_p$.

A search (symbolic/search/box_search.py) asks four things of a matrix $A \in \mathbb{F}_p^{r\times c}$
(entries ``numpy.int64`` in $[0, p)$, $p < 2^{31}$): its rank, a basis of its right null space
$\{x : Ax = 0\}$ (the rows of the answer), its reduced row echelon form (canonical, so that those
of several primes are the reductions of the rational one) and a product $AB$. That is the
protocol :class:`Backend`; FLINT ``nmod_mat`` is the default (``"flint"``).

**Adding a back end is one file.** A module ``symbolic/search/backend_<name>.py`` that defines a
class with the four methods and calls :func:`register` at import; :func:`get` imports it by name
on first use (``backend="<name>"`` of any search). Nothing else switches on back-end names.

The elementwise mod-$p$ tools every search uses (:func:`inv_mod`, :func:`sqrt_minus_one`) and the
lifting from residues to rationals (:func:`crt`, :func:`ratrecon`) live here too.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from typing import Protocol

import flint
import numpy as np
import sympy as sp

__all__ = ["PRIMES", "Backend", "FlintBackend", "register", "get", "names", "inv_mod", "sqrt_minus_one",
           "crt", "ratrecon"]

#: Primes p = 1 mod 4 below 2^28 (a square root of -1 exists; products of two residues fit in
#: int64 with room for sums of 2^7 of them).
PRIMES = (268435361, 268435337, 268435313, 268435273, 268435157)


class Backend(Protocol):
    """Dense linear algebra over $\\mathbb{F}_p$ on ``int64`` arrays with entries in $[0, p)$."""

    name: str

    def rank(self, A: np.ndarray, p: int) -> int:
        """$\\mathrm{rank}_p A$."""

    def nullspace(self, A: np.ndarray, p: int) -> np.ndarray:
        """A basis of $\\{x : Ax = 0\\}$ over $\\mathbb{F}_p$, as the rows of a (nullity, cols) array."""

    def rref(self, A: np.ndarray, p: int) -> np.ndarray:
        """The reduced row echelon form of $A$ without its zero rows (canonical)."""

    def matmul(self, A: np.ndarray, B: np.ndarray, p: int) -> np.ndarray:
        """$AB \\bmod p$."""


def _nmod(A: np.ndarray, p: int) -> flint.nmod_mat:
    A = np.asarray(A, dtype=np.int64)
    return flint.nmod_mat(A.shape[0], A.shape[1], A.ravel().tolist(), p)


def _array(X: flint.nmod_mat, rows: int | None = None, cols: int | None = None) -> np.ndarray:
    out = np.array(X.tolist(), dtype=np.int64).reshape(X.nrows(), X.ncols())
    return out[:rows, :cols]


class FlintBackend:
    """FLINT ``nmod_mat`` (python-flint): the default back end."""

    name = "flint"

    def rank(self, A, p):
        """$\\mathrm{rank}_p A$ (``nmod_mat.rank``)."""
        if 0 in np.shape(A):
            return 0
        return _nmod(A, p).rank()

    def nullspace(self, A, p):
        """Rows: a basis of the right null space (``nmod_mat.nullspace``)."""
        cols = np.shape(A)[1]
        if np.shape(A)[0] == 0:
            return np.eye(cols, dtype=np.int64)
        X, nullity = _nmod(A, p).nullspace()
        return _array(X, cols=nullity).T.copy()

    def rref(self, A, p):
        """The non-zero rows of the RREF (``nmod_mat.rref``)."""
        if 0 in np.shape(A):
            return np.zeros((0, np.shape(A)[1]), np.int64)
        R, rank = _nmod(A, p).rref()
        return _array(R, rows=rank)

    def matmul(self, A, B, p):
        """$AB \\bmod p$ (``nmod_mat`` product)."""
        return _array(_nmod(A, p) * _nmod(B, p))


_REGISTRY: dict[str, Callable[[], Backend]] = {"flint": FlintBackend}


def register(name: str, factory: Callable[[], Backend]) -> None:
    """Make ``factory`` (a class or a function returning a :class:`Backend`) the back end ``name``."""
    _REGISTRY[name] = factory


def get(name: str | Backend = "flint") -> Backend:
    """The back end ``name`` (imports ``symbolic/search/backend_<name>.py`` on first use), or
    ``name`` itself when it already is one. Unknown name: ValueError naming the known ones."""
    if not isinstance(name, str):
        return name
    if name not in _REGISTRY:
        try:
            importlib.import_module(f"{__package__}.backend_{name}")
        except ModuleNotFoundError:
            pass
    if name not in _REGISTRY:
        raise ValueError(f"unknown linear-algebra back end {name!r} (known: {', '.join(names())})")
    return _REGISTRY[name]()


def names() -> list[str]:
    """The registered back ends."""
    return sorted(_REGISTRY)


def inv_mod(x: np.ndarray, p: int) -> np.ndarray:
    """Elementwise inverse mod p (Fermat); zero maps to zero."""
    x = np.asarray(x, dtype=np.int64) % p
    out = np.ones_like(x)
    base, e = x.copy(), p - 2
    while e:
        if e & 1:
            out = out * base % p
        base = base * base % p
        e >>= 1
    return out


def sqrt_minus_one(p: int) -> int:
    """A square root of $-1$ modulo a prime $p \\equiv 1 \\bmod 4$."""
    for c in range(2, 200):
        r = pow(c, (p - 1) // 4, p)
        if r * r % p == p - 1:
            return r
    raise ArithmeticError(f"no square root of -1 mod {p}")


def ratrecon(a: int, m: int):
    """Rational reconstruction of a mod m with |num|, den <= sqrt(m/2); None if none."""
    bound = int((m // 2) ** 0.5)
    r0, r1, s0, s1 = m, a % m, 0, 1
    while r1 > bound:
        q = r0 // r1
        r0, r1, s0, s1 = r1, r0 - q * r1, s1, s0 - q * s1
    if s1 == 0 or abs(s1) > bound:
        return None
    return sp.Rational(r1, s1) if s1 > 0 else sp.Rational(-r1, -s1)


def crt(res, mods) -> int:
    """The x mod prod(mods) with x = res[i] mod mods[i] (Chinese remainder theorem)."""
    x, m = 0, 1
    for r, q in zip(res, mods):
        t = ((r - x) * pow(m, -1, q)) % q
        x, m = x + m * t, m * q
    return x
