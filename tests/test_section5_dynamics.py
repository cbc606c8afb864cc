r"""Section 5 as dynamics: the derived 4D field, the reduced field and the closed forms, integrated.

* a 4D trajectory pushed to the invariants follows the derived reduced field (mpmath, 30 digits);
* on $\mathcal{H}$ the corrected closed form of S5:H-linear follows the 4D flow, from several generic
  initial conditions ($G_0 \ne 0$), while the printed one does not;
* a steady rotation ($\eta_0\times\xi_0 = 0$) keeps $\Omega$ constant and follows
  $M(t) = e^{-\Omega_0 t}M_0e^{\Omega_0 t}$, $\gamma(t) = e^{-\Omega_0 t}\gamma_0$.

The right-hand sides are the derived numerators of :mod:`symbolic.fourd` / :mod:`symbolic.reduction.reduced_n4`
evaluated term by term with exact rational coefficients converted at the working precision.
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
import scipy.integrate
import scipy.linalg
import sympy as sp
from chaplygin_nd.symbolic import fourd
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.printed import section5 as printed
from chaplygin_nd.symbolic.reduction import invariants_n4 as ri
from chaplygin_nd.symbolic.reduction import reduced_n4


@pytest.fixture(autouse=True)
def _mp_reset():
    saved = mpmath.mp.prec
    yield
    mpmath.mp.prec = saved


def compile_poly(p, gens):
    """A function of the generator values (mpf or float) evaluating ring element ``p`` term by term.
    Coefficients are exact rationals converted at call time (mpf at the current precision)."""
    terms = [(int(c.numerator), int(c.denominator), mon) for mon, c in p.terms()]
    idx = [i for i in range(len(gens))]

    def f(vals, use_mp=True):
        total = mpmath.mpf(0) if use_mp else 0.0
        for num, den, mon in terms:
            t = (mpmath.mpf(num) / den) if use_mp else num / den
            for i in idx:
                e = mon[i]
                if e:
                    t *= vals[i] ** e
            total += t
        return total
    return f


def _four_d_rhs():
    kd, ud, qd, xd = fourd.field_numerators()
    comps = [compile_poly(c, fourd.GENS) for c in (*kd, *ud, *qd, xd)]
    Dn = compile_poly(fourd.D, fourd.GENS)

    def rhs(a, b, y, use_mp=True):
        vals = [a, b, y[9], *y[0:3], *y[3:6], *y[6:9]] + [0] * 6
        d = Dn(vals, use_mp)
        return [c(vals, use_mp) / d for c in comps]
    return rhs


def _reduced_rhs():
    X = reduced_n4.field_numerators()
    comps = {n: compile_poly(p, ri.INV_GENS) for n, p in X.items()}
    Dn = compile_poly(ri.INV_RING(sp.expand(reduced_n4.D)), ri.INV_GENS)

    def rhs(a, b, z):
        A, B, E, G, F1, x, delta = z
        vals = [a, b, x, A, B, E, G, F1, delta]
        d = Dn(vals)
        return [comps[n](vals) / d for n in reduced_n4.COORDS]
    return rhs


def _invariants(y):
    k, u, q, x = (mpmath.matrix(y[0:3]), mpmath.matrix(y[3:6]), mpmath.matrix(y[6:9]), y[9])
    dot = lambda p, r: sum(p[i] * r[i] for i in range(3))  # noqa: E731
    kxu = [k[1] * u[2] - k[2] * u[1], k[2] * u[0] - k[0] * u[2], k[0] * u[1] - k[1] * u[0]]
    return [dot(k, k), dot(u, u), dot(k, q), dot(u, q), dot(k, u), x, dot(q, kxu)]


def _phase(seed):
    rng = points.generator(seed, "s5 dynamics")
    g = points.sphere_point(rng, 4)
    par = points.axisymmetric_parameters(rng)
    y = [*points.rationals(rng, 3, -1, 1), *points.rationals(rng, 3, -1, 1), *g]
    return par["a"], par["b"], y


@pytest.mark.parametrize("seed", [1, 2])
def test_4d_flow_projects_to_reduced_flow(seed):
    mpmath.mp.dps = 30
    a_, b_, y0 = _phase(seed)
    a, b = mpmath.mpf(a_.p) / a_.q, mpmath.mpf(b_.p) / b_.q
    rhs4, rhs7 = _four_d_rhs(), _reduced_rhs()
    Y0 = [mpmath.mpf(v.p) / v.q for v in y0]
    T = mpmath.mpf(3) / 2
    sol4 = mpmath.odefun(lambda t, y: rhs4(a, b, y), 0, Y0)
    Z0 = _invariants(Y0)
    sol7 = mpmath.odefun(lambda t, z: rhs7(a, b, z), 0, Z0)
    for t in (T / 2, T):
        z4 = _invariants(sol4(t))
        z7 = sol7(t)
        err = max(abs(p - r) for p, r in zip(z4, z7, strict=True))
        assert err < mpmath.mpf(10) ** -24, (t, err)
    # and the motion is not trivial: the invariants did move
    assert max(abs(p - r) for p, r in zip(_invariants(sol4(T)), Z0, strict=True)) > 1e-3


def _float_field():
    rhs = _four_d_rhs()
    return lambda a, b: (lambda t, y: np.array(rhs(a, b, list(y), use_mp=False), dtype=float))


def _horizontal_start(seed):
    """Exact point of H with x != 0 and G = <u, q> != 0: k = q x u / x."""
    rng = points.generator(seed, "s5 horizontal")
    while True:
        g = points.sphere_point(rng, 4)
        par = points.axisymmetric_parameters(rng)
        u = sp.Matrix(points.rationals(rng, 3, -1, 1))
        q, x = g[:3, 0], g[3]
        if x != 0 and abs(x) < sp.Rational(9, 10) and (u.T * q)[0] != 0:
            k = q.cross(u) / x
            return par["a"], par["b"], [*k, *u, *q, x]


def _level_values(a_, b_, y):
    k, u, q, x = sp.Matrix(y[0:3]), sp.Matrix(y[3:6]), sp.Matrix(y[6:9]), y[9]
    inv = {ri.A: (k.T * k)[0], ri.B: (u.T * u)[0], ri.E: (k.T * q)[0], ri.G: (u.T * q)[0],
           ri.F1: (k.T * u)[0], ri.delta: (q.T * k.cross(u))[0], fourd.x: x,
           fourd.a: a_, fourd.b: b_}
    ints = reduced_n4.integrals()
    return inv[ri.G], ints["H"].xreplace(inv), ints["F2"].xreplace(inv)


@pytest.mark.parametrize("seed", [3, 4, 5, 6])
def test_horizontal_closed_form_matches_4d_flow(seed):
    a_, b_, y0 = _horizontal_start(seed)
    G0, h, f2 = _level_values(a_, b_, y0)
    x0 = y0[9]
    assert G0 != 0
    nu2 = reduced_n4.horizontal_frequency_squared(h, f2).xreplace({fourd.a: a_, fourd.b: b_})
    nu = float(sp.sqrt(nu2))
    fld = _float_field()(float(a_), float(b_))
    T = 4.0
    ts = np.linspace(0, T, 9)
    sol = scipy.integrate.solve_ivp(fld, (0, T), [float(v) for v in y0], method="DOP853",
                                    rtol=1e-12, atol=1e-13, t_eval=ts)
    S = float(a_ + b_ + 2)
    x_closed = float(x0) * np.cos(nu * ts) + float(G0) / (S * nu) * np.sin(nu * ts)
    G_closed = float(G0) * np.cos(nu * ts) - S * float(x0) * nu * np.sin(nu * ts)
    x_flow = sol.y[9]
    G_flow = np.einsum("it,it->t", sol.y[3:6], sol.y[6:9])
    assert np.max(np.abs(x_flow - x_closed)) < 1e-9
    assert np.max(np.abs(G_flow - G_closed)) < 1e-9
    # the printed closed form (frequency omega, no G0 term) is far from the flow
    omega = float(sp.sqrt(printed.omega_squared(h, f2, G0, x0, a_, b_)[0]))
    x_printed = np.array([float(printed.H_linear_solution(t, x0, omega, a_, b_)[0]) for t in ts])
    assert np.max(np.abs(x_flow - x_printed)) > 1e-2


def test_steady_rotation_keeps_omega_constant():
    rng = points.generator(7, "s5 steady")
    g = points.sphere_point(rng, 4)
    a_, b_ = sp.Rational(-1, 2), sp.Rational(3, 2)
    eta0 = sp.Matrix(points.rationals(rng, 3, -1, 1))
    xi0 = sp.Rational(-3, 4) * eta0
    R = fourd.RV
    kk, uu = fourd.L_blocks(R["eta"], R["xi"])
    sub = [*zip(R["eta"], eta0, strict=False), *zip(R["xi"], xi0, strict=False), *zip(R["q"], g[:3, 0], strict=False), (R["x"], g[3]),
           (R["a"], a_), (R["b"], b_)]
    k0 = [sp.Rational(c.subs(sub).as_expr()) for c in kk]
    u0 = [sp.Rational(c.subs(sub).as_expr()) for c in uu]
    y0 = [*k0, *u0, *g]
    fld = _float_field()(float(a_), float(b_))
    ts = np.linspace(0, 5, 6)
    sol = scipy.integrate.solve_ivp(fld, (0, 5), [float(v) for v in y0], method="DOP853",
                                    rtol=1e-12, atol=1e-13, t_eval=ts)
    Om0 = np.array(fourd.block([float(v) for v in eta0], [float(v) for v in xi0]), dtype=float)
    M0 = np.array(fourd.block(k0, u0), dtype=float)
    g0 = np.array([float(v) for v in g], dtype=float)
    xi_f, eta_f = fourd.xi_eta()
    args = (fourd.a, fourd.b, *fourd.k, *fourd.u, *fourd.q, fourd.x)
    inv = sp.lambdify(args, [*xi_f, *eta_f], "numpy")
    for i, t in enumerate(ts):
        y = sol.y[:, i]
        vals = inv(float(a_), float(b_), *y[0:9], y[9])
        assert np.allclose(vals[:3], [float(v) for v in xi0], atol=1e-10)
        assert np.allclose(vals[3:], [float(v) for v in eta0], atol=1e-10)
        E = scipy.linalg.expm(-Om0 * t)
        M_closed = E @ M0 @ E.T
        M_flow = np.array(fourd.block(list(y[0:3]), list(y[3:6])), dtype=float)
        assert np.allclose(M_flow, M_closed, atol=1e-10)
        assert np.allclose(y[6:10], E @ g0, atol=1e-10)
    # the motion is not trivial
    assert np.max(np.abs(sol.y[:, -1] - sol.y[:, 0])) > 1e-2
