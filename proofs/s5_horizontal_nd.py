r"""S5:H-linear-nD — horizontal momentum for every $n \ge 3$: $(x, G)$ obey a linear system.

**Claim (ours; the paper states it for $n = 4$ only, S5:H-linear and eq:A-on-J).** On
$\mathcal{H} = \{M = (M\gamma)\wedge\gamma\}$ (eq:def-H-V) of the axisymmetric sphere in any
dimension $n \ge 3$, put

.. math::
    x = \langle\gamma, E_n\rangle,\quad G = \langle ME_n, \gamma\rangle,\quad
    f_2 = \lVert M\rVert_\kappa^2,\quad h = H = \tfrac12\langle M, \Omega\rangle_\kappa,\quad
    A = \lVert M - (ME_n)\wedge E_n\rVert_\kappa^2,\quad S = a+b+2,

($\langle X, Y\rangle_\kappa = -\tfrac12\operatorname{tr}XY$; $A$ is the energy of the
$\mathfrak{so}(n-1)$ block of $M$, for $n = 4$ it is $\lVert k\rVert^2$, and $f_2$ is the
coefficient of $\lambda^{n-2}$ in $p(\lambda, 0)$, for $n = 4$ the $F_2$ of Section 5). Then

.. math::
    \dot x = \frac{G}{S}, \qquad \dot G = -\omega^2 x, \qquad
    \omega^2 = \frac{f_2 - 2bh}{2+a} = \frac{aG^2 + 4hS}{S(2 + a(1-x^2))},
    \qquad \frac{d}{dt}\omega^2 = 0,

$S(1-x^2)\,\omega^2 = G^2 + 2SA/\Delta(x) \ge 0$, and both printed expressions of eq:A-on-J hold
verbatim: $A = \frac{(2h(1-x^2)S - G^2)\Delta(x)}{S(2+a(1-x^2))} = (1-x^2)f_2 - G^2$. Hence, with
$\nu^2 = \omega^2/S$, every solution on $\mathcal{H}$ has
$x(t) = x_0\cos\nu t + \frac{G_0}{S\nu}\sin\nu t$, $G(t) = G_0\cos\nu t - Sx_0\nu\sin\nu t$ (the
corrected solution of S5:H-linear), and $A(t) = (1-x^2)f_2 - G^2$, $B(t) := \lVert ME_n\rVert^2 =
f_2 - A$ follow. (The printed formulas of Section 5 are called through :mod:`symbolic.printed`;
for $n \ne 4$ they are our generalisation, not a statement of the paper.)

**Invariance of $\mathcal{H}$** for every $n$ is row eq:def-H-V ($g = M - (M\gamma)\wedge\gamma$
obeys $\dot g = [g, \Omega]$ for any $\Omega$). **Conservation of $\omega^2$**: $f_2$ is conserved on
all of $P$ ($\langle M, [M, \Omega]\rangle_\kappa = 0$, ad-invariance); $h$ by S2.2:energy, whose
symbolic proof is at $n = 3$ for a general $J$ (so on $\mathcal{H}$ of the axisymmetric sphere), and
the reduction argument below carries it to every $n$; we also check $\frac{d}{dt}\omega^2 = 0$ on
$\mathcal{H}$ exactly at seeded points for $n = 3..12, 16, 20, 24$ (a symbolic $\dot\Omega$ is too slow for the
ledger budget).

The parametrisation. For $\lVert\gamma\rVert = 1$, $M = v\wedge\gamma$ lies in $\mathcal{H}$ for every
$v \in \mathbb{R}^n$ ($(v\wedge\gamma)\gamma = v - \langle v,\gamma\rangle\gamma$, whose wedge with
$\gamma$ is $v\wedge\gamma$ again), and every point of $\mathcal{H}$ is of this form ($v = M\gamma$).
So identities on $\mathcal{H}$ are identities in $(v, \gamma)$ modulo $\lVert\gamma\rVert^2 = 1$, with
$v$ free: exact and without a chart.

The reduction argument (every $n$ from $n = 3$). Each residual below is a scalar built from $M$,
$\gamma$, $E_n$, $\Omega = L_\gamma^{-1}M$, $\dot M = [M, \Omega]$, $\dot\gamma = -\Omega\gamma$ and
$\dot\Omega = L_\gamma^{-1}(\dot M - \dot L_\gamma\Omega)$ by products, wedges and $\kappa$-pairings. For
a linear isometry $\iota: \mathbb{R}^3 \to \mathbb{R}^n$ with $\iota E_3 = E_n$ we have
$\mathbb{J}\iota = \iota\mathbb{J}'$, so $L_{\iota\gamma'}(\iota\Omega'\iota^T) = \iota L_{\gamma'}(\Omega')\iota^T$
and, $L_\gamma$ being invertible, $L^{-1}_{\iota\gamma'}(\iota M'\iota^T) = \iota L^{-1}_{\gamma'}(M')\iota^T$;
every other ingredient is natural too and $\kappa$, $x$, $G$ are invariant. So the residual at
$(\iota v', \iota\gamma')$ in $\mathbb{R}^n$ equals the residual at $(v', \gamma')$ in $\mathbb{R}^3$.
Every $(v, \gamma)$ is of that form: $\operatorname{span}\{E_n, \gamma, v\}$ has dimension $\le 3$
and lies in the image of such an $\iota$. Hence **the exact symbolic check at $n = 3$ proves the claim for every $n \ge 3$** (we take
$\gamma = (0, s, x)$, no loss by $SO(2)$-naturality; a fully generic $\gamma \in S^2$ is in the slow
tests). The same reasoning shows more: $\Omega \in \Lambda^2 W$ for
$W = \operatorname{span}\{E_n, \gamma, v\}$, so $W$ is invariant and a horizontal motion in
$\mathbb{R}^n$ *is* a 3D horizontal motion inside $W$. The ledger also checks $n = 4$ symbolically
($\gamma = (0, \dots, 0, s, x)$, no loss by $SO(n-1)$-naturality), and every residual at one seeded
exact rational point of $\mathcal{H}$ for each $n = 3..12, 16, 20, 24$, where $\Omega$ and $\dot\Omega$ come from
exact linear solves of eq:M-O (a route to $L_\gamma^{-1}$ independent of the closed form of
P:inversion used symbolically). tests/test_section5_horizontal_nd.py (slow) repeats the symbolic
check for $n = 5, 6$ and with fully generic $\gamma$ for $n = 3$.

The closed form solves the linear system: proved with $c = \cos\nu t$, $s = \sin\nu t$,
$\dot c = -\nu s$, $\dot s = \nu c$, $\omega^2 = S\nu^2$.

**Uses** eq:def-H-V (invariance of $\mathcal{H}$), P:inversion (closed-form $L_\gamma^{-1}$ in the
symbolic checks), eq:M-O-axi-symm. No floats.
"""

from __future__ import annotations

from functools import cache

import sympy as sp
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.proofs.s4_common import SAMPLERS, combine, frame_gamma, gamma_symbols
from chaplygin_nd.symbolic.algebra import commutator, killing, skew_symbols, vector_symbols, wedge
from chaplygin_nd.symbolic.axisym_inverse import inverse_denominator, inverse_numerator
from chaplygin_nd.symbolic.axisymmetric import E_n, a, b, mass_tensor
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.exact.identity import point_engines, rational_identity, zero_at_points
from chaplygin_nd.symbolic.model import angular_velocity
from chaplygin_nd.symbolic.printed import section5 as printed
from chaplygin_nd.symbolic.reduction.reduced_n4 import (
    horizontal_blocks,
    horizontal_frequency_squared,
    horizontal_solution,
)

SECTION = "Section 5 — n = 4"
SYMBOLIC_N = (3, 4)
#: Also proved symbolically, in tests/test_section5_horizontal_nd.py (slow): n = 5, 6 and a
#: fully generic gamma at n = 3.
SLOW_SYMBOLIC_N = (5, 6)
POINT_N = tuple(points.all_n(3))
S = a + b + 2

#: Names of the residuals of :func:`residuals`, in order.
NAMES = ("x_dot = G/S (printed, line 922)", "G_dot = -omega^2 x (printed, line 922)",
         "omega^2: the two printed expressions agree (line 930)",
         "S(1-x^2) omega^2 = G^2 + 2SA/Delta", "d(omega^2)/dt = 0",
         "eq:A-on-J first expression", "eq:A-on-J second expression",
         "A = the emitted block A(x, G, f2)", "B = ||M E_n||^2 = the emitted block B(x, G, f2)")


def _scalar(m):
    return m[0, 0]


def residuals(M, gamma, Omega, Omega_dot_of, a_, b_) -> list:
    r"""The residuals of the claim at $(M, \gamma) \in \mathcal{H}$ (module docstring), each $0$ iff its
    statement holds; ``Omega_dot_of(X)`` returns $L_\gamma^{-1}X$, used for $\dot\Omega =
    L_\gamma^{-1}(\dot M - \dot L_\gamma\Omega)$ (``None``: the conservation residual is not
    computed). Any $n \ge 3$, exact entries."""
    n = gamma.rows
    E = E_n(n)
    x = gamma[n - 1]
    Mdot, gdot = commutator(M, Omega), -Omega * gamma
    G = _scalar(gamma.T * M * E)
    G_dot = _scalar(gdot.T * M * E) + _scalar(gamma.T * Mdot * E)
    f2, h = killing(M, M), killing(M, Omega) / 2
    if Omega_dot_of is None:  # the conservation residual is not asked for
        f2_dot = h_dot = sp.nan
    else:
        Ld = b_ * (wedge(Omega * gdot, gamma) + wedge(Omega * gamma, gdot))
        Odot = Omega_dot_of(Mdot - Ld)
        f2_dot, h_dot = 2 * killing(M, Mdot), (killing(Mdot, Omega) + killing(M, Odot)) / 2
    A = killing(M - wedge(M * E, E), M - wedge(M * E, E))
    B = _scalar((M * E).T * (M * E))
    A_blocks, B_blocks = horizontal_blocks(x, G, f2)  # what generated/reduced.py evaluates
    Gdot_p, xdot_p = printed.H_linear_system(G, x, h, f2, a_, b_)
    w2, w2_alt = printed.omega_squared(h, f2, G, x, a_, b_)
    A_first, A_second = printed.A_on_J(G, x, h, f2, a_, b_)
    Delta = printed.Delta(a_, b_, x)
    S_ = a_ + b_ + 2
    return [gdot[n - 1] - xdot_p, G_dot - Gdot_p, w2 - w2_alt,
            S_ * (1 - x**2) * w2 - (G**2 + 2 * S_ * A / Delta),
            (f2_dot - 2 * b_ * h_dot) / (2 + a_), A - A_first, A - A_second,
            A - A_blocks, B - B_blocks]


CONSERVATION = 4  # index of d(omega^2)/dt in NAMES


@cache
def _symbolic(n: int, generic_gamma: bool = False):
    """The residuals on $\\mathcal{H}$ with $M = v\\wedge\\gamma$, $\\gamma$ in the frame
    $(0, \\dots, 0, s, x)$ (or fully generic), $\\Omega = N/D$ from the closed form of P:inversion, and the sphere
    symbols. The conservation residual is ``None`` here (see :func:`h_linear_nd`)."""
    gamma = gamma_symbols(n) if generic_gamma else frame_gamma(n)
    v = vector_symbols("v", n)
    M = wedge(v, gamma)
    Omega = inverse_numerator(M, gamma) / inverse_denominator(a, b, gamma[n - 1])
    sphere = tuple(gamma) if generic_gamma else tuple(gamma[n - 2:])
    res = residuals(M, gamma, Omega, None, a, b)
    res[CONSERVATION] = None
    return tuple(res), sphere


def _point(n: int):
    def sample(rng):
        pt = points.axisymmetric_parameters(rng)
        gamma = points.sphere_point(rng, n)
        v = sp.Matrix(points.rationals(rng, n))
        pt.update({"n": n, "gamma": gamma, "M": wedge(v, gamma)})
        return pt
    return sample


def _at_point(pt, which: slice):
    J = mass_tensor(pt["n"], pt["a"])

    def omega_dot(X):
        return angular_velocity(X, pt["gamma"], J, pt["b"])

    Omega = angular_velocity(pt["M"], pt["gamma"], J, pt["b"])
    return residuals(pt["M"], pt["gamma"], Omega, omega_dot, pt["a"], pt["b"])[which]


SYMBOLIC_METHOD = ("exact symbolic identity on H (M = v ^ gamma, v generic) modulo ||gamma||^2 = 1 "
                   "for n in {3, 4} (gamma = (0,..,0,s,x), no loss by SO(n-1)-naturality; n = 5, 6 "
                   "and fully generic gamma at n = 3 in the slow tests)")


def _points(which: slice, label: str):
    pts = [zero_at_points(lambda p: _at_point(p, which), _point(n), count=1, label=f"{label}-pt{n}",
                          describe=f"H in so({n}) x S^{n - 1}", engines=point_engines(n)) for n in POINT_N]
    return combine(pts, method=f"exact at 1 seeded rational point of H for each n in {points.n_text(points.all_n(3))}, Omega "
                               f"(and Omega_dot) by exact linear solves of eq:M-O (seed "
                               f"{points.ledger_seed()})")


def _checks(which: slice, label: str):
    sym = []
    for n in SYMBOLIC_N:
        res, sphere = _symbolic(n)
        sym.append(rational_identity(list(res[which]), sphere=sphere, samplers=SAMPLERS,
                                     label=f"{label}-n{n}"))
    return combine(sym, method=SYMBOLIC_METHOD)


def _f2_conserved():
    r"""$\langle M, [M, \Omega]\rangle_\kappa = 0$ for any skew $M, \Omega$ (ad-invariance): $f_2$ is
    conserved on all of $P$; symbolic for $n = 3..6$ (the identity is trace-cyclic for every $n$)."""
    return combine([rational_identity(killing(skew_symbols("m", n), commutator(
        skew_symbols("m", n), skew_symbols("w", n))), label=f"f2-n{n}") for n in SYMBOLIC_N],
        method="<M, [M, Omega]>_kappa = 0 for generic skew M, Omega, n = 3..6 (tr(M(MW - WM)) = 0 "
               "by cyclicity for every n)")


def _closed_form():
    """The corrected closed form with the derived frequency nu^2(h, f2) (both emitted) solves the
    printed linear system x_dot = G/S, G_dot = -omega^2 x (omega^2 printed, in h and f2)."""
    from chaplygin_nd.proofs.s5_horizontal_vertical import closed_form_residuals

    t, x0, G0, nu, h, f2 = sp.symbols("t x0 G0 nu h f2", real=True)
    omega2, _ = printed.omega_squared(h, f2, sp.Symbol("G"), sp.Symbol("x"), a, b)
    return rational_identity(closed_form_residuals(
        horizontal_solution, horizontal_frequency_squared(h, f2), omega2, t, x0, G0, nu),
        label="HnD closed form")


CONSERVATION_METHOD = (
    "f2: ad-invariance, symbolic; h: exact d(omega^2)/dt = 0 at 1 seeded point of H for each n in "
    "3..12 (Omega_dot = L^-1(M_dot - L_dot Omega) by exact linear solves); for every n: dH/dt = 0 is "
    "the symbolic n = 3 identity of S2.2:energy (general J, all of P, so on H), carried to every n by "
    "the reduction argument")

REDUCTION = ("reduction argument (module docstring): the residuals are natural scalars of (v, gamma) "
             "and span{E_n, gamma, v} has dimension <= 3, so the symbolic n = 3 check covers "
             "every n >= 3")


@claim("S5:H-linear-nD", uses=("eq:def-H-V", "P:inversion", "eq:M-O-axi-symm", "S2.2:energy",
                                "S5:H-linear"),
       adds=(SECTION, "every n ≥ 3: on H, ẋ = G/(a+b+2), Ġ = −ω²x with ω² = (f₂−2bh)/(2+a) "
                      "conserved (G = ⟨MEₙ,γ⟩, f₂ = ‖M‖²_κ, h = H); eq:A-on-J with A = ‖so(n−1) "
                      "block‖²_κ; the corrected closed form of S5:H-linear solves it"))
def h_linear_nd() -> Verdict:
    def part(name, check):
        return Verdict.all_of([(name, check)], n_values=POINT_N).as_part(name)

    every_n = _points(slice(0, len(NAMES)), "HnD")
    return Verdict.of_parts([
        part(f"all residuals at seeded exact points of H, n = {points.n_text(points.all_n(3))} (Omega by linear solve)", every_n),
        part("the linear system x_dot = G/S, G_dot = -omega^2 x (as printed for n = 4)",
             _checks(slice(0, 2), "lin")),
        part("omega^2: both printed expressions agree; S(1-x^2) omega^2 = G^2 + 2SA/Delta >= 0",
             _checks(slice(2, 4), "w2")),
        part("omega^2 conserved on H", combine([_f2_conserved(), every_n],
                                                method=CONSERVATION_METHOD)),
        part("eq:A-on-J (both printed expressions) for every n",
             _checks(slice(5, 7), "AJ")),
        part("the blocks A = (1-x^2) f2 - G^2, B = x^2 f2 + G^2 the kernels evaluate, for every n",
             _checks(slice(7, 9), "blocks")),
        part("x = x0 cos nu t + G0 sin nu t/(S nu), G = G0 cos nu t - S x0 nu sin nu t, "
             "nu^2 = (f2 - 2bh)/((2+a)S) = omega^2/S (the kernels' frequency), solves it",
             _closed_form()),
    ], n_values=POINT_N, notes=REDUCTION)
