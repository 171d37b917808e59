"""The figures draw the data they are given."""

import math

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
