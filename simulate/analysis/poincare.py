r"""Poincaré sections of $n = 4$ orbits in the reduced invariants, a test that a section is a curve,
and the figure of the scene output ``poincare``.

Section $\Sigma = \{G = 0,\ \dot G < 0\}$: since $\dot x = G/(a+b+2)$ (eq:red-system) these are the
maxima of $x = \gamma_4$. Crossings are located on the cubic through four consecutive samples of
$G$ (bisection on the interpolant) and $(E, \delta)$ is read off the cubics of its samples, so the
interpolation error is $O(dt^4)$. On an invariant 2-torus the section is a closed curve; on a
chaotic orbit of a 5-dimensional level set it is a cloud.
"""

from __future__ import annotations

import numpy as np
from chaplygin_nd.simulate.dynamics import so
from chaplygin_nd.simulate.dynamics.so import reduced_invariants

__all__ = ["reduced_samples", "section", "section_curve_scatter", "figure"]


def reduced_samples(y: np.ndarray, model: str) -> np.ndarray:
    r"""$(A, B, E, G, F_1, x, \delta)$ along one orbit: ``y`` itself for the reduced model, else
    computed from $(M, \gamma)$ (the definitions of Section 5, Reduction by SO(3)); $n = 4$."""
    if model == "reduced":
        return y
    return reduced_invariants(so.unvec(y[:, :6], 4), y[:, 6:10])


def _cubic(vals: np.ndarray, s: float) -> np.ndarray:
    """Lagrange cubic through nodes -1, 0, 1, 2 at s in [0, 1] (vals: (4, ...))."""
    w = np.array([-s * (s - 1) * (s - 2) / 6, (s + 1) * (s - 1) * (s - 2) / 2,
                  -(s + 1) * s * (s - 2) / 2, (s + 1) * s * (s - 1) / 6])
    return np.tensordot(w, vals, axes=1)


def section(r: np.ndarray, coords=(2, 6)) -> np.ndarray:
    r"""Points of $\Sigma$ (see module) along samples ``r`` of shape ``(S, 7)``, in the coordinates
    ``coords`` (default $(E, \delta)$); shape ``(crossings, len(coords))``."""
    G = r[:, 3]
    idx = np.nonzero((G[1:-2] > 0) & (G[2:-1] <= 0))[0] + 1
    out = []
    for i in idx:
        nodes = r[i - 1:i + 3]
        lo, hi = 0.0, 1.0
        for _ in range(50):
            mid = 0.5 * (lo + hi)
            if _cubic(nodes[:, 3], mid) > 0:
                lo = mid
            else:
                hi = mid
        out.append(_cubic(nodes[:, list(coords)], 0.5 * (lo + hi)))
    return np.array(out).reshape(-1, len(coords))


def section_curve_scatter(y: np.ndarray, exp, neighbours: int = 8) -> float:
    r"""How far the section of one orbit is from a curve: coordinates scaled to unit standard
    deviation, then for each point the ratio $\sigma_2/\sigma_1$ of the singular values of its
    ``neighbours`` nearest neighbours (centred); the median. A smooth curve gives a small value
    (its curvature times the point spacing); a 2-dimensional cloud gives $O(1)$. ``nan`` when the
    orbit crosses $\Sigma$ fewer than 20 times."""
    pts = section(reduced_samples(y, exp.model))
    if len(pts) < 20:
        return float("nan")
    pts = (pts - pts.mean(0)) / np.maximum(pts.std(0), 1e-300)
    d = np.linalg.norm(pts[:, None] - pts[None], axis=-1)
    ratios = []
    for i in range(len(pts)):
        near = pts[np.argsort(d[i])[:neighbours + 1]]
        sv = np.linalg.svd(near - near.mean(0), compute_uv=False)
        ratios.append(sv[1] / max(sv[0], 1e-300))
    return float(np.median(ratios))


def figure(path, panels, title: str) -> None:
    r"""Write a PNG: one panel per entry of ``panels`` = ``[(panel title, [(label, points), ...])]``,
    each a scatter of section points $(E, \delta)$."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(panels), figsize=(6.2 * len(panels), 6.2), squeeze=False)
    markers = "o^sDvP"
    for ax, (sub, series) in zip(axes[0], panels):
        for k, (label, pts) in enumerate(series):
            ax.plot(pts[:, 0], pts[:, 1], markers[k % len(markers)], ms=max(5.0 - 1.2 * k, 2.2),
                    alpha=0.85, label=label, mfc="none" if k else None)
        ax.set_xlabel(r"$E = \langle k, q\rangle$")
        ax.set_ylabel(r"$\delta = \langle q, k\times u\rangle$")
        ax.set_title(sub, fontsize=10)
        ax.legend(fontsize=8, markerscale=1.5, loc="upper center", bbox_to_anchor=(0.5, -0.11),
                  ncol=2 if max(len(lab) for lab, _ in series) > 24 else 3, frameon=False)
        ax.grid(alpha=0.3)
    fig.suptitle(title, fontsize=11)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
