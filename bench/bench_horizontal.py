r"""What the horizontal closed form for every $n$ saves (S5:H-linear-nD).

On $\mathcal H$ the planner's model ``horizontal`` evaluates $x(t), G(t)$ (and the blocks $A, B$)
in closed form instead of integrating the full system eq:motion-general. For seeded horizontal
initial conditions in $n = 5$ and $n = 6$ we time both to a horizon ``T`` and measure the largest
error of $(x, G)$ over the samples against a 50-digit reference: the proved closed form evaluated
in mpmath, with $\Omega_0 = L_{\gamma_0}^{-1}M_0$ by an mpmath linear solve of the definition
(:func:`simulate.integrators.taylor.L_matrix_mp`), $f_2 = \lVert M_0\rVert_\kappa^2$,
$h = \tfrac12\langle M_0, \Omega_0\rangle_\kappa$ (the floats of $M_0, \gamma_0$ taken as exact).

Rows are dicts with keys ``scene, T, method, setting, error, seconds, compile_seconds`` (no JIT
here: ``compile_seconds`` is 0). ``seconds`` is the best of several runs and includes, for the
closed form, the kernel evaluation of $\Omega_0$ and of the invariants at $t = 0$.

Run: ``python -m chaplygin_nd.bench.bench_horizontal [OUTDIR]`` (prints a table, writes ``horizontal.md``), or
``make bench``. ``BENCH_QUICK=1`` shrinks the horizon.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import mpmath
import numpy as np
from chaplygin_nd.bench.runs import timed
from chaplygin_nd.simulate.dynamics import families
from chaplygin_nd.simulate.dynamics.closed_forms import horizontal_invariants, horizontal_nd
from chaplygin_nd.simulate.dynamics.field import FullField
from chaplygin_nd.simulate.integrators import dop853
from chaplygin_nd.simulate.integrators.taylor import L_matrix_mp
from chaplygin_nd.simulate.kernels import active

from chaplygin_nd.writing import write_atomic

QUICK = os.environ.get("BENCH_QUICK") == "1"
#: (scene name, n, a, b, seed) — seeded horizontal initial conditions.
SCENES = (("horizontal5d", 5, 0.7, 0.4, 3), ("horizontal6d", 6, -0.4, 1.5, 7))
RTOLS = (1e-6, 1e-9, 1e-12)


def reference(M0: np.ndarray, gamma0: np.ndarray, a: float, b: float, t: np.ndarray,
              dps: int = 50) -> np.ndarray:
    r"""$(x, G)(t)$ at ``dps`` digits from the closed form of S5:H-linear-nD (see module docstring);
    shape ``(S, 2)``; one initial condition on $\mathcal H$."""
    n = gamma0.shape[-1]
    with mpmath.workdps(dps):
        am, bm = mpmath.mpf(a), mpmath.mpf(b)
        g = [mpmath.mpf(v) for v in gamma0]
        Mm = mpmath.matrix(M0.tolist())
        i, j = np.triu_indices(n, 1)
        w = mpmath.lu_solve(L_matrix_mp(g, am, bm, n), mpmath.matrix([Mm[p, q] for p, q in zip(i, j)]))
        f2 = mpmath.fsum(Mm[p, q] ** 2 for p, q in zip(i, j))
        h = mpmath.fsum(Mm[p, q] * w[r] for r, (p, q) in enumerate(zip(i, j))) / 2
        x0 = g[-1]
        G0 = mpmath.fsum(Mm[p, n - 1] * g[p] for p in range(n))
        S = am + bm + 2
        nu = mpmath.sqrt((f2 - 2 * bm * h) / ((2 + am) * S))
        out = []
        for tk in t:
            c, s = mpmath.cos(nu * tk), mpmath.sin(nu * tk)
            out.append([x0 * c + G0 * s / (S * nu), G0 * c - S * x0 * nu * s])
        return np.array([[float(v) for v in row] for row in out])


def rows(T: float | None = None, samples: int = 201) -> list[dict]:
    """The benchmark rows (module docstring) for n = 5 and n = 6 to horizon ``T``."""
    T = T if T is not None else (10.0 if QUICK else 100.0)
    t = np.linspace(0.0, T, samples)
    k = active()
    out = []
    for name, n, a, b, seed in SCENES:
        M0, g0 = families.draw("horizontal", n, a, b, seed)
        ref = reference(M0[0], g0[0], a, b, t)

        def closed(M0=M0, g0=g0, a=a, b=b):
            Omega0 = k.require("angular_velocity")(M0, g0, a, b)
            return horizontal_nd(M0, g0, Omega0, a, b, t)[:, 0, :2]

        sec, xg = timed(closed, 20)
        out.append({"scene": name, "T": T, "method": "closed form (S5:H-linear-nD)",
                    "setting": "cos/sinc kernel", "error": float(np.max(np.abs(xg - ref))),
                    "seconds": sec, "compile_seconds": 0.0})
        for rtol in RTOLS:
            f = FullField(n, a, b)

            def full(f=f, rtol=rtol, M0=M0, g0=g0):
                return dop853.integrate(f, f.pack(M0, g0), t, rtol=rtol, atol=rtol)

            sec, sol = timed(full, 1 if rtol < 1e-10 else 2)
            M, gamma = f.unpack(sol.y)
            xg = horizontal_invariants(M, gamma)[:, 0, :2]
            out.append({"scene": name, "T": T, "method": "full + DOP853",
                        "setting": f"rtol=atol={rtol:g}", "error": float(np.max(np.abs(xg - ref))),
                        "seconds": sec, "compile_seconds": 0.0})
    return out


def table(rs: list[dict]) -> str:
    """Markdown table of the rows, with the speed-up of the closed form per scene."""
    lines = ["| scene | T | method | setting | error (x, G) | seconds | vs closed form |",
             "|---|---|---|---|---|---|---|"]
    closed = {r["scene"]: r["seconds"] for r in rs if r["method"].startswith("closed")}
    for r in rs:
        ratio = r["seconds"] / closed[r["scene"]]
        lines.append(f"| {r['scene']} | {r['T']:g} | {r['method']} | {r['setting']} | "
                     f"{r['error']:.1e} | {r['seconds']:.2e} | {ratio:.0f}x |")
    return "\n".join(lines)


def main(outdir="bench/out") -> None:
    """Run :func:`rows`, print the table and write ``horizontal.md`` into ``outdir``."""
    rs = rows()
    text = table(rs)
    print(text)
    out = Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    write_atomic(out / "horizontal.md",
                 "# Horizontal closed form vs full system (S5:H-linear-nD)\n\n" + text + "\n")


if __name__ == "__main__":
    main(*sys.argv[1:])
