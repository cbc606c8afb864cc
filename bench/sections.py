r"""Sections 1–3 of the work–precision benchmark (see :mod:`bench.bench_work_precision`): each
runs its methods, draws its figure and returns ``(rows, target lines)``."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
from chaplygin_nd.bench.figures import figure
from chaplygin_nd.bench.report import target
from chaplygin_nd.bench.runs import (
    Point,
    Row,
    best,
    dop853_rows,
    drift,
    heyoka_note,
    heyoka_rows,
    odefun_run,
    reference,
    rkmk4_rows,
    timed,
)
from chaplygin_nd.simulate.dynamics import families, so
from chaplygin_nd.simulate.dynamics.closed_forms import relative_equilibrium
from chaplygin_nd.simulate.integrators import taylor
from chaplygin_nd.simulate.kernels import active

RTOLS = (1e-6, 1e-8, 1e-10, 1e-11, 1e-12, 1e-13, 2.3e-14)
STEPS = (0.2, 0.1, 0.05, 0.025)
HY_TOLS = (1e-6, 1e-9, 1e-12, 1e-15)


@dataclasses.dataclass
class Context:
    """Where to write, whether this is a smoke run, whether heyoka imports."""

    out: Path
    cache: Path
    quick: bool
    heyoka: bool

    @property
    def scale(self) -> float:
        return 0.1 if self.quick else 1.0


def cheapest(rows, max_error):
    ok = [r for r in rows if r.error <= max_error]
    return min(ok, key=lambda r: r.seconds) if ok else None


def versus(ours, hy, label, factor):
    """Target line: heyoka row ``hy`` at least ``factor`` x faster than ``ours`` (warm), with the
    cold ratio (run + this process's compile or cache load) beside it."""
    if hy is None or ours is None:
        return target(label, False, "not measured (heyoka not importable or no run reached the "
                      "error)" if hy is None else "no reference run reached the error")
    warm = ours.seconds / hy.seconds
    cold = ours.seconds / (hy.seconds + hy.compile_seconds)
    return target(label, warm >= factor,
                  f"warm {warm:.0f}x: heyoka {hy.setting} error {hy.error:.1e} in "
                  f"{hy.seconds * 1e3:.2f} ms vs {ours.method} {ours.setting} error "
                  f"{ours.error:.1e} in {ours.seconds * 1e3:.1f} ms; with heyoka's "
                  f"{hy.note.split('; ')[-1]} {hy.compile_seconds:.2f} s: {cold:.2g}x")


def section_generic4d(ctx: Context):
    """Generic n = 4 to T = 100: DOP853, RKMK4, heyoka against a 30-digit reference."""
    g4 = Point.draw("generic", 4, 0.5, 1.0, 7)
    T = 100.0 * ctx.scale
    t = np.linspace(0.0, T, 11)
    ref, how = reference(g4, t, 30, ctx.cache)
    name = f"generic4d T={T:g}"
    dops = dop853_rows(name, g4, t, ref, RTOLS)
    rows = dops + rkmk4_rows(name, g4, t, ref, STEPS[:2] if ctx.quick else STEPS)
    hys, compact = [], []
    if ctx.heyoka:
        hys = heyoka_rows(name, g4.field(), g4.y0(), t, ref, HY_TOLS, drift_of=lambda y: drift(g4, y))
        compact = heyoka_rows(name, g4.field(), g4.y0(), t, ref, (1e-12,), compact=True,
                              drift_of=lambda y: drift(g4, y))
        for r in compact:
            r.method = "heyoka Taylor (compact mode)"
    rows += hys + compact
    fastest = cheapest(dops, 1e-12)
    best_dop = fastest or min(dops, key=lambda r: r.error)
    lines = [target(f"DOP853 error <= 1e-12 on generic n=4 to T={T:g} in < 1 s",
                    fastest is not None and fastest.seconds < 1,
                    f"{best_dop.setting}: error {best_dop.error:.1e} in {best_dop.seconds:.3f} s "
                    f"({best_dop.calls} calls)")]
    hy = cheapest(hys, min(best_dop.error, 1e-12)) if hys else None
    lines.append(versus(best_dop, hy, f"heyoka >= 50x faster than DOP853 at equal error <= 1e-12 "
                         f"(generic n=4, T={T:g}, warm cache)", 50))
    script = _hand_written(name, g4, t, ref, float(hy.setting.split("=")[1])) if hy else None
    if script is not None:
        rows.append(script)
    figure(ctx.out / "work_precision_generic4d.png", rows,
           f"generic n=4, a=0.5, b=1, T={T:g}; reference: our Taylor, 30 digits ({how})")
    lines.append(target(
        f"heyoka (ours) within 1.5x of a hand-written heyoka script (generic n=4, T={T:g})",
        script is not None and hy.seconds <= 1.5 * script.seconds,
        f"ours {hy.seconds * 1e3:.3f} ms vs script {script.seconds * 1e3:.3f} ms at {script.setting}"
        f" ({hy.seconds / script.seconds:.2f}x; errors {hy.error:.1e} vs {script.error:.1e}); "
        f"script compile {script.compile_seconds:.1f} s (heyoka's disk cache off)"
        if script is not None else "not measured: heyoka not importable"))
    return rows, lines


def _hand_written(name, point: Point, t, ref, tol: float) -> Row:
    """What a user would write by hand (``bench.bench_heyoka.hand_written_script``: ``from_sympy`` of
    our derived SymPy field, one ``taylor_adaptive``, ``propagate_grid``) at tolerance ``tol``."""
    from chaplygin_nd.bench.bench_heyoka import hand_written_script

    err, seconds, compile_seconds = hand_written_script(tol)(point.y0()[0], t, ref[:, 0])
    return Row(name, float(t[-1]), "heyoka hand-written script", f"tol={tol:g}", err, seconds,
               compile_seconds, note="heyoka.from_sympy of the derived SymPy field; no cache")


def section_vertical5d(ctx: Context):
    """Vertical n = 5 to T = 100: the closed form of Th:Re against the integrators."""
    v5 = Point.draw("vertical", 5, -0.6, 2.0, 11)
    T = 100.0 * ctx.scale
    t = np.linspace(0.0, T, 11)
    ref, how = reference(v5, t, 30, ctx.cache)
    name = f"vertical5d T={T:g}"
    k = active()

    def closed():
        zeta = k.require("zeta")(v5.M0, v5.gamma0, v5.a, v5.b)
        Omega0 = k.require("angular_velocity")(v5.M0, v5.gamma0, v5.a, v5.b)
        return relative_equilibrium(zeta[0], v5.M0[0], v5.gamma0[0], Omega0[0], t)

    seconds, sol = timed(closed)
    y = np.concatenate([so.vec(sol["M"]), sol["gamma"]], axis=-1)[:, None, :]
    cf = Row(name, T, "closed form (Th:Re)", "exp(zeta t)", float(np.max(np.abs(y - ref))), seconds,
             0.0, 2, 0, drift(v5, y))
    dops = dop853_rows(name, v5, t, ref, RTOLS)
    rows = [cf, *dops, *rkmk4_rows(name, v5, t, ref, STEPS[1:2] if ctx.quick else STEPS[1:])]
    if ctx.heyoka:  # compact mode: n = 5 unrolled compiles in ~20 s per tolerance (measured)
        for r in heyoka_rows(name, v5.field(), v5.y0(), t, ref, (1e-9, 1e-15), compact=True,
                             drift_of=lambda y: drift(v5, y)):
            r.method = "heyoka Taylor (compact mode)"
            rows.append(r)
    figure(ctx.out / "work_precision_vertical5d.png", rows,
           f"vertical n=5, a=-0.6, b=2, T={T:g}; reference: our Taylor, 30 digits ({how})")
    equal = cheapest(dops, cf.error)
    cmp = equal or min(dops, key=lambda r: r.error)
    ratio = cmp.seconds / cf.seconds
    return rows, [target(
        f"closed form >= 100x cheaper than DOP853 at equal accuracy (vertical n=5, T={T:g})",
        ratio >= 100,
        f"closed form error {cf.error:.1e} in {cf.seconds * 1e3:.2f} ms; DOP853 {cmp.setting} error "
        f"{cmp.error:.1e} in {cmp.seconds * 1e3:.1f} ms: {ratio:.0f}x"
        + ("" if equal else " (DOP853 never reaches the closed form's error; its most accurate run)"))]


def exact_point() -> Point:
    r"""Generic n = 4 (a = 0.5, b = 1) with $\gamma_0 = (1/2, 1/2, 1/2, 1/2)$, exactly on $S^3$ in binary
    floats. Needed beyond 20 digits: off the sphere (a float-normalised $\gamma_0$ has
    $\|\gamma_0\|^2 - 1 \approx 10^{-16}$) heyoka's field (the derived $L_\gamma^{-1}$ formula, valid
    on the sphere) and our Taylor method (a solve of $L_\gamma$) are different ODEs: measured, they
    part at $6.5\cdot10^{-21}$ by $T = 0.5$ at every precision."""
    M0, _ = families.draw("generic", 4, 0.5, 1.0, 7)
    return Point(4, 0.5, 1.0, M0, np.full((1, 4), 0.5))


def _mp_error(high, ref):
    return float(max(abs(x - y) for x, y in zip(high, ref, strict=True)))


def section_precision(ctx: Context):
    """Generic n = 4 exactly on the sphere (:func:`exact_point`): our Taylor method, mpmath.odefun
    and heyoka real128/real at 15-40 digits to T = 5; the 30-digit reference to T = 20 by our Taylor
    method and by heyoka real."""
    g4 = exact_point()
    f, y0 = g4.field(), g4.y0()
    Tm = 5.0 * ctx.scale
    tm = np.array([0.0, Tm])
    ref = taylor.integrate(f, y0, tm, dps=60).y_high[-1, 0]
    name = f"generic4d T={Tm:g}"
    rows = []
    for dps in (15, 20, 30, 40):
        sol = best(lambda dps=dps: taylor.integrate(f, y0, tm, dps=dps), 2)
        rows.append(Row(name, Tm, "Taylor (ours, mpmath)", f"{dps} digits",
                        _mp_error(sol.y_high[-1, 0], ref), sol.seconds, 0.0, sol.calls, sol.steps))
    for dps in (15, 20):  # 30 digits took 17.5 s (cost ~ dps^2.7); the trend shows at 15, 20
        err, seconds, calls = odefun_run(g4, Tm, dps, ref)
        rows.append(Row(name, Tm, "mpmath.odefun", f"{dps} digits", err, seconds, 0.0, calls, 0))
    hy_rows = []
    if ctx.heyoka:
        from chaplygin_nd.simulate.integrators import heyoka_taylor as ht

        for label, prec in (("real128", "real128"), *((f"real, {d} digits", ht.bits_for_digits(d))
                                                        for d in (20, 30, 40))):
            sol = best(lambda prec=prec: ht.integrate(f, y0, tm, precision=prec, compact=True), 2)
            hy_rows.append(Row(name, Tm, "heyoka Taylor", label, _mp_error(sol.y_high[-1, 0], ref),
                               sol.seconds, sol.compile_seconds, sol.calls, sol.steps,
                               note=heyoka_note(sol)))
    rows += hy_rows
    figure(ctx.out / "work_precision_mpmath.png", rows,
           f"generic n=4, T={Tm:g}: high precision; reference: our Taylor, 60 digits")
    # the 30-digit reference to T = 20
    T20 = 20.0 * ctx.scale
    t20 = np.array([0.0, T20])
    s40 = taylor.integrate(f, y0, t20, dps=40).y_high[-1, 0]
    s30 = best(lambda: taylor.integrate(f, y0, t20, dps=30), 2)
    e30 = _mp_error(s30.y_high[-1, 0], s40)
    n20 = f"generic4d T={T20:g}"
    rows.append(Row(n20, T20, "Taylor (ours, mpmath)", "30 digits", e30, s30.seconds, 0.0, s30.calls,
                    s30.steps, note="error against our Taylor at 40 digits"))
    lines = [target(f"30-digit reference to T={T20:g} in < 10 s (our Taylor)",
                    s30.seconds < 10 and e30 < 1e-29,
                    f"{s30.seconds:.2f} s, {s30.steps} steps, difference to 40 digits {e30:.1e}")]
    if ctx.heyoka:
        from chaplygin_nd.simulate.integrators import heyoka_taylor as ht

        hsol = best(lambda: ht.integrate(f, y0, t20, precision=ht.bits_for_digits(30)), 3)
        eh = _mp_error(hsol.y_high[-1, 0], s40)
        agree = _mp_error(hsol.y_high[-1, 0], s30.y_high[-1, 0])
        digits = -np.log10(max(agree, 1e-40))
        rows.append(Row(n20, T20, "heyoka Taylor", "real, 30 digits", eh, hsol.seconds,
                        hsol.compile_seconds, hsol.calls, hsol.steps,
                        note=f"{heyoka_note(hsol)}; agrees with our Taylor (30 digits) to "
                             f"{agree:.1e}"))
        warm = s30.seconds / hsol.seconds
        how = heyoka_note(hsol).split("; ")[-1]
        same = next((r for r in hy_rows if r.setting == "real, 30 digits"), None)
        if same is not None and hsol.compile_seconds == 0.0:  # compiled for the T = 5 row above
            hsol.compile_seconds = same.compile_seconds
            how = same.note.split("; ")[-1] + " (T = 5 row)"
        cold = s30.seconds / (hsol.seconds + hsol.compile_seconds)
        lines.append(target(
            f"30-digit reference to T={T20:g}: heyoka real faster than our mpmath Taylor (warm), "
            "agreement >= 28 digits", warm > 1 and digits >= 28,
            f"warm {warm:.1f}x ({hsol.seconds:.3f} s vs {s30.seconds:.2f} s); with heyoka's "
            f"{how} {hsol.compile_seconds:.2f} s: {cold:.2g}x; the two agree to "
            f"{agree:.1e} ({digits:.1f} digits); errors against 40 digits: heyoka {eh:.1e}, "
            f"ours {e30:.1e}"))
    else:
        lines.append(target(f"30-digit reference to T={T20:g}: heyoka real faster than our Taylor",
                            False, "not measured: heyoka not importable"))
    return rows, lines
