r"""The validation of the GALI rule (:mod:`simulate.analysis.gali`) on systems whose torus dimension
is known, before any row uses it: drawn orbits of each, the rule's class and dimension per orbit,
false alarms (chaotic on an integrable system), misses (regular on a chaotic one) and the rate of
each wrong dimension.

Systems (orbits drawn from ``seed``; heyoka tolerance $10^{-10}$, batch 8; ``K`` deviation vectors,
$K = \min(5, d)$ so that dimensions up to 4 can be read, 3 on the spheres' quotients):

* **uncoupled pendula** $\ddot q_i = -w_i^2\sin q_i$, $i = 1..m$, $m = 2, 3, 4$: Liouville
  integrable with the $m$ energies, every orbit off the separatrices on an $m$-torus whose frequencies
  change with the energies (rotation and libration alike); $w_i$ drawn in $[0.5, 1.5]$, $q_i$
  uniform, $p_i$ normal: true dimension $m$;
* **the 3D Chaplygin sphere with generic inertia** (eq:motion3D, $\mathbb J = \mathrm{diag}(1, 2, 0.5)$,
  Chaplygin's theorem: 4 integrals on a 6-dimensional space, no symmetry): dimension 2, vectors
  projected onto $TP$ only;
* **the axisymmetric $n = 4$ sphere on $P$**, vectors transverse to the $SO(3)$ orbits (the quotient
  of S5:EJ-tori: Euler–Jacobi, proved integrals): dimension 2;
* **the chaotic standard map** $p' = p + K\sin x$, $x' = x + p'$ at $K = 10$ (tangent map exact;
  GALI$_2$ of its 2 vectors) — chaotic — and its twist map $K = 0$ (invariant circles whose rotation
  number is $p$): dimension 1;
* **mixed** — the generic non-symmetric $n = 4$ sphere ``CHAOTIC_J[4]`` (the rows' chaos control):
  most orbits chaotic, the truth of one orbit unknown: the fraction read chaotic, not a miss rate.

Run: ``python -m chaplygin_nd.simulate.analysis.gali_study [--quick]`` (prints the tables; the
numbers the rows cite are :data:`STUDY`).
"""

from __future__ import annotations

import sys
import time

import numpy as np
from chaplygin_nd.simulate.analysis import gali as gl
from chaplygin_nd.simulate.analysis import gali_runs
from chaplygin_nd.simulate.integrators.heyoka_systems import System

__all__ = ["pendula", "systems", "standard_map", "run", "rates", "STUDY", "T", "DT"]

SEED = 20261121
T, DT = 4096.0, 0.5
J3 = (1.0, 2.0, 0.5)


def pendula(m: int) -> System:
    r"""$m$ uncoupled pendula $\dot q_i = p_i$, $\dot p_i = -w_i^2\sin q_i$; parameters $w_i^2$."""
    def build(v, p, ops):
        hy = ops.hy
        return list(v[m:]) + [-p[i] * hy.sin(v[i]) for i in range(m)]

    return System(f"pendula m={m}", tuple(f"q{i}" for i in range(m)) + tuple(f"p{i}" for i in range(m)),
                  tuple(f"w{i}sq" for i in range(m)), build)


def _pendula_orbits(m: int, count: int, seed: int):
    rng = np.random.default_rng([seed, 0x9E4D, m])
    w = rng.uniform(0.5, 1.5, (count, m))
    q = rng.uniform(-np.pi, np.pi, (count, m))
    p = rng.normal(0.0, 1.0, (count, m)) * w
    return np.concatenate([q, p], 1), (w ** 2).T


def systems(count: int, seed: int = SEED) -> list[dict]:
    """The flows of the study (module docstring): name, truth (``regular`` with its dimension, or
    ``mixed``) and what :func:`simulate.analysis.gali_runs.integrate` needs."""
    from chaplygin_nd.simulate.analysis import draws
    from chaplygin_nd.simulate.analysis.control import CHAOTIC_J, general_system
    from chaplygin_nd.simulate.dynamics import so
    from chaplygin_nd.simulate.integrators import heyoka_systems as hs

    out = []
    for m in (2, 3, 4):
        y0, pars = _pendula_orbits(m, count, seed)
        out.append({"name": f"uncoupled pendula, m = {m}", "truth": "regular", "dimension": m,
                    "system": pendula(m), "y0": y0, "pars": pars, "K": min(5, 2 * m)})

    def sphere(label, n):
        ens = draws.draw(f"gali-study {label}", "generic", n, count, seed)
        return ens, np.concatenate([so.vec(ens.M0), ens.gamma0], -1)

    ens, y0 = sphere("sphere3", 3)
    out.append({"name": f"Chaplygin sphere n = 3, J = diag{J3} (no symmetry)", "truth": "regular",
                "dimension": 2, "system": general_system(J3), "y0": y0,
                "pars": np.stack([ens.a, ens.b]), "K": 3, "time_factor": ens.time_factor, "n": 3,
                "symmetric": False})
    ens, y0 = sphere("full4", 4)
    out.append({"name": "axisymmetric n = 4 on P/SO(3)", "truth": "regular", "dimension": 2,
                "system": hs.full(4), "y0": y0, "pars": np.stack([ens.a, ens.b]), "K": 4,
                "time_factor": ens.time_factor, "n": 4})
    ens, y0 = sphere("control4", 4)
    out.append({"name": f"generic J = diag{CHAOTIC_J[4]} sphere n = 4 (control)", "truth": "mixed",
                "dimension": None, "system": general_system(CHAOTIC_J[4]), "y0": y0,
                "pars": np.stack([ens.a, ens.b]), "K": 3, "time_factor": ens.time_factor, "n": 4,
                "symmetric": False})
    return out


def standard_map(K: float, count: int, seed: int = SEED, steps: int = 4096) -> list:
    r"""GALI$_2$ verdicts of ``count`` orbits of the standard map at ``K`` (``steps`` iterations,
    :func:`simulate.analysis.gali.verdict` with time = iteration), the two vectors renormalised
    each step (their directions are what GALI reads)."""
    rng = np.random.default_rng([seed, 0x57A9, int(K * 100)])
    x, p = rng.uniform(0, 2 * np.pi, count), rng.uniform(0, 2 * np.pi, count)
    u = rng.standard_normal((count, 2, 2))
    u /= np.linalg.norm(u, axis=-1, keepdims=True)
    g = np.empty((steps + 1, count, 2))
    g[0] = gl.gali(u)
    for s in range(1, steps + 1):
        c = K * np.cos(x)
        dp = u[..., 1] + c[:, None] * u[..., 0]
        dx = u[..., 0] + dp
        p = p + K * np.sin(x)
        x = x + p
        u = np.stack([dx, dp], -1)
        u /= np.linalg.norm(u, axis=-1, keepdims=True)
        g[s] = gl.gali(u)
    t = np.arange(steps + 1, dtype=float)
    return [gl.verdict(t, g[:, k]) for k in range(count)]


def run(count: int, map_count: int, seed: int = SEED) -> list[dict]:
    """Every system of :func:`systems` and the two standard maps: ``[{name, truth, dimension,
    results: [GaliResult], seconds}]``."""
    rows = []
    for s in systems(count, seed):
        t0 = time.perf_counter()
        out = gali_runs.integrate(s["system"], s["y0"], s["pars"], K=s["K"], T=T, dt=DT, seed=seed,
                                  time_factor=s.get("time_factor"), n=s.get("n"),
                                  symmetric=s.get("symmetric", True), stride=8)
        rows.append({"name": s["name"], "truth": s["truth"], "dimension": s["dimension"],
                     "results": out["gali"], "seconds": time.perf_counter() - t0})
    for K, truth, dim in ((10.0, "chaotic", None), (0.0, "regular", 1)):
        t0 = time.perf_counter()
        rows.append({"name": f"standard map K = {K:g}", "truth": truth, "dimension": dim,
                     "results": standard_map(K, map_count, seed),
                     "seconds": time.perf_counter() - t0})
    return rows


def _upper(k: int, total: int) -> float:
    """The one-sided 95 % upper bound of a rate seen k times in total (exact binomial;
    3/total for k = 0)."""
    from scipy.stats import beta

    return 1.0 if k >= total else float(beta.ppf(0.95, k + 1, total - k))


def rates(rows: list[dict]) -> dict:
    """False alarms, misses and dimension errors over the systems of known truth."""
    reg = [(r, row["dimension"]) for row in rows if row["truth"] == "regular" for r in row["results"]]
    cha = [r for row in rows if row["truth"] == "chaotic" for r in row["results"]]
    fa = sum(r.cls == "chaotic" for r, _ in reg)
    miss = sum(r.cls == "regular" for r in cha)
    ok = [(r, d) for r, d in reg if r.cls == "regular"]
    over = sum(r.dimension > d for r, d in ok)
    under = sum(r.dimension < d for r, d in ok)
    return {"regular_orbits": len(reg), "chaotic_orbits": len(cha), "false_alarms": fa,
            "false_alarm_upper": _upper(fa, len(reg)), "misses": miss,
            "miss_upper": _upper(miss, len(cha)), "over": over, "over_upper": _upper(over, len(reg)),
            "under": under, "under_upper": _upper(under, len(reg)),
            "exact": sum(r.dimension == d for r, d in ok)}


def table(rows: list[dict]) -> str:
    """The per-system table (Markdown)."""
    lines = ["| system | true dimension | orbits | chaotic | dimension read (count) | seconds |",
             "|---|---|---|---|---|---|"]
    for row in rows:
        res = row["results"]
        dims: dict = {}
        for r in res:
            if r.cls == "regular":
                dims[r.dimension] = dims.get(r.dimension, 0) + 1
        read = ", ".join(f"{d}: {k}" for d, k in sorted(dims.items())) or "-"
        true = row["dimension"] if row["dimension"] is not None else row["truth"]
        lines.append(f"| {row['name']} | {true} | {len(res)} | "
                     f"{sum(r.cls == 'chaotic' for r in res)} | {read} | {row['seconds']:.1f} |")
    return "\n".join(lines)


#: the study's numbers (``python -m chaplygin_nd.simulate.analysis.gali_study``), cited by the rows
STUDY = ("simulate/analysis/gali_study.py (2026-11-27, seed 20261121, T = 4096, 32 orbits per flow, "
         "200 per map): 360 orbits of known torus dimension (uncoupled pendula m = 2, 3, 4; the "
         "3D Chaplygin sphere with J = diag(1, 2, 0.5); the n = 4 sphere on P/SO(3); the twist "
         "map, dimension 1) and 200 of the chaotic standard map K = 10: false alarms 0 of 360 "
         "(< 0.83 % at 95 %), misses 0 of 200 (< 1.5 % at 95 %); dimension read exactly on 358 "
         "of 360, one above (the n = 4 sphere read 3), one below (pendula m = 2 read 1; both "
         "< 1.3 % at 95 %); the generic-J n = 4 control: 30 of 32 chaotic")


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    quick = "--quick" in argv
    rows = run(8 if quick else 32, 64 if quick else 200)
    print(table(rows))
    print(rates(rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
