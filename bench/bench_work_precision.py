r"""Work–precision: error against an independent high-precision reference versus wall time.

Scenes (``--quick`` divides every horizon by 10 and drops the slowest settings):

1. generic $n = 4$ to $T = 100$ — DOP853 across tolerances, RKMK4 across steps, heyoka Taylor
   across tolerances;
2. vertical $n = 5$ to $T = 100$ — the closed form of Th:Re against the same integrators;
3. precision, generic $n = 4$ to $T = 5$ — our Taylor method at 15–40 digits, ``mpmath.odefun`` at 15, 20,
   heyoka at ``real128`` and multiprecision ``real``; and the 30-digit reference to $T = 20$ by our
   Taylor method and by heyoka ``real``, each checked against our Taylor method at 40 digits;
4. long run, generic $n = 4$ to $T = 10^3$ with 101 samples — DOP853, RKMK4 ($h = 0.05$,
   $2\cdot10^4$ steps) and heyoka: error against a 21-digit reference and the drift of the integrals.
   The drift of RKMK4's isospectral invariants grows like a random walk of rounding errors; its
   growth exponent is fitted on the samples and extrapolated to $10^6$ steps (the former run of
   $10^6$ steps to $T = 10^4$ took 5.5 min; the extrapolation is labelled as such);
5. models, $n = 4$, reduced invariants only — full field versus the reduced 7D field (DOP853 and
   heyoka) versus the closed form, and the planner's choice for such a scene;
6. an ensemble of 256 generic $n = 4$ points to $T = 10$ — stacked DOP853, vectorised RKMK4, heyoka
   in batch (SIMD) mode.

heyoka rows appear when heyoka imports (else the Markdown says so and they are omitted); their
``seconds`` is the run alone (warm: the compiled integrator in memory) and ``compile_seconds`` the
cold compile or the warm load from the disk cache in this process. References: our mpmath Taylor
method (cached in ``out/cache``), independent of every integrator judged.

Writes ``work_precision.json`` (rows: ``scene``, ``T``, ``method``, ``setting``, ``error``,
``seconds``, ``compile_seconds``, ...), ``work_precision.md`` (targets MET / NOT MET, all rows) and
the figures ``work_precision_*.png``. Reproduce: ``chaplygin bench work_precision``.
"""

from __future__ import annotations

import os
import time
from pathlib import Path

from chaplygin_nd.bench import sections, sections_models
from chaplygin_nd.bench.report import heyoka_available, machine, write_atomic, write_rows
from chaplygin_nd.bench.runs import MD_HEAD, Row

SECTIONS = (sections.section_generic4d, sections.section_vertical5d, sections.section_precision,
            sections_models.section_long, sections_models.section_models,
            sections_models.section_ensemble)


def main(outdir: Path, quick: bool = False, cold: bool = False) -> int:
    """Run every scene, write the JSON rows, the Markdown and the figures into ``outdir``."""
    out = Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    has_heyoka, why = heyoka_available()
    cache = Path(os.environ.get("BENCH_CACHE") or out / "cache")
    ctx = sections.Context(out=out, cache=cache, quick=quick, heyoka=has_heyoka)
    rows: list[Row] = []
    targets: list[str] = []
    timings = []
    for section in SECTIONS:
        start = time.perf_counter()
        r, t = section(ctx)
        rows += r
        targets += t
        timings.append(f"{section.__name__.removeprefix('section_')} "
                       f"{time.perf_counter() - start:.1f} s")
        print(f"  {timings[-1]}", flush=True)
    heading = ["# Work–precision", "", *machine(),
               f"- heyoka: {'used (its rows and curves are included)' if has_heyoka else why}",
               f"- mode: {'--quick (smoke run; numbers not meaningful)' if quick else 'full'}, "
               f"{'cold (every cache empty: --cold)' if cold else 'caches as found'}; "
               f"sections: {', '.join(timings)}",
               "", "Reproduce: `chaplygin bench work_precision` (from the repository root; "
               "`make bench` runs it with the throughput). The bench keeps its caches in `bench/out/cache` "
               "(references, compiled heyoka objects, heyoka's own LLVM disk cache); cold: "
               "`chaplygin bench --cold` empties them first; warm: a second run.", ""]
    lines = heading + ["## Targets", "", *targets, "", "## All runs", "", *MD_HEAD,
                       *[r.md() for r in rows], "",
                       "Errors: max over samples and components of (vec M, gamma) (models: of the "
                       "reduced invariants). seconds: the run alone, minimum over repeats; "
                       "compile s: heyoka's cold compile or warm cache load, apart. RHS calls: "
                       "RKMK4 4 per step; Taylor: coefficient evaluations; heyoka: steps. Shared "
                       "2-core machine: times are noisy.", "",
                       "Figures: " + ", ".join(sorted(p.name for p in out.glob("work_precision_*.png")))]
    write_rows(out / "work_precision.json", [r.as_dict() for r in rows])
    write_atomic(out / "work_precision.md", "\n".join(lines) + "\n")
    print("\n".join(["work-precision targets:", *targets, f"written {out / 'work_precision.md'}"]),
          flush=True)
    return 0
