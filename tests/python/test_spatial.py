"""The spatial model of issue 26 (sloshdyn.spatial; docs/model.md, "Spatial model and swirl").

The right-hand side is checked against an independent derivation: the Euler-Lagrange equations
that sympy derives here from the kinetic and potential energy of the two masses written in
Cartesian positions, the Rayleigh function of the rods' and the linear sloshing damping, and the
generalised force of eq (5) on the radial tilt, solved numerically at random states.
"""

import functools

import numpy as np
import pytest
import sympy as sp

import sloshdyn
from sloshdyn import spatial

PARAMS = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.8, theta0=np.pi / 4, beta=0.7, gamma=0.01,
                             delta=0.05, A=0.3, rho=0.51, zeta=0.02, n=6, p=2)


@functools.lru_cache(maxsize=1)
def _lagrangian_equations(n, p):
    """E(x, x', x'', G) = 0 of the spatial model, from its Lagrangian by sympy, as numerical
    functions: mass(x, x') = dE/dx'' and rest(x, x', Xdd, Ydd, Xd, Yd) = E at x'' = 0."""
    tau = sp.Symbol("tau")
    s1, mu1, kappa, th0, beta, gamma, delta, zeta = sp.symbols(
        "s1 mu1 kappa theta0 beta gamma delta zeta", positive=True)
    xs = [sp.Function(name)(tau) for name in ("x1", "x2", "y1", "y2")]
    X, Y = sp.Function("X")(tau), sp.Function("Y")(tau)
    ax, px, ay, py = (th0 * x for x in xs)          # theta_x, phi_x, theta_y, phi_y [rad]
    tilt_t = sp.Matrix([sp.sin(px) * sp.cos(py), sp.sin(py), sp.cos(px) * sp.cos(py)])
    tilt_n = sp.Matrix([sp.sin(ax) * sp.cos(ay), sp.sin(ay), -sp.cos(ax) * sp.cos(ay)])
    base = sp.Matrix([X, Y, 0])
    r_tank = base + tilt_t                            # unit L
    r_mass = r_tank + s1 * tilt_n
    v_tank, v_mass = r_tank.diff(tau), r_mass.diff(tau)
    kinetic = (1 - mu1) * v_tank.dot(v_tank) / 2 + mu1 * v_mass.dot(v_mass) / 2
    Phi = sp.acos(sp.cos(px) * sp.cos(py))            # the rods' tilt from the vertical
    Theta = sp.acos(sp.cos(ax) * sp.cos(ay))          # the pendulum's tilt
    potential = (kappa * Phi**2 / 2 + s1 * ((1 - mu1) * r_tank[2] + mu1 * r_mass[2])
                 + mu1 * s1**2 * beta * th0 / (2 * n) * (Theta / th0)**(2 * n))
    rayleigh = (gamma * tilt_t.diff(tau).dot(tilt_t.diff(tau)) / 2
                + zeta * mu1 * s1**2 * tilt_n.diff(tau).dot(tilt_n.diff(tau)))
    theta_rate = Theta.diff(tau)
    lag = kinetic - potential
    eqs = []
    for x in xs:
        dx = x.diff(tau)
        radial = -delta * mu1 * s1**2 * (Theta / th0)**(2 * p) * theta_rate * Theta.diff(x)
        eqs.append(lag.diff(dx).diff(tau) - lag.diff(x) + rayleigh.diff(dx) - radial)
    # plain symbols for the state, its derivatives and the ground motion
    q = sp.symbols("q0:4")
    dq = sp.symbols("dq0:4")
    ddq = sp.symbols("ddq0:4")
    xdd, ydd, xd, yd = sp.symbols("Xdd Ydd Xd Yd")
    subs = {}
    for x, a, b, c in zip(xs, q, dq, ddq):
        subs[x.diff(tau, 2)] = c
    for x, b in zip(xs, dq):
        subs[x.diff(tau)] = b
    subs.update({X.diff(tau, 2): xdd, Y.diff(tau, 2): ydd, X.diff(tau): xd, Y.diff(tau): yd})
    eqs = [e.subs(subs) for e in eqs]
    eqs = [e.subs(dict(zip(xs, q))) for e in eqs]
    E = sp.Matrix(eqs)
    mass = E.jacobian(ddq)
    rest = E.subs(dict.fromkeys(ddq, 0))
    args = (q, dq, (xdd, ydd, xd, yd), (s1, mu1, kappa, th0, beta, gamma, delta, zeta))
    return sp.lambdify(args, mass, "numpy"), sp.lambdify(args, rest, "numpy")


def _lagrangian_rhs(params, tau, y, azimuth=0.0, ellipticity=0.0, base_velocity=(0.3, -0.2)):
    mass_f, rest_f = _lagrangian_equations(params.n, params.p)
    q, dq = y[0::2], y[1::2]
    major = -params.A * params.rho**2 * np.sin(params.rho * tau)
    minor = -ellipticity * params.A * params.rho**2 * np.cos(params.rho * tau)
    g = (np.cos(azimuth) * major - np.sin(azimuth) * minor,
         np.sin(azimuth) * major + np.cos(azimuth) * minor, *base_velocity)
    groups = (params.s1, params.mu1, params.kappa, params.theta0, params.beta, params.gamma,
              params.delta, params.zeta)
    m = np.array(mass_f(q, dq, g, groups), dtype=float)
    r = np.array(rest_f(q, dq, g, groups), dtype=float).ravel()
    xdd = np.linalg.solve(m, -r)
    dydt = np.empty(8)
    dydt[0::2], dydt[1::2] = dq, xdd
    return dydt


def test_right_hand_side_is_the_lagrangian_one_at_random_states():
    rng = np.random.default_rng(26)
    for _ in range(12):
        y = rng.uniform(-1.1, 1.1, 8)
        tau = rng.uniform(0, 10)
        got = spatial.equations_of_motion(PARAMS, tau, y, azimuth=0.7, ellipticity=0.3).dydt
        want = _lagrangian_rhs(PARAMS, tau, y, azimuth=0.7, ellipticity=0.3)
        # the base velocity must drop out of the Lagrange equations: another value, same answer
        again = _lagrangian_rhs(PARAMS, tau, y, azimuth=0.7, ellipticity=0.3,
                                base_velocity=(-1.0, 2.0))
        np.testing.assert_allclose(again, want, rtol=1e-11, atol=1e-11)
        np.testing.assert_allclose(got, want, rtol=1e-10, atol=1e-10)


def test_planar_states_give_the_planar_equations():
    rng = np.random.default_rng(1)
    for _ in range(10):
        y = np.zeros(8)
        y[:4] = rng.uniform(-1.2, 1.2, 4)
        m = spatial.equations_of_motion(PARAMS, 1.3, y)
        planar = sloshdyn.equations_of_motion(PARAMS, 1.3, y[:4])
        np.testing.assert_allclose(m.dydt[:4], planar.dydt, rtol=1e-14, atol=1e-14)
        assert np.all(m.dydt[4:] == 0)
        np.testing.assert_allclose(m.mass[:2, :2], planar.mass, rtol=0, atol=1e-15)


def test_bad_spatial_inputs_name_the_variable():
    with pytest.raises(sloshdyn.InputError, match="p = 0"):
        spatial.equations_of_motion(sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.8, theta0=0.5,
                                                        p=0), 0.0, np.zeros(8))
    with pytest.raises(sloshdyn.InputError, match="ellipticity"):
        spatial.equations_of_motion(PARAMS, 0.0, np.zeros(8), ellipticity=1.5)
    with pytest.raises(sloshdyn.InputError, match="azimuth"):
        spatial.equations_of_motion(PARAMS, 0.0, np.zeros(8), azimuth=float("nan"))
    with pytest.raises(sloshdyn.InputError, match="y"):
        spatial.equations_of_motion(PARAMS, 0.0, np.zeros(4))
