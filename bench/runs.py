r"""The pieces of a work–precision run: one row per (scene, method, setting), the cached
high-precision references, and the timed runs of each integrator (DOP853, RKMK4, heyoka).

A reference is our mpmath Taylor method (``simulate.integrators.taylor``) at ``digits`` digits: an
implementation independent of DOP853, RKMK4 and heyoka, which it judges. It is cached under
``out/cache`` keyed by the SHA-256 of (n, a, b, y0, t, digits, method); a cached file that does
not load, or whose stored key differs, is recomputed. The row says whether its reference was
computed (cold) or loaded (warm), and how long the computation took.
"""

from __future__ import annotations

import dataclasses
import hashlib
import io
import time
from pathlib import Path

import numpy as np
from chaplygin_nd.bench.report import write_atomic
from chaplygin_nd.simulate.dynamics import families, so
from chaplygin_nd.simulate.dynamics.field import FullField
from chaplygin_nd.simulate.integrators import dop853, lie, taylor
from chaplygin_nd.simulate.kernels import active
from chaplygin_nd.simulate.scene.outputs import p_coefficients


@dataclasses.dataclass
class Row:
    """One measured run: wall time ``seconds`` (minimum over repeats; run only), the compile or
    cache-load time of a compiled integrator apart in ``compile_seconds``, the largest error
    against the reference, and the drift of the integrals."""

    scene: str
    T: float
    method: str
    setting: str
    error: float
    seconds: float
    compile_seconds: float = 0.0
    calls: int = 0
    steps: int = 0
    drift: dict = dataclasses.field(default_factory=dict)
    note: str = ""

    def as_dict(self) -> dict:
        """The JSON row."""
        return dataclasses.asdict(self)

    def md(self) -> str:
        """The Markdown table row."""
        d = ", ".join(f"{k} {v:.1e}" for k, v in self.drift.items())
        comp = f"{self.compile_seconds:.2f}" if self.compile_seconds else ""
        return (f"| {self.scene} | {self.method} | {self.setting} | {self.error:.2e} | "
                f"{self.seconds:.4g} | {comp} | {self.calls} | {self.steps} | {d} | {self.note} |")


MD_HEAD = ["| scene | method | setting | max error | seconds | compile s | RHS calls | steps | "
           "integral drift | note |", "|---|---|---|---|---|---|---|---|---|---|"]


@dataclasses.dataclass(frozen=True)
class Point:
    """An initial condition of the full system: n, a, b, M0 (1, N), gamma0 (1, n)."""

    n: int
    a: float
    b: float
    M0: np.ndarray
    gamma0: np.ndarray

    @classmethod
    def draw(cls, family: str, n: int, a: float, b: float, seed: int) -> Point:
        """A seeded point of ``family`` (simulate.dynamics.families)."""
        return cls(n, a, b, *families.draw(family, n, a, b, seed))

    def field(self) -> FullField:
        return FullField(self.n, self.a, self.b)

    def y0(self) -> np.ndarray:
        return self.field().pack(self.M0, self.gamma0)


def drift(point: Point, y: np.ndarray) -> dict:
    """Largest deviation over ``y`` (times, 1, dim) of H, of the coefficients of p(lambda, sigma)
    and of |gamma|^2 - 1 from their initial values."""
    f = point.field()
    M, gamma = f.unpack(y)
    Omega = active().require("angular_velocity")(M, gamma, point.a, point.b)
    H = 0.5 * so.killing(M, Omega)
    p = p_coefficients(M, gamma)
    g2 = np.einsum("...i,...i->...", gamma, gamma)
    return {"H": float(np.max(np.abs(H - H[:1]))), "p": float(np.max(np.abs(p - p[:1]))),
            "|gamma|^2": float(np.max(np.abs(g2 - 1.0)))}


def reference(point: Point, t: np.ndarray, digits: int, cache: Path) -> tuple[np.ndarray, str]:
    """The state at times ``t`` by our Taylor method at ``digits`` digits, and how it was obtained
    ("computed in S s (cold)" or "cached (computed in S s)")."""
    y0 = point.y0()
    key = repr(("taylor-mpmath", point.n, point.a, point.b, y0.tobytes().hex(),
                np.asarray(t, float).tobytes().hex(), digits))
    name = hashlib.sha256(key.encode()).hexdigest()[:24]
    path = cache / f"ref-{name}.npz"
    if path.exists():
        try:
            with np.load(path) as data:
                if str(data["key"]) == key:
                    return data["y"], f"cached (computed in {float(data['seconds']):.1f} s)"
        except (OSError, ValueError, KeyError):
            pass  # corrupt or foreign: recomputed below, never trusted
    sol = taylor.integrate(point.field(), y0, t, dps=digits)
    buf = io.BytesIO()
    np.savez(buf, y=sol.y, seconds=sol.seconds, key=key)
    write_atomic(path, buf.getvalue())
    return sol.y, f"computed in {sol.seconds:.1f} s (cold)"


def best(fn, repeats: int):
    """The solution with the smallest ``seconds`` over ``repeats`` runs (the first run's
    ``compile_seconds`` is kept: it is the cold compile or the warm load of this process)."""
    first = fn()
    out = first
    for _ in range(repeats - 1):
        sol = fn()
        if sol.seconds < out.seconds:
            out = sol
    out.compile_seconds = first.compile_seconds
    out.note = first.note
    return out


def dop853_rows(scene, point: Point, t, ref, rtols, repeats=3, with_drift=True) -> list[Row]:
    """DOP853 (scipy) at rtol = atol for each of ``rtols``."""
    rows = []
    for rtol in rtols:
        f = point.field()
        sol = best(lambda f=f, rtol=rtol: dop853.integrate(f, point.y0(), t, rtol=rtol, atol=rtol),
                   repeats)
        rows.append(Row(scene, float(t[-1]), "DOP853", f"rtol=atol={rtol:g}",
                        float(np.max(np.abs(sol.y - ref))), sol.seconds, 0.0, sol.calls, sol.steps,
                        drift(point, sol.y) if with_drift else {}))
    return rows


def rkmk4_rows(scene, point: Point, t, ref, steps, repeats=2) -> list[Row]:
    """The RKMK4 Lie-group integrator at each fixed step ``h`` (one run when it takes > 1 s)."""
    rows = []
    for h in steps:
        f = point.field()
        sol = lie.integrate(f, point.y0(), t, h=h)
        if sol.seconds < 1.0:
            sol = best(lambda f=f, h=h: lie.integrate(f, point.y0(), t, h=h), repeats)
        rows.append(Row(scene, float(t[-1]), "RKMK4", f"h={h:g}", float(np.max(np.abs(sol.y - ref))),
                        sol.seconds, 0.0, sol.calls, sol.steps, drift(point, sol.y)))
    return rows


def heyoka_rows(scene, field, y0, t, ref, tols, repeats=5, error=None, drift_of=None,
                precision="double", compact=None) -> list[Row]:
    """heyoka Taylor (our derived field, :mod:`simulate.integrators.heyoka_taylor`) at each
    tolerance; ``compile_seconds`` is the cold compile or warm cache load of the first run, the
    note says which. ``error(sol)`` overrides the max-abs error against ``ref``."""
    from chaplygin_nd.simulate.integrators import heyoka_taylor

    rows = []
    for tol in tols:
        sol = best(lambda tol=tol: heyoka_taylor.integrate(field, y0, t, tol=tol,
                                                           precision=precision, compact=compact),
                   repeats)
        err = error(sol) if error is not None else float(np.max(np.abs(sol.y - ref)))
        rows.append(Row(scene, float(t[-1]), "heyoka Taylor", f"tol={tol:g}" if precision == "double"
                        else f"{precision}", err, sol.seconds, sol.compile_seconds, sol.calls,
                        sol.steps, drift_of(sol.y) if drift_of is not None else {},
                        heyoka_note(sol)))
    return rows


def heyoka_note(sol) -> str:
    """"order p; unrolled|compact[, batch w]; cold compile|warm load|in memory" of a heyoka run."""
    parts = sol.note.split("; ")
    how = " ".join(parts[-1].split()[:2])
    return f"{sol.method.split(', ')[1]}; {'; '.join(parts[1:-1])}; {how}"


def timed(fn, repeats: int = 20) -> tuple[float, object]:
    """Minimum seconds of ``fn()`` over ``repeats`` calls, and its last value."""
    best_s, value = np.inf, None
    for _ in range(repeats):
        start = time.perf_counter()
        value = fn()
        best_s = min(best_s, time.perf_counter() - start)
    return best_s, value


def odefun_run(point: Point, t_end: float, dps: int, ref) -> tuple[float, float, int]:
    r"""``mpmath.odefun`` (its own Taylor method) on eq:motion-general to ``t_end`` at ``dps``
    digits, $\Omega$ by an mpmath solve of the definition of $L_\gamma$: (error against the mpmath
    values ``ref``, seconds, right-hand-side calls)."""
    import mpmath

    n, a, b = point.n, point.a, point.b
    rows, cols = so.pairs(n)
    N = len(rows)
    calls = [0]
    y0 = point.y0()[0]
    with mpmath.workdps(dps):

        def rhs(_t, y):
            calls[0] += 1
            m, g = y[:N], mpmath.matrix(y[N:])
            w = mpmath.lu_solve(taylor.L_matrix_mp(g, a, b, n), mpmath.matrix(m))
            O, M = mpmath.zeros(n, n), mpmath.zeros(n, n)
            for c, (i, j) in enumerate(zip(rows, cols, strict=True)):
                O[i, j], O[j, i], M[i, j], M[j, i] = w[c], -w[c], m[c], -m[c]
            C, Og = M * O - O * M, O * g
            return [C[i, j] for i, j in zip(rows, cols, strict=True)] + [-Og[k] for k in range(n)]

        start = time.perf_counter()
        F = mpmath.odefun(rhs, 0, [mpmath.mpf(float(v)) for v in y0])
        y = F(t_end)
        seconds = time.perf_counter() - start
        err = max(abs(x - r) for x, r in zip(y, ref, strict=True))
    return float(err), seconds, calls[0]
