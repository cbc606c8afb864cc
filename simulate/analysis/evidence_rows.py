r"""The drawn experiments behind the evidence rows: which ensembles, which settings,
the re-run of unresolved orbits at a longer $T$, and the rules, all fixed before the runs.

Ensembles (:mod:`simulate.analysis.draws`, the ledger's seed; $(a, b)$ over $\{-0.9, -0.5, 0.5, 2\}\times\{0.5, 2\}$,
energy scales $0.5, 1, 2$):

* ``reduced``  — S5:EJ-tori: ``LEVEL_SETS`` = 50 generic $n = 4$ points, each with ``len(SHIFTS)`` = 3
  more orbits on its level set of $(F_1, F_2, F_3, H)$ (:func:`simulate.analysis.evidence.level_set_points`):
  200 orbits of eq:red-system, expected 2 frequencies;
* ``full4``    — S5:reconstruction: 200 generic $n = 4$ orbits of eq:motion-general, expected 3 on $P$
  (2 reduced + rank $SO(3)$), and 2 from the $SO(3)$-invariant observables alone;
* ``vertical`` — Th:Re-tori:frequencies: 50 points of $\mathcal V$ for each $n = 4..7$ with
  $a \in \{-0.9, -0.5, 0, 0.5, 2\}$; expected $\lfloor(n-1)/2\rfloor$, 0 at $a = 0$;
* ``control4`` — 50 generic $n = 4$ orbits of the general-$\mathbb{J}$ sphere, $\mathbb{J}$ =
  ``CHAOTIC_J[4]`` (:mod:`simulate.analysis.control`), the same analysis: the control of the three rows.

Orbits: $T = 4096$, $dt = 1/2$ at energy scale 1 (reduced and $P$), $T = 3000$, $dt = 5/4$ ($\mathcal V$,
$n \le 6$; 6000 for $n = 7$); heyoka tolerance ``TOL`` = $10^{-9}$ (:mod:`simulate.analysis.drawn_evidence`).
The first ``RERUN`` = 4 unresolved orbits of an ensemble (in draw order; for $\mathcal V$ the first
of each $n$) are integrated again with ``LONGER`` = 4 times $T$ and classified again.
"""

from __future__ import annotations

import numpy as np
from chaplygin_nd.simulate.analysis import draws
from chaplygin_nd.simulate.analysis.control import CHAOTIC_J
from chaplygin_nd.simulate.analysis.drawn_evidence import Setting, measure, merge_longer, subset
from chaplygin_nd.simulate.dynamics import so

__all__ = ["LEVEL_SETS", "SHIFTS", "RERUN", "LONGER", "reduced_row", "full4_row", "vertical_row",
           "control4_row", "start_shared", "run_with_rerun", "SETTINGS", "open_row", "open_setting",
           "OPEN_COUNTS"]

LEVEL_SETS = 50
SHIFTS = (0.04, 0.08, 0.12)     # times the energy scale: distances across the flow on a level set
RERUN, LONGER = 4, 4.0
#: the horizon ladder of the frequencies: unresolved orbits again at 2T, then 4T
LADDER_FACTORS = (2.0, 4.0)
VERTICAL_A = (-0.9, -0.5, 0.0, 0.5, 2.0)
VERTICAL_T = {4: 3000.0, 5: 3000.0, 6: 3000.0, 7: 6000.0}
VERTICAL_DT = 1.25

SETTINGS = {
    "reduced": Setting("reduced", "reduced", 4, 4096.0, 0.5, observables="reduced", expected=2),
    "full4": Setting("full4", "full", 4, 4096.0, 0.5, observables="four", expected=3,
                     invariant=2),
    "control4": Setting("control4", "control", 4, 4096.0, 0.5, observables="four",
                        J=CHAOTIC_J[4], expected=3),
}


def _full_state(ens) -> np.ndarray:
    return np.concatenate([so.vec(ens.M0), ens.gamma0], axis=-1)


def run_with_rerun(setting: Setting, ens, y0: np.ndarray, seed: int, rerun: int | None = None
                   ) -> dict:
    """The horizon ladder of the frequencies: every orbit at ``T``; the unresolved ones (all, or
    the first ``rerun``) again at ``2T`` and those still unresolved at ``4T`` (frequency-only
    runs continued from the state at the shorter horizon, :mod:`simulate.analysis.continuation`;
    :func:`simulate.analysis.drawn_evidence.merge_longer`: the chaos indicator stays that of ``T``).
    ``{"results": the merged records, "at_T": the records at T, "rerun_index": the orbits re-run,
    "rerun": their merged records, "ladder": {factor: orbits run at it}}``."""
    from chaplygin_nd.simulate.analysis import continuation
    from chaplygin_nd.simulate.analysis.drawn_evidence import settings

    base = settings(setting, ens, y0, seed)
    try:
        results = measure(setting, ens, y0, seed, on_signals=lambda Z, final: continuation.remember(
            base, 1.0, range(len(y0)), Z, final))
        todo = [k for k, r in enumerate(results) if r.cls == "unresolved"]
        todo = todo if rerun is None else todo[:rerun]
        first, merged, ladder = list(todo), list(results), {}
        previous = 1.0
        for factor in LADDER_FACTORS:
            continuation.retain(base, previous, todo)
            if not todo:
                break
            ladder[factor] = len(todo)
            longer = continuation.extend(setting, ens, y0, seed, factor, todo)
            for k, r in zip(todo, longer):
                merged[k] = merge_longer(merged[k], r, factor)
            todo = [k for k in todo if merged[k].cls == "unresolved"]
            previous = factor
    finally:
        continuation.forget(base)
    return {"results": merged, "at_T": results, "rerun_index": first,
            "rerun": [merged[k] for k in first], "ladder": ladder}


def reduced_row(seed: int) -> dict:
    """The S5:EJ-tori ensemble (module docstring); also ``groups``: the orbit indices of each level
    set and ``failed``: level-set points Newton did not reach (reported, not replaced)."""
    from chaplygin_nd.simulate.analysis.evidence import level_set_points
    from chaplygin_nd.simulate.dynamics.so import reduced_invariants

    base = draws.draw("S5:EJ-tori", "generic", 4, LEVEL_SETS, seed)
    r0 = reduced_invariants(base.M0, base.gamma0)
    rows: list = []
    pick: list = []
    groups: list = []
    failed = 0
    for k in range(base.count):
        group = [len(rows)]
        rows.append(r0[k])
        pick.append(k)
        for shift in SHIFTS:
            try:
                rows.append(level_set_points(r0[k], (shift * base.scale[k],), base.a[k], base.b[k])[0])
            except RuntimeError:
                failed += 1
                continue
            group.append(len(rows) - 1)
            pick.append(k)
        groups.append(group)
    ens = subset(base, pick)
    out = run_with_rerun(SETTINGS["reduced"], ens, np.array(rows), seed)
    out.update(groups=groups, failed=failed)
    return out


def full4_row(seed: int) -> dict:
    """The S5:reconstruction ensemble on $P$ (each orbit also counted on its two $SO(3)$-invariant
    observables alone: ``invariant_count``)."""
    ens = draws.draw("S5:reconstruction", "generic", 4, 200, seed)
    return run_with_rerun(SETTINGS["full4"], ens, _full_state(ens), seed)


#: orbits of the n = 4 control (50: its mass tensor makes it 2x costlier per orbit,
#: and its power is established by the validation study, bench/bench_evidence.py)
CONTROL4_COUNT = 50


def control4_row(seed: int) -> dict:
    """The chaotic control: ``CONTROL4_COUNT`` generic $n = 4$ orbits of the general-$\\mathbb{J}$
    sphere, at $T$ only (its unresolved orbits are not re-run: for the control they are the
    expected outcome)."""
    ens = draws.draw("control4", "generic", 4, CONTROL4_COUNT, seed)
    return {"results": measure(SETTINGS["control4"], ens, _full_state(ens), seed), "rerun": [],
            "rerun_index": []}


#: Orbits per open-problem row (axisymmetric, general-J control): n = 5 is row S6:open-reduced-n5;
#: n = 6 is row S6:open-reduced-n6, fewer orbits: its field costs ~1.5x.
OPEN_COUNTS = {5: (100, 24), 6: (16, 4)}
N5_COUNT, N5_CONTROL = OPEN_COUNTS[5]


def open_setting(n: int, J: tuple[float, ...] = ()) -> Setting:
    r"""The setting of the open-problem rows in dimension ``n`` (axisymmetric, or the general-$\mathbb{J}$
    control when ``J`` is given): $T = 4096$, $dt = 1/2$, the two $SO(n-1)$-invariant signals counted
    apart. For $n = 5$ these are the settings of row S6:open-reduced-n5 unchanged (names, cache keys)."""
    name = f"control{n}" if J else f"full{n}"
    return Setting(name, "control" if J else "full", n, 4096.0, 0.5,
                   observables="invariant+general", invariant=2, limit=n + 1, J=tuple(J))


N5_SETTING = open_setting(5)


def open_row(n: int, seed: int, count: int | None = None, control: int | None = None) -> dict:
    r"""The open problem in dimension $n$ (rows S6:open-reduced-n5, S6:open-reduced-n6): ``count``
    generic orbits of the axisymmetric sphere and ``control`` of the general-$\mathbb{J}$ sphere
    ``CHAOTIC_J[n]``, the same analysis (the $SO(n-1)$-invariant observables counted apart); defaults
    from ``OPEN_COUNTS``. The $n = 4$ control is :func:`full4_row`."""
    count = OPEN_COUNTS[n][0] if count is None else count
    control = OPEN_COUNTS[n][1] if control is None else control
    ens = draws.draw(f"S6:open-reduced-n{n}", "generic", n, count, seed)
    # the frequency ladder for the first RERUN unresolved only (cost; the row's rule counts the
    # resolved orbits, it does not need every orbit resolved)
    sym = run_with_rerun(open_setting(n), ens, _full_state(ens), seed, rerun=RERUN)
    out = {"symmetric": sym, "control": []}
    if control:
        cens = draws.draw(f"S6:open-reduced-n{n} control", "generic", n, control, seed)
        out["control"] = measure(open_setting(n, CHAOTIC_J[n]), cens, _full_state(cens), seed)
    return out


def n5_row(seed: int) -> dict:
    r"""The open problem for $n = 5$ (row S6:open-reduced-n5): :func:`open_row` at $n = 5$."""
    return open_row(5, seed)


def vertical_setting(n: int) -> Setting:
    r"""The setting of the $\mathcal V$ orbits in dimension $n$ (expected $\lfloor(n-1)/2\rfloor$ = rank
    $SO(n-1)$, 0 at $a = 0$)."""
    return Setting(f"vertical{n}", "full", n, VERTICAL_T[n], VERTICAL_DT, observables="general",
                   expected=int((n - 1) // 2), vertical=True, tangent="V")


def vertical_row(seed: int, per_n: int = 50) -> dict:
    """Th:Re-tori:frequencies: ``{n: run_with_rerun(...)}`` for $n = 4..7$, each with ``zeta``: the
    comparison of every orbit with the exact frequencies of Th:Re (:func:`zeta_check`)."""
    out = {}
    for n in VERTICAL_T:
        ens = draws.draw(f"Th:Re-tori:frequencies n={n}", "vertical", n, per_n, seed,
                         a_values=VERTICAL_A)
        out[n] = run_with_rerun(vertical_setting(n), ens, _full_state(ens), seed)
        out[n]["zeta"] = zeta_check(ens, out[n]["results"], vertical_setting(n).T)
    return out


#: an orbit on V agrees with Th:Re iff each measured frequency is within this many resolutions
#: 2 pi / T of a combination of the exact rates (the study's V orbits: bench/bench_evidence.py)
ZETA_MATCH = 0.01


def zeta_rates(ens) -> list[np.ndarray]:
    r"""Per orbit the rates $\lambda_i > 0$ of $\zeta(M_0, \gamma_0)$ (Th:Re, generated kernel;
    $\mathrm{spec}\,\zeta = \{\pm i\lambda_i\}$, each once), at energy scale 1 (divided by the orbit's $s$)."""
    from chaplygin_nd.simulate.kernels import active

    zeta = active().require("zeta")
    out = []
    for k in range(ens.count):
        z = zeta(ens.M0[k:k + 1], ens.gamma0[k:k + 1], float(ens.a[k]), float(ens.b[k]))[0]
        lam = np.sort(np.abs(np.linalg.eigvals(z).imag))[::-2] / ens.scale[k]
        out.append(np.sort(lam[lam > 1e-9 * max(1.0, float(np.max(lam, initial=0.0)))]))
    return out


def zeta_check(ens, results, T: float, K: int = 2) -> list[dict]:
    r"""Each drawn orbit of $\mathcal V$ against the exact answer of Th:Re: $M(t)$ and $\gamma(t)$ move by
    $\exp(t\zeta)$, so every line of the observables is an integer combination of the rates
    $\lambda_i$ of $\zeta$ (:func:`zeta_rates`) and the number of independent frequencies is the
    number of rates. Per orbit: ``rates``; ``error`` = the largest distance of a measured frequency
    to the nearest $|\sum_i c_i\lambda_i|$ ($|c_i| \le$ ``K``), in units of the resolution $2\pi/T_h$
    ($T_h$ the horizon whose frequencies the record holds); ``rank`` = the number of rates;
    ``agrees`` = resolved, ``count == rank`` and ``error <=`` :data:`ZETA_MATCH`."""
    import itertools

    out = []
    for lam, r in zip(zeta_rates(ens), results):
        res = 2 * np.pi / (T * r.horizon)
        combos = np.array([abs(np.dot(c, lam)) for c in itertools.product(range(-K, K + 1),
                                                                          repeat=len(lam))
                           if any(c)]) if len(lam) else np.zeros(0)
        errs = [float(np.min(np.abs(combos - f))) if len(combos) else abs(f) for f in r.frequencies]
        error = max(errs, default=0.0) / res
        resolved = r.cls != "unresolved"
        out.append({"rates": [float(v) for v in lam], "rank": int(len(lam)),
                    "error": float(error) if resolved else float("nan"),
                    "agrees": bool(resolved and r.count == len(lam) and error <= ZETA_MATCH)})
    return out


#: The ensembles several evidence rows share: the n = 4 control of S5:EJ-tori, S5:reconstruction
#: and Th:Re-tori:frequencies, and the P ensemble of S5:reconstruction, which is also the n = 4
#: control of S6:open-reduced-n5 and -n6.
SHARED = {"control4": control4_row, "full4": full4_row}


def start_shared(name: str, seed: int) -> bool:
    """Compute the shared ensemble ``name`` of :data:`SHARED` now, into the cache, unless another
    process is computing it or there is no usable cache (a value it could not keep would be
    computed twice); never waits. A row that needs a shared ensemble calls this first: under
    ``verify --jobs`` the first such row computes it while the others do their own orbits, where
    before every row ended on it and all but one waited for that one, their cores idle (seen:
    S6:open-reduced-n5 and -n6, started together, both 66 s). True iff computed here."""
    from chaplygin_nd.simulate.analysis import result_cache as rc

    folder = rc.private_folder("evidence")
    if folder is None:
        return False
    with rc.locked(folder / f"shared-{name}-{seed}", wait=False) as held:
        if not held:
            return False
        SHARED[name](seed)   # fills the cache entries (those already there are only read)
        return True
