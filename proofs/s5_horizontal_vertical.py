r"""S5:H-SO3, S5:V-SO3, S5:V-equilibria, eq:A-on-J, S5:H-linear — $\mathcal{H}$ and $\mathcal{V}$ reduced.

**Claims (lines 887-937).**
$\mathcal{H}/SO(3) = \{F_1 = 0, E = 0, xA = -\delta, (1-x^2)B - G^2 = -x\delta\}$,
$\mathcal{V}/SO(3) = \{G = 0, F_1 = 0, xB = \delta, (1-x^2)A - E^2 = x\delta\}$, both invariant;
$\mathcal{V}/SO(3)$ consists of equilibria; on $\mathcal{H}/SO(3)\cap\{H = h, F_2 = f_2\}$
$A = \frac{(2h(1-x^2)(a+b+2) - G^2)\Delta}{(a+b+2)(2+a(1-x^2))} = (1-x^2)f_2 - G^2$ (eq:A-on-J),
$\dot G = -\frac{f_2-2bh}{2+a}x$, $\dot x = \frac{G}{a+b+2}$, solved by $x = x_0\cos\omega t$,
$G = -(a+b+2)x_0\omega\sin\omega t$ with
$\omega^2 = \frac{f_2-2bh}{2+a} = \frac{aG_0^2 + 4h(a+b+2)}{(a+b+2)(2+a(1-x_0^2))} \ge 0$.

In our words. On $\mathcal{H}$ with $x\ne0$, $k = q\times u/x$ (S5:HV4D), which gives the four printed
relations; conversely any $(A, G, x)$ satisfying them with $A\ge0$, $|x|<1$ is realised (choose
$u, q$ with Gram $(B, G, 1-x^2)$ — possible as $(1-x^2)B - G^2 = x^2A \ge 0$ — and $k = q\times u/x$),
so $\mathcal{H}/SO(3)$ is the graph over $(A, G, x)$ of $F_1 = E = 0$, $\delta = -xA$,
$B = (x^2A + G^2)/(1-x^2)$ (dimension 3); on it $F_3 = 0$. Likewise $\mathcal{V}/SO(3)$ is the graph
over $(B, E, x)$ of $G = F_1 = 0$, $\delta = xB$, $A = (E^2 + x^2B)/(1-x^2)$ ($u = -k\times q/x$). The
derived reduced field is tangent to both and vanishes on $\mathcal{V}/SO(3)$; both expressions of
eq:A-on-J, the linear system and the equality of the two $\omega^2$ hold; moreover
$\omega^2 = (G^2 + 2(a+b+2)A/\Delta)/((a+b+2)(1-x^2)) \ge 0$.

**Finding.** The printed solution is wrong twice: it has $G(0) = 0$ (so it only covers $G_0 = 0$),
and its frequency is off: $\dot x = G/S$, $\dot G = -\omega^2x$ ($S = a+b+2$) give
$\ddot x = -(\omega^2/S)x$, so the frequency is $\nu = \omega/\sqrt{S}$, not $\omega$. Corrected:
$x(t) = x_0\cos\nu t + \frac{G_0}{S\nu}\sin\nu t$, $G(t) = G_0\cos\nu t - Sx_0\nu\sin\nu t$,
$\nu^2 = \frac{f_2-2bh}{(2+a)(a+b+2)}$.

**Uses** S5:HV4D, eq:red-system, S5:red-integrals. **Proves** exact rational identities in the
graph coordinates (and on the slices $x = 0$); the printed solution is refuted at exact points of
$\mathcal{H}$; the corrected one is proved with $c = \cos\nu t$, $s = \sin\nu t$,
$\dot c = -\nu s$, $\dot s = \nu c$, with the derived $\nu^2(h, f_2)$ the kernels use
(:func:`symbolic.reduction.reduced_n4.horizontal_frequency_squared`, modulo $\nu^2 - \nu^2(h, f_2)$) against the
printed $\omega^2(h, f_2)$; the kernels' $A(x, G; h)$ (:func:`symbolic.reduction.reduced_n4.horizontal_level_A`)
is compared with the first expression of eq:A-on-J. $n = 4$.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.proofs.s5_common import SAMPLERS, exact, horizontal_point, invariants_at, on_P
from chaplygin_nd.symbolic import fourd
from chaplygin_nd.symbolic.exact.identity import rational_identity, zero_at_points
from chaplygin_nd.symbolic.printed import section5 as printed
from chaplygin_nd.symbolic.reduction import invariants_n4 as ri
from chaplygin_nd.symbolic.reduction import reduced_n4

a, b, x, k, u, q = fourd.a, fourd.b, fourd.x, fourd.k, fourd.u, fourd.q
A, B, E, G, F1, delta = ri.A, ri.B, ri.E, ri.G, ri.F1, ri.delta
S = a + b + 2
h, f2, t, x0, G0, nu, c, s = sp.symbols("h f2 t x0 G0 nu c s", real=True)


def _inv(kk, uu, qq):
    d = lambda p, r: (p.T * r)[0, 0]  # noqa: E731
    return {A: d(kk, kk), B: d(uu, uu), E: d(kk, qq), G: d(uu, qq), F1: d(kk, uu),
            delta: d(qq, kk.cross(uu))}


def _on_S2(expr, label):
    """Identity on the slice x = 0 of S^3, i.e. for q on the unit sphere S^2."""
    return rational_identity(expr, sphere=tuple(q), samplers=SAMPLERS, label=label)


def _on(sub, exprs):
    return [sp.together(sp.sympify(e).xreplace(sub)) for e in exprs]


def _tangent(constraints, graph, label):
    X = reduced_n4.field()
    lie = [sum(sp.diff(cn, reduced_n4.SYMBOLS[n]) * X[n] for n in reduced_n4.COORDS) for cn in constraints]
    return exact(sp.Matrix(_on(graph, lie)), label)


@claim("S5:H-SO3", uses=("S5:HV4D", "eq:red-system", "S5:red-integrals"))
def h_so3() -> Verdict:
    shown = printed.H_SO3(A, B, E, G, F1, x, delta)
    image = _inv(q.cross(u) / x, u, q)                          # H, x != 0
    w = sp.Matrix(sp.symbols("w1:4", real=True))
    slice0 = {**_inv(q.cross(w), G0 * q, q), x: 0}             # H at x = 0: k _|_ q, u = G q
    ints = reduced_n4.integrals()
    return Verdict.all_of([
        ("pi(H), x != 0, satisfies the relations", on_P(sp.Matrix(_on(image, shown)), "HSO3 image")),
        ("pi(H), x = 0", _on_S2(sp.Matrix(_on(slice0, shown)), "HSO3 x=0")),
        ("graph satisfies the relations", exact(sp.Matrix(_on(reduced_n4.horizontal_set(), shown)),
                                                "HSO3 graph")),
        ("invariant under the reduced field", _tangent(shown, reduced_n4.horizontal_set(), "HSO3 inv")),
        ("F1 = F3 = 0 on it", exact(sp.Matrix(_on(reduced_n4.horizontal_set(),
                                                  [ints["F1"], ints["F3"]])), "HSO3 F3")),
    ], n_values=(4,), method="exact rational identities (image of k = q x u/x modulo |gamma|^2 = 1; "
                             "graph over (A, G, x); tangency of the derived reduced field)")


@claim("S5:V-SO3", uses=("S5:HV4D", "eq:red-system"))
def v_so3() -> Verdict:
    shown = printed.V_SO3(A, B, E, G, F1, x, delta)
    image = _inv(k, -k.cross(q) / x, q)
    w = sp.Matrix(sp.symbols("w1:4", real=True))
    slice0 = {**_inv(E * q, q.cross(w), q), x: 0}              # V at x = 0: k = E q, u _|_ q
    return Verdict.all_of([
        ("pi(V), x != 0, satisfies the relations", on_P(sp.Matrix(_on(image, shown)), "VSO3 image")),
        ("pi(V), x = 0", _on_S2(sp.Matrix(_on(slice0, shown)), "VSO3 x=0")),
        ("graph satisfies the relations", exact(sp.Matrix(_on(reduced_n4.vertical_set(), shown)),
                                                "VSO3 graph")),
        ("invariant under the reduced field", _tangent(shown, reduced_n4.vertical_set(), "VSO3 inv")),
    ], n_values=(4,), method="exact rational identities (image of u = -k x q/x modulo "
                             "|gamma|^2 = 1; graph over (B, E, x); tangency)")


@claim("S5:V-equilibria", uses=("S5:V-SO3", "eq:red-system", "Th:Re"))
def v_equilibria() -> Verdict:
    X = reduced_n4.field()
    on_graph = sp.Matrix(_on(reduced_n4.vertical_set(), [X[n] for n in reduced_n4.COORDS]))
    at0 = sp.Matrix(_on({G: 0, F1: 0, delta: 0, A: E**2, x: 0}, [X[n] for n in reduced_n4.COORDS]))
    return Verdict.all_of([("x != 0", exact(on_graph, "Veq graph")),
                           ("x = 0 (A = E^2, delta = 0)", exact(at0, "Veq x=0"))], n_values=(4,),
                          method="exact: all 7 derived components vanish on the graph of V/SO(3)")


def _level():
    """h, f2 as functions of (A, G, x) on H/SO(3) (derived integrals)."""
    ints = reduced_n4.integrals()
    g = reduced_n4.horizontal_set()
    return sp.together(ints["H"].xreplace(g)), sp.together(ints["F2"].xreplace(g))


@claim("eq:A-on-J", uses=("S5:H-SO3", "S5:red-integrals"))
def a_on_j() -> Verdict:
    hh, ff = _level()
    first, second = printed.A_on_J(G, x, hh, ff, a, b)
    level = reduced_n4.horizontal_level_A(h)  # A(x, G; h), what generated/reduced_n4.py evaluates
    first_h, _ = printed.A_on_J(G, x, h, f2, a, b)
    return Verdict.all_of([("first (from H = h)", exact(first - A, "AJ 1")),
                           ("second (from F2 = f2)", exact(second - A, "AJ 2")),
                           ("the emitted A(x, G; h) (solved from the derived H) = first",
                            exact(level - first_h, "AJ emitted"))], n_values=(4,),
                          method="exact: with h = H and f2 = F2 evaluated on the graph of H/SO(3); "
                                 "the kernel's A(x, G; h) against the first printed expression")


def _printed_solution_at(pt):
    inv = invariants_at(pt)
    hh, ff = (sp.sympify(v).xreplace({A: inv[A], G: inv[G], x: pt["x"], a: pt["a"], b: pt["b"]})
              for v in _level())
    w2, _ = printed.omega_squared(hh, ff, inv[G], pt["x"], pt["a"], pt["b"])
    om = sp.Symbol("omega", positive=True)
    xs, Gs = printed.H_linear_solution(t, pt["x"], om, pt["a"], pt["b"])
    Sv = pt["a"] + pt["b"] + 2
    res = [xs - pt["x"], Gs - inv[G], sp.diff(xs, t) - Gs / Sv, sp.diff(Gs, t) + om**2 * xs]
    return [sp.expand(r.subs(t, 0).subs(om, sp.sqrt(w2))) for r in res]


def _horizontal_point_G0(rng):
    """An exact point of H with x != 0 and G = <u, q> = 0 (u = q x w, k = q x u / x)."""
    pt = horizontal_point(rng)
    pt["u"] = pt["q"].cross(pt["u"])
    pt["k"] = pt["q"].cross(pt["u"]) / pt["x"]
    return pt


def modulo_frequency(residuals, nu2, nu_=nu) -> list:
    r"""Numerators of ``residuals`` (rational in $\nu$) reduced modulo $\nu^2 - \nu^2(h, f_2)$:
    each is zero iff the residual vanishes at $\nu = \sqrt{\nu^2(h, f_2)}$ (the remainder is
    linear in $\nu$, and $\nu$ is algebraic of degree 2 over the rational functions)."""
    out = []
    for r in residuals:
        num = sp.expand(sp.fraction(sp.together(r))[0])
        out.append(sp.rem(num, nu_**2 - nu2, nu_))
    return out


def closed_form_residuals(horizontal_solution, frequency_squared, omega2, t_, x0_, G0_, nu_):
    r"""Residuals of the closed form $(x(t), G(t))$ (``horizontal_solution(t, x0, G0, nu)``) as a
    solution of the printed linear system $\dot x = G/S$, $\dot G = -\omega^2x$ with $\omega^2$
    ``omega2`` (the printed expression in $h, f_2$) and $\nu^2$ = ``frequency_squared`` (the
    derived one the kernels use), with $c = \cos\nu t$, $s = \sin\nu t$, $\dot c = -\nu s$,
    $\dot s = \nu c$; modulo $\nu^2 - \nu^2(h, f_2)$ (:func:`modulo_frequency`)."""
    xs, Gs = horizontal_solution(t_, x0_, G0_, nu_)
    cs = {sp.cos(nu_ * t_): c, sp.sin(nu_ * t_): s}
    xs, Gs = xs.xreplace(cs), Gs.xreplace(cs)

    def ddt(f):
        return sp.diff(f, c) * (-nu_ * s) + sp.diff(f, s) * (nu_ * c)
    return modulo_frequency([xs.subs({c: 1, s: 0}) - x0_, Gs.subs({c: 1, s: 0}) - G0_,
                             ddt(xs) - Gs / S, ddt(Gs) + omega2 * xs], frequency_squared, nu_)


def _corrected_solution():
    """The corrected closed form with the derived frequency (both emitted into generated/reduced_n4.py)
    solves the printed linear system (whose omega^2 is checked against the derived field)."""
    omega2, _ = printed.omega_squared(h, f2, G, x, a, b)
    return exact(sp.Matrix(closed_form_residuals(reduced_n4.horizontal_solution,
                                                 reduced_n4.horizontal_frequency_squared(h, f2),
                                                 omega2, t, x0, G0, nu)), "Hlin corrected")


@claim("S5:H-linear", uses=("S5:H-SO3", "eq:A-on-J", "eq:red-system", "S5:red-integrals"))
def h_linear() -> Verdict:
    X = reduced_n4.field()
    g = reduced_n4.horizontal_set()
    hh, ff = _level()
    Gdot, xdot = printed.H_linear_system(G, x, hh, ff, a, b)
    w_a, w_b = printed.omega_squared(hh, ff, G, x, a, b)
    Dl = printed.Delta(a, b, x)
    fix = _corrected_solution()
    fix_latex = (r"x(t) = x_0\cos\nu t + \frac{G_0}{(a+b+2)\nu}\sin\nu t,\quad "
                 r"G(t) = G_0\cos\nu t - (a+b+2)x_0\nu\sin\nu t,\quad "
                 r"\nu^2 = \frac{\omega^2}{a+b+2} = \frac{f_2-2bh}{(2+a)(a+b+2)}")
    shown_latex = r"x(t) = x_0\cos\omega t,\quad G(t) = -(a+b+2)x_0\omega\sin\omega t"
    initial = Verdict.decide(
        zero_at_points(lambda pt: _printed_solution_at(pt)[:2], horizontal_point, count=4,
                       label="Hlin printed IC", describe="H (x != 0), at t = 0"),
        n_values=(4,), corrected=fix, printed_latex=shown_latex, correction_latex=fix_latex,
        kind="formula")
    frequency = Verdict.decide(
        zero_at_points(lambda pt: _printed_solution_at(pt)[2:], _horizontal_point_G0, count=4,
                       label="Hlin printed ODE", describe="H with G_0 = 0 (x != 0), at t = 0"),
        n_values=(4,), corrected=fix, printed_latex=shown_latex, correction_latex=fix_latex,
        kind="formula")
    return Verdict.of_parts([
        Verdict.all_of([("G_dot", exact(Gdot - X["G"].xreplace(g), "Hlin G")),
                        ("x_dot", exact(xdot - X["x"], "Hlin x"))], n_values=(4,)).as_part(
            "the linear system"),
        Verdict.all_of([("equal", exact(w_a - w_b, "Hlin w2")),
                        (">= 0", exact(w_b - (G**2 + 2 * S * A / Dl) / (S * (1 - x**2)), "Hlin pos"))],
                       n_values=(4,), notes="omega^2 = (G^2 + 2(a+b+2)A/Delta)/((a+b+2)(1-x^2)) "
                       ">= 0 as A >= 0, Delta > 0").as_part("both omega^2 and omega^2 >= 0"),
        initial.as_part("solution: initial condition G(0) = G_0"),
        frequency.as_part("solution: solves the system (frequency), even for G_0 = 0"),
    ], n_values=(4,))
