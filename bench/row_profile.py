r"""Where one ledger row's seconds go: run it in this process under :mod:`cProfile` and split its
wall time into the stages of the evidence machinery (``python -m chaplygin_nd.bench.row_profile ID
OUT.json``; used by ``chaplygin bench verify-cold``).

Stages (seconds of wall time, from the profile; every stage is a set of functions whose inclusive
times do not overlap):

* ``imported`` — importing the package and discovering the proofs, before the row starts (not
  part of ``wall``);
* ``compile`` — building heyoka integrators that were not in a cache: the expression graph (its
  own column ``graph``: the field, the MEGNO tangent by ``hy.diff``) and heyoka's construction
  (decomposition, LLVM code generation and compilation) — ``runtime.jit_cache`` misses;
* ``load`` — compiled integrators unpickled from the project's cache (hits);
* ``integrate`` — inside heyoka's ``propagate_grid`` (the Taylor steps and the dense output);
* ``megno`` — $\langle Y\rangle$ and its ladder from the samples (:mod:`simulate.analysis.chaos`);
* ``integrals`` — the drift of the proved integrals along the orbits (:mod:`simulate.analysis.kept`);
* ``naff`` — the frequency analysis and the classification of every orbit (NAFF, the
  integer-relation searches, :func:`simulate.analysis.drawn_evidence._measure` after the integration);
* ``cache`` — reading and writing the result cache (the code manifest's hashes included);
* ``draws`` — drawing the initial states (and moving them on level sets: a Newton iteration);
* ``exact`` — the exact part of a drawn row (SymPy, FLINT ranks), or the whole of a row without a
  drawn measurement;
* ``other`` — the rest of the row's wall time (Python overhead: observables, padding, the rule).

The profiler's own overhead falls mostly on ``other`` and ``exact`` (many small Python calls);
heyoka's and NumPy's long calls are timed as one call each.
"""

from __future__ import annotations

import cProfile
import json
import pstats
import sys
import time

__all__ = ["profile_row", "stages"]

#: (stage, module path fragment, function name, inclusive?) — the functions of each stage
STAGES = (
    ("build", "runtime/jit_cache.py", "_load_or_build", True),
    ("load", "runtime/jit_cache.py", "_load", True),
    ("graph", "simulate/integrators/heyoka_systems.py", "equations", True),
    ("integrate", "~", "propagate_grid", False),
    ("megno", "simulate/analysis/chaos.py", "megno_from_samples", True),
    ("megno", "simulate/analysis/chaos.py", "megno_ladder", True),
    ("integrals", "simulate/analysis/kept.py", "drift", True),
    ("measure", "simulate/analysis/drawn_evidence.py", "_measure", True),
    ("measure", "simulate/analysis/continuation.py", "compute", True),  # the ladder's longer runs
    ("integrate_all", "simulate/analysis/drawn_evidence.py", "_integrate", True),
    ("cached", "simulate/analysis/result_cache.py", "cached_json", True),
    ("draws", "simulate/analysis/draws.py", "draw", True),
    ("draws", "simulate/analysis/evidence.py", "level_set_points", True),
    ("exact", "proofs/s6_open_reduced_n5.py", "reduced_dimension_check", True),
)


def _times(stats: pstats.Stats) -> dict[str, float]:
    """Inclusive (or exclusive, for builtins) seconds of each function group of :data:`STAGES`."""
    out: dict[str, float] = {}
    for (path, _line, name), (_cc, _nc, tt, ct, _callers) in stats.stats.items():  # type: ignore[attr-defined]
        for stage, where, fname, inclusive in STAGES:
            if where == "~":
                hit = path == "~" and fname in name
            else:
                hit = path.replace("\\", "/").endswith(where) and name == fname
            if hit:
                out[stage] = out.get(stage, 0.0) + (ct if inclusive else tt)
    return out


def stages(stats: pstats.Stats, wall: float, imported: float) -> dict[str, float]:
    """The stages of the module docstring from a profile of one row (``wall``: the row's seconds,
    ``imported``: the seconds before it). A row with no evidence measurement is all ``exact``."""
    t = _times(stats)
    load = t.get("load", 0.0)
    compile_ = max(0.0, t.get("build", 0.0) - load)
    integrate, megno, integrals = t.get("integrate", 0.0), t.get("megno", 0.0), t.get("integrals", 0.0)
    naff = max(0.0, t.get("measure", 0.0) - t.get("integrate_all", 0.0))
    cache = max(0.0, t.get("cached", 0.0) - t.get("measure", 0.0))
    exact = t.get("exact", 0.0) if "cached" in t else wall
    out = {"compile": compile_, "load": load, "integrate": integrate, "megno": megno,
           "integrals": integrals, "naff": naff, "cache": cache, "draws": t.get("draws", 0.0),
           "exact": exact}
    out["other"] = max(0.0, wall - sum(out.values()))
    out.update(wall=wall, graph=t.get("graph", 0.0), imported=imported)
    return out


def profile_row(claim_id: str) -> dict:
    """Decide ``claim_id`` in this process under the profiler; its stages and verdict."""
    start = time.perf_counter()
    from chaplygin_nd.ledger.catalog import resolve
    from chaplygin_nd.ledger.runner import discover, run, select
    from chaplygin_nd.symbolic.exact import points

    discover()
    rows = select(resolve([claim_id]))
    imported = time.perf_counter() - start
    prof = cProfile.Profile()
    t0 = time.perf_counter()
    prof.enable()
    (result,) = run(rows, jobs=1, seed=points.DEFAULT_SEED)
    prof.disable()
    wall = time.perf_counter() - t0
    out = stages(pstats.Stats(prof), wall, imported)
    out.update(id=claim_id, status=result.status, error=result.error)
    return out


if __name__ == "__main__":
    record = profile_row(sys.argv[1])
    with open(sys.argv[2], "w", encoding="utf-8") as fh:
        json.dump(record, fh)
