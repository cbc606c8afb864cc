r"""The linear conditions of a first-integral search, as values at sampled points mod $p$.

For a monomial $m = \prod_j c_j^{e_j}$ in coordinate functions $c_j$ (the torus coordinates of
symbolic/search/candidate_basis.py, or the invariant generators of
symbolic/search/invariant_search.py) and a point $z$ where no $c_j$ vanishes,

.. math::  X(m)(z) - k\,m(z)\,\frac{X(D)}{D}(z) = m(z)\Big(\sum_j e_j \frac{\dot c_j}{c_j}(z) - k\,\frac{X(D)}{D}(z)\Big),

$\dot c_j = dc_j(X)$: the entry (point, monomial) of the condition $X(P/D^k) = 0$ times $D^k$
(symbolic/search/integral_search.py). Search and reconstruction both build their rows here.
"""

from __future__ import annotations

import numpy as np
from chaplygin_nd.symbolic.search import backend

__all__ = ["coordinate_values", "monomial_values", "block_apply", "admissible", "condition_values"]


def coordinate_values(co, z: np.ndarray, p: int, i_p: int) -> np.ndarray:
    """Values (points x coordinates) mod p of the Gaussian-integer linear forms ``co.re + i co.im``
    of candidate_basis.Coordinates at the real points ``z``, with $i \\mapsto$ ``i_p``."""
    return (z % p) @ ((co.re + i_p * co.im) % p).T % p


def monomial_values(E: np.ndarray, cv: np.ndarray, p: int) -> np.ndarray:
    """Values (points x monomials) of the monomials with exponent rows E at coordinate values cv."""
    out = np.ones((cv.shape[0], E.shape[0]), dtype=np.int64)
    for j in range(E.shape[1]):
        top = int(E[:, j].max()) if len(E) else 0
        if top == 0:
            continue
        pw = np.ones((cv.shape[0], top + 1), dtype=np.int64)
        for e in range(1, top + 1):
            pw[:, e] = pw[:, e - 1] * cv[:, j] % p
        out = out * pw[:, E[:, j]] % p
    return out


def block_apply(Y: np.ndarray, blk, p: int) -> np.ndarray:
    """Columns of a block from monomial columns: sum of sign * Y[:, monomial] per column
    (candidate_basis.Block)."""
    order = np.argsort(blk.column, kind="stable")
    cols = blk.column[order]
    starts = np.flatnonzero(np.r_[True, cols[1:] != cols[:-1]])
    signed = Y[:, blk.monomial[order]] * blk.sign[order][None, :] % p
    return np.add.reduceat(signed, starts, axis=1) % p


def admissible(cv: np.ndarray, cd: np.ndarray, dlog: np.ndarray, rows: int):
    """The first ``rows`` points where no coordinate vanishes (the log-derivative needs them):
    (cv, cd, dlog) cut to those; ArithmeticError when there are fewer."""
    good = (cv != 0).all(axis=1)
    cv, cd, dlog = cv[good][:rows], cd[good][:rows], dlog[good][:rows]
    if len(cv) < rows:
        raise ArithmeticError("too few admissible points")
    return cv, cd, dlog


def condition_values(E: np.ndarray, cv: np.ndarray, cd: np.ndarray, dlog: np.ndarray, k: int,
                     p: int) -> np.ndarray:
    r"""The entries (points x monomials of ``E``) of the module docstring: coordinate values
    ``cv``, their derivatives along $X$ ``cd``, $X(D)/D$ ``dlog``, the power $k$ of $D$."""
    ratio = cd * backend.inv_mod(cv, p) % p
    lin = (ratio @ E.T - k * dlog[:, None]) % p
    return monomial_values(E, cv, p) * lin % p
