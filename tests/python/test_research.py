"""The research toolkit (issue 27): the Lyapunov spectrum of the full equations against
Liouville's formula (the sum of the exponents is the mean trace of the Jacobian along the run,
integrated here by scipy) and Floquet theory (on a periodic orbit the exponents are log|mu|/T of
the multipliers of the shooting's monodromy matrix)."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import sloshdyn
from sloshdyn import Lyapunov

FIG12 = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=math.pi / 4,
                            gamma=0.001, A=0.00075, rho=0.50)


def kaplan_yorke(exponents):
    """D = k + (l1 + .. + lk)/|l_{k+1}|, k the largest count with a partial sum >= 0."""
    l = np.sort(exponents)[::-1]
    partial = np.cumsum(l)
    if l[0] < 0:
        return 0.0
    if partial[-1] >= 0:
        return float(len(l))
    k = int(np.max(np.nonzero(partial >= 0)[0])) + 1
    return k + partial[k - 1] / abs(l[k])


def test_spectrum_sum_is_the_mean_divergence_along_the_run():
    """Liouville: l1 + .. + l4 = (1/t) int tr J dtau over the measured run (from tau = 0 here,
    transient_periods = 0), tr J along the trajectory from scipy's DOP853, the trace itself
    checked against central differences of y'."""
    p = FIG12.replace(rho=0.509615)                    # Fig 14: the beat, from rest
    n = 40
    spectrum = sloshdyn.lyapunov_spectrum(p, lyapunov=Lyapunov(transient_periods=0, n_periods=n))
    assert spectrum.exponents.shape == (4,) and spectrum.history.shape == (4, n)

    def field(tau, z):
        motion = sloshdyn.equations_of_motion(p, tau, z[:4])
        return np.concatenate([motion.dydt, [np.trace(motion.jacobian)]])

    t_end = n * 2 * math.pi / p.rho
    run = solve_ivp(field, (0, t_end), np.zeros(5), method="DOP853", rtol=1e-9, atol=1e-12)
    divergence = run.y[4, -1] / t_end
    assert spectrum.sum == pytest.approx(divergence, rel=1e-3)   # measured 1.4e-8 (300 periods)

    y, tau, h = run.y[:4, run.y.shape[1] // 2], run.t[run.y.shape[1] // 2], 1e-6
    trace = sum((sloshdyn.equations_of_motion(p, tau, y + h * e).dydt[i]
                 - sloshdyn.equations_of_motion(p, tau, y - h * e).dydt[i]) / (2 * h)
                for i, e in enumerate(np.eye(4)))
    assert np.trace(sloshdyn.equations_of_motion(p, tau, y).jacobian) == pytest.approx(trace,
                                                                                       rel=1e-6)


def test_spectrum_on_a_periodic_orbit_is_log_floquet_over_period():
    """On a stable periodic orbit the exponents are log|mu|/T (Floquet). The multipliers come in
    two complex pairs: the QR method splits a pair's common exponent with an error bounded over
    the run (O(1/t)), while the sum over the pair (the growth of the invariant plane) converges
    at once: each exponent to 1e-4 absolute, each pair's sum to 1e-4 relative."""
    p = FIG12.replace(rho=0.513, gamma=0.05, A=0.05)   # damped, so the run converges fast
    orbit = sloshdyn.periodic_orbit(p, sloshdyn.steady_state(p).y_end)
    floquet = np.sort(np.log(np.abs(orbit.multipliers)) * p.rho / (2 * math.pi))[::-1]
    spectrum = sloshdyn.lyapunov_spectrum(p, orbit.y0,
                                          lyapunov=Lyapunov(transient_periods=200, n_periods=1000))
    exponents = spectrum.exponents
    assert np.all(np.abs(exponents - floquet) < 1e-4)               # measured 1.9e-5
    assert exponents[0] + exponents[1] == pytest.approx(floquet[0] + floquet[1], rel=1e-4)
    assert exponents[2] + exponents[3] == pytest.approx(floquet[2] + floquet[3], rel=1e-4)
    assert spectrum.kaplan_yorke == 0.0                             # all negative: a point


@pytest.mark.parametrize("p, y0, n", [
    (FIG12.replace(rho=0.509615), None, 4),                       # from rest, short
    (FIG12.replace(rho=0.513, gamma=0.05, A=0.05), None, 300),    # two complex pairs
    (FIG12.replace(rho=0.513, A=2.0), None, 20)])                 # Fig 17, chaotic, short
def test_spectrum_is_sorted_with_its_history(p, y0, n):
    """Issue 44, item 9: the exponents come sorted, largest first (docs/model.md: l1 >= .. >=
    l4), whatever the QR columns' order at the end of the run, and the history's rows follow
    them (its last column is the exponents)."""
    spectrum = sloshdyn.lyapunov_spectrum(p, y0, lyapunov=Lyapunov(transient_periods=0,
                                                                   n_periods=n))
    assert np.all(np.diff(spectrum.exponents) <= 0), spectrum.exponents
    assert np.array_equal(spectrum.history[:, -1], spectrum.exponents)
    assert spectrum.kaplan_yorke == pytest.approx(kaplan_yorke(spectrum.exponents), rel=1e-12)


def test_largest_of_the_spectrum_is_the_largest_exponent():
    """The first QR column is Benettin's single tangent vector (same start direction, only the
    step sequence differs: the error norm covers four columns instead of one)."""
    p = FIG12.replace(rho=0.513)
    y0 = sloshdyn.periodic_orbit(p, sloshdyn.steady_state(p).y_end).y0
    settings = Lyapunov(transient_periods=0, n_periods=50, renormalise_every=5)
    spectrum = sloshdyn.lyapunov_spectrum(p, y0, lyapunov=settings)
    largest = sloshdyn.lyapunov_exponent(p, y0, lyapunov=settings).exponent
    assert spectrum.exponents[0] == pytest.approx(largest, rel=1e-6)


def test_chaotic_spectrum_and_kaplan_yorke_dimension():
    """Fig 17 (rho = 0.513, A = 2), chaotic: the largest exponent is positive, the sum negative
    (dissipation), and the Kaplan-Yorke dimension is its definition on the sorted exponents
    (computed here), between 1 and 4."""
    p = FIG12.replace(rho=0.513, A=2.0)
    y0 = sloshdyn.steady_state(p, steady=sloshdyn.Steady(max_transient_periods=2000)).y_end
    spectrum = sloshdyn.lyapunov_spectrum(p, y0, lyapunov=Lyapunov(transient_periods=100,
                                                                   n_periods=500))
    assert spectrum.exponents[0] > 0.05 and spectrum.sum < 0
    assert spectrum.kaplan_yorke == pytest.approx(kaplan_yorke(spectrum.exponents), rel=1e-12)
    assert 1 < spectrum.kaplan_yorke < 4


def test_lyapunov_settings_are_checked():
    with pytest.raises(sloshdyn.InputError, match="n_periods"):
        sloshdyn.lyapunov_spectrum(FIG12, lyapunov=Lyapunov(n_periods=7, renormalise_every=2))
    with pytest.raises(sloshdyn.InputError, match="lyapunov"):
        sloshdyn.lyapunov_spectrum(FIG12, lyapunov=(1, 2, 3))


def test_namelist_spectrum_runs_the_same_spectrum(tmp_path):
    """&lyapunov spectrum = .true.: the executable writes lyapunov_spectrum.csv, whose rows are
    the running estimates of sloshdyn.lyapunov_spectrum with the same settings (one reader, one
    core), and whose last row sums to the mean divergence (checked by scipy above)."""
    from conftest import run, write
    from test_one_reader import MODEL, sys_exe
    text = (MODEL + "&excitation A = 0.00075, rho = 0.509615 /\n&analysis kind = 'lyapunov' /\n"
            "&lyapunov spectrum = .true., transient_periods = 20, n_periods = 40, "
            "renormalise_every = 2 /\n&output directory = 'out' /\n")
    write(tmp_path, text)
    exe = run(sys_exe(), "input.nml", tmp_path)
    assert exe.returncode == 0, exe.stderr
    assert "Kaplan-Yorke dimension" in exe.stdout
    table = np.loadtxt(tmp_path / "out" / "lyapunov_spectrum.csv", delimiter=",", skiprows=1)
    spectrum = sloshdyn.lyapunov_spectrum(FIG12.replace(rho=0.509615), lyapunov=Lyapunov(
        transient_periods=20, n_periods=40, renormalise_every=2))
    assert np.array_equal(table[:, 0], spectrum.periods)
    assert np.array_equal(table[:, 1:].T, spectrum.history)
    assert np.array_equal(table[-1, 1:], spectrum.exponents)


# ---- the beats continued: limit cycles of the 3:1 slow flow ----------------------------------

@pytest.fixture(scope="module")
def beats():
    from sloshdyn.figures import FIG12 as fig12
    return fig12, sloshdyn.slow_flow_cycles(fig12, (0.49, 0.53))


def test_beat_branch_joins_the_two_hopf_points_of_fig12(beats):
    """From the Fig 14 cycle (rho = 0.509615) the branch runs down to one Hopf point of the
    steady states and up to the other (the ends stop hopf_gap = 1e-3 of the interval short of
    them), stable all along, with no fold, period doubling or Neimark-Sacker point between."""
    fig12, beats = beats
    hopf = sorted(s.rho for s in sloshdyn.frequency_response(fig12, (0.49, 0.53)).special_points
                  if s.kind == "hopf")
    assert beats.ends == ("hopf", "hopf")
    gap = 1e-3 * (hopf[1] - hopf[0])
    assert beats.rho[0] == pytest.approx(hopf[0] + gap, abs=1e-12)
    assert beats.rho[-1] == pytest.approx(hopf[1] - gap, abs=1e-12)
    assert [s.kind for s in beats.special_points] == ["hopf", "hopf"]
    assert np.all(np.diff(beats.rho) > 0) and beats.stable.all()
    trivial = beats.multipliers[np.arange(len(beats.rho)),
                                np.argmin(np.abs(beats.multipliers - 1), axis=1)]
    assert np.all(np.abs(trivial - 1) < 1e-6)          # the flow direction


def test_beat_period_along_the_branch_is_the_one_point_cycle(beats):
    """At rho = 0.509615 the period is the one-point slow_flow_cycle value (233.7648 forcing
    periods, Fig 14); at other points of the branch too (slow_flow_cycle integrates from rest
    and shoots with a section: an independent route to the same cycle)."""
    fig12, beats = beats
    k = int(np.argmin(np.abs(beats.rho - 0.509615)))
    assert beats.rho[k] == 0.509615
    assert beats.beat_periods[k] == pytest.approx(233.7648, rel=1e-6)
    assert beats.beat_periods[k] == pytest.approx(sloshdyn.slow_flow_cycle(fig12).beat_periods,
                                                  rel=1e-9)
    for k in (5, len(beats.rho) - 8):
        one = sloshdyn.slow_flow_cycle(fig12.replace(rho=beats.rho[k]))
        assert beats.beat_periods[k] == pytest.approx(one.beat_periods, rel=1e-6)  # meas. 3e-12


def test_beat_period_tends_to_the_hopf_frequency(beats):
    """Near a Hopf point the cycle is the linear oscillation of the Hopf pair: its period tends
    to 2 pi/omega (omega = sqrt(C3/C1) of the steady state's Routh-Hurwitz coefficients), in
    forcing periods rho/omega; the last three points extrapolated (quadratic in rho) to the
    Hopf point give it to 1e-5 (measured 7e-8), and each end is nearer to it than the point
    before."""
    fig12, beats = beats
    low, high = beats.special_points[0], beats.special_points[-1]
    for end, hopf in ((slice(0, 3), low), (slice(-1, -4, -1), high)):
        rho, period = beats.rho[end], beats.beat_periods[end]
        expected = hopf.rho / next(s.frequency for s in sloshdyn.frequency_response(
            fig12, (0.49, 0.53)).special_points if s.kind == "hopf" and s.rho == hopf.rho)
        assert hopf.beat_periods == pytest.approx(expected, rel=1e-15)
        assert np.polyval(np.polyfit(rho, period, 2), hopf.rho) == pytest.approx(expected,
                                                                                   rel=1e-5)
        assert abs(period[0] - expected) < abs(period[1] - expected) < abs(period[2] - expected)
        assert abs(period[0] / expected - 1) < 1e-3


def test_beat_cycles_solve_eq53_by_scipy(beats):
    """Every few points: eq (53) typed in numpy (test_response.complex_slow_flow) integrated by
    scipy's DOP853 from the cycle's point over its period returns to it; the point lies where
    Re B1 is extremal (the phase condition)."""
    from scipy.integrate import solve_ivp
    from test_response import complex_slow_flow
    fig12, beats = beats
    coefficients = sloshdyn.modal_coefficients(fig12)
    for k in range(0, len(beats.rho), 10):
        f = complex_slow_flow(coefficients, beats.rho[k], fig12.A)
        x = beats.x[k]
        run = solve_ivp(f, (0, beats.period[k]), x, method="DOP853", rtol=1e-11, atol=1e-14)
        assert run.y[:, -1] == pytest.approx(x, abs=1e-7 * np.max(np.abs(x)))
        assert abs(f(0, x)[0]) < 1e-9 * np.max(np.abs(f(0, run.y[:, len(run.t) // 3])))
        assert beats.amplitudes[k, 1] == pytest.approx(np.max(np.hypot(run.y[0], run.y[1])),
                                                       rel=1e-3)


def test_no_beat_where_the_slow_flow_settles():
    """Above the Hopf interval the steady states of Fig 12 are stable: no cycle, said so."""
    from sloshdyn.figures import FIG12 as fig12
    with pytest.raises(sloshdyn.ConvergenceError, match="no cycle: the slow flow settles"):
        sloshdyn.slow_flow_cycles(fig12, (0.511, 0.53))


def test_beat_plot_draws_the_cycles_over_the_response(beats, tmp_path):
    """The band is the cycles' min..max |B1| (and |B2|); the beat period panel ends on the Hopf
    points' rho/omega; every axis says its unit."""
    fig12, cycles = beats
    from sloshdyn.research import plot_beats
    response = sloshdyn.frequency_response(fig12, (0.505, 0.515))
    fig = plot_beats(response, cycles)
    band = fig.axes[0].collections[0].get_paths()[0].vertices
    assert np.isclose(band[:, 1].max(), cycles.amplitudes[:, 1].max())
    assert np.isclose(band[:, 1].min(), cycles.amplitudes[:, 0].min())
    assert np.array_equal(fig.axes[2].lines[0].get_ydata(), cycles.beat_periods)
    assert all("[" in ax.get_ylabel() for ax in fig.axes) and "[" in fig.axes[2].get_xlabel()
    fig.savefig(tmp_path / "beats.png")
    assert (tmp_path / "beats.png").stat().st_size > 1000


def test_beat_continued_in_A_from_its_hopf_point_to_the_range_end():
    """In A at rho = 0.509615 the steady states of Fig 12 have one Hopf point below
    A = 0.00075: the branch runs from it (period tending to rho/omega there, quadratic
    extrapolation to 1e-5) to the range's end, the one-point cycle's period on the way."""
    from sloshdyn.figures import FIG12 as fig12
    beats = sloshdyn.slow_flow_cycles(fig12, A_range=(1e-4, 0.0009))
    assert beats.ends == ("hopf", "range end") and beats.parameter == "A"
    assert beats.A[-1] == 0.0009 and np.all(beats.rho == fig12.rho)
    hopf = beats.special_points[0]
    assert hopf.kind == "hopf" and beats.A[0] > hopf.A
    assert np.polyval(np.polyfit(beats.A[:3], beats.beat_periods[:3], 2),
                      hopf.A) == pytest.approx(hopf.beat_periods, rel=1e-5)
    k = 5
    one = sloshdyn.slow_flow_cycle(fig12.replace(A=beats.A[k]))
    assert beats.beat_periods[k] == pytest.approx(one.beat_periods, rel=1e-6)   # meas. 6e-12
