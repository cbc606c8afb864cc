r"""The shape of every exact search: a base that owns the box loop, the exact sandwich and the
lifting to $\mathbb{Q}$; strategies say what is searched.

A search looks for the linear space $V$ of solutions of a linear condition (here: $X(F) = 0$ for
$F = P/D^k$, a first integral) in a finite-dimensional **box** of candidates, one box at a time.
A strategy (a subclass of :class:`BoxSearch`) overrides

* :meth:`BoxSearch.prepare` — the **ansatz**: the unknowns of the box, split into blocks that the
  condition does not mix (``blocks``: label -> number of unknowns), and whatever the other hooks
  need (the returned context object);
* :meth:`BoxSearch.condition_matrices` — the **linear conditions**: per block, a matrix over
  $\mathbb{F}_p$ whose rows every element of $V$ (reduced mod $p$) satisfies;
* :meth:`BoxSearch.known_values` and :meth:`BoxSearch.basis_values` — the **known solutions**:
  values of the known elements of the box at points, and of the block's unknowns at the same
  points (the recovery check puts a kernel basis there);
* :meth:`BoxSearch.unknown_counts` — the block sizes without building anything (for the cost
  estimate before a run).

The base keeps for itself (do not override): the loop over boxes (:meth:`BoxSearch.run`), the
**exact sandwich** per block,
$\mathrm{rank}_p(\text{known}) \le \dim_\mathbb{Q} K \le \dim_\mathbb{Q} V \le \mathrm{nullity}_p(A)$ —
the left inequality because the known values are reductions of rational ones, the right one
because a basis of the saturated lattice $V \cap \mathbb{Z}^N$ stays independent mod $p$ and
satisfies every row (the strategy's docstring gives that argument for its conditions) — so equal
ends settle the box exactly (:attr:`DegreeResult.settled`); the **recovery check** (the known
elements lie in the $\mathbb{F}_p$ kernel: a search that misses a known solution fails); and the
**lifting** of a kernel from several primes to $\mathbb{Q}$ (:meth:`BoxSearch.rational_kernel`:
canonical RREF per prime, CRT, rational reconstruction, one more prime to check). The linear
algebra goes through one back end (symbolic/search/backend.py; FLINT by default).

The degree $\to$ box rule (:func:`box_for`) is written here once; the command line and the API use it.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np
from chaplygin_nd.symbolic.search import backend as backends

__all__ = ["BoxSearch", "BlockResult", "DegreeResult", "box_for", "MARGIN", "RECOVERY_MAX",
           "PRIMES"]

#: rows beyond the number of unknowns of a block (more rows never add solutions, only conditions)
MARGIN = 24
#: blocks up to this size also get an explicit F_p kernel and the recovery check
RECOVERY_MAX = 1200
PRIMES = backends.PRIMES


def box_for(d: int, k: int = 1, d_gamma: int | None = None) -> tuple[int, int, int]:
    r"""The box searched at $M$-degree $d$ over $D^k$: $(d, d_\gamma, k)$ with $d_\gamma = d + 2k$
    unless given (the $\gamma$-degree that $P/D^k$ needs when $P$ is a product of known integrals
    of $\gamma$-degree at most their $M$-degree, times $D^k$ of $\gamma$-degree $2k$)."""
    if d < 1 or k < 0 or (d_gamma is not None and d_gamma < 0):
        raise ValueError("need d >= 1, k >= 0, d_gamma >= 0")
    return (d, d + 2 * k if d_gamma is None else d_gamma, k)


@dataclass
class BlockResult:
    character: int
    unknowns: int
    nullity: int
    known_rank: int
    recovered: bool | None      # None: not checked (block too large)


@dataclass
class DegreeResult:
    n: int
    kind: str
    d: int
    d_gamma: int
    k: int
    prime: int
    unknowns: int
    found: int                  # sum of nullities: >= dim of the integrals (equal when settled)
    known: int                  # sum of known ranks: <= dim of the span of the known products
    products: int
    settled: bool               # found == known: no integral beyond the known algebra
    recovered: bool | None
    seconds: float = field(compare=False)  # a time taken: no part of the result's value
    blocks: list[BlockResult] = field(default_factory=list)

    def as_dict(self) -> dict:
        return asdict(self)


class BoxSearch:
    """Base of the exact searches (module docstring). ``model``: what is searched (for the
    integral searches a symbolic/search/sampled_field.Model); ``backend``: a back-end name or
    object; ``include_new``: count the integrals found by the search among the known ones."""

    @property
    def invariance(self) -> str:
        """The invariance class the strategy searches, as said in a statement."""
        return "none (every polynomial of the box)"

    def __init__(self, model, *, backend: str | Any = "flint", prime_index: int = 0, seed: int = 0,
                 include_new: bool = True):
        self.model = model
        self.backend = backends.get(backend)
        self.prime_index = prime_index
        self.seed = seed
        self.include_new = include_new

    # ------------------------------------------------------------ what a strategy overrides
    def prepare(self, box: tuple, p: int) -> Any:
        """The ansatz of ``box`` mod ``p``: a context with ``blocks`` (dict label -> unknowns)."""
        raise NotImplementedError

    def condition_matrices(self, ctx) -> dict:
        """Per block label: the conditions (rows) over F_p; may be consumed (popped) by the base."""
        raise NotImplementedError

    def known_values(self, ctx, label) -> np.ndarray:
        """Values (points x known elements) of the known elements of the box in block ``label``."""
        raise NotImplementedError

    def known_count(self, ctx) -> int:
        """The number of known elements (products) placed in the box."""
        raise NotImplementedError

    def basis_values(self, ctx, label) -> np.ndarray:
        """Values (points x unknowns) of the block's unknowns at the points of :meth:`known_values`."""
        raise NotImplementedError

    def unknown_counts(self, box: tuple) -> list[int]:
        """The block sizes of ``box``, cheaply (no field, no points)."""
        raise NotImplementedError

    # ------------------------------------------------------------ what the base owns
    @property
    def prime(self) -> int:
        """The prime of this search (``PRIMES[prime_index]``)."""
        return PRIMES[self.prime_index]

    def run_box(self, box: tuple, progress: Callable[[str], None] | None = None) -> DegreeResult:
        """The sandwich of every block of ``box`` = (d, d_gamma, k) at one prime (module docstring)."""
        d, d_gamma, k = box
        if d < 1 or d_gamma < 0 or k < 0:
            raise ValueError("need d >= 1, d_gamma >= 0, k >= 0")
        t0 = time.perf_counter()
        p, la = self.prime, self.backend
        ctx = self.prepare(box, p)
        mats = self.condition_matrices(ctx)
        results = []
        for label, cols in ctx.blocks.items():
            A = mats.pop(label)
            K = self.known_values(ctx, label)
            known = la.rank(K, p) if K.shape[1] else 0
            recovered = None
            if cols <= RECOVERY_MAX:
                N = la.nullspace(A, p)
                del A
                nullity = len(N)
                if nullity and K.shape[1]:
                    F = la.matmul(self.basis_values(ctx, label), N.T, p)
                    recovered = la.rank(np.concatenate([F, K], axis=1), p) == nullity
                else:
                    recovered = known == 0
            else:
                nullity = cols - la.rank(A, p)
                del A
            results.append(BlockResult(label, cols, nullity, known, recovered))
            if progress:
                progress(f"n={self.model.n} d={d} d_gamma={d_gamma} k={k}: block "
                         f"{self.block_name(label)} {cols} unknowns, nullity {nullity}, "
                         f"known rank {known}")
        found = sum(r.nullity for r in results)
        kn = sum(r.known_rank for r in results)
        checked = [r.recovered for r in results if r.recovered is not None]
        return DegreeResult(self.model.n, self.model.kind, d, d_gamma, k, p,
                            sum(ctx.blocks.values()), found, kn, self.known_count(ctx), found == kn,
                            all(checked) if checked else None,
                            round(time.perf_counter() - t0, 3), results)

    def block_name(self, label) -> str:
        """How progress lines name a block."""
        return f"chi={label:#x}" if isinstance(label, int) else str(label)

    def run(self, boxes: Iterable[tuple], progress=None) -> list[DegreeResult]:
        """:meth:`run_box` over ``boxes``."""
        return [self.run_box(tuple(b), progress) for b in boxes]

    def known_ranks(self, box: tuple) -> dict:
        """Per block: the rank mod p of the known elements of ``box`` (a lower bound of the
        dimension of their span), without the conditions."""
        ctx = self.prepare(box, self.prime)
        return {label: (self.backend.rank(K, self.prime) if (K := self.known_values(ctx, label)).shape[1]
                        else 0) for label in ctx.blocks}

    def kernel_rref(self, A: np.ndarray, p: int) -> np.ndarray:
        """The canonical basis (RREF rows) of the kernel of ``A`` over F_p."""
        N = self.backend.nullspace(A, p)
        return self.backend.rref(N, p) if len(N) else N

    def rational_kernel(self, kernel_at: Callable[[int], np.ndarray], primes: int = 4) -> list:
        """The rational RREF of a kernel from its RREF mod ``primes`` primes (``kernel_at(index)``;
        the last prime checks): CRT and rational reconstruction; ArithmeticError when the primes
        disagree or need more."""
        mats = [kernel_at(i) for i in range(primes)]
        if len({m.shape for m in mats}) != 1:
            raise ArithmeticError("the kernel dimension differs between primes")
        ps = [PRIMES[i] for i in range(primes)]
        modulus = 1
        for q in ps[:-1]:
            modulus *= q
        out = []
        for r in range(mats[0].shape[0]):
            row = []
            for j in range(mats[0].shape[1]):
                v = backends.crt([int(m[r, j]) for m in mats[:-1]], ps[:-1])
                q = backends.ratrecon(v, modulus)
                if q is None:
                    raise ArithmeticError("rational reconstruction failed: more primes needed")
                if (q.p * pow(q.q, -1, ps[-1]) - int(mats[-1][r, j])) % ps[-1]:
                    raise ArithmeticError("the check prime disagrees: more primes needed")
                row.append(q)
            out.append(row)
        return out
