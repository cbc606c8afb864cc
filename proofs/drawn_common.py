r"""The verdict rule of the drawn evidence rows (issue 16), shared by proofs/s5_tori_evidence.py and
proofs/s6_open_reduced_n5.py. Fixed before the drawn ensembles were run (a timing pilot of 8
orbits each of the $n = 4$ and $n = 5$ spheres had been seen; it is reported in docs/design-notes/i16b.md).

Per orbit (simulate/analysis/drawn_evidence.py): frequency class ``predicted`` / ``resonant`` / ``excess`` /
``unresolved`` and MEGNO class ``regular`` / ``chaotic`` / ``undecided`` (simulate/analysis/chaos.py).

* **contradicting** orbit: MEGNO ``chaotic`` or frequency class ``excess`` (a regular orbit with
  more independent frequencies than the torus allows).
* the statement is **supported** iff at most ``CONTRADICTING_MAX`` = 2 % of the drawn orbits
  contradict it, at least ``MEGNO_REGULAR_MIN`` = 90 % are MEGNO-regular, and at least
  ``PREDICTED_MIN`` = 20 % show exactly the predicted count (so the prediction is observed, not
  merely not refuted); unresolved orbits neither support nor contradict and are reported, with what
  $4T$ does to the first 4 of them (1 per $n$ on $\mathcal V$).
* the control **separates on MEGNO** iff at least ``CONTROL_CHAOTIC_MIN`` = 50 % of its orbits are
  MEGNO-chaotic while at most 2 % of the row's are; **on the frequencies** iff its median
  diffusion is at least ``SEPARATION`` = 100 times the row's median diffusion. The row needs both.
"""

from __future__ import annotations

import numpy as np

CONTRADICTING_MAX = 0.02
MEGNO_REGULAR_MIN = 0.90
PREDICTED_MIN = 0.20
CONTROL_CHAOTIC_MIN = 0.50
SEPARATION = 100.0

RULE = ("contradicting orbit: MEGNO <Y>(T) >= 4 (chaotic) or, with D < 1e-5, more independent "
        "frequencies than predicted; the statement is contradicted if more than 2 % of the drawn "
        "orbits contradict it; it is supported if at most 2 % contradict, at least 90 % are "
        "MEGNO-regular (<Y> <= 2.5) and at least 20 % show exactly the predicted count. The "
        "control separates iff >= 50 % of its orbits are MEGNO-chaotic (<= 2 % of the row's) and "
        "its median diffusion is >= 100 x the row's")


def fraction(results, test) -> float:
    """The fraction of ``results`` for which ``test(r)`` holds."""
    return sum(bool(test(r)) for r in results) / len(results) if results else 0.0


def contradicting(r) -> bool:
    """An orbit that contradicts a torus statement (module docstring)."""
    return r.megno_cls == "chaotic" or r.cls == "excess"


def supported(results) -> bool:
    """The support rule of the module docstring."""
    return (fraction(results, contradicting) <= CONTRADICTING_MAX
            and fraction(results, lambda r: r.megno_cls == "regular") >= MEGNO_REGULAR_MIN
            and fraction(results, lambda r: r.cls == "predicted") >= PREDICTED_MIN)


def unmet(results) -> list[str]:
    """The parts of the support rule (module docstring) that ``results`` fail, each with its
    numbers (``[]`` iff :func:`supported`): what an ``open`` row names as its reason."""
    n = len(results)
    if not n:
        return ["no drawn orbits"]
    counts = [(sum(contradicting(r) for r in results), "are chaotic or excess (contradict)",
               lambda k: k / n <= CONTRADICTING_MAX, "more than", CONTRADICTING_MAX),
              (sum(r.megno_cls == "regular" for r in results), "are MEGNO-regular",
               lambda k: k / n >= MEGNO_REGULAR_MIN, "fewer than", MEGNO_REGULAR_MIN),
              (sum(r.cls == "predicted" for r in results), "show exactly the predicted count",
               lambda k: k / n >= PREDICTED_MIN, "fewer than", PREDICTED_MIN)]
    return [f"{k} of {n} orbits {what}: {100 * k / n:g} %, {side} the rule's {100 * bound:g} %"
            for k, what, ok, side, bound in counts if not ok(k)]


def separates(results, control) -> tuple[bool, bool]:
    """(on MEGNO, on the frequency diffusion): the separation rule of the module docstring."""
    chaotic = lambda r: r.megno_cls == "chaotic"  # noqa: E731
    megno = (fraction(control, chaotic) >= CONTROL_CHAOTIC_MIN
             and fraction(results, chaotic) <= CONTRADICTING_MAX)
    d_row = float(np.median([r.diffusion for r in results]))
    d_ctl = float(np.median([r.diffusion for r in control]))
    return megno, bool(d_ctl >= SEPARATION * max(d_row, 1e-300))


def tally(results, key: str = "cls") -> str:
    """``"predicted 174, resonant 4, unresolved 22"``-style counts of one class field."""
    counts: dict = {}
    for r in results:
        counts[getattr(r, key)] = counts.get(getattr(r, key), 0) + 1
    return ", ".join(f"{k} {v}" for k, v in sorted(counts.items(), key=lambda kv: -kv[1]))


def describe(results, label: str) -> str:
    """One sentence: the distribution of classes, counts, MEGNO and D of ``results``."""
    if not results:
        return f"{label}: none"
    ys = np.array([r.megno for r in results])
    ds = np.array([r.diffusion for r in results])
    counts: dict = {}
    for r in results:
        counts[r.count] = counts.get(r.count, 0) + 1
    return (f"{label} ({len(results)} orbits): {tally(results)}; MEGNO {tally(results, 'megno_cls')} "
            f"(<Y> median {np.median(ys):.2f}, range {ys.min():.2f}..{ys.max():.2f}); "
            f"D median {np.median(ds):.1e}; independent frequencies "
            + ", ".join(f"{c}: {k}" for c, k in sorted(counts.items())))


def resonances(results, limit: int = 3) -> str:
    """The integer relations named for the first ``limit`` resonant orbits."""
    named = []
    for r in results:
        if r.cls != "resonant":
            continue
        if r.relation:
            named.append(r.relation)
        elif r.count == 1:
            named.append(f"periodic: every line a multiple of w = {r.frequencies[0]:.10g}")
        elif r.count == 0:
            named.append("no line: an equilibrium")
    named = list(dict.fromkeys(named))
    return "; ".join(named[:limit]) if named else "none named"


def record(results) -> list[dict]:
    """The per-orbit numbers for the ledger's JSON (rounded)."""
    return [{"a": r.a, "b": r.b, "scale": r.scale, "count": r.count, "class": r.cls,
             "diffusion": float(f"{r.diffusion:.3g}"), "megno": round(r.megno, 3),
             "lyapunov": float(f"{r.lyapunov:.3g}"), "megno_class": r.megno_cls}
            for r in results]


def without_heyoka() -> str:
    """Why an evidence row cannot run here, or ``""``: its drawn orbits and MEGNO tangents are
    integrated with heyoka (the extra ``fast``), which the base install does not have. The row then
    says ``open`` with this reason instead of raising."""
    from chaplygin_nd.simulate.integrators import heyoka_taylor

    if heyoka_taylor.available():
        return ""
    return ("not measured here: the drawn orbits are integrated with heyoka, which is not "
            "installed (pip install 'chaplygin-nd[fast]')")
