r"""The validation of the re-examination rule of :mod:`simulate.analysis.reconstruction` on flows
whose torus dimension is known, before it decides the row ``S5:reconstruction``.

Systems: $m$ uncoupled pendula $\ddot q_i = -w_i^2\sin q_i$ (:func:`simulate.analysis.gali_study.pendula`;
Liouville integrable, every orbit off the separatrices on an $m$-torus), $w_i$ drawn in
$[0.05, 0.5]$ (the frequencies of the $n = 4$ orbits lie in $0.005 .. 0.6$), $q_i$ uniform,
$p_i$ normal times $w_i$: librations, rotations and orbits near the separatrix (a slow frequency
with many harmonics) alike. The signals mix the pendula as the reconstruction mixes the reduced
and the group motion, with $v_i = \sin q_i + i p_i/w_i$:

* "reduced" signals $v_1 + 0.3v_2$, $v_2 + 0.4v_1v_2$ (frequencies $\omega_1, \omega_2$ only);
* "on P" signals $v_3(1 + 0.4v_1)(1 + 0.3v_2)(1 + \epsilon v_4)$, $\bar v_3 + 0.3v_3v_1$,
  $v_3v_1 + 0.2v_2 + \epsilon v_4v_3$.

With $m = 3$ ($\epsilon = 0$) the true count is 3; with $m = 4$ it is 4, the fourth frequency
entering with the weight $\epsilon$ drawn log-uniform in $[0.05, 0.5]$ — weak lines, as a real
fourth frequency of the reconstruction could be. Every orbit (not only those the row's count
calls ``excess``) is re-examined from $T = 4096$, $dt = 1/2$ to $8T$ and classified by the rule;
a false alarm is a 3-torus read ``fourth frequency``, a miss a 4-torus read otherwise (worst: read
``rank 3``, the class the row counts as predicted). Also reported: the row's own count at $T$.

Run: ``python -m chaplygin_nd.simulate.analysis.reconstruction_study [count [seed]]`` (minutes).
"""

from __future__ import annotations

import sys
import time

import numpy as np
from chaplygin_nd.simulate.analysis import naff, reconstruction
from chaplygin_nd.simulate.analysis.frequencies import REGULAR

__all__ = ["orbits", "signals", "visible", "run", "rates", "T", "DT", "SEED"]

SEED = 20261121
T, DT = 4096.0, 0.5
TOL = reconstruction.TOL   # the re-examination runs at the tolerance validated here
BATCH = 8


def orbits(m: int, count: int, seed: int = SEED):
    """``(y0 (count, 2m), pars (m, count), eps (count,))`` of the study (module docstring)."""
    rng = np.random.default_rng([seed, 0x5EC0, m])
    w = rng.uniform(0.05, 0.5, (count, m))
    q = rng.uniform(-np.pi, np.pi, (count, m))
    p = rng.normal(0.0, 1.0, (count, m)) * w
    eps = np.exp(rng.uniform(np.log(0.05), np.log(0.5), count)) if m == 4 else np.zeros(count)
    return np.concatenate([q, p], 1), (w ** 2).T, eps


def signals(Y: np.ndarray, w: np.ndarray, eps: np.ndarray) -> np.ndarray:
    """The five complex signals ``(orbits, 5, samples)`` of the module docstring from the states
    ``Y`` ``(samples, orbits, 2m)``, frequencies ``w`` ``(orbits, m)`` and weights ``eps``."""
    m = Y.shape[-1] // 2
    v = [np.sin(Y[..., i]) + 1j * Y[..., m + i] / w[None, :, i] for i in range(m)]
    v4 = v[3] if m == 4 else np.zeros_like(v[0])
    e = eps[None, :]
    z = [v[0] + 0.3 * v[1], v[1] + 0.4 * v[0] * v[1],
         v[2] * (1 + 0.4 * v[0]) * (1 + 0.3 * v[1]) * (1 + e * v4),
         np.conj(v[2]) + 0.3 * v[2] * v[0],
         v[2] * v[0] + 0.2 * v[1] + e * v4 * v[2]]
    return np.moveaxis(np.array(z), (0, 1, 2), (1, 2, 0))


def _integrate(m: int, y0, pars, eps, T_end: float):
    from chaplygin_nd.simulate.analysis.gali_study import pendula
    from chaplygin_nd.simulate.integrators.heyoka_taylor import compiled_integrator

    ta, _, _ = compiled_integrator(pendula(m), "double", TOL, compact=True, batch=BATCH)
    t = np.arange(int(round(T_end / DT)) + 1) * DT
    used = len(y0)
    pad = np.concatenate([y0, np.repeat(y0[-1:], BATCH - used, 0)])
    ppad = np.concatenate([pars, np.repeat(pars[:, -1:], BATCH - used, 1)], 1)
    ta.state[:] = pad.T
    ta.pars[:] = ppad
    ta.set_time(0.0)
    _, states = ta.propagate_grid(np.repeat(t[:, None], BATCH, 1))
    Y = np.moveaxis(states[:, :, :used], 1, 2)
    w = np.sqrt(pars.T)
    own = np.stack([naff.fundamental_frequencies((np.sin(Y[..., i]) + 1j * Y[..., m + i] / w[None, :, i]).T,
                                                 DT) for i in range(m)], 1)
    return signals(Y, w, eps), np.abs(own)


def visible(lines, own, K: int = 12, rel: float = 1e-6) -> bool:
    r"""Whether one of the strong ``lines`` (``(|omega|, amp)``) is no combination $|c| \le$ ``K``
    of the first three pendula's own frequencies ``own[:3]`` within ``rel`` times the largest line:
    the fourth frequency shows among the lines a count can see (a line weaker than 5 % of its
    signal's strongest is never pooled)."""
    from chaplygin_nd.simulate.analysis import combinations

    tol = rel * max((f for f, _ in lines), default=1.0)
    return any(combinations.explain(f, own[:3], tol, K) is None for f, _ in lines)


def _row_count(Z: np.ndarray) -> list[str]:
    """The row's class at T (:mod:`simulate.analysis.drawn_evidence`, expected 3) per orbit."""
    from chaplygin_nd.simulate.analysis import combinations
    from chaplygin_nd.simulate.analysis.drawn_evidence import classify

    n = int(round(T / DT)) + 1
    whole, first, second = naff.lines_batch(Z[:, :, :n], DT)
    out = []
    for w, f, h in zip(whole, first, second):
        spec = naff.spectrum_from_lines(w, f, h)
        info = {"ambiguous": 0}
        if spec.diffusion < REGULAR and spec.count > 3:
            scale = max(abs(x) for x, _ in spec.lines)
            basis, info = combinations.recount(spec.lines, spec.tolerance * scale, 6,
                                               resolution=2 * np.pi / T)
            spec = naff.Spectrum(spec.lines, sorted(basis), spec.diffusion, spec.tolerance)
        out.append(classify(spec, 3, info["ambiguous"]))
    return out


def run(count: int = 64, seed: int = SEED, stream=None) -> list[dict]:
    """Per system (m = 3, 4): ``{"m", "truth", "classes": rule class per orbit, "row": the row's
    class at T per orbit, "eps"}``."""
    stream = stream or sys.stdout
    rows = []
    for m in (3, 4):
        y0, pars, eps = orbits(m, count, seed)
        classes, row, seen = [], [], []
        t0 = time.perf_counter()
        for start in range(0, count, BATCH):
            sl = slice(start, min(start + BATCH, count))
            Z, own = _integrate(m, y0[sl], pars[:, sl], eps[sl], T * max(reconstruction.HORIZONS))
            row += _row_count(Z)
            found = reconstruction.examine_signals(Z, DT, T)
            classes += [e.cls for e in found]
            seen += [bool(m == 4 and visible(e.looks[-1].lines, o)) for e, o in zip(found, own)]
        rows.append({"m": m, "truth": m, "classes": classes, "row": row, "visible": seen,
                     "eps": [float(e) for e in eps]})
        print(f"m = {m}: {count} orbits, {time.perf_counter() - t0:.0f} s; rule: "
              f"{_tally(classes)}; row's count at T: {_tally(row)}; fourth frequency among the "
              f"strong lines: {sum(seen)} (rule on those: "
              f"{_tally(c for c, v in zip(classes, seen) if v)})", file=stream, flush=True)
    return rows


def _tally(xs) -> str:
    out: dict = {}
    for x in xs:
        out[x] = out.get(x, 0) + 1
    return ", ".join(f"{k} {v}" for k, v in sorted(out.items(), key=lambda kv: -kv[1]))


def _upper(k: int, total: int) -> float:
    """One-sided 95 % upper bound of a rate with ``k`` events in ``total`` (Clopper-Pearson)."""
    from scipy.stats import beta

    return 1.0 if k >= total else float(beta.ppf(0.95, k + 1, total - k))


def rates(rows: list[dict]) -> dict:
    """False alarms (3-tori read ``fourth frequency``), misses (4-tori whose fourth frequency is
    among the strong lines, :func:`visible`, read otherwise) and the worst misses (those read
    ``rank 3``), each with its 95 % upper bound."""
    three = [c for r in rows if r["truth"] == 3 for c in r["classes"]]
    four = [c for r in rows if r["truth"] == 4 for c, v in zip(r["classes"], r["visible"]) if v]
    fa = sum(c == "fourth frequency" for c in three)
    miss = sum(c != "fourth frequency" for c in four)
    worst = sum(c == "rank 3" for c in four)
    return {"false_alarms": (fa, len(three), _upper(fa, len(three))),
            "misses": (miss, len(four), _upper(miss, len(four))),
            "read_rank3": (worst, len(four), _upper(worst, len(four)))}


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    count = int(argv[0]) if argv else 64
    seed = int(argv[1]) if len(argv) > 1 else SEED
    print(f"seed {seed}, {count} orbits per system")
    rows = run(count, seed)
    for k, (n, total, up) in rates(rows).items():
        print(f"{k}: {n} of {total} (< {100 * up:.1f} % at 95 %)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
