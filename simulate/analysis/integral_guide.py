r"""A numerical guide for the exact first-integral search on the $n = 5$ reduced space.

Not a verdict. On drawn $n = 5$ orbits of one $(a, b)$, integrated in the reduced coordinates
$r = (x, A_\pm, B, G, E_\pm, S_{uu}, S_{uq}, S_{qq})$ (row S6:reduced-n5, ``generated.reduced5``),
find the combinations of a basis of functions that stay constant along every orbit:

.. math::
    \phi_{m,e}(r) = m(r)\,x^e/\Delta(x)^J,\qquad m \text{ a monomial of } M\text{-degree } k,\ e \le E,

($M$-degrees: $G$ 1; $A_\pm, B, E_\pm, S_{qq}$ 2; $S_{uq}$ 3; $S_{uu}$ 4). The field raises the
$M$-degree by one, so each $M$-homogeneous part of an integral is an integral: one $k$ at a time.
With the samples of every orbit centred on the orbit's mean and each column scaled to unit norm,
the right singular vectors of the stacked matrix with singular values below the noise floor span
the orbit-constant combinations. Two kinds are expected and subtracted, both measured the same way
at random points of the reduced space (invariants of random phase points):

* functions that vanish on the reduced space (multiples of the relations $R_1, R_2$): the null
  space of the basis at random points;
* products of the known integrals (``reduced5_integrals``: $c_{\lambda^3}, c_{\lambda^1}, c_{\sigma\lambda^2}$,
  $H$, and $L$ with $L^2 = c_{\sigma\lambda^0}$, $L = (E_+ - E_-)/2 - x(A_+ - A_-)/4$) of $M$-degree $k$ with at
  most $J$ factors $H$: the dimension of the intersection of their span with the basis span
  (rank$\,\Phi$ + rank$\,\Psi$ - rank$[\Phi\,\Psi]$).

``excess`` = (orbit null dimension - relation dimension) - known dimension: a positive excess
suggests an integral beyond the known ones in that space.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np
from chaplygin_nd.simulate.kernels import reduced5

__all__ = ["WEIGHTS", "basis", "orbits", "guide", "GuideRow"]

NAMES = ("x", "Ap", "Am", "B", "G", "Ep", "Em", "Suu", "Suq", "Sqq")
#: $M$-degree of each coordinate after $x$.
WEIGHTS = {"Ap": 2, "Am": 2, "B": 2, "G": 1, "Ep": 2, "Em": 2, "Suu": 4, "Suq": 3, "Sqq": 2}


def monomials(k: int) -> list[dict]:
    """Exponent dicts of the monomials of $M$-degree ``k`` in the coordinates after $x$."""
    names = list(WEIGHTS)
    out = []

    def rec(i, left, cur):
        if i == len(names):
            if left == 0:
                out.append(dict(cur))
            return
        w = WEIGHTS[names[i]]
        for e in range(left // w + 1):
            rec(i + 1, left - e * w, {**cur, names[i]: e} if e else cur)
    rec(0, k, {})
    return out


def basis(R: np.ndarray, k: int, E: int, J: int, a: float, b: float) -> np.ndarray:
    r"""The columns $\phi_{m,e}(r)$ (module docstring) at the rows of ``R`` ``(samples, 10)``."""
    col = {n: R[:, i] for i, n in enumerate(NAMES)}
    x = col["x"]
    Dl = ((2 + a) * (2 + b) - a * b * x * x) ** J
    cols = []
    for mon in monomials(k):
        v = np.ones(len(R))
        for n, e in mon.items():
            v = v * col[n] ** e
        for e in range(E + 1):
            cols.append(v * x**e / Dl)
    return np.array(cols).T


def known_products(R: np.ndarray, k: int, J: int, a: float, b: float) -> np.ndarray:
    """Products of the known integrals of $M$-degree ``k`` with at most ``J`` factors $H$."""
    F = reduced5().reduced5_integrals(R, a, b)
    x, Ap, Am, Ep, Em = R[:, 0], R[:, 1], R[:, 2], R[:, 5], R[:, 6]
    L = (Ep - Em) / 2 - x * (Ap - Am) / 4
    known = [(F[:, 0], 2, 0), (F[:, 1], 4, 0), (F[:, 2], 2, 0), (L, 2, 0), (F[:, 4], 2, 1)]
    cols = []
    for r_ in range(1, k // 2 + 1):
        for combo in itertools.combinations_with_replacement(range(len(known)), r_):
            if sum(known[i][1] for i in combo) != k or sum(known[i][2] for i in combo) > J:
                continue
            v = np.ones(len(R))
            for i in combo:
                v = v * known[i][0]
            cols.append(v)
    return np.array(cols).T if cols else np.zeros((len(R), 0))


def orbits(a: float, b: float, count: int, seed: int, T: float = 600.0, dt: float = 0.25):
    """Reduced orbits of ``count`` drawn generic $n = 5$ points at one $(a, b)$ (heyoka, tol 1e-15):
    list of arrays ``(samples, 10)``, and random points of the reduced space ``(4000, 10)``."""
    from chaplygin_nd.simulate.analysis import draws
    from chaplygin_nd.simulate.integrators import heyoka_systems, heyoka_taylor

    ens = draws.draw(f"integral-guide a={a} b={b}", "generic", 5, count, seed, a_values=(a,),
                     b_values=(b,))
    iu = np.triu_indices(5, 1)
    ta, _, _ = heyoka_taylor.compiled_integrator(heyoka_systems.reduced5(), "double", 1e-15)
    out = []
    for k in range(count):
        r0 = reduced5().reduced5_invariants(ens.M0[k][iu], ens.gamma0[k])
        ta.state[:] = r0
        ta.pars[:] = [a, b]
        ta.time = 0.0
        grid = np.arange(int(T / dt) + 1) * dt / ens.scale[k]
        out.append(ta.propagate_grid(grid)[-1].copy())
    rng = np.random.default_rng(seed)
    M = rng.normal(size=(4000, 5, 5))
    M = M - np.swapaxes(M, 1, 2)
    g = rng.normal(size=(4000, 5))
    g /= np.linalg.norm(g, axis=1)[:, None]
    return out, reduced5().reduced5_invariants(M[:, iu[0], iu[1]], g)


def _svals(A: np.ndarray) -> np.ndarray:
    A = A / np.maximum(np.linalg.norm(A, axis=0), 1e-300)
    return np.linalg.svd(A, compute_uv=False)


def _rank(s: np.ndarray, floor: float) -> int:
    return int(np.sum(s > floor * s[0])) if len(s) else 0


@dataclass
class GuideRow:
    """One basis space: $(k, E, J)$, its size, the orbit null dimension and the expected parts."""

    k: int
    E: int
    J: int
    size: int
    orbit_null: int
    relations: int
    known: int
    excess: int
    last_kept: float      # smallest singular value above the floor (orbit matrix)
    first_null: float     # largest singular value below the floor


def guide(orbs, random_pts, a, b, spaces, floor: float = 1e-9) -> list[GuideRow]:
    """The table of the module docstring for each ``(k, E, J)`` of ``spaces``; singular values
    relative to the largest, ``floor`` the noise floor."""
    rows = []
    for k, E, J in spaces:
        blocks = []
        for R in orbs:
            Bk = basis(R, k, E, J, a, b)
            blocks.append(Bk - Bk.mean(axis=0))
        s = _svals(np.vstack(blocks))
        size = len(s)
        null = size - _rank(s, floor)
        Phi = basis(random_pts, k, E, J, a, b)
        sp_ = _svals(Phi)
        rel = size - _rank(sp_, floor)
        Psi = known_products(random_pts, k, J, a, b)
        known = 0
        if Psi.shape[1]:
            known = (_rank(sp_, floor) + _rank(_svals(Psi), floor)
                     - _rank(_svals(np.hstack([Phi, Psi])), floor))
        rel_s = s / s[0]
        kept = rel_s[rel_s > floor]
        below = rel_s[rel_s <= floor]
        rows.append(GuideRow(k, E, J, size, null, rel, known, null - rel - known,
                             float(kept[-1]) if len(kept) else float("nan"),
                             float(below[0]) if len(below) else float("nan")))
    return rows
