r"""Th:Re as dynamics: the relative equilibria $e^{\zeta t}\cdot(M_0, \gamma_0)$ on $\mathcal{V}$.

Exact part: for seeded rational points of $\mathcal{V}$ ($n = 3..6$) the curve's velocity at
$t = 0$ equals the vector field of eq:motion-general and $\zeta \in \mathfrak{so}(n-1)$; with the
$SO(n-1)$-equivariance (row eq:action) this is the whole proof that the curve is a solution.

Numerical part (not a ledger verdict): eq:motion-general is integrated with ``mpmath.odefun``
(Taylor series) at 30 digits, with $\Omega$ from an **mpmath linear solve of the definition of
$L_\gamma$** (not from any closed form), over about three periods of the fastest rotation of
$e^{\zeta t}$, and compared with $e^{\zeta T}M_0e^{-\zeta T}$, $e^{\zeta T}\gamma_0$ computed by
``mpmath.expm`` from the exact $\zeta$. The motion itself is required to be non-trivial.
"""

from __future__ import annotations

import mpmath as mp
import pytest
import sympy as sp

from symbolic import points
from symbolic.algebra import commutator
from symbolic.axisym_inverse import inverse_closed_form
from symbolic.axisymmetric import E_n
from symbolic.vertical import vertical_point, zeta

SEED = 3_20261121
DPS = 30


def _vertical_point(n: int):
    """Seeded exact point of V with a = 1, b = 1/2, rescaled so that zeta is of order one."""
    rng = points.generator(SEED, "RE", n)
    a, b = sp.Integer(1), sp.Rational(1, 2)
    for _ in range(50):
        g = points.sphere_point(rng, n)
        M = vertical_point(points.skew_matrix(rng, n), g)
        z = zeta(M, g, a, b)
        size = max(abs(v) for v in z)
        if size > sp.Rational(1, 100):
            scale = sp.Integer(int(2 / size) + 1)
            return a, b, g, scale * M
    raise AssertionError("no point of V with a non-zero zeta")


@pytest.mark.parametrize("n", range(3, 7))
def test_velocity_of_the_curve_is_the_vector_field_exactly(n):
    a, b, g, M = _vertical_point(n)
    z = zeta(M, g, a, b)
    Omega = inverse_closed_form(M, g, a, b)
    assert z * E_n(n) == sp.zeros(n, 1)               # exp(zeta t) lies in SO(n-1)
    assert commutator(z, M) == commutator(M, Omega)   # M_dot(0)
    assert z * g == -Omega * g                        # gamma_dot(0)
    assert z != sp.zeros(n, n)                        # a genuine rotation, not an equilibrium


def _mp(q) -> mp.mpf:
    q = sp.Rational(q)
    return mp.mpf(int(q.p)) / int(q.q)


def _integrate(n: int, a, b, g, M, T):
    """(M(T), gamma(T)) of eq:motion-general by mpmath.odefun; Omega by an mpmath linear solve."""
    pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]
    A, B = _mp(a), _mp(b)

    def skew(coords):
        S = mp.matrix(n, n)
        for c, (i, j) in zip(coords, pairs, strict=True):
            S[i, j], S[j, i] = c, -c
        return S

    basis = [skew([1 if k == m else 0 for k in range(len(pairs))]) for m in range(len(pairs))]

    def wedge(u, v):
        return u * v.T - v * u.T

    def L(Om, gam):  # eq:M-O with J of eq:axisymm: J Om + Om J + b (Om gam)^gam
        J = mp.eye(n)
        J[n - 1, n - 1] = 1 + A
        return J * Om + Om * J + B * wedge(Om * gam, gam)

    def rhs(t, y):
        m, gam = y[: len(pairs)], mp.matrix(y[len(pairs):])
        Lm = mp.matrix(len(pairs), len(pairs))
        for c, Bk in enumerate(basis):
            LB = L(Bk, gam)
            for r, (i, j) in enumerate(pairs):
                Lm[r, c] = LB[i, j]
        Om = skew(mp.lu_solve(Lm, mp.matrix(m)))
        Mm = skew(m)
        MO = Mm * Om - Om * Mm
        gd = -(Om * gam)
        return [MO[i, j] for i, j in pairs] + [gd[i] for i in range(n)]

    y0 = [_mp(M[i, j]) for i, j in pairs] + [_mp(v) for v in g]
    yT = mp.odefun(rhs, 0, y0)(T)
    return skew(yT[: len(pairs)]), mp.matrix(yT[len(pairs):])


def _check_against_closed_form(n: int, periods: int):
    a, b, g, M = _vertical_point(n)
    z = zeta(M, g, a, b)
    with mp.workdps(DPS):
        Z = mp.matrix([[_mp(z[i, j]) for j in range(n)] for i in range(n)])
        omega_max = max(abs(ev) for ev in mp.eig(Z)[0])
        T = periods * 2 * mp.pi / omega_max
        MT, gT = _integrate(n, a, b, g, M, T)
        R = mp.expm(Z * T)
        M0 = mp.matrix([[_mp(M[i, j]) for j in range(n)] for i in range(n)])
        g0 = mp.matrix([_mp(v) for v in g])
        M_ref, g_ref = R * M0 * R.T, R * g0
        err = max(mp.mnorm(MT - M_ref, 1), mp.norm(gT - g_ref))
        moved = mp.mnorm(R * M0 * R.T - M0, 1) + mp.mnorm(mp.expm(Z * T / 4) * M0
                                                          * mp.expm(-Z * T / 4) - M0, 1)
        x_drift = abs(gT[n - 1] - g0[n - 1])
    assert moved > mp.mpf("1e-3"), "the relative equilibrium must actually move"
    assert err < mp.mpf(10) ** (-(DPS - 6)), f"integration differs from exp(zeta t): {err}"
    assert x_drift < mp.mpf(10) ** (-(DPS - 6)), "x = gamma_n must stay constant"


def test_relative_equilibrium_n3_three_periods_mpmath():
    _check_against_closed_form(3, periods=3)


@pytest.mark.slow
@pytest.mark.parametrize("n", (4, 5, 6))
def test_relative_equilibrium_higher_n_mpmath(n):
    _check_against_closed_form(n, periods=2 if n < 6 else 1)
