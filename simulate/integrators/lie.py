r"""A Lie-group (Runge–Kutta–Munthe-Kaas) integrator of order 4 on the $SO(n)$-orbits.

The field of eq:motion-general is an infinitesimal action: $(\dot M, \dot\gamma) = A\cdot(M, \gamma)$
with $A = -\Omega(M, \gamma) \in \mathfrak{so}(n)$ and $X\cdot(M, \gamma) = ([X, M], X\gamma)$; the group
acts by $Q\cdot(M, \gamma) = (QMQ^T, Q\gamma)$. With $k_i = hA(\cdot)$ (the commutator-reduced
RKMK4 of Munthe-Kaas, Appl. Numer. Math. 29 (1999); see Iserles, Munthe-Kaas, Nørsett, Zanna,
Acta Numerica 9 (2000); its order 4 is checked in tests/test_simulate_integrators.py):

.. math::
    k_1 = hA(y),\ k_2 = hA(e^{k_1/2}y),\ k_3 = hA(e^{k_2/2 - [k_1,k_2]/8}y),\ k_4 = hA(e^{k_3}y),\\
    \Theta = \tfrac16(k_1 + 2k_2 + 2k_3 + k_4) - \tfrac1{12}[k_1, k_4],\qquad y \leftarrow e^{\Theta}\cdot y.

Every update is a conjugation by an orthogonal matrix, so $\|\gamma\|$ and the spectrum of
$M + \sigma\gamma\gamma^T$ for every $\sigma$ (eq:iso-spectral, the coefficients of $p(\lambda,\sigma)$) are
kept to rounding at any step size; the energy is kept to $O(h^4)$.
Reconstruction: $g \leftarrow g\,e^{\Theta T}$ (since $\gamma = g^TE_n$ and $\dot g = g\Omega$) and
$\dot c = r\,g\Omega\gamma$ by the RK4 quadrature on the stages.
"""

from __future__ import annotations

import math
import time

import numpy as np
from chaplygin_nd.simulate.dynamics import so
from chaplygin_nd.simulate.integrators import settings
from chaplygin_nd.simulate.integrators.base import Solution
from chaplygin_nd.simulate.integrators.registry import Integrator, register
from chaplygin_nd.simulate.integrators.settings import Calibration, Step

__all__ = ["integrate", "step"]


def _act(Q, M, gamma):
    return Q @ M @ np.swapaxes(Q, -1, -2), (Q @ gamma[..., None])[..., 0]


def step(field, M, gamma, h):
    r"""One RKMK4 step of size ``h`` from $(M, \gamma)$ (batched); returns $(Q, \{(h\cdot\text{weight}, \text{stage})\})$
    with $Q = e^\Theta$ and the four stages $(Q_i, A_i)$ for the reconstruction quadrature."""
    def gen(Q):
        Mi, gi = _act(Q, M, gamma) if Q is not None else (M, gamma)
        return field.generator(Mi, gi), Mi, gi

    A1, _, _ = gen(None)
    k1 = h * A1
    Q2 = so.expm_small(0.5 * k1)
    A2, M2, g2 = gen(Q2)
    k2 = h * A2
    Q3 = so.expm_small(0.5 * k2 - 0.125 * so.commutator(k1, k2))
    A3, M3, g3 = gen(Q3)
    k3 = h * A3
    Q4 = so.expm_small(k3)
    A4, M4, g4 = gen(Q4)
    k4 = h * A4
    theta = (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0 - so.commutator(k1, k4) / 12.0
    stages = ((h / 6, None, A1, gamma), (h / 3, Q2, A2, g2), (h / 3, Q3, A3, g3), (h / 6, Q4, A4, g4))
    return so.expm_small(theta), stages


def integrate(field, y0: np.ndarray, t: np.ndarray, h: float = 0.01, progress=None) -> Solution:
    r"""Integrate eq:motion-general (``field``: a :class:`simulate.dynamics.field.FullField`) with RKMK4 at a
    step $\le h$ chosen so that every sample time is hit exactly. Domain: as the field."""
    y = np.array(y0, dtype=float)
    parts = field.unpack(y)
    M, gamma = parts[:2]
    g, c = (parts[2], parts[3]) if field.reconstruct else (None, None)
    out = np.empty((len(t),) + y.shape)
    out[0] = y
    steps = 0
    calls0 = field.calls
    start = time.perf_counter()
    for i in range(1, len(t)):
        span = t[i] - t[i - 1]
        m = max(1, math.ceil(span / h - 1e-9))
        hh = span / m
        for _ in range(m):
            Q, stages = step(field, M, gamma, hh)
            if g is not None:
                dc = 0.0
                for w, Qi, Ai, gi in stages:
                    gi_rot = g if Qi is None else g @ np.swapaxes(Qi, -1, -2)
                    # g_i Omega_i gamma_i with Omega_i = -A_i
                    dc = dc + w * np.einsum("...ij,...jk,...k->...i", gi_rot, -Ai, gi)
                c = c + field.radius * dc
                g = g @ np.swapaxes(Q, -1, -2)
            M, gamma = _act(Q, M, gamma)
            steps += 1
            if progress is not None:
                progress(t[i - 1] + hh * (_ + 1))
        out[i] = field.pack(M, gamma, g, c) if g is not None else field.pack(M, gamma)
    seconds = time.perf_counter() - start
    return Solution(t=np.asarray(t), y=out, method=f"RKMK4 h<={h:g}", steps=steps,
                    calls=field.calls - calls0, seconds=seconds)


def _run(f, y0, t, s: Step, *, checked, progress=None, compact=None) -> Solution:
    return integrate(f, y0, t, h=s.h, progress=progress)


LIE = register(Integrator(
    "lie", Step, _run,
    calibrate=lambda target, span, step=0.01, dps=30, precision="double":
        settings.step("lie", target, span, step),
    error=settings.step_error,
    describe=lambda s: f"RKMK4, step h = {s.h:.3g}",
    reduced=False,  # acts on (M, gamma) only
    # the constant C of C h^4 span, measured by ``chaplygin bench calibration`` (rounded up)
    calibration=(("lie", Calibration(measured=0.02)),)))
