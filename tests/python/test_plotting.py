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
    omega, amp = sloshdyn.spectrum(sim.x1, period / 16)
    plotting.spectrum(omega, amp, marks=(p.rho, 3 * p.rho)).savefig(tmp_path / "spectrum.png")
    assert (tmp_path / "history.png").stat().st_size > 1000


def test_sweep_plot_separates_up_and_down(fig12):
    quick = sloshdyn.Steady(transient_periods=20, settle_tol=0, window_periods=16)
    sw = sloshdyn.frequency_sweep(fig12, sloshdyn.sweep_values(0.50, 0.52, 3, "both"), steady=quick)
    fig = plotting.sweep(sw)
    up, down = fig.axes[0].lines[:2]
    assert list(up.get_xdata()) == [0.50, 0.51, 0.52]
    assert list(down.get_xdata()) == [0.52, 0.51, 0.50]
