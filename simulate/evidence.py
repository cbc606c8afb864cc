r"""Orbits for the numerical evidence of Section 5 (issue 11), integrated once and cached on disk.

An :class:`Experiment` names a vector field (the reduced field eq:red-system, the full field
eq:motion-general with the generated $L_\gamma^{-1}$, or the general-$\mathbb{J}$ control of
:mod:`simulate.control`), its parameters, the initial conditions (a family and seed of
:mod:`simulate.families`, optionally moved along a level set of the reduced integrals), the
sampling and the DOP853 tolerance. :func:`orbits` returns the samples, from the cache when the
cache key matches, else by integrating (and then writing the cache atomically).

Cache key: SHA-256 of the experiment (JSON), of every file of ``generated/`` and of the source
of the modules that turn it into numbers (this one, :mod:`simulate.field`, :mod:`simulate.control`,
:mod:`simulate.families`, the DOP853 wrapper). A changed kernel, scene or setting therefore
recomputes; nothing is read that this code cannot reproduce. Location: the ``evidence/`` subfolder of the
project's cache folder (:mod:`chaplygin_nd.cache`).
"""

from __future__ import annotations

import fcntl
import hashlib
import json
import os
import tempfile
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np
from chaplygin_nd.simulate import families, so
from chaplygin_nd.simulate.control import general_inertia_kernels
from chaplygin_nd.simulate.dispatch import active
from chaplygin_nd.simulate.field import FullField, ReducedField
from chaplygin_nd.simulate.integrators import dop853
from chaplygin_nd.simulate.run import reduced_invariants

from chaplygin_nd import cache as project_cache

__all__ = ["Experiment", "Orbits", "orbits", "cache_dir", "level_set_points", "signals"]

ROOT = Path(__file__).resolve().parent.parent
_SOURCES = ("simulate/evidence.py", "simulate/field.py", "simulate/control.py",
            "simulate/families.py", "simulate/integrators/dop853.py", "simulate/run.py")


@dataclass(frozen=True)
class Experiment:
    r"""One ensemble of orbits. ``model``: ``reduced`` | ``full`` | ``control``; ``J``: the diagonal
    mass tensor of the control; ``members``: which members of the family draw to use;
    ``level_shifts``: for ``reduced``, extra orbits on the level set of the first member, moved
    by these distances across the flow (:func:`level_set_points`)."""

    name: str
    model: str
    n: int
    a: float
    b: float
    family: str
    seed: int
    members: tuple[int, ...]
    dt: float
    samples: int
    rtol: float = 1e-11
    scale: float = 1.0
    J: tuple[float, ...] = ()
    level_shifts: tuple[float, ...] = ()

    def key(self) -> str:
        h = hashlib.sha256(json.dumps(asdict(self), sort_keys=True).encode())
        for path in sorted((ROOT / "generated").glob("*.py")) + [ROOT / s for s in _SOURCES]:
            h.update(path.name.encode())
            h.update(path.read_bytes())
        return h.hexdigest()[:20]


@dataclass
class Orbits:
    """Samples ``y`` of shape ``(samples + 1, count, dim)`` at ``t``, with the integration cost."""

    experiment: Experiment
    t: np.ndarray
    y: np.ndarray
    seconds: float
    steps: int
    cached: bool = False
    info: dict = field(default_factory=dict)


def cache_dir() -> Path:
    """The ``evidence/`` subfolder of the project's cache folder (:mod:`chaplygin_nd.cache`)."""
    return project_cache.cache_dir("evidence")


def _reduced_constraints(r: np.ndarray, a: float, b: float) -> np.ndarray:
    r"""$(F_1, F_2, F_3, H, \delta^2 - \det\Lambda)$ at $r = (A, B, E, G, F_1, x, \delta)$ (S5:red-integrals
    from :mod:`generated`; $\Lambda$ as defined in Section 5, Reduction by SO(3))."""
    A, B, E, G, F1, x, d = np.moveaxis(r, -1, 0)
    Lam = np.stack([np.stack([A, F1, E], -1), np.stack([F1, B, G], -1),
                    np.stack([E, G, 1 - x**2], -1)], -2)
    ints = active().require("reduced_integrals")(r, a, b)
    return np.concatenate([ints, (d**2 - np.linalg.det(Lam))[..., None]], axis=-1)


def level_set_points(r0: np.ndarray, shifts, a: float, b: float) -> np.ndarray:
    r"""Points of $\mathcal{R}$ on the level set of $(F_1, F_2, F_3, H)$ through ``r0`` but on other
    orbits: step by ``s`` along the direction of the level set's tangent plane (the kernel of the
    5 gradients, central differences) orthogonal to the flow, then Newton (minimum-norm) back onto
    the level set to $10^{-13}$. Raises if Newton does not converge."""
    f = ReducedField(a, b)
    target = _reduced_constraints(r0, a, b)

    def jac(r):
        h = 1e-6
        cols = [(_reduced_constraints(r + h * e, a, b) - _reduced_constraints(r - h * e, a, b))
                / (2 * h) for e in np.eye(7)]
        return np.array(cols).T

    out = []
    for s in shifts:
        _, sv, vt = np.linalg.svd(jac(r0))
        tangent = vt[5:]                      # the 2-dimensional kernel
        v = f(0.0, r0)
        v_t = tangent @ v
        across = tangent.T @ np.array([-v_t[1], v_t[0]])
        r = r0 + s * across / np.linalg.norm(across)
        for _ in range(50):
            res = _reduced_constraints(r, a, b) - target
            if np.max(np.abs(res)) < 1e-13:
                break
            r = r - np.linalg.lstsq(jac(r), res, rcond=None)[0]
        else:
            raise RuntimeError(f"level-set Newton did not converge (residual {np.abs(res).max():.2e})")
        out.append(r)
    return np.array(out)


def initial_states(exp: Experiment):
    """(field, y0) of the experiment."""
    M0, g0 = families.draw(exp.family, exp.n, exp.a, exp.b, exp.seed,
                           count=max(exp.members) + 1, scale=exp.scale)
    M0, g0 = M0[list(exp.members)], g0[list(exp.members)]
    if exp.model == "reduced":
        f = ReducedField(exp.a, exp.b)
        r0 = reduced_invariants(M0, g0)
        extra = level_set_points(r0[0], exp.level_shifts, exp.a, exp.b) if exp.level_shifts \
            else np.zeros((0, 7))
        return f, np.concatenate([r0[:1], extra, r0[1:]])
    kernels = general_inertia_kernels(exp.J, exp.b) if exp.model == "control" else None
    f = FullField(exp.n, exp.a, exp.b, kernels=kernels)
    return f, f.pack(M0, g0)


def orbits(exp: Experiment, use_cache: bool = True) -> Orbits:
    """The sampled orbits of ``exp``, from the cache if its key matches, else integrated with
    DOP853 (one stacked system for the ensemble) and cached."""
    path = cache_dir() / f"{exp.name}-{exp.key()}.npz"
    if not use_cache:
        return _integrate(exp, None)
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path.with_suffix(".lock"), "w") as lock:  # one process integrates, the others wait
        fcntl.flock(lock, fcntl.LOCK_EX)
        if path.exists():
            with np.load(path) as d:
                return Orbits(exp, d["t"], d["y"], float(d["seconds"]), int(d["steps"]),
                              cached=True)
        return _integrate(exp, path)


def _integrate(exp: Experiment, path: Path | None) -> Orbits:
    f, y0 = initial_states(exp)
    t = np.arange(exp.samples + 1) * exp.dt
    start = time.perf_counter()
    sol = dop853.integrate(f, y0, t, rtol=exp.rtol, atol=exp.rtol)
    seconds = time.perf_counter() - start
    if path is not None:
        fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=".npz", dir=path.parent)
        os.close(fd)
        try:
            np.savez(tmp, t=t, y=sol.y, seconds=seconds, steps=sol.steps)
            os.replace(tmp, path)
        finally:
            if os.path.exists(tmp):
                os.unlink(tmp)
    return Orbits(exp, t, sol.y, seconds, sol.steps)


def signals(orb: Orbits, member: int) -> list[np.ndarray]:
    r"""Complex observables of one orbit. Reduced: $x + iG/(a+b+2)$ ($= x + i\dot x$) and $E + i\delta$.
    Full / control ($n = 4$): the same two (computed from $k, u, q$), which see only the reduced
    frequencies, and $q_1 + iq_2$, $k_1 + ik_2$, $u_1 + iu_2$, which also see the $SO(3)$ motion.
    Other $n$, and the ``vertical`` family: $\gamma_j + i\gamma_{j+1}$ ($j < n-1$) and
    $M_{1,j} + iM_{1,j+1}$."""
    exp = orb.experiment
    y = orb.y[:, member]
    four = exp.model == "reduced" or (exp.n == 4 and exp.family != "vertical")
    if exp.model == "reduced":
        r = y
    elif four:
        M = so.unvec(y[:, :6], 4)
        g = y[:, 6:]
        r = reduced_invariants(M, g)
        k, u = so.split4(M)
    nu = exp.a + exp.b + 2
    if four:
        out = [r[:, 5] + 1j * r[:, 3] / nu, r[:, 2] + 1j * r[:, 6]]
        if exp.model != "reduced":
            out += [g[:, 0] + 1j * g[:, 1], k[:, 0] + 1j * k[:, 1], u[:, 0] + 1j * u[:, 1]]
        return out
    n, N = exp.n, so.so_dim(exp.n)
    M = so.unvec(y[:, :N], n)
    g = y[:, N:]
    return [g[:, j] + 1j * g[:, j + 1] for j in range(n - 2)] + \
           [M[:, 0, j] + 1j * M[:, 0, j + 1] for j in range(1, n - 1)]
