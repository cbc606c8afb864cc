r"""The NAFF count of an orbit over a horizon ladder: $T$, then $2T$, then $4T$ for the orbits whose
frequencies the shorter horizon did not resolve — the ladder of every drawn row
(:data:`simulate.analysis.evidence_rows.LADDER_FACTORS`), here for the torus rows and their
validation study (:mod:`simulate.analysis.torus_rows`, :mod:`simulate.analysis.gali_study`).

**Why a ladder** (measured on 48 orbits per $n$ of a draw of its own, label ``torus-diagnosis-n{n}``,
not the rows' orbits). At $T = 4096$ NAFF resolved ($D < 10^{-5}$) 20, 21 and 12 of 48 orbits for
$n = 6, 7, 8$. Of the unresolved, the median $D$ was $1.9\cdot10^{-4}$, $1.4\cdot10^{-4}$,
$2.0\cdot10^{-4}$ (75 % below $10^{-3}$); the line that set $D$ was slow (fewer than 3 turns in
a half) on 5, 0, 4 orbits, within 3 Fourier bins of another line on 2, 3, 3, and isolated on 21,
24, 29. On those isolated lines $D$ fell steeply with the horizon (typically by $10^2$ per doubling:
e.g. $5.1\cdot10^{-5} \to 5.2\cdot10^{-7} \to 6.6\cdot10^{-9}$ at $T, 2T, 4T$), as a NAFF error on a
torus does, and subtracting more lines per half (4, 8, 12) changed no $D$ (the strong lines are
found first; what biases them is the leakage of the dense lattice of weaker lines of a 3- or
4-torus, which only a longer window reduces). So most orbits were unresolved because $T$ was too
short for the precision the rule asks, not by near-resonance or chaos; at $2T$ / $4T$ the same
orbits resolved 30 / 42, 40 / 43, 24 / 33 of 48 (the ladder: 43, 43, 34).

**Rule** (fixed from that diagnosis before any run of the rows' draws, validated by
:mod:`simulate.analysis.gali_study`). Every orbit is analysed at $T$; one unresolved there
(:func:`resolved` false) is continued, frequency-only (no deviation vectors), to $2T$ and analysed
on $[0, 2T]$ at the same sampling, and if still unresolved to $4T$, analysed on $[0, 4T]$ sampled
twice as sparsely (as :meth:`simulate.analysis.drawn_evidence.Setting.longer`). Its count and
resolution are those of the first horizon that resolves it (else of $4T$); $D$ at $T$ is kept
too (the controls' separation compares $D$ at the same horizon $T$). Counting is that of every
drawn row (:func:`count`): $|c| \le 4$, then $|c| \le 12$ for a count above the prediction, with the
Fourier bin $2\pi/(fT)$ of the horizon.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from chaplygin_nd.simulate.analysis import combinations, naff
from chaplygin_nd.simulate.analysis.frequencies import REGULAR

__all__ = ["FACTORS", "count", "resolved", "ladder"]

#: the horizons after T, in units of T (as simulate.analysis.evidence_rows.LADDER_FACTORS)
FACTORS = (2.0, 4.0)


def count(whole, first, second, expected: int, T: float) -> tuple[naff.Spectrum, dict]:
    r"""The spectrum of one orbit from its lines (:func:`simulate.analysis.naff.lines_batch`) at the
    horizon ``T``: the $|c| \le 4$ count, and when it is resolved and above ``expected`` the recount
    with combinations $|c| \le 12$ (:func:`simulate.analysis.combinations.recount`, resolution
    $2\pi/T$). ``extra``: ``count4`` (the $|c| \le 4$ count), ``ambiguous``, ``relations``,
    ``expected``."""
    spec = naff.spectrum_from_lines(whole, first, second)
    extra = {"count4": int(spec.count), "ambiguous": 0, "relations": [], "expected": int(expected)}
    if spec.diffusion < REGULAR and spec.count > expected:
        scale = max(abs(x) for x, _ in spec.lines)
        basis, info = combinations.recount(spec.lines, spec.tolerance * scale, expected + 2,
                                           resolution=2 * np.pi / T)
        spec = naff.Spectrum(spec.lines, sorted(basis), spec.diffusion, spec.tolerance)
        extra.update(ambiguous=int(info["ambiguous"]), relations=list(info["relations"]))
    return spec, extra


def resolved(spec: naff.Spectrum, extra: dict) -> bool:
    """NAFF resolved: $D <$ ``REGULAR`` and no line left ambiguous by the recount unless the count
    is above the prediction all the same (an excess, as
    :func:`simulate.analysis.drawn_evidence.classify` decides)."""
    excess = spec.count > extra.get("expected", spec.count)
    return bool(spec.diffusion < REGULAR and (excess or not extra.get("ambiguous", 0)))


def ladder(signals: np.ndarray, dt: float, T: float, expected, extend: Callable,
           factors=FACTORS) -> list[tuple[naff.Spectrum, dict]]:
    r"""The rule of the module docstring for an ensemble: ``signals`` ``(orbits, signals, samples)``
    sampled every ``dt`` on $[0, T]$; ``expected`` the predicted count (one int, or one per orbit);
    ``extend(idx, t0, t1)`` the signals of the orbits ``idx`` continued from $t_0$ to $t_1$ (in units
    of the sampling: the samples $t_0 + dt, \dots, t_1$), shape ``(len(idx), signals, samples)``.
    Per orbit ``(spectrum, extra)``; ``extra`` adds ``horizon`` (the factor of $T$ of the count),
    ``diffusion_T`` ($D$ at $T$) and ``diffusions`` (D at each horizon run)."""
    count_ = len(signals)
    exp = np.broadcast_to(np.asarray(expected), (count_,))
    out: list = [None] * count_
    whole, first, second = naff.lines_batch(signals, dt)
    for k in range(count_):
        spec, extra = count(whole[k], first[k], second[k], int(exp[k]), T)
        extra.update(horizon=1.0, diffusion_T=float(spec.diffusion),
                     diffusions=[float(spec.diffusion)])
        out[k] = (spec, extra)
    todo = [k for k in range(count_) if not resolved(*out[k])]
    kept = {k: signals[k] for k in todo}
    previous = 1.0
    for factor in factors:
        if not todo:
            break
        more = extend(np.array(todo), previous * T, factor * T)
        for j, k in enumerate(todo):
            kept[k] = np.concatenate([kept[k], more[j]], axis=-1)
        stride = int(max(1.0, factor / 2))
        Z = np.stack([kept[k][:, ::stride] for k in todo])
        whole, first, second = naff.lines_batch(Z, dt * stride)
        for j, k in enumerate(todo):
            spec, extra = count(whole[j], first[j], second[j], int(exp[k]), factor * T)
            extra.update(horizon=float(factor), diffusion_T=out[k][1]["diffusion_T"],
                         diffusions=out[k][1]["diffusions"] + [float(spec.diffusion)])
            out[k] = (spec, extra)
        todo = [k for k in todo if not resolved(*out[k])]
        kept = {k: kept[k] for k in todo}
        previous = factor
    return out
