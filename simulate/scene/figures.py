r"""Figures of a scene's outputs: one PNG per output, readable without the code.

Every figure has labelled axes (the quantity and its symbol: ``t``, $x = \gamma_n$, $M_{ij}$, ...), a
legend, and a title that says what is drawn. Conventions:

* skew matrices ($M$, $\Omega$): only the independent entries $i < j$;
* the reduced invariants $(A, B, E, G, F_1, x, \delta)$ of Section 5: one named panel each;
* drift $|I(t) - I(0)|$ of a first integral (S2.2:energy, eq:pol-first-integrals,
  S5:red-integrals): on a log axis of the values themselves (exact zeros, e.g. at $t = t_0$, are
  left out, never lifted to a floor); a quantity whose drift is identically zero is named in the
  figure instead of drawn, and a figure where every drift is zero uses a linear axis;
* an ensemble (``count > 1``): every member as a thin line, the median and the 5–95 % band;
* the contact path: for $n = 3$ the path in the plane $(c_1, c_2)$; for $n = 4$ the path in
  $\mathbb{R}^3$; for $n \ge 5$ its projection onto $(c_1, c_2, c_3)$, said in the title, with every
  coordinate against $t$ beside it;
* the orientation $g(t) \in SO(n)$: an $n\times n$ grid, one panel per entry $g_{ij}$.

Titles are figure titles (``suptitle``), so they never collide with an axis' offset text. Time
series and drift figures use fixed margins in inches (:func:`_fixed_layout`; constrained layout
cost more than a third of a warm ensemble scene); the grids (orientation, contact path, zeta) keep
constrained layout. An ensemble's members are one line collection (one artist, not one per member). :func:`figure` builds the :class:`matplotlib.figure.Figure` (tests inspect its
artists); :func:`plot` saves it.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

__all__ = ["figure", "plot", "series", "drift", "contact_path", "orientation", "zeta",
           "REDUCED_NAMES", "INTEGRAL_NAMES"]

#: The reduced invariants of Section 5 (Reduction by SO(3)), in the order of ``reduced``.
REDUCED_NAMES = (r"$A = \|k\|^2$", r"$B = \|u\|^2$", r"$E = \langle k, q\rangle$",
                 r"$G = \langle u, q\rangle$", r"$F_1 = \langle k, u\rangle$", r"$x = \gamma_4$",
                 r"$\delta = \langle q, k\times u\rangle$")
#: Symbols of the first integrals written by :func:`simulate.scene.outputs.collect` (``drift.<key>``).
INTEGRAL_NAMES = {"energy": "H", "gamma_norm2": r"\|\gamma\|^2", "F1": "F_1", "F2": "F_2",
                  "F3": "F_3"}
_SEPARATE = 12  # at most this many panels for an ensemble of a vector output
_AXIS_LABELS = {"M": "$M_{ij}$", "Omega": r"$\Omega_{ij}$", "gamma": r"$\gamma_i$"}
_STYLES = ("-", "--", ":")  # line style per block of ten colours
_OUTSIDE = {"loc": "upper left", "bbox_to_anchor": (1.01, 1.0)}  # legend right of the axes


def _pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def _sub(i: int, j: int | None = None, n: int = 0) -> str:
    """Subscript of entry ``(i, j)`` (1-based), with a comma when an index has two digits."""
    if j is None:
        return f"{i}"
    return f"{i},{j}" if n >= 10 else f"{i}{j}"


def _fixed_layout(fig, legend_cols: int = 0, bottom_legend: bool = False, panels: bool = False):
    """Margins in inches instead of constrained layout (which measured 37 % of a warm ensemble
    scene: it lays every text out twice): room for the tick labels and axis labels, the figure
    title on top, a legend of ``legend_cols`` columns right of the axes or one row below them."""
    w, h = fig.get_size_inches()
    right = 0.2 + 1.85 * legend_cols
    bottom = 0.55 + (0.45 if bottom_legend else 0.0)
    fig.subplots_adjust(left=0.85 / w, right=1 - right / w, bottom=bottom / h, top=1 - 0.75 / h,
                        wspace=0.38 if panels else 0.2, hspace=0.3 if panels else 0.2)


def _members(arr: np.ndarray) -> np.ndarray:
    """``arr (S, count, ...)`` as ``(S, count, components)``; a scalar output gets one component."""
    S = arr.shape[0]
    if arr.ndim == 1:
        return arr.reshape(S, 1, 1)
    return arr.reshape(S, arr.shape[1], -1)


def _components(name: str, arr: np.ndarray) -> tuple[list[str], np.ndarray, str]:
    """(labels, values ``(S, count, k)``, description) of a time-series output."""
    if name in ("M", "Omega"):
        n = arr.shape[-1]
        sym = "M" if name == "M" else r"\Omega"
        pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]
        values = np.stack([arr[..., i, j] for i, j in pairs], axis=-1)
        labels = [f"${sym}_{{{_sub(i + 1, j + 1, n)}}}$" for i, j in pairs]
        what = ("angular momentum $M$ about the contact point" if name == "M"
                else r"angular velocity $\Omega$")
        return labels, values, f"{what} (body frame), entries $i<j$ of the ${n}\\times{n}$ skew matrix"
    if name == "gamma":
        n = arr.shape[-1]
        return ([rf"$\gamma_{{{i + 1}}}$" for i in range(n)], arr,
                r"Poisson vector $\gamma$ (normal of the plane, body frame)")
    if name == "x":
        return [r"$x = \gamma_n$"], arr[..., None], r"$x = \gamma_n = \langle\gamma, E_n\rangle$, cosine of the angle between the symmetry axis and the normal"
    if name == "reduced":
        return list(REDUCED_NAMES), arr, r"reduced invariants of $SO(3)$ (Section 5)"
    if name == "horizontal":
        return ([r"$x = \gamma_n$", r"$G = \langle M E_n, \gamma\rangle$", "$A$", "$B$"], arr,
                r"horizontal invariants $(x, G, A, B)$ on $\mathcal{H}$ (S5:H-linear-nD)")
    raise KeyError(name)


def _constant(ax, y) -> bool:
    """If ``y`` is constant to rounding (spread <= 1e-9 of its size), centre a readable y-range
    on it and say so in the legend; returns whether it did."""
    y = np.asarray(y, dtype=float)
    size = max(1.0, float(np.max(np.abs(y))))
    spread = float(np.max(y) - np.min(y))
    if not spread <= 1e-9 * size:
        return False
    mid = float(np.mean(y))
    half = 0.05 * max(abs(mid), 1e-3 * size)
    ax.set_ylim(mid - half, mid + half)
    ax.plot([], [], " ", label=f"constant: max - min = {spread:.1e}")
    return True


def _ensemble(ax, t, Y, color="C0", label=None, legend=True):
    """All members of ``Y (S, count)`` thin, the median bold and the 5-95 % band."""
    count = Y.shape[1]
    import warnings

    with warnings.catch_warnings():  # a sample where every member is nan (e.g. a zero drift at t0)
        warnings.simplefilter("ignore", RuntimeWarning)
        lo, med, hi = np.nanpercentile(Y, [5, 50, 95], axis=1)
    ax.fill_between(t, lo, hi, color=color, alpha=0.12, lw=0, label="5–95 % of members")
    from matplotlib.collections import LineCollection

    # One collection for all members (one artist instead of `count`: drawing and layout cost O(1)
    # artists; measured 64 members: the figure is several times faster to save).
    segments = np.stack(np.broadcast_arrays(t[None, :], Y.T), axis=-1)
    thin = LineCollection(segments, colors=color, linewidths=0.5,
                          alpha=max(0.2, min(0.6, 16 / count)), label=f"members ({count})")
    ax.add_collection(thin)
    ax.autoscale_view()
    ax.plot(t, med, color="k", lw=1.2, label="median")
    if legend:
        ax.legend(fontsize=7, **_OUTSIDE)
    if label:
        ax.set_ylabel(label)


def _series_figure(plt, name, t, arr):
    labels, values, what = _components(name, arr)
    vals = _members(values)
    count, k = vals.shape[1], vals.shape[2]
    panels = name == "reduced" or (count > 1 and k > 1)
    if not panels:
        fig, ax = plt.subplots(figsize=(7.5, 4.2))
        if count == 1:
            for i, lab in enumerate(labels):
                ax.plot(t, vals[:, 0, i], lw=0.9, ls=_STYLES[i // 10 % 3], label=lab)
            if k == 1:
                _constant(ax, vals[:, 0, 0])
            ax.legend(fontsize=8, ncol=max(1, (k + 9) // 10), **_OUTSIDE)
            ax.set_ylabel(labels[0] if k == 1 else _AXIS_LABELS.get(name, name))
        else:
            _ensemble(ax, t, vals[:, :, 0], label=labels[0])
        ax.set_xlabel("t")
        ax.grid(True, lw=0.3)
        ax.ticklabel_format(axis="y", useOffset=False)
        fig.suptitle(what + (f", {count} initial conditions" if count > 1 else ""), fontsize=10)
        _fixed_layout(fig, max(1, (k + 9) // 10) if count == 1 else 1)
        return fig
    shown = min(k, _SEPARATE)
    cols = 2 if shown <= 8 else 3
    rows = -(-shown // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 2.1 * rows + 0.6), sharex=True,
                             squeeze=False)
    for i in range(rows * cols):
        ax = axes.flat[i]
        if i >= shown:
            ax.set_axis_off()
            continue
        if count == 1:
            ax.plot(t, vals[:, 0, i], lw=0.9, color=f"C{i % 10}", label=labels[i])
            _constant(ax, vals[:, 0, i])
            ax.legend(fontsize=8, loc="best")
            ax.set_ylabel(labels[i])
        else:
            _ensemble(ax, t, vals[:, :, i], color=f"C{i % 10}", label=labels[i], legend=False)
            if i == 0:
                fig.legend(*ax.get_legend_handles_labels(), loc="lower center", ncol=3,
                           fontsize=8)
        ax.grid(True, lw=0.3)
        ax.ticklabel_format(axis="y", useOffset=False)
        if i + cols >= shown:  # nothing below: this panel carries the t axis
            ax.set_xlabel("t")
            ax.xaxis.set_tick_params(labelbottom=True)
    note = f"; first {shown} of {k} entries" if shown < k else ""
    fig.suptitle(what + (f", {count} initial conditions" if count > 1 else "") + note,
                 fontsize=10)
    _fixed_layout(fig, bottom_legend=count > 1, panels=True)
    return fig


def _drift_labels(key: str, arr: np.ndarray) -> tuple[list[str], np.ndarray, str]:
    if key == "p":
        n = arr.shape[-2] - 1
        labels = [rf"$\lambda^{{{i}}}\sigma^{{{j}}}$" for i in range(n + 1) for j in range(2)]
        return labels, arr.reshape(arr.shape[:2] + (-1,)), (
            r"drift of the coefficients of $p(\lambda,\sigma) = \det(M + \sigma\gamma\gamma^T"
            r" - \lambda\,\mathrm{Id})$ (eq:pol-first-integrals)")
    sym = INTEGRAL_NAMES.get(key, key)
    source = {"energy": "energy, S2.2:energy", "gamma_norm2": "trivial integral"}.get(
        key, "S5:red-integrals")
    return [rf"$|{sym}(t) - {sym}(t_0)|$"], arr[..., None] if arr.ndim == 2 else arr[:, None, None], \
        rf"drift of ${sym}$ ({source})"


def _drift_figure(plt, key, t, arr):
    labels, vals, what = _drift_labels(key, arr)
    vals = np.abs(_members(vals))
    count = vals.shape[1]
    fig, ax = plt.subplots(figsize=(7.5, 4.2))
    ax.set_xlabel("t")
    if count > 1:
        worst = vals.max(axis=2)  # (S, count): the largest component per member
        pos = np.where(worst > 0, worst, np.nan)
        if np.all(np.isnan(pos)):
            ax.plot(t, worst, lw=0.8)
            ax.set_ylabel(r"$|I(t) - I(t_0)|$ (identically 0)")
        else:
            ax.set_yscale("log")
            _ensemble(ax, t, pos, label=labels[0] if len(labels) == 1 else
                      r"$\max_{\mathrm{coefficients}} |I(t) - I(t_0)|$")
        fig.suptitle(f"{what}, {count} initial conditions", fontsize=10)
        ax.grid(True, which="both", lw=0.3)
        _fixed_layout(fig, 0 if np.all(np.isnan(pos)) else 1)
        return fig
    zero = [lab for i, lab in enumerate(labels) if not np.any(vals[:, 0, i])]
    live = [i for i, lab in enumerate(labels) if lab not in zero]
    gaps = any(np.any(vals[1:, 0, i] == 0) for i in live)
    if live:
        ax.set_yscale("log")
        for i in live:
            y = np.where(vals[:, 0, i] > 0, vals[:, 0, i], np.nan)
            ax.plot(t, y, lw=0.6 if gaps else 0.8, ls=_STYLES[i // 10 % 3],
                    marker="." if gaps or len(t) <= 60 else None, ms=2.5,
                    label=labels[i] if len(labels) > 1 else labels[0])
        ax.set_ylabel(r"$|I(t) - I(t_0)|$" if len(labels) > 1 else labels[0])
    else:
        ax.plot(t, vals[:, 0, 0], lw=0.8, label=labels[0] if len(labels) == 1 else "every coefficient")
        ax.set_ylabel(r"$|I(t) - I(t_0)|$")
    if gaps:
        ax.plot([], [], " ", label="gaps: drift exactly 0 there")
    if zero:
        text = ", ".join(zero) if len(zero) <= 6 else f"{len(zero)} of {len(labels)}"
        ax.plot([], [], " ", label=f"identically 0: {text}")
    ax.legend(fontsize=8, ncol=2 if len(live) > 12 else 1, **_OUTSIDE)
    ax.grid(True, which="both", lw=0.3)
    fig.suptitle(what, fontsize=10)
    _fixed_layout(fig, 2 if len(live) > 12 else 1)
    return fig


def _contact_figure(plt, t, arr):
    """Contact path ``arr (S, count, n-1)``: the path itself and its coordinates against t."""
    vals = arr if arr.ndim == 3 else arr[:, None, :]
    count, d = vals.shape[1], vals.shape[2]
    n = d + 1
    fig = plt.figure(figsize=(11, 4.8), layout="constrained")
    three = d >= 3
    ax = fig.add_subplot(1, 2, 1, projection="3d" if three else None)
    lw = 1.0 if count == 1 else 0.5
    for e in range(count):
        P = vals[:, e, :3] if three else vals[:, e, :2] if d >= 2 else np.c_[vals[:, e, 0], 0 * t]
        label = "contact point = centre seen from the plane" if e == 0 else None
        ax.plot(*P.T, lw=lw, color="C0", alpha=1.0 if count == 1 else 0.4, label=label)
        ax.plot(*P[:1].T, "o", color="C2", ms=5, label="start $t_0$" if e == 0 else None)
        ax.plot(*P[-1:].T, "s", color="C3", ms=5, label="end" if e == 0 else None)
    ax.set_xlabel("$c_1$")
    ax.set_ylabel("$c_2$")
    if three:
        ax.set_zlabel("$c_3$")
        ax.tick_params(labelsize=7)
        where = (r"in the hyperplane $\mathbb{R}^3$ (all coordinates, no projection)" if n == 4 else
                 f"projected onto $(c_1, c_2, c_3)$ of $\\mathbb{{R}}^{{{d}}}$; "
                 + ("$c_4$ is" if d == 4 else f"$c_4, \\ldots, c_{{{d}}}$ are")
                 + " in the right panel")
    else:
        ax.set_aspect("equal", "datalim")
        ax.grid(True, lw=0.3)
        where = "in the plane $(c_1, c_2)$, seen from above"
    if three:    # a 3D view has no empty corner to find: the legend goes below the panels
        fig.legend(*ax.get_legend_handles_labels(), fontsize=8, ncol=3, loc="outside lower left")
    else:
        ax.legend(fontsize=8, loc="best")
    ax.set_title(where, fontsize=9)
    right = fig.add_subplot(1, 2, 2)
    for i in range(d):
        if count == 1:
            right.plot(t, vals[:, 0, i], lw=0.9, label=f"$c_{{{i + 1}}}$")
        else:
            right.plot(t, vals[:, :, i], lw=0.4, color=f"C{i % 10}", alpha=0.4)
            right.plot([], [], color=f"C{i % 10}", label=f"$c_{{{i + 1}}}$ ({count} members)")
    right.set_xlabel("t")
    right.set_ylabel("contact point coordinate")
    right.legend(fontsize=8, loc="best", ncol=1 if d <= 6 else 2)
    right.grid(True, lw=0.3)
    right.set_title("coordinates of the contact point against t", fontsize=9)
    fig.suptitle(f"contact path of the ball on the {'plane' if d == 2 else 'hyperplane'} "
                 f"$\\mathbb{{R}}^{{{d}}}$ "
                 f"(n = {n}, space frame)", fontsize=10)
    return fig


def _orientation_figure(plt, t, arr):
    vals = arr if arr.ndim == 4 else arr[:, None]
    count, n = vals.shape[1], vals.shape[-1]
    size = min(1.7, 9.5 / n)
    fig, axes = plt.subplots(n, n, figsize=(size * n + 0.6, size * n * 0.8 + 0.8), sharex=True,
                             sharey=True, layout="constrained", squeeze=False)
    for i in range(n):
        for j in range(n):
            ax = axes[i, j]
            Y = vals[:, :, i, j]
            ax.plot(t, Y, lw=0.6 if count == 1 else 0.3, color="C0",
                    alpha=1.0 if count == 1 else 0.4, label="$g_{ij}(t)$")
            ax.set_title(f"$g_{{{_sub(i + 1, j + 1, n)}}}$", fontsize=8, pad=2)
            ax.set_ylim(-1.05, 1.05)
            ax.tick_params(labelsize=6)
            ax.grid(True, lw=0.3)
            if i == n - 1:
                ax.set_xlabel("t", fontsize=8)
    axes[0, 0].set_ylabel("entry", fontsize=8)
    axes[0, 0].legend(fontsize=6, loc="lower left")
    fig.suptitle(f"orientation $g(t) \\in SO({n})$ (body to space frame), entry $(i, j)$ "
                 "in row i, column j" + (f", {count} members" if count > 1 else ""), fontsize=10)
    return fig


def _zeta_figure(plt, arr):
    Z = arr[0]
    n = Z.shape[-1]
    fig, ax = plt.subplots(figsize=(1.1 * n + 2.5, 1.0 * n + 1.2), layout="constrained")
    lim = float(np.max(np.abs(Z))) or 1.0
    im = ax.imshow(Z, cmap="RdBu_r", vmin=-lim, vmax=lim)
    for i in range(n):
        for j in range(n):  # white on dark cells, black on light ones (relative luminance)
            r, g, b, _ = im.cmap(im.norm(Z[i, j]))
            dark = 0.2126 * r + 0.7152 * g + 0.0722 * b < 0.45
            ax.text(j, i, f"{Z[i, j]:.3g}", ha="center", va="center", fontsize=8,
                    color="white" if dark else "black")
    ax.set_xticks(range(n), [str(j + 1) for j in range(n)])
    ax.set_yticks(range(n), [str(i + 1) for i in range(n)])
    ax.set_xlabel("column j")
    ax.set_ylabel("row i")
    fig.colorbar(im, ax=ax, label=r"$\zeta_{ij}$")
    ax.set_title(r"$\zeta E_n = 0$: the last row and column vanish (up to rounding)", fontsize=8)
    more = f" (first of {arr.shape[0]} initial conditions)" if arr.shape[0] > 1 else ""
    fig.suptitle(r"$\zeta \in \mathfrak{so}(n-1)$ of the vertical solution (Th:Re)" + more,
                 fontsize=10)
    return fig


# -- the drawings an output registers (simulate.scene.output_registry): draw(plt, key, t, arr) --


def series(plt, key: str, t: np.ndarray, arr: np.ndarray):
    """A time series (the default drawing of an output array)."""
    return _series_figure(plt, key, t, arr)


def drift(plt, key: str, t: np.ndarray, arr: np.ndarray):
    """The drift of a first integral, ``key`` = ``drift.<name>``."""
    return _drift_figure(plt, key[6:], t, arr)


def contact_path(plt, key: str, t: np.ndarray, arr: np.ndarray):
    """The contact path."""
    return _contact_figure(plt, t, arr)


def orientation(plt, key: str, t: np.ndarray, arr: np.ndarray):
    """The orientation grid."""
    return _orientation_figure(plt, t, arr)


def zeta(plt, key: str, t: np.ndarray, arr: np.ndarray):
    """The matrix zeta."""
    return _zeta_figure(plt, arr)


def figure(name: str, t: np.ndarray, arr: np.ndarray):
    r"""The figure of output ``name`` (a key of :func:`simulate.scene.outputs.collect`) with samples ``t``
    and values ``arr`` (shapes as in :mod:`simulate.scene.outputs`), drawn as its output registered
    (:mod:`simulate.scene.output_registry`); see the module docstring. Returns a
    :class:`matplotlib.figure.Figure`; the caller closes it."""
    from chaplygin_nd.simulate.scene import output_registry

    draw = output_registry.drawing(name, series)
    if draw is None:
        raise ValueError(f"the output array {name!r} has no figure")
    return draw(_pyplot(), name, t, arr)


def _fit(fig, pad: float = 0.08) -> None:
    r"""Grow a fixed-layout figure (:func:`_fixed_layout`) by whatever its texts overflow — a
    y-label pushed left by wide log-axis tick labels ($6\times10^{-17}$), a legend with long
    entries — keeping every axes' size in inches, so nothing is cut at an edge. Constrained
    layouts fit themselves."""
    if fig.get_layout_engine() is not None:
        return
    box = fig.get_tightbbox(fig.canvas.get_renderer())  # inches
    w, h = fig.get_size_inches()
    left, right = max(0.0, pad - box.x0), max(0.0, box.x1 - (w - pad))
    bottom, top = max(0.0, pad - box.y0), max(0.0, box.y1 - (h - pad))
    if not (left or right or bottom or top):
        return
    sp = fig.subplotpars
    W, H = w + left + right, h + bottom + top
    edges = dict(left=(sp.left * w + left) / W, right=(sp.right * w + left) / W,
                 bottom=(sp.bottom * h + bottom) / H, top=(sp.top * h + bottom) / H)
    fig.set_size_inches(W, H)
    fig.subplots_adjust(**edges)
    suptitle = getattr(fig, "_suptitle", None)
    if suptitle is not None and any(text is suptitle for text in fig.texts):  # same height above
        suptitle.set_y(1 - (1 - suptitle.get_position()[1]) * h / H)


def plot(path: str | Path, t: np.ndarray, arr: np.ndarray, name: str) -> None:
    """Draw :func:`figure`, fit it (:func:`_fit`) and save it as a PNG at ``path``."""
    plt = _pyplot()
    fig = figure(name, t, arr)
    try:
        _fit(fig)
        fig.savefig(path, dpi=100, pil_kwargs={"compress_level": 1})  # zlib level 6: 2x the encode time
    finally:
        plt.close(fig)
