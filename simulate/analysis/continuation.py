r"""The frequency ladder's longer runs, continued from the state at the shorter horizon.

An orbit left unresolved at $T$ (:mod:`simulate.analysis.evidence_rows`) has its frequencies measured
again at $2T$, and, if still unresolved, at $4T$ (:meth:`simulate.analysis.drawn_evidence.Setting.longer`:
the same sampling step to $2T$, twice it to $4T$). The samples up to the shorter horizon are already
known, so the longer run integrates only the rest: from the sampled state at $T$ over $(T, 2T]$,
from the state at $2T$ over $(2T, 4T]$ (every second sample of $[0, 2T]$ kept), with the field
without the tangent vector (a frequency-only run: the chaos indicator stays that of $T$). The
fields are autonomous, so the continuation starts its clock at 0. Each horizon integrates half of
what a run from 0 would.

**Deterministic, whatever the cache holds.** A continuation always starts from the sampled state
of the run at the shorter horizon — the run at $T$ *with* its tangent vector (whose step sizes
also follow the tangent), then the continuation to $2T$ — never from an independent run. The
signals and end states of those runs are kept in this process (:func:`remember`) while a row runs.
When a longer run is not in the result cache but the shorter one was read from it (so its samples
are not in memory), the shorter one is integrated again first — the whole ensemble at $T$, since
the tangent vectors are drawn per ensemble — and the numbers are those of a cold run.

Memory: the signals of the orbits of one ensemble (for $n = 4$, 200 orbits, 5 signals, 8193
samples: 130 MB) until the row's ladder is done (:func:`forget`).
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import asdict, replace

import numpy as np
from chaplygin_nd.simulate.analysis import drawn_evidence as de
from chaplygin_nd.simulate.analysis import result_cache as rc

__all__ = ["remember", "retain", "forget", "extend"]

#: (settings key of the ensemble's run at T, factor) -> {orbit: (signals, end state)}
_TRAILS: dict[tuple[str, float], dict[int, tuple[np.ndarray, np.ndarray]]] = {}


def _key(base: dict) -> str:
    return hashlib.sha256(json.dumps(base, sort_keys=True, default=str).encode()).hexdigest()


def remember(base: dict, factor: float, orbits, Z: np.ndarray, final: np.ndarray) -> None:
    """Keep the signals ``Z`` ``(count, signals, samples)`` and end states ``final`` of the run at
    ``factor`` times $T$ of the orbits ``orbits`` (indices in the ensemble of the run at $T$, whose
    :func:`simulate.analysis.drawn_evidence.settings` are ``base``)."""
    trail = _TRAILS.setdefault((_key(base), float(factor)), {})
    for k, orbit in enumerate(orbits):
        trail[int(orbit)] = (Z[k], final[k])


def retain(base: dict, factor: float, orbits) -> None:
    """Keep in memory only the orbits ``orbits`` of the run at ``factor`` times T (those the
    ladder goes on with)."""
    trail = _TRAILS.get((_key(base), float(factor)), {})
    wanted = {int(k) for k in orbits}
    for k in [k for k in trail if k not in wanted]:
        del trail[k]


def forget(base: dict) -> None:
    """Drop what :func:`remember` kept for the ensemble ``base`` (its ladder is done)."""
    key = _key(base)
    for k in [k for k in _TRAILS if k[0] == key]:
        del _TRAILS[k]


def _trail(s, ens, y0, seed: int, factor: float, index: list[int]):
    """Signals and end states of the orbits ``index`` at ``factor`` times T: from memory, or
    integrated again (module docstring)."""
    base = de.settings(s, ens, y0, seed)
    trail = _TRAILS.get((_key(base), float(factor)), {})
    missing = [k for k in index if k not in trail]
    if missing:
        if factor == 1.0:
            Z, _, _, extra = de._integrate(s, ens, y0, seed)       # the whole ensemble (tangents)
            remember(base, 1.0, range(len(y0)), Z, extra["final"])
        else:
            _continue(s, ens, y0, seed, factor, missing)
        trail = _TRAILS[(_key(base), float(factor))]
    return [trail[k][0] for k in index], np.array([trail[k][1] for k in index])


def _continue(s, ens, y0, seed: int, factor: float, index: list[int]):
    """Integrate the orbits ``index`` from ``factor / 2`` to ``factor`` times T; their whole
    signals and the chaos/drift records of the continuation (kept in memory for the next rung)."""
    previous = factor / 2
    longer = s.longer(factor, tangent="none")
    shorter_dt = s.dt * max(1.0, previous / 2)
    step = int(round(longer.dt / shorter_dt))        # 1 to 2T, 2 to 4T (Setting.longer)
    Z0, start = _trail(s, ens, y0, seed, previous, index)
    piece = replace(longer, T=longer.T - s.T * previous)
    sub = de.subset(ens, index)
    Z1, megno, lyap, extra = de._integrate(piece, sub, start, seed, first=1, anchor=y0[index])
    Z = np.concatenate([np.stack([z[:, ::step] for z in Z0]), Z1], axis=-1)
    remember(de.settings(s, ens, y0, seed), factor, index, Z, extra["final"])
    return longer, sub, Z, megno, lyap, extra


def extend(s, ens, y0, seed: int, factor: float, index, use_cache: bool = True) -> list:
    r"""The records of the orbits ``index`` of the ensemble ``(ens, y0)`` at ``factor`` (2 or 4)
    times the horizon of ``s``, continued from the run at ``factor / 2`` (module docstring):
    frequency fields at the longer horizon, no chaos indicator (``nan``), the drift of the
    integrals over the added samples from the orbits' initial states. Cached like
    :func:`simulate.analysis.drawn_evidence.measure` (keyed by the ensemble's settings at T, the
    factor and the orbits). Domain: ``factor`` a power of 2, ``index`` a subset of the orbits of
    the run at ``factor / 2``."""
    index = [int(k) for k in index]
    longer = s.longer(factor, tangent="none")
    key = {"kind": "continued", "base": de.settings(s, ens, y0, seed), "factor": float(factor),
           "orbits": index, "setting": asdict(longer)}

    def compute():
        longer_, sub, Z, megno, lyap, extra = _continue(s, ens, y0, seed, factor, index)
        return de.analyse(longer_, sub, Z, megno, lyap, extra)

    out, _ = rc.cached_json("evidence", f"drawn-{longer.name}-continued", key, compute,
                            encode=lambda res: [r.to_dict() for r in res], decode=de._decode,
                            use_cache=use_cache, heyoka=True)
    if len(out) != len(index):
        raise RuntimeError(f"{longer.name}: {len(out)} results for {len(index)} orbits")
    return out
