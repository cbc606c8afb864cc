r"""Frequency maps (Laskar's frequency-map analysis) of the 4D sphere and of a control: the picture
of integrability.

A 2D grid of initial conditions on one energy level set $H = h$ (S2.2:energy) of the $n = 4$
sphere: $\gamma_0 = (\sqrt{1 - x_0^2}, 0, 0, x_0)$ and $M_0 \propto \cos\varphi\,P + \sin\varphi\,Q$
($P, Q$ two seeded skew matrices), scaled so that $H(M_0, \gamma_0) = h$; the axes are $x_0$ and
$\varphi \in [0, \pi)$. Each orbit is integrated on the full field eq:motion-general in
$(M, \gamma)$ (heyoka, batch mode), sampled on a uniform grid, and the fundamental frequency of the
SO(3)-invariant observables $x + iG/(a + b + 2)$ and $E + i\delta$ (the reduced invariants of
Section 5, the signals of :func:`simulate.analysis.evidence.signals`) is measured on the first and the
second half of the orbit (:func:`simulate.analysis.naff.fundamental_frequencies`). The colour is the
frequency diffusion $D = \log_{10}\max|\omega^{(1)} - \omega^{(2)}|$ over the two observables
(of $|\omega|$: a real oscillation has lines $\pm\omega$ of nearly equal amplitude, and which of
the two is the strongest may differ between the halves).

Why the full field for both maps and not the reduced 7D one: the control (a generic mass tensor,
:mod:`simulate.analysis.control`) has no SO(3) symmetry and so no reduced system; integrating both on the
same 9D phase space with the same observables, integrator and tolerance makes the two maps differ
only in $\mathbb{J}$. The axisymmetric map uses the derived field (P:inversion, generated builders,
:func:`simulate.integrators.heyoka_systems.full`); the control solves $L_\gamma(\Omega) = M$ from the
definition (eq:M-O, eq:Inertia) by Gaussian elimination inside the compiled field
(:func:`control_system`; tested against the NumPy linear solve of :mod:`simulate.analysis.control`).

Work is cut into chunks of ``chunk`` orbits, each integrated by one compiled batch integrator
(per process: compiled once, then from memory) and analysed vectorised. Chunks run in this
process (``workers = 1``), in worker processes, or on a Dask cluster (``scheduler``: an address,
or ``"local"`` for a :class:`distributed.LocalCluster`); the result does not depend on which.
"""

from __future__ import annotations

import os
import threading
from dataclasses import asdict, dataclass

import numpy as np
from chaplygin_nd.simulate.analysis import naff
from chaplygin_nd.simulate.analysis.control import general_inertia_kernels
from chaplygin_nd.simulate.dynamics import so
from chaplygin_nd.simulate.dynamics.so import reduced_invariants
from chaplygin_nd.simulate.integrators import heyoka_systems

from chaplygin_nd import processes

__all__ = ["MapSpec", "control_system", "control_omega", "initial_conditions", "run_map",
           "diffusion_of_chunk"]

_LOCK = threading.Lock()  # one compiled integrator per process: chunks of one process take turns


@dataclass(frozen=True)
class MapSpec:
    r"""One frequency map: the sphere ($a, b$; ``J`` a diagonal mass tensor for the control, empty
    for the axisymmetric sphere $\mathbb{J} = \mathrm{diag}(1, 1, 1, 1 + a)$), the energy ``h``,
    the grid ``size`` $\times$ ``size`` over $x_0 \in$ ``x_range``, $\varphi \in [0, \pi)$, the seed
    of $P, Q$, the sampling (``samples`` per half, step ``dt``), the Taylor tolerance ``tol`` and
    the chunk size."""

    a: float
    b: float
    h: float
    size: int
    samples: int
    dt: float
    seed: int = 1
    J: tuple[float, ...] = ()
    x_range: tuple[float, float] = (-0.9, 0.9)
    tol: float = 1e-12
    chunk: int = 64

    @property
    def mass_tensor(self) -> tuple[float, ...]:
        """The diagonal of $\\mathbb{J}$ (the axisymmetric one when ``J`` is empty)."""
        return tuple(self.J) if self.J else (1.0, 1.0, 1.0, 1.0 + self.a)


# -- the control's field, assembled from the definition (any scalar arithmetic) ----------------

def _pairs(n):
    return [(i, j) for i in range(n) for j in range(i + 1, n)]


def _add(u, v):
    if isinstance(u, int) and u == 0:
        return v
    if isinstance(v, int) and v == 0:
        return u
    return u + v


def _mul(u, v):
    if (isinstance(u, int) and u == 0) or (isinstance(v, int) and v == 0):
        return 0
    return u * v


def _skew(m, n):
    M = [[0] * n for _ in range(n)]
    for v, (i, j) in zip(m, _pairs(n)):
        M[i][j], M[j][i] = v, _mul(-1, v)
    return M


def _matvec(A, x):
    out = []
    for row in A:
        acc = 0
        for a_, x_ in zip(row, x):
            acc = _add(acc, _mul(a_, x_))
        out.append(acc)
    return out


def _L_column(i, j, gamma, J, b, n):
    r"""$\mathrm{vec}\,L_\gamma(E_i\wedge E_j)$ (eq:M-O, eq:Inertia) for diagonal $\mathbb{J}$."""
    L = [[0] * n for _ in range(n)]
    L[i][j] = _add(J[i], J[j])
    L[j][i] = _mul(-1, L[i][j])
    Eg = [0] * n                                    # (E_i ^ E_j) gamma = gamma_j E_i - gamma_i E_j
    Eg[i], Eg[j] = gamma[j], _mul(-1, gamma[i])
    return [_add(L[p][q], _mul(b, _add(_mul(Eg[p], gamma[q]), _mul(-1, _mul(Eg[q], gamma[p])))))
            for p, q in _pairs(n)]


def control_omega(m, gamma, J, b):
    r"""$\mathrm{vec}\,\Omega$ with $L_\gamma(\Omega) = M$ for the diagonal mass tensor ``J``
    (eq:M-O): the matrix of $L_\gamma$ in the basis $E_i\wedge E_j$ assembled from the definition,
    solved by Gaussian elimination without pivoting (valid: $L_\gamma$ is positive definite for
    $J_i > 0$, $b > 0$). Any scalar arithmetic (floats, heyoka expressions)."""
    n = len(gamma)
    cols = [_L_column(i, j, gamma, J, b, n) for i, j in _pairs(n)]
    N = len(cols)
    A = [[cols[c][r] for c in range(N)] + [m[r]] for r in range(N)]   # augmented, row-major
    for k in range(N):
        for r in range(k + 1, N):
            if isinstance(A[r][k], int) and A[r][k] == 0:
                continue
            f = A[r][k] / A[k][k]
            A[r] = [A[r][c] if c <= k else _add(A[r][c], _mul(-1, _mul(f, A[k][c])))
                    for c in range(N + 1)]
    x = [0] * N
    for k in reversed(range(N)):
        acc = A[k][N]
        for c in range(k + 1, N):
            acc = _add(acc, _mul(-1, _mul(A[k][c], x[c])))
        x[k] = acc / A[k][k]
    return x


def control_system(n: int = 4) -> heyoka_systems.System:
    r"""eq:motion-general, $\dot M = [M, \Omega]$, $\dot\gamma = -\Omega\gamma$, for a diagonal mass
    tensor $\mathbb{J}$ given as runtime parameters $(J_1..J_n, b)$, $\Omega$ from
    :func:`control_omega`; the state of :class:`simulate.dynamics.field.FullField`."""
    pairs = _pairs(n)
    names = tuple([f"M{i + 1}_{j + 1}" for i, j in pairs] + [f"gamma{i + 1}" for i in range(n)])

    def build(v, p, ops):
        N = len(pairs)
        m, gamma = v[:N], v[N:]
        w = control_omega(m, gamma, p[:n], p[n], )
        M, Om = _skew(m, n), _skew(w, n)
        out = []
        for i, j in pairs:
            acc = 0
            for k in range(n):
                acc = _add(acc, _add(_mul(M[i][k], Om[k][j]), _mul(-1, _mul(Om[i][k], M[k][j]))))
            out.append(acc)
        out += [_mul(-1, g) for g in _matvec(Om, gamma)]
        return out

    return heyoka_systems.System(f"general-J control n={n}", names,
                                 tuple(f"J{i + 1}" for i in range(n)) + ("b",), build)


# -- the grid -----------------------------------------------------------------------------------

def initial_conditions(spec: MapSpec) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    r"""``(y0, x0, phi)``: states ``(size*size, 10)`` (vec M, gamma) on $H = h$ for the sphere of
    ``spec`` (row-major over ($\varphi$, $x_0$)), and the axes."""
    n = 4
    rng = np.random.default_rng(spec.seed)
    P, Q = (so.unvec(rng.standard_normal(so.so_dim(n)), n) for _ in range(2))
    x0 = np.linspace(*spec.x_range, spec.size)
    phi = np.arange(spec.size) * np.pi / spec.size
    X, F = np.meshgrid(x0, phi)
    gamma = np.stack([np.sqrt(1 - X**2), 0 * X, 0 * X, X], -1).reshape(-1, n)
    M = (np.cos(F)[..., None, None] * P + np.sin(F)[..., None, None] * Q).reshape(-1, n, n)
    solve = general_inertia_kernels(spec.mass_tensor, spec.b).angular_velocity
    assert solve is not None  # general_inertia_kernels always provides it
    Omega = solve(M, gamma, spec.a, spec.b)
    H = 0.5 * np.einsum("...i,...i->...", so.vec(M), so.vec(Omega))     # S2.2:energy
    M = M * np.sqrt(spec.h / H)[:, None, None]
    return np.concatenate([so.vec(M), gamma], -1), x0, phi


def _system(spec: MapSpec):
    if spec.J:
        return control_system(4), list(spec.J) + [spec.b]
    return heyoka_systems.full(4), [spec.a, spec.b]


def diffusion_of_chunk(spec: MapSpec, y0: np.ndarray) -> np.ndarray:
    r"""$D = \log_{10}\max|\omega^{(1)} - \omega^{(2)}|$ (see the module docstring) of each orbit of
    ``y0`` ``(count, 10)``: one batch integration (compiled once per process), then NAFF vectorised
    over the orbits. Non-finite or failed orbits give nan."""
    from chaplygin_nd.simulate.integrators import heyoka_taylor

    system, pars = _system(spec)
    t = np.arange(2 * spec.samples) * spec.dt
    with _LOCK:
        sol = heyoka_taylor.integrate(system, y0, t, tol=spec.tol, pars=pars, batch=True)
    y = np.moveaxis(sol.y, 1, 0)                                  # (count, samples, dim)
    r = reduced_invariants(so.unvec(y[..., :6], 4), y[..., 6:])
    nu = spec.a + spec.b + 2
    half = spec.samples
    worst = np.zeros(len(y0))
    for z in (r[..., 5] + 1j * r[..., 3] / nu, r[..., 2] + 1j * r[..., 6]):
        w1 = naff.fundamental_frequencies(z[:, :half], spec.dt)
        w2 = naff.fundamental_frequencies(z[:, half:], spec.dt)
        worst = np.maximum(worst, np.abs(np.abs(w1) - np.abs(w2)))
    with np.errstate(divide="ignore"):
        return np.log10(worst)


def _task(args):
    spec_dict, y0 = args
    return diffusion_of_chunk(MapSpec(**spec_dict), y0)


def require_heyoka() -> None:
    """Stop the run (:class:`RunStopped`, one line) when heyoka, which every map needs, is not
    installed: checked again by the scene before its plan line (a new user's trial: the plan was
    printed, then the error)."""
    from chaplygin_nd.simulate.integrators import heyoka_taylor
    from chaplygin_nd.simulate.integrators.stops import RunStopped

    if not heyoka_taylor.available():
        raise RunStopped("frequency maps need heyoka: pip install 'chaplygin-nd[fast]'")


def where(workers: int | None, scheduler: str | None) -> str:
    """Where the orbits of a map run (:func:`run_map`), for the plan and the summary:
    ``"Dask scheduler ADDRESS"``, ``"a local Dask cluster of N processes"`` or ``"N worker
    processes"`` (``"this process"`` for one)."""
    count = workers or os.cpu_count() or 1
    if scheduler == "local":
        return f"a local Dask cluster of {count} process{'es' if count > 1 else ''}"
    if scheduler:
        return f"Dask scheduler {scheduler}"
    return "this process" if count == 1 else f"{count} worker processes"


def run_map(spec: MapSpec, workers: int | None = None, scheduler: str | None = None,
            on_orbits=None) -> np.ndarray:
    r"""The frequency map of ``spec``: $D$ ``(size, size)`` (rows $\varphi$, columns $x_0$). Chunks
    run here (``workers = 1``), in ``workers`` processes (default: the CPU count), or on a Dask
    cluster (``scheduler``: its address, or ``"local"`` for a local cluster of ``workers``
    single-threaded processes). ``on_orbits(k)`` is called as each chunk of ``k`` orbits is done
    (the progress line). Requires heyoka (extra ``fast``) and, for a cluster, Dask (extra
    ``cluster``)."""
    require_heyoka()
    on_orbits = on_orbits or (lambda k: None)
    y0, _, _ = initial_conditions(spec)
    chunks = [(asdict(spec), y0[s:s + spec.chunk]) for s in range(0, len(y0), spec.chunk)]
    if scheduler is not None:
        parts = _on_dask(chunks, scheduler, workers, on_orbits)
    elif (workers or os.cpu_count() or 1) == 1:
        parts = []
        for c in chunks:
            parts.append(_task(c))
            on_orbits(len(c[1]))
    else:
        import multiprocessing as mp

        with processes.pool(min(workers or os.cpu_count() or 1, len(chunks)),
                            mp.get_context("spawn")) as pool:
            futures = {pool.submit(_task, c): len(c[1]) for c in chunks}
            for done in processes.as_completed(futures):
                on_orbits(futures[done])
            parts = [f.result() for f in futures]
    return np.concatenate(parts).reshape(spec.size, spec.size)


def _ignore_ctrl_c() -> None:
    """In a Dask worker process (its event loop runs in the main thread): ignore SIGINT."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _on_dask(chunks, scheduler: str, workers: int | None, on_orbits):
    from chaplygin_nd.simulate.integrators.stops import RunStopped

    try:
        from distributed import Client, LocalCluster, as_completed
    except ImportError:
        raise RunStopped("--scheduler needs Dask: pip install 'chaplygin-nd[cluster]'") from None

    def gather(client):
        futures = client.map(_task, chunks, pure=False)
        sizes = {f.key: len(c[1]) for f, c in zip(futures, chunks)}
        for done in as_completed(futures):
            on_orbits(sizes[done.key])
        return client.gather(futures)

    if scheduler == "local":
        import logging

        # no dashboard, and the scheduler's HTTP server (it starts one even without a
        # dashboard, on port 8787 by default) on a free port of this host only: a port taken by
        # another cluster or program made Dask warn and, under warnings as errors, fail (seen in CI)
        with LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1,
                          processes=True, host="127.0.0.1", dashboard_address=None,
                          scheduler_kwargs={"dashboard": False,
                                            "dashboard_address": "127.0.0.1:0"},
                          silence_logs=logging.CRITICAL) as cluster, Client(cluster) as client:
            client.run(processes.die_with_parent, os.getpid())  # its workers are ours: see processes
            # and Ctrl-C is the parent's (processes): a Ctrl-C to the process group made each
            # worker print a KeyboardInterrupt traceback; the cluster's own log lines (a worker
            # restarted, a task lost on close) are not the user's either
            client.run(_ignore_ctrl_c)
            return gather(client)
    try:
        client = Client(scheduler, timeout="20s")
    except (OSError, TimeoutError, ValueError) as exc:
        raise RunStopped(f"cannot reach the Dask scheduler {scheduler!r} ({exc})") from None
    with client:
        return gather(client)
