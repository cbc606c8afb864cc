r"""Throughput of $\Omega = L_\gamma^{-1}M$ for $n = 4$ on $10^6$ points, measured in one run.

Compared: the generated component kernel ``generated.axisym.angular_velocity_axisym_4d`` (CSE,
chunked), a batched ``numpy.linalg.solve`` of the $6\times6$ matrix of $L_\gamma$ (assembly by the
generated ``L_matrix_axisym_4d`` included), a plain ``sympy.lambdify`` of the same derived
expressions without CSE (whole-array evaluation), and the floor: a memory copy of the same bytes
(inputs read + output written). Targets (issue 5): >= 50x the solve, >= 2x plain lambdify, within
10x of the copy. Writes ``throughput.md`` in the output folder. Reproduce: ``make bench`` or
``python -m bench bench_throughput``.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

COUNT = 1_000_000
A, B = 0.3, 1.7


def _best(fn, repeat=3):
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times)


def measure(count: int = COUNT, repeat: int = 3) -> dict[str, float]:
    """Seconds (best of ``repeat``) of each route on ``count`` points, and a correctness check."""
    import sympy as sp

    from generated import axisym
    from symbolic.emit.axisym import component_kernels

    rng = np.random.default_rng(2026)
    gamma = rng.standard_normal((count, 4))
    gamma /= np.linalg.norm(gamma, axis=-1, keepdims=True)
    M = rng.standard_normal((count, 6))

    kernel = next(k for k in component_kernels(4) if k.name == "angular_velocity_axisym_4d")
    syms = [s for arg in kernel.arguments for s in arg.symbols]
    plain = sp.lambdify(syms, list(kernel.outputs), modules="numpy", cse=False)

    def generated():
        return axisym.angular_velocity_axisym_4d(M, gamma, A, B)

    def solve():
        L = axisym.L_matrix_axisym_4d(gamma, A, B)
        return np.linalg.solve(L, M[..., None])[..., 0]

    def lambdified():
        cols = plain(*M.T, *gamma.T, A, B)
        return np.stack([np.broadcast_to(c, (count,)) for c in cols], axis=-1)

    src = np.concatenate([M, gamma], axis=-1)
    dst = np.empty((count, 6 + 4 + 6))

    def copy():  # the same bytes: read the inputs, write inputs + output sized buffer
        np.copyto(dst[:, :10], src)
        np.copyto(dst[:, 10:], M)

    out = generated()
    assert np.allclose(out, solve(), rtol=0, atol=1e-12)
    assert np.allclose(out, lambdified(), rtol=0, atol=1e-12)
    return {"generated": _best(generated, repeat), "solve": _best(solve, repeat),
            "lambdify": _best(lambdified, repeat), "copy": _best(copy, repeat)}


def main(outdir: Path) -> int:
    t = measure()
    rows = [("batched numpy.linalg.solve (assembly incl.)", t["solve"], t["solve"] / t["generated"], ">= 50"),
            ("plain lambdify, no CSE", t["lambdify"], t["lambdify"] / t["generated"], ">= 2"),
            ("memory copy of the same bytes (floor)", t["copy"], t["copy"] / t["generated"], ">= 0.1")]
    lines = [f"# L_gamma^-1, n = 4, {COUNT:,} points (one run, best of 3)", "",
             f"generated kernel: {t['generated']:.3f} s", "",
             "| route | seconds | route / generated | target |", "|---|---|---|---|"]
    lines += [f"| {name} | {sec:.3f} | {ratio:.2f} | {target} |" for name, sec, ratio, target in rows]
    text = "\n".join(lines) + "\n"
    (outdir / "throughput.md").write_text(text)
    print(text)
    return 0
