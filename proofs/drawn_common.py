r"""How the drawn evidence rows word their verdicts, shared by proofs/s5_tori_evidence.py and
proofs/s6_open_reduced_n5.py: the rules themselves (what each reads of an orbit, its thresholds,
what contradicts, how the control separates) are registered in :mod:`simulate.analysis.rules`,
fixed before the runs; here are the verdict's texts, records and the rule's one-line statement.

Per orbit (simulate/analysis/drawn_evidence.py): frequency class ``predicted`` / ``resonant`` / ``excess`` /
``unresolved`` (``excess`` only for a line no integer combination with $|c| \le 12$ explains,
simulate/analysis/combinations.py), the chaos class over the horizon ladder ``regular`` / ``chaotic`` /
``undecided`` (simulate/analysis/chaos.py ``ladder_class``: $\langle Y\rangle$ grew by $\ge 1$ over the last doubling
$T/2 \to T$ and is $\ge 4$: chaos; moved by $\le 0.75$: bounded, regular — 0, 2 or $2p$ alike), and the
drift of the proved integrals (simulate/analysis/kept.py; kept iff $\le 10^{-6}$ at energy scale 1).
Unresolved orbits get the horizon ladder (again at $2T$, then $4T$) before they are counted.

**Validation** (bench/bench_evidence.py, ``chaplygin bench evidence``; the numbers are
:data:`STUDY`): the ladder rule on systems with known answers — false alarms (chaotic on an
integrable system) and misses (regular on a chaotic one).
"""

from __future__ import annotations

import numpy as np
from chaplygin_nd.simulate.analysis import chaos, rules
from chaplygin_nd.simulate.analysis.rules import (  # noqa: F401  (the rule's thresholds, for the rows)
    CONTRADICTING_MAX,
    CONTROL_CHAOTIC_MIN,
    KEPT_MIN,
    MEGNO_REGULAR_MIN,
    PREDICTED_MIN,
    SEPARATION,
    contradicting,
    fraction,
    separates,
    unmet,
)

#: the validation study's numbers (bench/out/evidence.md of the run named there): the rule's own
#: record, :data:`simulate.analysis.chaos.STUDY`
STUDY = chaos.STUDY

RULE = ("contradicting orbit: chaotic by the MEGNO horizon ladder (<Y>(T) - <Y>(T/2) >= 1 and "
        "<Y>(T) >= 4) or, with D < 1e-5, a line no integer combination |c| <= 12 explains beyond "
        "the predicted count; supported iff >= 98 % of the orbits keep the proved integrals (drift "
        "<= 1e-6), at most 2 % contradict, at least 90 % are regular by the ladder (|<Y>(T) - "
        "<Y>(T/2)| <= 0.75) and at least 20 % show exactly the predicted count (unresolved orbits "
        "re-run at 2T, 4T first). The control separates iff >= 90 % of its orbits are chaotic by "
        "the ladder (<= 2 % of the row's) and its median diffusion is >= 100 x the row's")


#: what each row said on the planted defects of bench/planted.py (``chaplygin bench evidence``,
#: 2026-11-26): one coefficient of the field 1 % off, one sign flipped; which part caught it
PLANTED = {
    "S5:reconstruction": (
        "planted defects (bench/planted.py): a coefficient of the full field 1 % off -> open, "
        "caught by the integrals alone (drift median 1.9e-3, every orbit); the chaos indicator "
        "and the frequency count did not see it (tori survive a 1 % perturbation: <= 2 % excess, "
        ">= 20 % predicted count); a sign flipped -> open (integrals, drift median 0.51; chaos "
        "indicator; the control no longer separates)"),
    "Th:Re-tori:frequencies": (
        "planted defects (bench/planted.py): a coefficient 1 % off -> open (integrals kept on "
        "only 114 of 200 orbits, drift median 5e-7; and the frequencies against zeta); a sign "
        "flipped -> open (integrals on 40 of 200; 61 excess orbits; zeta); the chaos indicator "
        "part held on both (<= 2 % chaotic, >= 90 % regular by the ladder)"),
    "S6:open-reduced-n5": (
        "planted defects (bench/planted.py): a coefficient of the full field 1 % off -> open, "
        "caught by the integrals alone (drift median 1.5e-3); a sign flipped -> open (integrals, "
        "drift median 0.44; chaos; the n = 4 control no longer passes)"),
    "S5:EJ-tori": (
        "planted defects (bench/planted.py): one coefficient of the reduced field 1 % off -> open "
        "(integrals: drift median 2.3e-3 on every orbit; and the rotation numbers of a level set); "
        "a sign flipped -> the row errors (heyoka stopped early: an orbit left the domain)"),
}


def keeps(r) -> bool:
    """The orbit keeps the proved integrals (simulate/analysis/kept.py)."""
    return rules.get("integrals").criteria[0].counts(r)


def supported(results) -> bool:
    """The support rule of the module docstring."""
    return not unmet(results)


def parts(results) -> dict:
    """Which parts of the rule hold, one per registered rule: ``{"integrals": ..., "chaos": ...,
    "frequencies": ...}`` (what a planted defect was caught by, bench/planted.py)."""
    labels = [u.split(":", 1)[0] for u in unmet(results)]
    return {k: not any(k in label for label in labels) for k in (r.part for r in rules.rules())}


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
             "lyapunov": float(f"{r.lyapunov:.3g}"), "megno_class": r.megno_cls,
             "ladder": [round(v, 3) for v in r.ladder], "drift": float(f"{r.drift:.3g}"),
             "drift_of": r.drift_of, "horizon": r.horizon, "large_combinations": r.large,
             "p_false": float(f"{r.p_false:.3g}")}
            for r in results]


def integrals_text(results) -> str:
    """One phrase: how well the drawn orbits kept the proved integrals."""
    d = np.array([r.drift for r in results if np.isfinite(r.drift)])
    if not len(d):
        return "integrals not measured"
    worst = max(results, key=lambda r: r.drift if np.isfinite(r.drift) else -1)
    return (f"proved integrals kept (drift <= 1e-6 at scale 1) on {sum(keeps(r) for r in results)} "
            f"of {len(results)} orbits (median drift {np.median(d):.1e}, worst {d.max():.1e} in "
            f"{worst.drift_of})")


def ladder_text(results) -> str:
    """One phrase: what the frequency ladder (2T, 4T) did."""
    h = {}
    for r in results:
        h[r.horizon] = h.get(r.horizon, 0) + 1
    big = sum(r.large for r in results)
    return (f"frequencies read at T / 2T / 4T on {h.get(1.0, 0)} / {h.get(2.0, 0)} / {h.get(4.0, 0)} "
            f"orbits; lines explained by combinations with |c| > 4: {big} (largest false-match "
            f"probability {max((r.p_false for r in results), default=0.0):.1e})")


def without_heyoka() -> str:
    """Why an evidence row cannot run here, or ``""``: its drawn orbits and MEGNO tangents are
    integrated with heyoka (the extra ``fast``), which the base install does not have. The row then
    says ``open`` with this reason instead of raising."""
    from chaplygin_nd.simulate.integrators import heyoka_taylor

    if heyoka_taylor.available():
        return ""
    return ("not measured here: the drawn orbits are integrated with heyoka, which is not "
            "installed (pip install 'chaplygin-nd[fast]')")
