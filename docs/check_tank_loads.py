"""Check what docs/model.md says of a tank's seismic response against the installed sloshdyn:

1. the linear limit: with stiff supports and small motion, the peak sloshing displacement
   l sin(theta) equals the spectral displacement S_d(T, zeta) of the record (an exact piecewise-linear SDOF
   solution, independent of the integrators), and the peak wave 2R/(xi^2 - 1) S_a/g;
2. the base shear and the overturning moment of seismic.csv against the formulas of "Loads",
   with the accelerations a_t, a_m taken by finite differences of the velocities rebuilt from
   x1, x2 and the ground acceleration (an independent route).

Run from the repository root:  python docs/check_tank_loads.py   (needs sloshdyn and numpy)
It prints the numbers and stops with an AssertionError if a relation fails.
"""

from pathlib import Path

import numpy as np

import sloshdyn

RECORD = Path(__file__).resolve().parents[1] / "data/examples/records/synthetic_kt.AT2"
XI = 1.84


def linear_limit():
    tank = sloshdyn.Tank(radius=5.0, liquid_depth=6.0, freeboard=1.0, liquid_density=1000,
                         tank_mass=5e4, support_frequency=50.0, support_damping=0.02)
    period = tank.sloshing_period
    quake = sloshdyn.GroundMotion.from_file(RECORD).scaled(sa=0.01, period=period,
                                                           damping=0.005, units="g")
    spectrum = quake.response_spectrum([period], damping=0.005)
    response = sloshdyn.seismic_response(tank, quake, n_out=200001)
    peak, _ = response.peaks["sloshing_displacement"]
    wave, _ = response.peaks["wave_height"]
    wave_linear = 2 * tank.radius / (XI**2 - 1) * spectrum.psa[0] / tank.gravity
    print(f"linear limit: T = {period:.6f} s, S_d = {spectrum.sd[0]:.7f} m, peak l sin(theta) = "
          f"{peak:.7f} m (ratio {peak / spectrum.sd[0]:.6f}); peak wave {wave:.7f} m, "
          f"2R S_a/((xi^2 - 1) g) = {wave_linear:.7f} m")
    assert abs(peak / spectrum.sd[0] - 1) < 1e-3 and abs(wave / wave_linear - 1) < 1e-3


def loads_by_finite_differences():
    tank = sloshdyn.Tank(radius=5.0, liquid_depth=6.0, freeboard=1.0, liquid_density=1000,
                         tank_mass=5e4, support_frequency=2.0, support_damping=0.02)
    quake = sloshdyn.GroundMotion.from_file(RECORD).scaled(sa=0.2, period=tank.sloshing_period,
                                                           damping=0.005, units="g")
    r = sloshdyn.seismic_response(tank, quake, n_out=40001)
    p = tank.properties
    M, m, l, L = p["total_mass"], p["sloshing_mass"], p["pendulum_length"], p["support_height"]
    m0, h_c, h0 = p["rigid_mass"], p["convective_height"], p["impulsive_height"]
    t, theta, phi = r.t, p["theta0"] * r.x1, p["theta0"] * r.x2
    ground_velocity = np.concatenate([[0.0], np.cumsum(0.5 * np.diff(t) *
                                                       (r.ground_acceleration[1:] +
                                                        r.ground_acceleration[:-1]))])
    v_tank = ground_velocity + L * np.cos(phi) * np.gradient(phi, t)
    v_mass = v_tank + l * np.cos(theta) * np.gradient(theta, t)
    a_t, a_m = np.gradient(v_tank, t), np.gradient(v_mass, t)
    shear = (M - m) * a_t + m * a_m
    moment = (m0 * h0 + tank.tank_mass * (tank.liquid_depth + tank.freeboard) / 2) * a_t + \
        m * h_c * a_m
    inner = slice(200, -200)
    shear_error = np.max(np.abs(shear - r.base_shear)[inner]) / np.max(np.abs(r.base_shear))
    moment_error = np.max(np.abs(moment - r.overturning_moment)[inner]) / \
        np.max(np.abs(r.overturning_moment))
    print(f"finite differences: base shear within {shear_error:.1e}, overturning moment within "
          f"{moment_error:.1e} of their peaks ({np.max(np.abs(r.base_shear)):.6g} N, "
          f"{np.max(np.abs(r.overturning_moment)):.6g} N m)")
    assert shear_error < 1e-3 and moment_error < 1e-3


if __name__ == "__main__":
    linear_limit()
    loads_by_finite_differences()
