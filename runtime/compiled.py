r"""Compiled batch evaluation of derived formulas (heyoka ``cfunc``, LLVM, SIMD): $L_\gamma^{-1}$ first.

The same expression graph the Taylor integrator compiles — $\Omega = L_\gamma^{-1}M$ assembled by
:mod:`runtime.expressions` from the derived coefficients of P:inversion (generated builders) — is
compiled by ``heyoka.cfunc`` into a vectorised function of the points, with $a, b$ as runtime
parameters. Compiled functions are cached on disk like the integrators (:mod:`runtime.jit_cache`).
Requires heyoka (extra ``fast``); the NumPy kernels of ``generated/`` stay the pure, SymPy-free path.

Layouts. :func:`angular_velocity_columns` is the fast interface: component-major ``(d + n, N)``
inputs (rows: $\mathrm{vec}\,M$ in the basis order $(i, j)$, $i<j$, then $\gamma$), output
``(d, N)``, $d = n(n-1)/2$ — the layout heyoka reads without copying. :func:`angular_velocity` takes
and returns matrices ``(..., n, n)`` like :func:`runtime.axisym.angular_velocity` (at the cost of the
transposes).
"""

from __future__ import annotations

import hashlib

import numpy as np
from chaplygin_nd.runtime import expressions as rx
from chaplygin_nd.runtime import jit_cache

__all__ = ["angular_velocity_function", "angular_velocity_columns", "angular_velocity"]


def angular_velocity_function(n: int, cache: bool = True):
    r"""``(cfunc, seconds, how)``: the compiled $\mathrm{vec}\,L_\gamma^{-1}M$ for this $n$ (P:inversion),
    variables $(\mathrm{vec}\,M, \gamma)$, parameters $(a, b)$; ``how``: cold compile / warm load / in
    memory, ``seconds`` of that. A warm call is a dictionary lookup (the graph is built and hashed
    only when it must be compiled, :mod:`runtime.jit_cache`)."""
    hit = jit_cache.memory_hit(("cfunc angular_velocity", n, cache))
    if hit is not None:
        return hit, 0.0, "in memory"
    import heyoka as hy

    key = {"object": "cfunc", "function": f"angular_velocity n={n}", "precision": "double",
           "heyoka": hy.__version__}
    graph: list = []

    def outputs_and_variables():
        if not graph:
            ops = rx.HeyokaArithmetic(hy, "double", 53)
            pairs = rx.pairs(n)
            m = [hy.expression(f"M{i + 1}_{j + 1}") for i, j in pairs]
            gamma = [hy.expression(f"gamma{i + 1}") for i in range(n)]
            Omega = rx.angular_velocity(rx.unvec(m, n), gamma, hy.par[0], hy.par[1], ops)
            outputs = [Omega[i][j] if not isinstance(Omega[i][j], int) else hy.expression(0.0)
                       for i, j in pairs]
            graph.extend([outputs, m + gamma])
        return graph

    def source() -> str:
        return hashlib.sha256("\n".join(map(str, outputs_and_variables()[0])).encode()).hexdigest()

    return jit_cache.load_or_build(
        key, lambda: hy.cfunc(*outputs_and_variables()), use_disk=cache, source=source,
        expect=(hy.cfunc_dbl,) if hasattr(hy, "cfunc_dbl") else (),
        token=("cfunc angular_velocity", n, cache))


def angular_velocity_columns(inputs: np.ndarray, a, b, out: np.ndarray | None = None,
                             pars: np.ndarray | None = None) -> np.ndarray:
    r"""$\mathrm{vec}\,\Omega$ ``(d, N)`` from contiguous component-major ``inputs`` ``(d + n, N)``
    (P:inversion; domain $\gamma \in S^{n-1}$, $\Delta(x)(2+a+b) \ne 0$). ``a, b`` scalars or ``(N,)``
    arrays; ``pars``, a ``(2, N)`` buffer to fill with them (avoids an allocation); ``out`` a
    ``(d, N)`` buffer."""
    rows, count = inputs.shape
    n = int(round((np.sqrt(8 * rows + 1) - 1) / 2))  # d + n = n(n+1)/2
    if n * (n + 1) // 2 != rows:
        raise ValueError(f"{rows} input rows is not n(n+1)/2 for any n")
    fn, _, _ = angular_velocity_function(n)
    if pars is None:
        pars = np.empty((2, count))
    pars[0] = a
    pars[1] = b
    if out is None:
        out = np.empty((n * (n - 1) // 2, count))
    fn(inputs, pars=pars, outputs=out)
    return out


def angular_velocity(M, gamma, a, b) -> np.ndarray:
    r"""$\Omega = L_\gamma^{-1}(M)$ (P:inversion) for matrices ``(..., n, n)`` and ``gamma`` ``(..., n)``,
    every leading axis broadcast (as :func:`runtime.axisym.angular_velocity`). Domain:
    $\gamma \in S^{n-1}$, $\Delta(x)(2+a+b) \ne 0$."""
    M, gamma = np.asarray(M, dtype=float), np.asarray(gamma, dtype=float)
    n = gamma.shape[-1]
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    batch = np.broadcast_shapes(M.shape[:-2], gamma.shape[:-1], a.shape, b.shape)
    i, j = np.triu_indices(n, 1)
    cols = np.concatenate([np.broadcast_to(M, batch + (n, n))[..., i, j],
                           np.broadcast_to(gamma, batch + (n,))], axis=-1).reshape(-1, len(i) + n)
    count = cols.shape[0]
    out = angular_velocity_columns(np.ascontiguousarray(cols.T), np.broadcast_to(a, batch).ravel(),
                                   np.broadcast_to(b, batch).ravel())
    Omega = np.zeros((count, n, n))
    Omega[:, i, j] = out.T
    Omega[:, j, i] = -out.T
    return Omega.reshape(batch + (n, n))
