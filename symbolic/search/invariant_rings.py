r"""Invariant rings for the first-integral search in the invariant ring
(symbolic/search/invariant_search.py): generators of the $G$-invariant polynomials on
$P = \mathfrak{so}(n)\times S^{n-1}$ evaluated modulo $p$, and the dimension of each graded piece.

Write $M = \begin{pmatrix} K & u\\ -u^T & 0\end{pmatrix}$, $\gamma = (q, x)$, $x = \gamma_n$. The stabiliser
$G = SO(n-1)$ of $E_n$ (eq:SOnminus1) acts on $(K, u, q)$ and fixes $x$ (eq:action). A ring here is:

* generators $g_1, \dots, g_r$: $G$-invariant polynomials in $(K, u, q)$, each of $M$-degree
  $\deg_M g$ and $q$-degree $\deg_q g$ (integer coefficients);
* ``dimension(d, l)``: $\dim$ of the $G$-invariant polynomials in $(K, u, q)$ of $M$-degree $d$ and
  $q$-degree $l$ — from characters, exactly; the search proves that the generator products of
  that bidegree **span** it by a rank mod $p$ equal to it (rank$_p \le$ rank$_\mathbb{Q} \le$ dim);
* ``reflections``: coordinate reflections $g_k$ that commute with $X$ (diagonal $\mathbb{J}$) and
  normalise $G$; each generator is even or odd under each (read off at a point mod $p$).

Rings: ``trivial`` ($n = 3$, a generic mass tensor: every polynomial; generators the coordinates),
``SO(n-1)`` for $n = 6, 7$ (generators chosen among natural candidates, dimensions from
Weyl's character formula: symbolic/search/orthogonal_invariants.py), ``SO3`` ($n = 4$: the Gram entries of $k, u, q$ and $\delta = \langle q, k\times u\rangle$,
symbolic/reduction/invariants_n4.py), ``SO4`` ($n = 5$: $A_\pm, B, G, E_\pm, S_{uu}, S_{uq}, S_{qq}, s$
of symbolic/reduction/invariants_n5.py, row S6:reduced-n5, taken as $A_+ \pm A_-$, $E_+ \pm E_-$ so
that every generator is even or odd under the reflection $g_1$).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cache
from math import comb

import numpy as np
from chaplygin_nd.symbolic.search.weights import symmetric_power, tensor_product

__all__ = ["Ring", "ring_for", "phase_arrays"]


@dataclass(frozen=True)
class Ring:
    """An invariant ring (module docstring): ``values(z, p)`` -> (points, generators) mod p."""

    name: str
    n: int
    group: str
    names: tuple[str, ...]
    m_degree: tuple[int, ...]
    q_degree: tuple[int, ...]
    values: Callable[[np.ndarray, int], np.ndarray]   # (z, p) -> int64 (points, generators)
    dimension: Callable[[int, int], int]               # (d, l) -> dim I_{d,l}
    reflections: tuple[int, ...]   # coordinate indices k of the reflections g_k (0-based)

    def __post_init__(self):
        # g_k = diag(1, .., -1_k, .., 1) exists only for 0 <= k < n; reflect() would read any
        # other index as the identity, and the split by characters would silently lose a sign
        if len(set(self.reflections)) != len(self.reflections) or not all(
                0 <= k < self.n for k in self.reflections):
            raise ValueError(f"ring {self.name}: reflections {self.reflections} are not distinct "
                             f"coordinate indices 0..{self.n - 1}")
        if not len(self.names) == len(self.m_degree) == len(self.q_degree):
            raise ValueError(f"ring {self.name}: {len(self.names)} generators but "
                             f"{len(self.m_degree)} M-degrees and {len(self.q_degree)} q-degrees")


def phase_arrays(z: np.ndarray, n: int, p: int):
    """(M, gamma) mod p as arrays (points, n, n) and (points, n) from the rows
    $z = ((M_{ij})_{i<j}, \\gamma)$ of symbolic/search/sampled_field.py."""
    R = z.shape[0]
    M = np.zeros((R, n, n), dtype=np.int64)
    c = 0
    for i in range(n):
        for j in range(i + 1, n):
            M[:, i, j], M[:, j, i] = z[:, c] % p, (-z[:, c]) % p
            c += 1
    return M, z[:, c:] % p


def _dot(v, w, p):
    return np.einsum("ri,ri->r", v % p, w % p) % p


def _mv(A, v, p):
    return np.einsum("rij,rj->ri", A % p, v % p) % p


# --------------------------------------------------------------------------- n = 3, no symmetry
def _trivial_values(z, p):
    return np.asarray(z[:, :-1], dtype=np.int64) % p


def _trivial(n: int) -> Ring:
    dim_m, dim_q = n * (n - 1) // 2, n - 1
    names = tuple(f"M_{i + 1}{j + 1}" for i in range(n) for j in range(i + 1, n)) + \
        tuple(f"gamma_{i + 1}" for i in range(n - 1))
    return Ring("trivial", n, "{1}", names, (1,) * dim_m + (0,) * dim_q, (0,) * dim_m + (1,) * dim_q,
                _trivial_values,
                lambda d, l: comb(d + dim_m - 1, dim_m - 1) * comb(l + dim_q - 1, dim_q - 1),
                tuple(range(n)))


# --------------------------------------------------------------------------- n = 4, SO(3)
def _so3_values(z, p):
    M, g = phase_arrays(z, 4, p)
    k = np.stack([M[:, 1, 2], M[:, 2, 0], M[:, 0, 1]], axis=1)
    u, q = M[:, :3, 3], g[:, :3]
    cross = np.stack([k[:, 1] * u[:, 2] - k[:, 2] * u[:, 1], k[:, 2] * u[:, 0] - k[:, 0] * u[:, 2],
                      k[:, 0] * u[:, 1] - k[:, 1] * u[:, 0]], axis=1) % p
    return np.stack([_dot(k, k, p), _dot(u, u, p), _dot(k, u, p), _dot(k, q, p), _dot(u, q, p),
                     _dot(q, q, p), _dot(q, cross, p)], axis=1)


@cache
def _so3_dimension(d: int, l: int) -> int:
    r"""$SU(2)$ characters (doubled weights $-2, 0, 2$ on $\mathbb{R}^3$ for $k$, $u$, $q$): the trivial
    multiplicity of $S^i\otimes S^j\otimes S^l$ is $c_0 - c_2$, summed over $i + j = d$."""
    V = ((2,), (0,), (-2,))
    out = 0
    for i in range(d + 1):
        ch = tensor_product(tensor_product(symmetric_power(V, i), symmetric_power(V, d - i)), symmetric_power(V, l))
        out += ch[(0,)] - ch[(2,)]
    return out


# --------------------------------------------------------------------------- n = 5, SO(4)
_HODGE = ((0, 1, 2, 3, 1), (0, 2, 1, 3, -1), (0, 3, 1, 2, 1), (1, 2, 0, 3, 1), (1, 3, 0, 2, -1),
          (2, 3, 0, 1, 1))


def _so4_values(z, p):
    """$A_+ \\pm A_-, B, G, E_+ \\pm E_-, S_{uu}, S_{uq}, S_{qq}, s$ mod p (invariants_n5's generators)."""
    M, g = phase_arrays(z, 5, p)
    K, u, q = M[:, :4, :4], M[:, :4, 4], g[:, :4]
    S = np.zeros_like(K)
    for i, j, k, l, sign in _HODGE:
        S[:, i, j] = sign * K[:, k, l] % p
        S[:, j, i] = (-S[:, i, j]) % p
    Kp, Km = (K + S) % p, (K - S) % p
    kp = np.stack([K[:, 0, 1] + K[:, 2, 3], K[:, 0, 2] - K[:, 1, 3], K[:, 0, 3] + K[:, 1, 2]], 1) % p
    km = np.stack([K[:, 0, 1] - K[:, 2, 3], K[:, 0, 2] + K[:, 1, 3], K[:, 0, 3] - K[:, 1, 2]], 1) % p
    Ap, Am = _dot(kp, kp, p), _dot(km, km, p)
    Ep, Em = _dot(u, _mv(Kp, q, p), p), _dot(u, _mv(Km, q, p), p)
    Su, Sq = _mv(Kp, _mv(Km, u, p), p), _mv(Kp, _mv(Km, q, p), p)
    return np.stack([(Ap + Am) % p, (Ap - Am) % p, _dot(u, u, p), _dot(u, q, p), (Ep + Em) % p,
                     (Ep - Em) % p, _dot(u, Su, p), _dot(u, Sq, p), _dot(q, Sq, p), _dot(q, q, p)], 1)


@cache
def _so4_dimension(d: int, l: int) -> int:
    from chaplygin_nd.symbolic.reduction.invariants_n5 import invariant_dimension

    return sum(invariant_dimension(i, d - i, l) for i in range(d + 1))


@cache
def ring_for(n: int, kind: str) -> Ring:
    """The ring the search uses for the model (n, kind): ``general`` (no symmetry) -> trivial;
    ``axisymmetric`` n = 4 -> SO(3), n = 5 -> SO(4). Other n: ValueError (no derived generators)."""
    if kind == "general":
        return _trivial(n)
    if n == 4:
        return Ring("SO3", 4, "SO(3)", ("A", "B", "F1", "E", "G", "s", "delta"),
                    (2, 2, 2, 1, 1, 0, 2), (0, 0, 0, 1, 1, 2, 1), _so3_values, _so3_dimension, (0, 3))
    if n == 5:
        return Ring("SO4", 5, "SO(4)", ("Ap+Am", "Ap-Am", "B", "G", "Ep+Em", "Ep-Em", "Suu", "Suq",
                                        "Sqq", "s"),
                    (2, 2, 2, 1, 2, 2, 4, 3, 2, 0), (0, 0, 0, 1, 1, 1, 0, 1, 2, 2), _so4_values,
                    _so4_dimension, (0, 4))
    if 6 <= n <= MAX_N:
        return _orthogonal(n)
    raise ValueError(f"no invariant generators derived for the axisymmetric n = {n} "
                     f"(the invariant-ring search covers n = 4..{MAX_N}; use the weight-zero search)")


#: the largest n with a ring (candidates with m! terms each; n = 8 would have 5040)
MAX_N = 7
#: the bidegrees the generators of n >= 6 are searched to (boxes beyond them are refused)
ORTHOGONAL_BOUNDS = (6, 6)


def _orthogonal(n: int) -> Ring:
    """SO(n-1) for n >= 6: generators chosen among the candidates of
    symbolic/search/orthogonal_invariants.py up to :data:`ORTHOGONAL_BOUNDS`."""
    from chaplygin_nd.symbolic.search import backend
    from chaplygin_nd.symbolic.search import orthogonal_invariants as oi

    m = n - 1
    gens = oi.generators(m, *ORTHOGONAL_BOUNDS, backend.PRIMES[2])

    def values(z, p):
        M, g = phase_arrays(z, n, p)
        return oi.evaluate(list(gens), M[:, :m, :m], M[:, :m, m], g[:, :m], p)

    return Ring(f"SO{m}", n, f"SO({m})", tuple(c.name for c in gens), tuple(c.m_degree for c in gens),
                tuple(c.q_degree for c in gens), values, lambda d, l: oi.dimension(m, d, l), (0, n - 1))


def products(ring: Ring, d: int, l: int) -> list[tuple[int, ...]]:
    """Exponent vectors of the generator products of M-degree d and q-degree l."""
    from chaplygin_nd.symbolic.search.orthogonal_invariants import products_of

    return products_of(ring.m_degree, ring.q_degree, d, l)


def reflect(z: np.ndarray, n: int, mask: int, p: int) -> np.ndarray:
    """The points g.z for the product g of the reflections g_k with bit k of ``mask`` set."""
    s = np.array([-1 if mask >> i & 1 else 1 for i in range(n)])
    real = np.array([s[i] * s[j] for i in range(n) for j in range(i + 1, n)] + list(s))
    return z * real[None, :] % p


__all__ += ["products", "reflect"]
