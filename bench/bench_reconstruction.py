r"""The deep look at the orbits of ``S5:reconstruction`` whose count exceeded 3, and the validation
of the re-examination rule (:mod:`simulate.analysis.reconstruction`,
:mod:`simulate.analysis.reconstruction_study`). ``chaplygin bench reconstruction`` writes
``reconstruction.md`` and ``reconstruction.json``.

Per orbit of the row's ``excess`` class (the row's draw and seed, read from the cache or measured):

* one straight run to $16T$ at the row's tolerance (``TOL`` of
  :mod:`simulate.analysis.drawn_evidence`) and one to $8T$ at $10^{-13}$: the lines must agree
  (integration error) — and the run to $4T$ sampled at $dt = 1$ (the row's ladder samples $4T$
  that sparsely) against $dt = 1/2$ (aliasing of the output grid);
* at $T, 2T, 4T, 8T, 16T$: the row's count, $D$, and the offending line — the member of the row's
  basis at its own horizon that the lattice at $8T$ does not hold with $|c| \le 4$ — its nearest
  line's frequency and amplitude (a frequency stays put, an artefact moves or shrinks);
* the rule's verdict at $8T$ (the lattice, its largest $|c|$ and $P_{false}$) and the nearest
  resonance $|\langle k, \omega\rangle|$, $0 < \max|k_i| \le 12$, of the lattice and of the two
  reduced frequencies alone, in Fourier bins $2\pi/T$.
"""

from __future__ import annotations

import json
import os
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

SEED = 20261121
HORIZONS = (1.0, 2.0, 4.0, 8.0, 16.0)


def _row(seed: int):
    from chaplygin_nd.simulate.analysis import draws
    from chaplygin_nd.simulate.analysis import evidence_rows as er

    out = er.full4_row(seed)
    ens = draws.draw("S5:reconstruction", "generic", 4, 200, seed)
    return out["results"], ens, er._full_state(ens), er.SETTINGS["full4"]


def _signals(setting, ens, y0, seed, index, factor, tol, dt=None):
    from chaplygin_nd.simulate.analysis import drawn_evidence as de

    s = replace(setting, name=f"{setting.name}-deep", T=setting.T * factor, tangent="none", tol=tol,
                dt=setting.dt if dt is None else dt)
    Z, _, _, extra = de._integrate(s, de.subset(ens, index), y0[index], seed)
    return Z, extra["drift"]


def _lines(Z, dt, T):
    from chaplygin_nd.simulate.analysis import naff
    from chaplygin_nd.simulate.analysis import reconstruction as rc5

    whole, first, second = naff.lines_batch(Z, dt)
    return [rc5.look(w, f, h, 1.0, T) for w, f, h in zip(whole, first, second)]


def _max_shift(a, b) -> float:
    """The largest distance of a line of ``a`` to the nearest line of ``b`` (distinct lines)."""
    return max((min(abs(f - g) for g, _ in b.lines) for f, _ in a.lines[:12]), default=0.0)


def examine(seed: int = SEED) -> list[dict]:
    """The table's records (module docstring)."""
    from chaplygin_nd.simulate.analysis import combinations, naff
    from chaplygin_nd.simulate.analysis import reconstruction as rc5
    from chaplygin_nd.simulate.analysis.frequencies import REGULAR

    results, ens, y0, setting = _row(seed)
    index = [k for k, r in enumerate(results) if r.cls == "excess"]
    T, dt = setting.T, setting.dt
    Z16, drift = _signals(setting, ens, y0, seed, index, max(HORIZONS), setting.tol)
    Z8f, drift_f = _signals(setting, ens, y0, seed, index, 8.0, 1e-13)
    Z4c, _ = _signals(setting, ens, y0, seed, index, 4.0, setting.tol, dt=2 * dt)
    n4 = int(round(4 * T / dt)) + 1
    looks = {}
    for h in HORIZONS:
        n = int(round(h * T / dt)) + 1
        whole, first, second = naff.lines_batch(Z16[:, :, :n], dt)
        looks[h] = [(rc5.look(w, f, s, h, T), naff.spectrum_from_lines(w, f, s),
                     naff.spectrum_from_lines(w[:2], f[:2], s[:2])) for w, f, s in zip(whole, first, second)]
    decided = rc5.examine_signals(Z16[:, :, :int(round(8 * T / dt)) + 1], dt, T)
    tol_check = [_max_shift(a, b) for a, b in zip(_lines(Z16[:, :, :int(round(8 * T / dt)) + 1], dt, 8 * T),
                                                  _lines(Z8f, dt, 8 * T))]
    grid_check = [_max_shift(a, b) for a, b in zip(_lines(Z16[:, :, :n4], dt, 4 * T),
                                                   _lines(Z4c, 2 * dt, 4 * T))]
    out = []
    for j, k in enumerate(index):
        r = results[k]
        e = decided[j]
        basis8 = e.looks[-1].fit.get("basis") or e.looks[-1].fit.get("closest_basis") or []
        at_row = looks[r.horizon][j][1] if r.horizon in looks else None
        row_basis = list(at_row.frequencies) if at_row is not None else r.frequencies
        tol8 = e.looks[-1].tol
        inv = looks[8.0][j][2].frequencies
        # the count's lines that are not a frequency of the rank-3 basis (or, unresolved, of the
        # reduced ones): the lines that made it excess
        known = basis8 or inv
        extra = [f for f in row_basis if min(abs(f - g) for g in known) > 1e-6]
        track = []
        for f in extra:
            for h in HORIZONS:
                lk = looks[h][j][0]
                g, a = min(lk.lines, key=lambda ln: abs(ln[0] - f), default=(float("nan"), 0.0))
                c = combinations.explain(g, basis8, 10 * tol8, 24) if basis8 else None
                track.append({"line": f, "horizon": h, "f": g, "amp": a, "D": lk.diffusion,
                              "bins_from_row": abs(g - f) / (2 * np.pi / (T * h)),
                              "in_lattice": list(c) if c is not None else None})
        out.append({
            "orbit": k, "a": r.a, "b": r.b, "scale": r.scale, "row_horizon": r.horizon,
            "row_frequencies": r.frequencies, "row_basis_straight": row_basis,
            "counts": {h: (looks[h][j][1].count if looks[h][j][1].diffusion < REGULAR else None)
                       for h in HORIZONS},
            "D": {h: looks[h][j][1].diffusion for h in HORIZONS},
            "reduced": inv, "rule": e.cls, "reason": e.reason,
            "lattice": basis8, "max_c": e.looks[-1].fit.get("max_c"),
            "p_false": e.looks[-1].fit.get("p_false"), "track": track,
            "resonance_P": {**rc5.near_resonance(basis8), "bins_T": rc5.near_resonance(basis8)["value"]
                            / (2 * np.pi / T)} if basis8 else {},
            "resonance_reduced": {**rc5.near_resonance(inv), "bins_T": rc5.near_resonance(inv)["value"]
                                  / (2 * np.pi / T)} if len(inv) else {},
            "tolerance_shift": tol_check[j], "grid_shift": grid_check[j],
            "drift": [float(drift[j]), float(drift_f[j])]})
    return out


def _table(rows: list[dict]) -> str:
    head = ("| orbit (a, b, s) | row: horizon, frequencies | count / D at T, 2T, 4T, 8T, 16T | "
            "offending line: f (amp) at T .. 16T | rule at 8T | nearest resonance (bins 2π/T) | "
            "tol 1e-10 vs 1e-13, dt 1/2 vs 1 |\n|---|---|---|---|---|---|---|\n")
    lines = []
    for r in rows:
        counts = ", ".join(f"{r['counts'][h] if r['counts'][h] is not None else 'u'}"
                           f"/{r['D'][h]:.0e}" for h in HORIZONS)
        track = "; ".join(f"{t['f']:.7f} ({t['amp']:.2f})" for t in r["track"])
        res = r["resonance_P"]
        lines.append(
            f"| {r['orbit']} ({r['a']:g}, {r['b']:g}, {r['scale']:g}) | {r['row_horizon']:g}T: "
            f"{', '.join(f'{f:.7f}' for f in r['row_frequencies'])} | {counts} | {track} | "
            f"{r['rule']}: {r['reason']} | "
            + (f"k = {tuple(res['k'])}: {res['bins_T']:.2f}" if res else "—")
            + f" | {r['tolerance_shift']:.1e}, {r['grid_shift']:.1e} |")
    return head + "\n".join(lines) + "\n"


def main(out: Path, quick: bool = False) -> int:
    """The deep look at the row's excess orbits (and, unless ``quick``, the validation study on a
    fresh seed); writes ``reconstruction.md`` and ``reconstruction.json`` into ``out``."""
    from chaplygin_nd.simulate.analysis import reconstruction_study as st

    load0 = os.getloadavg()[0]
    start = time.process_time()
    rows = examine()
    result = {"orbits": rows}
    if not quick:
        study = st.run(100, 20270101)
        result["study"] = {"seed": 20270101, "rates": st.rates(study),
                           "systems": [{k: v for k, v in s.items()} for s in study]}
    result.update(cpu=round(time.process_time() - start, 1),
                  load=[round(load0, 2), round(os.getloadavg()[0], 2)])
    (out / "reconstruction.json").write_text(json.dumps(result, indent=1, default=float),
                                             encoding="utf-8")
    text = "# S5:reconstruction — the orbits whose count exceeded 3\n\n" + _table(rows)
    if "study" in result:
        text += "\n" + "\n".join(f"- {k}: {n} of {t} (< {100 * u:.1f} % at 95 %)"
                                 for k, (n, t, u) in result["study"]["rates"].items()) + "\n"
    (out / "reconstruction.md").write_text(text, encoding="utf-8")
    print(text)
    return 0
