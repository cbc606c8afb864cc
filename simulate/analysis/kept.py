r"""How well the proved first integrals are kept along a sampled orbit: the cheapest and
sharpest sign that the integrated field is the right one.

* On $P$ (the axisymmetric full field eq:motion-general, any $n$, and the general-$\mathbb{J}$ control
  of :mod:`simulate.analysis.control`): the energy $H = \frac12\langle M, \Omega\rangle$ (Killing form
  $\langle A, B\rangle = -\frac12\mathrm{tr}\,AB$, $\Omega = L_\gamma^{-1}M$ from the generated kernel, or the
  control's solve) and the coefficients of $p(\lambda, \sigma) = \det(M + \sigma\gamma\gamma^T - \lambda)$
  (eq:pol-first-integrals), which is affine in $\sigma$: $p = \chi_M(\lambda) + \sigma(\chi_{M + \gamma\gamma^T}(\lambda)
  - \chi_M(\lambda))$, $\chi_A$ the characteristic polynomial (:func:`_charpoly`).
* On the reduced space $\mathcal R$ (eq:red-system): $(F_1, F_2, F_3, H)$ of S5:red-integrals (generated).

Every quantity is computed at energy scale 1 (the field is homogeneous: $M \to M/s$, and on
$\mathcal R$ the coordinates $(A, B, E, G, F_1, x, \delta)$ by $s^{-(2, 2, 1, 1, 2, 0, 2)}$), so the *drift*
$\max_t |I(t) - I(0)|$ of each integral is an absolute number on the scale of 1, also for
integrals that vanish on the orbit (the $\sigma$ coefficients on $\mathcal V$). The drift of an orbit
is the largest over its integrals; :func:`drift` also names which one.
"""

from __future__ import annotations

import numpy as np
from chaplygin_nd.simulate.dynamics import so

__all__ = ["p_coefficients", "energy", "drift", "REDUCED_DEGREES", "KEPT"]

#: homogeneity degrees in M of r = (A, B, E, G, F1, x, delta) (simulate.dynamics.so.reduced_invariants)
REDUCED_DEGREES = np.array([2, 2, 1, 1, 2, 0, 2])
#: an orbit keeps its integrals iff the drift is at most this (at scale 1; the Taylor tolerance of
#: the rows is 1e-9, and the study's integrable orbits kept them to < 1e-8, bench/bench_evidence.py)
KEPT = 1e-6


def _charpoly(A: np.ndarray) -> np.ndarray:
    r"""Coefficients (highest first, leading 1 dropped) of $\det(\lambda - A)$, batched ``(..., n, n)``,
    by the Faddeev–LeVerrier recursion $N_1 = \mathrm{Id}$, $c_k = -\mathrm{tr}(AN_k)/k$,
    $N_{k+1} = AN_k + c_k\mathrm{Id}$ ($n$ batched matrix products; Gantmacher, *The Theory of
    Matrices* I, IV.4). Measured on the rows' matrices ($n \le 7$, entries of order 1): equal to the
    coefficients from the eigenvalues to $10^{-15}$ relative, 20–30 times faster (the eigenvalues
    of a million small matrices were a tenth of a cold Th:Re-tori:frequencies)."""
    n = A.shape[-1]
    c = np.empty(A.shape[:-2] + (n,))
    eye = np.eye(n)
    N = np.broadcast_to(eye, A.shape)
    for k in range(1, n + 1):
        AN = A @ N
        c[..., k - 1] = -np.trace(AN, axis1=-2, axis2=-1) / k
        N = AN + c[..., k - 1, None, None] * eye
    return c


def p_coefficients(M: np.ndarray, gamma: np.ndarray) -> np.ndarray:
    r"""The non-leading coefficients of $p(\lambda, \sigma)$ (eq:pol-first-integrals) at each state:
    those of $\chi_M$ and of the $\sigma$ part $\chi_{M + \gamma\gamma^T} - \chi_M$, shape ``(..., 2n)``.
    Domain: $M$ skew ``(..., n, n)``, $\gamma$ ``(..., n)``."""
    base = _charpoly(M)
    shifted = _charpoly(M + gamma[..., :, None] * gamma[..., None, :])
    return np.concatenate([base, shifted - base], axis=-1)


def energy(M: np.ndarray, Omega: np.ndarray) -> np.ndarray:
    r"""$H = \frac12\langle M, \Omega\rangle = -\frac14\mathrm{tr}(M\Omega)$ (eq:energy with the Killing form)."""
    return -0.25 * np.einsum("...ij,...ji->...", M, Omega)


def drift(kind: str, Y: np.ndarray, a: np.ndarray, b: np.ndarray, scale: np.ndarray, n: int,
          J=()) -> tuple[np.ndarray, list[str]]:
    r"""Per orbit, the largest drift of its first integrals along the samples ``Y``
    ``(samples, orbits, dim)`` (module docstring) and the name of the integral that drifted most.
    ``kind``: ``reduced`` (``Y`` on $\mathcal R$), ``full`` (axisymmetric, generated $L_\gamma^{-1}$) or
    ``control`` (diagonal mass tensor ``J``). ``a``, ``b``, ``scale``: per orbit."""
    from chaplygin_nd.simulate.kernels import active

    out, names = np.empty(Y.shape[1]), []
    for k in range(Y.shape[1]):
        y = Y[:, k]
        if kind == "reduced":
            r = y / scale[k] ** REDUCED_DEGREES
            ints = np.asarray(active().require("reduced_integrals")(r, a[k], b[k]))
            labels = ["F1", "F2", "F3", "H"]
        else:
            N = so.so_dim(n)
            M, g = so.unvec(y[:, :N] / scale[k], n), y[:, N:N + n]
            if kind == "control":
                from chaplygin_nd.simulate.analysis.control import general_inertia_kernels

                Om = general_inertia_kernels(J, b[k]).require("angular_velocity")(M, g, a[k], b[k])
            else:
                Om = active().require("angular_velocity")(M, g, a[k], b[k])
            ints = np.concatenate([energy(M, Om)[:, None], p_coefficients(M, g)], axis=-1)
            labels = ["H"] + [f"p[lambda^{n - 1 - i}]" for i in range(n)] + \
                     [f"p[sigma lambda^{n - 1 - i}]" for i in range(n)]
        d = np.max(np.abs(ints - ints[:1]), axis=0)
        i = int(np.argmax(d))
        out[k] = float(d[i])
        names.append(labels[i])
    return out, names
