"""The figures of the work–precision benchmark: error versus wall time per method (heyoka's
compile or cache-load time shown apart), and the drift of the integrals over a long run."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from chaplygin_nd.bench.report import save_figure


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def figure(path: Path, rows, title: str) -> None:
    """Log–log error against seconds, one curve per (scene, method); each point labelled with its
    setting. heyoka: filled markers = run alone (warm), hollow markers joined by a dotted line =
    run + this process's compile or cache load."""
    import matplotlib.ticker

    plt = _plt()
    fig, ax = plt.subplots(figsize=(8, 5.2))
    several = len({r.scene for r in rows}) > 1

    def key(r):
        return f"{r.scene.split()[0]}: {r.method}" if several else r.method

    for label in dict.fromkeys(key(r) for r in rows):
        rs = [r for r in rows if key(r) == label]
        xs = [max(r.seconds, 1e-6) for r in rs]
        ys = [max(r.error, 1e-40) for r in rs]
        (line,) = ax.loglog(xs, ys, "o-", label=label, ms=4)
        for r, x, y in zip(rs, xs, ys, strict=True):
            ax.annotate(r.setting, (x, y), fontsize=6, xytext=(3, 3), textcoords="offset points")
        if any(r.compile_seconds for r in rs):
            ax.loglog([x + r.compile_seconds for x, r in zip(xs, rs, strict=True)], ys, "o:",
                      mfc="none", color=line.get_color(), ms=4, lw=0.8,
                      label=f"{label} incl. compile/load")
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_xlabel("wall time [s] (min of runs)")
    ax.set_ylabel("max error against the reference")
    ax.set_title(title, fontsize=9)
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    save_figure(fig, path)
    plt.close(fig)


def drift_figure(path: Path, t: np.ndarray, drifts: dict, title: str) -> None:
    """Semilog drift against t: for each method, |H(t) - H(0)| (solid) and max |p(t) - p(0)|
    (dashed); ``drifts[label] = (H_drift, p_drift)`` arrays over ``t``."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(8, 4.8))
    for label, (dH, dp) in drifts.items():
        (line,) = ax.semilogy(t, dH + 1e-18, label=f"{label}: |H(t) - H(0)|")
        ax.semilogy(t, dp + 1e-18, "--", color=line.get_color(), label=f"{label}: max |p(t) - p(0)|")
    ax.set_xlabel("t")
    ax.set_ylabel("drift (+1e-18 to show zeros)")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(True, which="both", lw=0.3)
    fig.tight_layout()
    save_figure(fig, path)
    plt.close(fig)
