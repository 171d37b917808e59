"""The figures draw the data they are given."""

import math

import matplotlib.colors
import numpy as np

import sloshdyn
from sloshdyn import plotting


def test_plots_draw_the_simulation(tmp_path, fig12):
    p = fig12.replace(rho=0.513)
    period = 2 * math.pi / p.rho
    sim = sloshdyn.simulate(p, 40 * period, n_out=40 * 16 + 1)
    fig = plotting.time_history(sim, ("x1", "u1", "impact_force"))
    assert np.array_equal(fig.axes[1].lines[0].get_ydata(), sim.u[0])
    fig.savefig(tmp_path / "history.png")
    fig = plotting.phase_plane(sim, "x1", rho=p.rho)
    section = fig.axes[0].lines[1].get_xdata()
    assert len(section) == 41 and np.allclose(section, sim.x1[::16])
    line = sloshdyn.spectrum(sim.x1, period / 16)
    omega, amp = line.omega, line.amplitude
    plotting.spectrum(omega, amp, marks=(p.rho, 3 * p.rho)).savefig(tmp_path / "spectrum.png")
    assert (tmp_path / "history.png").stat().st_size > 1000


def test_sweep_plot_separates_up_and_down(fig12):
    quick = sloshdyn.Steady(transient_periods=20, settle_tol=0, window_periods=16)
    sw = sloshdyn.frequency_sweep(fig12, sloshdyn.sweep_values(0.50, 0.52, 3, "both"), steady=quick)
    fig = plotting.sweep(sw)
    up, down = fig.axes[0].lines[:2]
    assert list(up.get_xdata()) == [0.50, 0.51, 0.52]
    assert list(down.get_xdata()) == [0.52, 0.51, 0.50]


def test_response_plots_split_stable_and_unstable():
    p = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=math.pi / 4,
                            gamma=0.001, A=0.00075)
    r = sloshdyn.frequency_response(p, (0.49, 0.53))
    fig = plotting.frequency_response(r)
    styles = {line.get_linestyle() for line in fig.axes[0].lines}
    assert {"-", "--"} <= styles               # both stable and unstable parts are drawn
    dashed = np.concatenate([l.get_xdata() for l in fig.axes[0].lines if l.get_linestyle() == "--"])
    unstable = r.table["rho"][r.table["stable"] == 0]
    assert np.all(np.isin(unstable, dashed))
    fig = plotting.routh_delta3(r, zoom=(0.508, 0.511))
    assert len([l for l in fig.axes[0].lines if l.get_linestyle() == ":"]) == 2   # two Hopf points


def test_response_spectrum_returns_its_figure():
    # the module's promise: every function returns the matplotlib Figure (this one returned None)
    from matplotlib.figure import Figure
    quake = sloshdyn.GroundMotion.harmonic(0.2, 0.5)
    periods = np.array([0.5, 1.0, 2.0, 4.0])
    fig = plotting.response_spectrum(quake.response_spectrum(periods), marks=[2.0])
    assert isinstance(fig, Figure)
    psa, sd = (ax.lines[0].get_ydata() for ax in fig.axes)
    # pseudo-spectral acceleration (drawn in g) = (2 pi/T)^2 x spectral displacement
    assert np.allclose(psa * 9.80665, (2 * np.pi / periods) ** 2 * sd, rtol=1e-12)
    assert [line.get_xdata()[0] for ax in fig.axes for line in ax.lines[1:]] == [2.0, 2.0]


def _paper_figure(monkeypatch, tmp_path, number):
    """The matplotlib figure `reproduce` saves for Fig `number` (quick)."""
    from sloshdyn import figures
    saved = {}

    def keep(fig, path):
        saved[path.name] = fig
    monkeypatch.setattr(figures, "save_figure", keep)
    figures.FIGURES[number](tmp_path, quick=True)
    return saved[f"fig{number}.png"]


def _style(line):
    return (line.get_linestyle(), line.get_marker(), matplotlib.colors.to_hex(line.get_color()))


def test_fig12_legend_names_every_kind_of_curve(monkeypatch, tmp_path):
    """Issue 44 item 11: Fig 12's legend named only the direct simulation; now every style drawn
    (stable solid, unstable dashed, folds, Hopf points, simulation crosses) has its entry."""
    fig = _paper_figure(monkeypatch, tmp_path, "12")
    for ax in fig.axes:
        drawn = {_style(line) for line in ax.get_lines() if len(line.get_xdata())}
        legend = ax.get_legend()
        assert legend is not None
        named = {_style(h) for h in legend.legend_handles}
        assert drawn == named, (drawn, named)
        texts = {t.get_text() for t in legend.get_texts()}
        assert {"stable", "unstable", "fold", "Hopf point", "direct simulation"} <= texts


def _overlapping_labels(ax, renderer):
    boxes = [t.get_window_extent(renderer) for t in ax.get_xticklabels()
             if t.get_visible() and t.get_text()]
    return [(a, b) for i, a in enumerate(boxes) for b in boxes[i + 1:] if a.overlaps(b)]


def test_fig13_x_labels_do_not_overlap(monkeypatch, tmp_path):
    """Issue 44 item 11: the zoom's labels 0.50850 ... 0.51050 ran into each other; now no two
    tick labels of either panel overlap, drawn at the saved size."""
    fig = _paper_figure(monkeypatch, tmp_path, "13")
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    for ax in fig.axes:
        assert len([t for t in ax.get_xticklabels() if t.get_text()]) >= 3
        assert _overlapping_labels(ax, renderer) == []
