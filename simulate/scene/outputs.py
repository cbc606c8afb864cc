r"""The requested outputs of a scene, computed from a :class:`simulate.scene.run.Trajectory`, and written.

Output arrays (``S`` samples, ``count`` initial conditions):

* ``M``, ``Omega``, ``orientation`` ($g$): ``(S, count, n, n)``; ``gamma``: ``(S, count, n)``;
* ``x`` $= \gamma_n$: ``(S, count)``; ``zeta`` (Th:Re): ``(count, n, n)``;
* ``reduced`` $= (A, B, E, G, F_1, x, \delta)$ (Section 5): ``(S, count, 7)``;
* ``horizontal`` $= (x, G, A, B)$, $G = \langle ME_n, \gamma\rangle$, $A = \lVert M - (ME_n)\wedge E_n\rVert_\kappa^2$,
  $B = \lVert ME_n\rVert^2$ (S5:H-linear-nD; any $n$): ``(S, count, 4)``;
* ``contact_path``: the first $n-1$ coordinates of the centre $c$ (= the contact point), ``(S, count, n-1)``;
* ``integrals``: energy $H = \tfrac12\langle M, \Omega\rangle_\kappa$ (S2.2:energy), the coefficients of
  $p(\lambda, \sigma)$ (eq:pol-first-integrals), $\|\gamma\|^2$; or, from the reduced model,
  $F_1, F_2, F_3, H$ (S5:red-integrals). Each with its drift $I(t) - I(0)$.

:func:`write` puts ``outputs.npz``, one CSV per output and one PNG per output (drawn by
:mod:`simulate.scene.figures`) into the output folder, all of them or none (:mod:`simulate.scene.outdir`
decides which folders may be written).
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from pathlib import Path
from typing import Any

import numpy as np
from chaplygin_nd.simulate import kernels
from chaplygin_nd.simulate.dynamics import so
from chaplygin_nd.simulate.kernels import active
from chaplygin_nd.simulate.scene import figures, output_registry
from chaplygin_nd.simulate.scene.figures import plot
from chaplygin_nd.simulate.scene.outdir import OutputFolder
from chaplygin_nd.simulate.scene.output_registry import Output, register

__all__ = ["collect", "integrals", "p_coefficients", "write", "FIGURE_SUFFIX", "without_figures"]

#: What a figure is, for every scene kind: an output file with this suffix (trajectory outputs,
#: ``poincare.png``, the frequency maps' ``fma_*.png``).
FIGURE_SUFFIX = ".png"


def without_figures(files: dict[str, Callable[[Path], Any]]) -> dict[str, Callable[[Path], Any]]:
    """``files`` (``{name: writer(path)}``) without its figures: what ``--no-plots`` or
    ``outputs.figures = false`` writes, for every scene kind (the one place that drops them; the
    writers are lazy, so a dropped figure is never drawn)."""
    return {name: w for name, w in files.items() if not name.endswith(FIGURE_SUFFIX)}


def p_coefficients(M: np.ndarray, gamma: np.ndarray) -> np.ndarray:
    r"""Coefficients of $p(\lambda,\sigma) = \det(M + \sigma\gamma\gamma^T - \lambda\,\mathrm{Id})$
    (eq:pol-first-integrals), ``out[..., i, j]`` multiplying $\lambda^i\sigma^j$, for all samples and
    members at once (:func:`simulate.kernels.p_coefficients`: the generated closed form for
    $n = 3, 4$, batched eigenvalues otherwise); any $n$."""
    return kernels.p_coefficients(M, gamma)


def integrals(M, gamma, Omega) -> dict[str, np.ndarray]:
    r"""$H$, the coefficients of $p(\lambda,\sigma)$ and $\|\gamma\|^2$ along the samples (see module)."""
    return {"energy": 0.5 * so.killing(M, Omega), "p": p_coefficients(M, gamma),
            "gamma_norm2": np.einsum("...i,...i->...", gamma, gamma)}


def collect(scene, traj) -> dict[str, np.ndarray]:
    """The arrays of the outputs ``scene.outputs`` (names as in the module docstring), plus
    ``t`` and, for ``integrals``, ``integrals.<name>`` and ``drift.<name>`` arrays: each output's
    registered ``collect`` (:mod:`simulate.scene.output_registry`), in the scene's order."""
    d = traj.data
    out = {"t": traj.t}
    wanted = [output_registry.get(name) for name in scene.outputs]
    need_omega = any(e.omega for e in wanted) and "reduced" not in d
    if need_omega and "Omega" not in d:
        d["Omega"] = active().require("angular_velocity")(d["M"], d["gamma"], scene.a, scene.b)
    for entry in wanted:
        if entry.collect is not None:
            out.update(entry.collect(scene, d))
    return out


# -- the outputs of a trajectory, one entry each -----------------------------------------------


def _state(name: str) -> Output:
    """An output that is one array of the trajectory as it stands (``M``, ``Omega``, ``gamma``)."""
    return register(Output(name, lambda scene, d: {name: d[name]}, omega=name == "Omega"))


def _x(scene, d) -> dict[str, np.ndarray]:
    return {"x": d["gamma"][..., -1] if "gamma" in d else d["horizontal"][..., 0]
            if "horizontal" in d else d["reduced"][..., 5]}


def _integrals(scene, d) -> dict[str, np.ndarray]:
    if "M" in d:
        vals = integrals(d["M"], d["gamma"], d["Omega"])
    else:
        F = active().require("reduced_integrals")(d["reduced"], scene.a, scene.b)
        vals = {"F1": F[..., 0], "F2": F[..., 1], "F3": F[..., 2], "energy": F[..., 3]}
    out = {}
    for key, v in vals.items():
        out[f"integrals.{key}"] = v
        out[f"drift.{key}"] = v - v[:1]
    return out


def _horizontal(scene, d) -> dict[str, np.ndarray]:
    if "horizontal" in d:
        return {"horizontal": d["horizontal"]}
    from chaplygin_nd.simulate.dynamics.closed_forms import horizontal_invariants
    return {"horizontal": horizontal_invariants(d["M"], d["gamma"])}


def _reduced(scene, d) -> dict[str, np.ndarray]:
    if "reduced" in d:
        return {"reduced": d["reduced"]}
    from chaplygin_nd.simulate.dynamics.so import reduced_invariants
    return {"reduced": reduced_invariants(d["M"], d["gamma"])}


def _zeta_csv(path: Path, t: np.ndarray, arr: np.ndarray, name: str) -> None:
    np.savetxt(path, arr.reshape(arr.shape[0], -1), delimiter=",")


M_OUTPUT, OMEGA_OUTPUT, GAMMA_OUTPUT = _state("M"), _state("Omega"), _state("gamma")
X_OUTPUT = register(Output("x", _x, reduced=True, horizontal=True))
INTEGRALS_OUTPUT = register(Output(
    "integrals", _integrals, figures={"integrals.": None, "drift.": figures.drift},
    reduced=True, omega=True, reduced_kernels=("reduced_integrals",)))
ZETA_OUTPUT = register(Output(  # only the vertical closed form computes zeta (a full run does not)
    "zeta", lambda scene, d: {"zeta": d["zeta"]} if "zeta" in d else {},
    figures={"zeta": figures.zeta}, csv=_zeta_csv, vertical=True))
REDUCED_OUTPUT = register(Output("reduced", _reduced, reduced=True, only_n=4))
HORIZONTAL_OUTPUT = register(Output("horizontal", _horizontal, horizontal=True))
ORIENTATION_OUTPUT = register(Output(
    "orientation", lambda scene, d: {"orientation": d["g"]},
    figures={"orientation": figures.orientation}, reconstruct=True))
CONTACT_PATH_OUTPUT = register(Output(
    "contact_path", lambda scene, d: {"contact_path": d["c"][..., :-1]},
    figures={"contact_path": figures.contact_path}, reconstruct=True))


def max_drift(arrays: dict[str, np.ndarray]) -> dict[str, float]:
    """Largest $|I(t) - I(0)|$ per integral."""
    return {k[6:]: float(np.max(np.abs(v))) for k, v in arrays.items() if k.startswith("drift.")}


def _csv(path: Path, t: np.ndarray, arr: np.ndarray, name: str) -> None:
    S = arr.shape[0]
    if arr.ndim == 1:
        arr = arr[:, None]
    count = arr.shape[1]
    comp = arr.reshape(S, count, -1)
    idx = np.stack(np.unravel_index(np.arange(comp.shape[-1]), arr.shape[2:] or (1,)), -1) + 1
    head = ["t", "member"] + [name + ("_" + "_".join(map(str, i)) if arr.ndim > 2 else "")
                              for i in idx]
    # rows ordered member by member, sample by sample (vectorised: no Python loop over rows)
    rows = np.concatenate([np.tile(t, count)[:, None], np.repeat(np.arange(count), S)[:, None],
                           comp.transpose(1, 0, 2).reshape(count * S, -1)], axis=1)
    np.savetxt(path, rows, delimiter=",", header=",".join(head), comments="",
               fmt="%.17g")


def write(folder: OutputFolder, arrays: dict[str, np.ndarray], summary: str,
          plots: bool = True, extra: dict | None = None) -> Path:
    """Write ``arrays`` (NPZ, CSV per output, PNG per output), the ``extra`` files
    (``{name: writer(path)}``, e.g. :func:`simulate.scene.tori.files`) and ``summary.txt`` into
    ``folder`` (claimed by :func:`simulate.scene.outdir.claim`), whole or not at all; returns its
    path. ``plots`` false (``--no-plots``, ``outputs.figures = false``) leaves out every figure, the
    extra ones included (:func:`without_figures`)."""
    t = arrays["t"]
    files: dict[str, Callable[[Path], Any]] = {
        "outputs.npz": lambda p: np.savez(p, **arrays)}  # type: ignore[arg-type]  # numpy stub: **kwds
    for name, arr in arrays.items():
        if name == "t":
            continue
        found = output_registry.owner(name)
        table = (found[0].csv if found else None) or _csv
        files[f"{name}.csv"] = partial(table, t=t, arr=arr, name=name.replace(".", "_"))
        if output_registry.drawing(name, figures.series) is not None:
            files[f"{name}{FIGURE_SUFFIX}"] = partial(plot, t=t, arr=arr, name=name)
    files.update(extra or {})
    files["summary.txt"] = lambda p: p.write_text(summary + "\n", encoding="utf-8")
    return folder.write(files if plots else without_figures(files))
