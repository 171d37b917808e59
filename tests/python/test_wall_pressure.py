"""The hydrodynamic wall and base pressure of a rigid circular tank (sloshdyn_wall_pressure,
sloshdyn.wall_pressure): the series against independent evaluations with scipy, the resultants
against quadrature of the pressure, the impulsive mass of the trial tank (289 t, issue 25), the
convective masses and heights against the sloshing modes the core already computes, the
symmetry in the angle, the combinations, and the messages of bad input."""

import math

import numpy as np
import pytest
from scipy.special import ive, jnp_zeros, jv

import sloshdyn
from sloshdyn import InputError, Tank

RHO = 1000.0


def tank(radius, depth, **extra):
    return Tank(radius=radius, liquid_depth=depth, freeboard=0.05*radius, liquid_density=RHO,
                tank_mass=1.0e4, support_frequency=5.0, **extra)


def nu(terms):
    return (2*np.arange(terms) + 1)*np.pi/2


def i1_over_i1_prime(x, scale=None):
    """I1(x scale)/I1'(x) from scipy's exponentially scaled ive (no overflow)."""
    scale = 1.0 if scale is None else scale
    return ive(1, x*scale)*np.exp(x*(scale - 1))/(ive(0, x) - ive(1, x)/x)


def ci_series(gamma, xi, zeta, terms):
    """C_i(xi, zeta) of EN 1998-4 A.2.1.2 typed from the code, summed plainly with scipy."""
    n = nu(terms)
    signs = (-1.0)**np.arange(terms)
    return 2*np.sum(signs*np.cos(n*zeta)*i1_over_i1_prime(n/gamma, xi)/n**2)


def convective_reference(radius, gamma, xi, zeta, mode):
    """p_cn/(rho A_n) of EN 1998-4 A.2.1.3 with psi_n typed from the code, scipy's roots of
    J1' and J1."""
    lam = jnp_zeros(1, mode)[-1]
    psi = 2*radius/((lam**2 - 1)*jv(1, lam)*np.cosh(lam*gamma))
    return psi*np.cosh(lam*gamma*zeta)*jv(1, lam*xi)


TANKS = [(5.0, 6.0), (10.0, 3.0), (2.0, 12.0), (20.0, 1.0)]   # trial, broad, slender, squat


@pytest.mark.parametrize("radius, depth", TANKS)
def test_impulsive_wall_and_base_equal_scipy_series(radius, depth):
    """C_i on the wall (random heights) and on the base (random radii) equal the code's series
    summed with scipy (2e5 terms on the wall, where the series falls like 1/n: its partial sums
    then err by < 1e-6; the base series alternates and falls fast)."""
    rng = np.random.default_rng(25)
    gamma = depth/radius
    zeta = np.sort(rng.uniform(0, 1, 6))
    xi = np.sort(rng.uniform(0, 0.98, 6))
    result = sloshdyn.wall_pressure(tank(radius, depth), 1.0, heights=zeta*depth)
    base = sloshdyn.wall_pressure(tank(radius, depth), 1.0, radii=xi*radius)
    wall_ci = result.impulsive_pressure/(RHO*depth)
    base_ci = base.base_impulsive_pressure/(RHO*depth)
    np.testing.assert_allclose(wall_ci, [ci_series(gamma, 1.0, z, 200_000) for z in zeta],
                               rtol=0, atol=2e-6)
    np.testing.assert_allclose(base_ci, [ci_series(gamma, x, 0.0, 200_000) for x in xi],
                               rtol=0, atol=1e-9)


@pytest.mark.parametrize("radius, depth", TANKS)
def test_impulsive_wall_equals_rigid_liquid_minus_all_sloshing_modes(radius, depth):
    """A second, independent expansion: the impulsive pressure is the rigid liquid's, rho R A
    on the wall, minus the pressures of every convective mode at the same acceleration (the
    series in the roots of J1', fast below the surface): to 1e-12 of rho H A_g."""
    gamma = depth/radius
    zeta = np.array([0.0, 0.2, 0.45, 0.7, 0.85])
    lam = jnp_zeros(1, 5000)
    x = lam*gamma
    reference = [(1 - np.sum(2/(lam**2 - 1)*np.exp(x*(z - 1))*(1 + np.exp(-2*x*z))
                             / (1 + np.exp(-2*x))))/gamma for z in zeta]
    ci = sloshdyn.wall_pressure(tank(radius, depth), 1.0, heights=zeta*depth).impulsive_pressure
    np.testing.assert_allclose(ci/(RHO*depth), reference, rtol=0, atol=1e-12)


@pytest.mark.parametrize("radius, depth", TANKS)
def test_convective_pressure_equals_scipy_closed_form(radius, depth):
    """p_cn = rho psi_n cosh(lambda_n gamma zeta) J1(lambda_n xi) A_n for modes 1..4 at random
    points on the wall and the base ('sum' keeps each mode's sign)."""
    rng = np.random.default_rng(7)
    gamma = depth/radius
    zeta, xi = rng.uniform(0, 1, 5), rng.uniform(0, 1, 5)
    for mode in range(1, 5):
        accelerations = np.zeros(4)
        accelerations[mode - 1] = 1.5
        result = sloshdyn.wall_pressure(tank(radius, depth), 0.0, accelerations,
                                        heights=zeta*depth, radii=xi*radius, combination="sum")
        np.testing.assert_allclose(
            result.convective_pressure,
            [1.5*RHO*convective_reference(radius, gamma, 1.0, z, mode) for z in zeta],
            rtol=1e-11, atol=1e-12)
        np.testing.assert_allclose(
            result.base_convective_pressure,
            [1.5*RHO*convective_reference(radius, gamma, x, 0.0, mode) for x in xi],
            rtol=1e-10, atol=1e-9)


def graded_nodes(top, points=160):
    """Gauss-Legendre on [0, top] in u with z = top (1 - (1 - u)^3): nodes crowd at z = top,
    where the pressure has an s log s (wall, at the surface) or corner singularity."""
    u, w = np.polynomial.legendre.leggauss(points)
    u = (u + 1)/2
    return top*(1 - (1 - u)**3), top*3*(1 - u)**2*w/2


@pytest.mark.parametrize("radius, depth", TANKS)
def test_resultants_equal_quadrature_of_the_pressure(radius, depth):
    """The wall pressure integrated over the wall, int int p cos(theta) R dtheta dz = pi R int p
    dz (theta = 0 value), is the base shear m A; its moment about the bottom is m h A (EBP);
    adding the base pressure's moment pi int p r^2 dr gives m h' A (IBP): for the impulsive
    component and each of 3 convective modes, to 1e-6 relative (issue 25)."""
    z, wz = graded_nodes(depth)
    r, wr = graded_nodes(radius)
    a_g, a_n = 2.0, np.array([1.0, 0.7, 0.3])
    for component in range(4):
        a_i = a_g if component == 0 else 0.0
        a_c = np.where(np.arange(3) == component - 1, a_n, 0.0)
        result = sloshdyn.wall_pressure(tank(radius, depth), a_i, a_c, heights=z, radii=r,
                                        combination="sum")
        p_wall = result.total_pressure
        p_base = result.base_total_pressure
        shear = np.pi*radius*np.sum(wz*p_wall)
        moment_ebp = np.pi*radius*np.sum(wz*p_wall*z)
        moment_ibp = moment_ebp + np.pi*np.sum(wr*p_base*r**2)
        row = dict(zip(("component", "mass", "height_ebp", "height_ibp", "base_shear",
                        "moment_ebp", "moment_ibp"), result.resultant_table[:, component]))
        acceleration = a_g if component == 0 else a_n[component - 1]
        assert row["component"] == component
        assert shear == pytest.approx(row["mass"]*acceleration, rel=1e-6)
        assert shear == pytest.approx(row["base_shear"], rel=1e-12)
        assert moment_ebp == pytest.approx(row["mass"]*row["height_ebp"]*acceleration, rel=1e-6)
        assert moment_ibp == pytest.approx(row["mass"]*row["height_ibp"]*acceleration, rel=1e-6)
        assert row["moment_ibp"] == pytest.approx(moment_ibp, rel=1e-6)


def test_impulsive_mass_of_the_trial_tank_is_289_t():
    """R = 5 m, H = 6 m of water: m = rho pi R^2 H = 471.24 t and EN 1998-4 A.2.1.2's m_i =
    289 t (issue 25) to 0.1 %, and equal to the code's series m_i/m = 2 gamma sum
    I1(nu_n/gamma)/(nu_n^3 I1'(nu_n/gamma)) summed with scipy to 1e-9."""
    result = sloshdyn.wall_pressure(tank(5.0, 6.0), 1.0)
    m_liquid = RHO*np.pi*5.0**2*6.0
    assert m_liquid == pytest.approx(471.24e3, rel=1e-5)
    assert result.impulsive_mass == pytest.approx(289e3, rel=1e-3)
    n = nu(2_000_000)
    gamma = 6.0/5.0
    series = 2*gamma*np.sum(i1_over_i1_prime(n/gamma)/n**3)
    assert result.impulsive_mass/m_liquid == pytest.approx(series, rel=1e-9)


@pytest.mark.parametrize("radius, depth", TANKS)
def test_impulsive_heights_equal_scipy_series(radius, depth):
    """h_i/H = 1 - sum (-1)^n r_n/nu_n^4 / sum r_n/nu_n^3 and h_i' from the base moment sum
    (-1)^n I2/I1'(nu_n/gamma)/nu_n^3 (docs/model.md), summed with scipy, to 1e-8."""
    gamma = depth/radius
    n = nu(400_000)
    x = n/gamma
    r = i1_over_i1_prime(x)
    q = (ive(2, x))/(ive(0, x) - ive(1, x)/x)
    signs = (-1.0)**np.arange(n.size)
    s3, s4 = np.sum(r/n**3), np.sum(signs*r/n**4)
    base = 2*np.sum(signs*q/n**3)
    result = sloshdyn.wall_pressure(tank(radius, depth), 1.0)
    assert result.impulsive_height/depth == pytest.approx(1 - s4/s3, rel=1e-8)
    assert result.impulsive_height_ibp/depth == pytest.approx(
        (2*gamma*(s3 - s4) + base)/(2*gamma*s3), rel=1e-8)


def test_convective_masses_and_heights_equal_the_tank_modes():
    """The convective resultants are the sloshing modes the core computes for `&tank modes`
    (sloshdyn_tank's sloshing_modes, the 'tank_modes' table) for modes 2..10 to 1e-10; mode 1
    of that table is the paper's pendulum (eq 2, xi rounded to 1.84), so mode 1 is checked
    against the potential-flow closed forms m_c1 = m 2 tanh(x)/(x (lambda^2 - 1)), h_c1 = H -
    R tanh(x/2)/lambda, h_c1' = H (1 + (2 - cosh x)/(x sinh x)) (EN 1998-4 A.2.1.3)."""
    radius, depth = 5.0, 6.0
    modes = tank(radius, depth, modes=10)
    result = sloshdyn.wall_pressure(modes, 0.0, np.ones(10))
    np.testing.assert_allclose(result.convective_masses[1:], modes.convective_masses[1:],
                               rtol=1e-10)
    np.testing.assert_allclose(result.convective_heights[1:], modes.convective_heights[1:],
                               rtol=1e-10)
    lam = jnp_zeros(1, 1)[0]
    x = lam*depth/radius
    m_liquid = RHO*np.pi*radius**2*depth
    assert result.convective_masses[0] == pytest.approx(
        m_liquid*2*np.tanh(x)/(x*(lam**2 - 1)), rel=1e-12)
    assert result.convective_heights[0] == pytest.approx(depth - radius*np.tanh(x/2)/lam,
                                                         rel=1e-12)
    assert result.convective_heights_ibp[0] == pytest.approx(
        depth*(1 + (2 - np.cosh(x))/(x*np.sinh(x))), rel=1e-12)


def test_pressure_varies_as_cos_theta():
    """Every pressure at the angle theta is its value at theta = 0 times cos(theta): zero at
    pi/2, the opposite at pi."""
    t = tank(5.0, 6.0)
    reference = sloshdyn.wall_pressure(t, 2.0, [1.0, 0.4], angle=0.0, combination="sum")
    for theta in (0.3, np.pi/2, 2.0, np.pi):
        turned = sloshdyn.wall_pressure(t, 2.0, [1.0, 0.4], angle=theta, combination="sum")
        for name in ("impulsive_pressure", "convective_pressure", "total_pressure",
                     "hoop_force", "base_impulsive_pressure", "base_total_pressure"):
            np.testing.assert_allclose(getattr(turned, name),
                                       getattr(reference, name)*np.cos(theta),
                                       rtol=1e-13, atol=1e-9)


def test_combinations_and_hoop_force():
    """'srss' gives the square root of the sum of the squares of the single modes' convective
    pressures, then of impulsive and convective; 'sum' the algebraic sums; the hoop force per
    unit height is the total pressure times R."""
    t = tank(5.0, 6.0)
    a_n = np.array([1.2, 0.8, 0.5])
    single = [sloshdyn.wall_pressure(t, 0.0, np.where(np.arange(3) == k, a_n, 0.0),
                                     combination="sum").convective_pressure for k in range(3)]
    impulsive = sloshdyn.wall_pressure(t, 2.0, combination="sum").impulsive_pressure
    srss = sloshdyn.wall_pressure(t, 2.0, a_n)
    added = sloshdyn.wall_pressure(t, 2.0, a_n, combination="sum")
    np.testing.assert_allclose(srss.convective_pressure, np.sqrt(np.sum(np.square(single), 0)),
                               rtol=1e-13)
    np.testing.assert_allclose(srss.total_pressure, np.hypot(impulsive, srss.convective_pressure),
                               rtol=1e-13)
    np.testing.assert_allclose(added.total_pressure, impulsive + np.sum(single, 0), rtol=1e-13)
    np.testing.assert_allclose(srss.hoop_force, srss.total_pressure*5.0, rtol=1e-15)
    assert srss.units["hoop_force"] == "N/m" and srss.units["total_pressure"] == "Pa"


def test_slender_and_squat_tanks_stay_finite_and_meet_their_limits():
    """H/R = 100: deep below the surface the liquid moves as a rigid body (p = rho R A_g on
    the wall); H/R = 0.01: finite, and the impulsive mass is the rigid liquid's minus every
    sloshing mode's (the series in the roots of J1', summed with scipy to 2e5 roots)."""
    slender = sloshdyn.wall_pressure(tank(0.1, 10.0), 1.0, np.ones(10), heights=[0.0, 5.0])
    assert slender.impulsive_pressure == pytest.approx(RHO*0.1, rel=1e-9)
    assert np.all(np.isfinite(slender.convective_pressure))
    squat = sloshdyn.wall_pressure(tank(100.0, 1.0), 1.0, np.ones(10))
    for name in ("impulsive_pressure", "convective_pressure", "base_impulsive_pressure",
                 "base_convective_pressure"):
        assert np.all(np.isfinite(getattr(squat, name)))
    lam = jnp_zeros(1, 200_000)
    x = lam*0.01
    rigid_minus_modes = 1 - np.sum(2*np.tanh(x)/(x*(lam**2 - 1)))
    m_liquid = RHO*np.pi*100.0**2
    assert squat.impulsive_mass/m_liquid == pytest.approx(rigid_minus_modes, rel=1e-4)


def test_plot_has_units():
    fig = sloshdyn.wall_pressure(tank(5.0, 6.0), 2.0, [1.0]).plot()
    ax = fig.axes[0]
    assert "[kPa]" in ax.get_xlabel() and "[m]" in ax.get_ylabel()
    assert len(ax.get_lines()) >= 3


@pytest.mark.parametrize("call, words", [
    (lambda t: sloshdyn.wall_pressure(t, 1.0, heights=[0.0, 7.0]),
     ["heights(2) = 7", "[0, liquid_depth = 6]"]),
    (lambda t: sloshdyn.wall_pressure(t, 1.0, heights=[-1.0]),
     ["heights(1) = -1", "[0, liquid_depth"]),
    (lambda t: sloshdyn.wall_pressure(t, 1.0, radii=[6.0]), ["radii(1) = 6", "[0, radius = 5]"]),
    (lambda t: sloshdyn.wall_pressure(t, 1.0, np.ones(11)),
     ["convective_accelerations", "11", "10"]),
    (lambda t: sloshdyn.wall_pressure(t, math.nan), ["impulsive_acceleration", "NaN"]),
    (lambda t: sloshdyn.wall_pressure(t, 1.0, [1.0, math.inf]), ["convective_accelerations[1]"]),
    (lambda t: sloshdyn.wall_pressure(t, 1.0, angle=math.inf), ["angle"]),
    (lambda t: sloshdyn.wall_pressure(t, 1.0, combination="max"),
     ["combination = 'max'", "'srss'"]),
])
def test_bad_input_names_the_variable_its_value_and_range(call, words):
    with pytest.raises(InputError) as error:
        call(tank(5.0, 6.0))
    for word in words:
        assert word in str(error.value)


def test_too_slender_and_rectangular_tanks_are_refused():
    with pytest.raises(InputError, match=r"liquid_depth/radius = 200 .*\(0, 100\]"):
        sloshdyn.wall_pressure(tank(0.05, 10.0), 1.0)
    rectangular = Tank(shape="rectangular", length=10.0, width=4.0, liquid_depth=3.0,
                       freeboard=0.5, liquid_density=RHO, tank_mass=1.0e4, support_frequency=5.0)
    with pytest.raises(InputError, match="circular tanks only"):
        sloshdyn.wall_pressure(rectangular, 1.0)


def tapered_record(dt=0.01, duration=16.0, pga=2.0):
    """Three sines (0.25 Hz ~ the sloshing frequency, 0.9 and 2.3 Hz) under a Hann taper."""
    t = dt*np.arange(int(round(duration/dt)) + 1)
    a = np.sin(np.pi*t/t[-1])**2*(np.sin(2*np.pi*0.25*t) + 0.8*np.sin(2*np.pi*0.9*t + 1)
                                   + 0.5*np.sin(2*np.pi*2.3*t + 2))
    return sloshdyn.GroundMotion(dt=dt, acceleration=a*pga/np.max(np.abs(a)), units="m/s^2")


@pytest.mark.parametrize("modes", [1, 3])
def test_pressure_at_the_peaks_of_a_seismic_run_integrates_to_its_loads(modes):
    """At the output times nearest the base shear and overturning moment peaks of a run, the
    pressure (rigid liquid with the tank plus each modelled mode's relative part) integrated over
    the wall (quadrature), plus the shell's inertia, gives the instant's base shear and moments
    (1e-6); these equal the run's own 'seismic' table there but for one known term: the
    pressure's first mode is potential flow (lambda_1 = 1.8412) while the run's pendulum is eq
    (2) (1.84), so they differ by exactly (m_c1 - m)(a_1 - a_t) (shear) and (m_c1 h_c1 - m h_c)
    (a_1 - a_t) (moment), to 1e-9 of the load (rounding)."""
    radius, depth, shell = 5.0, 6.0, 5.0e4
    t = Tank(radius=radius, liquid_depth=depth, freeboard=1.0, liquid_density=RHO,
             tank_mass=shell, support_frequency=5.0, modes=modes)
    run = sloshdyn.seismic_response(t, tapered_record(), t_end=20.0, n_out=2001)
    z, wz = graded_nodes(depth)
    r, wr = graded_nodes(radius)
    times = [run.peaks[key][1] for key in ("base_shear", "overturning_moment")]
    at_peaks = sloshdyn.seismic_pressures(run, times=times, heights=z, radii=r)
    # by default: at the peaks themselves, from the accelerations the run kept there
    kept = sloshdyn.seismic_pressures(run, heights=z, radii=r)
    assert list(kept.t) == [run.peaks[key][1] for key in
                            ("base_shear", "overturning_moment", "overturning_moment_ibp")]
    assert kept.mode_accelerations.shape == (3, modes)
    exact = sloshdyn.wall_pressure(t, 0.0, np.zeros(1))
    dm = exact.convective_masses[0] - t.convective_mass
    dmh = (exact.convective_masses[0]*exact.convective_heights[0]
           - t.convective_mass*t.convective_height)
    shell_height = (depth + 1.0)/2      # the shell at mid-height (sloshdyn_vessel)
    dt = run.t[1] - run.t[0]
    for k, (name, (peak, time)) in enumerate((key, run.peaks[key])
                                             for key in ("base_shear", "overturning_moment")):
        assert at_peaks.times[k] == time
        assert abs(at_peaks.t[k] - time) <= dt/2 + 1e-12
        a_t = at_peaks.tank_acceleration[k]
        shear = np.pi*radius*np.sum(wz*at_peaks.total_pressure[k]) + shell*a_t
        moment = np.pi*radius*np.sum(wz*at_peaks.total_pressure[k]*z) + shell*shell_height*a_t
        moment_ibp = moment + np.pi*np.sum(wr*at_peaks.base_total_pressure[k]*r**2)
        assert shear == pytest.approx(at_peaks.base_shear[k], rel=1e-6)
        assert moment == pytest.approx(at_peaks.overturning_moment[k], rel=1e-6)
        assert moment_ibp == pytest.approx(at_peaks.overturning_moment_ibp[k], rel=1e-6)
        i = int(np.argmin(abs(run.t - at_peaks.t[k])))
        relative = at_peaks.mode_accelerations[k, 0] - a_t
        assert at_peaks.base_shear[k] - run.base_shear[i] == pytest.approx(
            dm*relative, abs=1e-9*abs(run.base_shear[i]))
        assert at_peaks.overturning_moment[k] - run.overturning_moment[i] == pytest.approx(
            dmh*relative, abs=1e-9*abs(run.overturning_moment[i]))
        if modes > 1:      # the peaks of a run with higher modes are at its output times
            assert abs(getattr(run, name)[i]) == pytest.approx(peak, rel=1e-12)
    assert at_peaks.mode_accelerations.shape == (2, modes)
