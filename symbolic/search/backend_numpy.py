r"""A second linear-algebra back end: Gauss–Jordan elimination mod $p$ in NumPy (``"numpy"``).

Plain row reduction over $\mathbb{F}_p$ on ``int64`` rows (a product of two residues $< 2^{62}$ for
$p < 2^{31}$); $O(rc\min(r, c))$ NumPy operations, so for small boxes only (a reference that shares
no code with FLINT: the same box gives the same nullity and rank by both, tests/test_search_shape.py).
It is the whole of what a back end needs (symbolic/search/backend.py): this one file, which
registers itself on import; ``backend="numpy"`` in a search selects it.
"""

from __future__ import annotations

import numpy as np
from chaplygin_nd.symbolic.search import backend

__all__ = ["NumpyBackend"]


def _rref(A: np.ndarray, p: int) -> tuple[np.ndarray, list[int]]:
    R = np.asarray(A, dtype=np.int64) % p
    R = R.copy()
    rows, cols = R.shape
    pivots: list[int] = []
    r = 0
    for c in range(cols):
        if r == rows:
            break
        nz = np.flatnonzero(R[r:, c])
        if not len(nz):
            continue
        k = r + int(nz[0])
        if k != r:
            R[[r, k]] = R[[k, r]]
        R[r] = R[r] * pow(int(R[r, c]), p - 2, p) % p
        f = R[:, c].copy()
        f[r] = 0
        R = (R - f[:, None] * R[r][None, :] % p) % p
        pivots.append(c)
        r += 1
    return R[:r], pivots


class NumpyBackend:
    """Gauss–Jordan mod p in NumPy (small matrices)."""

    name = "numpy"

    def rank(self, A, p):
        """The number of pivots of the Gauss–Jordan form."""
        return len(_rref(A, p)[1]) if A.size else 0

    def rref(self, A, p):
        """The Gauss–Jordan form without its zero rows."""
        return _rref(A, p)[0]

    def nullspace(self, A, p):
        """One kernel vector per free column, read off the Gauss–Jordan form."""
        cols = A.shape[1]
        R, piv = _rref(A, p) if A.size else (np.zeros((0, cols), np.int64), [])
        free = [c for c in range(cols) if c not in set(piv)]
        out = np.zeros((len(free), cols), dtype=np.int64)
        for t, f in enumerate(free):
            out[t, f] = 1
            for i, c in enumerate(piv):
                out[t, c] = (-R[i, f]) % p
        return out

    def matmul(self, A, B, p):
        """$AB \\bmod p$ with Python integers (no overflow)."""
        prod = np.asarray(A, dtype=object) @ np.asarray(B, dtype=object)
        return (prod % p).astype(np.int64)


backend.register("numpy", NumpyBackend)
