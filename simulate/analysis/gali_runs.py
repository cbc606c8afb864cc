r"""Orbits with deviation vectors: integrate (heyoka batch mode, runtime parameters ``par[i]``, one
compiled integrator per system and number of vectors), sample the observables for NAFF and the
deviation vectors for GALI (:mod:`simulate.analysis.gali`) in the same pass.

:func:`integrate` is the one loop the validation study (:mod:`simulate.analysis.gali_study`) and the
torus rows (:mod:`simulate.analysis.torus_rows`) share: ``system`` any
:class:`simulate.integrators.heyoka_systems.System`, orbit $k$ run to $T\cdot f_k$ and sampled every
$dt\cdot f_k$ (``time_factor`` $f_k$: the energy scale of :mod:`simulate.analysis.draws`), the vectors
read every ``stride`` samples (GALI needs the trend, not every sample), in time chunks of bounded
memory. Orbits share a batch by the measured prediction of their cost
(:func:`simulate.analysis.packing.order`: a short pilot run; the orbits do not change). :func:`extend` continues orbits frequency-only (no deviation vectors) from their last
states: the horizon ladder of :mod:`simulate.analysis.naff_ladder`.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from chaplygin_nd.simulate.analysis import gali as gl
from chaplygin_nd.simulate.analysis import packing
from chaplygin_nd.simulate.integrators.heyoka_systems import System

__all__ = ["integrate", "extend", "BATCH", "TOL", "OPT_LEVEL"]

#: orbits per compiled step (as simulate.analysis.drawn_evidence.BATCH)
BATCH = 8
TOL = 1e-10
#: samples per propagate_grid call (memory: chunk x lanes x state)
CHUNK = 512
#: LLVM optimisation level of the compiled integrators: 1, as the drawn rows
#: (simulate.analysis.drawn_evidence.OPT_LEVEL; the same orbits, a faster compile)
OPT_LEVEL = 1


def integrate(system: System, y0: np.ndarray, pars: np.ndarray, *, K: int, T: float, dt: float,
              seed: int, time_factor: np.ndarray | None = None, n: int | None = None,
              symmetric: bool = True, signals: Callable | None = None, stride: int = 4,
              tol: float = TOL) -> dict:
    r"""Every orbit ``y0[k]`` (``(orbits, d)``, parameters ``pars[:, k]``) of ``system`` with ``K``
    deviation vectors (:func:`simulate.analysis.gali.initial_deviations`, projected transverse to
    the $SO(n-1)$ orbits when ``n`` is given and ``symmetric``, onto $TP$ only when not).
    Returns ``{"gali": [GaliResult], "series": (orbits, samples, K) GALI, "t": sample times at
    scale 1, "signals": (orbits, signals, samples) or None, "final": (orbits, d) the states at
    the last sample}``; ``signals(Y, lanes)`` maps states
    ``(samples, lanes, d)`` to complex ``(lanes, signals, samples)``. Domain: ``K >= 2``."""
    from chaplygin_nd.simulate.integrators.heyoka_taylor import compiled_integrator

    ext = gl.deviation_system(system, K)
    ta, _, _ = compiled_integrator(ext, "double", tol, compact=True, batch=BATCH, opt_level=OPT_LEVEL)
    count, d = y0.shape
    f = np.ones(count) if time_factor is None else np.asarray(time_factor, float)
    u0 = gl.initial_deviations(y0, K, seed, n, symmetric)
    steps = int(round(T / dt))
    t = np.arange(steps + 1) * dt
    keep = np.arange(0, steps + 1, stride)
    series = np.empty((count, len(keep), K))
    final = np.empty((count, d))
    sig = None
    full = np.concatenate([y0, u0.reshape(count, K * d)], axis=1)
    for lanes, used in packing.batches(packing.order(ta, full, pars, T * f), BATCH):
        idx = lanes[:used]
        ta.state[:] = full[lanes].T
        ta.pars[:] = pars[:, lanes]
        ta.set_time(0.0)
        chunks_y, chunks_u = [], []
        for c0 in range(0, steps + 1, CHUNK):
            rows = np.arange(c0, min(c0 + CHUNK, steps + 1))
            # each grid starts at the current time: the previous chunk's last sample, dropped
            first = rows if c0 == 0 else np.concatenate([[c0 - 1], rows])
            grid = t[first][:, None] * f[lanes][None, :]
            _, states = ta.propagate_grid(grid)
            states = states if c0 == 0 else states[1:]
            for lane, res in enumerate(ta.propagate_res[:used]):
                if str(res[0]) != "taylor_outcome.time_limit":
                    raise RuntimeError(f"{system.name}: heyoka stopped early ({res[0]}) on orbit "
                                       f"{idx[lane]}")
            Y = np.moveaxis(states[:, :d, :used], 1, 2)            # (rows, lanes, d)
            chunks_y.append(Y)
            sel = np.isin(rows, keep)
            U = np.moveaxis(states[sel, d:, :used], 1, 2).reshape(sel.sum(), used, K, d)
            chunks_u.append((Y[sel], U))
        Y = np.concatenate(chunks_y)
        final[idx] = Y[-1]
        if signals is not None:
            z = signals(Y, idx)
            if sig is None:
                sig = np.empty((count,) + z.shape[1:], dtype=z.dtype)
            sig[idx] = z
        Yk = np.concatenate([y for y, _ in chunks_u])
        U = np.concatenate([u for _, u in chunks_u])                 # (samples, lanes, K, d)
        if n is not None:
            U = gl.project(U, Yk, n, symmetric)
        series[idx] = np.moveaxis(gl.gali(U), 0, 1)
    tk = t[keep]
    return {"gali": [gl.verdict(tk, series[k]) for k in range(count)], "series": series, "t": tk,
            "signals": sig, "final": final}


def extend(system: System, y: np.ndarray, pars: np.ndarray, *, t0: float, t1: float, dt: float,
           signals: Callable, time_factor: np.ndarray | None = None, tol: float = TOL
           ) -> tuple[np.ndarray, np.ndarray]:
    r"""The orbits of ``system`` (no deviation vectors) from the states ``y`` ``(orbits, d)`` at time
    $t_0$, parameters ``pars[:, k]``, to $t_1$: the signals ``signals(Y, lanes)`` (as
    :func:`integrate`) at $t_0 + dt, \dots, t_1$, times ``time_factor`` $f_k$ for orbit $k$ (the
    field is autonomous: the integration restarts at 0). Returns the signals ``(orbits, signals,
    samples)`` and the states at $t_1$ ``(orbits, d)``."""
    from chaplygin_nd.simulate.integrators.heyoka_taylor import compiled_integrator

    ta, _, _ = compiled_integrator(system, "double", tol, compact=True, batch=BATCH,
                                   opt_level=OPT_LEVEL)
    count, d = y.shape
    f = np.ones(count) if time_factor is None else np.asarray(time_factor, float)
    t = np.arange(int(round((t1 - t0) / dt)) + 1) * dt
    sig, final = None, np.empty_like(y)
    for lanes, used in packing.batches(packing.order(ta, y, pars, (t1 - t0) * f), BATCH):
        idx = lanes[:used]
        ta.state[:] = y[lanes].T
        ta.pars[:] = pars[:, lanes]
        ta.set_time(0.0)
        _, states = ta.propagate_grid(t[:, None] * f[lanes][None, :])
        for lane, res in enumerate(ta.propagate_res[:used]):
            if str(res[0]) != "taylor_outcome.time_limit":
                raise RuntimeError(f"{system.name}: heyoka stopped early ({res[0]}) on orbit "
                                   f"{idx[lane]}")
        Y = np.moveaxis(states[1:, :d, :used], 1, 2)          # (samples, lanes, d)
        final[idx] = Y[-1]
        z = signals(Y, idx)
        if sig is None:
            sig = np.empty((count,) + z.shape[1:], dtype=z.dtype)
        sig[idx] = z
    if sig is None:
        raise ValueError("extend: no orbit to continue")
    return sig, final


def continuation(system: System, final: np.ndarray, pars: np.ndarray, *, dt: float,
                 signals: Callable, time_factor: np.ndarray | None = None, tol: float = TOL
                 ) -> Callable:
    r"""The ``extend(idx, t0, t1)`` of :func:`simulate.analysis.naff_ladder.ladder` for orbits that
    :func:`integrate` ran to $t_0$ (``final``: their states there): each call runs :func:`extend`
    on the orbits ``idx`` from their last states and keeps the new ones; ``signals(Y, orbits)``
    receives the orbits' indices in ``final``."""
    state = np.array(final, float)
    f = np.ones(len(state)) if time_factor is None else np.asarray(time_factor, float)

    def run(idx, t0, t1):
        idx = np.asarray(idx, int)
        z, end = extend(system, state[idx], pars[:, idx], t0=t0, t1=t1, dt=dt,
                        signals=lambda Y, lanes: signals(Y, idx[lanes]), time_factor=f[idx],
                        tol=tol)
        state[idx] = end
        return z

    return run
