r"""The validation of the NAFF count over the horizon ladder (:mod:`simulate.analysis.naff_ladder`) on
systems whose torus dimension is known, before the torus rows use it: per system the orbits
resolved at $T$ and over the ladder, the counts read, **false alarms** (a resolved orbit of an
integrable system counting more frequencies than its torus dimension: what the rows call
*contradicting*) and **misses** (a chaotic orbit resolved at any horizon of the ladder).

Systems (orbits drawn from ``seed``; heyoka tolerance $10^{-10}$, batch 8; $T = 4096$, $dt = 1/2$, the
rows' settings; frequency-only runs):

* **uncoupled pendula** $\ddot q_i = -w_i^2\sin q_i$, $m = 2, 3, 4$ (:func:`simulate.analysis.gali_study.pendula`),
  $w_i$ drawn in $[0.1, 0.3]$ (the rows' lines lie in $0.02..0.8$; slower than the GALI study's
  $[0.5, 1.5]$ so that the harmonics of rotating pendula stay below the Nyquist frequency $\pi$ of
  the $4T$ sampling), $q_i$ uniform, $p_i = w_i\cdot$ normal: an $m$-torus; signals
  $\sum_i \alpha_i(\sin q_i + i\,p_i/w_i)$ and $\sum_i \beta_i(\cos q_i + i\,(p_i/w_i)^2/2)$ with fixed
  unequal weights;
* **the axisymmetric $n = 4$ sphere** on its two $SO(3)$-invariant signals (the rows' signals at
  $n = 4$): the reduced motion lies on 2-tori (S5:EJ-tori);
* **the twist map** (standard map $K = 0$, signal $e^{ix}$): dimension 1;
* **chaotic:** the standard map $K = 10$ (signals $e^{ix}$, $e^{ip}$), and the generic-$\mathbb J$
  $n = 4$ sphere ``CHAOTIC_J[4]`` (the rows' control; mixed, so its fraction resolved is reported,
  not a miss rate).

Run: ``python -m chaplygin_nd.simulate.analysis.naff_study [--quick]``; the numbers the rows cite
are :data:`STUDY`.
"""

from __future__ import annotations

import sys
import time

import numpy as np
from chaplygin_nd.simulate.analysis import gali_runs, naff_ladder
from chaplygin_nd.simulate.analysis.gali_study import _upper, pendula

__all__ = ["run", "rates", "table", "STUDY", "T", "DT", "SEED"]

SEED = 20261121
T, DT = 4096.0, 0.5
ALPHA = (1.0, 0.7, 0.5, 0.35)
BETA = (0.35, 0.5, 0.7, 1.0)


def _pendula_case(m: int, count: int, seed: int) -> dict:
    rng = np.random.default_rng([seed, 0x4AFF, m])
    w = rng.uniform(0.1, 0.3, (count, m))
    q = rng.uniform(-np.pi, np.pi, (count, m))
    p = rng.normal(0.0, 1.0, (count, m)) * w

    def signals(Y, idx):                     # Y (samples, lanes, 2m) -> (lanes, 2, samples)
        q_, v = Y[..., :m], Y[..., m:] / w[idx][None]
        z1 = sum(ALPHA[i] * (np.sin(q_[..., i]) + 1j * v[..., i]) for i in range(m))
        z2 = sum(BETA[i] * (np.cos(q_[..., i]) + 0.5j * v[..., i] ** 2) for i in range(m))
        return np.moveaxis(np.array([z1, z2]), (0, 1, 2), (1, 2, 0))

    return {"name": f"uncoupled pendula, m = {m}", "truth": "regular", "dimension": m,
            "system": pendula(m), "y0": np.concatenate([q, p], 1), "pars": (w ** 2).T,
            "signals": signals}


def _sphere_case(label: str, J, count: int, seed: int) -> dict:
    from chaplygin_nd.simulate.analysis import draws
    from chaplygin_nd.simulate.analysis.control import general_system
    from chaplygin_nd.simulate.analysis.drawn_evidence import Setting, observables
    from chaplygin_nd.simulate.dynamics import so
    from chaplygin_nd.simulate.integrators import heyoka_systems as hs

    ens = draws.draw(f"naff-study {label}", "generic", 4, count, seed)
    s = Setting("naff-study", "full", 4, T, DT, observables="invariant+general")

    def signals(Y, idx):
        return observables(s, Y, ens.a[idx], ens.b[idx])[:, :2]

    case = {"y0": np.concatenate([so.vec(ens.M0), ens.gamma0], -1), "pars": np.stack([ens.a, ens.b]),
            "time_factor": ens.time_factor, "signals": signals}
    if J:
        return {**case, "name": f"generic J = diag{J} sphere n = 4 (the rows' control)",
                "truth": "mixed", "dimension": None, "system": general_system(J)}
    return {**case, "name": "axisymmetric n = 4 sphere, SO(3)-invariant signals", "truth": "regular",
            "dimension": 2, "system": hs.full(4)}


def _flow(case: dict) -> list:
    """The ladder on one flow: signals on $[0, T]$ from the initial states, continued on demand."""
    y0, pars, signals = case["y0"], case["pars"], case["signals"]
    f = case.get("time_factor")
    f = np.ones(len(y0)) if f is None else f
    z0 = signals(y0[None], np.arange(len(y0)))
    z, final = gali_runs.extend(case["system"], y0, pars, t0=0.0, t1=T, dt=DT, signals=signals,
                                time_factor=f)
    extend = gali_runs.continuation(case["system"], final, pars, dt=DT, signals=signals,
                                    time_factor=f)
    expected = case["dimension"] if case["dimension"] is not None else 99
    return naff_ladder.ladder(np.concatenate([z0, z], -1), DT, T, expected, extend)


def _map_case(K: float, count: int, seed: int) -> list:
    r"""The ladder on ``count`` orbits of the standard map at ``K`` (time = iteration, $dt = 1$)."""
    rng = np.random.default_rng([seed, 0x4AF5, int(K * 100)])
    x, p = rng.uniform(0, 2 * np.pi, count), rng.uniform(0, 2 * np.pi, count)
    steps = int(4 * T)
    X, P = np.empty((steps + 1, count)), np.empty((steps + 1, count))
    X[0], P[0] = x, p
    for s in range(1, steps + 1):
        p = p + K * np.sin(x)
        x = x + p
        X[s], P[s] = x, p
    sig = [np.exp(1j * X.T)] + ([np.exp(1j * P.T)] if K else [])
    Z = np.stack(sig, 1)                                        # (orbits, signals, steps + 1)
    n0 = int(T)

    def extend(idx, t0, t1):
        return Z[idx, :, int(t0) + 1:int(t1) + 1]

    return naff_ladder.ladder(Z[:, :, :n0 + 1], 1.0, T, 1 if K == 0 else 99, extend)


def run(count: int, map_count: int, seed: int = SEED) -> list[dict]:
    """Every system of the module docstring: ``[{name, truth, dimension, results: [(spectrum,
    extra)], seconds}]``."""
    from chaplygin_nd.simulate.analysis.control import CHAOTIC_J

    rows = []
    cases = [_pendula_case(m, count, seed) for m in (2, 3, 4)]
    cases += [_sphere_case("full4", (), count, seed), _sphere_case("control4", CHAOTIC_J[4], count, seed)]
    for case in cases:
        t0 = time.perf_counter()
        rows.append({"name": case["name"], "truth": case["truth"], "dimension": case["dimension"],
                     "results": _flow(case), "seconds": time.perf_counter() - t0})
    for K, truth, dim in ((0.0, "regular", 1), (10.0, "chaotic", None)):
        t0 = time.perf_counter()
        rows.append({"name": f"standard map K = {K:g}", "truth": truth, "dimension": dim,
                     "results": _map_case(K, map_count, seed), "seconds": time.perf_counter() - t0})
    return rows


def rates(rows: list[dict]) -> dict:
    """Resolved at $T$ and over the ladder, false alarms, misses, counts exact / below over the
    systems of known truth, with one-sided 95 % upper bounds."""
    reg = [(r, row["dimension"]) for row in rows if row["truth"] == "regular" for r in row["results"]]
    cha = [r for row in rows if row["truth"] == "chaotic" for r in row["results"]]
    res = [(s, d) for (s, e), d in reg if naff_ladder.resolved(s, e)]
    # the false alarms of the orbits the ladder resolved (2T, 4T) apart
    fa = sum(s.count > d for s, d in res)
    fa_ladder = sum(s.count > d for (s, e), d in reg if naff_ladder.resolved(s, e) and e["horizon"] > 1)
    miss = sum(naff_ladder.resolved(s, e) for s, e in cha)
    return {"regular_orbits": len(reg), "resolved_at_T": sum(
                naff_ladder.resolved(s, e) and e["horizon"] == 1.0 for (s, e), _ in reg),
            "resolved": len(res), "false_alarms": fa, "false_alarm_upper": _upper(fa, len(res)), "false_alarms_ladder": fa_ladder,
            "exact": sum(s.count == d for s, d in res), "below": sum(s.count < d for s, d in res),
            "chaotic_orbits": len(cha), "misses": miss, "miss_upper": _upper(miss, len(cha))}


def table(rows: list[dict]) -> str:
    """The per-system table (Markdown)."""
    lines = ["| system | true dimension | orbits | resolved at T / 2T / 4T | counts of the resolved "
             "| seconds |", "|---|---|---|---|---|---|"]
    for row in rows:
        res = row["results"]
        at = {h: sum(naff_ladder.resolved(s, e) and e["horizon"] == h for s, e in res)
              for h in (1.0, 2.0, 4.0)}
        counts: dict = {}
        for s, e in res:
            if naff_ladder.resolved(s, e):
                counts[s.count] = counts.get(s.count, 0) + 1
        read = ", ".join(f"{c}: {k}" for c, k in sorted(counts.items())) or "-"
        true = row["dimension"] if row["dimension"] is not None else row["truth"]
        lines.append(f"| {row['name']} | {true} | {len(res)} | {at[1.0]} / {at[2.0]} / {at[4.0]} | "
                     f"{read} | {row['seconds']:.1f} |")
    return "\n".join(lines)


#: the study's numbers (``python -m chaplygin_nd.simulate.analysis.naff_study``), cited by the rows
STUDY = ("simulate/analysis/naff_study.py (2026-11-27, seed 20261121, T = 4096, the ladder 2T, 4T; 48 "
         "orbits per flow, 200 per map): 392 orbits of known torus dimension (uncoupled pendula "
         "m = 2, 3, 4; the axisymmetric n = 4 sphere on its invariant signals; the twist map), 315 "
         "resolved at T and 368 over the ladder; counts exact on 357, below on 2, above (false "
         "alarms) on 9 of 368 (2.4 %, < 4.2 % at 95 %): 6 at T, 3 at 2T or 4T; 8 are pendula "
         "(a doubled line entering the basis before the fundamental, or a weak line measured off "
         "its combination), one an n = 4 orbit resolved at 4T whose slow frequency's sidebands "
         "need |c| = 14 > 12; misses 0 of 200 orbits of the chaotic standard map K = 10 at any "
         "horizon (< 1.5 % at 95 %); the generic-J n = 4 control: 0 of 48 resolved at any horizon")


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    quick = "--quick" in argv
    rows = run(8 if quick else 48, 64 if quick else 200)
    print(table(rows))
    print(rates(rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
