r"""NAFF lines explained by integer combinations of an orbit's fundamental frequencies, with the
chance of a false match.

The count of independent frequencies (:func:`simulate.analysis.naff.independent_frequencies`) searches
relations with coefficients $|c| \le 4$; a line that is a combination with larger coefficients (5 to
12 were seen on $P$) then looks like a new frequency and the orbit like an "excess" one — the bound,
not the dynamics. Here every strong line $f$ that the basis $\omega_1..\omega_k$ does not explain with
$|c| \le 4$ is searched again for $f = \sum_i c_i\omega_i$ (up to sign) with $|c_i| \le$ ``K`` = 12,
within the tolerance $\tau$ of the count (the measured precision of the strong lines) divided by
the line's relative amplitude (weaker lines are measured less precisely); a line within 3 Fourier
bins of another is not established (:func:`recount`).

**False matches.** A frequency unrelated to the torus, uniform on $[0, \Omega]$ ($\Omega$ the largest
line of the orbit), falls within $\tau$ of one of the candidate combinations with probability
$P_{false} = |\bigcup_c [\langle c, \omega\rangle - \tau, \langle c, \omega\rangle + \tau] \cap [0, \Omega]|/\Omega$
(computed exactly from the sorted candidates, at most $\min(1, 2\tau N_c/\Omega)$ with $N_c$ the number of
candidates in range). An explanation is *credible* iff $P_{false} \le$ ``CREDIBLE`` = 1 %; a line with
no credible explanation is *unexplained*, and only such a line makes an orbit ``excess``. The search
is exhaustive (meet in the middle: the candidates of the first half of the basis against the
sorted candidates of the second), so "no combination" means none exists within the bound.
"""

from __future__ import annotations

import functools
import itertools
from typing import Any

import numpy as np

__all__ = ["K", "CREDIBLE", "candidates", "false_match", "explain", "recount"]

K = 12
CREDIBLE = 0.01
#: a line's tolerance is tol / amplitude, the amplitude (relative to its signal's strongest line)
#: floored here (the count pools lines of at least 5 %)
AMP_FLOOR = 0.05
#: two lines closer than this many Fourier bins 2 pi / T interfere in the order-2 Hann window
CLOSE = 3.0


@functools.lru_cache(maxsize=16)
def _grid(K: int, k: int) -> np.ndarray:
    return np.array(list(itertools.product(range(-K, K + 1), repeat=k)), dtype=float).reshape(-1, k)


def candidates(basis, K: int = K) -> np.ndarray:
    r"""Every $|\sum_i c_i\omega_i|$, $|c_i| \le K$, sorted (for $k \le 3$ frequencies; used for
    :func:`false_match`). Domain: ``basis`` of at most 3 finite floats."""
    basis = np.asarray(basis, float)
    return np.sort(np.abs(_grid(K, len(basis)) @ basis))


def false_match(basis, tol: float, top: float, K: int = K) -> float:
    r"""$P_{false}$ of the module docstring: the fraction of $[0, $ ``top`` $]$ within ``tol`` of a
    candidate combination of ``basis`` with $|c_i| \le$ ``K``. For more than 3 frequencies the bound
    $\min(1, 2\tau N_c/\Omega)$ with $N_c = (2K+1)^k$ (no enumeration)."""
    basis = [float(b) for b in basis if b > 0]
    if not basis or top <= 0:
        return 0.0
    if len(basis) > 3:
        return float(min(1.0, 2 * tol * (2 * K + 1) ** len(basis) / top))
    c = candidates(basis, K)
    c = c[c <= top + tol]
    lo, hi = np.maximum(c - tol, 0.0), np.minimum(c + tol, top)
    covered, end = 0.0, -np.inf
    for a, b in zip(lo, hi):                 # union of sorted intervals
        if b <= end:
            continue
        covered += b - max(a, end)
        end = b
    return float(covered / top)


def explain(f: float, basis, tol: float, K: int = K) -> tuple[int, ...] | None:
    r"""Integers $c$, $|c_i| \le K$, with $\big||f| - |\sum_i c_i\omega_i|\big| \le$ ``tol`` (of the
    matches found, the one with the smallest $\max|c_i|$), or None. Exhaustive: the sums of the
    first half of the basis against the sorted sums of the second half. Domain: finite floats."""
    basis = np.asarray([float(b) for b in basis], float)
    f = abs(float(f))
    k = len(basis)
    if k == 0:
        return () if f <= tol else None
    h = k // 2
    lgrid = _grid(K, h) if h else np.zeros((1, 0))
    left = lgrid @ basis[:h]
    rgrid = _grid(K, k - h)
    right = rgrid @ basis[h:]
    order = np.argsort(right, kind="stable")
    rs = right[order]
    best = None
    for target in (f, -f):
        need = target - left
        lo = np.searchsorted(rs, need - tol, side="left")
        hi = np.searchsorted(rs, need + tol, side="right")
        for j in np.nonzero(hi > lo)[0]:
            for r in order[lo[j]:hi[j]]:
                c = tuple(int(x) for x in np.concatenate([lgrid[j], rgrid[r]]))
                if best is None or max(map(abs, c)) < max(map(abs, best)):
                    best = c
    return best


def recount(lines, tol: float, limit: int, K: int = K, resolution: float = 0.0
            ) -> tuple[list[float], dict]:
    r"""The independent frequencies of the pooled ``lines`` (pairs ``(omega, amplitude)``, strongest
    first, amplitudes relative to the strongest line of their signal) when combinations up to
    $|c_i| \le$ ``K`` explain a line. A line joins the basis only if

    * no relation with $|c_i| \le 4$ explains it at ``tol`` (rational ones too,
      :func:`simulate.analysis.naff._relation`; the count's own search), and
    * no combination with $|c_i| \le K$ explains it at its own tolerance ``tol / amplitude`` (a
      NAFF frequency's error grows like the inverse of its amplitude; floored at ``AMP_FLOOR``), and
    * it is not within ``CLOSE`` $\times$ ``resolution`` ($2\pi/T$) of a line already seen or of 0: two
      lines that close interfere in the window, and a line that slow makes fewer than ``CLOSE``
      turns; neither frequency is established.

    An explanation with $|c_i| > 4$ counts only if it is credible (:func:`false_match` at that
    tolerance $\le$ ``CREDIBLE``); a line with only an incredible explanation, or too close to
    another, is *ambiguous*: it neither joins the basis nor is explained (the orbit is then
    unresolved, not excess). Returns the basis and ``{"large": lines explained with |c| > 4,
    "ambiguous": ..., "close": ..., "p_false": the largest P_false met, "relations": up to 3}``.
    Stops at ``limit`` frequencies."""
    from chaplygin_nd.simulate.analysis import naff

    top = max((abs(w) for w, _ in lines), default=0.0)
    basis: list[float] = []
    seen: list[float] = [0.0]          # a line within CLOSE bins of 0 makes < 3 turns: not established
    info: dict[str, Any] = {"large": 0, "ambiguous": 0, "close": 0, "p_false": 0.0, "relations": []}
    for w, amp in lines:
        if len(basis) >= limit:
            break
        f = abs(float(w))
        if f <= tol or naff._relation(f, basis, tol, 4) is not None:
            seen.append(f)
            continue
        own = tol / max(float(amp), AMP_FLOOR)
        c = explain(f, basis, own, K) if basis else None
        if c is None:
            if resolution > 0 and any(abs(f - g) < CLOSE * resolution for g in seen):
                info["close"] += 1
                info["ambiguous"] += 1
            else:
                basis.append(f)
            seen.append(f)
            continue
        seen.append(f)
        p = false_match(basis, own, top, K)
        info["p_false"] = max(info["p_false"], p)
        if p <= CREDIBLE:
            info["large"] += int(max(map(abs, c)) > 4)
            if len(info["relations"]) < 3:
                rhs = " + ".join(f"{x}*w{i + 1}" for i, x in enumerate(c) if x)
                info["relations"].append(f"{f:.10g} = |{rhs}|")
        else:
            info["ambiguous"] += 1
    return basis, info
