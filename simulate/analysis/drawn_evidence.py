r"""Drawn ensembles of the evidence rows: integrate (heyoka batch mode, with the MEGNO tangent of
:mod:`simulate.analysis.chaos`), observe, count frequencies (:func:`simulate.analysis.naff.analyse_batch`), classify.

A :class:`Setting` names the system (the reduced field eq:red-system, the axisymmetric full field
eq:motion-general for any $n$, or the general-$\mathbb{J}$ control of :mod:`simulate.analysis.control`), the
orbit length, the sampling, the Taylor tolerance and the observables. :func:`measure` runs an
:class:`simulate.analysis.draws.Ensemble` through it and returns one :class:`OrbitResult` per orbit,
cached as JSON beside the evidence orbits (:func:`simulate.analysis.evidence.cache_dir`), keyed by
:meth:`simulate.analysis.evidence.Experiment.key` of the setting and draw and by the source of the modules
below (so a change of the analysis recomputes).

Classes of an orbit (rule fixed before looking; ``expected`` = the predicted number of independent
frequencies, ``REGULAR`` = $10^{-5}$ from :mod:`simulate.analysis.frequencies`):

* ``predicted``  — frequency diffusion $D <$ ``REGULAR`` and exactly ``expected`` frequencies;
* ``resonant``   — $D <$ ``REGULAR`` and fewer: the lines lie on a lower-rank lattice; the integer
  relation that made the strongest extra line dependent is named;
* ``excess``     — $D <$ ``REGULAR`` and more than ``expected`` (contradicts a torus of that dimension);
* ``unresolved`` — $D \ge$ ``REGULAR``: the lines moved between the two halves of the orbit.

Beside it, MEGNO's class (``regular`` / ``chaotic`` / ``undecided``, :mod:`simulate.analysis.chaos`).
Frequencies are reported in the units of energy scale 1 (time multiplied by the orbit's scale
$s$, :mod:`simulate.analysis.draws`): counts and diffusions do not depend on it.
"""

from __future__ import annotations

import hashlib
import json
import os
import tempfile
from dataclasses import asdict, dataclass, replace
from pathlib import Path

import numpy as np
from chaplygin_nd.simulate.analysis import chaos, draws, naff, result_cache
from chaplygin_nd.simulate.analysis.draws import Ensemble
from chaplygin_nd.simulate.analysis.frequencies import REGULAR
from chaplygin_nd.simulate.dynamics import so

__all__ = ["Setting", "OrbitResult", "measure", "classify", "summary", "schedule", "BATCH"]

#: orbits per compiled step of heyoka's batch mode (one compiled integrator per system). 8, not
#: heyoka's recommended SIMD width 4: measured per orbit (CPU, n = 5 / 7 tangent systems, one
#: batch of equal orbits) 0.087 / 0.136 s at 4, 0.050 / 0.084 s at 8, 0.047 / 0.085 s at 16. The
#: lanes are independent, so the width changes no orbit (bit-identical, tests/test_naff_projections.py).
BATCH = 8


@dataclass(frozen=True)
class Setting:
    """One experiment: ``system`` in ``reduced`` | ``full`` | ``control``; ``J`` for the control;
    ``observables`` in ``reduced`` | ``four`` | ``general`` | ``invariant``; ``T``, ``dt`` at energy
    scale 1; ``tol`` of the Taylor method; ``expected`` count (None: only measured)."""

    name: str
    system: str
    n: int
    T: float
    dt: float
    tol: float = 1e-10
    observables: str = "general"
    J: tuple[float, ...] = ()
    expected: int | None = None
    limit: int = 5
    #: the expected count is 0 at a = 0 (V: equilibria, Th:Re-tori)
    vertical: bool = False
    #: the first ``invariant`` signals are SO(n-1)-invariant: also counted on their own
    invariant: int = 0

    def expected_at(self, a: float) -> int | None:
        """The predicted count of an orbit with parameter ``a``."""
        return 0 if (self.vertical and a == 0) else self.expected

    def longer(self, factor: float) -> Setting:
        """The same setting with ``factor`` times the orbit length."""
        return replace(self, name=f"{self.name}-x{factor:g}", T=self.T * factor)


@dataclass
class OrbitResult:
    """The measurement of one drawn orbit."""

    a: float
    b: float
    scale: float
    count: int
    frequencies: list[float]
    diffusion: float
    megno: float
    lyapunov: float
    cls: str = ""
    megno_cls: str = ""
    relation: str = ""
    invariant_count: int = -1
    invariant_frequencies: list | None = None
    invariant_diffusion: float = float("nan")

    def to_dict(self) -> dict:
        return asdict(self)


def _system(s: Setting):
    from chaplygin_nd.simulate.analysis.control import general_system
    from chaplygin_nd.simulate.integrators import heyoka_systems as hs

    base = {"reduced": lambda: hs.reduced(), "full": lambda: hs.full(s.n),
            "control": lambda: general_system(s.J)}[s.system]()
    return chaos.tangent_system(base)


def observables(s: Setting, Y: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    r"""Complex signals ``(lanes, signals, samples)`` from states ``Y`` ``(samples, lanes, dim)``.
    ``reduced``: $x + iG/(a+b+2)$, $E + i\delta$ (see :func:`simulate.analysis.evidence.signals`); ``four``
    ($n = 4$ on $P$): those two from $(k, u, q)$ and $q_1 + iq_2$, $k_1 + ik_2$, $u_1 + iu_2$;
    ``general``: $\gamma_j + i\gamma_{j+1}$ ($j < n-1$), $M_{1j} + iM_{1,j+1}$; ``invariant+general``:
    first two $SO(n-1)$-invariant signals (they see only the reduced motion), $x + i(M\gamma)_n$ and
    $\|ME_n\|^2 + i\langle ME_n, M\gamma\rangle$, then the ``general`` ones."""
    nu = (a + b + 2)[None, :]
    if s.observables == "reduced":
        r = Y
        z = [r[..., 5] + 1j * r[..., 3] / nu, r[..., 2] + 1j * r[..., 6]]
    else:
        n, N = s.n, so.so_dim(s.n)
        M, g = so.unvec(Y[..., :N], n), Y[..., N:N + n]
        if s.observables == "four":
            from chaplygin_nd.simulate.dynamics.so import reduced_invariants

            r = reduced_invariants(M, g)
            k, u = so.split4(M)
            z = [r[..., 5] + 1j * r[..., 3] / nu, r[..., 2] + 1j * r[..., 6],
                 g[..., 0] + 1j * g[..., 1], k[..., 0] + 1j * k[..., 1], u[..., 0] + 1j * u[..., 1]]
        else:
            z = []
            if s.observables == "invariant+general":
                Mg = np.einsum("...ij,...j->...i", M, g)
                Me = M[..., :, n - 1]
                z = [g[..., n - 1] + 1j * Mg[..., n - 1],
                     np.sum(Me * Me, -1) + 1j * np.sum(Me * Mg, -1)]
            z += [g[..., j] + 1j * g[..., j + 1] for j in range(n - 2)]
            z += [M[..., 0, j] + 1j * M[..., 0, j + 1] for j in range(1, n - 1)]
    return np.moveaxis(np.array(z), (0, 1, 2), (1, 2, 0))


def schedule(ens: Ensemble) -> np.ndarray:
    r"""The order in which the orbits of ``ens`` fill heyoka's batches: sorted by $(a, b, s)$.

    A batch runs until its slowest lane is done, and the number of Taylor steps of an orbit
    depends mostly on $a$ (measured on the $n = 5$ draw: about 8000 at $a = -0.9$, 3000 at $a = 2$),
    while the draws cycle $a$ with period 4: in draw order every batch held orbits of every $a$
    and waited for the slowest (with 4 lanes: 1.4x the steps of the sorted order). Each lane is
    integrated independently (its own step sizes), so the order changes no orbit: the results are
    bit-identical (tests/test_drawn_evidence.py) and are returned in draw order."""
    return np.lexsort((ens.scale, ens.b, ens.a))


def _integrate(s: Setting, ens: Ensemble, y0: np.ndarray, seed: int):
    """Signals ``(count, signals, samples)``, MEGNO and Lyapunov estimates per orbit (draw order)."""
    from chaplygin_nd.simulate.integrators.heyoka_taylor import compiled_integrator

    system = _system(s)
    ta, _, _ = compiled_integrator(system, "double", s.tol, compact=True, batch=BATCH)
    d = y0.shape[1]
    u0 = chaos.initial_tangents(len(y0), d, seed)
    order = schedule(ens)
    ens, y0, u0 = subset(ens, order), y0[order], u0[order]
    t = np.arange(int(round(s.T / s.dt)) + 1) * s.dt
    sig, megno, lyap = None, np.empty(len(y0)), np.empty(len(y0))
    for start in range(0, len(y0), BATCH):
        sl = slice(start, min(start + BATCH, len(y0)))
        used = sl.stop - sl.start
        where = order[sl]                                     # their places in draw order

        def pad(x, used=used):
            return np.concatenate([x, np.repeat(x[-1:], BATCH - used, 0)])

        state = np.concatenate([y0[sl], u0[sl], np.zeros((used, 2))], axis=1)
        factor = pad(ens.time_factor[sl])
        ta.state[:] = pad(state).T
        ta.pars[:] = np.stack([pad(ens.a[sl]), pad(ens.b[sl])])
        ta.set_time(0.0)
        grid = t[:, None] * factor[None, :]
        _, states = ta.propagate_grid(grid)
        for lane, res in enumerate(ta.propagate_res[:used]):
            if str(res[0]) != "taylor_outcome.time_limit":
                raise RuntimeError(f"{s.name}: heyoka stopped early ({res[0]}) on orbit {where[lane]}")
        states = states[:, :, :used]
        Y = np.moveaxis(states[:, :d, :], 1, 2)              # (samples, lanes, dim)
        z = observables(s, Y, ens.a[sl], ens.b[sl])
        if sig is None:
            sig = np.empty((len(y0),) + z.shape[1:], dtype=z.dtype)
        sig[where] = z
        megno[where] = chaos.megno_from_samples(grid[:, :used], states[:, -1, :])
        lyap[where] = states[-1, -2, :] / grid[-1, :used]
    return sig, megno, lyap


def _relation(spec: naff.Spectrum) -> str:
    """The integer relation that made the strongest line outside the basis dependent."""
    basis = spec.frequencies
    if not basis:
        return ""
    scale = max((abs(w) for w, _ in spec.lines), default=1.0)
    tol = spec.tolerance * scale
    for w, _ in spec.lines:
        f = abs(w)
        if f <= tol or min(abs(f - x) for x in basis) <= tol:
            continue
        rel = naff._relation(f, basis, tol, 4)
        if rel is not None:
            rhs = " + ".join(f"{c}*w{i + 1}" for i, c in enumerate(rel[1:]) if c)
            return f"{rel[0]}*{f:.8g} = {rhs or '0'} (w = {', '.join(f'{x:.8g}' for x in basis)})"
    return ""


def classify(spec: naff.Spectrum, expected: int | None) -> str:
    """``predicted`` / ``resonant`` / ``excess`` / ``unresolved`` (module docstring); with
    ``expected`` None: ``regular`` or ``unresolved``."""
    if not spec.diffusion < REGULAR:
        return "unresolved"
    if expected is None:
        return "regular"
    if spec.count == expected:
        return "predicted"
    return "resonant" if spec.count < expected else "excess"


def _key(s: Setting, ens: Ensemble, y0: np.ndarray, seed: int) -> str:
    from chaplygin_nd.simulate.analysis import evidence

    exp = evidence.Experiment(f"drawn-{s.name}", s.system, s.n, 0.0, 0.0, ens.family, int(seed),
                              (ens.count,), s.dt, int(round(s.T / s.dt)), s.tol, J=tuple(s.J))
    h = hashlib.sha256(exp.key().encode())
    h.update(json.dumps({"setting": asdict(s), "draw": ens.describe()}, sort_keys=True).encode())
    h.update(np.ascontiguousarray(y0).tobytes())
    here = Path(__file__).resolve().parent.parent  # simulate/
    for name in ("analysis/drawn_evidence.py", "analysis/chaos.py", "analysis/draws.py",
                 "analysis/naff.py", "analysis/control.py", "integrators/heyoka_systems.py",
                 "integrators/heyoka_taylor.py", "dynamics/so.py"):
        h.update((here / name).read_bytes())
    for name in ("runtime/expressions.py", "generated/expression_builders.py"):
        h.update((here.parent / name).read_bytes())
    return h.hexdigest()[:20]


def measure(s: Setting, ens: Ensemble, y0: np.ndarray, seed: int,
            use_cache: bool = True) -> list[OrbitResult]:
    """Every orbit of ``ens`` (initial states ``y0`` ``(count, dim)``) through setting ``s``:
    MEGNO, Lyapunov estimate, NAFF count, diffusion, class. Cached (module docstring)."""
    import fcntl

    from chaplygin_nd.simulate.analysis import evidence

    path = evidence.cache_dir() / f"drawn-{s.name}-{_key(s, ens, y0, seed)}.json"
    if not use_cache:
        return _measure(s, ens, y0, seed)
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path.with_suffix(".lock"), "w") as lock:   # one process computes, the others wait
        fcntl.flock(lock, fcntl.LOCK_EX)
        if path.exists():
            found = result_cache.read_entry(
                path, lambda text: [OrbitResult(**d) for d in json.loads(text)])
            if found is not None:
                return found
        out = _measure(s, ens, y0, seed)
        fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", dir=path.parent)
        with os.fdopen(fd, "w") as fh:
            json.dump([r.to_dict() for r in out], fh)
        os.replace(tmp, path)
    return out


def _limited(spec: naff.Spectrum, limit: int) -> naff.Spectrum:
    """Recount with the integer-relation search allowed to reach ``limit + 1``."""
    if spec.count < limit or not spec.lines:
        return spec
    scale = max(abs(w) for w, _ in spec.lines)
    basis = naff.independent_frequencies([w for w, _ in spec.lines], spec.tolerance * scale, 4,
                                         limit=limit + 1)
    return naff.Spectrum(spec.lines, sorted(abs(f) for f in basis), spec.diffusion, spec.tolerance)


def _measure(s: Setting, ens: Ensemble, y0: np.ndarray, seed: int) -> list[OrbitResult]:
    Z, megno, lyap = _integrate(s, ens, y0, seed)
    specs, inv = [], []
    for start in range(0, len(Z), 32):                       # bounded memory
        whole, first, second = naff.lines_batch(Z[start:start + 32], s.dt)
        for w, f, h in zip(whole, first, second):
            specs.append(naff.spectrum_from_lines(w, f, h))
            if s.invariant:   # the same lines, only those of the invariant signals
                k = s.invariant
                inv.append(naff.spectrum_from_lines(w[:k], f[:k], h[:k]))
    out = []
    for k, spec in enumerate(specs):
        spec = _limited(spec, s.limit)
        cls = classify(spec, s.expected_at(float(ens.a[k])))
        r = OrbitResult(float(ens.a[k]), float(ens.b[k]), float(ens.scale[k]), spec.count,
                        [float(f) for f in spec.frequencies], float(spec.diffusion),
                        float(megno[k]), float(lyap[k]), cls, chaos.megno_class(megno[k]),
                        _relation(spec) if cls == "resonant" else "")
        if s.invariant:
            r.invariant_count = inv[k].count
            r.invariant_frequencies = [float(f) for f in inv[k].frequencies]
            r.invariant_diffusion = float(inv[k].diffusion)
        out.append(r)
    return out


def subset(ens: Ensemble, index) -> Ensemble:
    """The orbits ``index`` of ``ens`` (e.g. the unresolved ones, for a longer run)."""
    index = np.asarray(index, int)
    return replace(ens, a=ens.a[index], b=ens.b[index], scale=ens.scale[index],
                   M0=ens.M0[index], gamma0=ens.gamma0[index],
                   label=f"{ens.label}[{','.join(map(str, index))}]")


def summary(results: list[OrbitResult]) -> dict:
    """Counts of every class and MEGNO class, and the extremes of D and MEGNO."""
    out: dict = {"orbits": len(results)}
    for key in ("cls", "megno_cls"):
        tally: dict = {}
        for r in results:
            tally[getattr(r, key)] = tally.get(getattr(r, key), 0) + 1
        out[key] = dict(sorted(tally.items()))
    ds = [r.diffusion for r in results]
    ys = [r.megno for r in results]
    out["diffusion_median"] = float(np.median(ds)) if ds else float("nan")
    out["megno_median"] = float(np.median(ys)) if ys else float("nan")
    out["megno_max"] = float(np.max(ys)) if ys else float("nan")
    out["megno_min"] = float(np.min(ys)) if ys else float("nan")
    out["counts"] = dict(sorted({c: sum(r.count == c for r in results)
                                 for c in {r.count for r in results}}.items()))
    return out


__all__ += ["observables", "subset", "draws"]
