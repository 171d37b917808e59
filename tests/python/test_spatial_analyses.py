"""The spatial model in the analyses beside 'seismic' and 'swirl' (issue 26: "every analysis that
makes sense for the spatial model accepts it"): its time history (kind = 'simulate',
sloshdyn.spatial.simulate) and one of its periodic orbits (kind = 'steady_state',
sloshdyn.spatial.swirl_orbit), at both front doors; the analyses that refuse it, with why.

Independent sources: the planar model's own simulation (the plane is invariant: the spatial
history with y-states and y-forcing zero is the planar one); the energy and the angular
momentum about the vertical, written here from the Cartesian positions of the two masses
(conserved without damping and forcing); the symmetry of the model under rotations about the
vertical (forcing along an azimuth from rest moves the pendulum in that vertical plane exactly
as the planar model moves); scipy's DOP853 for the periodicity of an orbit."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import sloshdyn
from sloshdyn import spatial
from conftest import read_csv, run, write

PAPER = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=np.pi / 4, gamma=0.001,
                            zeta=0.01, A=0.001, rho=0.5)
TIGHT = sloshdyn.Integration(rtol=1e-14, atol=1e-16, method="vern9")
SWIRL = sloshdyn.Parameters(s1=1.0, mu1=0.01, kappa=1e3, theta0=1.4, beta=0.0, gamma=0.0,
                            delta=0.0, A=1e-3, rho=1.003, zeta=5e-4, n=6, p=2)


def test_the_plane_is_the_planar_simulation():
    tau = np.linspace(0, 60, 121)
    planar = sloshdyn.simulate(PAPER, 60, [0.5, 0, 0.3, 0], tau_out=tau, integration=TIGHT)
    space = spatial.simulate(PAPER, 60, [0.5, 0, 0.3, 0, 0, 0, 0, 0], tau_out=tau,
                             integration=TIGHT)
    # the RMS error norm over 8 states takes other steps than over 4: equal to the tolerance
    # (measured 2.9e-13 with x1 up to 0.76)
    assert np.abs(space.y[:4] - planar.y).max() < 1e-12
    assert np.all(space.y[4:] == 0)                       # the plane is invariant, exactly
    np.testing.assert_allclose(space.tilt, np.abs(planar.x1), rtol=1e-12, atol=1e-12)
    x1 = space.y[0]
    assert np.all(space.tilt_azimuth[x1 > 0] == 0) and np.all(space.tilt_azimuth[x1 < 0] == np.pi)
    assert space.method == "vern9" and space.tau_reached == 60


def _invariants(params, y):
    """Energy and angular momentum about the vertical relative to the ground (unit M L^2 omega^2
    and M L^2 omega), from the Cartesian positions (docs/model.md eq S2-S3), by numpy."""
    t0, s1, mu1 = params.theta0, params.s1, params.mu1

    def unit(a, b, sigma, da, db):
        u = np.array([np.sin(a) * np.cos(b), np.sin(b), sigma * np.cos(a) * np.cos(b)])
        du_a = np.array([np.cos(a) * np.cos(b), 0, -sigma * np.sin(a) * np.cos(b)])
        du_b = np.array([-np.sin(a) * np.sin(b), np.cos(b), -sigma * np.cos(a) * np.sin(b)])
        return u, du_a * da + du_b * db

    n, vn = unit(t0 * y[0], t0 * y[4], -1, t0 * y[1], t0 * y[5])
    t, vt = unit(t0 * y[2], t0 * y[6], 1, t0 * y[3], t0 * y[7])
    rb, vb = t + s1 * n, vt + s1 * vn
    rods = np.arccos(np.cos(t0 * y[2]) * np.cos(t0 * y[6]))
    tilt = np.arccos(np.cos(t0 * y[0]) * np.cos(t0 * y[4]))
    energy = ((1 - mu1) * vt @ vt / 2 + mu1 * vb @ vb / 2 + params.kappa * rods**2 / 2
              + s1 * (t[2] + mu1 * s1 * n[2])
              + mu1 * s1**2 * params.beta * t0 / (2 * params.n) * (tilt / t0)**(2 * params.n))
    momentum = (1 - mu1) * (t[0] * vt[1] - t[1] * vt[0]) + mu1 * (rb[0] * vb[1] - rb[1] * vb[0])
    return energy, momentum


def test_energy_and_angular_momentum_are_conserved_without_damping_and_forcing():
    free = PAPER.replace(gamma=0.0, delta=0.0, zeta=0.0, A=0.0, beta=10.0)
    y0 = [0.6, 0.1, 0.2, 0.0, 0.5, -0.3, -0.1, 0.05]     # swirling, up to the impact range
    run_ = spatial.simulate(free, 100, y0, n_out=51, integration=sloshdyn.Integration(
        rtol=1e-12, atol=1e-14, method="dop853"))
    e, l = np.array([_invariants(free, run_.y[:, i]) for i in range(51)]).T
    assert run_.tilt.max() > 0.7      # the impact potential acts (beta (0.7)^11 = 0.2)
    assert np.ptp(e) < 1e-9 * abs(e[0]) and np.ptp(l) < 1e-10
    assert abs(l[0]) > 1e-2                               # a swirl, not a planar motion


def test_forcing_along_an_azimuth_moves_the_pendulum_in_that_plane():
    """Rotational symmetry: from rest, forcing along alpha gives the planar motion turned by
    alpha; the tilt is the planar |x1|, towards alpha or alpha + pi."""
    alpha = 0.7
    tau = np.linspace(0, 80, 161)
    opts = sloshdyn.Integration(rtol=1e-12, atol=1e-14, method="dop853")
    planar = sloshdyn.simulate(PAPER, 80, tau_out=tau, integration=opts)
    space = spatial.simulate(PAPER, 80, azimuth=alpha, tau_out=tau, integration=opts)
    np.testing.assert_allclose(space.tilt, np.abs(planar.x1), rtol=0, atol=1e-9)
    moving = np.abs(planar.x1) > 1e-3
    turned = np.angle(np.exp(1j * (space.tilt_azimuth - alpha)))   # 0 or pi
    sign = np.where(planar.x1 > 0, 0.0, np.pi)
    np.testing.assert_allclose(np.abs(np.angle(np.exp(1j * (turned - sign))))[moving], 0,
                               atol=1e-6)


SIMULATE = ("&model s1 = 1.5, mu1 = 0.5, kappa = 1.804897259, theta0 = 0.7853981633974483, "
            "gamma = 0.001, zeta = 0.01, planar = .false. /\n"
            "&excitation A = 0.001, rho = 0.5, azimuth = 0.4, ellipticity = 0.5 /\n"
            "&analysis kind = 'simulate' /\n"
            "&simulation t_end = 40, n_out = 81, y0 = 0.2, 0, 0.1, 0, 0.1, 0.05, 0, 0 /\n"
            "&integration method = 'dop853', rtol = 1e-11 /\n&output directory = 'out' /\n")


def test_simulate_door_equals_the_python_api(exe, tmp_path):
    path = write(tmp_path, SIMULATE)
    result = run(exe, path.name, tmp_path)
    assert result.returncode == 0, result.stderr
    inp = sloshdyn.read_namelist(path)
    assert not inp.planar and inp.spatial == {"azimuth": 0.4, "ellipticity": 0.5}
    assert inp.simulation["y0"] == [0.2, 0, 0.1, 0, 0.1, 0.05, 0, 0]
    r = spatial.simulate(inp.params, inp.simulation["t_end"], inp.simulation["y0"],
                         n_out=inp.simulation["n_out"], integration=inp.integration,
                         **inp.spatial)
    rows = read_csv(tmp_path / "out" / "spatial_history.csv")
    assert [row["tau"] for row in rows] == list(r.tau)
    for i, name in enumerate(("x1", "dx1", "x2", "dx2", "y1", "dy1", "y2", "dy2")):
        assert [row[name] for row in rows] == list(r.y[i]), name
    assert [row["tilt"] for row in rows] == list(r.tilt)
    assert [row["tilt_azimuth"] for row in rows] == list(r.tilt_azimuth)
    counts = read_csv(tmp_path / "out" / "simulation.csv")[0]
    assert counts["n_accepted"] == r.n_accepted and counts["n_rhs"] == r.n_rhs
    assert not (tmp_path / "out" / "history.csv").exists()


ORBIT = ("&model s1 = 1.0, mu1 = 0.01, kappa = 1000, theta0 = 1.4, beta = 0, gamma = 0, "
         "delta = 0, zeta = 5e-4, n = 6, p = 2, planar = .false. /\n"
         "&excitation A = 0.001, rho = 1.003 /\n&analysis kind = 'steady_state' /\n"
         "&simulation y0 = 0.1, 0, 0, 0, 0.01, 0, 0, 0 /\n&steady transient_periods = 400 /\n"
         "&output directory = 'out' /\n")


def _period_gap(params, y0):
    """max|y(T) - y0| by scipy's DOP853 on the spatial equations (independent of the shooting)."""
    sol = solve_ivp(lambda tau, y: spatial.equations_of_motion(params, tau, y).dydt,
                    (0, 2 * np.pi / params.rho), y0, method="DOP853", rtol=1e-12, atol=1e-14)
    assert sol.success
    return np.abs(sol.y[:, -1] - y0).max()


def test_steady_state_door_is_the_swirl_orbit(exe, tmp_path):
    path = write(tmp_path, ORBIT)
    result = run(exe, path.name, tmp_path)
    assert result.returncode == 0, result.stderr
    inp = sloshdyn.read_namelist(path)
    orbit = spatial.swirl_orbit(inp.params, inp.simulation["y0"], transient=400,
                                integration=inp.integration)
    row = read_csv(tmp_path / "out" / "swirl_orbit.csv")[0]
    assert [row[f"y{i}"] for i in range(1, 9)] == list(orbit.y0)
    assert row["swirl_amplitude"] == orbit.swirl_amplitude
    assert row["angular_momentum"] == orbit.angular_momentum
    assert [row[f"re_mu{i}"] + 1j * row[f"im_mu{i}"] for i in range(1, 9)] == \
        list(orbit.multipliers)
    assert orbit.swirl_amplitude > 0.5 * orbit.max_x1             # it left the plane
    assert _period_gap(SWIRL, orbit.y0) < 1e-8
    assert ("clockwise" in result.stdout) and orbit.stable


def test_a_turned_forcing_gives_the_turned_swirl():
    """The same swirl, whatever the azimuth of the forcing: |L_z| and the amplitudes agree."""
    start = [0.1, 0, 0, 0, 0.01, 0, 0, 0]
    a = spatial.swirl_orbit(SWIRL, start, transient=400)
    b = spatial.swirl_orbit(SWIRL, start, transient=400, azimuth=0.5)
    assert abs(b.angular_momentum) == pytest.approx(abs(a.angular_momentum), rel=1e-8)
    assert _period_gap(SWIRL, a.y0) < 1e-8
    tilt = lambda o: spatial.simulate(SWIRL, 2 * np.pi / SWIRL.rho, o.y0, n_out=257,  # noqa
                                      azimuth=0.5 if o is b else 0.0).tilt.max()
    assert tilt(b) == pytest.approx(tilt(a), rel=1e-6)


MODEL = ("&model s1 = 1.5, mu1 = 0.5, kappa = 1.804897259, theta0 = 0.7853981633974483{planar} /\n"
         "&excitation A = 0.001, rho = 0.5{excitation} /\n&analysis kind = '{kind}' /\n"
         "&simulation t_end = 10{y0} /\n&lyapunov n_periods = 10 /\n"
         "&sweep start = 0.4, stop = 0.5, n_points = 3 /\n&response start = 0.4, stop = 0.5 /\n")


@pytest.mark.parametrize("planar,excitation,kind,y0,words", [
    ("", ", azimuth = 0.3", "simulate", "", ["&excitation", "azimuth", "planar = .false."]),
    ("", ", ellipticity = 0.3", "simulate", "", ["&excitation", "ellipticity",
                                                  "planar = .false."]),
    ("", "", "simulate", ", y0(5) = 0.1", ["&simulation", "y0(5:8)", "planar = .false."]),
    (", planar = .false.", ", ellipticity = 2", "simulate", "", ["&excitation",
                                                                  "ellipticity = 2", "[0, 1]"]),
    (", planar = .false.", ", azimuth = 9", "simulate", "", ["&excitation", "azimuth = 9",
                                                              "[-2 pi, 2 pi]"]),
    (", planar = .false.", "", "lyapunov", "", ["planar = .false.", "'lyapunov'", "not built"]),
    (", planar = .false.", "", "linear", "", ["'linear'", "symmetric about the vertical",
                                              "planar = .true."]),
    (", planar = .false.", "", "sweep", "", ["'sweep'", "kind = 'swirl'"]),
    (", planar = .false.", "", "frequency_response", "", ["'frequency_response'",
                                                          "slow flow"]),
    (", planar = .false.", "", "periodic_response", "", ["'periodic_response'",
                                                         "swirling orbits is not built"]),
])
def test_bad_input_names_the_variable_at_both_doors(exe, tmp_path, planar, excitation, kind, y0,
                                                    words):
    path = write(tmp_path, MODEL.format(planar=planar, excitation=excitation, kind=kind, y0=y0))
    result = run(exe, path.name, tmp_path)
    assert result.returncode == 3, result.stderr
    with pytest.raises(sloshdyn.InputError) as info:
        sloshdyn.read_namelist(path)
    for word in words:
        assert word in result.stderr, (word, result.stderr)
        assert word in str(info.value), (word, str(info.value))


@pytest.mark.parametrize("call,name", [
    (lambda: spatial.simulate(PAPER, 10, np.zeros(4)), "y0"),
    (lambda: spatial.simulate(PAPER, 10, azimuth=float("nan")), "azimuth"),
    (lambda: spatial.simulate(PAPER, 10, ellipticity=-0.1), "ellipticity"),
    (lambda: spatial.simulate(PAPER, 10, np.full(8, 2e3)), "y0(1)"),
    (lambda: spatial.simulate(PAPER.replace(p=0), 10), "p = 0"),
    (lambda: spatial.swirl_orbit(PAPER, np.zeros(8), azimuth=7.0), "azimuth"),
])
def test_bad_python_input_names_the_variable(call, name):
    with pytest.raises(sloshdyn.InputError, match=name.replace("(", r"\(").replace(")", r"\)")):
        call()


BOUNDARY = ("&model s1 = 1.0, mu1 = 0.01, kappa = 1000, theta0 = 1.4, beta = 0, gamma = 0, "
            "delta = 0, zeta = 5e-4, n = 6, p = 2, planar = .false. /\n"
            "&excitation A = 0.001, rho = 1.0 /\n&analysis kind = 'swirl' /\n"
            "&response parameter = 'rho', start = 1.0, stop = 1.02 /\n"
            "&sweep parameter = '{parameter}', start = 1e-3, stop = 2e-3, n_points = 2 /\n"
            "&output directory = 'out' /\n")


def test_swirl_with_a_sweep_in_A_is_the_swirl_boundary(exe, tmp_path):
    path = write(tmp_path, BOUNDARY.format(parameter="A"))
    result = run(exe, path.name, tmp_path)
    assert result.returncode == 0, result.stderr
    rows = read_csv(tmp_path / "out" / "swirl_boundary.csv")
    inp = sloshdyn.read_namelist(path)
    r = inp.response_range
    values = sorted({row["A"] for row in rows})
    assert values == [1e-3, 2e-3]
    boundary = spatial.swirl_boundary(inp.params, (r["start"], r["stop"]), values,
                                      continuation=inp.response, integration=inp.integration)
    assert [row["A"] for row in rows] == list(boundary.edges["A"])
    assert [row["lambda"] for row in rows] == list(boundary.edges["rho"])
    for name in ("y1", "y2", "y3", "y4", "max_x1", "refined"):
        assert [row[name] for row in rows] == list(boundary.edges[name]), name
    # Miles' averaged equations (S9): the edge's detuning scales as A^(2/3) (measured 1.6 %)
    rho = dict(zip(boundary.edges["A"], boundary.edges["rho"]))
    assert (rho[2e-3] - 1) / (rho[1e-3] - 1) == pytest.approx(2 ** (2 / 3), rel=0.03)


@pytest.mark.parametrize("text,words", [
    (BOUNDARY.format(parameter="rho"), ["&sweep", "parameter = 'A'", "kind = 'swirl'"]),
    (BOUNDARY.format(parameter="A").replace("rho = 1.0 /", "rho = 1.0, azimuth = 0.2 /"),
     ["&excitation", "kind = 'swirl'", "azimuth = 0.2"]),
])
def test_bad_swirl_input_names_the_variable(exe, tmp_path, text, words):
    path = write(tmp_path, text)
    result = run(exe, path.name, tmp_path)
    assert result.returncode == 3, result.stderr
    with pytest.raises(sloshdyn.InputError) as info:
        sloshdyn.read_namelist(path)
    for word in words:
        assert word in result.stderr and word in str(info.value), (word, result.stderr)


@pytest.mark.parametrize("text", [SIMULATE, ORBIT])
def test_both_front_doors_write_the_same_files(tmp_path, text):
    """The executable and `sloshdyn-py run` (the one reader and driver through the bridge)."""
    from test_one_reader import both_front_doors, same_csv_files
    exe_out, py_out, (exe, py) = both_front_doors(tmp_path, text)
    assert exe.returncode == 0 and py.returncode == 0, (exe.stderr, py.stderr)
    same_csv_files(exe_out, py_out)


def test_a_tank_under_harmonic_motion_simulates_its_spatial_model(exe, tmp_path):
    """&tank planar = .false. with &ground_motion azimuth and ellipticity: the tank's
    dimensionless spatial model under its harmonic ground motion, as Python's spatial.simulate
    of the parameters the reader derives from the tank."""
    text = ("&tank radius = 5, liquid_depth = 6, freeboard = 1, liquid_density = 1000, "
            "tank_mass = 5e4, support_frequency = 2, support_damping = 0.02, planar = .false. /\n"
            "&ground_motion peak_acceleration = 0.05, frequency = 0.29872, azimuth = 0.5, "
            "ellipticity = 0.3 /\n&analysis kind = 'simulate' /\n"
            "&simulation t_end = 30, n_out = 31 /\n&output directory = 'out' /\n")
    path = write(tmp_path, text)
    result = run(exe, path.name, tmp_path)
    assert result.returncode == 0, result.stderr
    inp = sloshdyn.read_namelist(path)
    assert inp.spatial == {"azimuth": 0.5, "ellipticity": 0.3} and len(inp.simulation["y0"]) == 8
    r = spatial.simulate(inp.params, 30, n_out=31, integration=inp.integration, **inp.spatial)
    rows = read_csv(tmp_path / "out" / "spatial_history.csv")
    assert [row["y1"] for row in rows] == list(r.y[4])
    assert [row["tilt"] for row in rows] == list(r.tilt)
    assert np.abs(r.y[4]).max() > 0.1          # the elliptical motion drives the y-plane
