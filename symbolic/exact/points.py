r"""Seeded exact rational sample points (the random half of the identity engine).

Every generator is a :class:`random.Random` seeded from an explicit integer seed *and* a tuple
of labels through SHA-256, so that a check's points depend only on ``(seed, labels)``, never on
``hash()`` (randomised per process) or on the order checks run in.

Points on the unit sphere $S^{n-1}$ are exact: the inverse stereographic projection
$t \in \mathbb{Q}^{n-1} \mapsto \big(2t, \lVert t\rVert^2 - 1\big)/(\lVert t\rVert^2 + 1)$
maps rational points to rational points of $S^{n-1}$ (every rational point but the pole arises).
"""

from __future__ import annotations

import hashlib
import random
from collections.abc import Sequence

import flint
import sympy as sp
from chaplygin_nd.symbolic.algebra import column, unvec
from chaplygin_nd.symbolic.exact.flint_engine import to_fmpq, to_sympy_matrix

__all__ = [
    "DEFAULT_SEED", "ledger_seed", "set_ledger_seed", "generator", "rational", "rationals", "sphere_point", "skew_matrix",
    "rational_rotation", "axisymmetric_parameters", "ALL_N_MAX", "all_n", "SPARSE_LARGE_N", "n_text",
]

#: The largest n of the seeded exact point checks of the rows about every n (DESIGN.md, "All n,
#: honestly"); above ``symbolic.exact.identity.SYMPY_POINT_MAX_N`` FLINT alone decides them.
ALL_N_MAX = 24


#: Above n = 12 the all-n rows sample these n (exact points cost ~n^4..n^6 even in FLINT:
#: bench/out/exact_growth.md); ``chaplygin bench exact_growth`` measures every n up to ALL_N_MAX.
SPARSE_LARGE_N = (16, 20, 24)


def all_n(start: int = 3, top: int | None = None) -> tuple[int, ...]:
    """The n of the seeded exact point checks of an all-n row: every n from ``start`` to 12, then
    :data:`SPARSE_LARGE_N` up to ``top`` (default ALL_N_MAX)."""
    top = ALL_N_MAX if top is None else min(top, ALL_N_MAX)
    return tuple(range(start, min(12, top) + 1)) + tuple(
        n for n in SPARSE_LARGE_N if start <= n <= top)


def n_text(ns) -> str:
    """``(3, 4, 5, 6, 16, 20)`` -> ``"3..6, 16, 20"`` (runs of consecutive n shortened)."""
    ns = sorted(set(ns))
    runs: list[list[int]] = []
    out: list[str] = []
    for n in ns:
        if runs and n == runs[-1][-1] + 1:
            runs[-1].append(n)
        else:
            runs.append([n])
    for r in runs:
        out.append(f"{r[0]}..{r[-1]}" if len(r) > 2 else ", ".join(map(str, r)))
    return ", ".join(out)

#: The seed of a ledger run unless ``chaplygin verify --seed N`` (``make verify SEED=N``) names another.
DEFAULT_SEED = 20261121
_ledger_seed = DEFAULT_SEED


def ledger_seed() -> int:
    """The seed of the ledger run in this process: every seeded check that names no seed of its
    own draws its points from it. The runner sets it in each worker before each row
    (:func:`set_ledger_seed`), so it is an explicit parameter of a run, recorded in its report."""
    return _ledger_seed


def set_ledger_seed(seed: int) -> int:
    """Make ``seed`` the seed of the ledger checks in this process; returns the previous one."""
    global _ledger_seed
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise ValueError(f"a ledger seed is a non-negative integer, not {seed!r}")
    previous, _ledger_seed = _ledger_seed, seed
    return previous


def generator(seed: int, *labels: object) -> random.Random:
    """A ``random.Random`` determined by ``seed`` and ``labels`` (stable across processes)."""
    digest = hashlib.sha256(repr((int(seed),) + tuple(str(x) for x in labels)).encode()).digest()
    return random.Random(int.from_bytes(digest[:16], "big"))


def rational(rng: random.Random, lo: sp.Rational | int = -3, hi: sp.Rational | int = 3,
             max_den: int = 12, *, nonzero: bool = False,
             open_lo: bool = False, open_hi: bool = False) -> sp.Rational:
    """A random rational ``p/q`` with ``1 <= q <= max_den`` in ``[lo, hi]`` (ends excluded on request)."""
    lo, hi = sp.Rational(lo), sp.Rational(hi)
    if lo > hi:
        raise ValueError(f"empty interval [{lo}, {hi}]")
    for _ in range(10_000):
        q = rng.randint(1, max_den)
        # ceil(lo q) and floor(hi q) in integer arithmetic (SymPy's ceiling/floor build function
        # objects: they were most of the cost of drawing a point)
        p = rng.randint(-((-lo.p * q) // lo.q), (hi.p * q) // hi.q)
        r = sp.Rational(p, q)
        if (nonzero and r == 0) or (open_lo and r == lo) or (open_hi and r == hi):
            continue
        return r
    raise ValueError(f"no admissible rational in [{lo}, {hi}] with denominator <= {max_den}")


def rationals(rng: random.Random, count: int, lo=-3, hi=3, max_den: int = 12) -> list[sp.Rational]:
    """``count`` independent draws of :func:`rational`."""
    return [rational(rng, lo, hi, max_den) for _ in range(count)]


def sphere_point(rng: random.Random, n: int, max_den: int = 6) -> sp.Matrix:
    r"""An exact rational point of $S^{n-1} \subset \mathbb{R}^n$ (column vector), by inverse
    stereographic projection of a random $t \in \mathbb{Q}^{n-1}$. The last coordinate is
    $(\lVert t\rVert^2-1)/(\lVert t\rVert^2+1)$, so it takes every rational value in $(-1, 1]$ in turn."""
    if n < 2:
        raise ValueError("the sphere S^{n-1} needs n >= 2")
    t = rationals(rng, n - 1, -2, 2, max_den)
    s = sum(ti**2 for ti in t)
    gamma = column([2 * ti / (s + 1) for ti in t] + [(s - 1) / (s + 1)])
    # Randomise which coordinate plays the role of the pole, so no coordinate is special.
    perm = list(range(n))
    rng.shuffle(perm)
    return column([gamma[p] for p in perm])


def skew_matrix(rng: random.Random, n: int, lo=-3, hi=3, max_den: int = 12) -> sp.Matrix:
    r"""A random exact element of $\mathfrak{so}(n)$."""
    return unvec(rationals(rng, n * (n - 1) // 2, lo, hi, max_den), n)


def rational_rotation(rng: random.Random, n: int) -> sp.Matrix:
    r"""A random exact rotation $h \in SO(n)$ with rational entries: the Cayley transform
    $h = (I - S)^{-1}(I + S)$ of a random skew $S$ (always invertible, $\det h = 1$)."""
    S = skew_matrix(rng, n, -2, 2, 4)
    eye = sp.eye(n)
    # the exact solve by FLINT's fmpq_mat (the same rationals as SymPy's LUsolve, ~50x faster at
    # n = 23); a sample point, not a verdict, so one engine suffices here
    def mat(A):
        return flint.fmpq_mat(A.rows, A.cols, [to_fmpq(v) for v in A])

    return to_sympy_matrix(mat(eye - S).solve(mat(eye + S)))


def axisymmetric_parameters(rng: random.Random, *, a_zero: bool = False) -> dict[str, sp.Rational]:
    r"""Physical parameters of the axisymmetric sphere (eq:axisymm): $a \in [-1, 1]$ and $b > 0$."""
    a = sp.Integer(0) if a_zero else rational(rng, -1, 1, 8)
    b = rational(rng, 0, 4, 8, open_lo=True)
    return {"a": a, "b": b}


def pick(rng: random.Random, options: Sequence):
    """One element of ``options`` (re-exported so callers need only this module)."""
    return options[rng.randrange(len(options))]
