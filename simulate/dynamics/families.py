r"""Initial conditions: explicit $(M_0, \gamma_0)$ or $(\Omega_0, \gamma_0)$, or a family drawn from a seed.

Families (phase space $P = \mathfrak{so}(n)\times S^{n-1}$, Sections 3–5):

* ``vertical``   — $\mathcal V = \{M\gamma = 0\}$ (eq:def-H-V): $M_0 = \Pi A \Pi$, $\Pi = \mathrm{Id} - \gamma_0\gamma_0^T$;
* ``horizontal`` — $\mathcal H = \{M = (M\gamma)\wedge\gamma\}$ (eq:def-H-V): $M_0 = v\wedge\gamma_0$, $v\perp\gamma_0$;
* ``steady-rotation`` — $n = 4$, $\eta_0\times\xi_0 = 0$ (P:steady-rot): $\Omega_0$ with $\eta_0 = s\,\xi_0$,
  $M_0 = L_{\gamma_0}(\Omega_0)$;
* ``generic``    — $A$ skew with standard normal entries, $\gamma_0$ uniform on $S^{n-1}$.

Random points come from ``numpy.random.default_rng([seed, index])`` (never ``hash()``), so a
scene reproduces bit for bit. The membership tests used to validate a family claim are here too.
"""

from __future__ import annotations

import numpy as np
from chaplygin_nd.simulate.dynamics import so
from chaplygin_nd.simulate.kernels import active

__all__ = ["FAMILIES", "draw", "claim_residual", "steady_residual"]

FAMILIES = ("generic", "vertical", "horizontal", "steady-rotation")


def _sphere(rng: np.random.Generator, n: int) -> np.ndarray:
    g = rng.standard_normal(n)
    return g / np.linalg.norm(g)


def _skew(rng: np.random.Generator, n: int) -> np.ndarray:
    return so.unvec(rng.standard_normal(so.so_dim(n)), n)


def draw(family: str, n: int, a: float, b: float, seed: int, count: int = 1,
         scale: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    r"""``count`` initial conditions $(M_0, \gamma_0)$ of ``family`` (see module docstring), shapes
    ``(count, n, n)`` and ``(count, n)``; $\|M_0\|_\kappa = $ ``scale``. Domain: $n\ge 3$
    ($n = 4$ for ``steady-rotation``), $a\in[-1, 1]$, $b > 0$."""
    if family not in FAMILIES:
        raise ValueError(f"unknown family {family!r}; one of {FAMILIES}")
    Ms, gammas = [], []
    for index in range(count):
        rng = np.random.default_rng([int(seed), index])
        gamma = _sphere(rng, n)
        A = _skew(rng, n)
        if family == "generic":
            M = A
        elif family == "vertical":
            P = np.eye(n) - np.outer(gamma, gamma)
            M = P @ A @ P
        elif family == "horizontal":
            v = rng.standard_normal(n)
            v -= (v @ gamma) * gamma
            M = so.wedge(v, gamma)
        else:  # steady-rotation, P:steady-rot
            if n != 4:
                raise ValueError("the steady-rotation family (P:steady-rot) is for n = 4")
            xi = rng.standard_normal(3)
            eta = rng.standard_normal() * xi
            Omega = so.join4(eta, xi)
            M = active().require("L_gamma")(Omega, gamma, a, b)
        M = M * (scale / max(np.sqrt(so.killing(M, M)), 1e-300))
        Ms.append(M)
        gammas.append(gamma)
    return np.array(Ms), np.array(gammas)


def claim_residual(family: str, M: np.ndarray, gamma: np.ndarray) -> float:
    r"""Relative distance of $(M, \gamma)$ from the set named by ``family`` (0 for ``generic``):
    $\|M\gamma\|/\|M\|$ for $\mathcal V$, $\|M - (M\gamma)\wedge\gamma\|/\|M\|$ for $\mathcal H$
    (eq:def-H-V). ``steady-rotation`` is checked on $\Omega$ by :func:`steady_residual`."""
    norm = max(float(np.linalg.norm(M)), 1e-300)
    if family == "vertical":
        return float(np.linalg.norm(M @ gamma) / norm)
    if family == "horizontal":
        return float(np.linalg.norm(M - so.wedge(M @ gamma, gamma)) / norm)
    return 0.0


def steady_residual(Omega: np.ndarray) -> float:
    r"""$\|\eta_0\times\xi_0\| / (\|\eta_0\|\|\xi_0\|)$ for $\Omega_0\in\mathfrak{so}(4)$ (P:steady-rot);
    0 when $\eta_0$ or $\xi_0$ vanishes."""
    eta, xi = so.split4(Omega)
    den = np.linalg.norm(eta) * np.linalg.norm(xi)
    return 0.0 if den == 0 else float(np.linalg.norm(np.cross(eta, xi)) / den)
