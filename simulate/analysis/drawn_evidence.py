r"""Drawn ensembles of the evidence rows: integrate (heyoka batch mode, with the MEGNO tangent of
:mod:`simulate.analysis.chaos`), observe, count frequencies (:func:`simulate.analysis.naff.analyse_batch`), classify.

A :class:`Setting` names the system (the reduced field eq:red-system, the axisymmetric full field
eq:motion-general for any $n$, or the general-$\mathbb{J}$ control of :mod:`simulate.analysis.control`), the
orbit length, the sampling, the Taylor tolerance and the observables. :func:`measure` runs an
:class:`simulate.analysis.draws.Ensemble` through it and returns one :class:`OrbitResult` per orbit,
cached as JSON beside the evidence orbits by the one mechanism of
:func:`simulate.analysis.result_cache.cached_json`: keyed by the setting, the draw and the initial
states, and trusted only while every project module loaded by the computation keeps its source.

Classes of an orbit (rule fixed before looking; ``expected`` = the predicted number of independent
frequencies, ``REGULAR`` = $10^{-5}$ from :mod:`simulate.analysis.frequencies`):

* ``predicted``  — frequency diffusion $D <$ ``REGULAR`` and exactly ``expected`` frequencies;
* ``resonant``   — $D <$ ``REGULAR`` and fewer: the lines lie on a lower-rank lattice; the integer
  relation that made the strongest extra line dependent is named;
* ``excess``     — $D <$ ``REGULAR`` and more than ``expected`` even when integer combinations up to
  $|c| \le 12$ explain lines (:func:`simulate.analysis.combinations.recount`, with the chance of a
  false match): a line no combination explains (contradicts a torus of that dimension);
* ``unresolved`` — $D \ge$ ``REGULAR``: the lines moved between the two halves of the orbit; or a
  line whose only explanation is a combination that is not credible (``ambiguous``).

Beside it, MEGNO's class over the horizon ladder (``regular`` / ``chaotic`` / ``undecided``,
:func:`simulate.analysis.chaos.ladder_class`; ``megno`` is $\langle Y\rangle(T)$, ``ladder`` the values at
$T/8, T/4, T/2, T$), the growth of the tangent vector over the last doubling (``power``: $p$ of $t^p$,
$(\ell(T) - \ell(T/2))/\ln 2$), and how well the proved integrals are kept (``drift``,
:mod:`simulate.analysis.kept`). On $\mathcal V$ (``tangent = "V"``) the tangent vector starts in the
tangent space of $\mathcal V$ (:func:`v_tangents`), which the flow preserves.
Frequencies are reported in the units of energy scale 1 (time multiplied by the orbit's scale
$s$, :mod:`simulate.analysis.draws`): counts and diffusions do not depend on it.
"""

from __future__ import annotations

import hashlib
from dataclasses import asdict, dataclass, field, replace
from typing import Any

import numpy as np
from chaplygin_nd.simulate.analysis import chaos, combinations, draws, kept, naff, packing
from chaplygin_nd.simulate.analysis import result_cache as rc
from chaplygin_nd.simulate.analysis.draws import Ensemble
from chaplygin_nd.simulate.analysis.frequencies import REGULAR
from chaplygin_nd.simulate.dynamics import so

__all__ = ["Setting", "OrbitResult", "measure", "classify", "summary", "schedule", "BATCH", "TOL",
           "analyse"]

#: orbits per compiled step of heyoka's batch mode (one compiled integrator per system). 8, not
#: heyoka's recommended SIMD width 4: measured per orbit (CPU, n = 5 / 7 tangent systems, one
#: batch of equal orbits) 0.087 / 0.136 s at 4, 0.050 / 0.084 s at 8, 0.047 / 0.085 s at 16. The
#: lanes are independent, so the width changes no orbit (bit-identical, tests/test_naff_projections.py).
BATCH = 8
#: LLVM's optimisation level of the compiled integrators: 1 compiles faster than heyoka's default 3
#: and gives bit-identical orbits at the same speed in compact mode
#: (:func:`simulate.integrators.heyoka_taylor.compiled_integrator`)
OPT_LEVEL = 1
#: heyoka's tolerance of the drawn runs (the MEGNO runs and their frequency-only continuations,
#: :meth:`Setting.longer`). heyoka sets the Taylor order from it alone (the step size
#: follows from the order and the series' radius of convergence): 1e-9 runs at order 12, 1e-10 at 13.
#: Measured side by side (bench/bench_tangent_tol.py, 16 orbits of each setting of the rows): the
#: same steps (within 3 %), 0.86-0.90x the CPU per orbit (0.87x over the rows' orbits), the state at
#: T within 6.8e-8 of a 1e-13 reference on the regular orbits (1e-10: 2.2e-8; before the tangent's
#: l and m were scaled, 5.9e-8 at n = 5), every MEGNO and frequency class as at 1e-10; 3e-10 gives
#: the orbits of 1e-9 (the same order, steps and errors). The validation study (bench/bench_evidence.py)
#: at 1e-9 keeps every count of its confusion tables (false alarms 0 of 456, misses 0 of 200,
#: undecided 3 of 456, mixed controls 60 of 64 chaotic); the drift of the integrals of its
#: integrable orbits rose from <= 1.1e-9 to <= 6.2e-9 (docs/pages/evidence-study.md).
TOL = 1e-9


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
    tol: float = TOL
    observables: str = "general"
    J: tuple[float, ...] = ()
    expected: int | None = None
    limit: int = 5
    #: the expected count is 0 at a = 0 (V: equilibria, Th:Re-tori)
    vertical: bool = False
    #: the first ``invariant`` signals are SO(n-1)-invariant: also counted on their own
    invariant: int = 0
    #: ``full``: the MEGNO tangent starts anywhere; ``V``: in the tangent space of V = {M gamma = 0};
    #: ``none``: no tangent (frequencies only: the re-runs of the horizon ladder)
    tangent: str = "full"
    #: the field's parameter values override (a, b) of the draw when given (the study's Manakov top: b = 0)
    b_override: float | None = None

    def expected_at(self, a: float) -> int | None:
        """The predicted count of an orbit with parameter ``a``."""
        return 0 if (self.vertical and a == 0) else self.expected

    def longer(self, factor: float, tangent: str | None = None) -> Setting:
        """The same setting with ``factor`` times the orbit length (and another ``tangent``); from
        ``factor`` 4 on, sampled ``factor / 2`` times more sparsely (at most twice the samples of
        ``T``: NAFF's cost grows with them; at dt = 1/2 the Nyquist frequency of 4T is pi, the
        lines of the rows lie below 1)."""
        return replace(self, name=f"{self.name}-x{factor:g}", T=self.T * factor,
                       dt=self.dt * max(1.0, factor / 2),
                       tangent=self.tangent if tangent is None else tangent)


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
    ladder: list = field(default_factory=list)
    power: float = float("nan")
    drift: float = float("nan")
    drift_of: str = ""
    large: int = 0
    ambiguous: int = 0
    p_false: float = 0.0
    #: the horizon (in units of T) whose frequency analysis this record holds (the ladder's re-runs)
    horizon: float = 1.0

    def to_dict(self) -> dict:
        return asdict(self)


def _system(s: Setting):
    from chaplygin_nd.simulate.analysis.control import general_system
    from chaplygin_nd.simulate.integrators import heyoka_systems as hs

    base = {"reduced": lambda: hs.reduced(), "full": lambda: hs.full(s.n),
            "control": lambda: general_system(s.J)}[s.system]()
    return base if s.tangent == "none" else chaos.tangent_system(base)


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
    r"""The orbits of ``ens`` sorted by $(a, b, s)$: the order of the pilot's batches and of ties in
    the packed order of the run (:func:`simulate.analysis.packing.order`).

    A batch runs until its slowest lane is done, and the number of Taylor steps of an orbit
    depends mostly on $a$ (measured on the $n = 5$ draw: about 8000 at $a = -0.9$, 3000 at $a = 2$),
    while the draws cycle $a$ with period 4: in draw order every batch held orbits of every $a$
    and waited for the slowest (with 4 lanes: 1.4x the steps of the sorted order). Each lane is
    integrated independently (its own step sizes), so the order changes no orbit: the results are
    bit-identical (tests/test_naff_projections.py) and are returned in draw order."""
    return np.lexsort((ens.scale, ens.b, ens.a))


def _integrate(s: Setting, ens: Ensemble, y0: np.ndarray, seed: int, first: int = 0,
               anchor: np.ndarray | None = None):
    """Signals ``(count, signals, samples)``, MEGNO and Lyapunov estimates per orbit (draw order),
    and in ``extra`` the ladder, the tangent's growth, the drift of the integrals and ``final``:
    each orbit's state at the last sample, ``steps``: its Taylor steps (batches packed by
    :func:`simulate.analysis.packing.order`). ``first``: the index of the first sample (1: the
    samples dt, 2 dt, ..., T of a continuation from ``y0``, whose time is taken as 0 — the
    fields are autonomous); ``anchor``: the states the integrals' drift is measured from (default
    ``y0``; a continuation passes the orbits' initial states)."""
    from chaplygin_nd.simulate.integrators.heyoka_taylor import compiled_integrator

    system = _system(s)
    ta, _, _ = compiled_integrator(system, "double", s.tol, compact=True, batch=BATCH,
                                   opt_level=OPT_LEVEL)
    d = y0.shape[1]
    u0 = chaos.initial_tangents(len(y0), d, seed)
    if s.tangent == "V":
        u0 = v_tangents(u0, y0, s.n)
    full = y0 if s.tangent == "none" else np.concatenate([y0, u0, np.zeros((len(y0), 2))], axis=1)
    b_all = ens.b if s.b_override is None else np.full(len(y0), float(s.b_override))
    order = packing.order(ta, full, np.stack([ens.a, b_all]), s.T * ens.time_factor,
                          first=schedule(ens))
    ens, y0, full = subset(ens, order), y0[order], full[order]
    anchor = y0 if anchor is None else anchor[order]
    t = np.arange(int(round(s.T / s.dt)) + 1) * s.dt     # heyoka's grid starts at the start
    sig, megno, lyap = None, np.empty(len(y0)), np.empty(len(y0))
    final = np.empty_like(y0)
    ladder, power = np.empty((len(y0), len(chaos.LADDER))), np.empty(len(y0))
    drift, drift_of = np.empty(len(y0)), [""] * len(y0)
    steps = np.empty(len(y0), dtype=np.int64)
    stride = max(1, (len(t) - 1) // 1024)                 # the integrals at <= 1025 samples
    if first and s.tangent != "none":
        raise ValueError("a continuation carries no tangent vector (MEGNO is that of the first run)")
    for start in range(0, len(y0), BATCH):
        sl = slice(start, min(start + BATCH, len(y0)))
        used = sl.stop - sl.start
        where = order[sl]                                     # their places in draw order

        def pad(x, used=used):
            return np.concatenate([x, np.repeat(x[-1:], BATCH - used, 0)])

        factor = pad(ens.time_factor[sl])
        ta.state[:] = pad(full[sl]).T
        b_lane = ens.b[sl] if s.b_override is None else np.full(used, float(s.b_override))
        ta.pars[:] = np.stack([pad(ens.a[sl]), pad(b_lane)])
        ta.set_time(0.0)
        grid = t[:, None] * factor[None, :]
        _, states = ta.propagate_grid(grid)
        for lane, res in enumerate(ta.propagate_res[:used]):
            if str(res[0]) != "taylor_outcome.time_limit":
                raise RuntimeError(f"{s.name}: heyoka stopped early ({res[0]}) on orbit {where[lane]}")
            steps[where[lane]] = int(res[3])
        states = states[first:, :, :used]                    # a continuation drops its start
        Y = np.moveaxis(states[:, :d, :], 1, 2)              # (samples, lanes, dim)
        final[where] = Y[-1]
        z = observables(s, Y, ens.a[sl], ens.b[sl])
        if sig is None:
            sig = np.empty((len(y0),) + z.shape[1:], dtype=z.dtype)
        sig[where] = z
        if s.tangent == "none":                       # a frequency-only run (the ladder's re-runs)
            megno[where], lyap[where], ladder[where], power[where] = np.nan, np.nan, np.nan, np.nan
        else:
            ell, m = chaos.unscaled(states)
            megno[where] = chaos.megno_from_samples(grid[:, :used], m)
            lyap[where] = ell[-1] / grid[-1, :used]
            ladder[where] = chaos.megno_ladder(grid[:, :used], m).T
            half = (len(t) - 1) // 2
            power[where] = (ell[-1] - ell[half]) / np.log(2.0)
        kept_at = Y[::stride] if not first else np.concatenate([anchor[None, sl], Y[::stride]])
        dr, names = kept.drift(s.system, kept_at, ens.a[sl], b_lane, ens.scale[sl], s.n, s.J)
        drift[where] = dr
        for w, name in zip(where, names):
            drift_of[w] = name
    return sig, megno, lyap, {"ladder": ladder, "power": power, "drift": drift,
                              "drift_of": drift_of, "final": final, "steps": steps}


def v_tangents(u0: np.ndarray, y0: np.ndarray, n: int) -> np.ndarray:
    r"""Unit tangent vectors of $\mathcal V = \{M\gamma = 0\}$ (eq:def-H-V) at the states ``y0``, made from
    the drawn ``u0``: with $\Pi = \mathrm{Id} - \gamma\gamma^T$, $\delta\gamma = \Pi u_\gamma$, $v = -M\delta\gamma$
    ($\perp \gamma$ since $M\gamma = 0$) and $\delta M = \Pi X\Pi + v\gamma^T - \gamma v^T$ ($X$ = the drawn skew
    part): then $\delta M\gamma + M\delta\gamma = 0$ and $\langle\gamma, \delta\gamma\rangle = 0$, the linearised
    constraints. The flow preserves $\mathcal V$, so its tangent flow preserves these vectors' space.
    Domain: ``y0`` on $\mathcal V$ (full state, :func:`simulate.dynamics.so.vec` layout)."""
    N = so.so_dim(n)
    M, g = so.unvec(y0[:, :N], n), y0[:, N:N + n]
    X, ug = so.unvec(u0[:, :N], n), u0[:, N:N + n]
    P = np.eye(n)[None] - g[:, :, None] * g[:, None, :]
    dg = np.einsum("kij,kj->ki", P, ug)
    v = -np.einsum("kij,kj->ki", M, dg)
    dM = P @ X @ P + v[:, :, None] * g[:, None, :] - g[:, :, None] * v[:, None, :]
    u = np.concatenate([so.vec(dM), dg], axis=1)
    return u / np.linalg.norm(u, axis=1, keepdims=True)


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


def classify(spec: naff.Spectrum, expected: int | None, ambiguous: int = 0) -> str:
    """``predicted`` / ``resonant`` / ``excess`` / ``unresolved`` (module docstring); with
    ``expected`` None: ``regular`` or ``unresolved``. ``ambiguous``: lines whose only explanation
    is not credible (:func:`simulate.analysis.combinations.recount`): unresolved unless excess."""
    if not spec.diffusion < REGULAR:
        return "unresolved"
    if expected is None:
        return "regular"
    if spec.count > expected:
        return "excess"
    if ambiguous:
        return "unresolved"
    if spec.count == expected:
        return "predicted"
    return "resonant"


def settings(s: Setting, ens: Ensemble, y0: np.ndarray, seed: int) -> dict:
    """What a measurement depends on besides the code: the setting, the draw, the initial states
    (their SHA-256) and the seed of the tangent vectors (the cache's settings key)."""
    return {"kind": "drawn", "setting": asdict(s), "draw": ens.describe(), "seed": int(seed),
            "y0": hashlib.sha256(np.ascontiguousarray(y0, dtype=float).tobytes()).hexdigest()}


def _decode(stored) -> list[OrbitResult]:
    if not isinstance(stored, list) or not all(isinstance(d, dict) for d in stored):
        raise TypeError("not a list of orbit records")
    return [OrbitResult(**d) for d in stored]


def measure(s: Setting, ens: Ensemble, y0: np.ndarray, seed: int,
            use_cache: bool = True, on_signals=None) -> list[OrbitResult]:
    """Every orbit of ``ens`` (initial states ``y0`` ``(count, dim)``) through setting ``s``:
    MEGNO over the horizon ladder, Lyapunov estimate, the drift of the integrals, NAFF count,
    diffusion, class. Cached (:func:`simulate.analysis.result_cache.cached_json`; a damaged entry
    is recomputed, one warning line). ``on_signals(Z, final)``: called with the signals and end
    states when they are computed (not when read from the cache): the frequency ladder keeps them
    for its continuations (:mod:`simulate.analysis.continuation`)."""
    out, _ = rc.cached_json(
        "evidence", f"drawn-{s.name}", settings(s, ens, y0, seed),
        lambda: _measure(s, ens, y0, seed, on_signals),
        encode=lambda res: [r.to_dict() for r in res], decode=_decode,
        use_cache=use_cache, heyoka=True)
    if len(out) != len(y0):
        raise RuntimeError(f"{s.name}: {len(out)} results for {len(y0)} orbits")
    return out


def _limited(spec: naff.Spectrum, limit: int) -> naff.Spectrum:
    """Recount with the integer-relation search allowed to reach ``limit + 1``."""
    if spec.count < limit or not spec.lines:
        return spec
    scale = max(abs(w) for w, _ in spec.lines)
    basis = naff.independent_frequencies([w for w, _ in spec.lines], spec.tolerance * scale, 4,
                                         limit=limit + 1)
    return naff.Spectrum(spec.lines, sorted(abs(f) for f in basis), spec.diffusion, spec.tolerance)


def _measure(s: Setting, ens: Ensemble, y0: np.ndarray, seed: int,
             on_signals=None) -> list[OrbitResult]:
    Z, megno, lyap, extra = _integrate(s, ens, y0, seed)
    if on_signals is not None:
        on_signals(Z, extra["final"])
    return analyse(s, ens, Z, megno, lyap, extra)


def analyse(s: Setting, ens: Ensemble, Z: np.ndarray, megno, lyap, extra) -> list[OrbitResult]:
    """The records of the orbits of ``ens`` from their signals ``Z`` ``(count, signals, samples)``
    sampled at ``s.dt`` over ``s.T``, and the chaos indicators and drift of :func:`_integrate`:
    NAFF, the integer-relation counts and the class of the module docstring."""
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
        expected = s.expected_at(float(ens.a[k]))
        info: dict[str, Any] = {"large": 0, "ambiguous": 0, "p_false": 0.0, "relations": []}
        if expected is not None and spec.diffusion < REGULAR and spec.count > expected:
            # lines beyond the |c| <= 4 lattice: search combinations up to |c| <= 12
            scale = max(abs(w) for w, _ in spec.lines)
            basis, info = combinations.recount(spec.lines, spec.tolerance * scale, s.limit + 1,
                                               resolution=2 * np.pi / s.T)
            spec = naff.Spectrum(spec.lines, sorted(basis), spec.diffusion, spec.tolerance)
        cls = classify(spec, expected, info["ambiguous"])
        relation = _relation(spec) if cls == "resonant" else "; ".join(info["relations"])
        r = OrbitResult(float(ens.a[k]), float(ens.b[k]), float(ens.scale[k]), spec.count,
                        [float(f) for f in spec.frequencies], float(spec.diffusion),
                        float(megno[k]), float(lyap[k]), cls,
                        chaos.ladder_class(extra["ladder"][k]), relation,
                        ladder=[float(v) for v in extra["ladder"][k]],
                        power=float(extra["power"][k]), drift=float(extra["drift"][k]),
                        drift_of=extra["drift_of"][k], large=int(info["large"]),
                        ambiguous=int(info["ambiguous"]), p_false=float(info["p_false"]))
        if s.invariant:
            r.invariant_count = inv[k].count
            r.invariant_frequencies = [float(f) for f in inv[k].frequencies]
            r.invariant_diffusion = float(inv[k].diffusion)
        out.append(r)
    return out


FREQUENCY_FIELDS = ("count", "frequencies", "diffusion", "cls", "relation", "invariant_count",
                    "invariant_frequencies", "invariant_diffusion", "large", "ambiguous", "p_false")


def merge_longer(at_T: OrbitResult, longer: OrbitResult, factor: float) -> OrbitResult:
    """The record of an orbit whose frequencies were measured again at ``factor`` times T (a
    frequency-only re-run): its frequency fields from ``longer``, its chaos indicator from the
    run at T, the larger drift of the integrals."""
    out = replace(at_T, **{k: getattr(longer, k) for k in FREQUENCY_FIELDS}, horizon=float(factor))
    if np.isfinite(longer.drift) and not longer.drift <= at_T.drift:
        out.drift, out.drift_of = longer.drift, longer.drift_of
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
