r"""Orbits for the numerical evidence of Section 5, integrated once and cached on disk.

An :class:`Experiment` names a vector field (the reduced field eq:red-system, the full field
eq:motion-general with the generated $L_\gamma^{-1}$, or the general-$\mathbb{J}$ control of
:mod:`simulate.analysis.control`), its parameters, the initial conditions (a family and seed of
:mod:`simulate.dynamics.families`, optionally moved along a level set of the reduced integrals), the
sampling and the DOP853 tolerance. :func:`orbits` returns the samples, from the cache when the
cache key matches, else by integrating (and then writing the cache atomically).

Cache (:mod:`simulate.analysis.result_cache`): an entry is found by the SHA-256 of the experiment (JSON)
and of the library versions, and trusted only if the source of every project module that was
loaded when it was computed (recorded in the entry, :func:`simulate.analysis.result_cache.code_manifest`)
is unchanged: an edited field (:mod:`simulate.dynamics.so`), kernel, integrator or analysis recomputes.
Entries are ``.npz`` read without pickle; a corrupt entry is recomputed, an unusable or shared
folder is reported and the run goes on uncached. Location: the ``evidence/`` subfolder of the
project's cache folder (:mod:`chaplygin_nd.cache`).
"""

from __future__ import annotations

import hashlib
import json
import os
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np
from chaplygin_nd.simulate.analysis import result_cache as rc
from chaplygin_nd.simulate.analysis.control import general_inertia_kernels
from chaplygin_nd.simulate.dynamics import families, so
from chaplygin_nd.simulate.dynamics.field import FullField, ReducedField
from chaplygin_nd.simulate.dynamics.so import reduced_invariants
from chaplygin_nd.simulate.integrators import dop853
from chaplygin_nd.simulate.kernels import active

from chaplygin_nd import cache as project_cache

__all__ = ["Experiment", "Orbits", "orbits", "cache_dir", "level_set_points", "signals"]



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
        """The settings key: SHA-256 of the experiment and the library versions (the code is
        checked apart, against the manifest stored in the entry)."""
        text = json.dumps({"experiment": asdict(self), "versions": rc.environment(heyoka=True)},
                          sort_keys=True)
        return hashlib.sha256(text.encode()).hexdigest()[:20]

    def shape(self) -> tuple[int, int, int]:
        """``(samples + 1, orbits, state dimension)`` of the sampled orbits."""
        count = len(self.members) + (len(self.level_shifts) if self.model == "reduced" else 0)
        dim = 7 if self.model == "reduced" else so.so_dim(self.n) + self.n
        return self.samples + 1, count, dim


@dataclass
class Orbits:
    """Samples ``y`` of shape ``(samples + 1, count, dim)`` at ``t``, with the integration cost;
    ``info["manifest"]``: the code that computed them (:func:`simulate.analysis.result_cache.code_manifest`)."""

    experiment: Experiment
    t: np.ndarray
    y: np.ndarray
    seconds: float
    steps: int
    cached: bool = False
    info: dict = field(default_factory=dict)


def cache_dir() -> Path:
    """The ``evidence/`` subfolder of the project's cache folder (:mod:`chaplygin_nd.cache`); not
    created here (:func:`simulate.analysis.result_cache.private_folder` creates and checks it)."""
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
    f: ReducedField | FullField
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
    """The sampled orbits of ``exp``: from the cache if an entry with its settings key was
    computed by the code loaded now, else integrated with DOP853 (one stacked system for the
    ensemble) and cached (:mod:`simulate.analysis.result_cache`)."""
    folder = rc.private_folder("evidence") if use_cache else None
    if folder is None:
        return _integrate(exp)
    path = folder / f"{exp.name}-{exp.key()}.npz"
    with rc.locked(path):  # one process integrates, the others wait
        if os.path.lexists(path):
            found = _load(path, exp)
            if found is not None:
                return found
        orb = _integrate(exp)
        rc.write_atomic(path, lambda tmp: np.savez(
            tmp, t=orb.t, y=orb.y, seconds=orb.seconds, steps=orb.steps,
            manifest=json.dumps(orb.info["manifest"], sort_keys=True)))
        return orb


def _load(path: Path, exp: Experiment) -> Orbits | None:
    """The cached orbits at ``path`` if they parse, have the experiment's shape and were computed
    by the code loaded now; None otherwise (after one warning if the entry is corrupt)."""
    try:
        with open(path, "rb") as fh, np.load(fh, allow_pickle=False) as d:
            t, y = d["t"], d["y"]
            seconds, steps = float(d["seconds"]), int(d["steps"])
            manifest = json.loads(str(d["manifest"]))
        expected_t = np.arange(exp.samples + 1) * exp.dt
        if (y.dtype != np.float64 or y.shape != exp.shape() or not np.array_equal(t, expected_t)
                or not np.all(np.isfinite(y))):
            raise ValueError(f"arrays of the wrong shape or type ({y.shape}, {y.dtype})")
    except Exception as exc:  # noqa: BLE001 - any unreadable entry is recomputed, never trusted
        rc.damaged(path, exc)
        return None
    if not rc.code_unchanged(manifest):
        return None  # computed by other code: a miss
    return Orbits(exp, t, y, seconds, steps, cached=True, info={"manifest": manifest})


def _integrate(exp: Experiment) -> Orbits:
    f, y0 = initial_states(exp)
    t = np.arange(exp.samples + 1) * exp.dt
    start = time.perf_counter()
    sol = dop853.integrate(f, y0, t, rtol=exp.rtol, atol=exp.rtol)
    seconds = time.perf_counter() - start
    return Orbits(exp, t, sol.y, seconds, sol.steps, info={"manifest": rc.code_manifest()})


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
