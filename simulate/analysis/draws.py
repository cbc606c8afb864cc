r"""Initial conditions of the evidence rows, drawn by the ledger's seed — never picked.

An :class:`Ensemble` is ``count`` initial conditions $(M_0, \gamma_0)$ of one family
(:mod:`simulate.dynamics.families`: ``generic`` or ``vertical``) in dimension $n$, each with its own
parameters $(a, b)$ and energy scale $s = \|M_0\|_\kappa$:

* $(a, b)$ runs through ``A_VALUES`` $\times$ ``B_VALUES`` ($a \in \{-0.9, -0.5, 0.5, 2\}$, $b \in \{0.5, 2\}$:
  oblate and prolate bodies, $a = 2$ is a prolate ball outside the paper's $[-1, 1]$, S4:physical-ball)
  cyclically, so every pair gets the same number of orbits;
* $s$ runs through ``SCALES`` $= (0.5, 1, 2)$; the direction of $M_0$ and $\gamma_0$ is drawn from
  ``numpy.random.default_rng([seed, label, index])`` — ``seed`` is the ledger's seed
  (``chaplygin verify --seed``), ``label`` a fixed integer per ensemble.

The energy is a time scale. The field is homogeneous: $\Omega$ is linear in $M$, so
$(M(t), \gamma(t))$ solves eq:motion-general iff $(sM(st), \gamma(st))$ does. An orbit of energy scale
$s$ is therefore integrated to $T/s$ and sampled every $dt/s$ (``Ensemble.time_factor``), so every
orbit shows the same number of turns; the level sets that differ are those of the scale-free
ratios of the integrals, which the drawn directions cover.
"""

from __future__ import annotations

import zlib
from dataclasses import dataclass

import numpy as np
from chaplygin_nd.simulate.dynamics import families

__all__ = ["A_VALUES", "B_VALUES", "SCALES", "Ensemble", "draw"]

A_VALUES = (-0.9, -0.5, 0.5, 2.0)
B_VALUES = (0.5, 2.0)
SCALES = (0.5, 1.0, 2.0)


@dataclass(frozen=True)
class Ensemble:
    """Drawn initial conditions: ``a``, ``b``, ``scale`` of shape ``(count,)``, ``M0``
    ``(count, n, n)``, ``gamma0`` ``(count, n)``."""

    label: str
    family: str
    n: int
    seed: int
    a: np.ndarray
    b: np.ndarray
    scale: np.ndarray
    M0: np.ndarray
    gamma0: np.ndarray

    @property
    def count(self) -> int:
        return len(self.a)

    @property
    def time_factor(self) -> np.ndarray:
        """$1/s$: orbit $k$ runs to $T/s_k$ with step $dt/s_k$ (see the module docstring)."""
        return 1.0 / self.scale

    def describe(self) -> dict:
        """What identifies the draw (for cache keys and reports)."""
        return {"label": self.label, "family": self.family, "n": self.n, "seed": self.seed,
                "count": self.count, "a_values": A_VALUES, "b_values": B_VALUES,
                "scales": SCALES}


def draw(label: str, family: str, n: int, count: int, seed: int, *, a_values=A_VALUES,
         b_values=B_VALUES, scales=SCALES, base_scale: float = 1.0) -> Ensemble:
    r"""``count`` initial conditions (module docstring). ``a_values`` may contain 0 (the spherical
    case) for rows that test it; ``base_scale`` multiplies every $s$ (the vertical row uses 10).
    Domain: $n \ge 3$, $b > 0$, $a \ge -1$."""
    code = zlib.crc32(label.encode())
    # the directions do not depend on (a, b) for these families: one draw, then each its scale
    M1, g = families.draw(family, n, 0.0, 1.0, seed=code ^ int(seed), count=count, scale=1.0)
    k = np.arange(count)
    na, nb = len(a_values), len(b_values)
    a = np.array([a_values[i % na] for i in k], float)
    b = np.array([b_values[(i // na) % nb] for i in k], float)
    s = base_scale * np.array([scales[(i // (na * nb)) % len(scales)] for i in k], float)
    Ms = M1 * s[:, None, None]
    return Ensemble(label, family, n, int(seed), a, b, s, Ms, g)
