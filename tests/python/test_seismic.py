"""Acceptance tests of issue 12, a real tank under ground motion in SI units (sloshdyn.Tank,
GroundMotion, seismic_response, harmonic_sweep, the sloshing damping zeta).

Every expected value comes from a source independent of the code under test, named beside it:
a closed form, potential-flow theory, the design codes' printed formulas, scipy on the same
(linear) equations, finite differences of the computed state, or an energy balance. The
agreement measured when the tests were written is quoted in the comments.

Shared facts used below (docs/model.md, sloshdyn_vessel): theta = theta0 x1, phi = theta0 x2,
tau = omega t with omega = sqrt(g/l); the tank is at u + L sin(phi), the sloshing mass m at
u + L sin(phi) + l sin(theta); the linear sloshing damping is the moment 2 zeta omega m l^2 theta'.
"""

import math
import os
import pathlib
import subprocess

import numpy as np
import pytest
from scipy.linalg import expm
from scipy.special import jnp_zeros

import sloshdyn
from conftest import EXAMPLES, directory_tree, ec8_impulsive, run

TANK = dict(radius=5.0, liquid_depth=6.0, freeboard=1.0, liquid_density=1000.0, tank_mass=5.0e4)
TIGHT = sloshdyn.Integration(rtol=1e-11, atol=1e-14)
G = 9.80665
XI = float(jnp_zeros(1, 1)[0])    # 1.8411837813406593, first root of J1' (the paper rounds 1.84)


def stiff_tank(**changes):
    """The tank of docs/python.md on 50 Hz supports: (f_sloshing/f_supports)^2 = 4e-5, so the tank
    follows the ground and the pendulum is an SDOF on a rigid base."""
    return sloshdyn.Tank(**{**TANK, "support_frequency": 50.0, "sloshing_damping": 0.01,
                            **changes})


def sdof_exact(knots, accel, omega, zeta, t_out):
    """x'' + 2 zeta omega x' + omega^2 x = -a(t) from rest at knots[0], with a(t) linear between
    the knots (a repeated knot is a jump), by the matrix exponential of the system augmented with
    the load and its slope (scipy.linalg.expm): exact for such loads, independent of the
    Nigam-Jennings recurrence of sloshdyn_sdof. Returns x at the ascending times t_out."""
    system = np.array([[0, 1, 0, 0], [-omega**2, -2 * zeta * omega, -1, 0], [0, 0, 0, 1],
                       [0, 0, 0, 0.0]])
    cache = {}

    def propagator(h):
        key = round(h, 12)     # times equal to 1e-12 s share one exponential
        if key not in cache:
            cache[key] = expm(system * key)
        return cache[key]

    x = np.empty(len(t_out))
    state = np.zeros(2)
    j = 0
    for i in range(len(knots) - 1):
        t0, t1 = knots[i], knots[i + 1]
        if t1 == t0:
            continue
        load = np.array([state[0], state[1], accel[i], (accel[i + 1] - accel[i]) / (t1 - t0)])
        while j < len(t_out) and t_out[j] <= t1:
            x[j] = (propagator(t_out[j] - t0) @ load)[0]
            j += 1
        state = (propagator(t1 - t0) @ load)[:2]
    x[j:] = np.nan
    return x


def record_knots(ground, t_end):
    """Knots of the ground acceleration of a record: its samples, then rest to t_end (knots at
    the same step; the ground stops right after the last sample, as &ground_motion in docs/namelist.md
    says, hence a repeated knot there)."""
    n_rest = int(math.ceil((t_end - ground.duration) / ground.dt)) + 1
    t = ground.dt * np.arange(len(ground.acceleration) + n_rest)
    a = np.append(ground.acceleration, np.zeros(n_rest))
    last = len(ground.acceleration) - 1
    return np.insert(t, last + 1, t[last]), np.insert(a, last + 1, 0.0)


def tapered_sines(dt=0.01, duration=20.0, pga=0.05):
    """Three sines (0.2, 0.3 ~ the sloshing frequency, 1.1 Hz) under a Hann taper: ends at 0."""
    t = dt * np.arange(int(round(duration / dt)) + 1)
    a = np.sin(np.pi * t / t[-1])**2 * (np.sin(2 * np.pi * 0.2 * t) +
                                        0.8 * np.sin(2 * np.pi * 0.3 * t + 1) +
                                        0.5 * np.sin(2 * np.pi * 1.1 * t + 2))
    return sloshdyn.GroundMotion(dt=dt, acceleration=a * pga / np.max(np.abs(a)),
                                 units="m/s^2")


def sine_pulse(dt=0.01, duration=12.0, pga=0.05):
    """One cycle of a 0.5 Hz sine, then rest: a near-fault pulse."""
    t = dt * np.arange(int(round(duration / dt)) + 1)
    return sloshdyn.GroundMotion(dt=dt, acceleration=np.where(t <= 2.0, pga * np.sin(np.pi * t),
                                                              0.0), units="m/s^2")


def truncated_sine(dt=0.02, pga=0.05):
    """A 0.3 Hz sine cut off at 2.5 s, where it is at -pga: the ground stops abruptly."""
    t = dt * np.arange(int(round(2.5 / dt)) + 1)
    return sloshdyn.GroundMotion(dt=dt, acceleration=pga * np.sin(2 * np.pi * 0.3 * t),
                                 units="m/s^2")


def example_record(pga=0.05):
    """The example's synthetic Kanai-Tajimi record (filtered noise; ends at -1e-3 g, not at 0),
    scaled to pga [m/s^2]."""
    return sloshdyn.GroundMotion.from_file(EXAMPLES / "records" / "synthetic_kt.AT2").scaled(
        pga=pga, units="m/s^2")


# --- 1. linear limit: peak sloshing displacement = the exact SDOF response -------------------

@pytest.mark.parametrize("make_record", [example_record, tapered_sines, sine_pulse,
                                         truncated_sine])
def test_linear_limit_is_the_sdof_at_the_sloshing_period(make_record):
    """On stiff supports and at small amplitude the pendulum obeys l theta'' + 2 zeta omega l
    theta' + g theta = -u'' (participation factor 1 for the displacement l theta relative to the
    tank), so the peak sloshing displacement is the spectral displacement Sd(T_sloshing, zeta).
    Measured: within 9e-6 (noise), 1.4e-5 (sines), 1e-6 (pulse), 6e-6 (truncated sine), the
    whole history within 3e-4 to 6e-4 of the peak; the issue asks 1 %. The spectrum, like the model, has the ground at rest after the last sample
    (it used to ramp down over one more step: 0.8 % too large for the truncated sine)."""
    tank = stiff_tank()
    ground = make_record()
    period, zeta = tank.sloshing_period, tank.sloshing_damping
    n_out = int(round((ground.duration + 5 * period) / ground.dt)) + 1
    t_end = (n_out - 1) * ground.dt                 # outputs at the record's samples
    r = sloshdyn.seismic_response(tank, ground, t_end=t_end, n_out=n_out, integration=TIGHT)
    assert np.max(np.abs(r.x1)) < 0.1               # theta << theta0: the linear regime

    peak = np.max(np.abs(r.sloshing_displacement))
    spectrum = ground.response_spectrum([period], damping=zeta, tail_duration=t_end - ground.duration)
    x = sdof_exact(*record_knots(ground, t_end), 2 * np.pi / period, zeta, r.t)
    assert peak == pytest.approx(spectrum.sd[0], rel=1e-3)
    assert peak == pytest.approx(np.max(np.abs(x)), rel=1e-3)
    # the whole history, not only its peak
    assert np.max(np.abs(r.sloshing_displacement - x)) < 1e-3 * peak
    # the project's spectrum (Nigam-Jennings) and expm agree to round-off on the same load
    assert spectrum.sd[0] == pytest.approx(np.max(np.abs(x)), rel=1e-9)


# --- 2. harmonic motion in SI = the dimensionless model at tau = omega t ---------------------

@pytest.mark.parametrize("peak_g,frequency", [(0.05, 0.29872), (0.1, 1.3)])
def test_harmonic_si_equals_dimensionless_simulation(peak_g, frequency):
    """seismic_response of harmonic ground motion and simulate of tank.parameters(ground) (A, rho
    by A = a/(L (2 pi f)^2), rho = 2 pi f/omega) integrate the same equations: x1, x2 agree at
    tau = omega t. Measured: 1e-14 (0.05 g at resonance, roof impacts) and 1e-15."""
    tank = sloshdyn.Tank(**TANK, support_frequency=2.0, support_damping=0.02)
    ground = sloshdyn.GroundMotion.harmonic(peak_g, frequency, units="g")
    r = sloshdyn.seismic_response(tank, ground, t_end=60.0, n_out=1201, integration=TIGHT)
    omega = tank.properties["omega"]
    sim = sloshdyn.simulate(tank.parameters(ground), omega * 60.0, n_out=1201, integration=TIGHT)
    assert np.max(np.abs(sim.tau - omega * r.t)) < 1e-12
    assert np.max(np.abs(sim.x1 - r.x1)) < 1e-10 and np.max(np.abs(sim.x2 - r.x2)) < 1e-10
    # the ground acceleration column is the harmonic motion itself
    assert r.ground_acceleration == pytest.approx(
        -peak_g * G * np.sin(2 * np.pi * frequency * r.t), abs=1e-12 * peak_g * G)


# --- 3. convective period, masses and heights ------------------------------------------------

def potential_flow(radius, depth, xi, liquid_mass, gravity=G):
    """First sloshing mode of a rigid cylinder in potential flow with the root xi of J1':
    period [s], convective mass [kg] and height of its wall-pressure resultant (EBP) [m]."""
    x = xi * depth / radius
    period = 2 * np.pi / np.sqrt(gravity * xi / radius * np.tanh(x))
    mass = liquid_mass * 2 * np.tanh(x) / (xi * (xi**2 - 1) * depth / radius)
    # (cosh x - 1)/(x sinh x) = tanh(x/2)/x: the series' high modes would overflow cosh
    height = depth * (1 - np.tanh(x / 2) / x)
    return period, mass, height


def housner_height(depth, x):
    """Housner's EBP height of the convective resultant, H [1 - (cosh x - 1)/(x sinh x)]."""
    return depth * (1 - (math.cosh(x) - 1) / (x * math.sinh(x)))


@pytest.mark.parametrize("radius,depth", [(5.0, 6.0), (10.0, 5.0), (2.0, 8.0)])
def test_convective_period_mass_and_heights_against_potential_flow(radius, depth):
    tank = sloshdyn.Tank(radius=radius, liquid_depth=depth, freeboard=0.5, liquid_density=1000.0,
                         tank_mass=5e4, support_frequency=2.0)
    p = tank.properties
    mf = p["liquid_mass"]
    assert mf == pytest.approx(np.pi * 1000.0 * radius**2 * depth, rel=1e-14)
    t184, m184, h184 = potential_flow(radius, depth, 1.84, mf)
    t_exact, m_exact, h_exact = potential_flow(radius, depth, XI, mf)

    # the period is potential flow with xi rounded to 1.84 (eq 2): exact to round-off; the exact
    # root makes it 0.032-0.051 % shorter (1.84 is 6.4e-4 below XI)
    assert tank.sloshing_period == pytest.approx(t184, rel=1e-13)
    assert 0 < tank.sloshing_period / t_exact - 1 < 6e-4
    # the mass is eq (2), m_F R tanh(1.84 h/R)/(2.2 h): 2.2 rounds xi (xi^2 - 1)/2 = 2.2002 of the
    # exact root, so it is within 3.1e-4 of potential flow with the exact root; with 1.84 in
    # both places it would be 1.84 (1.84^2 - 1)/2 = 2.194752, 0.24 % away
    assert tank.convective_mass == pytest.approx(mf * radius / (2.2 * depth) *
                                                 np.tanh(1.84 * depth / radius), rel=1e-13)
    assert tank.convective_mass == pytest.approx(m_exact, rel=4e-4)
    assert tank.convective_mass / m184 - 1 == pytest.approx(1.84 * (1.84**2 - 1) / 4.4 - 1,
                                                            abs=1e-12)
    # convective height: Housner's EBP with 1.84, exactly; the exact root lowers it by < 2e-4
    assert tank.convective_height == pytest.approx(housner_height(depth, 1.84 * depth / radius),
                                                   rel=1e-13)
    assert h184 == pytest.approx(tank.convective_height, rel=1e-13)
    assert tank.convective_height == pytest.approx(h_exact, rel=2e-4)

    # impulsive: m0 = m_F - m (eq 3), placed so that slow motion gives the rigid liquid's
    # moment m_F h/2 (quasi-static: the wall force of a rigidly moving liquid is uniform in depth)
    assert tank.impulsive_mass == pytest.approx(mf - tank.convective_mass, rel=1e-14)
    assert (tank.impulsive_mass * tank.impulsive_height +
            tank.convective_mass * tank.convective_height) == pytest.approx(mf * depth / 2,
                                                                            rel=1e-13)
    # Veletsos' exact rigid-tank series (all modes xi_n of J1'): m_i = m_F - sum m_cn, m_i h_i =
    # m_F h/2 - sum m_cn h_cn. One mode puts the higher modes' mass into m0: measured +2.7 %,
    # +13 %, +0.57 % on m_i and +3.0 %, +9.4 %, +0.64 % on h_i for h/R = 1.2, 0.5, 4
    roots = jnp_zeros(1, 20000)        # the truncated tail is < 1e-9 m_F
    _, masses, heights = potential_flow(radius, depth, roots, mf)
    m_i = mf - masses.sum()
    h_i = (mf * depth / 2 - (masses * heights).sum()) / m_i
    higher = masses[1:].sum()
    assert tank.impulsive_mass - m_i == pytest.approx(higher + masses[0] - tank.convective_mass,
                                                      rel=1e-6)
    assert 0 < tank.impulsive_mass / m_i - 1 < 1.01 * higher / m_i + 4e-4
    assert 0 < tank.impulsive_height / h_i - 1 < 0.1


def spectral_acceleration(ground, period, damping, tail):
    """Sa = omega^2 max|x| over the samples of the record and of a tail after it (expm)."""
    steps = int(math.ceil(tail / ground.dt - 1e-9))
    t = ground.dt * np.arange(len(ground.acceleration) + steps)
    omega = 2 * np.pi / period
    return omega**2 * np.max(np.abs(sdof_exact(*record_knots(ground, t[-1]), omega, damping, t)))


def test_design_code_table_columns():
    """Tank.design_codes (and design_codes.csv): the sloshdyn column is the tank's own values,
    each code's column its printed formulas (typed here from the codes), the wave heights each
    source's formula applied to Sa at its own period and the tank's sloshing damping (Sa by expm,
    tail 5 times the longest period). D/H = 1.67 >= 1.333: the squat-tank forms."""
    tank = sloshdyn.Tank(**TANK, support_frequency=2.0)
    ground = tapered_sines(pga=2.0)
    codes = tank.design_codes(ground)
    assert codes.sources == ["sloshdyn", "API 650", "EC8-4", "ACI 350.3"]
    assert codes.columns == ["convective_period", "convective_mass", "impulsive_mass",
                             "convective_height", "impulsive_height", "wave_height"]
    R, H, mf = TANK["radius"], TANK["liquid_depth"], tank.properties["liquid_mass"]
    D = 2 * R
    api_x = 3.67 * H / D
    ec8_x = 1.841 * H / R
    aci_x = 3.68 * H / D
    impulsive = math.tanh(0.866 * D / H) / (0.866 * D / H)
    ec8_ratio, ec8_height, _ = ec8_impulsive(R, H)       # A.2.1's series, by scipy
    expected = {
        "sloshdyn": [tank.sloshing_period, tank.convective_mass, tank.impulsive_mass,
                     tank.convective_height, tank.impulsive_height],
        "API 650": [1.8 * 0.578 / math.sqrt(math.tanh(3.68 * H / D)) * math.sqrt(D),   # E.4.5.2
                    0.230 * D / H * math.tanh(api_x) * mf, impulsive * mf,            # E.6.1.1
                    housner_height(H, api_x), 0.375 * H],                           # E.6.1.2.1
        "EC8-4": [2 * math.pi / math.sqrt(G * 1.841 / R * math.tanh(ec8_x)),         # A.2.1
                  2 * math.tanh(ec8_x) / (1.841 * (1.841**2 - 1) * H / R) * mf,
                  ec8_ratio * mf, housner_height(H, ec8_x), ec8_height],
        "ACI 350.3": [2 * math.pi / (math.sqrt(3.68 * G * math.tanh(aci_x)) / math.sqrt(D)),
                      0.230 * D / H * math.tanh(aci_x) * mf, impulsive * mf,       # 9-15, 9-16
                      housner_height(H, aci_x), 0.375 * H],                        # 9-19, 9-18
    }
    periods = [expected[source][0] for source in codes.sources]
    sa = [spectral_acceleration(ground, period, tank.sloshing_damping, 5 * max(periods))
          for period in periods]
    expected["sloshdyn"].append(2 * R / (1.84**2 - 1) * sa[0] / G)
    expected["API 650"].append(0.42 * D * sa[1] / G)                                 # E.7.2-1
    expected["EC8-4"].append(0.84 * R * sa[2] / G)
    expected["ACI 350.3"].append(R * sa[3] / G)                                     # 7-2, I = 1
    for source, values in expected.items():
        got = [codes.value(source, column) for column in codes.columns]
        assert got == pytest.approx(values, rel=1e-9, nan_ok=True), source
    # ACI's period and height are sloshdyn's (3.68 = 2 x 1.84); API's 1.8 = sqrt(3.28 ft/m)
    # rounded makes its period 0.53 % shorter
    assert codes.difference("ACI 350.3", "convective_period") == pytest.approx(0, abs=1e-12)
    assert codes.difference("API 650", "convective_period") == pytest.approx(-0.527, abs=1e-3)


def test_harmonic_motion_lasts_40_forcing_periods_unless_told():
    """One default, the core's (sloshdyn_ground's harmonic_periods), for GroundMotion's
    spectrum and the design codes' wave heights: the Sa of harmonic motion is that of its
    samples (200 per period) over 40 forcing periods taken as a record (expm, tail 5 times the
    longest period)."""
    tank = sloshdyn.Tank(**TANK, support_frequency=2.0)
    f, a = 0.25, 0.5
    ground = sloshdyn.GroundMotion.harmonic(a, f, units="m/s^2")
    dt = 1 / (200 * f)
    t = dt * np.arange(int(40 / f / dt) + 1)
    sampled = sloshdyn.GroundMotion(dt=dt, acceleration=-a * np.sin(2 * np.pi * f * t),
                                    units="m/s^2")
    codes = tank.design_codes(ground)
    periods = [codes.value(source, "convective_period") for source in codes.sources]
    tail = 5 * max(periods)
    sa = spectral_acceleration(sampled, tank.sloshing_period, tank.sloshing_damping, tail)
    spectrum = ground.response_spectrum([tank.sloshing_period], damping=tank.sloshing_damping,
                                        tail_duration=tail)
    assert spectrum.psa[0] == pytest.approx(sa, rel=1e-9)
    assert codes.value("sloshdyn", "wave_height") == pytest.approx(
        2 * TANK["radius"] / (1.84**2 - 1) * sa / G, rel=1e-9)
    shorter = ground.response_spectrum([tank.sloshing_period], damping=tank.sloshing_damping,
                                       tail_duration=tail, duration=2 / f)
    assert shorter.psa[0] != pytest.approx(sa, rel=1e-3)     # the duration matters


@pytest.mark.parametrize("peak_g, frequency", [(0.05, 0.29872), (0.3, 1.7)])
def test_a_tanks_harmonic_A_and_rho_are_the_namelists(tmp_path, peak_g, frequency):
    """Tank.parameters(harmonic ground motion) has the A and rho that the namelist reader sets
    for &tank with &ground_motion, bit for bit (one routine of the core), and they are
    rho = Omega/omega and A = a/(L Omega^2) (the base displacement amplitude over L)."""
    tank = sloshdyn.Tank(**TANK, support_frequency=2.0)
    (tmp_path / "in.nml").write_text(namelist(
        tank, f"peak_acceleration = {peak_g!r}, frequency = {frequency!r}",
        "&analysis kind = 'seismic' /\n"))
    read = sloshdyn.read_namelist(tmp_path / "in.nml").params
    python = tank.parameters(sloshdyn.GroundMotion.harmonic(peak_g, frequency))
    assert (python.A, python.rho) == (read.A, read.rho)
    omega, big_omega = tank.properties["omega"], 2 * math.pi * frequency
    assert python.rho == pytest.approx(big_omega / omega, rel=1e-14)
    assert python.A == pytest.approx(peak_g * G / (tank.properties["support_height"]
                                                   * big_omega**2), rel=1e-14)
    with pytest.raises(sloshdyn.InputError, match="record has no A and rho"):
        tank.parameters(truncated_sine())


# --- 4. base shear = rate of change of the total horizontal momentum; 5. energy balance -------

def write_at2(path, ground):
    """A PEER NGA .AT2 file of the record (values in g, 17 digits: read back exactly)."""
    values = [repr(float(v)) for v in ground.acceleration / G]
    lines = [" ".join(values[i:i + 5]) for i in range(0, len(values), 5)]
    path.write_text("TEST RECORD\nsloshdyn test_seismic\nACCELERATION TIME SERIES IN UNITS OF G\n"
                    f"NPTS= {len(values)}, DT= {ground.dt!r} SEC\n" + "\n".join(lines) + "\n")


def namelist(tank, ground_lines, analysis_lines):
    """A namelist for the tank (every field, full precision) with the given other groups."""
    fields = ", ".join(f"{name} = {value!r}" for name, value in
                       zip(tank.__dataclass_fields__, tank.array().tolist())
                       if name not in ("n", "p", "shape", "modes", "roof_contact")) + \
        f", n = {tank.n}, p = {tank.p}, shape = '{tank.shape}', modes = {tank.modes}" \
        f", roof_contact = '{tank.roof_contact}'"
    return (f"&tank {fields} /\n&ground_motion {ground_lines} /\n{analysis_lines}"
            "&integration rtol = 1e-11, atol = 1e-14 /\n&output directory = 'out' /\n")


class Run:
    """A tank's response on a time grid: the state y (4, n) from a simulation and the
    SeismicResponse at the same times, and the ground's u'' and u' there."""

    def __init__(self, tank, ground, t, y, response, accel, velocity):
        self.tank, self.ground, self.t, self.y, self.r = tank, ground, t, y, response
        self.accel, self.velocity = accel, velocity
        p = tank.properties
        self.M, self.m = p["total_mass"], p["sloshing_mass"]
        self.L, self.l = p["support_height"], p["pendulum_length"]
        self.theta0, self.omega = p["theta0"], p["omega"]
        self.theta, self.phi = self.theta0 * y[0], self.theta0 * y[2]
        self.theta_d, self.phi_d = self.omega * self.theta0 * y[1], self.omega * self.theta0 * y[3]


def record_velocity(ground, t):
    """u'(t) from rest at t = 0: the exact integral of the piecewise-linear record (constant
    after it)."""
    a, dt = ground.acceleration, ground.dt
    at_samples = np.concatenate([[0.0], np.cumsum((a[1:] + a[:-1]) * dt / 2)])
    k = np.clip(np.floor(t / dt + 1e-9).astype(int), 0, len(a) - 2)
    s = np.minimum(t - k * dt, dt)
    return at_samples[k] + a[k] * s + (a[k + 1] - a[k]) * s**2 / (2 * dt)


#: the tank with its roof out of reach (the loads are then the free motion's momentum rate, the
#: restricted-sloshing method never starting), swinging far enough for the geometric
#: nonlinearity of the pendulum and the rods to count
HIGH_ROOF = dict(TANK, freeboard=4.0)


@pytest.fixture(scope="module")
def record_run(exe, tmp_path_factory):
    """The tank on 2 Hz supports under a strong record (the pendulum swings by 0.63 rad, below
    the roof): states from the executable's 'simulate' (history.csv: x1, x1', x2, x2'), loads
    from seismic_response on the same tau grid, 16 outputs per record step."""
    tank = sloshdyn.Tank(**HIGH_ROOF, support_frequency=2.0, support_damping=0.02)
    ground = tapered_sines(dt=0.04, duration=16.0, pga=2.0)
    folder = tmp_path_factory.mktemp("record_run")
    write_at2(folder / "r.AT2", ground)
    ground = sloshdyn.GroundMotion.from_file(folder / "r.AT2")
    t_end, n_out = 24.0, 16 * 600 + 1
    omega = tank.properties["omega"]
    (folder / "sim.nml").write_text(namelist(
        tank, "record = 'r.AT2'", f"&analysis kind = 'simulate' /\n&simulation t_end = "
        f"{omega * t_end!r}, n_out = {n_out} /\n"))
    result = run(exe, "sim.nml", folder)
    assert result.returncode == 0, result.stderr
    history = np.loadtxt(folder / "out" / "history.csv", delimiter=",", skiprows=1)
    r = sloshdyn.seismic_response(tank, ground, t_end=t_end, n_out=n_out, integration=TIGHT)
    # the same integration twice: the same trajectory
    assert np.max(np.abs(history[:, 0] - omega * r.t)) < 1e-12
    assert np.max(np.abs(history[:, 1] - r.x1)) < 1e-12
    assert np.max(np.abs(r.pendulum_angle)) > 0.6 and not r.roof_reached
    t = r.t
    accel = np.interp(t, ground.time, ground.acceleration, right=0.0)
    return Run(tank, ground, t, history[:, 1:5].T, r, accel, record_velocity(ground, t))


@pytest.fixture(scope="module")
def harmonic_run():
    """The tank of docs/python.md under 0.05 g at its sloshing frequency, its roof out of reach
    (the pendulum swings by 1 rad): states from simulate, loads from seismic_response, 400
    outputs per second."""
    tank = sloshdyn.Tank(**HIGH_ROOF, support_frequency=2.0, support_damping=0.02)
    a, f = 0.05 * G, 0.29872
    ground = sloshdyn.GroundMotion.harmonic(a, f, units="m/s^2")
    t_end, n_out = 30.0, 400 * 30 + 1
    r = sloshdyn.seismic_response(tank, ground, t_end=t_end, n_out=n_out, integration=TIGHT)
    omega = tank.properties["omega"]
    sim = sloshdyn.simulate(tank.parameters(ground), omega * t_end, n_out=n_out,
                            integration=TIGHT)
    assert np.max(np.abs(r.pendulum_angle)) > 1.0 and not r.roof_reached
    t = r.t
    return Run(tank, ground, t, sim.y, r, -a * np.sin(2 * np.pi * f * t),
               a / (2 * np.pi * f) * np.cos(2 * np.pi * f * t))


def cell_weights(per_cell, moments):
    """Weights w[j] of the per_cell + 1 points of a cell (offsets 0..per_cell, unit step) that
    apply a linear functional exactly to polynomials of degree per_cell: moments(j) gives the
    functional of 1, (x - j), (x - j)^2, ... for the point j."""
    offsets = np.arange(per_cell + 1.0)
    return np.array([np.linalg.solve(np.vander(offsets - j, increasing=True).T, moments(j))
                     for j in offsets])


def cells_of(values, per_cell):
    """The (n_cells, per_cell + 1) points of each cell of a uniform grid."""
    n_cells = (len(values) - 1) // per_cell
    assert n_cells * per_cell == len(values) - 1
    cells = values[:-1].reshape(n_cells, per_cell)
    return np.column_stack([cells, np.append(cells[1:, 0], values[-1])])


def cell_derivative(values, h, per_cell):
    """d/dt of values on a uniform grid (step h) by the polynomial of degree per_cell through
    the points of each cell of per_cell steps; a point on a cell boundary uses the cell to its
    right (the last point the one to its left). Cells aligned with a record's samples never
    straddle its kinks. Error ~ h^per_cell."""
    weights = cell_weights(per_cell, lambda j: np.eye(per_cell + 1)[1])
    nodes = cells_of(values, per_cell)
    derivative = np.empty_like(values)
    derivative[:-1] = (nodes @ weights[:per_cell].T).ravel() / h
    derivative[-1] = nodes[-1] @ weights[per_cell] / h
    return derivative


def cell_integral(values, h, per_cell):
    """The integral from the first point to each cell boundary (Newton-Cotes on each cell)."""
    powers = np.arange(per_cell + 1)
    # the integral over the cell [0, per_cell] of (x - j)^k
    weights = cell_weights(per_cell, lambda j: ((per_cell - j)**(powers + 1) -
                                                (-j)**(powers + 1)) / (powers + 1))
    return np.concatenate([[0.0], np.cumsum(cells_of(values, per_cell) @ weights[0] * h)])


@pytest.mark.parametrize("name", ["harmonic_run", "record_run"])
def test_base_shear_is_the_rate_of_change_of_horizontal_momentum(name, request):
    """P = (M - m)(u' + L cos(phi) phi') + m (u' + L cos(phi) phi' + l cos(theta) theta') from the
    state, differentiated numerically, equals the base shear (M - m) a_tank + m a_mass at every
    output time (every other one, where the two step sizes meet). Tolerance 1e-8 of the peak
    base shear: the 8th-order differences' own error, estimated from h and 2h, is asserted
    below a tenth of it. Measured: 7.7e-10 (harmonic) and 7.8e-10 (record) of the peak."""
    s = request.getfixturevalue(name)
    momentum = s.M * s.velocity + s.M * s.L * np.cos(s.phi) * s.phi_d + \
        s.m * s.l * np.cos(s.theta) * s.theta_d
    h = s.t[1] - s.t[0]
    fine = cell_derivative(momentum, h, 8)[::2]           # cells of half a record step
    coarse = cell_derivative(momentum[::2], 2 * h, 8)     # cells of a record step
    scale = np.max(np.abs(s.r.base_shear))
    assert np.max(np.abs(fine - coarse)) / (2**8 - 1) < 1e-9 * scale
    assert np.max(np.abs(s.r.base_shear[::2] - fine)) < 1e-8 * scale


@pytest.mark.parametrize("name", ["harmonic_run", "record_run"])
def test_energy_balance_with_damping(name, request):
    """In the frame of the ground (which accelerates by u''), eq (6)-(8) without the u' terms:
    E = (M/2) L^2 phi'^2 + (m/2) l^2 theta'^2 + m l L theta' phi' cos(theta + phi)
        + (k/2) phi^2 - M g L (1 - cos phi) + m g l (1 - cos theta) + (b theta0/(2n)) x1^(2n),
    and the inertia force -u'' of each mass does the work of the ground, -u'' Q with the
    relative horizontal momentum Q = M L cos(phi) phi' + m l cos(theta) theta'. The dissipation:
    c phi'^2 (rods), d x1^(2p) theta'^2 (eq 5, d = delta omega m l^2) and 2 zeta omega m l^2
    theta'^2 (the linear sloshing damping). Then E(t) - E(0) = int_0^t (-u'' Q - dissipated) at
    every cell boundary, by 8th-order Newton-Cotes on cells aligned with the record's samples.
    Tolerance 1e-9 of the largest work done, the quadrature's own error estimated from h and 2h
    asserted below a tenth of it. Measured: 4e-11 (harmonic), 2e-11 (record); the damping
    dissipates 75 % and 48 % of that work."""
    s = request.getfixturevalue(name)
    p, tank = s.tank.properties, s.tank
    # the tank's model has no wall below the roof (roof_contact = 'none': beta = delta = 0)
    model = tank.parameters()
    k, c, g = p["support_stiffness"], p["support_damping_coefficient"], tank.gravity
    b = model.beta * s.m * g * s.l
    d = model.delta * s.omega * s.m * s.l**2
    x1 = s.y[0]
    energy = (s.M / 2 * s.L**2 * s.phi_d**2 + s.m / 2 * s.l**2 * s.theta_d**2 +
              s.m * s.l * s.L * s.theta_d * s.phi_d * np.cos(s.theta + s.phi) +
              k / 2 * s.phi**2 - 2 * s.M * g * s.L * np.sin(s.phi / 2)**2 +
              2 * s.m * g * s.l * np.sin(s.theta / 2)**2 +
              b * s.theta0 / (2 * tank.n) * x1**(2 * tank.n))
    ground_power = -s.accel * (s.M * s.L * np.cos(s.phi) * s.phi_d +
                               s.m * s.l * np.cos(s.theta) * s.theta_d)
    dissipated = c * s.phi_d**2 + (d * x1**(2 * tank.p) +
                                   2 * tank.sloshing_damping * s.omega * s.m * s.l**2) * s.theta_d**2
    h = s.t[1] - s.t[0]
    work = cell_integral(ground_power - dissipated, h, 8)
    coarse = cell_integral((ground_power - dissipated)[::2], 2 * h, 8)
    scale = np.max(np.abs(cell_integral(ground_power, h, 8)))
    assert np.max(np.abs(work[::2] - coarse)) / (2**9 - 1) < 1e-10 * scale
    assert np.max(np.abs(energy[::8] - energy[0] - work)) < 1e-9 * scale
    # the dissipation is not negligible: without it the balance fails by far
    assert np.max(np.abs(energy[::8] - energy[0] - cell_integral(ground_power, h, 8))) > \
        1e-3 * scale


# --- 6. both front doors ----------------------------------------------------------------------

def copy_example(example, folder):
    folder.mkdir()
    (folder / example).write_bytes((EXAMPLES / example).read_bytes())
    (folder / "records").mkdir()
    for record in (EXAMPLES / "records").glob("*.AT2"):
        (folder / "records" / record.name).write_bytes(record.read_bytes())


@pytest.fixture(scope="module", params=["tank_seismic.nml", "tank_harmonic.nml",
                                        "tank_linear.nml"])
def both_doors(request, exe, tmp_path_factory):
    """An example run by the executable and by `sloshdyn-py run`, each in its own folder."""
    example = request.param
    root = tmp_path_factory.mktemp(example.replace(".", "_"))
    folders = {door: root / door for door in ("exe", "py")}
    for door, folder in folders.items():
        copy_example(example, folder)
        command = [exe] if door == "exe" else [str(pathlib.Path(exe).with_name("sloshdyn-py")),
                                               "run"]
        result = subprocess.run(command + [example], cwd=folder, capture_output=True, text=True,
                                timeout=120)
        assert result.returncode == 0, result.stderr
    out = sloshdyn.read_namelist(folders["exe"] / example).directory
    return example, folders["exe"] / out, folders["py"] / out


def test_both_front_doors_write_identical_csv_files(both_doors):
    example, exe_out, py_out = both_doors
    names = sorted(path.name for path in exe_out.glob("*.csv"))
    assert names == sorted(path.name for path in py_out.glob("*.csv"))
    assert "tank.csv" in names and "design_codes.csv" in names
    for name in names:
        assert (exe_out / name).read_bytes() == (py_out / name).read_bytes(), name


def test_python_api_gives_the_numbers_of_the_csv_files(both_doors):
    """seismic_response and Tank.design_codes on the namelist's tank and ground motion give
    the executable's numbers bit for bit (17 significant digits in the CSV round-trip)."""
    example, exe_out, _ = both_doors
    inp = sloshdyn.read_namelist(EXAMPLES / example)
    codes = np.loadtxt(exe_out / "design_codes.csv", delimiter=",", skiprows=1,
                       usecols=range(1, 7))
    assert np.array_equal(codes, inp.tank.design_codes(inp.ground_motion).table.T,
                          equal_nan=True)
    if inp.analysis != "seismic":
        return
    t_end, n_out = inp.seismic["t_end"], inp.seismic["n_out"]
    r = sloshdyn.seismic_response(inp.tank, inp.ground_motion, t_end=t_end or None,
                                  n_out=n_out or None,
                                  integration=inp.integration)
    table = np.loadtxt(exe_out / "seismic.csv", delimiter=",", skiprows=1)
    assert np.array_equal(table.T, r.table)
    peaks = np.loadtxt(exe_out / "seismic_peaks.csv", delimiter=",", skiprows=1)
    assert np.array_equal(peaks, list(r.peak_table.values()), equal_nan=True)


def test_the_pressure_files_are_the_pressure_at_the_run_peaks(both_doors):
    """A seismic run writes the hydrodynamic pressure at its base shear and overturning moment
    peaks: pressure_at_peaks.csv and the wall and base profiles at each are
    sloshdyn.seismic_pressures of the same run on the files' heights and radii, bit for bit;
    and the wall's pressure integrated over the wall (trapezoids on 21 heights) plus the shell's
    inertia is the base shear of the instant (docs/model.md, "Pressure at an instant")."""
    example, exe_out, _ = both_doors
    inp = sloshdyn.read_namelist(EXAMPLES / example)
    written = sorted(path.name for path in exe_out.glob("*pressure_at_*.csv"))
    if inp.analysis != "seismic":
        assert written == []
        return
    assert written == ["base_pressure_at_moment_ibp_peak.csv",
                       "base_pressure_at_moment_peak.csv", "base_pressure_at_shear_peak.csv",
                       "pressure_at_peaks.csv", "wall_pressure_at_moment_ibp_peak.csv",
                       "wall_pressure_at_moment_peak.csv", "wall_pressure_at_shear_peak.csv"]
    run = sloshdyn.seismic_response(inp.tank, inp.ground_motion,
                                    t_end=inp.seismic["t_end"] or None,
                                    n_out=inp.seismic["n_out"] or None,
                                    integration=inp.integration)
    walls = [np.loadtxt(exe_out / f"wall_pressure_at_{peak}_peak.csv", delimiter=",",
                        skiprows=1) for peak in ("shear", "moment", "moment_ibp")]
    floors = [np.loadtxt(exe_out / f"base_pressure_at_{peak}_peak.csv", delimiter=",",
                         skiprows=1) for peak in ("shear", "moment", "moment_ibp")]
    at_peaks = sloshdyn.seismic_pressures(run, heights=walls[0][:, 0], radii=floors[0][:, 0])
    instants = np.loadtxt(exe_out / "pressure_at_peaks.csv", delimiter=",", skiprows=1)
    assert np.array_equal(instants.T, [at_peaks.t, at_peaks.tank_acceleration,
                                       at_peaks.base_shear, at_peaks.overturning_moment,
                                       at_peaks.overturning_moment_ibp])
    assert list(at_peaks.times) == [run.peaks["base_shear"][1],
                                    run.peaks["overturning_moment"][1],
                                    run.peaks["overturning_moment_ibp"][1]]
    tank = inp.tank
    for k in range(3):
        assert np.array_equal(walls[k][:, 1:].T, [at_peaks.impulsive_pressure[k],
                                                  at_peaks.convective_pressure[k],
                                                  at_peaks.total_pressure[k],
                                                  at_peaks.hoop_force[k]])
        assert np.array_equal(floors[k][:, 1:].T, [at_peaks.base_impulsive_pressure[k],
                                                   at_peaks.base_convective_pressure[k],
                                                   at_peaks.base_total_pressure[k]])
        z, p = walls[k][:, 0], walls[k][:, 3]
        shear = (np.pi*tank.radius*np.sum((p[1:] + p[:-1])/2*np.diff(z))
                 + tank.tank_mass*at_peaks.tank_acceleration[k])
        assert shear == pytest.approx(at_peaks.base_shear[k], rel=2e-3)


@pytest.mark.parametrize("example", ["tank_harmonic.nml", "tank_linear.nml"])
def test_python_prints_the_design_code_table_of_the_executable(exe, tmp_path, example):
    """str(DesignCodes) is the table the executable prints, line for line (one formatter, the
    driver's): with wave heights (ground motion) and without (NaN cells as '-')."""
    copy_example(example, tmp_path / "run")
    result = subprocess.run([exe, example], cwd=tmp_path / "run", capture_output=True,
                            text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    inp = sloshdyn.read_namelist(EXAMPLES / example)
    table = str(inp.tank.design_codes(inp.ground_motion)).splitlines()
    printed = result.stdout.splitlines()
    first = printed.index(table[0])
    assert printed[first:first + len(table)] == table and len(table) == 7
    assert "ACI 350.3" in table[0] and table[1].startswith("  convective period [s]")


# --- 7. bad input through every front door; the record file untouched -----------------------

AT2_HEAD = "TITLE\nSOURCE\nACCELERATION TIME SERIES IN UNITS OF G\n"
BAD_RECORDS = {
    # name: (file name, its text (None: no file), units, words of the message)
    "one AT2 sample": ("r.AT2", AT2_HEAD + "NPTS= 1, DT= 0.01 SEC\n 0.1\n", "g",
                       ["only 1 sample", "at least 2"]),
    "one column sample": ("r.csv", "0.0, 0.1\n", "m/s^2", ["only 1 sample", "at least 2"]),
    "non-uniform step": ("r.csv", "0, 0.1\n0.01, 0.2\n0.03, 0.1\n", "m/s^2",
                         ["line 3", "non-uniform time step", "0.02 s"]),
    "time repeats": ("r.csv", "0, 0.1\n0.01, 0.2\n0.01, 0.1\n", "m/s^2",
                     ["line 3", "time does not increase", "t = 0.01 s"]),
    "time decreases": ("r.csv", "0, 0.1\n-0.01, 0.2\n", "m/s^2",
                       ["line 2", "time does not increase"]),
    "NaN sample": ("r.csv", "0, 0.1\n0.01, NaN\n0.02, 0.1\n", "m/s^2",
                   ["line 2", "'NaN' is not finite"]),
    "Inf sample": ("r.AT2", AT2_HEAD + "NPTS= 3, DT= 0.01 SEC\n 0.1 -Inf 0.2\n", "g",
                   ["line 5", "value 2", "'-Inf' is not finite"]),
    "unknown units": ("r.csv", "0, 0.1\n0.01, 0.2\n", "furlongs",
                      ["units = 'furlongs'", "g, m/s^2 or cm/s^2"]),
    "AT2 without NPTS": ("r.AT2", AT2_HEAD + "DT= 0.01 SEC\n 0.1 0.2\n", "g",
                         ["line 4", "no number of points NPTS"]),
    "AT2 with DT = 0": ("r.AT2", AT2_HEAD + "NPTS= 2, DT= 0.0 SEC\n 0.1 0.2\n", "g",
                        ["line 4", "no time step DT > 0"]),
    "AT2 with DT < 0": ("r.AT2", AT2_HEAD + "NPTS= 2, DT= -0.01 SEC\n 0.1 0.2\n", "g",
                        ["no time step DT > 0", "DT= -0.01"]),
    "fewer values than NPTS": ("r.AT2", AT2_HEAD + "NPTS= 5, DT= 0.01 SEC\n 0.1 0.2 0.3\n", "g",
                               ["NPTS = 5", "3 values"]),
    "missing file": ("nowhere.AT2", None, "g", ["nowhere.AT2", "no such file"]),
}
SEISMIC_TANK = "&tank " + ", ".join(f"{k} = {v!r}" for k, v in TANK.items()) + \
    ", support_frequency = 2.0 /\n&analysis kind = 'seismic' /\n&output directory = 'out' /\n"


def bad_record_case(folder, case):
    """Write the case's record and namelist into folder; the record's mtime set in the past."""
    name, text, units, words = BAD_RECORDS[case]
    record = folder / name
    if text is not None:
        record.write_text(text)
        os.utime(record, ns=(1_000_000_000_000_000_000, 1_000_000_000_000_000_000))
    (folder / "input.nml").write_text(
        SEISMIC_TANK + f"&ground_motion record = '{name}', units = '{units}' /\n")
    return record, units, words


def file_state(path):
    return (path.read_bytes(), path.stat().st_mtime_ns) if path.exists() else None


@pytest.mark.parametrize("case", BAD_RECORDS)
def test_bad_record_through_every_door(exe, tmp_path, case):
    """The executable exits 3 (bad input) with one message naming the file, the line and the
    rule, prints nothing else and writes nothing; Python raises the same exception class with
    the same message from the namelist and from GroundMotion.from_file; the record is never
    modified (bytes and mtime)."""
    record, units, words = bad_record_case(tmp_path, case)
    before, tree = file_state(record), directory_tree(tmp_path)
    result = run(exe, "input.nml", tmp_path)
    assert result.returncode == 3 and result.stdout == ""
    assert result.stderr.startswith("sloshdyn: error: &ground_motion: ")
    for word in words:
        assert word in result.stderr, (word, result.stderr)
    assert directory_tree(tmp_path) == tree and file_state(record) == before

    with pytest.raises(sloshdyn.SloshdynError) as from_namelist:
        sloshdyn.read_namelist(tmp_path / "input.nml")
    with pytest.raises(sloshdyn.SloshdynError) as from_file:
        sloshdyn.GroundMotion.from_file(record, units=units)
    assert type(from_file.value) is type(from_namelist.value)
    assert str(from_namelist.value) == "&ground_motion: " + str(from_file.value)
    for word in words:
        assert word in str(from_file.value)
    assert directory_tree(tmp_path) == tree and file_state(record) == before


@pytest.mark.parametrize("case", ["AT2 without NPTS", "non-uniform step", "missing file"])
def test_bad_record_through_sloshdyn_py_run(exe, tmp_path, case):
    record, _, words = bad_record_case(tmp_path, case)
    before, tree = file_state(record), directory_tree(tmp_path)
    result = subprocess.run([str(pathlib.Path(exe).with_name("sloshdyn-py")), "run", "input.nml"],
                            cwd=tmp_path, capture_output=True, text=True, timeout=60)
    assert result.returncode == 3 and result.stdout == ""
    assert result.stderr.startswith("sloshdyn-py: error: &ground_motion: ")
    for word in words:
        assert word in result.stderr
    assert directory_tree(tmp_path) == tree and file_state(record) == before


@pytest.mark.parametrize("field,value,words", [
    ("freeboard", 0.0, ["freeboard = 0", "> 0"]),
    ("freeboard", -1.0, ["freeboard = -1", "> 0"]),
    ("radius", -5.0, ["radius = -5", "> 0"]),
    ("liquid_depth", -6.0, ["liquid_depth = -6", "> 0"]),
    ("tank_mass", -1.0, ["tank_mass = -1", ">= 0"]),
    ("liquid_density", -1000.0, ["liquid_density = -1000", "give exactly one"]),
    ("support_height", -1.0, ["support_height = -1", ">= 0"]),
    ("support_damping", -0.1, ["support_damping = -0.1", "[0, 1)"]),
    ("support_damping", 1.0, ["support_damping = 1", "[0, 1)"]),
    ("sloshing_damping", -0.01, ["sloshing_damping = -0.01", "[0, 1)"]),
    ("sloshing_damping", 1.0, ["sloshing_damping = 1", "[0, 1)"]),
])
def test_bad_tank_in_python_and_in_the_executable(exe, tmp_path, field, value, words):
    """Tank(...) refuses what &tank refuses, with the same message (test_bad_input.py covers a
    few of these for the namelist alone)."""
    with pytest.raises(sloshdyn.InputError) as info:
        sloshdyn.Tank(**{**TANK, "support_frequency": 2.0, field: value})
    for word in words:
        assert word in str(info.value), (word, str(info.value))
    (tmp_path / "input.nml").write_text(SEISMIC_TANK.replace(" /", f", {field} = {value!r} /", 1)
                                        + "&ground_motion peak_acceleration = 0.1, "
                                          "frequency = 0.3 /\n")
    result = run(exe, "input.nml", tmp_path)
    assert result.returncode == 3 and result.stderr.strip() == \
        f"sloshdyn: error: &tank: {info.value}"
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("make,words", [
    (lambda: sloshdyn.GroundMotion(dt=0.01, acceleration=[0.1]), ["1 samples", "at least 2"]),
    (lambda: sloshdyn.GroundMotion(dt=0.0, acceleration=[0.1, 0.2]), ["dt = 0", "at least 1e-6 s"]),
    (lambda: sloshdyn.GroundMotion(dt=0.01, acceleration=[0.1, math.nan]),
     ["sample 2 = NaN", "finite"]),
    (lambda: sloshdyn.GroundMotion(dt=0.01, acceleration=[math.inf, 0.1]),
     ["sample 1 = +Infinity", "finite"]),
    (lambda: sloshdyn.GroundMotion(dt=0.01, acceleration=[0.1, 0.2], units="furlongs"),
     ["units = 'furlongs'"]),
    (lambda: sloshdyn.GroundMotion.harmonic(0.1, 0.0), ["frequency = 0", "> 0"]),
    (lambda: sloshdyn.GroundMotion.harmonic(-0.1, 1.0), ["peak_acceleration = -0.980665"]),
    (lambda: tapered_sines().scaled(sa=0.1, period=3.0, damping=1.0),
     ["target_damping = 1", "[0, 1)"]),
    (lambda: tapered_sines().response_spectrum([3.0], damping=-0.01), ["damping = -0.01"]),
])
def test_bad_ground_motion_in_python(make, words):
    with pytest.raises(sloshdyn.InputError) as info:
        make()
    for word in words:
        assert word in str(info.value), (word, str(info.value))


# --- 8. the linear sloshing damping zeta -------------------------------------------------------

# The code before zeta existed (commit f9651fc, the parent of the issue 12 change), run on the
# paper's Fig 12 parameters at rho = 0.513, A = 2 from y0 = (1.05, 0, 0.01, 0) beyond the wall:
# the state at tau = 60 by each method, eq (15) and its Jacobian at y = (1.1, -0.4, 0.05, 0.2),
# tau = 1.3, and the eigenvalues of the trivial equilibrium (Fig 12 parameters), as hex floats.
# The trajectories' bits also depend on the sine glibc picks at run time: BEFORE_ZETA_NO_FMA is
# the same commit run with glibc's sine for processors without FMA (GLIBC_TUNABLES=
# glibc.cpu.hwcaps=-AVX2,-FMA); its right-hand side, Jacobian and eigenvalues are BEFORE_ZETA's.
BEFORE_ZETA_NO_FMA = {
    "rk45": ["-0x1.449a05b8b844ep-2", "-0x1.0d748b3d66b03p+0", "-0x1.e2ae00ecdcc1cp+0",
             "0x1.50546a3fd42c3p-4"],
    "dop853": ["-0x1.448c67b9d44cbp-2", "-0x1.0d884ce4715fcp+0", "-0x1.e2a02ba4af9b2p+0",
               "0x1.504f232a934cbp-4"],
}
BEFORE_ZETA = {
    "rk45": ["-0x1.449a05bb04ad8p-2", "-0x1.0d748b3a121a8p+0", "-0x1.e2ae00ef3183fp+0",
             "0x1.50546a40b89e1p-4"],
    "dop853": ["-0x1.448c67ba1dcf8p-2", "-0x1.0d884ce406f63p+0", "-0x1.e2a02ba4fa1aep+0",
               "0x1.504f232ab0de9p-4"],
    "dydt": ["-0x1.999999999999ap-2", "-0x1.7081b7f1a5b89p+5", "0x1.999999999999ap-3",
             "0x1.5dc6471a36695p+4"],
    "jacobian": ["0x0.0p+0", "0x1.0000000000000p+0", "0x0.0p+0", "0x0.0p+0",
                 "-0x1.ac256584ad454p+8", "0x1.009338e33356ep-7", "0x1.626ce4eb8d62cp+4",
                 "0x1.a1bffdd123a0cp-3", "0x0.0p+0", "0x0.0p+0", "0x0.0p+0",
                 "0x1.0000000000000p+0", "0x1.63119a1e78d72p+7", "-0x1.7ead305244bb2p-2",
                 "-0x1.fddeba19f90cdp+4", "-0x1.8809249f26de3p-4"],
    "eigenvalues": ["-0x1.5298a5a8f25e2p-11", "-0x1.5298a5a8f25e2p-11", "-0x1.7362296a85c3fp-12",
                    "-0x1.7362296a85c3fp-12", "0x1.887824932c769p+0", "-0x1.887824932c769p+0",
                    "0x1.04cafe890cd5fp-1", "-0x1.04cafe890cd5fp-1"],
}


def hex_floats(values):
    return [float(v).hex() for v in np.ravel(values)]


def test_zeta_zero_is_the_papers_model_bit_for_bit():
    from sloshdyn.figures import FIG12
    assert FIG12.zeta == 0
    p = FIG12.replace(rho=0.513, A=2.0)
    runs = {method: hex_floats(sloshdyn.simulate(p, 60.0, [1.05, 0, 0.01, 0], n_out=7,
                                                 integration=sloshdyn.Integration(method=method)
                                                 ).y[:, -1])
            for method in ("rk45", "dop853")}
    assert runs in ({method: BEFORE_ZETA[method] for method in runs}, BEFORE_ZETA_NO_FMA)
    m = sloshdyn.equations_of_motion(p, 1.3, [1.1, -0.4, 0.05, 0.2])
    assert hex_floats(m.dydt) == BEFORE_ZETA["dydt"]
    assert hex_floats(m.jacobian) == BEFORE_ZETA["jacobian"]
    eigenvalues = sloshdyn.equilibria(FIG12).trivial.eigenvalues
    assert hex_floats(np.concatenate([eigenvalues.real, eigenvalues.imag])) == \
        BEFORE_ZETA["eigenvalues"]


@pytest.mark.parametrize("zeta", [0.005, 0.02, 0.1])
def test_free_decay_has_the_logarithmic_decrement_of_zeta(zeta):
    """Free sloshing from x1 = 0.01 on stiff supports: the peaks decay as exp(-zeta omega t),
    so with s = -d ln(peak)/dtau and the damped frequency w_d (peak spacing), zeta = s/sqrt(w_d^2
    + s^2). Measured: within 1.8e-5 (the 50 Hz supports' coupling)."""
    p = stiff_tank(sloshing_damping=zeta).parameters()
    assert p.zeta == zeta
    step = 2 * np.pi / 256
    tau = step * np.arange(20 * 256 + 1)
    x = sloshdyn.simulate(p, tau[-1], [0.01, 0, 0, 0], tau_out=tau,
                          integration=sloshdyn.Integration(rtol=1e-12, atol=1e-15)).x1
    i = np.flatnonzero((x[1:-1] > x[:-2]) & (x[1:-1] >= x[2:])) + 1
    before, at, after = x[i - 1], x[i], x[i + 1]
    shift = 0.5 * (before - after) / (before - 2 * at + after)    # the parabola's vertex
    peaks, times = at - 0.25 * (before - after) * shift, tau[i] + shift * step
    slope = -np.polyfit(times, np.log(peaks), 1)[0]
    damped = 2 * np.pi / np.mean(np.diff(times))
    assert slope / math.hypot(damped, slope) == pytest.approx(zeta, rel=1e-4)


def linearised(p):
    """Eq (10) linearised at rest, typed from eq (11): M q'' + C q' + K q = 0 with
    M = [[1, 1/s1], [mu1 s1, 1]], C = diag(2 zeta (+ delta if p = 0), gamma),
    K = diag(1, kappa - s1); the first-order system matrix."""
    mass = np.array([[1, 1 / p.s1], [p.mu1 * p.s1, 1]])
    damping = np.diag([2 * p.zeta + (p.delta if p.p == 0 else 0), p.gamma])
    stiffness = np.diag([1, p.kappa - p.s1])
    return np.block([[np.zeros((2, 2)), np.eye(2)],
                     [-np.linalg.solve(mass, stiffness), -np.linalg.solve(mass, damping)]]), \
        np.linalg.solve(mass, damping), np.linalg.solve(mass, stiffness)


@pytest.mark.parametrize("changes", [dict(zeta=0.03), dict(zeta=0.03, p=0, delta=0.2),
                                     dict(zeta=0.2, gamma=0.05)])
def test_linear_analysis_includes_zeta(changes):
    """The trivial equilibrium's eigenvalues (dgeev of the code's Jacobian) and the Routh-Hurwitz
    coefficients of eq (20) (errata: the p = 0 form) are those of the independent linearisation;
    the multiple-scales modal damping gamma11, gamma22 are the diagonal of the damping in modal
    coordinates, V^-1 M^-1 C V (invariant to the scaling of the mode shapes V)."""
    from sloshdyn.figures import FIG12
    p = FIG12.replace(**changes)
    system, damping, stiffness = linearised(p)
    expected = np.linalg.eigvals(system)
    eq = sloshdyn.equilibria(p)
    computed = eq.trivial.eigenvalues
    assert np.sort_complex(computed) == pytest.approx(np.sort_complex(expected), rel=1e-12,
                                                      abs=1e-14)
    assert eq.routh_coefficients == pytest.approx(np.poly(expected)[1:].real, rel=1e-12)
    if p.p >= 1:
        squares, shapes = np.linalg.eig(stiffness)
        shapes = shapes[:, np.argsort(squares)]
        modal = np.linalg.solve(shapes, damping @ shapes)
        m = sloshdyn.modal_coefficients(p)
        assert [m.coefficients["gamma11"], m.coefficients["gamma22"]] == pytest.approx(
            np.diag(modal), rel=1e-12)


def test_jacobian_with_zeta_matches_finite_differences():
    """The analytic Jacobian (zeta in d(x1'')/d(x1')) against central differences of eq (15)
    at random states, harmonic forcing on; relative 1e-7 (the differences' error ~ h^2, h = 1e-6)."""
    from sloshdyn.figures import FIG12
    p = FIG12.replace(zeta=0.07, rho=0.6, A=0.3, p=1)
    rng = np.random.default_rng(12)
    for y in rng.uniform(-1.2, 1.2, size=(10, 4)):
        tau = rng.uniform(0, 20)
        jacobian = sloshdyn.equations_of_motion(p, tau, y).jacobian
        h = 1e-6
        columns = [(sloshdyn.equations_of_motion(p, tau, y + h * e).dydt -
                    sloshdyn.equations_of_motion(p, tau, y - h * e).dydt) / (2 * h)
                   for e in np.eye(4)]
        assert np.max(np.abs(jacobian - np.array(columns).T)) < 1e-7 * np.max(np.abs(jacobian))
    # zeta enters the Jacobian by -2 zeta in d(x1'')/d(x1') (through M^-1): the difference of
    # two zetas is linear in it
    y = np.array([0.3, 0.2, -0.1, 0.05])
    delta = sloshdyn.equations_of_motion(p, 1.0, y).jacobian - \
        sloshdyn.equations_of_motion(p.replace(zeta=0.0), 1.0, y).jacobian
    c12 = math.cos(p.theta0 * (y[0] + y[2]))
    det = 1 - p.mu1 * c12**2
    assert delta[[1, 3], 1] == pytest.approx([-2 * p.zeta / det, 2 * p.zeta * p.mu1 * p.s1 * c12 /
                                              det], rel=1e-12)


# --- 9. a record's samples are never stepped over ----------------------------------------------

def spike(index, dt=0.002, n=5001):
    a = np.zeros(n)
    a[index] = 1.0
    return sloshdyn.GroundMotion(dt=dt, acceleration=a, units="m/s^2")


@pytest.mark.parametrize("index", [1000, 5000], ids=["inside", "last sample"])
@pytest.mark.parametrize("n_out", [101, 4001])
def test_a_single_sample_spike_is_felt_exactly(index, n_out):
    """A record of zeros but one sample of 1 m/s^2: a triangular pulse 2 dt = 4 ms wide (at the
    last sample only its rising half: the ground is at rest after the record). From rest and
    without load the step size grows without bound, so an integrator that did not end a step
    on every sample would step over the pulse; the output times (101: none near the pulse) play
    no part. Against the exact SDOF response (expm): peak within 1e-4 (measured 1.8e-5), the
    history within 1e-3 of the peak once the supports' 50 Hz ringing has gone (1 s after the
    pulse; measured 1.4e-4) and within 1 % during it (measured 0.4 %: the tank lags the ground
    for those 4 ms)."""
    tank = stiff_tank()
    ground = spike(index)
    r = sloshdyn.seismic_response(tank, ground, t_end=20.0, n_out=n_out, integration=TIGHT)
    x = sdof_exact(*record_knots(ground, 20.0), 2 * np.pi / tank.sloshing_period,
                   tank.sloshing_damping, r.t)
    peak = np.max(np.abs(x))
    assert peak > 4e-4
    assert np.max(np.abs(r.sloshing_displacement)) == pytest.approx(peak, rel=1e-4)
    error = np.abs(r.sloshing_displacement - x)
    assert np.max(error[r.t > index * ground.dt + 1]) < 1e-3 * peak
    assert np.max(error) < 1e-2 * peak


def test_every_sample_ends_a_step(exe, tmp_path):
    """The executable's step count for the spike record: at least one accepted step per sample
    interval (the breakpoints), although the load is zero almost everywhere."""
    ground = spike(1000)
    write_at2(tmp_path / "spike.AT2", ground)
    tank = stiff_tank()
    (tmp_path / "input.nml").write_text(namelist(
        tank, "record = 'spike.AT2'", "&analysis kind = 'simulate' /\n&simulation t_end = 40.0,"
        " n_out = 3 /\n"))
    assert run(exe, "input.nml", tmp_path).returncode == 0
    counts = np.loadtxt(tmp_path / "out" / "simulation.csv", delimiter=",", skiprows=1)
    record_end = tank.properties["omega"] * ground.duration       # 18.8 < t_end = 40 in tau
    assert record_end < 40 and counts[1] >= len(ground.acceleration) - 1


# --- 10. harmonic sweeps at constant peak ground acceleration ---------------------------------

@pytest.mark.parametrize("start_from,threads", [("y0", 2), ("previous", 1)])
def test_harmonic_sweep_at_small_amplitude_is_the_damped_sdof(start_from, threads):
    """0.005 g at frequency ratios 1/3, 1/2, 2, 3 on stiff supports, 5 % sloshing damping:
    the peak ground acceleration column is the given one at every frequency (A rho^2 kept), and
    the wave height, sloshing displacement and pendulum angle follow from the steady amplitude of
    x'' + 2 zeta omega x' + omega^2 x = a sin(Omega t), X = a/sqrt((omega^2 - Omega^2)^2 +
    (2 zeta omega Omega)^2), theta = X/l, wave = 2 R sin(theta)/(1.84^2 - 1). Tolerance 1e-3
    (the window's maximum is sampled 512 times a period: 2e-5; the 50 Hz supports amplify the
    base motion by 1/(1 - (f/f_s)^2)); measured 3e-6 to 2e-4."""
    tank = stiff_tank(sloshing_damping=0.05)
    p = tank.properties
    omega, length, zeta = p["omega"], p["pendulum_length"], tank.sloshing_damping
    frequencies = omega / (2 * np.pi) * np.array([1 / 3, 1 / 2, 2, 3])
    steady = sloshdyn.Steady(transient_periods=100, settle_tol=1e-9, window_periods=20,
                             samples_per_period=512)
    h = sloshdyn.harmonic_sweep(tank, 0.005, frequencies, units="g", steady=steady,
                                start_from=start_from, threads=threads, integration=TIGHT)
    a = 0.005 * G
    assert h.peak_ground_acceleration == pytest.approx(np.full(4, a), rel=1e-14)
    forcing = 2 * np.pi * frequencies
    theta = a / np.hypot(omega**2 - forcing**2, 2 * zeta * omega * forcing) / length
    assert h.pendulum_angle == pytest.approx(theta, rel=1e-3)
    assert h.sloshing_displacement == pytest.approx(length * np.sin(theta), rel=1e-3)
    assert h.wave_height == pytest.approx(2 * TANK["radius"] / (1.84**2 - 1) * np.sin(theta),
                                          rel=1e-3)
    assert list(h.motion) == [1] * 4 and not any(h.roof_reached)


def test_harmonic_sweep_judges_the_roof_on_the_free_wave():
    """The sweep's roof verdict is the free wave's (the tank without a roof, beta = delta = 0),
    as seismic_response's: 0.05 g at 1/3, 1 and 3 times the sloshing frequency, 5 % sloshing
    damping, on 50 Hz supports. Off resonance the free wave is the damped SDOF's (as above,
    1e-3); at resonance it is about twice the 1 m freeboard, so the roof is reached for beta =
    10 and 1000 alike, with and without the paper's impact model: the tank's own sweep (no
    wall) reports the free wave capped at the roof; with roof_contact = 'impact' at beta = 1000
    the impact model's own wave, pushed back by the smooth wall, stays below the freeboard (the
    old verdict, |x1| >= 1, said 'not reached')."""
    steady = sloshdyn.Steady(transient_periods=100, settle_tol=1e-9, window_periods=20,
                             samples_per_period=512)
    verdicts = []
    for beta, contact in ((10.0, "none"), (1000.0, "none"), (10.0, "impact"),
                          (1000.0, "impact")):
        tank = stiff_tank(sloshing_damping=0.05, impact_stiffness=beta, roof_contact=contact)
        p = tank.properties
        omega, length = p["omega"], p["pendulum_length"]
        frequencies = omega / (2 * np.pi) * np.array([1 / 3, 1, 3])
        h = sloshdyn.harmonic_sweep(tank, 0.05, frequencies, units="g", steady=steady,
                                    start_from="y0", integration=TIGHT)
        a, forcing = 0.05 * G, 2 * np.pi * frequencies[[0, 2]]
        theta = a / np.hypot(omega**2 - forcing**2, 2 * 0.05 * omega * forcing) / length
        assert h.free_wave_height[[0, 2]] == pytest.approx(
            2 * TANK["radius"] / (1.84**2 - 1) * np.sin(theta), rel=1e-3)
        assert h.free_wave_height[1] > 1.5 * TANK["freeboard"]
        verdicts.append(list(h.roof_reached))
        if contact == "none":
            assert h.wave_height[1] == pytest.approx(TANK["freeboard"], rel=1e-12)
        elif beta == 1000.0:
            assert h.wave_height[1] < TANK["freeboard"]
    assert verdicts == [[0, 1, 0]] * 4


def test_frequency_sweep_example_reduced_through_both_doors(exe, tmp_path):
    """A reduced copy of tank_frequency_sweep.nml (3 frequencies up and down, short transients):
    the executable's harmonic_sweep.csv keeps the peak ground acceleration at 0.05 g on every
    row, and Python's harmonic_sweep gives the same table bit for bit."""
    text = (EXAMPLES / "tank_frequency_sweep.nml").read_text()
    text = text.replace("n_points = 26", "n_points = 3").replace(
        "&output", "&steady transient_periods = 20, settle_tol = 0, window_periods = 16 /\n"
                   "&output")
    (tmp_path / "sweep.nml").write_text(text)
    result = run(exe, "sweep.nml", tmp_path)
    assert result.returncode == 0, result.stderr
    inp = sloshdyn.read_namelist(tmp_path / "sweep.nml")
    table = np.loadtxt(tmp_path / inp.directory / "harmonic_sweep.csv", delimiter=",",
                       skiprows=1)
    assert table[:, 0].tolist() == [0.2, 0.325, 0.45, 0.325, 0.2]     # up, then back down
    assert np.all(table[:, 1] == table[0, 1]) and table[0, 1] == pytest.approx(0.05 * G,
                                                                               rel=1e-14)
    h = sloshdyn.harmonic_sweep(inp.tank, 0.05, table[:, 0], units="g",
                                steady=sloshdyn.Steady(transient_periods=20, settle_tol=0,
                                                       window_periods=16))
    assert np.array_equal(h.table.T, table)


# --- loads: their definitions, and the rigid liquid under slow motion -------------------------

def test_loads_are_the_documented_functions_of_the_state(record_run):
    """seismic.csv's columns from x1, x2 (docs/namelist.md, docs/model.md): pendulum angle
    theta = theta0 x1, sloshing displacement l sin(theta), wave height 2 R sin(theta)/(1.84^2 -
    1) (below the roof: the free wave), tank drift L sin(phi); the tank's and the convective
    mass's accelerations a_t and a_m from the state and its numerical derivative (the momentum
    test's differences), the moment with the base pressure from the two (docs/model.md,
    "Loads": the rigid liquid's m_F a_t R^2/(4h), the mode's m (h_c' - h_c)(a_m - a_t)); the
    paper's impact force is not there (roof_contact = 'none')."""
    s = record_run
    r, tank = s.r, s.tank
    assert np.array_equal(r.x1, s.y[0]) or np.max(np.abs(r.x1 - s.y[0])) < 1e-12
    theta = s.theta0 * r.x1
    assert r.pendulum_angle == pytest.approx(theta, rel=1e-15, abs=0)
    assert r.sloshing_displacement == pytest.approx(s.l * np.sin(theta), rel=1e-14, abs=1e-300)
    assert r.wave_height == pytest.approx(2 * tank.radius / (1.84**2 - 1) * np.sin(theta),
                                          rel=1e-14, abs=1e-300)
    assert r.tank_drift == pytest.approx(s.L * np.sin(s.theta0 * r.x2), rel=1e-14, abs=1e-300)
    assert r.impact_force is None and r.free_wave_height == pytest.approx(r.wave_height)
    assert r.ground_acceleration == pytest.approx(s.accel, rel=0, abs=1e-12 * 2.0)   # pga 2
    h = s.t[1] - s.t[0]
    tank_velocity = s.velocity + s.L * np.cos(s.phi) * s.phi_d
    mass_velocity = tank_velocity + s.l * np.cos(s.theta) * s.theta_d
    for accel, velocity in ((r.tank_acceleration, tank_velocity),
                            (r.convective_acceleration, mass_velocity)):
        differences = cell_derivative(velocity, h, 8)[::2]
        np.testing.assert_allclose(accel[::2], differences, rtol=0,
                                   atol=1e-7 * np.max(np.abs(accel)))
    p = tank.properties
    rise = tank.radius / 1.84 / np.sinh(1.84 * tank.liquid_depth / tank.radius)
    expected = r.overturning_moment + p["liquid_mass"] * tank.radius**2 / (
        4 * tank.liquid_depth) * r.tank_acceleration + s.m * rise * (
        r.convective_acceleration - r.tank_acceleration)
    np.testing.assert_allclose(r.overturning_moment_ibp, expected, rtol=1e-12,
                               atol=1e-12 * np.max(np.abs(expected)))


def test_slow_ground_motion_gives_the_rigid_liquid_loads():
    """Ground motion 150 times slower than the sloshing (0.002 Hz), stiff supports, heavy
    sloshing damping (0.9, so the start-up transient is gone after 60 s): the liquid moves with
    the tank as a rigid body, so the base shear is M u'' and the overturning moment about the
    bottom is (m_F h/2 + m_tank (h + freeboard)/2) u'' (a rigidly accelerated liquid loads the
    wall uniformly in depth: its resultant at h/2; the shell and roof at their mid-height).
    This checks the impulsive and convective heights through the loads. Error ~ (f/f_sloshing)^2
    = 4.5e-5; measured 1.5e-5 (shear), 1.9e-5 (moment)."""
    tank = stiff_tank(sloshing_damping=0.9)
    p = tank.properties
    ground = sloshdyn.GroundMotion.harmonic(0.5, 0.002, units="m/s^2")
    r = sloshdyn.seismic_response(tank, ground, t_end=500.0, n_out=1001, integration=TIGHT)
    later = r.t > 60
    a = r.ground_acceleration[later]
    h, freeboard = TANK["liquid_depth"], TANK["freeboard"]
    moment = (p["liquid_mass"] * h / 2 + TANK["tank_mass"] * (h + freeboard) / 2) * a
    assert np.max(np.abs(r.base_shear[later] - p["total_mass"] * a)) < \
        1e-4 * p["total_mass"] * 0.5
    assert np.max(np.abs(r.overturning_moment[later] - moment)) < 1e-4 * np.max(np.abs(moment))
