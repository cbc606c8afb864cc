r"""Physical balls: from mass $m$, radius $r$ and moments of inertia to the paper's $(a, b)$.

The map and the realisability conditions are the ledger row S4:physical-ball (derived and proved
in :mod:`symbolic.physical_ball` / ``proofs/s4_physical_ball.py``; a test compares this numeric
copy with the derived SymPy map). For an axisymmetric body with mass tensor
$\mathbb{J} = \operatorname{diag}(j_1, \dots, j_1, j_n)$ about its centre (eq:Inertia), the moment
of inertia in a plane $(E_i, E_j)$ is $J_i + J_j$:

* $I_1 = j_1 + j_n$ in every plane that contains the symmetry axis $E_n$,
* $I_n = 2j_1$ in every plane orthogonal to it (for $n = 3$: principal moments $(I_1, I_1, I_3)$);

.. math::
    s = \frac{I_n}{2}, \qquad a = \frac{2(I_1 - I_n)}{I_n}, \qquad b = \frac{2mr^2}{I_n},

$L^{\text{ball}}_\gamma = sL_\gamma$: $M_{\text{ball}} = sM$, $H_{\text{ball}} = sH$; $\Omega$, $\gamma$,
$x$ and $t$ are the paper's. A body inside radius $r$ has $\mathbb{J} \succeq 0$ and
$\operatorname{tr}\mathbb{J} \le mr^2$, i.e. $a \ge -1$ and $b \ge n + a$; both are also sufficient.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Ball", "from_moments", "from_mass_tensor", "ball_violations", "parameter_violations"]


@dataclass(frozen=True)
class Ball:
    r"""A ball of mass ``mass`` and radius ``radius`` with plane moments ``I1`` (planes containing
    $E_n$) and ``In`` (planes orthogonal to $E_n$), and its paper parameters ``s, a, b``."""

    n: int
    mass: float
    radius: float
    I1: float
    In: float

    @property
    def s(self) -> float:
        """$s = I_n/2 = j_1$: $M_{\\text{ball}} = sM$ (S4:physical-ball)."""
        return self.In / 2

    @property
    def a(self) -> float:
        """$a = 2(I_1 - I_n)/I_n$ (eq:axisymm, S4:physical-ball)."""
        return 2 * (self.I1 - self.In) / self.In

    @property
    def b(self) -> float:
        """$b = 2mr^2/I_n$ (eq:M-O, S4:physical-ball)."""
        return 2 * self.mass * self.radius**2 / self.In

    @property
    def mass_tensor(self) -> tuple[float, float]:
        """$(j_1, j_n) = (I_n/2, I_1 - I_n/2)$."""
        return self.In / 2, self.I1 - self.In / 2


def from_moments(n: int, mass: float, radius: float, I1: float, In: float) -> Ball:
    """The ball with plane moments ``I1`` (planes containing the axis) and ``In`` (planes
    orthogonal to it); check :func:`ball_violations` before use."""
    return Ball(n, float(mass), float(radius), float(I1), float(In))


def from_mass_tensor(n: int, mass: float, radius: float, j1: float, jn: float) -> Ball:
    r"""The ball with mass tensor $\operatorname{diag}(j_1, \dots, j_1, j_n)$ about its centre:
    $I_1 = j_1 + j_n$, $I_n = 2j_1$."""
    return Ball(n, float(mass), float(radius), float(j1) + float(jn), 2.0 * float(j1))


#: Relative tolerance of the realisability bounds (a flat disc [0.15, 0.1 + 0.2] is j_n = -2.8e-17).
REL_TOL = 1e-12


def ball_violations(ball: Ball) -> list[str]:
    """The realisability inequalities (S4:physical-ball) that ``ball`` violates, in words."""
    n, (j1, jn) = ball.n, ball.mass_tensor
    out = []
    if not ball.In > 0:
        out.append(f"I_n = 2 j_1 > 0 fails (I_n = {ball.In:g}): all the mass would lie on the axis")
    # both bounds with the same relative tolerance (rounding of moments given in decimal)
    if not jn >= -REL_TOL * max(abs(ball.I1), abs(ball.In)):
        out.append(f"J >= 0 fails: j_n = I_1 - I_n/2 = {jn:g} < 0 (needs 2 I_1 >= I_n, the "
                   "triangle inequality of the moments)")
    trace = (n - 1) * j1 + jn
    if not trace <= ball.mass * ball.radius**2 * (1 + REL_TOL):
        out.append(f"tr J <= m r^2 fails: tr J = I_1 + (n-2) I_n/2 = {trace:g} > m r^2 = "
                   f"{ball.mass * ball.radius**2:g} (no body inside radius r has these moments)")
    return out


def parameter_violations(n: int, a: float, b: float) -> list[str]:
    """The realisability inequalities that the paper's parameters ``(a, b)`` violate, in words:
    ``a >= -1`` (J positive semidefinite) and ``b >= n + a`` (tr J <= m r^2)."""
    out = []
    if not a >= -1:
        out.append(f"a >= -1 fails (a = {a:g}): J = Id + a E_n E_n^T is not positive semidefinite")
    if not b >= n + a:
        out.append(f"b >= n + a = {n + a:g} fails (b = {b:g}): tr J <= m r^2, no body inside the "
                   "radius has this mass tensor")
    return out
