r"""What the scaling of the MEGNO tangent's log and moment does to the orbits of the evidence rows
(:mod:`simulate.analysis.chaos`): ``chaplygin bench megno-scaling`` writes ``megno-scaling.md`` and
``megno-scaling.json``.

heyoka's error control is absolute while the largest state component is below 1 and relative to
it above. The moment $m = \int_0^t s\,\sigma\,ds$ grows like $t$ on a torus, so carried unscaled it
loosens the stated tolerance on the physical state late in each orbit; the rows now carry
$2^{-16}\ell$ and $2^{-24}m$ (exact). Per row system, 8 of the row's drawn orbits (every
``len/8``-th in the schedule's order, the row's seed, tangents and horizon): the Taylor steps and
the integration CPU of the unscaled form and of the scaled one at the row's tolerance (and at
``LOOSER``), and the largest deviation of the physical state from a scaled run at $10^{-13}$ at
$T/4$ and $T$. The chaotic control is listed for its cost only (its orbits separate by nature).
"""

from __future__ import annotations

import json
import os
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

SEED = 20261121
REFERENCE = 1e-13
LOOSER = 1e-9
#: (label, row) of the row systems measured (``quick``: the first two)
CASES = (("open5", "S6:open-reduced-n5"), ("full4", "S5:reconstruction"),
         ("reduced", "S5:EJ-tori"), ("vertical4", "Th:Re-tori:frequencies n = 4"),
         ("vertical7", "Th:Re-tori:frequencies n = 7"), ("open6", "S6:open-reduced-n6"),
         ("control5", "S6:open-reduced-n5 control"))


def _case(label: str):
    """The row's setting, its drawn ensemble and initial states."""
    from chaplygin_nd.simulate.analysis import draws
    from chaplygin_nd.simulate.analysis import evidence_rows as er
    from chaplygin_nd.simulate.analysis.control import CHAOTIC_J
    from chaplygin_nd.simulate.dynamics.so import reduced_invariants

    if label.startswith("open"):
        n = int(label[4:])
        ens = draws.draw(f"S6:open-reduced-n{n}", "generic", n, er.OPEN_COUNTS[n][0], SEED)
        return er.open_setting(n), ens, er._full_state(ens)
    if label.startswith("control"):
        n = int(label[7:])
        ens = draws.draw(f"S6:open-reduced-n{n} control", "generic", n, er.OPEN_COUNTS[n][1], SEED)
        return er.open_setting(n, CHAOTIC_J[n]), ens, er._full_state(ens)
    if label.startswith("vertical"):
        n = int(label[8:])
        ens = draws.draw(f"Th:Re-tori:frequencies n={n}", "vertical", n, 50, SEED,
                         a_values=er.VERTICAL_A)
        return er.vertical_setting(n), ens, er._full_state(ens)
    if label == "reduced":
        ens = draws.draw("S5:EJ-tori", "generic", 4, er.LEVEL_SETS, SEED)
        return er.SETTINGS["reduced"], ens, reduced_invariants(ens.M0, ens.gamma0)
    ens = draws.draw("S5:reconstruction", "generic", 4, 200, SEED)
    return er.SETTINGS["full4"], ens, er._full_state(ens)


def _run(s, ens, y0, scales: tuple[float, float], tol: float) -> dict:
    """One batch of 8 orbits: steps, CPU of ``propagate_grid`` and the physical states."""
    from chaplygin_nd.simulate.analysis import chaos
    from chaplygin_nd.simulate.analysis import drawn_evidence as de
    from chaplygin_nd.simulate.integrators.heyoka_taylor import compiled_integrator

    system = chaos.tangent_system(de._system(replace(s, tangent="none")), *scales)
    ta, _, _ = compiled_integrator(system, "double", tol, compact=True, batch=de.BATCH,
                                   opt_level=de.OPT_LEVEL)
    d = y0.shape[1]
    u0 = chaos.initial_tangents(len(y0), d, SEED)
    if s.tangent == "V":
        u0 = de.v_tangents(u0, y0, s.n)
    ta.state[:] = np.concatenate([y0, u0, np.zeros((len(y0), 2))], axis=1).T
    b = ens.b if s.b_override is None else np.full(len(y0), float(s.b_override))
    ta.pars[:] = np.stack([ens.a, b])
    ta.set_time(0.0)
    t = np.arange(int(round(s.T / s.dt)) + 1) * s.dt
    start = time.process_time()
    _, states = ta.propagate_grid(t[:, None] * ens.time_factor[None, :])
    cpu = time.process_time() - start
    aux = np.abs(states[:, -2:, :]).max()
    return {"steps": int(sum(int(r[3]) for r in ta.propagate_res)), "cpu": cpu,
            "state": states[:, :d, :], "largest_aux": float(aux)}


def measure(label: str) -> dict:
    """The comparison of the module docstring for one row system."""
    from chaplygin_nd.simulate.analysis import chaos
    from chaplygin_nd.simulate.analysis import drawn_evidence as de

    s, ens, y0 = _case(label)
    order = de.schedule(ens)
    pick = order[::max(1, len(order) // de.BATCH)][:de.BATCH]
    ens, y0 = de.subset(ens, pick), y0[pick]
    scaled = (chaos.LOG_SCALE, chaos.MOMENT_SCALE)
    ref = _run(s, ens, y0, scaled, REFERENCE)["state"]
    out = {}
    for name, scales, tol in (("unscaled", (1.0, 1.0), s.tol), ("scaled", scaled, s.tol),
                              (f"scaled {LOOSER:g}", scaled, LOOSER)):
        r = _run(s, ens, y0, scales, tol)
        err = np.abs(r["state"] - ref).max(axis=1)            # (samples, lanes)
        out[name] = {"steps": r["steps"], "cpu": round(r["cpu"], 3), "largest_aux": r["largest_aux"],
                     "error_T/4": float(err[(len(err) - 1) // 4].max()),
                     "error_T": float(err[-1].max())}
    return out


def table(result: dict) -> str:
    """Markdown: one line per row system and form."""
    lines = ["| system (row) | form | Taylor steps | CPU s | largest carried aux | state error T/4 | "
             "state error T |", "|---|---|---|---|---|---|---|"]
    for label, row in CASES:
        for form, r in result.get(label, {}).items():
            lines.append(f"| {label} ({row}) | {form} | {r['steps']} | {r['cpu']:.2f} | "
                         f"{r['largest_aux']:.3g} | {r['error_T/4']:.1e} | {r['error_T']:.1e} |")
    return "\n".join(lines)


def main(out: Path, quick: bool = False) -> int:
    """Measure every case (``quick``: two) and write ``megno-scaling.md`` / ``.json`` into ``out``."""
    load0 = os.getloadavg()[0]
    result = {label: measure(label) for label, _ in (CASES[:2] if quick else CASES)}
    load = [round(load0, 2), round(os.getloadavg()[0], 2)]
    (out / "megno-scaling.json").write_text(json.dumps({"cases": result, "load": load}, indent=1),
                                            encoding="utf-8")
    text = (f"# The MEGNO tangent's scaling, per row system (8 orbits each; load {load[0]} -> "
            f"{load[1]} on {os.cpu_count()} cores)\n\n" + table(result) + "\n")
    (out / "megno-scaling.md").write_text(text, encoding="utf-8")
    print(text)
    return 0
