r"""Which orbits share a batch of heyoka's SIMD mode: packed by a measured prediction of their cost.

A compiled batch integrator advances ``width`` lanes together, one Taylor step of each lane per
call, until the slowest lane has reached its end: a batch costs ``width`` $\times \max_k s_k$ lane-steps
($s_k$ the Taylor steps of orbit $k$), and the fraction of useful work is
$\sum_k s_k / \sum_{\text{batches}} \text{width}\cdot\max s_k$. Steps vary two- to threefold between the
orbits of one draw, mostly through $a$ and the energy scale, but also from orbit to orbit at the same
$(a, b, s)$; so a sort by the parameters leaves much of the batch waiting (measured, cold runs of the
evidence rows: 0.58–0.84 useful). :func:`order` measures instead: a *pilot* integrates every orbit
over ``PILOT`` $= 1/32$ of its own horizon with the same compiled integrator, counts its steps, and
the orbits are integrated in decreasing order of that count, ``width`` at a time (consecutive blocks
of a sorted list minimise $\sum \max$ over blocks of equal size). The pilot's steps are paid on top
(about $1/32$ of the run, itself batched in the parameter order).

**The orbits do not change.** Each lane is integrated independently (its own step sizes; a step's
size depends only on that lane's state), the integrator's state, parameters and time are set in
full before every batch, and results are written back to the orbits' places: the order only
decides which orbits wait for which (bit-identical results, tests/test_packing.py).

Measured side by side (:mod:`bench.bench_packing`, 2 shared cores at load 8–11, CPU of the
integration with the pilot): useful fraction 0.52–0.79 in the parameter order, 0.70–0.85 packed
(the oracle, packed by the real steps, 0.77–0.97); CPU 1–16 % less on five of the seven ensembles,
the same on the 24-orbit control, and 14 % more, within the noise at that load, on the 16 orbits of
n = 6 (two batches, the same fraction). Width 16, packed: 14–16 % less CPU than 8 on the ensembles
of 100 and 200 orbits, from 3 % less to 18 % more on those of 16–50; width 4: 22–50 % more. A width
per ensemble size would compile a second integrator per system (a cold compile per row), so the
width stays 8.
"""

from __future__ import annotations

import numpy as np

__all__ = ["PILOT", "order", "pilot_steps", "efficiency", "batches"]

#: the pilot's horizon as a fraction of each orbit's own. Lane-steps saved by packing net of the
#: pilot's, as fractions of the parameter order's, at 1/64 / 1/32 / 1/16 (bench packing's sweep):
#: the 200 orbits of S5:reconstruction -0.6 / 3.0 / 4.0 % (pilot-to-run correlation of the steps
#: 0.92 / 0.96 / 0.98), n = 5 (100 orbits) 7.6 / 7.2 / 7.4 %, the reduced field (50) 12.3 / 13.1 /
#: 13.5 %, V at n = 7 (50) 14.0 / 13.5 / 11.0 %: 1/32 is within 1 % of the best on each
PILOT = 1.0 / 32.0


def batches(index: np.ndarray, width: int):
    """``(lanes, used)`` for consecutive blocks of ``index``: the ``width`` orbit indices of a
    batch (the last orbit repeated to fill a short block: a repeated lane costs nothing extra,
    it takes the same steps as the orbit it copies) and how many of them are real."""
    index = np.asarray(index, int)
    for start in range(0, len(index), width):
        block = index[start:start + width]
        used = len(block)
        yield np.concatenate([block, np.repeat(block[-1:], width - used)]), used


def pilot_steps(ta, states: np.ndarray, pars: np.ndarray, ends: np.ndarray,
                first: np.ndarray | None = None) -> np.ndarray:
    r"""The Taylor steps each orbit takes from time 0 to ``ends[k]`` in the batch integrator ``ta``
    (width = ``ta``'s batch size): ``states`` ``(count, dim)`` the lanes' full initial states,
    ``pars`` ``(npar, count)`` their runtime parameters. ``first``: the order of the pilot's own
    batches (default: as given). Domain: ``ends > 0``; the integrator's state, parameters and time
    are left as the last batch made them (the caller sets them in full before its own runs)."""
    width = int(ta.batch_size)
    count = len(states)
    out = np.empty(count, dtype=np.int64)
    first = np.arange(count) if first is None else np.asarray(first, int)
    for lanes, used in batches(first, width):
        ta.state[:] = states[lanes].T
        ta.pars[:] = pars[:, lanes]
        ta.set_time(0.0)
        ta.propagate_until(np.asarray(ends, float)[lanes])
        for lane, res in enumerate(ta.propagate_res[:used]):
            if str(res[0]) != "taylor_outcome.time_limit":
                raise RuntimeError(f"pilot: heyoka stopped early ({res[0]}) on orbit {lanes[lane]}")
            out[lanes[lane]] = int(res[3])
    return out


def order(ta, states: np.ndarray, pars: np.ndarray, horizons: np.ndarray,
          first: np.ndarray | None = None, pilot: float = PILOT) -> np.ndarray:
    r"""The order in which the orbits fill the batches of ``ta``: decreasing Taylor steps of a pilot
    run over ``pilot`` times each orbit's ``horizons[k]`` (:func:`pilot_steps`; ties in the order
    ``first``, default the given order). One batch or fewer: ``first`` unchanged, no pilot.
    Domain: ``horizons > 0``, ``0 < pilot <= 1``."""
    count = len(states)
    first = np.arange(count) if first is None else np.asarray(first, int)
    if count <= int(ta.batch_size):
        return first
    if not 0.0 < pilot <= 1.0:
        raise ValueError(f"pilot fraction {pilot} is not in (0, 1]")
    steps = pilot_steps(ta, states, pars, pilot * np.asarray(horizons, float), first)
    return first[np.argsort(-steps[first], kind="stable")]


def efficiency(steps: np.ndarray, index: np.ndarray, width: int) -> float:
    r"""The useful fraction $\sum_k s_k / \sum_{\text{batches}} \text{width} \cdot \max s_k$ of the
    batches filled in the order ``index`` with orbits of ``steps`` Taylor steps each."""
    steps = np.asarray(steps, float)
    cost = sum(width * steps[lanes[:used]].max() for lanes, used in batches(index, width))
    return float(steps[np.asarray(index, int)].sum() / cost) if cost else 1.0
