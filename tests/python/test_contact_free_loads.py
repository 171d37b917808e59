"""Issue 37: tank loads an engineer can sign. Below its roof a tank's liquid feels no contact
(the tank's model has no wall, beta = delta = 0); from the free wave's first contact with the
roof on, the restricted-sloshing method (the confined convective mass moves with the tank);
the paper's impact model is opt-in (roof_contact = 'impact') and feeds no load; two components
are judged like one (docs/model.md, "Loads" and "Roof loads").

Independent sources: the loads of the same tank and record for other impact stiffnesses and
dampings and with the impact model switched on (they must not move at all); the method's
formulas typed here and integrated by scipy (the confined share of the free wave's first
moment, the uplift); the free motion itself, which does not depend on where the roof is (a run
of the same tank with the roof out of reach gives V_free, a_t and a_m, from which the
method's V = V_free + m_conf (a_t - a_m) is rebuilt); linear potential flow (the convective
pressure at the free surface is rho g eta; EN 1998-4 A.2.1's convective masses and heights,
typed here, for the pressure's resultants); the records' own lengths.
"""

import math
import subprocess

import numpy as np
import pytest
from scipy.integrate import dblquad, quad
from scipy.special import j1, jnp_zeros

import sloshdyn
from conftest import EXAMPLES

G = 9.80665
#: a broad and a slender steel tank and a rectangular concrete basin (three modes), each on
#: supports given by frequency with the rod length fixed, so that the free motion does not
#: depend on the freeboard (test_restricted_sloshing_is_the_free_run_plus_the_confined_mass)
TANKS = {
    "broad": dict(radius=15.0, liquid_depth=10.0, freeboard=1.0, liquid_density=1000.0,
                  tank_mass=3.0e5, support_frequency=3.0, support_height=11.0),
    "slender": dict(radius=3.0, liquid_depth=12.0, freeboard=1.5, liquid_density=1000.0,
                    tank_mass=4.0e4, support_frequency=4.0, support_height=13.5),
    "rectangular": dict(shape="rectangular", length=12.0, width=8.0, liquid_depth=4.0,
                        freeboard=0.8, liquid_density=1000.0, tank_mass=2.0e5,
                        support_frequency=5.0, modes=3, support_height=4.8),
}
#: the contact models every load must be blind to: (beta, delta, roof_contact)
CONTACTS = [(beta, delta, "none") for beta in (0.0, 1.0, 10.0, 100.0, 1000.0)
            for delta in (0.0, 0.1)] + [(1.0, 0.0, "impact"), (1000.0, 0.1, "impact")]
#: every load column of seismic.csv (with the roof contact 'none')
LOADS = ["wave_height", "sloshing_displacement", "pendulum_angle", "tank_drift",
         "tank_acceleration", "convective_acceleration", "base_shear", "overturning_moment",
         "overturning_moment_ibp", "free_wave_height"]


def kt_record():
    """The example's synthetic Kanai-Tajimi record (30 s at 0.01 s)."""
    return sloshdyn.GroundMotion.from_file(EXAMPLES / "records" / "synthetic_kt.AT2")


def tapered_sines(tank):
    """Three sines (half, one and 2.5 times the sloshing frequency) under a Hann taper, 20 s."""
    f = 1 / tank.sloshing_period
    t = 0.01 * np.arange(2001)
    a = np.sin(np.pi * t / t[-1]) ** 2 * (np.sin(np.pi * f * t) + 0.8 * np.sin(2 * np.pi * f * t)
                                           + 0.5 * np.sin(5 * np.pi * f * t + 2))
    return sloshdyn.GroundMotion(dt=0.01, acceleration=a, units="m/s^2")


def sine_pulse(tank):
    """One cycle at the sloshing frequency, then rest: a near-fault pulse."""
    period = tank.sloshing_period
    t = 0.01 * np.arange(int(round(1.5 * period / 0.01)) + 1)
    return sloshdyn.GroundMotion(dt=0.01, acceleration=np.where(
        t <= period, np.sin(2 * np.pi * t / period), 0.0), units="m/s^2")


RECORDS = {"kt": lambda tank: kt_record(), "sines": tapered_sines, "pulse": sine_pulse}


def scaled_to(tank, ground, ratio):
    """The record scaled so that the free wave's largest height at the wall is `ratio` times
    the freeboard (the free wave is nearly linear in the scale: two correction steps)."""
    for _ in range(2):
        run = sloshdyn.seismic_response(tank, ground)
        ground = ground.scaled(ratio * tank.freeboard / run.peak_table["free_wave_height"])
    return ground


def tank_with(name, beta=10.0, delta=0.1, contact="none", **changes):
    return sloshdyn.Tank(**{**TANKS[name], **changes}, impact_stiffness=beta,
                         impact_damping=delta, roof_contact=contact)


def same(a, b):
    """Equal, NaN equal to NaN (a roof never reached has no first contact)."""
    return a == b or (math.isnan(a) and math.isnan(b))


def assert_same_loads(run, reference, what):
    for load in LOADS:
        np.testing.assert_allclose(getattr(run, load), getattr(reference, load), rtol=1e-12,
                                   atol=0, err_msg=f"{what}: {load}")
    for name, value in reference.peak_table.items():
        assert same(run.peak_table[name], value), f"{what}: {name}"


@pytest.mark.parametrize("record", sorted(RECORDS))
@pytest.mark.parametrize("name", sorted(TANKS))
@pytest.mark.parametrize("ratio", [0.7, 1.5])
def test_no_load_depends_on_the_contact_model(name, record, ratio):
    """Below the roof (the free wave at 0.7 of the freeboard) and above it (1.5): every load
    column, its peaks, the roof verdict and (circular tanks) the wall pressure at the peaks are
    the same, to 1e-12, for beta = 0 .. 1000, delta = 0 and 0.1 and with the paper's impact
    model beside the run."""
    ground = scaled_to(tank_with(name), RECORDS[record](tank_with(name)), ratio)
    reference = sloshdyn.seismic_response(tank_with(name, 0.0, 0.0), ground)
    assert reference.roof_reached is (ratio > 1)
    pressure = (sloshdyn.seismic_pressures(reference) if TANKS[name].get("shape") is None
                else None)
    for beta, delta, contact in CONTACTS:
        run = sloshdyn.seismic_response(tank_with(name, beta, delta, contact), ground)
        assert_same_loads(run, reference, f"beta {beta}, delta {delta}, {contact}")
        assert (run.impact_force is None) is (contact == "none")
        if pressure is not None:
            np.testing.assert_allclose(sloshdyn.seismic_pressures(run).total_pressure,
                                       pressure.total_pressure, rtol=1e-12, atol=0)
    if ratio > 1 and record == "kt":
        # the impact model is the paper's, with its own beta: its force moves, the loads do not
        weak, stiff = (sloshdyn.seismic_response(tank_with(name, b, 0.1, "impact"), ground)
                       for b in (1.0, 1000.0))
        assert weak.peaks["impact_force"][0] != stiff.peaks["impact_force"][0]


@pytest.mark.parametrize("name", ["broad", "slender"])
@pytest.mark.parametrize("record", ["kt", "pulse"])
def test_two_components_do_not_depend_on_the_contact_model(name, record):
    """The spatial run (record along x, the example's second component across): its table,
    peaks, the codes' SRSS and 100/30 of the planar runs and the roof are the same for every
    contact model."""
    tank = tank_with(name)
    ground = scaled_to(tank, RECORDS[record](tank), 1.3)
    across = (sloshdyn.GroundMotion.from_file(EXAMPLES / "records" / "synthetic_kt_y.AT2")
              .scaled(ground.scale_factor))
    reference = sloshdyn.spatial.seismic_response_2d(tank_with(name, 0.0, 0.0), ground, across)
    for beta, delta, contact in CONTACTS[1::3]:
        run = sloshdyn.spatial.seismic_response_2d(tank_with(name, beta, delta, contact), ground,
                                                  across)
        for column, values in reference.table.items():
            np.testing.assert_allclose(run.table[column], values, rtol=1e-12, atol=0,
                                       err_msg=column)
        for key, value in reference.peaks.items():
            assert same(run.peaks[key], value), key


def circular_roof_hand_calculation(tank, d):
    """The method's formulas for a flat roof of a circular tank, typed from docs/model.md
    "Roof loads" and integrated by scipy: head d - f; uplift rho g of the integral of
    (eta - f)+ over the roof with eta = d J1(xi r/R)/J1(xi) cos(a); confined mass m_c times
    the cut first moment of eta over the crest's."""
    xi, radius, f = float(jnp_zeros(1, 1)[0]), tank.radius, tank.freeboard

    def eta(a, r):
        return d * j1(xi * r / radius) / j1(xi) * np.cos(a)

    tol = dict(epsabs=1e-12, epsrel=1e-10)
    uplift, _ = dblquad(lambda a, r: max(eta(a, r) - f, 0.0) * r, 0, radius, -np.pi / 2,
                        np.pi / 2, **tol)
    cut, _ = dblquad(lambda a, r: max(eta(a, r) - f, 0.0) * r * np.cos(a) * r, 0, radius,
                     -np.pi / 2, np.pi / 2, **tol)
    crest, _ = dblquad(lambda a, r: eta(a, r) * r * np.cos(a) * r, 0, radius, -np.pi / 2,
                       np.pi / 2, **tol)
    return d - f, 1000.0 * G * uplift, tank.convective_mass * cut / crest


def rectangular_roof_hand_calculation(tank, d):
    """The same for a rectangular tank's flat roof: eta(x) = d sin(pi x/L), x from the centre,
    integrated by scipy's quad over the crest side (the width W uniform)."""
    length, f = tank.length, tank.freeboard

    def eta(x):
        return d * np.sin(np.pi * x / length)

    uplift, _ = quad(lambda x: max(eta(x) - f, 0.0), 0, length / 2, epsabs=1e-13, limit=200)
    cut, _ = quad(lambda x: max(eta(x) - f, 0.0) * x, 0, length / 2, epsabs=1e-13, limit=200)
    crest, _ = quad(lambda x: eta(x) * x, 0, length / 2, epsabs=1e-13)
    return d - f, 1000.0 * G * tank.width * uplift, tank.convective_mass * cut / crest


@pytest.mark.parametrize("name", sorted(TANKS))
@pytest.mark.parametrize("record", ["kt", "sines"])
def test_restricted_sloshing_is_the_free_run_plus_the_confined_mass(name, record):
    """Above the roof: the head and the confined mass are the hand calculation of the run's
    largest free wave, and from the first contact on the base shear and the moments are the
    free tank's plus m_conf (a_t - a_m) at the convective heights. The free tank's own
    V_free, a_t and a_m come from the same tank with its roof out of reach (the same supports
    and rods: the free motion does not depend on the freeboard; the model's x1 scales with it,
    so the two runs agree to the integrator's tolerance, not bit for bit)."""
    tank = tank_with(name)
    ground = scaled_to(tank, RECORDS[record](tank), 1.5)
    run = sloshdyn.seismic_response(tank, ground)
    assert run.roof_reached
    d = run.peak_table["free_wave_height"]
    hand = (rectangular_roof_hand_calculation if tank.shape == "rectangular"
            else circular_roof_hand_calculation)(tank, d)
    assert run.peak_table["roof_head"] == pytest.approx(hand[0], rel=1e-12)
    assert run.peak_table["roof_uplift_force"] == pytest.approx(hand[1], rel=1e-6)
    m_conf = run.peak_table["confined_convective_mass"]
    assert m_conf == pytest.approx(hand[2], rel=1e-6) and m_conf > 0
    # the same free motion with the roof out of reach (the free wave at 1.5 f, the roof at 1.6 f)
    free = sloshdyn.seismic_response(tank_with(name, freeboard=1.6 * tank.freeboard), ground,
                                     run.t_end, len(run.t))
    assert not free.roof_reached
    np.testing.assert_allclose(free.free_wave_height, run.free_wave_height, rtol=0,
                               atol=1e-7 * d)
    after = run.t >= run.first_roof_time
    assert 0 < after.sum() < len(run.t)
    relative = free.tank_acceleration - free.convective_acceleration
    p = tank.properties
    x = (math.pi / tank.length if tank.shape == "rectangular"
         else 1.84 / tank.radius) * tank.liquid_depth          # mode 1's k h (eq 2's 1.84)
    rise = tank.liquid_depth / x / math.sinh(x)                  # h_c' - h_c = csch(kh)/k
    # the shell and roof sit at (h + f)/2: the higher roof raises their moment
    shell = tank.tank_mass * (1.6 - 1) * tank.freeboard / 2 * free.tank_acceleration
    for load, arm, lower in (("base_shear", 1.0, 0.0),
                             ("overturning_moment", p["convective_height"], shell),
                             ("overturning_moment_ibp", p["convective_height"] + rise, shell)):
        expected = getattr(free, load) - lower + np.where(after, m_conf * arm * relative, 0.0)
        scale = np.max(np.abs(expected))
        np.testing.assert_allclose(getattr(run, load), expected, rtol=0, atol=1e-6 * scale,
                                   err_msg=load)
    # the reported wave is capped at the roof, the free one beside it
    assert np.max(np.abs(run.wave_height)) == pytest.approx(tank.freeboard, rel=1e-12)
    assert run.peaks["wave_height"][0] == tank.freeboard


def test_the_convective_pressure_at_the_surface_is_rho_g_eta_and_integrates_to_the_loads():
    """At a moderate amplitude (pendulum angle below 0.2 rad, below the roof) linear theory
    puts the convective pressure at the free surface at the wall at rho g eta; at the load
    peaks and the wave's (the run's output times nearest them) it is within 1 % (the sloshing
    damping, the pendulum's nonlinearity and eq (2)'s xi = 1.84 against 1.8412 make up the
    rest). eta is the wave at the +x wall, which is angle = pi of the pressure (its angle is
    measured from the direction of the inertia force). The pressure's resultants are the run's base
    shear and moments but for mode 1's mass and heights: potential flow's (EN 1998-4 A.2.1,
    typed here with lambda_1 = 1.8412) against eq (2)'s pendulum (xi = 1.84), exactly."""
    tank = tank_with("broad")
    run = sloshdyn.seismic_response(tank, scaled_to(tank, kt_record(), 0.6))
    assert np.max(np.abs(run.pendulum_angle)) < 0.2 and not run.roof_reached
    times = [run.peaks[load][1] for load in ("base_shear", "overturning_moment",
                                             "overturning_moment_ibp", "wave_height")]
    at = sloshdyn.seismic_pressures(run, times=times, heights=[tank.liquid_depth],
                                    angle=math.pi)
    k = [int(np.argmin(np.abs(run.t - t))) for t in times]
    eta = run.free_wave_height[k]
    np.testing.assert_allclose(at.convective_pressure[:, 0], 1000.0 * G * eta, rtol=0.01)
    assert np.all(np.abs(eta) > 0.2 * tank.freeboard)       # not a near-zero comparison
    # resultants: potential flow's mode 1 against the pendulum's, and everything else equal
    lam = float(jnp_zeros(1, 1)[0])
    R, h, m_f = tank.radius, tank.liquid_depth, tank.properties["liquid_mass"]
    x = lam * h / R
    m_pf = m_f * 2 * math.tanh(x) / (x * (lam ** 2 - 1))
    h_pf = h * (1 - math.tanh(x / 2) / x)
    h_pf_ibp = h * (1 + (2 - math.cosh(x)) / (x * math.sinh(x)))
    m, h_c = tank.convective_mass, tank.convective_height
    h_c_ibp = h_c + R / 1.84 / math.sinh(1.84 * h / R)
    relative = run.convective_acceleration[k] - run.tank_acceleration[k]
    for load, difference in (("base_shear", m_pf - m),
                             ("overturning_moment", m_pf * h_pf - m * h_c),
                             ("overturning_moment_ibp", m_pf * h_pf_ibp - m * h_c_ibp)):
        np.testing.assert_allclose(getattr(at, load) - getattr(run, load)[k],
                                   difference * relative, rtol=0,
                                   atol=1e-9 * np.max(np.abs(getattr(run, load))),
                                   err_msg=load)


def test_the_pressure_at_the_peaks_is_at_the_peaks():
    """The run keeps the accelerations where its loads peak (one integration): the pressure's
    base shear at the base shear peak is that peak (but for potential flow's mode 1, as above,
    a few 1e-5 here), at the peak's own time, between the outputs."""
    tank = tank_with("slender")
    run = sloshdyn.seismic_response(tank, scaled_to(tank, kt_record(), 0.8))
    at = sloshdyn.seismic_pressures(run)
    for j, load in enumerate(("base_shear", "overturning_moment", "overturning_moment_ibp")):
        peak, when = run.peaks[load]
        assert at.t[j] == when and not np.any(run.t == when)
        assert abs(getattr(at, load)[j]) == pytest.approx(peak, rel=2e-4)


def test_two_components_reach_the_roof_where_the_planar_run_does():
    """The example pair of records along and across a broad tank: the planar run of the first
    reaches the roof, and so does the spatial run, judged on its free wave around the wall,
    with the time and azimuth of the first contact and the restricted-sloshing loads; its wave
    is capped at the roof, the free wave beside it."""
    tank = tank_with("broad")
    ground = scaled_to(tank, kt_record(), 1.4)
    across = (sloshdyn.GroundMotion.from_file(EXAMPLES / "records" / "synthetic_kt_y.AT2")
              .scaled(ground.scale_factor))
    planar = sloshdyn.seismic_response(tank, ground)
    assert planar.roof_reached
    run = sloshdyn.spatial.seismic_response_2d(tank, ground, across)
    p = run.peaks
    assert p["roof_reached"] == 1 and p["roof_impacts"] >= 1
    wave = run.table["free_wave_height"]
    first = int(np.argmax(wave >= tank.freeboard))
    assert run.table["t"][first - 1] <= p["first_roof_time"] <= run.table["t"][first]
    assert p["first_contact_azimuth"] == pytest.approx(run.table["wave_azimuth"][first], abs=1e-12)
    assert p["free_wave_height"] == pytest.approx(np.max(wave), rel=1e-12)
    assert p["free_wave_height"] >= planar.peak_table["free_wave_height"] * 0.5
    assert np.max(run.table["wave_height"]) == pytest.approx(tank.freeboard, rel=1e-12)
    hand = circular_roof_hand_calculation(tank, p["free_wave_height"])
    assert p["confined_convective_mass"] == pytest.approx(hand[2], rel=1e-6)
    assert p["roof_head"] == pytest.approx(hand[0], rel=1e-12)


def test_a_longer_record_y_is_used_to_its_end():
    """record_y longer than record: the run lasts until the longer record and five sloshing
    periods after it have passed, and what record_y does after the first record has ended is
    in the response (a pulse across the tank that starts when the first record is over)."""
    tank = tank_with("slender")
    short = sloshdyn.GroundMotion(dt=0.01, acceleration=np.zeros(501), units="m/s^2")
    t = 0.01 * np.arange(2001)
    pulse = np.where((t >= 8) & (t <= 8 + tank.sloshing_period),
                     0.5 * np.sin(2 * np.pi * (t - 8) / tank.sloshing_period), 0.0)
    late = sloshdyn.GroundMotion(dt=0.01, acceleration=pulse, units="m/s^2")
    times = sloshdyn.seismic_defaults(tank, short, ground_motion_2=late)
    assert times.t_end >= 20.0 + 5 * tank.sloshing_period - 0.01
    run = sloshdyn.spatial.seismic_response_2d(tank, short, late)
    assert run.table["t"][-1] == pytest.approx(times.t_end, rel=1e-12)
    wave_y = np.abs(run.table["wave_height_y"])
    assert np.max(wave_y[run.table["t"] < 8]) == 0
    assert np.max(wave_y[run.table["t"] > 8]) > 0.01          # the late pulse is felt
    assert np.max(np.abs(run.table["wave_height_x"])) < 1e-12 * np.max(wave_y)


def test_roof_contact_is_a_named_choice_in_both_doors(exe, tmp_path):
    """&tank roof_contact: 'none' (no impact columns), 'impact' (impact_force, its peak and
    beta_sensitive, labelled as the paper's model in the summary); anything else is refused
    with the variable, the value and the choices."""
    base = (EXAMPLES / "tank_seismic.nml").read_text()
    record = (EXAMPLES / "records" / "synthetic_kt.AT2").resolve()
    base = base.replace("'records/synthetic_kt.AT2'", f"'{record}'")
    for contact in ("none", "impact"):
        text = base.replace("&tank", f"&tank\n  roof_contact = '{contact}'", 1).replace(
            "directory", f"directory = '{tmp_path / contact}' !", 1)
        path = tmp_path / f"{contact}.nml"
        path.write_text(text)
        done = subprocess.run([exe, str(path)], capture_output=True, text=True)
        assert done.returncode == 0, done.stderr
        header = (tmp_path / contact / "seismic.csv").read_text().splitlines()[0]
        peaks = (tmp_path / contact / "seismic_peaks.csv").read_text().splitlines()[0]
        assert ("impact_force" in header) is (contact == "impact")
        assert ("beta_sensitive" in peaks) is (contact == "impact")
        assert ("the paper's impact model" in done.stdout) is (contact == "impact")
    bad = tmp_path / "bad.nml"
    bad.write_text(base.replace("&tank", "&tank\n  roof_contact = 'wall'", 1))
    done = subprocess.run([exe, str(bad)], capture_output=True, text=True)
    assert done.returncode == 3
    assert "roof_contact = 'wall'" in done.stderr and "none, impact" in done.stderr
    with pytest.raises(sloshdyn.InputError, match="roof_contact = 'wall'"):
        tank_with("broad", contact="wall")


@pytest.mark.parametrize("ratio", [0.7, 1.5])
def test_the_design_checks_nonlinear_row_is_blind_to_the_impact_model(ratio):
    """The design check's 'sloshdyn nonlinear' row takes a time history's peaks: its loads,
    its freeboard verdict and its checks are the same for every contact model beside the run,
    and the freeboard suffices exactly when the free wave stays below the roof."""
    ground = scaled_to(tank_with("broad"), kt_record(), ratio)

    def nonlinear(beta, delta, contact):
        tank = tank_with("broad", beta, delta, contact)
        check = sloshdyn.design_check(tank, ground,
                                      response=sloshdyn.seismic_response(tank, ground))
        return (check.loads["sloshdyn nonlinear"], check.freeboard["sloshdyn nonlinear"],
                [row for row in check.checks if row["code"] == "sloshdyn nonlinear"])
    reference = nonlinear(0.0, 0.0, "none")
    assert reference[1]["sufficient"] == (ratio < 1)
    assert reference[1]["wave_height"] == pytest.approx(ratio * TANKS["broad"]["freeboard"],
                                                        rel=1e-2)     # the record's scaling
    assert [row["verdict"] for row in reference[2]][-1] == ("OK" if ratio < 1 else "NOT OK")
    for beta, delta, contact in CONTACTS:
        loads, freeboard, checks = nonlinear(beta, delta, contact)
        what = f"beta {beta}, delta {delta}, {contact}"
        for row, expected in ((loads, reference[0]), (freeboard, reference[1])):
            assert row.keys() == expected.keys()
            assert all(same(row[k], expected[k]) for k in row), what
        assert checks == reference[2], what
