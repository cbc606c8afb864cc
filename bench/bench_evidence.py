r"""The validation study of the evidence rows' chaos rule: systems whose answer is known,
drawn orbits of each, every indicator the rows use, and the confusion table of each candidate rule.

Systems (drawn by :func:`simulate.analysis.draws.draw` with the ledger's default seed; the rows'
machinery, :func:`simulate.analysis.drawn_evidence.measure`, heyoka tolerance ``TOL`` = $10^{-9}$):

* **integrable** — the 3D Chaplygin sphere with the *generic* mass tensor $\mathbb{J} = \mathrm{diag}(1, 2,
  0.5)$ (inertia $\mathrm{diag}(2.5, 1.5, 3)$; integrable by Chaplygin's theorem, no symmetry); the
  $n = 4$ axisymmetric sphere on $P$ and its reduced system eq:red-system (Euler–Jacobi); the free
  rigid body on $\mathfrak{so}(4)$ (Manakov: the same generic $\mathbb{J}$ as the $n = 4$ control, $b = 0$,
  with $\gamma$ carried along); orbits on $\mathcal V$ ($n = 4$ and $6$, $a$ as in the row, 0
  included; Th:Re's closed form), with the tangent vector in $T\mathcal V$ and, apart, in the whole
  space (for even $n$ the latter grows like $t^p$, $p \approx 2$: $\langle Y\rangle \to 4$);
* **chaotic** — the Chirikov standard map at $K = 10$ (no island of measurable size; Lyapunov
  exponent $\ln(K/2) + O(K^{-2})$, Chirikov, Phys. Rep. 52 (1979) 263), which ties the scale of
  $\langle Y\rangle$ to the literature: under chaos $\langle Y\rangle \approx \lambda t/2$; the twist map
  $K = 0$ is its integrable partner;
* **mixed** — the generic non-symmetric $n = 4$ and $n = 5$ spheres (``CHAOTIC_J``, the rows'
  controls): no integral beyond $H$ and $p(\lambda, \sigma)$ is known and most drawn orbits are
  chaotic, but the phase space may hold regular (KAM) orbits, so the truth of a single orbit is not
  known; they give the fraction a control shows, not a miss rate.

Indicators per orbit: $\langle Y\rangle$ at $T/8, T/4, T/2, T$ (the ladder), the growth exponent of the
tangent vector over the last doubling ($p$ of $t^p$: an FLI read over a ladder), the finite-time
Lyapunov exponent, the frequency diffusion $D$, the frequency class and the drift of the integrals.
Rules compared: the old single threshold ($\langle Y\rangle(T) \le 2.5$ regular, $\ge 4$ chaotic), the MEGNO
ladder (:func:`simulate.analysis.chaos.ladder_class`) and the tangent-growth ladder ($p \le$
``P_REGULAR`` regular, $\ge$ ``P_CHAOTIC`` chaotic). Writes ``evidence.json``, ``evidence.md`` and
``evidence.png`` into the output folder, and (``planted``, :mod:`bench.planted`) the planted-defect table.

Run: ``chaplygin bench evidence`` (``--quick``: 8 orbits per system, 64 map orbits).
"""

from __future__ import annotations

import json
import os
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

SEED = 20261121
COUNT, QUICK_COUNT = 32, 8
MAP_COUNT, MAP_STEPS = 200, 4096
P_REGULAR, P_CHAOTIC = 3.0, 6.0
TRUTHS = ("integrable", "chaotic", "mixed")
J3 = (1.0, 2.0, 0.5)


def _systems(count: int):
    """``(name, truth, setting, ensemble, y0)`` of every flow of the study."""
    from chaplygin_nd.simulate.analysis import draws
    from chaplygin_nd.simulate.analysis import evidence_rows as er
    from chaplygin_nd.simulate.analysis.control import CHAOTIC_J
    from chaplygin_nd.simulate.analysis.drawn_evidence import Setting
    from chaplygin_nd.simulate.dynamics.so import reduced_invariants

    def gen(label, n, family="generic", **kw):
        ens = draws.draw(f"bench-evidence {label}", family, n, count, SEED, **kw)
        return ens, er._full_state(ens)

    out = []
    ens, y0 = gen("sphere3", 3)
    out.append(("Chaplygin sphere n=3, generic J", "integrable",
                Setting("study-sphere3", "control", 3, 4096.0, 0.5, J=J3, expected=2), ens, y0))
    ens, y0 = gen("full4", 4)
    out.append(("axisymmetric n=4 on P", "integrable",
                replace(er.SETTINGS["full4"], name="study-full4"), ens, y0))
    ens, _ = gen("reduced4", 4)
    out.append(("reduced n=4 (Euler-Jacobi)", "integrable",
                replace(er.SETTINGS["reduced"], name="study-reduced"), ens,
                reduced_invariants(ens.M0, ens.gamma0)))
    ens, y0 = gen("manakov4", 4)
    out.append(("Manakov top so(4) (b = 0)", "integrable",
                Setting("study-manakov", "control", 4, 4096.0, 0.5, observables="four",
                        J=CHAOTIC_J[4], b_override=0.0), ens, y0))
    for n in (4, 6):   # even n: in the whole space the tangent grows like t^p, p ~ 2
        ens, y0 = gen(f"vertical{n}", n, "vertical", a_values=er.VERTICAL_A)   # a = 0: equilibria
        v = er.vertical_setting(n)
        out.append((f"V, n={n}, tangent in TV", "integrable", replace(v, name=f"study-v{n}"),
                    ens, y0))
        out.append((f"V, n={n}, tangent in the whole space", "integrable",
                    replace(v, name=f"study-v{n}-full", tangent="full"), ens, y0))
    ens, y0 = gen("control4", 4)
    out.append(("generic J sphere n=4 (control)", "mixed",
                replace(er.SETTINGS["control4"], name="study-control4"), ens, y0))
    ens, y0 = gen("control5", 5)
    out.append(("generic J sphere n=5 (control)", "mixed",
                Setting("study-control5", "control", 5, 4096.0, 0.5, observables="invariant+general",
                        invariant=2, limit=6, J=CHAOTIC_J[5]), ens, y0))
    return out


def standard_map(K: float, count: int, steps: int, seed: int = SEED) -> dict:
    r"""MEGNO of the standard map $p' = p + K\sin x$, $x' = x + p'$ (mod $2\pi$) from ``count`` drawn
    points: $Y(N) = \frac2N\sum_{k\le N} k\ln(\|\delta_k\|/\|\delta_{k-1}\|)$, $\langle Y\rangle(N)$ its mean,
    at $N/8, N/4, N/2, N$; the growth exponent of $\|\delta\|$ over the last doubling; $\ln\|\delta_N\|/N$."""
    rng = np.random.default_rng([seed, int(1000 * K)])
    x, p = rng.uniform(0, 2 * np.pi, count), rng.uniform(0, 2 * np.pi, count)
    d = rng.standard_normal((2, count))
    d /= np.linalg.norm(d, axis=0)
    ell = np.zeros(count)
    ells = np.zeros((steps + 1, count))
    ysum = np.zeros(count)
    Y = np.zeros((steps + 1, count))
    for k in range(1, steps + 1):
        dp = d[1] + K * np.cos(x) * d[0]
        dx = d[0] + dp
        p = (p + K * np.sin(x)) % (2 * np.pi)
        x = (x + p) % (2 * np.pi)
        norm = np.hypot(dx, dp)
        d = np.array([dx, dp]) / norm
        ell += np.log(norm)
        ells[k] = ell
        ysum += k * np.log(norm)
        Y[k] = 2 * ysum / k
    mean = np.cumsum(Y, axis=0) / np.maximum(np.arange(steps + 1), 1)[:, None]
    idx = [steps // 8, steps // 4, steps // 2, steps]
    power = (ells[steps] - ells[steps // 2]) / np.log(2.0)
    return {"ladder": mean[idx].T.tolist(), "power": power.tolist(),
            "lyapunov": (ell / steps).tolist(), "horizons": idx}


def _classes(ladder, power, megno) -> dict:
    from chaplygin_nd.simulate.analysis import chaos

    p = float(power)
    fli = ("undecided" if not np.isfinite(p) else "chaotic" if p >= P_CHAOTIC
           else "regular" if p <= P_REGULAR else "undecided")
    return {"single threshold": chaos.megno_class(megno), "MEGNO ladder": chaos.ladder_class(ladder),
            "tangent-growth ladder": fli}


def run(count: int, map_count: int) -> dict:
    """Measure every system; per orbit the indicators and the class by each rule."""
    from chaplygin_nd.simulate.analysis.drawn_evidence import measure

    orbits, systems = [], []
    for name, truth, setting, ens, y0 in _systems(count):
        start = time.process_time()
        res = measure(setting, ens, y0, SEED)
        cpu = time.process_time() - start
        systems.append({"system": name, "truth": truth, "orbits": len(res), "cpu": round(cpu, 1),
                        "T": setting.T})
        for r in res:
            orbits.append({"system": name, "truth": truth, "ladder": r.ladder, "power": r.power,
                           "megno": r.megno, "lyapunov": r.lyapunov, "diffusion": r.diffusion,
                           "cls": r.cls, "count": r.count, "drift": r.drift,
                           "classes": _classes(r.ladder, r.power, r.megno)})
    for K, truth in ((10.0, "chaotic"), (0.0, "integrable")):
        name = f"standard map K = {K:g}"
        sm = standard_map(K, map_count, MAP_STEPS)
        systems.append({"system": name, "truth": truth, "orbits": map_count, "cpu": 0.0,
                        "T": MAP_STEPS, "lyapunov_mean": float(np.mean(sm["lyapunov"])),
                        "slope_mean": float(np.mean([2 * (y[3] - y[2]) / (MAP_STEPS / 2)
                                                     for y in sm["ladder"]])),
                        "literature_lyapunov": float(np.log(K / 2)) if K else 0.0})
        for y, p, lam in zip(sm["ladder"], sm["power"], sm["lyapunov"]):
            orbits.append({"system": name, "truth": truth, "ladder": y, "power": p, "megno": y[-1],
                           "lyapunov": lam, "diffusion": float("nan"), "cls": "", "count": -1,
                           "drift": float("nan"), "classes": _classes(y, p, y[-1])})
    return {"systems": systems, "orbits": orbits, "confusion": confusion(orbits)}


def confusion(orbits) -> dict:
    """Per rule: counts of (class, truth), the false-alarm rate P(chaotic | integrable), the miss
    rate P(regular | chaotic) and the undecided rates, with 95 % upper bounds when a count is 0."""
    out = {}
    for rule in orbits[0]["classes"]:
        table = {c: {t: 0 for t in TRUTHS} for c in ("regular", "chaotic", "undecided")}
        for o in orbits:
            table[o["classes"][rule]][o["truth"]] += 1
        ni, nc, nm = (sum(table[c][t] for c in table) for t in TRUTHS)
        out[rule] = {"table": table, "integrable": ni, "chaotic": nc, "mixed": nm,
                     "false_alarm": table["chaotic"]["integrable"] / ni,
                     "miss": table["regular"]["chaotic"] / nc,
                     "undecided_integrable": table["undecided"]["integrable"] / ni,
                     "undecided_chaotic": table["undecided"]["chaotic"] / nc,
                     "mixed_chaotic": table["chaotic"]["mixed"] / max(nm, 1),
                     "upper95_zero_integrable": 3.0 / ni, "upper95_zero_chaotic": 3.0 / nc}
    return out


def per_system(result) -> list[dict]:
    """Per system and rule: how many orbits each class got."""
    rows = []
    for s in result["systems"]:
        mine = [o for o in result["orbits"] if o["system"] == s["system"]]
        row = {"system": s["system"], "truth": s["truth"], "orbits": len(mine)}
        for rule in mine[0]["classes"]:
            row[rule] = {c: sum(o["classes"][rule] == c for o in mine)
                         for c in ("regular", "chaotic", "undecided")}
        row["drift_max"] = max((o["drift"] for o in mine if np.isfinite(o["drift"])), default=None)
        rows.append(row)
    return rows


def markdown(result) -> str:
    lines = ["# Validation study of the chaos rule (bench/bench_evidence.py)", "",
             f"Load average at start / end: {result['load'][0]} / {result['load'][1]} on "
             f"{result['cores']} cores; {result['count']} orbits per flow, {result['map_count']} per map.", "",
             "## Confusion tables (class x truth)", ""]
    for rule, c in result["confusion"].items():
        t = c["table"]
        lines += [f"### {rule}", "", "| class | truly integrable | truly chaotic | mixed (controls) |",
                  "|---|---|---|---|"]
        lines += [f"| {k} | {t[k]['integrable']} | {t[k]['chaotic']} | {t[k]['mixed']} |" for k in t]
        lines += ["", f"false alarms P(chaotic | integrable) = {c['false_alarm']:.3f} "
                      f"(of {c['integrable']}; 0 means < {c['upper95_zero_integrable']:.3f} at 95 %); "
                      f"misses P(regular | chaotic) = {c['miss']:.3f} (of {c['chaotic']}; 0 means < "
                      f"{c['upper95_zero_chaotic']:.3f} at 95 %); undecided: "
                      f"{c['undecided_integrable']:.3f} of the integrable, "
                      f"{c['undecided_chaotic']:.3f} of the chaotic; the mixed controls: "
                      f"{c['mixed_chaotic']:.3f} chaotic", ""]
    lines += ["## Per system", "", "| system | truth | orbits | single threshold r/c/u | MEGNO ladder "
              "r/c/u | tangent growth r/c/u | max drift of the integrals |", "|---|---|---|---|---|---|---|"]
    for r in per_system(result):
        cells = [f"{r[k]['regular']}/{r[k]['chaotic']}/{r[k]['undecided']}"
                 for k in ("single threshold", "MEGNO ladder", "tangent-growth ladder")]
        drift = f"{r['drift_max']:.1e}" if r["drift_max"] is not None else "-"
        lines.append(f"| {r['system']} | {r['truth']} | {r['orbits']} | " + " | ".join(cells)
                     + f" | {drift} |")
    for s in result["systems"]:
        if "slope_mean" in s and s["literature_lyapunov"]:
            lines += ["", f"{s['system']}: 2 x slope of <Y> over the last doubling = "
                          f"{s['slope_mean']:.3f}; finite-time Lyapunov exponent {s['lyapunov_mean']:.3f}; "
                          f"literature ln(K/2) = {s['literature_lyapunov']:.3f}"]
    return "\n".join(lines) + "\n"


def figure(result, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(16, 5))
    names = [s["system"] for s in result["systems"]]
    colours = plt.cm.tab20(np.linspace(0, 1, len(names)))
    frac = np.array([0.125, 0.25, 0.5, 1.0])
    for name, col in zip(names, colours):
        mine = [o for o in result["orbits"] if o["system"] == name]
        truth = mine[0]["truth"]
        style = {"integrable": "-", "chaotic": "--", "mixed": ":"}[truth]
        for i, o in enumerate(mine[:40]):
            axes[0].plot(frac, np.maximum(o["ladder"], 1e-2), style, color=col, alpha=0.5, lw=0.8,
                         label=name if i == 0 else None)
        g = [o["ladder"][-1] - o["ladder"][-2] for o in mine]
        y = [o["ladder"][-1] for o in mine]
        axes[1].scatter(np.maximum(y, 1e-2), np.clip(g, -5, 1e4), s=10, color=col,
                        marker="o" if truth == "integrable" else "x")
        axes[2].scatter(np.maximum(y, 1e-2), np.clip([o["power"] for o in mine], -5, 1e4), s=10,
                        color=col, marker="o" if truth == "integrable" else "x")
    from chaplygin_nd.simulate.analysis import chaos

    axes[0].set(xscale="log", yscale="log", xlabel="horizon / T", ylabel="<Y>",
                title="<Y> over the horizon ladder\n(solid: integrable, dashed: chaotic, dotted: mixed)")
    axes[0].legend(fontsize=7)
    axes[1].set(xscale="log", yscale="symlog", xlabel="<Y>(T)", ylabel="<Y>(T) - <Y>(T/2)",
                title="the MEGNO ladder rule\n(o integrable, x chaotic or mixed; lines: the thresholds)")
    axes[1].axhline(chaos.LADDER_GROWTH, color="r", lw=0.8)
    axes[1].axhline(chaos.LADDER_BOUNDED, color="g", lw=0.8)
    axes[1].axhline(-chaos.LADDER_BOUNDED, color="g", lw=0.8)
    axes[1].axvline(chaos.MEGNO_CHAOTIC, color="r", lw=0.8, ls=":")
    axes[2].set(xscale="log", yscale="symlog", xlabel="<Y>(T)", ylabel="p over the last doubling",
                title="tangent growth t^p over the last doubling\n(an FLI read over the ladder)")
    axes[2].axhline(P_REGULAR, color="g", lw=0.8)
    axes[2].axhline(P_CHAOTIC, color="r", lw=0.8)
    fig.tight_layout()
    from chaplygin_nd.bench.report import save_figure

    save_figure(fig, path)
    plt.close(fig)


def main(out: Path, quick: bool = False) -> int:
    """Run the study (and the planted defects unless ``quick``); write the files into ``out``
    (``EVIDENCE_REPLOT=1``: only re-render them from the last ``evidence.json``)."""
    if os.environ.get("EVIDENCE_REPLOT") == "1":      # re-render the last run's files
        result = json.loads((out / "evidence.json").read_text())
        _write_all(out, result)
        return 0
    load0 = os.getloadavg()[0]
    count, map_count = (QUICK_COUNT, 64) if quick else (COUNT, MAP_COUNT)
    start = time.process_time()
    result = run(count, map_count)
    result.update(count=count, map_count=map_count, cpu=round(time.process_time() - start, 1),
                  load=[round(load0, 2), round(os.getloadavg()[0], 2)], cores=os.cpu_count())
    result["per_system"] = per_system(result)
    if not quick and os.environ.get("EVIDENCE_PLANTED", "1") == "1":
        from chaplygin_nd.bench import planted

        result["planted"] = planted.run()
    _write_all(out, result)
    return 0


def _write_all(out: Path, result: dict) -> None:
    from chaplygin_nd.bench.report import write_atomic

    out.mkdir(parents=True, exist_ok=True)
    text = markdown(result)
    if "planted" in result:
        from chaplygin_nd.bench import planted

        text += "\n" + planted.markdown(result["planted"])
    write_atomic(out / "evidence.json", json.dumps(result, indent=1, default=float) + "\n")
    write_atomic(out / "evidence.md", text)
    figure(result, out / "evidence.png")
    print(text)
