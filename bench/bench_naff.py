r"""NAFF on the evidence rows' ensembles: the CPU seconds of
:func:`simulate.analysis.naff.lines_batch` against the earlier line loop (fresh arrays for every line,
every Newton step on every row), side by side in one process, on seeded quasi-periodic signals of
the rows' shapes ``(orbits, signals, samples)``: (32, 5, 16385) and (32, 5, 8193) of S5:EJ-tori and
S6:open-reduced-n5, (32, 10, 9601) of Th:Re-tori:frequencies. The two must give the same bits
(checked here on every shape; tests/test_naff_buffers.py checks it on small ones).
``chaplygin bench naff`` writes ``naff.md`` and ``naff.json``.
"""

from __future__ import annotations

import json
import os
import time
from pathlib import Path

import numpy as np

SHAPES = ((32, 5, 16385), (32, 5, 8193), (32, 10, 9601))
DT = 0.5


def earlier_find_lines(R, w, dt, pad, P, L, terms, newton, found_w, found_a) -> None:
    """The line loop as it was before the kept buffers and the frozen Newton rows (the reference
    of this bench and of tests/test_naff_buffers.py): fresh arrays for every line, ``abs`` of a
    padded FFT, every row through every Newton step."""
    from chaplygin_nd.simulate.analysis import naff_lines
    from scipy.fft import fft

    K, N = R.shape
    omega_grid = 2 * np.pi * np.fft.fftfreq(pad, d=dt)
    idx = np.arange(K)
    X = np.zeros((K, P * L), dtype=complex)
    for m in range(terms):
        np.multiply(R, w[None], out=X[:, :N])
        spec = np.abs(fft(X, n=pad, axis=1))
        i = np.argmax(spec, axis=1)
        y0, y1, y2 = (np.log(spec[idx, (i + s) % pad] + 1e-300) for s in (-1, 0, 1))
        den = y0 - 2 * y1 + y2
        shift = np.where(np.abs(den) > 0, 0.5 * (y0 - y2) / np.where(den == 0, 1, den), 0.0)
        nu = omega_grid[i] + shift * (2 * np.pi / (pad * dt))
        Xr = X.reshape(K, P, L)
        for _ in range(newton):
            phi, d1, d2 = naff_lines._projections(Xr, nu, dt, L, True)
            g = 2 * np.real(np.conj(phi) * d1)
            h = 2 * np.real(np.abs(d1) ** 2 + np.conj(phi) * d2)
            step = np.where(h < 0, g / np.where(h == 0, 1, h), 0.0)
            nu = nu - np.clip(step, -np.pi / (N * dt), np.pi / (N * dt))
        phi, alpha, beta = naff_lines._projections(Xr, nu, dt, L, False)
        found_w[:, m] = nu
        found_a[:, m] = np.abs(phi)
        line = alpha[:, :, None] * beta[:, None, :]
        np.conjugate(line, out=line)
        line = line.reshape(K, P * L)[:, :N]
        line *= phi[:, None]
        R -= line


def _signals(shape, seed: int) -> np.ndarray:
    """Seeded quasi-periodic signals: per orbit 3 frequencies, per signal 8 lines on their lattice."""
    rng = np.random.default_rng(seed)
    orbits, count, N = shape
    t = np.arange(N) * DT
    Z = np.zeros(shape, complex)
    for o in range(orbits):
        f = rng.uniform(0.05, 2.0, 3)
        for s in range(count):
            for _ in range(8):
                c = rng.integers(-3, 4, 3)
                Z[o, s] += rng.uniform(0.01, 1.0) * np.exp(1j * ((c @ f) * t + rng.uniform(0, 7)))
    return Z


def _bits(out) -> bytes:
    return b"".join(x.tobytes() for part in out for orbit in part for pair in orbit for x in pair)


def measure(shapes=SHAPES, repeats: int = 2) -> list[dict]:
    """Per shape: CPU seconds of the earlier and the current ``lines_batch`` (the best of
    ``repeats``, alternating), and whether their outputs are the same bits."""
    from chaplygin_nd.simulate.analysis import naff, naff_lines

    rows = []
    naff.lines_batch(_signals((2, 2, 1025), 0), DT)          # imports, FFT plans: not timed
    for k, shape in enumerate(shapes):
        Z = _signals(shape, 20261127 + k)
        times: dict = {"earlier": [], "current": []}
        outs = {}
        for _ in range(repeats):
            for name in ("earlier", "current"):
                current = naff_lines._find_lines
                if name == "earlier":
                    naff_lines._find_lines = earlier_find_lines
                try:
                    c0 = time.process_time()
                    outs[name] = naff.lines_batch(Z, DT)
                    times[name].append(time.process_time() - c0)
                finally:
                    naff_lines._find_lines = current
        rows.append({"shape": list(shape), "earlier_cpu": round(min(times["earlier"]), 3),
                     "current_cpu": round(min(times["current"]), 3),
                     "same_bits": _bits(outs["earlier"]) == _bits(outs["current"])})
    return rows


def main(out: Path, quick: bool = False) -> int:
    """The table of :func:`measure` (``quick``: one small shape) into ``naff.md`` / ``naff.json``."""
    load0 = os.getloadavg()[0]
    rows = measure(((8, 2, 2049),), 1) if quick else measure()
    load = [round(load0, 2), round(os.getloadavg()[0], 2)]
    (out / "naff.json").write_text(json.dumps({"rows": rows, "load": load}, indent=1),
                                   encoding="utf-8")
    lines = ["# NAFF lines_batch: earlier loop against the current one (CPU s, same process)", "",
             f"load average {load[0]} -> {load[1]}", "",
             "| shape | earlier | current | ratio | same bits |", "|---|---|---|---|---|"]
    lines += [f"| {tuple(r['shape'])} | {r['earlier_cpu']:.2f} | {r['current_cpu']:.2f} | "
              f"{r['current_cpu'] / r['earlier_cpu']:.2f} | {r['same_bits']} |" for r in rows]
    text = "\n".join(lines) + "\n"
    (out / "naff.md").write_text(text, encoding="utf-8")
    print(text)
    return 0 if all(r["same_bits"] for r in rows) else 1
