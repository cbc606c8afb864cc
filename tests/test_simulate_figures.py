"""Scene figures carry what a reader needs: legends, labelled axes, named quantities, only the
independent entries, no artificial floor on log axes, the whole ensemble, a real contact-path
picture and titles that do not collide. Checked on the matplotlib artists, not on pixels."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from chaplygin_nd.simulate.scene import cli  # noqa: E402
from chaplygin_nd.simulate.scene.figures import REDUCED_NAMES, figure  # noqa: E402
from matplotlib.collections import LineCollection, PolyCollection  # noqa: E402

T = np.linspace(0.0, 5.0, 41)


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def skew_series(n, count=1, seed=0):
    rng = np.random.default_rng(seed)
    A = rng.normal(size=(len(T), count, n, n))
    return A - np.swapaxes(A, -1, -2)


def labelled(ax):
    return bool(ax.get_xlabel()) and bool(ax.get_ylabel())


def no_overlap(fig):
    """The figure title overlaps no axis title, offset text or tick label."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    top = fig._suptitle.get_window_extent(renderer)
    others = []
    for ax in fig.axes:
        others += [ax.title, ax.yaxis.get_offset_text(), ax.xaxis.get_offset_text()]
        others += ax.get_yticklabels()
    return not any(o.get_text() and o.get_visible() and top.overlaps(o.get_window_extent(renderer))
                   for o in others)


@pytest.mark.parametrize("name", ["M", "Omega"])
def test_skew_matrix_shows_only_the_upper_triangle(name):
    n = 5
    fig = figure(name, T, skew_series(n))
    ax = fig.axes[0]
    labels = [line.get_label() for line in ax.get_lines()]
    assert len(labels) == n * (n - 1) // 2
    assert labels[0].endswith("_{12}$") and labels[-1].endswith("_{45}$")
    assert ax.get_legend() is not None and labelled(ax)
    assert no_overlap(fig)


def test_reduced_invariants_are_named_panels():
    rng = np.random.default_rng(1)
    fig = figure("reduced", T, rng.normal(size=(len(T), 1, 7)))
    panels = [ax for ax in fig.axes if ax.axison]
    assert [ax.get_ylabel() for ax in panels] == list(REDUCED_NAMES)
    assert all(ax.get_legend() is not None for ax in panels)
    assert any(ax.get_xlabel() == "t" for ax in panels)


def test_drift_uses_actual_values_on_a_log_axis():
    """Zeros (t = t0, exact rounding) are left out, never raised to a floor such as 1e-300."""
    rng = np.random.default_rng(2)
    d = 10.0 ** rng.uniform(-16, -13, size=(len(T), 1))
    d[0] = 0.0
    d[7] = 0.0
    fig = figure("drift.energy", T, d)
    ax = fig.axes[0]
    assert ax.get_yscale() == "log"
    low, high = ax.get_ylim()
    assert low > 1e-18 and high < 1e-11
    assert "H" in ax.get_ylabel() and ax.get_legend() is not None
    assert no_overlap(fig)


def test_identically_zero_drift_is_named_not_drawn():
    n = 4
    d = np.zeros((len(T), 1, n + 1, 2))
    d[1:, 0, 1, 0] = 1e-15
    fig = figure("drift.p", T, d)
    ax = fig.axes[0]
    texts = [tx.get_text() for tx in ax.get_legend().get_texts()]
    assert any(tx.startswith("identically 0") for tx in texts)
    assert sum(1 for line in ax.get_lines() if len(line.get_xdata())) == 1
    all_zero = figure("drift.gamma_norm2", T, np.zeros((len(T), 1)))
    assert all_zero.axes[0].get_yscale() == "linear"


def test_ensemble_figure_shows_every_member_and_the_band():
    count = 16
    rng = np.random.default_rng(3)
    fig = figure("x", T, rng.normal(size=(len(T), count)))
    ax = fig.axes[0]
    members = [c for c in ax.collections if isinstance(c, LineCollection)]  # one artist for all
    assert len(members) == 1 and len(members[0].get_segments()) == count
    assert len(ax.get_lines()) == 1  # the median
    assert any(isinstance(c, PolyCollection) for c in ax.collections)  # the 5-95 % band
    assert ax.get_legend() is not None and labelled(ax)
    gamma = figure("gamma", T, rng.normal(size=(len(T), count, 3)))
    assert sum(1 for a in gamma.axes if a.axison) == 3 and gamma.legends


@pytest.mark.parametrize("n, kind", [(3, "rectilinear"), (4, "3d"), (6, "3d")])
def test_contact_path_is_a_picture_of_the_path(n, kind):
    c = np.cumsum(np.random.default_rng(n).normal(size=(len(T), 1, n - 1)), axis=0)
    fig = figure("contact_path", T, c)
    path, coords = fig.axes[0], fig.axes[1]
    assert path.name == kind
    assert path.get_xlabel() == "$c_1$" and path.get_ylabel() == "$c_2$"
    # the path's legend: on its axes (2D) or below the panels (a 3D view has no free corner)
    legend = path.get_legend() if kind == "rectilinear" else fig.legends[0]
    assert [t.get_text() for t in legend.get_texts()] == [
        "contact point = centre seen from the plane", "start $t_0$", "end"]
    assert len(coords.get_lines()) == n - 1 and coords.get_legend() is not None
    if n >= 5:
        assert "projected onto $(c_1, c_2, c_3)$" in path.get_title()


def test_orientation_and_zeta_figures():
    n = 4
    g = np.broadcast_to(np.eye(n), (len(T), 1, n, n))
    fig = figure("orientation", T, g)
    assert len(fig.axes) == n * n
    assert fig.axes[0].get_legend() is not None
    z = figure("zeta", T, skew_series(n)[0])
    assert z.axes[0].get_xlabel() and "last row and column vanish" in z.axes[0].get_title()


def test_a_scene_writes_one_png_per_output(tmp_path):
    """The command line draws the figures (closed form: cheap)."""
    scene = tmp_path / "s.toml"
    scene.write_text('n = 4\na = 0.0\nb = 1.0\n[initial]\nfamily = "generic"\nseed = 1\n'
                     '[times]\nt_end = 2.0\nsamples = 11\n'
                     '[outputs]\nwant = ["M", "x", "integrals", "contact_path"]\n')
    assert cli.main([str(scene), "--out", str(tmp_path / "out")]) == 0
    pngs = sorted(p.name for p in (tmp_path / "out").glob("*.png"))
    assert pngs == ["M.png", "contact_path.png", "drift.energy.png", "drift.gamma_norm2.png",
                    "drift.p.png", "x.png"]


@pytest.mark.parametrize("how", ["scene", "option"])
def test_figures_false_or_no_plots_writes_no_png(tmp_path, how):
    """outputs.figures = false in the scene (or --no-plots): the outputs without the figures."""
    scene = tmp_path / "s.toml"
    scene.write_text('n = 4\na = 0.0\nb = 1.0\n[initial]\nfamily = "generic"\nseed = 1\n'
                     '[times]\nt_end = 2.0\nsamples = 11\n[outputs]\nwant = ["M", "x"]\n'
                     + ("figures = false\n" if how == "scene" else ""))
    args = [str(scene), "--out", str(tmp_path / "out")] + (["--no-plots"] if how == "option" else [])
    assert cli.main(args) == 0
    assert not list((tmp_path / "out").glob("*.png"))
    assert (tmp_path / "out" / "M.csv").exists() and (tmp_path / "out" / "x.csv").exists()


def test_figures_must_be_true_or_false(tmp_path, capsys):
    scene = tmp_path / "s.toml"
    scene.write_text('n = 4\na = 0.0\nb = 1.0\n[initial]\nfamily = "generic"\nseed = 1\n'
                     '[times]\nt_end = 2.0\nsamples = 11\n[outputs]\nwant = ["M"]\nfigures = "no"\n')
    assert cli.main([str(scene), "--out", str(tmp_path / "out")]) == 2
    assert "outputs.figures" in capsys.readouterr().err


def test_a_constant_output_gets_a_readable_axis_and_says_so():
    """x is constant on V (Th:Re): the axis is not stretched over 1e-16 and the legend says it."""
    x = np.full((len(T), 1), -0.15492323) + 1e-17 * np.arange(len(T))[:, None]
    ax = figure("x", T, x).axes[0]
    low, high = ax.get_ylim()
    assert high - low > 1e-3
    assert any("constant" in tx.get_text() for tx in ax.get_legend().get_texts())


def test_every_time_series_output_has_a_figure(tmp_path):
    """Every output a model produces as a time series can be drawn (a KeyError here once stopped
    the horizontal closed form after its computation, with a traceback)."""
    scene = tmp_path / "h.toml"
    scene.write_text('n = 5\na = 0.5\nb = 7.0\n[initial]\nfamily = "horizontal"\nseed = 2\n'
                     '[times]\nt_end = 2.0\nsamples = 11\n'
                     '[outputs]\nwant = ["x", "horizontal"]\n')
    assert cli.main([str(scene), "--out", str(tmp_path / "out")]) == 0
    assert sorted(p.name for p in (tmp_path / "out").glob("*.png")) == ["horizontal.png", "x.png"]
    fig = figure("horizontal", T, np.zeros((len(T), 2, 4)) + T[:, None, None])
    assert [ax.get_ylabel() for ax in fig.axes if ax.axison][2:] == ["$A$", "$B$"]


@pytest.mark.parametrize("no_plots", [False, True])
def test_no_plots_leaves_out_the_poincare_figure_too(tmp_path, capsys, no_plots):
    """A figure asked for as an output (poincare.png of the tori scenes) is a figure: --no-plots
    leaves it out as it does the other PNGs, and the summary says it was not drawn."""
    scene = tmp_path / "s.toml"
    scene.write_text('n = 4\na = -0.5\nb = 0.5\n[initial]\nfamily = "generic"\nseed = 3\n'
                     'members = [3, 1]\n[times]\nt_end = 10.0\nsamples = 64\n'
                     '[outputs]\nwant = ["x", "poincare"]\n')
    out = tmp_path / "out"
    assert cli.main([str(scene), "--out", str(out)] + (["--no-plots"] if no_plots else [])) == 0
    pngs = sorted(p.name for p in out.glob("*.png"))
    assert pngs == ([] if no_plots else ["poincare.png", "x.png"])
    assert (out / "x.csv").exists()
    line = next(s for s in capsys.readouterr().out.splitlines() if s.startswith("poincare"))
    assert ("not drawn" in line) == no_plots and ("poincare.png" in line) != no_plots


def _inside(fig) -> bool:
    """Whether everything ``fig`` draws (texts, legends, tick labels shown) lies on the canvas."""
    fig.canvas.draw()
    box = fig.get_tightbbox(fig.canvas.get_renderer())  # inches
    w, h = fig.get_size_inches()
    return box.x0 >= 0 and box.y0 >= 0 and box.x1 <= w and box.y1 <= h


@pytest.mark.parametrize("name,arr", [
    ("drift.energy", 6e-17 * (1 + np.sin(np.arange(41))[:, None] ** 2)),
    ("drift.gamma_norm2", 2.2e-16 * np.abs(np.cos(np.arange(41)))[:, None] + 1e-17),
    ("drift.p", 1e-16 * np.abs(np.sin(np.arange(41 * 12))).reshape(41, 1, 6, 2) + 1e-18),
    ("x", np.sin(T)[:, None]),
    ("M", skew_series(6)),
])
def test_no_label_or_legend_is_cut_at_an_edge(tmp_path, name, arr):
    """What plot() saves has every text inside the canvas (a log axis' wide tick labels pushed
    the y-label out at the left; long legend entries ran out at the right)."""
    from chaplygin_nd.simulate.scene import figures

    fig = figure(name, T, arr)
    figures._fit(fig)
    assert _inside(fig)


def test_numbers_on_dark_zeta_cells_are_white():
    Z = np.array([[[0.0, 1.0, -0.05], [-1.0, 0.0, 0.5], [0.05, -0.5, 0.0]]])
    fig = figure("zeta", T, Z)
    ax = fig.axes[0]
    colours = {t.get_text(): matplotlib.colors.to_hex(t.get_color()) for t in ax.texts}
    assert colours["1"] == colours["-1"] == "#ffffff"  # the darkest red and blue cells
    assert colours["0"] == colours["-0.05"] == "#000000"  # near-white cells
