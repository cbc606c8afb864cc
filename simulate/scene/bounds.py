r"""Error bounds of the closed forms at the scene's horizon, in float64.

A closed form is exact mathematics evaluated in float64, and its error grows with time: a phase
$\lambda t$ is known to about $|\lambda| t\,\varepsilon$, and a rotation rate computed with relative
error $\delta$ turns into a phase error $|\lambda|\,t\,\delta$. The integrals are kept exactly by a
rotation, so their drift cannot see a phase error: this module says what the outputs can. The
planner (:mod:`simulate.scene.planner`) takes a closed form only when :func:`closed_form` is at
most ``accuracy.target``.

What is measured and what is assumed, for one initial condition (the bound of a scene is the worst
over its initial conditions, relative to the largest value of each output at $t_0$, as the
cross-check measures; an output that is 0 at $t_0$ is bounded absolutely):

* **the velocity** $X$ ($X = -\Omega_0$, $\Omega_0 = L_{\gamma_0}^{-1}M_0$, or $X = \zeta$, Th:Re):
  its float64 error is *measured*, not assumed. The residual $M_0 - L_{\gamma_0}(\hat\Omega_0)$ is
  evaluated in extended precision (``numpy.longdouble``, 64-bit significand on x86-64), and one
  step of refinement $\delta\Omega = L^{-1}(\text{residual})$ gives the error of $\hat\Omega_0$
  (first order, so it is doubled). For $\zeta = \kappa(x_0)M_0 - \Omega_0$ the part along $M_0$ is
  the scalar $\kappa$, a low-degree rational function of $x_0$, whose error is
  measured too, from $(\kappa M_0 - \Omega_0)E_n = 0$ with the refined $\Omega_0$ (assumed within 16
  ulps where $M_0E_n$ is too small for that). Where ``longdouble`` is float64
  itself (e.g. on arm64 macOS) the documented kernel bound is used instead: 8 ulps of
  $\lVert L_\gamma^{-1}\rVert\lVert M\rVert_\kappa$, $\lVert L_\gamma^{-1}\rVert \le 1/\min(2, 2+a)$
  (``tests/test_kernels_axisym.py``; the cross-check of the formula's conditioning);
* **the exponential** $e^{Xt} = Ve^{-i\Lambda t}V^*$ (:func:`simulate.dynamics.so.expm_skew_t`, its
  modes paired as a real matrix needs): its backward error $\lVert X_\text{eff} - X\rVert$ and the
  loss of orthogonality $\lVert E^TE - I\rVert$ are measured in extended precision (and doubled); the phase $\lambda t$ is rounded once, by at
  most $|\lambda t|\,\varepsilon/2$ — the error no float64 evaluation avoids;
* so the rotation at time $t$ is off by at most
  $\varphi(t) = (\lVert\delta X\rVert + 2\lVert X_\text{eff} - X\rVert + \tfrac12\varepsilon\lVert X\rVert)\,t
  + 2\lVert E^TE - I\rVert + 4n\varepsilon$ ($e^{(X+\delta)t} - e^{Xt}$ has norm at most
  $\lVert\delta\rVert t$ for skew $X, \delta$), and the outputs by: $M$, $\Omega$: $(2\varphi + \varphi^2 + 2n\varepsilon)$ times
  their norm (plus $\lVert\delta\Omega_0\rVert$ for $\Omega$); $\gamma$, $x$: $\varphi + n\varepsilon$;
  $g$: $\varphi_W + \varphi + n\varepsilon$ ($W = \Omega_0 + X$); the contact path
  $r\,(\sum_\lambda |w_\lambda|\,\mathrm{rate}_W\min(T^2/2, T/|\lambda| + 2/\lambda^2) + T\lvert\delta v\rvert)$
  over the modes $\lambda$ of $W$ ($v = \Omega_0\gamma_0 = \sum w_\lambda$), relative to its
  largest computed value at the samples less that error;
  $\zeta$: $\lVert\delta X\rVert$;
* **the integrals** (energy, $p(\lambda,\sigma)$, $\lVert\gamma\rVert^2$) are invariant under the rotation,
  so their error does not grow with $t$: it is the evaluation noise of their formulas on rotated
  copies of the initial point, measured on four seeded random rotations (times 4);
* **the horizontal forms** (S5:H-linear, S5:H-linear-nD): $x(t) = R\cos(\nu t - \phi)$ and $G$ with
  $\nu^2 = (F_2 - 2bH)/((2+a)(2+a+b))$. The error of $\nu$ follows from those of $F_2$ (rounding)
  and $H = \tfrac12\langle M_0, \hat\Omega_0\rangle$ as the closed form computes them, each measured
  against extended precision with the refined $\Omega_0$: the
  formula's conditioning, large when $F_2 \approx 2bH$ (slow rotation). Then $|\delta x| \le
  R\,[(\nu t + 1)\,\delta\nu/\nu + 4\varepsilon\nu t + 8\varepsilon]$, $G$ likewise with amplitude
  $(2+a+b)\nu R$, and $(A, B) = (F_2 - B, F_2x^2 + G^2)$ to first order.

All of it is first order in $\varepsilon$ with the measured parts doubled; ``tests/test_closed_form_bounds.py``
compares the bound with the error measured against mpmath at 60 digits for $T$ up to $10^{12}$ for
every closed form and every family that reaches one. What is not covered: a point that is on the
family only to within the planner's membership test (:data:`simulate.scene.planner.APPLIES`) leaves
the family at a rate no closed form accounts for.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from chaplygin_nd.simulate.dynamics import so
from chaplygin_nd.simulate.kernels import Kernels

__all__ = ["Bound", "closed_form", "EPS", "EXTENDED"]

EPS = float(np.finfo(float).eps)
#: Whether ``numpy.longdouble`` carries more digits than float64 (the measured parts need it).
EXTENDED = float(np.finfo(np.longdouble).eps) < EPS / 100
#: Documented kernel bound in ulps of the condition scale (tests/test_kernels_axisym.py).
KERNEL_ULPS = 8.0
#: Assumed relative error of the scalar kappa(x0) of zeta (a low-degree rational function of x0).
KAPPA_ULPS = 16.0
#: Random rotations on which the integrals' evaluation noise is measured, and its safety factor.
ROTATIONS, NOISE_SAFETY = 4, 4.0


@dataclass
class Bound:
    """A closed form's relative error bound at the horizon ``span``: the worst output and each."""

    model: str
    span: float
    outputs: dict[str, float] = field(default_factory=dict)
    phase: float = 0.0  # the largest rotation error phi(T) (radians)

    @property
    def value(self) -> float:
        """The worst relative error bound over the outputs."""
        return max(self.outputs.values(), default=0.0)

    @property
    def worst(self) -> str:
        """The output with the largest bound."""
        return max(self.outputs, key=self.outputs.__getitem__) if self.outputs else ""

    def describe(self) -> str:
        """For the plan line: the bound, where it comes from and the output that sets it."""
        return (f"relative error <= {self.value:.2g} at T = {self.span:.3g} (float64: phase "
                f"error {self.phase:.2g} rad at T; worst output {self.worst})")


def _spectral_norm(X: np.ndarray) -> float:
    return float(np.linalg.norm(X, 2)) if X.size else 0.0


def _L_long(Omega, gamma, a, b):
    r"""$L_\gamma(\Omega) = \mathbb J\Omega + \Omega\mathbb J + b\,(\Omega\gamma)\wedge\gamma$ (eq:M-O) in
    ``numpy.longdouble``; $\mathbb J = \mathrm{Id} + aE_nE_n^T$."""
    O = Omega.astype(np.longdouble)
    g = gamma.astype(np.longdouble)
    JO = 2 * O
    JO[..., -1, :] += np.longdouble(a) * O[..., -1, :]
    JO[..., :, -1] += np.longdouble(a) * O[..., :, -1]
    Og = np.einsum("...ij,...j->...i", O, g)
    uv = Og[..., :, None] * g[..., None, :]
    return JO + np.longdouble(b) * (uv - np.swapaxes(uv, -1, -2))


def _refined(M0, gamma0, Omega0, a, b, k: Kernels):
    r"""$\hat\Omega_0$ plus one refinement step from the extended-precision residual (``longdouble``),
    and the step's size per initial condition."""
    residual = (M0.astype(np.longdouble) - _L_long(Omega0, gamma0, a, b)).astype(float)
    step = k.require("angular_velocity")(residual, gamma0, a, b)
    return Omega0.astype(np.longdouble) + step, np.array([_spectral_norm(s) for s in step])


def omega_error(M0, gamma0, Omega0, a, b, k: Kernels) -> np.ndarray:
    r"""Per initial condition, a bound on $\lVert\hat\Omega_0 - L_{\gamma_0}^{-1}M_0\rVert_2$ (module
    docstring): twice the refinement step from an extended-precision residual, or the documented
    kernel bound without extended precision."""
    n = M0.shape[-1]
    d = n * (n - 1) // 2
    normM = np.sqrt(np.maximum(so.killing(M0, M0), 0.0))
    if not EXTENDED:
        return math.sqrt(d) * KERNEL_ULPS * EPS * normM / min(2.0, 2.0 + a)
    _, step = _refined(M0, gamma0, Omega0, a, b, k)
    # the refinement's own rounding: the residual in extended precision, through L^-1
    floor = 64 * float(np.finfo(np.longdouble).eps) * normM / min(2.0, 2.0 + a)
    return 2 * step + floor


def zeta_error(zeta, M0, gamma0, Omega0, dOmega, a, b, k: Kernels) -> np.ndarray:
    r"""Per initial condition, a bound on the error of the computed $\zeta$ (Th:Re): twice its
    distance from $\kappa M_0 - \Omega_0$ with $\Omega_0$ refined in extended precision and
    $\kappa$ from $(\kappa M_0 - \Omega_0)E_n = 0$; where $M_0E_n$ is small ($< 10^{-3}\lVert M_0\rVert$)
    or without extended precision, the part off $M_0$ is measured against $\hat\Omega_0$ and
    $\kappa$ is assumed within :data:`KAPPA_ULPS` ulps."""
    normM = np.array([_spectral_norm(m) for m in M0])
    col = M0[:, :, -1]
    usable = EXTENDED and bool(np.all(np.linalg.norm(col, axis=-1) >= 1e-3 * normM))
    if usable:
        Oref, _ = _refined(M0, gamma0, Omega0, a, b, k)
        Ml = M0.astype(np.longdouble)
        kappa = (np.einsum("ei,ei->e", Ml[:, :, -1], Oref[:, :, -1])
                 / np.einsum("ei,ei->e", Ml[:, :, -1], Ml[:, :, -1]))
        rest = (zeta.astype(np.longdouble) - (kappa[:, None, None] * Ml - Oref)).astype(float)
        floor = 64 * float(np.finfo(np.longdouble).eps) * normM * (
            1 / min(2.0, 2.0 + a) + np.abs(kappa.astype(float)))  # the reference's own rounding
        return 2 * np.array([_spectral_norm(r) for r in rest]) + floor
    normM2 = np.maximum(so.killing(M0, M0), 1e-300)
    kappa = so.killing(zeta + Omega0, M0) / normM2  # zeta + Omega0 = kappa M0 (Th:Re)
    rest = zeta - (kappa[:, None, None] * M0 - Omega0)
    return (2 * np.array([_spectral_norm(r) for r in rest]) + 2 * dOmega
            + KAPPA_ULPS * EPS * np.abs(kappa) * normM)


def _eig_errors(X: np.ndarray, span: float) -> tuple[float, float]:
    r"""(backward error, loss of orthogonality) of $e^{Xt}$ as :func:`simulate.dynamics.so.expm_skew_t`
    builds it from :func:`simulate.dynamics.so.skew_modes`, measured in extended precision: the
    generator it really exponentiates, $X_\text{eff} = 2\sum_{\lambda>0}\lambda\,\mathrm{Im}(vv^*)$,
    against $X$ (the modes it sets to 0 included), and $\lVert E^TE - I\rVert$ at $t = 0$ and at the
    horizon; each doubled."""
    n = X.shape[-1]
    if not EXTENDED:
        return 4 * n * EPS * _spectral_norm(X), 4 * n * EPS  # LAPACK's backward-stability constant
    _, lam, V = so.skew_modes(X)
    Vl = V.astype(np.clongdouble)
    Xeff = 2 * np.imag((Vl * lam.astype(np.longdouble)) @ Vl.conj().T)
    back = float(np.sqrt(np.sum((Xeff - X.astype(np.longdouble)) ** 2)))
    E = so.expm_skew_t(X, np.array([0.0, span])).astype(np.longdouble)
    unit = max(float(np.sqrt(np.sum((e.T @ e - np.eye(n, dtype=np.longdouble)) ** 2))) for e in E)
    return 2 * back, 2 * unit + 4 * EPS


def _phase_terms(dX: float, X: np.ndarray, span: float) -> tuple[float, float]:
    """(rate, constant) of phi(t) = rate t + constant, the error of the computed e^{Xt} (module
    docstring)."""
    n = X.shape[-1]
    back, unit = _eig_errors(X, span)
    return dX + back + 0.5 * EPS * _spectral_norm(X), unit + 4 * n * EPS


def _phase(dX: float, X: np.ndarray, span: float) -> float:
    """phi(span): the error of the computed e^{Xt} at t = span (module docstring)."""
    rate, constant = _phase_terms(dX, X, span)
    return rate * span + constant


def _integral_phase(W: np.ndarray, v: np.ndarray, rate: float, span: float) -> float:
    r"""Error of $\int_0^T e^{Ws}ds\,v$ from a rate error ``rate`` of every eigenvalue: per mode
    $\lambda$ of weight $w$, $|\partial_\lambda (1 - e^{-i\lambda T})/(i\lambda)| \le
    \min(T^2/2,\ T/|\lambda| + 2/\lambda^2)$ times ``rate`` $|w|$ (the secular mode $\lambda = 0$
    grows like $T^2$, the others like $T$)."""
    lam, V = np.linalg.eigh(1j * W)
    w = np.abs(V.conj().T @ v)
    with np.errstate(divide="ignore"):
        per = np.minimum(span ** 2 / 2, span / np.abs(lam) + 2 / lam ** 2)
    return float(rate * np.sum(w * per))


def _relative(abs_errors, sizes) -> float:
    """Worst absolute error over the worst size (absolute when every size is 0)."""
    top = float(np.max(sizes)) if np.size(sizes) else 0.0
    worst = float(np.max(abs_errors)) if np.size(abs_errors) else 0.0
    return worst / top if top > 0 else worst


def _noise(values: list[dict[str, np.ndarray]]) -> dict[str, float]:
    """Relative spread of each integral over rotated copies of the same point (times the safety)."""
    out = {}
    for key in values[0]:
        stack = np.stack([np.asarray(v[key], dtype=float) for v in values])
        top = float(np.max(np.abs(stack)))
        spread = float(np.max(np.abs(stack - stack[:1])))
        out[key] = NOISE_SAFETY * (spread + 8 * EPS * top) / top if top > 0 else 0.0
    return out


def _integrals_noise(M0, gamma0, Omega0, dOmega, seed: int = 0) -> dict[str, float]:
    """The integrals' evaluation error on rotated copies (module docstring), with the effect of
    the error of Omega0 on the energy."""
    from chaplygin_nd.simulate.scene.outputs import integrals

    rng = np.random.default_rng(seed)
    n = M0.shape[-1]
    copies = [integrals(M0, gamma0, Omega0)]
    for _ in range(ROTATIONS):
        Q, _r = np.linalg.qr(rng.standard_normal((n, n)))
        Qt = Q.T
        copies.append(integrals(Q @ M0 @ Qt, np.einsum("ij,...j->...i", Q, gamma0),
                                Q @ Omega0 @ Qt))
    noise = _noise(copies)
    twoH = np.abs(so.killing(M0, Omega0))
    normM = np.sqrt(np.maximum(so.killing(M0, M0), 0.0))
    e_energy = np.sqrt(n * (n - 1) / 2) * normM * dOmega  # |<M0, dOmega>| <= |M0|_k |dOmega|_k
    noise["energy"] += _relative(0.5 * e_energy, 0.5 * twoH)
    return noise


def relative_equilibrium(X, M0, gamma0, Omega0, dX, dOmega, elapsed: np.ndarray, outputs,
                         reconstruct: bool, radius: float, model: str) -> Bound:
    """The bound of the relative-equilibrium closed forms (``constant-Omega``, ``vertical``) for
    the batch ``X, M0, gamma0, Omega0`` ``(count, n, n)``/``(count, n)`` with measured velocity
    errors ``dX`` and ``dOmega`` (module docstring), sampled at ``elapsed`` = t - t0."""
    count, n = gamma0.shape
    span = float(elapsed[-1])
    phi = np.array([_phase(float(dX[e]), X[e], span) for e in range(count)])
    normM = np.array([_spectral_norm(m) for m in M0])
    normO = np.array([_spectral_norm(o) for o in Omega0])
    grow = 2 * phi + phi ** 2 + 2 * n * EPS
    b = Bound(model, span, phase=float(np.max(phi)))
    want = set(outputs)
    if "M" in want:
        b.outputs["M"] = _relative(grow * normM, np.abs(M0).max(axis=(-1, -2)))
    if "Omega" in want:
        b.outputs["Omega"] = _relative(grow * normO + dOmega, np.abs(Omega0).max(axis=(-1, -2)))
    if "gamma" in want:
        b.outputs["gamma"] = _relative(phi + n * EPS, np.abs(gamma0).max(axis=-1))
    if "x" in want:
        b.outputs["x"] = _relative(phi + n * EPS, np.abs(gamma0[:, -1]))
    if "zeta" in want and model == "vertical":
        b.outputs["zeta"] = _relative(dX, np.abs(X).max(axis=(-1, -2)))
    if reconstruct:
        W = Omega0 + X
        termsW = [_phase_terms(float(dX[e] + dOmega[e]), W[e], span) for e in range(count)]
        phiW = np.array([rate * span + constant for rate, constant in termsW])
        if "orientation" in want:
            g0 = np.array([so.rotation_to(g) for g in gamma0])
            b.outputs["orientation"] = _relative(phiW + phi + n * EPS, np.abs(g0).max(axis=(-1, -2)))
        if "contact_path" in want:
            v = np.einsum("eij,ej->ei", Omega0, gamma0)
            dv = dOmega + 2 * n * EPS * np.linalg.norm(v, axis=-1)
            # int_0^T phi_W(s) ds |v| + T |dv|; the size: the largest computed |c| less that error
            rate = np.array([r for r, _ in termsW])
            const = np.array([c_ for _, c_ in termsW])
            err = radius * (np.array([_integral_phase(W[e], v[e], rate[e], span)
                                      for e in range(count)])
                            + const * span * np.linalg.norm(v, axis=-1) + dv * span)
            sizes = np.array([np.abs(so.expm_integral(W[e], v[e], elapsed)[:, :-1]).max()
                              for e in range(count)]) * radius
            b.outputs["contact_path"] = _relative(err, sizes - err) \
                if np.max(sizes - err) > 0 else math.inf
    if "integrals" in want:
        for key, value in _integrals_noise(M0, gamma0, Omega0, dOmega).items():
            b.outputs[f"integrals.{key}"] = value + (2 * n * EPS if key != "energy" else 0.0)
    return b


def _integral_errors(M0, gamma0, Omega0, dOmega, F2, H, a, b, k: Kernels):
    r"""Errors of the $F_2 = \lVert M_0\rVert_\kappa^2$ and $H = \tfrac12\langle M_0, \Omega_0\rangle_\kappa$ a
    horizontal form uses: measured against extended precision with the refined $\Omega_0$
    (doubled), or a priori without it."""
    n = M0.shape[-1]
    d = n * (n - 1) // 2
    normM = np.sqrt(np.maximum(so.killing(M0, M0), 0.0))
    if not EXTENDED:
        return (4 * d * EPS * np.abs(F2),
                0.5 * math.sqrt(d) * normM * dOmega + 4 * d * EPS * np.abs(H))
    eps_l = float(np.finfo(np.longdouble).eps)
    Ml = M0.astype(np.longdouble)
    Oref, _ = _refined(M0, gamma0, Omega0, a, b, k)
    F2l = 0.5 * np.sum(Ml * Ml, axis=(-1, -2))
    Hl = 0.25 * np.sum(Ml * Oref, axis=(-1, -2))
    dF2 = 2 * np.abs(F2 - F2l).astype(float) + 8 * d * eps_l * np.abs(F2)
    dH = 2 * np.abs(H - Hl).astype(float) + 64 * d * eps_l * normM ** 2 / min(2.0, 2.0 + a)
    return dF2, dH


def horizontal(M0, gamma0, Omega0, dOmega, a: float, b: float, span: float, outputs,
               model: str, k: Kernels) -> Bound:
    """The bound of the horizontal closed forms (``horizontal``: $(x, G, A, B)$ any $n$;
    ``horizontal-4D``: the reduced invariants) for the batch ``M0, gamma0, Omega0`` (module
    docstring)."""
    x0 = gamma0[:, -1]
    G0 = np.einsum("ei,ei->e", M0[:, :, -1], gamma0)
    if model == "horizontal-4D":  # F2, H as the closed form takes them: the reduced integrals
        F = k.require("reduced_integrals")(so.reduced_invariants(M0, gamma0), a, b)
        F2, H = F[..., 1], F[..., 3]
    else:
        F2, H = so.killing(M0, M0), 0.5 * so.killing(M0, Omega0)
    c = 2.0 + a + b
    dF2, dH = _integral_errors(M0, gamma0, Omega0, dOmega, F2, H, a, b, k)
    num = F2 - 2 * b * H
    nu2 = num / ((2.0 + a) * c)
    nu = np.sqrt(np.maximum(nu2, 0.0))
    dnu2 = 2 * (dF2 + 2 * b * dH) / ((2.0 + a) * c) + 4 * EPS * np.abs(nu2)
    with np.errstate(divide="ignore", invalid="ignore"):
        rel_nu = np.where(nu2 > 0, dnu2 / (2 * nu2), np.inf)
        R = np.sqrt(x0 ** 2 + np.where(nu > 0, (G0 / (c * nu)) ** 2, np.inf))
    T = span
    theta = nu * T
    factor = np.where(np.isfinite(rel_nu), (theta + 1) * rel_nu + 4 * EPS * theta + 8 * EPS,
                      np.inf)
    dx = R * factor
    RG = c * nu * R
    dG = RG * factor + 8 * EPS * np.abs(G0)
    Bmax = F2 * np.minimum(R, 1.0) ** 2 + RG ** 2
    dB = 2 * F2 * np.minimum(R, 1.0) * dx + 2 * RG * dG + dF2 + 4 * EPS * (F2 + Bmax)
    dA = dB + dF2 + 4 * EPS * F2
    A0 = F2 - (F2 * x0 ** 2 + G0 ** 2)
    B0 = F2 * x0 ** 2 + G0 ** 2
    bd = Bound(model, span, phase=float(np.max(theta * rel_nu + 4 * EPS * theta)))
    want = set(outputs)
    if "x" in want:
        bd.outputs["x"] = _relative(dx, np.abs(x0))
    if model == "horizontal" and "horizontal" in want:
        sizes = [np.abs(x0), np.abs(G0), np.abs(A0), np.abs(B0)]
        errs = [dx, dG, dA, dB]
        bd.outputs["horizontal"] = max(_relative(e, s) for e, s in zip(errs, sizes))
    if model == "horizontal-4D":
        if "reduced" in want:
            delta0 = -x0 * A0
            dd = np.minimum(R, 1.0) * dA + np.abs(A0 + dA) * dx
            sizes = [np.abs(A0), np.abs(B0), np.abs(G0), np.abs(x0), np.abs(delta0)]
            errs = [dA, dB, dG, dx, dd]
            bd.outputs["reduced"] = max(_relative(e, s) for e, s in zip(errs, sizes))
        if "integrals" in want:  # F1 = E = 0 exactly; F2, H and F3 from the reduced integrals
            bd.outputs["integrals"] = _relative(dA + dB + dH + dF2, np.abs(F2) + np.abs(H))
    return bd


def closed_form(model: str, scene, Omega0: np.ndarray, k: Kernels) -> Bound:
    """The bound of the closed form ``model`` for ``scene`` at its horizon ``t[-1] - t[0]``
    (module docstring); ``Omega0`` the planner's $L_{\\gamma_0}^{-1}M_0$."""
    span = float(scene.t[-1] - scene.t[0])
    M0, gamma0, a, b = scene.M0, scene.gamma0, scene.a, scene.b
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        dOmega = omega_error(M0, gamma0, Omega0, a, b, k)
        if model in ("constant-Omega", "vertical"):
            if model == "vertical":
                X = k.require("zeta")(M0, gamma0, a, b)
                dX = zeta_error(X, M0, gamma0, Omega0, dOmega, a, b, k)
            else:
                X, dX = -Omega0, dOmega
            return relative_equilibrium(X, M0, gamma0, Omega0, dX, dOmega, scene.t - scene.t[0],
                                        scene.outputs,
                                        bool(set(scene.outputs) & {"orientation", "contact_path"}),
                                        scene.radius, model)
        return horizontal(M0, gamma0, Omega0, dOmega, a, b, span, scene.outputs, model, k)
