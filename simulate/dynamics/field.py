r"""Vector fields on flat state arrays, for the integrators (one idea: the right-hand side).

Full system (eq:motion-general with $\Omega = L_\gamma^{-1}(M)$ from :mod:`generated`):

.. math::
    \dot M = [M, \Omega], \qquad \dot\gamma = -\Omega\gamma,

optionally with the reconstruction

.. math::
    \dot g = g\,\Omega, \qquad \dot c = r\, g\,\Omega\gamma,

$g\in SO(n)$ the orientation (body coordinates to space coordinates) and $c$ the centre of the
sphere, whose first $n-1$ coordinates are those of the contact point on the plane.

Derivation (our convention, consistent with eq:motion-general). Let the plane be
$\{X_n = 0\}$ with unit normal $E_n$ pointing to the sphere, and $\gamma = g^TE_n$ its body
coordinates. (i) $\dot g = g\Omega$ gives $\dot\gamma = \dot g^TE_n = -\Omega g^TE_n = -\Omega\gamma$
(the second equation of eq:motion-general) and $\tfrac{d}{dt}(gMg^T) = g(\dot M - [M, \Omega])g^T = 0$
(the space momentum is constant, Section 2.2); $\Omega$ is the body angular velocity and
$\omega = g\Omega g^T$ the space one. (ii) The material point at the contact, $c - rE_n$, has
velocity $\dot c + \omega(-rE_n)$; rolling without slipping sets it to 0:
$\dot c = r\,\omega E_n = r\,g\Omega\gamma$. Its last coordinate is $E_n^Tg\Omega\gamma =
\gamma^T\Omega\gamma = 0$, so the centre stays at height $r$ (we set $c_n(0) = 0$). With the opposite
sign of $\gamma$ the path is mirrored; $r$ (``radius``) is not fixed by $a, b$ ($b = mr^2$) and
only scales the path. Initial orientation: :func:`simulate.dynamics.so.rotation_to`.

Reduced system (n = 4): eq:red-system on $r = (A, B, E, G, F_1, x, \delta)$, from :mod:`generated`.

A state is an array of shape ``(count, dim)``; :class:`FullField` packs $(\mathrm{vec}\,M, \gamma[, g, c])$.
Every field counts its evaluations (``calls``; one call evaluates the whole ensemble).
"""

from __future__ import annotations

import numpy as np
from chaplygin_nd.simulate.dynamics import so
from chaplygin_nd.simulate.kernels import Kernels, active

__all__ = ["FullField", "ReducedField"]


class FullField:
    r"""eq:motion-general on $(\mathrm{vec}\,M, \gamma)$, plus $(g, c)$ when ``reconstruct``.
    Domain: $\gamma\in S^{n-1}$, $a\in[-1,1]$, $b>0$ (where $L_\gamma$ is invertible)."""

    def __init__(self, n: int, a: float, b: float, reconstruct: bool = False,
                 radius: float = 1.0, kernels: Kernels | None = None):
        self.n, self.a, self.b, self.radius = n, a, b, radius
        self.reconstruct = reconstruct
        self.N = so.so_dim(n)
        self.dim = self.N + n + (n * n + n if reconstruct else 0)
        self.kernels = kernels or active()
        self._omega = None  # bound on first use: the Taylor reference never needs it
        self.calls = 0

    def pack(self, M, gamma, g=None, c=None) -> np.ndarray:
        """State array ``(count, dim)`` from ``M (count, n, n)``, ``gamma (count, n)`` [, g, c]."""
        parts = [so.vec(M), gamma]
        if self.reconstruct:
            parts += [g.reshape(g.shape[0], -1), c]
        return np.concatenate(parts, axis=-1)

    def unpack(self, y):
        """``(M, gamma[, g, c])`` from a state array of shape ``(..., dim)``."""
        n, N = self.n, self.N
        M = so.unvec(y[..., :N], n)
        gamma = y[..., N:N + n]
        if not self.reconstruct:
            return M, gamma
        g = y[..., N + n:N + n + n * n].reshape(y.shape[:-1] + (n, n))
        return M, gamma, g, y[..., N + n + n * n:]

    def omega(self, M, gamma):
        r"""$\Omega = L_\gamma^{-1}(M)$ (P:inversion, generated kernel)."""
        if self._omega is None:
            self._omega = self.kernels.require("angular_velocity")
        return self._omega(M, gamma, self.a, self.b)

    def generator(self, M, gamma):
        r"""$-\Omega(M, \gamma)$, the element of $\mathfrak{so}(n)$ whose action $X\cdot(M, \gamma) =
        ([X, M], X\gamma)$ is the field (for Lie-group integrators); shape ``(count, n, n)``."""
        self.calls += 1
        return -self.omega(M, gamma)

    def __call__(self, t, y):
        r"""$\dot y$ for a state of shape ``(count, dim)`` (or ``(dim,)``)."""
        self.calls += 1
        parts = self.unpack(y)
        M, gamma = parts[:2]
        Omega = self.omega(M, gamma)
        Og = np.einsum("...ij,...j->...i", Omega, gamma)
        out = [so.vec(so.commutator(M, Omega)), -Og]
        if self.reconstruct:
            g = parts[2]
            gO = g @ Omega
            out += [gO.reshape(gO.shape[:-2] + (-1,)),
                    self.radius * np.einsum("...ij,...j->...i", gO, gamma)]
        return np.concatenate(out, axis=-1)


class ReducedField:
    r"""eq:red-system on $r = (A, B, E, G, F_1, x, \delta)$ ($n = 4$; generated kernel)."""

    dim = 7
    names = ("A", "B", "E", "G", "F1", "x", "delta")  # the order of eq:red-system

    def __init__(self, a: float, b: float, kernels: Kernels | None = None):
        self.a, self.b = a, b
        self.kernels = kernels or active()
        self._field = self.kernels.require("reduced_field")
        self.calls = 0

    def __call__(self, t, r):
        """$\\dot r$ for ``r`` of shape ``(count, 7)`` (or ``(7,)``)."""
        self.calls += 1
        return self._field(r, self.a, self.b)
