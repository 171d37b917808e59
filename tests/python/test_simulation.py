"""Direct simulation against independent sources: the energy of eq (6)-(7), scipy's DOP853 on
eq (10), the natural frequencies of eq (28), and the paper's Fig 14-15 observations."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import sloshdyn
from test_model import eq10_numpy


def energy(p, y):
    """Total energy of eq (6)-(7) without base motion, divided by M L^2 omega^2 theta0^2."""
    x1, v1, x2, v2 = y
    t0 = p.theta0
    return (0.5 * v2**2 + 0.5 * p.mu1 * p.s1**2 * v1**2
            + p.mu1 * p.s1 * v1 * v2 * np.cos(t0 * (x1 + x2))
            + 0.5 * p.kappa * x2**2 + p.s1 * np.cos(t0 * x2) / t0**2
            - p.mu1 * p.s1**2 * np.cos(t0 * x1) / t0**2
            + p.beta * p.mu1 * p.s1**2 * x1 ** (2 * p.n) / (2 * p.n * t0))


@pytest.mark.parametrize("y0", [(0.05, 0.0, 0.02, 0.0), (1.3, 0.0, 0.1, 0.0)],
                         ids=["small", "impacting"])
def test_energy_is_conserved(fig12, y0):
    p = fig12.replace(gamma=0.0, delta=0.0, A=0.0, beta=1.0)
    omega1 = sloshdyn.linear_modes(p).omega1
    t_end = 1000 * 2 * math.pi / omega1
    drifts = []
    for rtol in (1e-8, 1e-10):
        sim = sloshdyn.simulate(p, t_end, y0, n_out=2001,
                                integration=sloshdyn.Integration(rtol=rtol, atol=rtol * 1e-3))
        e = energy(p, sim.y)
        drifts.append(np.max(np.abs(e - e[0])) / abs(e[0]))
    if y0[0] > 1:   # the run really reaches the walls
        assert np.max(np.abs(sim.x1)) > 1
    # measured: drift ~ 5 rtol (small) and ~ 3e3 rtol (impacting: steep x1^11 wall, 1000 periods)
    assert drifts[1] < 1e-6
    assert 30 < drifts[0] / drifts[1] < 300     # the error is proportional to the tolerance


def test_agrees_with_scipy_dop853(fig12):
    p = fig12.replace(beta=1.0, delta=0.05)   # Fig 14 case, with impacts and dissipation active
    y0 = np.array([0.3, 0.0, 0.1, 0.0])
    t_end = 50 * 2 * math.pi / p.rho
    tau = np.linspace(0, t_end, 11)
    ref = solve_ivp(lambda t, y: eq10_numpy(p, t, y), (0, t_end), y0, method="DOP853",
                    rtol=1e-12, atol=1e-14, t_eval=tau)
    sim = sloshdyn.simulate(p, t_end, y0, tau_out=tau,
                            integration=sloshdyn.Integration(rtol=1e-12, atol=1e-14))
    assert np.allclose(sim.y, ref.y, rtol=0, atol=1e-8)


def test_free_vibration_shows_the_natural_frequencies(fig12):
    p = fig12.replace(gamma=0.0, A=0.0)
    modes = sloshdyn.linear_modes(p)
    omega1, omega2 = modes.omega1, modes.omega2
    dt = 0.5
    sim = sloshdyn.simulate(p, 40000.0, (1e-3, 0.0, 1e-3, 0.0), n_out=80001)
    line = sloshdyn.spectrum(sim.x1, dt)
    omega, amplitude = line.omega, line.amplitude
    resolution = 2 * math.pi / 40000.0
    peaks = omega[np.argsort(amplitude)[::-1]]
    top = [peaks[0]]
    for w in peaks[1:]:
        if all(abs(w - t) > 5 * resolution for t in top):
            top.append(w)
        if len(top) == 2:
            break
    assert sorted(top) == pytest.approx([omega1, omega2], abs=2 * resolution)


def test_fig15_spectral_lines_at_rho_and_3rho(fig12):
    p = fig12.replace(rho=0.513, beta=10.0, delta=0.1)
    st = sloshdyn.steady_state(p)
    assert st.motion == "periodic" and st.period == 1
    assert 0.005 < st.max_x1 < 0.05                     # paper: x1 of order 0.01
    period = 2 * math.pi / p.rho
    n_periods, per = 256, 32
    tau = np.arange(n_periods * per + 1) * period / per
    sim = sloshdyn.simulate(p, tau[-1], st.y_end, tau_out=tau)
    line = sloshdyn.spectrum(sim.x1[:-1], period / per, window=None)
    omega, amplitude = line.omega, line.amplitude
    # whole periods, no window: lines fall on bins; the two largest are rho and 3 rho
    top = omega[np.argsort(amplitude)[::-1][:2]]
    assert sorted(top) == pytest.approx([p.rho, 3 * p.rho], rel=1e-9)


def test_small_amplitude_does_not_depend_on_beta_and_delta(fig12):
    base = fig12.replace(rho=0.513)
    amplitudes = [sloshdyn.steady_state(base.replace(beta=b, delta=d)).max_x1
                  for b, d in ((0.0, 0.0), (1.0, 0.0), (10.0, 0.1), (100.0, 1.0))]
    assert max(amplitudes) - min(amplitudes) < 1e-4 * max(amplitudes)


def test_fig14_beats(fig12):
    p = fig12.replace(beta=10.0, delta=0.1)    # rho = 0.509615, between the Hopf points
    st = sloshdyn.steady_state(p, steady=sloshdyn.Steady(settle_tol=0, transient_periods=5000,
                                                         window_periods=1500))
    assert st.motion == "quasi-periodic" and st.spread > 0.1   # a closed curve, not a point
    # the beat two ways: the full equations' Poincare points turning about their closed curve,
    # and the limit cycle of the slow flow (first order in eps, with eps^2 = the detuning
    # (omega2 - 3 omega1)/omega1 of sec 4.2, so the two agree to O(eps) ~ 10 %)
    full = sloshdyn.beat_period(st.poincare)
    slow = sloshdyn.slow_flow_cycle(p)
    modes = sloshdyn.linear_modes(p)
    w1, w2 = modes.omega1, modes.omega2
    eps = math.sqrt(abs(w2 - 3 * w1) / w1)
    assert full == pytest.approx(slow.beat_periods, rel=eps)
    # the envelope of u1 beats with that period: its autocorrelation peaks one beat later
    period = 2 * math.pi / p.rho
    sim = sloshdyn.simulate(p, 1500 * period, st.y_end, n_out=1500 * 32 + 1)
    envelope = np.abs(sim.u[0][:-1]).reshape(1500, 32).max(axis=1)
    envelope -= envelope.mean()
    lags = np.arange(int(0.5 * full), int(1.5 * full))
    correlation = [np.dot(envelope[:-k], envelope[k:]) / (envelope.size - k) for k in lags]
    assert abs(lags[int(np.argmax(correlation))] - full) <= 2


def test_beat_period_of_points_turning_at_a_known_rate():
    """Points on a closed, non-circular curve advancing by a known rotation number nu per
    forcing period, at an uneven angular speed: the beat is 1/nu forcing periods."""
    nu = 1 / 237.3
    k = np.arange(3000)
    phase = 2 * math.pi * nu * k + 0.3 * np.sin(2 * math.pi * nu * k)    # uneven, monotone
    points = np.array([0.5 + np.cos(phase) * (1 + 0.2 * np.cos(2 * phase)), 2 * np.sin(phase)])
    assert sloshdyn.beat_period(points) == pytest.approx(1 / nu, rel=1e-4)
    with pytest.raises(sloshdyn.InputError, match="two whole turns"):
        sloshdyn.beat_period(points[:, :300])


def test_integration_failure_keeps_the_partial_history(fig12):
    with pytest.raises(sloshdyn.IntegrationError, match="max_steps") as info:
        sloshdyn.simulate(fig12, 1000.0, n_out=101, integration=sloshdyn.Integration(max_steps=50))
    partial = info.value.partial
    reached = partial.tau_reached
    assert 0 < reached < 1000
    assert np.all(np.isfinite(partial.y[:, partial.tau <= reached]))
    assert np.all(np.isnan(partial.y[:, partial.tau > reached]))


def test_sweep_carries_the_state(fig12):
    p = fig12.replace(beta=10.0, delta=0.1)
    steady = sloshdyn.Steady(transient_periods=300, settle_tol=0, window_periods=20)
    sweep = sloshdyn.frequency_sweep(p, [0.50, 0.52], steady=steady)
    first = sloshdyn.steady_state(p.replace(rho=0.50), steady=steady)
    second = sloshdyn.steady_state(p.replace(rho=0.52), first.y_end, steady=steady)
    assert sweep.points[0].max_x1 == first.max_x1
    assert sweep.points[1].max_x1 == second.max_x1         # bit for bit: started from first.y_end
    assert np.array_equal(sweep.y_final, second.y_end)


def test_dop853_method_agrees_with_rk45_in_fewer_steps(fig12):
    p = fig12.replace(beta=10.0, delta=0.1, A=0.3)
    t_end = 100 * 2 * math.pi / p.rho
    tau = np.linspace(0, t_end, 11)
    rk45 = sloshdyn.simulate(p, t_end, (0.3, 0, 0.1, 0), tau_out=tau, integration=sloshdyn.Integration(
        rtol=1e-12, atol=1e-14, method="rk45"))
    dop853 = sloshdyn.simulate(p, t_end, (0.3, 0, 0.1, 0), tau_out=tau, integration=sloshdyn.Integration(
        rtol=1e-12, atol=1e-14, method="dop853"))
    assert np.allclose(dop853.y, rk45.y, rtol=0, atol=1e-8)
    assert dop853.n_accepted < rk45.n_accepted / 3
    with pytest.raises(sloshdyn.InputError, match="method"):
        sloshdyn.simulate(p, 10.0, integration=sloshdyn.Integration(method="euler"))


def test_vern9_agrees_with_dop853_and_auto_runs_the_method_it_reports(fig12):
    """Verner's 9(8) (its interpolant at 11 output times) agrees with DOP853 at rtol 1e-12
    within the tolerance's reach and takes fewer steps; the default method 'auto' runs exactly
    the pair it reports (bit for bit the same history as that method asked for by name), and
    picks a higher-order pair for a tighter tolerance."""
    p = fig12.replace(beta=10.0, delta=0.1, A=0.3)
    t_end = 100 * 2 * math.pi / p.rho
    tau = np.linspace(0, t_end, 11)
    y0 = (0.3, 0, 0.1, 0)
    dop853 = sloshdyn.simulate(p, t_end, y0, tau_out=tau, integration=sloshdyn.Integration(
        rtol=1e-12, atol=1e-14, method="dop853"))
    vern9 = sloshdyn.simulate(p, t_end, y0, tau_out=tau, integration=sloshdyn.Integration(
        rtol=1e-12, atol=1e-14, method="vern9"))
    assert np.allclose(vern9.y, dop853.y, rtol=0, atol=1e-8)
    assert vern9.n_accepted < dop853.n_accepted
    used = []
    for rtol in (1e-3, 1e-7, 1e-12):
        auto = sloshdyn.simulate(p, t_end, y0, tau_out=tau,
                                 integration=sloshdyn.Integration(rtol=rtol, atol=rtol * 1e-3))
        named = sloshdyn.simulate(p, t_end, y0, tau_out=tau, integration=sloshdyn.Integration(
            rtol=rtol, atol=rtol * 1e-3, method=auto.method))
        assert named.method == auto.method
        assert np.array_equal(auto.y, named.y) and auto.n_rhs == named.n_rhs
        used.append(auto.method)
    order = ["rk45", "dop853", "vern9"]
    assert [order.index(m) for m in used] == sorted(order.index(m) for m in used)
    assert used[0] != used[-1]
