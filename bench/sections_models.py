r"""Sections 4–6 of the work–precision benchmark (see :mod:`bench.bench_work_precision`): the long
run and the drift of the integrals, the cheaper models for invariant-only outputs, and ensembles."""

from __future__ import annotations

import numpy as np
from chaplygin_nd.bench.figures import drift_figure, figure
from chaplygin_nd.bench.report import target
from chaplygin_nd.bench.runs import Point, Row, best, drift, heyoka_rows, reference, timed
from chaplygin_nd.bench.sections import Context, cheapest, versus
from chaplygin_nd.simulate.dynamics import families, so
from chaplygin_nd.simulate.dynamics.closed_forms import horizontal
from chaplygin_nd.simulate.dynamics.field import FullField, ReducedField
from chaplygin_nd.simulate.dynamics.so import reduced_invariants
from chaplygin_nd.simulate.integrators import dop853, lie
from chaplygin_nd.simulate.kernels import active
from chaplygin_nd.simulate.scene.outputs import p_coefficients

LONG_T, LONG_SAMPLES, LONG_H = 1000.0, 101, 0.05
ROUNDING = 1e-12  # "at rounding level": the isospectral invariants stay below this


def drift_series(point: Point, y: np.ndarray) -> dict[str, np.ndarray]:
    """|H(t) - H(0)|, max |p(t) - p(0)| and | |gamma(t)|^2 - 1 | at every sample of ``y``."""
    f = point.field()
    M, gamma = f.unpack(y[:, 0])
    Omega = active().require("angular_velocity")(M, gamma, point.a, point.b)
    H = 0.5 * so.killing(M, Omega)
    p = p_coefficients(M, gamma)
    return {"H": np.abs(H - H[0]), "p": np.max(np.abs(p - p[:1]), axis=(-1, -2)),
            "|gamma|^2": np.abs(np.einsum("...i,...i->...", gamma, gamma) - 1.0)}


def growth(steps: np.ndarray, series: np.ndarray) -> tuple[float, float]:
    r"""Fit $d_{\max}(N) \approx c N^\alpha$ to the running maximum of ``series`` against the step
    count over the second half of the samples; returns $(\alpha, c)$ (NaN when the drift is 0)."""
    running = np.maximum.accumulate(series)
    keep = (steps > 0) & (running > 0)
    keep[: len(steps) // 2] = False
    if keep.sum() < 3:
        return float("nan"), float("nan")
    alpha, logc = np.polyfit(np.log(steps[keep]), np.log(running[keep]), 1)
    return float(alpha), float(np.exp(logc))


def section_long(ctx: Context):
    """Generic n = 4 to T = 10^3 (101 samples): DOP853, RKMK4 (h = 0.05, 2e4 steps), heyoka;
    errors against a 21-digit reference; drift of the integrals, RKMK4's extrapolated to 1e6 steps."""
    g4 = Point.draw("generic", 4, 0.5, 1.0, 7)
    T = LONG_T * (0.01 if ctx.quick else 1.0)
    t = np.linspace(0.0, T, LONG_SAMPLES)
    ref, how = reference(g4, t, 21, ctx.cache)
    name = f"generic4d T={T:g}"
    rows, series = [], {}
    for rtol in (1e-10, 2.3e-14):
        f = g4.field()
        sol = dop853.integrate(f, g4.y0(), t, rtol=rtol, atol=rtol)
        rows.append(Row(name, T, "DOP853", f"rtol=atol={rtol:g}", float(np.max(np.abs(sol.y - ref))),
                        sol.seconds, 0.0, sol.calls, sol.steps, drift(g4, sol.y)))
        series[f"DOP853 rtol {rtol:g}"] = drift_series(g4, sol.y)
    f = g4.field()
    sol = lie.integrate(f, g4.y0(), t, h=LONG_H)
    rk = Row(name, T, "RKMK4", f"h={LONG_H:g}", float(np.max(np.abs(sol.y - ref))), sol.seconds, 0.0,
             sol.calls, sol.steps, drift(g4, sol.y))
    rows.append(rk)
    series[f"RKMK4 h={LONG_H:g}"] = rk_series = drift_series(g4, sol.y)
    if ctx.heyoka:
        hys = heyoka_rows(name, g4.field(), g4.y0(), t, ref, (1e-15,), repeats=2,
                          drift_of=lambda y: drift(g4, y))
        rows += hys
        from chaplygin_nd.simulate.integrators import heyoka_taylor

        hsol = heyoka_taylor.integrate(g4.field(), g4.y0(), t, tol=1e-15)
        series["heyoka tol 1e-15"] = drift_series(g4, hsol.y)
    figure(ctx.out / "work_precision_long.png", rows,
           f"generic n=4, T={T:g}; reference: our Taylor, 21 digits ({how})")
    drift_figure(ctx.out / "work_precision_drift.png", t,
                 {k: (v["H"], v["p"]) for k, v in series.items()},
                 f"integral drift, generic n = 4, T = {T:g} ({rk.steps} RKMK4 steps)")
    steps = np.round(t / LONG_H)
    fits = {k: growth(steps, rk_series[k]) for k in ("p", "|gamma|^2")}
    target_steps = 10 ** 6
    extrapolated = {k: rk.drift[k] * (target_steps / rk.steps) ** max(a, 0.5)
                    for k, (a, _) in fits.items() if np.isfinite(a)}
    worst = max(extrapolated.values(), default=max(rk.drift["p"], rk.drift["|gamma|^2"]))
    detail = (f"measured over {rk.steps:,} steps (T={T:g}, h={LONG_H:g}, {rk.seconds:.1f} s): drift p "
              f"{rk.drift['p']:.1e}, |gamma|^2 {rk.drift['|gamma|^2']:.1e}; growth exponents "
              + ", ".join(f"{k} {a:.2f}" for k, (a, _) in fits.items())
              + " (0.5 = random walk of rounding errors); extrapolated to 10^6 steps with "
              "max(exponent, 0.5): " + ", ".join(f"{k} {v:.1e}" for k, v in extrapolated.items())
              + f"; energy drift {rk.drift['H']:.1e} (O(h^4) truncation, not conserved by "
              "construction)")
    dops = [r for r in rows if r.method == "DOP853"]
    detail += "; DOP853 drift of p: " + ", ".join(f"{r.setting} {r.drift['p']:.1e}" for r in dops)
    return rows, [target("RKMK4 isospectral drift at rounding level (< 1e-12) over 10^6 steps "
                         "(extrapolated from the measured growth)", worst < ROUNDING, detail)]


def _model_rows(ctx: Context, label: str, point: Point, t, closed: bool) -> list[Row]:
    """Reduced invariants of ``point`` over ``t`` by each model, against the 30-digit reference."""
    T = float(t[-1])
    ref, _ = reference(point, t, 30, ctx.cache)
    f = point.field()
    r_ref = reduced_invariants(*f.unpack(ref))
    name = f"{label} T={T:g} (reduced outputs)"
    y0, r0 = point.y0(), reduced_invariants(point.M0, point.gamma0)
    red = ReducedField(point.a, point.b)
    rows = []

    def full_error(y):
        return float(np.max(np.abs(reduced_invariants(*f.unpack(y)) - r_ref)))

    for rtol in (1e-10, 1e-13):
        full = best(lambda rtol=rtol: dop853.integrate(f, y0, t, rtol=rtol, atol=rtol), 3)
        rows.append(Row(name, T, "full + DOP853", f"rtol={rtol:g}", full_error(full.y), full.seconds,
                        0.0, full.calls, full.steps))
        rs = best(lambda rtol=rtol: dop853.integrate(red, r0, t, rtol=rtol, atol=rtol), 3)
        rows.append(Row(name, T, "reduced 7D + DOP853", f"rtol={rtol:g}",
                        float(np.max(np.abs(rs.y - r_ref))), rs.seconds, 0.0, rs.calls, rs.steps))
    if ctx.heyoka:
        for r in heyoka_rows(name, f, y0, t, None, (1e-9, 1e-12), error=lambda s: full_error(s.y)):
            r.method = "full + heyoka"
            rows.append(r)
        for r in heyoka_rows(name, red, r0, t, None, (1e-9, 1e-12),
                             error=lambda s: float(np.max(np.abs(s.y - r_ref)))):
            r.method = "reduced 7D + heyoka"
            rows.append(r)
    if closed:
        seconds, r = timed(lambda: horizontal(r0, point.a, point.b, t))
        rows.append(Row(name, T, "closed form (S5:H-linear)", "corrected",
                        float(np.max(np.abs(r - r_ref))), seconds, 0.0, 3, 0))
    return rows


def section_models(ctx: Context):
    """n = 4, reduced invariants only, T = 100: full field versus the reduced 7D field (DOP853 and
    heyoka) versus the closed form; and what the planner picks for such a scene."""
    T = 100.0 * ctx.scale
    t = np.linspace(0.0, T, 11)
    rows, lines = [], []
    for label, family, a, b, seed in (("horizontal4d", "horizontal", 0.3, 1.0, 5),
                                      ("reduced4d", "generic", -0.4, 0.7, 21)):
        rows += _model_rows(ctx, label, Point.draw(family, 4, a, b, seed), t, family == "horizontal")
    figure(ctx.out / "work_precision_models.png", rows,
           f"n=4, reduced invariants only, T={T:g}: full vs reduced 7D vs closed form")
    mine = [r for r in rows if r.scene.startswith("reduced4d")]
    for tol in ("1e-09", "1e-12"):
        full = next((r for r in mine if r.method == "full + heyoka" and tol in r.setting), None)
        red = next((r for r in mine if r.method == "reduced 7D + heyoka" and tol in r.setting), None)
        lines.append(target(
            f"heyoka on the reduced 7D field beats heyoka on the full field (reduced outputs, "
            f"generic n=4, T={T:g}, tol {tol}, warm)",
            bool(full and red and red.seconds < full.seconds),
            f"reduced {red.seconds * 1e3:.2f} ms (error {red.error:.1e}) vs full "
            f"{full.seconds * 1e3:.2f} ms (error {full.error:.1e}): {full.seconds / red.seconds:.1f}x; "
            f"compile/load {red.compile_seconds:.2f} s vs {full.compile_seconds:.2f} s"
            if full and red else "not measured: heyoka not importable"))
    lines.append(_planner_line(mine))
    return rows, lines


def _planner_line(rows) -> str:
    """Is the planner's choice for ``scenes/reduced4d.toml`` (same point, T = 50) the cheapest
    measured run that meets its accuracy target?"""
    from pathlib import Path

    from chaplygin_nd.simulate.scene import planner
    from chaplygin_nd.simulate.scene.spec import load

    scene = load(Path(__file__).resolve().parent.parent / "scenes" / "reduced4d.toml")
    chosen = planner.plan(scene)
    ok = cheapest(rows, scene.target)
    label = {"full + DOP853": ("full", "dop853"), "reduced 7D + DOP853": ("reduced-7D", "dop853"),
             "full + heyoka": ("full", "heyoka"), "reduced 7D + heyoka": ("reduced-7D", "heyoka")}
    pick = label.get(ok.method) if ok else None
    return target("the planner's choice for invariant-only outputs is the cheapest measured run "
                  f"meeting the scene's target ({scene.target:g})",
                  pick == (chosen.model, chosen.method),
                  f"planner: {chosen.model} + {chosen.method}; cheapest measured (warm): "
                  + (f"{ok.method} {ok.setting}, {ok.seconds * 1e3:.2f} ms, error {ok.error:.1e}"
                     if ok else "none reached the target"))


def section_ensemble(ctx: Context):
    """An ensemble of 256 generic n = 4 points to T = 10: stacked DOP853, vectorised RKMK4, heyoka
    in batch (SIMD) mode; errors over the first 8 points against a 20-digit reference."""
    count = 32 if ctx.quick else 256
    T = 10.0
    a, b = 0.5, 1.0
    M0, g0 = families.draw("generic", 4, a, b, 99, count)
    f = FullField(4, a, b)
    y0 = f.pack(M0, g0)
    t = np.array([0.0, T])
    ref, how = reference(Point(4, a, b, M0[:8], g0[:8]), t, 20, ctx.cache)
    name = f"ensemble of {count}, n=4, T={T:g}"
    rows = []
    for rtol in (1e-10, 1e-12):
        st = best(lambda rtol=rtol: dop853.integrate(f, y0, t, rtol=rtol, atol=rtol), 2)
        rows.append(Row(name, T, "DOP853 stacked", f"rtol={rtol:g}",
                        float(np.max(np.abs(st.y[-1, :8] - ref[-1]))), st.seconds, 0.0, st.calls,
                        st.steps))
    lsol = lie.integrate(f, y0, t, h=0.05)
    rows.append(Row(name, T, "RKMK4 vectorised", "h=0.05",
                    float(np.max(np.abs(lsol.y[-1, :8] - ref[-1]))), lsol.seconds, 0.0, lsol.calls,
                    lsol.steps))
    hys = []
    if ctx.heyoka:
        hys = heyoka_rows(name, f, y0, t, None, (1e-9, 1e-12), repeats=3,
                          error=lambda s: float(np.max(np.abs(s.y[-1, :8] - ref[-1]))))
        for r in hys:
            r.method = "heyoka batch (SIMD)"
        rows += hys
    figure(ctx.out / "work_precision_ensemble.png", rows,
           f"{name}: error over 8 points against our Taylor, 20 digits ({how})")
    dop = rows[0]
    hy = cheapest(hys, dop.error)
    return rows, [versus(dop, hy, f"heyoka batch >= 10x faster than stacked DOP853 at equal or "
                         f"better error ({name})", 10)]
