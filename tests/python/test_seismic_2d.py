"""Ground motion in two horizontal components (sloshdyn.spatial.seismic_response_2d;
docs/model.md, "Spatial model and swirl").

Independent source: superposition. In the linear range (small records) the response to two
components is the sum of the two planar responses (sloshdyn.seismic_response, the planar
equations), each turned into its direction, at every azimuth of the wall.
"""

import numpy as np
import pytest

import sloshdyn
from sloshdyn import spatial

TANK = sloshdyn.Tank(radius=5.0, liquid_depth=6.0, freeboard=1.0, liquid_density=1000.0,
                     tank_mass=5.0e4, support_frequency=2.0)
# tight tolerances: the spatial and planar integrations take different steps
INTEGRATION = sloshdyn.Integration(rtol=1e-11, atol=1e-20, method="dop853")


def _record(freqs, phases, pga, dt=0.02, duration=16.0):
    t = dt * np.arange(int(round(duration / dt)) + 1)
    a = np.sin(np.pi * t / t[-1])**2 * sum(np.sin(2 * np.pi * f * t + p)
                                           for f, p in zip(freqs, phases))
    return sloshdyn.GroundMotion(dt=dt, acceleration=a * pga / np.max(np.abs(a)), units="m/s^2")


def _pair(pga):
    return (_record((0.2, 0.3, 1.1), (0.0, 1.0, 2.0), pga),
            _record((0.25, 0.33, 0.7), (0.5, -1.0, 0.3), 0.7 * pga))


@pytest.mark.parametrize("azimuth", [0.0, 0.4])
def test_linear_range_is_the_superposition_of_two_planar_runs(azimuth):
    first, second = _pair(1e-4)
    times = sloshdyn.seismic_defaults(TANK, first)
    both = spatial.seismic_response_2d(TANK, first, second, times.t_end, times.n_out,
                                       azimuth=azimuth, integration=INTEGRATION)
    run_1 = sloshdyn.seismic_response(TANK, first, times.t_end, times.n_out,
                                      integration=INTEGRATION)
    run_2 = sloshdyn.seismic_response(TANK, second, times.t_end, times.n_out,
                                      integration=INTEGRATION)
    np.testing.assert_allclose(both.table["t"], run_1.t, rtol=1e-15)
    scale = max(np.abs(run_1.wave_height).max(), np.abs(run_2.wave_height).max())
    for psi in np.linspace(0, 2 * np.pi, 12, endpoint=False):
        expected = (run_1.wave_height * np.cos(psi - azimuth)
                    + run_2.wave_height * np.sin(psi - azimuth))
        assert np.abs(both.wave_height_at(psi) - expected).max() <= 1e-6 * scale
    # the loads as vectors: component 1 along the azimuth, component 2 across it
    c, s = np.cos(azimuth), np.sin(azimuth)
    for name, column in (("base_shear", "base_shear"), ("overturning_moment",
                                                        "overturning_moment")):
        p1, p2 = getattr(run_1, column), getattr(run_2, column)
        big = max(np.abs(p1).max(), np.abs(p2).max())
        assert np.abs(both.table[f"{name}_x"] - (c * p1 - s * p2)).max() <= 1e-6 * big
        assert np.abs(both.table[f"{name}_y"] - (s * p1 + c * p2)).max() <= 1e-6 * big
        np.testing.assert_allclose(both.table[name], np.hypot(c * p1 - s * p2, s * p1 + c * p2),
                                   rtol=1e-6, atol=1e-6 * big)
    # the peak over the wall is never below the larger planar peak
    peaks = both.peaks
    larger = max(np.abs(run_1.wave_height).max(), np.abs(run_2.wave_height).max())
    assert peaks["wave_height"] >= (1 - 1e-6) * larger
    # the codes' combinations beside it, from these planar runs
    w1, w2 = np.abs(run_1.wave_height).max(), np.abs(run_2.wave_height).max()
    assert peaks["wave_height_run_1"] == pytest.approx(w1, rel=1e-12)
    assert peaks["wave_height_run_2"] == pytest.approx(w2, rel=1e-12)
    assert peaks["wave_height_srss"] == pytest.approx(np.hypot(w1, w2), rel=1e-12)
    assert peaks["wave_height_100_30"] == pytest.approx(max(w1 + 0.3 * w2, 0.3 * w1 + w2),
                                                        rel=1e-12)
    # where and when: the azimuth of the largest wave is that of the wave at that time
    k = int(np.argmax(both.table["wave_height"]))
    assert peaks["wave_time"] == both.table["t"][k]
    assert peaks["wave_azimuth"] == pytest.approx(np.arctan2(both.table["wave_height_y"][k],
                                                             both.table["wave_height_x"][k]))


def test_one_component_along_an_azimuth_is_the_planar_run_turned():
    """Isotropy beyond the linear range: one record along azimuth 1.0 (a silent second
    component) gives the planar response turned by 1.0, with the free pendulum beyond the
    roof: the free wave at the wall at that azimuth, and the wave capped at the roof."""
    first, _ = _pair(3.0)
    silent = sloshdyn.GroundMotion(dt=first.dt, acceleration=np.zeros(len(first.acceleration)),
                                   units="m/s^2")
    times = sloshdyn.seismic_defaults(TANK, first)
    both = spatial.seismic_response_2d(TANK, first, silent, times.t_end, times.n_out,
                                       azimuth=1.0, integration=INTEGRATION)
    run = sloshdyn.seismic_response(TANK, first, times.t_end, times.n_out,
                                    integration=INTEGRATION)
    assert np.abs(run.x1).max() > 1 and run.roof_reached
    big = np.abs(run.free_wave_height).max()
    assert np.abs(both.wave_height_at(1.0) - run.free_wave_height).max() <= 1e-6 * big
    assert np.abs(both.table["free_wave_height"] - np.abs(run.free_wave_height)).max() <= \
        1e-6 * big
    assert np.abs(both.table["wave_height"] - np.abs(run.wave_height)).max() <= 1e-6 * big


def _on_grid(ground, dt):
    """ground's samples on the time grid k dt over its duration, by numpy.interp (the record
    linear between its samples)."""
    t = ground.dt * np.arange(len(ground.acceleration))
    n = int((len(t) - 1) * ground.dt / dt + 1e-9) + 1
    return np.interp(dt * np.arange(n), t, ground.acceleration)


@pytest.mark.parametrize("dt_2", [0.03, 0.01])
def test_a_second_record_at_another_dt_is_put_on_the_first_ones_grid(dt_2):
    """Coarser or finer: the second record becomes its piecewise-linear function sampled on the
    first one's grid, as numpy.interp samples it; the run is then that of the resampled pair."""
    first, _ = _pair(0.5)
    second = _record((0.25, 0.33, 0.7), (0.5, -1.0, 0.3), 0.35, dt=dt_2, duration=15.0)
    resampled = sloshdyn.GroundMotion(dt=first.dt, acceleration=_on_grid(second, first.dt),
                                      units="m/s^2")
    times = sloshdyn.seismic_defaults(TANK, first)
    got = spatial.seismic_response_2d(TANK, first, second, times.t_end, times.n_out,
                                      azimuth=0.3, integration=INTEGRATION)
    want = spatial.seismic_response_2d(TANK, first, resampled, times.t_end, times.n_out,
                                       azimuth=0.3, integration=INTEGRATION)
    # equal samples up to the rounding of the two interpolation formulas
    for name in ("ground_acceleration_y", "wave_height", "base_shear", "y1"):
        scale = np.abs(want.table[name]).max()
        assert np.abs(got.table[name] - want.table[name]).max() <= 1e-9 * scale, name
    assert got.peaks["base_shear_run_2"] == pytest.approx(want.peaks["base_shear_run_2"],
                                                          rel=1e-9)


def test_the_second_component_must_be_a_record_with_a_record():
    first, _ = _pair(1e-3)
    with pytest.raises(sloshdyn.InputError, match="second component"):
        spatial.seismic_response_2d(TANK, first)


@pytest.mark.parametrize("ellipticity", [0.0, 0.6])
def test_harmonic_motion_has_the_codes_combinations_of_its_two_axes(ellipticity):
    """Harmonic motion along an azimuth with an ellipticity e: run 1 is the planar run under the
    major axis, run 2 under the minor one, e a (the codes combine peaks, phases left out; none
    for e = 0). Independent: the planar runs of sloshdyn.seismic_response, the SRSS and 100/30
    formulas, the planar model's linearity (P2 = e P1), and in the linear range the spatial
    response is the sum of the two axes' responses, so its peak over the wall lies between the
    larger planar peak and their SRSS."""
    a, f = 2e-5, 0.2                                  # [g, Hz], linear range
    major = sloshdyn.GroundMotion.harmonic(a, f)
    times = sloshdyn.seismic_defaults(TANK, major)
    both = spatial.seismic_response_2d(TANK, major, None, times.t_end, times.n_out, azimuth=0.4,
                                       ellipticity=ellipticity, integration=INTEGRATION)
    run_1 = sloshdyn.seismic_response(TANK, major, times.t_end, times.n_out,
                                      integration=INTEGRATION)
    for name in ("wave_height", "base_shear", "overturning_moment"):
        p1 = np.abs(getattr(run_1, name)).max()
        p2 = 0.0
        if ellipticity:
            minor = sloshdyn.GroundMotion.harmonic(ellipticity * a, f)
            p2 = np.abs(getattr(sloshdyn.seismic_response(TANK, minor, times.t_end, times.n_out,
                                                          integration=INTEGRATION),
                                name)).max()
            assert p2 == pytest.approx(ellipticity * p1, rel=1e-6)        # linearity
        peaks = both.peaks
        assert peaks[f"{name}_run_1"] == p1 and peaks[f"{name}_run_2"] == p2
        assert peaks[f"{name}_srss"] == pytest.approx(np.hypot(p1, p2), rel=1e-15)
        assert peaks[f"{name}_100_30"] == pytest.approx(max(p1 + 0.3 * p2, 0.3 * p1 + p2),
                                                        rel=1e-15)
        assert (1 - 1e-6) * p1 <= peaks[name] <= (1 + 1e-6) * np.hypot(p1, p2)
