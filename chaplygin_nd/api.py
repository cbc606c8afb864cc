r"""A small public API for notebooks: decide a ledger row, run a scene, evaluate the kernels.

Everything here is re-exported from :mod:`chaplygin_nd` and imported only when first used
(``import chaplygin_nd`` stays light: no SymPy, no NumPy)::

    import chaplygin_nd as cn
    cn.decide("P:inversion").status                 # 'holds'
    run = cn.simulate("steady4d")                   # a built-in scene, a path or TOML text
    run.times, run.outputs["M"], run.plan.model
    cn.angular_velocity(M, gamma, a, b)             # Omega = L_gamma^{-1}(M), P:inversion

Nothing here writes a file: :func:`simulate` returns the arrays that ``chaplygin simulate``
would write, :func:`decide` returns the row that ``chaplygin prove`` would print. Each example
below is a doctest (``make test`` runs them) that checks an identity, not a printed number.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # pragma: no cover
    import numpy as np

    from chaplygin_nd.ledger.runner import Result
    from chaplygin_nd.simulate.scene.planner import Plan
    from chaplygin_nd.simulate.scene.run import Trajectory
    from chaplygin_nd.simulate.scene.spec import Scene

__all__ = ["decide", "simulate", "Simulation", "angular_velocity", "L_gamma", "vector_field",
           "energy", "zeta", "first_integrals"]


def decide(claim_id: str, *, seed: int | None = None) -> Result:
    r"""Decide the ledger row ``claim_id`` (e.g. ``"P:inversion"``, the paper's label) in this
    process, as ``chaplygin prove claim_id`` does, and return its
    :class:`~chaplygin_nd.ledger.runner.Result`: ``result.status`` (``holds``, ``corrected``, …),
    ``result.verdict`` (method, ``n_values``, the exact counterexample of a corrected row, kind),
    ``result.seconds``, ``result.uses``. ``seed`` is the seed of the seeded checks (default: the
    ledger's, :data:`chaplygin_nd.symbolic.exact.points.DEFAULT_SEED`). An unknown id raises
    ``KeyError`` naming the nearest ids, as ``chaplygin prove`` does. Domain: every row of
    ``chaplygin prove --list``.

    P:inversion, $\Omega = \tfrac12 M + K/(2\Delta)$ with the printed $K$, is decided by two
    parts (the derived inverse solves $L_\gamma(\Omega) = M$; the printed formula equals it),
    exactly for $n = 3, 4, 5$ and by a reduction argument for every $n \ge 4$:

    >>> import chaplygin_nd as cn
    >>> r = cn.decide("P:inversion")
    >>> r.status, r.error, [part.verdict for part in r.verdict.parts]
    ('holds', '', ['holds', 'holds'])
    >>> {3, 4, 5} <= set(r.verdict.n_values) and r.verdict.counterexample is None
    True
    """
    from chaplygin_nd.ledger.catalog import resolve
    from chaplygin_nd.ledger.runner import run, select
    from chaplygin_nd.symbolic.exact import points

    if not isinstance(claim_id, str):
        raise TypeError(f"claim_id must be one ledger id (a str), not {type(claim_id).__name__}")
    (result,) = run(select(resolve([claim_id])), jobs=1,
                    seed=points.DEFAULT_SEED if seed is None else seed)
    return result


@dataclass
class Simulation:
    """The result of :func:`simulate`: the validated scene, the plan (model, method and why),
    the sample times and one array per output (the keys of ``outputs.npz`` of
    ``chaplygin simulate``: ``"M"``, ``"gamma"``, ``"integrals.energy"``, ``"drift.energy"``, …;
    a leading ensemble axis after the time axis)."""

    scene: Scene
    plan: Plan
    times: np.ndarray
    outputs: dict[str, np.ndarray]
    trajectory: Trajectory = field(repr=False)

    def __repr__(self) -> str:
        """A few lines: the scene, the model and method, the times, the outputs with their
        shapes; the arrays themselves are in ``times`` and ``outputs`` (and :meth:`summary`)."""
        t = self.times
        span = f"{t[0]:g} .. {t[-1]:g} ({t.size} samples)" if t.size else "no samples"
        shown = ", ".join(f"{k} {tuple(v.shape)}" for k, v in list(self.outputs.items())[:6])
        more = f", … {len(self.outputs) - 6} more" if len(self.outputs) > 6 else ""
        title = f" {self.scene.title!r}" if getattr(self.scene, "title", "") else ""
        return (f"<Simulation{title}: n = {self.scene.n}, a = {self.scene.a:g}, b = {self.scene.b:g}\n"
                f"  model {self.plan.model} ({self.plan.detail or self.plan.method})\n"
                f"  t = {span}\n"
                f"  outputs: {shown}{more}>")

    def summary(self) -> str:
        """The one-screen summary ``chaplygin simulate`` prints (scene, model, cost, drift)."""
        from chaplygin_nd.simulate.scene.report import summary

        return summary(self.scene, self.plan, self.trajectory, self.outputs,
                       self.trajectory.seconds + self.trajectory.compile_seconds)


def _scene(scene: str | Path, force: bool) -> Scene:
    """The validated scene; a frequency map (``[fma]``) is refused with :class:`SceneError`:
    it is a sweep of many orbits drawn as a figure, run by ``chaplygin simulate``, not a
    trajectory with arrays."""
    from chaplygin_nd.simulate.scene.spec import Scene, SceneError, find, loads

    if isinstance(scene, str) and ("\n" in scene or "=" in scene) and not _is_file(scene):
        found = loads(scene, source="<TOML text>", force=force)
    else:
        found = find(str(scene), force=force)
    if not isinstance(found, Scene):
        raise SceneError(str(scene) if "\n" not in str(scene) else "<TOML text>", "fma",
                         "a frequency map has no single trajectory to return",
                         "run it with `chaplygin simulate` (it writes the map and its figure)")
    return found


def _is_file(text: str) -> bool:
    """True when ``text`` names an existing file (a path may contain ``=``: ``runs/a=1.toml``)."""
    try:
        return Path(text).is_file()
    except (OSError, ValueError):  # too long a name, or a NUL byte: TOML text
        return False


def simulate(scene: str | Path, *, force: bool = False, progress: bool = False) -> Simulation:
    r"""Plan and run ``scene`` as ``chaplygin simulate`` does, without writing a file: a
    built-in scene name (``"steady4d"``; ``chaplygin simulate --list``), the path of a scene file,
    or the TOML text of a scene (scenes/README.md). The model is the cheapest exact one the
    planner finds (closed forms of P:steady-rot, Th:Re, S5:H-linear-nD before integration of
    eq:motion-general). ``force`` lifts the time and memory limits; ``progress`` shows progress on
    stderr for long runs. A scene that cannot give a right answer raises
    :class:`~chaplygin_nd.simulate.scene.spec.SceneError` or
    :class:`~chaplygin_nd.simulate.integrators.stops.RunStopped` (nothing is returned).

    A steady rotation (P:steady-rot) keeps $\Omega$ constant and conserves the energy
    (S2.2:energy):

    >>> import numpy as np, chaplygin_nd as cn
    >>> run = cn.simulate("steady4d")
    >>> run.plan.model, run.times.shape == run.outputs["M"].shape[:1]
    ('constant-Omega', True)
    >>> bool(np.allclose(run.outputs["Omega"], run.outputs["Omega"][:1], atol=1e-12))
    True
    >>> float(np.max(np.abs(run.outputs["drift.energy"]))) < 1e-12
    True
    """
    import numpy as np

    from chaplygin_nd.simulate.integrators.stops import check_finite
    from chaplygin_nd.simulate.scene.outputs import collect
    from chaplygin_nd.simulate.scene.planner import plan
    from chaplygin_nd.simulate.scene.run import execute

    sc = _scene(scene, force)
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):  # checked below
        p = plan(sc)
        traj = execute(sc, p, progress=progress, force=force)
        arrays = collect(sc, traj)
        for key, v in arrays.items():
            check_finite(key, v, sc.t if key != "zeta" else sc.t[0])
    times = arrays.pop("t")
    return Simulation(sc, p, times, arrays, traj)


#: Relative tolerance of the domain checks on float input (the scenes' default tolerance).
TOLERANCE = 1e-10


def _checked(name: str, X: Any, gamma: Any, a: Any, b: Any, *, vertical: bool = False,
             sphere: bool = True):
    r"""``(X, gamma)`` as float arrays after the domain checks of the kernels below, or
    ``ValueError`` naming the argument and its domain: ``X`` (``M``, ``Omega`` or ``M0``)
    ``(..., n, n)``, $n \ge 3$, real, finite and skew-symmetric ($\mathfrak{so}(n)$, eq:M-O)
    within :data:`TOLERANCE` relative to $\max(1, \lVert X\rVert)$, ``gamma`` ``(..., n)`` real
    and finite, $a \ge -1$ (eq:axisymm:
    $\mathbb{J} = \mathrm{Id} + aE_nE_n^T$ is a mass tensor; the paper assumes $-1 \le a \le 1$,
    $a > 1$ is a prolate body and allowed), $b > 0$ ($b = mr^2$, eq:M-O); with ``vertical``,
    $X\gamma = 0$ (the set $\mathcal{V}$ of Th:Re); with ``sphere`` (all but :func:`L_gamma`),
    $\gamma \in S^{n-1}$: $|\lVert\gamma\rVert - 1| \le$ :data:`TOLERANCE` (off the sphere the
    kernels, which reduce modulo $\lVert\gamma\rVert^2 = 1$, return a wrong $\Omega$ silently:
    $\gamma = 2E_4$ gave $\Omega_{03} = -0.667$). These hypotheses give $\Delta(x) > 0$ and
    $2 + a + b > 0$ for $|x| \le 1$ (eq:Delta), so $L_\gamma$ is invertible."""
    import numpy as np

    for label, value in ((name, X), ("gamma", gamma), ("a", a), ("b", b)):
        if np.iscomplexobj(value):  # float() would drop the imaginary part without a word
            raise ValueError(f"{label} is complex: the domain is real (its imaginary part would be "
                             "dropped)")
    X, gamma = np.asarray(X, dtype=float), np.asarray(gamma, dtype=float)
    if X.ndim < 2 or X.shape[-1] != X.shape[-2] or X.shape[-1] < 3:
        raise ValueError(f"{name} has shape {X.shape}: the domain is (..., n, n) skew-symmetric "
                         "matrices with n >= 3 (so(n), eq:M-O)")
    if gamma.ndim < 1 or gamma.shape[-1] != X.shape[-1]:
        raise ValueError(f"gamma has shape {gamma.shape}: the domain is (..., n) vectors with "
                         f"n = {X.shape[-1]} (the size of {name})")
    for label, value in ((name, X), ("gamma", gamma)):
        if not np.all(np.isfinite(value)):
            raise ValueError(f"{label} has a non-finite entry (inf or nan): the domain is finite "
                             f"real {label}")
    scale = np.maximum(1.0, np.linalg.norm(X, axis=(-2, -1)))
    skew = np.linalg.norm(X + np.swapaxes(X, -1, -2), axis=(-2, -1)) / scale
    if not np.all(skew <= TOLERANCE):  # also catches nan
        raise ValueError(f"{name} is not skew-symmetric (max |{name} + {name}^T|/max(1, |{name}|)"
                         f" = {np.max(skew):.3g} > {TOLERANCE:g}): the domain is so(n), "
                         f"{name}^T = -{name} (eq:M-O)")
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    if not np.all(a >= -1.0) or not np.all(np.isfinite(a)):
        raise ValueError(f"a = {_first_bad(a, a >= -1.0)} is outside the domain: a finite a >= -1 "
                         "(eq:axisymm: J = Id + a E_n E_n^T must be positive semidefinite; the "
                         "paper assumes -1 <= a <= 1)")
    if not np.all(b > 0.0) or not np.all(np.isfinite(b)):
        raise ValueError(f"b = {_first_bad(b, b > 0.0)} is outside the domain: a finite b > 0 "
                         "(b = m r^2, eq:M-O)")
    if sphere:
        off = np.abs(np.linalg.norm(gamma, axis=-1) - 1.0)
        if not np.all(off <= TOLERANCE):
            raise ValueError(f"gamma is off the unit sphere (max | |gamma| - 1 | = {np.max(off):.3g} "
                             f"> {TOLERANCE:g}): the domain is gamma in S^(n-1), |gamma| = 1 "
                             "(normalise it: gamma / |gamma|)")
    if vertical:
        Xg = np.einsum("...ij,...j->...i", X, gamma)
        off = np.linalg.norm(Xg, axis=-1) / scale
        if not np.all(off <= TOLERANCE):
            raise ValueError(f"{name} gamma0 != 0 (max |{name} gamma0|/max(1, |{name}|) = "
                             f"{np.max(off):.3g}): the domain is the vertical set V, "
                             f"{name} gamma0 = 0 (Th:Re)")
    return X, gamma


def _first_bad(values, ok) -> str:
    """The first value of ``values`` that is not ``ok`` (or not finite), as text."""
    import numpy as np

    bad = values[~(ok & np.isfinite(values))] if values.ndim else values
    return f"{float(bad.flat[0]):g}"


def angular_velocity(M: Any, gamma: Any, a: Any, b: Any) -> np.ndarray:
    r"""$\Omega = L_\gamma^{-1}(M)$ (P:inversion, eq:M-O), ``(..., n, n)`` for skew ``M``
    ``(..., n, n)`` and ``gamma`` ``(..., n)``, any $n \ge 3$ (generated kernels). Domain:
    $\gamma \in S^{n-1}$, $a \ge -1$, $b > 0$ (then $\Delta(x) > 0$ and $2+a+b > 0$); a non-skew
    ``M``, $a < -1$ or $b \le 0$ raises ``ValueError`` naming the argument.

    It inverts :func:`L_gamma` (a 5-dimensional example, where no component kernel exists):

    >>> import numpy as np, chaplygin_nd as cn
    >>> rng = np.random.default_rng(1)
    >>> A = rng.normal(size=(5, 5)); M = A - A.T
    >>> gamma = rng.normal(size=5); gamma /= np.linalg.norm(gamma)
    >>> Omega = cn.angular_velocity(M, gamma, 0.7, 0.3)
    >>> bool(np.allclose(cn.L_gamma(Omega, gamma, 0.7, 0.3), M, rtol=1e-12, atol=1e-12))
    True
    """
    from chaplygin_nd.runtime import angular_velocity as kernel

    M, gamma = _checked("M", M, gamma, a, b)
    return kernel(M, gamma, a, b)


def L_gamma(Omega: Any, gamma: Any, a: Any, b: Any) -> np.ndarray:
    r"""$M = L_\gamma(\Omega) = \mathbb{J}\Omega + \Omega\mathbb{J} + b(\Omega\gamma)\wedge\gamma$,
    $\mathbb{J} = \mathrm{Id} + aE_nE_n^T$ (eq:M-O with eq:axisymm), ``(..., n, n)``; any
    $\gamma \in \mathbb{R}^n$, any $n$; ``Omega`` skew, $a \ge -1$, $b > 0$ (else ``ValueError``).

    For $n = 3$ it is the symmetric operator of eq:mom3D: $\langle L_\gamma\Omega_1,
    \Omega_2\rangle = \langle \Omega_1, L_\gamma\Omega_2\rangle$ (trace pairing):

    >>> import numpy as np, chaplygin_nd as cn
    >>> rng = np.random.default_rng(2)
    >>> A, B = rng.normal(size=(2, 3, 3)); O1, O2 = A - A.T, B - B.T
    >>> gamma = np.array([2.0, 1.0, 2.0]) / 3
    >>> lhs = np.trace(cn.L_gamma(O1, gamma, 0.4, 0.9) @ O2.T)
    >>> rhs = np.trace(O1 @ cn.L_gamma(O2, gamma, 0.4, 0.9).T)
    >>> bool(np.isclose(lhs, rhs, rtol=1e-13))
    True
    """
    from chaplygin_nd.runtime import L_gamma as kernel

    Omega, gamma = _checked("Omega", Omega, gamma, a, b, sphere=False)
    return kernel(Omega, gamma, a, b)


def vector_field(M: Any, gamma: Any, a: Any, b: Any) -> tuple[np.ndarray, np.ndarray]:
    r"""$(\dot M, \dot\gamma) = ([M, \Omega], -\Omega\gamma)$ with $\Omega = L_\gamma^{-1}M$
    (eq:motion-general); domain as :func:`angular_velocity`.

    The flow keeps $\gamma$ on the sphere and, in 4D, conserves the energy (S2.2:energy):
    $\langle\gamma, \dot\gamma\rangle = 0$ and $\frac{d}{dt}H = 0$ (a finite-difference check):

    >>> import numpy as np, chaplygin_nd as cn
    >>> rng = np.random.default_rng(3)
    >>> A = rng.normal(size=(4, 4)); M = A - A.T
    >>> gamma = rng.normal(size=4); gamma /= np.linalg.norm(gamma)
    >>> dM, dgamma = cn.vector_field(M, gamma, 0.5, 0.5)
    >>> bool(abs(gamma @ dgamma) < 1e-12)
    True
    >>> h = 1e-6
    >>> dH = (cn.energy(M + h * dM, gamma + h * dgamma, 0.5, 0.5)
    ...       - cn.energy(M - h * dM, gamma - h * dgamma, 0.5, 0.5)) / (2 * h)
    >>> bool(abs(dH) < 1e-7)
    True
    """
    from chaplygin_nd.runtime import vector_field as kernel

    M, gamma = _checked("M", M, gamma, a, b)
    return kernel(M, gamma, a, b)


def energy(M: Any, gamma: Any, a: Any, b: Any) -> np.ndarray:
    r"""$H = \tfrac12\langle M, \Omega\rangle_\kappa = \tfrac12\sum_{i<j} M_{ij}\Omega_{ij}$
    (S2.2:energy), ``(...)``; domain as :func:`angular_velocity`.

    $H$ is a positive quadratic form in $M$ (for $|a| < 1$, $b > 0$): $H(2M) = 4H(M) > 0$:

    >>> import numpy as np, chaplygin_nd as cn
    >>> rng = np.random.default_rng(4)
    >>> A = rng.normal(size=(6, 6)); M = A - A.T
    >>> gamma = rng.normal(size=6); gamma /= np.linalg.norm(gamma)
    >>> H = cn.energy(M, gamma, 0.2, 1.5)
    >>> bool(H > 0 and np.isclose(cn.energy(2 * M, gamma, 0.2, 1.5), 4 * H, rtol=1e-13))
    True
    """
    from chaplygin_nd.runtime import energy as kernel

    M, gamma = _checked("M", M, gamma, a, b)
    return kernel(M, gamma, a, b)


def zeta(M0: Any, gamma0: Any, a: Any, b: Any) -> np.ndarray:
    r"""$\zeta = \kappa(x_0)M_0 - L_{\gamma_0}^{-1}M_0 \in \mathfrak{so}(n-1)$ (Th:Re), the
    generator of the relative equilibrium through a vertical state; domain: $(M_0, \gamma_0) \in
    \mathcal{V}$ ($M_0\gamma_0 = 0$, $\gamma_0 \in S^{n-1}$), $a \ge -1$, $b > 0$ (else
    ``ValueError``).

    $\zeta$ lies in $\mathfrak{so}(n-1)$: its last row and column vanish ($\zeta E_n = 0$). A
    vertical state: $M_0 = u\wedge v$ with $u, v \perp \gamma_0$:

    >>> import numpy as np, chaplygin_nd as cn
    >>> gamma0 = np.array([0.48, 0.0, 0.6, 0.64])
    >>> u = np.array([0.6, 0.0, -0.48, 0.0]); v = np.array([0.0, 1.0, 0.0, 0.0])
    >>> M0 = np.outer(u, v) - np.outer(v, u)
    >>> bool(np.allclose(M0 @ gamma0, 0))
    True
    >>> Z = cn.zeta(M0, gamma0, 0.8, 0.5)
    >>> bool(np.allclose(Z[:, -1], 0, atol=1e-14) and np.allclose(Z, -Z.T, atol=1e-14))
    True
    """
    from chaplygin_nd.runtime import zeta as kernel

    M0, gamma0 = _checked("M0", M0, gamma0, a, b, vertical=True)
    return kernel(M0, gamma0, a, b)


def first_integrals(n: int, degree: int, a: Any = None, b: Any = None, *, J: Any = None,
                    d_gamma: int | None = None, k: int = 1, paper_only: bool = False,
                    space: str = "weight-zero") -> list:
    r"""The exact first-integral search of row S6:first-integrals for M-degrees ``1..degree``:
    integrals $P/D^k$ of eq:motion-general with $P$ of $\gamma$-degree $\le$ ``d_gamma``
    (default $d + 2k$) on the sphere, $D = \Delta$ (eq:Delta) for the axisymmetric sphere
    (``a``, ``b``; eq:axisymm) or $\det L_\gamma$ for a diagonal mass tensor ``J`` (eq:Inertia).
    Returns one :class:`~chaplygin_nd.symbolic.search.integral_search.DegreeResult` per degree:
    ``found`` (an upper bound of the dimension of the integrals), ``known`` (a lower bound: the
    algebra of the known integrals), ``settled`` when they agree — then *exactly* nothing beyond
    the known integrals lies in the box. Parameters are exact rationals (``"-1/3"``, ``0.5``);
    bad input raises ``ValueError`` naming the field. Domain: $n \ge 3$, $b > 0$, $a \ge -1$
    or ``J`` positive. ``space``: ``"weight-zero"`` (monomials of weight zero for a maximal torus
    of $SO(n-1)$) or ``"invariant"`` (the $SO(n-1)$-invariant polynomials, the integrals of the
    reduced system; $n = 4..7$ or a generic ``J``; symbolic/search/invariant_search.py).

    Chaplygin's sphere with a generic mass tensor: $\langle M, \gamma\rangle$ at degree 1, then
    $\|M\|^2$, $\langle M, \gamma\rangle^2$ and the energy at degree 2, and nothing else:

    >>> import chaplygin_nd as cn
    >>> rows = cn.first_integrals(3, 2, J=(1, "3/2", "7/3"), b="1/2")
    >>> [(r.d, r.found) for r in rows], all(r.settled and r.recovered for r in rows)
    ([(1, 1), (2, 3)], True)
    """
    from chaplygin_nd.symbolic.search import integral_search as fi
    from chaplygin_nd.symbolic.search.command import parse_model
    from chaplygin_nd.symbolic.search.strategies import make_search

    if not isinstance(degree, int) or degree < 1:
        raise ValueError(f"degree = {degree!r}: an integer >= 1")
    if not isinstance(k, int) or k < 0 or (d_gamma is not None and (not isinstance(d_gamma, int)
                                                                    or d_gamma < 0)):
        raise ValueError("k and d_gamma must be integers >= 0")
    Jtext = None if J is None else [str(j) for j in J]
    model = parse_model(n, None if a is None else str(a), None if b is None else str(b), Jtext)
    if space not in ("weight-zero", "invariant"):
        raise ValueError(f"space = {space!r}: 'weight-zero' or 'invariant'")
    search = make_search(model, space, include_new=not paper_only)
    return search.run([fi.box_for(d, k, d_gamma) for d in range(1, degree + 1)])
