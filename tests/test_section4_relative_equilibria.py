r"""Th:Re as dynamics: the relative equilibria $e^{\zeta t}\cdot(M_0, \gamma_0)$ on $\mathcal{V}$.

Exact part: for seeded rational points of $\mathcal{V}$ ($n = 3..6$) the curve's velocity at
$t = 0$ equals the vector field of eq:motion-general and $\zeta \in \mathfrak{so}(n-1)$; with the
$SO(n-1)$-equivariance (row eq:action) this is the whole proof that the curve is a solution.

Numerical part (not a ledger verdict): eq:motion-general is integrated with ``mpmath.odefun``
(Taylor series) at 30 digits, with $\Omega$ from an **mpmath linear solve of the definition of
$L_\gamma$** (not from any closed form), over two or three periods of the fastest rotation of
$e^{\zeta t}$, and compared with $e^{\zeta T}M_0e^{-\zeta T}$, $e^{\zeta T}\gamma_0$ computed by
``mpmath.expm`` from the exact $\zeta$. The motion itself is required to be non-trivial.
"""

from __future__ import annotations

import mpmath as mp
import pytest
import sympy as sp
from chaplygin_nd.symbolic.algebra import commutator
from chaplygin_nd.symbolic.axisym_inverse import inverse_closed_form
from chaplygin_nd.symbolic.axisymmetric import E_n, L_matrix_axisym
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.vertical import vertical_point, zeta

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


def _L_matrix_mp(n: int, A, B, gam) -> mp.matrix:
    """Matrix of L_gamma(Omega) = J Omega + Omega J + b (Omega gamma)^gamma (eq:M-O with
    J = Id + a E_n E_n^T) in the basis e_i^e_j (i < j), written entry by entry in mpmath:
    column (i, j) holds the coordinates of the image of e_i^e_j."""
    pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]
    Jd = [mp.mpf(1)] * (n - 1) + [1 + A]
    Lm = mp.matrix(len(pairs), len(pairs))
    for c, (i, j) in enumerate(pairs):
        for r, (k, m) in enumerate(pairs):
            # ((e_i g_j - e_j g_i)^g)_{km} = u_k g_m - g_k u_m with u = e_i g_j - e_j g_i
            u_k = (gam[j] if k == i else 0) - (gam[i] if k == j else 0)
            u_m = (gam[j] if m == i else 0) - (gam[i] if m == j else 0)
            Lm[r, c] = B * (u_k * gam[m] - gam[k] * u_m)
        Lm[c, c] += Jd[i] + Jd[j]
    return Lm


def _integrate(n: int, a, b, g, M, T):
    """(M(T), gamma(T)) of eq:motion-general by mpmath.odefun; Omega by an mpmath linear solve."""
    pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]
    A, B = _mp(a), _mp(b)

    def skew(coords):
        S = mp.matrix(n, n)
        for c, (i, j) in zip(coords, pairs, strict=True):
            S[i, j], S[j, i] = c, -c
        return S

    def rhs(t, y):
        m, gam = y[: len(pairs)], mp.matrix(y[len(pairs):])
        Om = skew(mp.lu_solve(_L_matrix_mp(n, A, B, gam), mp.matrix(m)))
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


@pytest.mark.parametrize("n", (3, 5))
def test_mpmath_L_matrix_equals_the_exact_one(n):
    a, b, g, _ = _vertical_point(n)
    exact = L_matrix_axisym(g, a, b)
    with mp.workdps(DPS):
        Lm = _L_matrix_mp(n, _mp(a), _mp(b), mp.matrix([_mp(v) for v in g]))
        diff = max(abs(Lm[r, c] - _mp(exact[r, c])) for r in range(exact.rows) for c in range(exact.cols))
    assert diff < mp.mpf(10) ** (-(DPS - 2))


def test_relative_equilibrium_n3_three_periods_mpmath():
    _check_against_closed_form(3, periods=3)


@pytest.mark.slow
@pytest.mark.parametrize("n", (4, 5, 6))
def test_relative_equilibrium_higher_n_mpmath(n):
    _check_against_closed_form(n, periods=3 if n == 4 else 2)
