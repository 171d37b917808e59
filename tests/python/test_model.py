"""The core through Python against independent implementations (numpy, scipy) of the paper's
equations."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

import sloshdyn


def eq10_numpy(p, tau, y):
    """Eq (10) with X = A sin(rho tau), solved for the accelerations with numpy."""
    x1, v1, x2, v2 = y
    t0 = p.theta0
    xdd = -p.A * p.rho**2 * math.sin(p.rho * tau)
    c12, s12 = math.cos(t0 * (x1 + x2)), math.sin(t0 * (x1 + x2))
    mass = np.array([[1, c12 / p.s1], [p.mu1 * p.s1 * c12, 1]])
    f1 = (t0 / p.s1 * s12 * v2**2 - math.sin(t0 * x1) / t0 - p.beta / t0 * x1 ** (2 * p.n - 1)
          - p.delta * x1 ** (2 * p.p) * v1 - math.cos(t0 * x1) * xdd / (t0 * p.s1))
    f2 = (p.mu1 * p.s1 * t0 * s12 * v1**2 - p.kappa * x2 + p.s1 / t0 * math.sin(t0 * x2)
          - p.gamma * v2 - xdd * math.cos(t0 * x2) / t0)
    qdd = np.linalg.solve(mass, [f1, f2])
    return np.array([v1, qdd[0], v2, qdd[1]])


@pytest.mark.parametrize("y", [(0.3, -0.7, 0.2, 0.4), (1.05, 0.5, -0.3, -0.9), (-0.8, 1.3, 0.05, 0.2)])
def test_equations_of_motion_match_eq10(fig12, y):
    p = fig12.replace(beta=0.7, delta=0.05, A=0.3, gamma=0.01)
    motion = sloshdyn.equations_of_motion(p, 2.3, y)
    assert np.allclose(motion.dydt, eq10_numpy(p, 2.3, y), rtol=1e-13, atol=1e-14)
    # and its Jacobian against central differences of the numpy version
    fd = np.empty((4, 4))
    for j in range(4):
        h = 1e-6 * max(1.0, abs(y[j]))
        e = np.zeros(4)
        e[j] = h
        fd[:, j] = (eq10_numpy(p, 2.3, np.add(y, e)) - eq10_numpy(p, 2.3, np.subtract(y, e))) / (2 * h)
    assert np.allclose(motion.jacobian, fd, rtol=1e-7, atol=1e-7)


@pytest.mark.parametrize("n, p_exp", [(1, 0), (2, 1), (6, 2), (13, 5), (50, 50)])
def test_equations_of_motion_match_eq10_at_random_states(fig12, n, p_exp):
    """The core's right-hand side (angle addition for theta0 (x1 + x2), integer powers by
    binary powering, the 2x2 inertia system in closed form) against eq (10) written out and
    solved with numpy, to 1e-14 of the largest component, at random states up to and beyond
    the wall |x1| = 1, where the impact term x1^(2n-1) dominates."""
    rng = np.random.default_rng(28)
    p = fig12.replace(n=n, p=p_exp, A=0.02, gamma=0.01, zeta=0.0)
    for _ in range(40):
        x1 = rng.choice([-1, 1]) * rng.uniform(0.9, 1.08) if rng.random() < 0.5 else rng.uniform(-1, 1)
        y = (x1, rng.uniform(-2, 2), rng.uniform(-1.5, 1.5), rng.uniform(-2, 2))
        tau = rng.uniform(0, 1000)
        ref = eq10_numpy(p, tau, y)
        dydt = sloshdyn.equations_of_motion(p, tau, y).dydt
        assert np.allclose(dydt, ref, rtol=1e-14, atol=1e-14 * np.max(np.abs(ref))), (y, dydt, ref)


def omegas_eq28(s1, mu1, kappa):
    """Eq (28) as printed."""
    alpha = (1 - s1 + kappa) / (2 * (1 - mu1))
    beta = (kappa - s1) / (1 - mu1)
    return math.sqrt(alpha - math.sqrt(alpha**2 - beta)), math.sqrt(alpha + math.sqrt(alpha**2 - beta))


def test_natural_frequencies_match_eq28_and_the_paper(fig12):
    modes = sloshdyn.linear_modes(fig12)
    w1, w2 = modes.omega1, modes.omega2
    assert np.allclose((w1, w2), omegas_eq28(1.5, 0.5, 1.804897259), rtol=1e-12)
    assert round(w1, 5) == 0.50936 and round(w2, 5) == 1.53308   # paper, sec 4.2


@pytest.mark.parametrize("sigma1", [0.0, 0.005, -0.05, 0.3])
def test_kappa_for_detuning_matches_brentq(sigma1):
    f = lambda kappa: (lambda w: w[1] - 3 * w[0] - sigma1)(omegas_eq28(1.5, 0.5, kappa))
    grid = 1.5 + np.geomspace(1e-6, 1000, 20001)
    values = np.array([f(k) for k in grid])
    brackets = np.nonzero(np.sign(values[:-1]) != np.sign(values[1:]))[0]
    expected = [brentq(f, grid[i], grid[i + 1], xtol=1e-14) for i in brackets]
    found = sloshdyn.kappa_for_detuning(1.5, 0.5, sigma1)
    assert len(found) == len(expected) == 2
    assert np.allclose(found, expected, rtol=1e-10)


def test_kappa_for_detuning_paper_values():
    assert abs(sloshdyn.kappa_for_detuning(1.5, 0.5, 0.0)[0] - 1.808) < 5e-4     # sec 4.2, Fig 11
    assert abs(sloshdyn.kappa_for_detuning(1.5, 0.5, 0.005)[0] - 1.8049) < 5e-5  # sec 4.2, Fig 12


def test_frequency_ratio_map_fig7():
    sigma = np.linspace(0.05, 2, 40)
    for mu_t in (0.1, 0.5, 1.0):
        w = np.array([omegas_eq28(1.5, 1 - mu_t, 1.5 + s) for s in sigma]) if mu_t < 1 else None
        ratio = sloshdyn.frequency_ratio(sigma, mu_t)
        if w is not None:
            assert np.allclose(ratio, w[:, 1] / w[:, 0], rtol=1e-10)
    assert abs(sloshdyn.frequency_ratio(0.305, 0.5) - 3) < 0.01   # sec 3.2


def all_roots(f, lower, upper, n=200001):
    grid = np.linspace(lower, upper, n)
    values = f(grid)
    idx = np.nonzero(np.sign(values[:-1]) * np.sign(values[1:]) < 0)[0]
    return sorted([brentq(f, grid[i], grid[i + 1], xtol=1e-14) for i in idx] + [0.0])


@pytest.mark.parametrize("beta_hat", [0.001, 0.005, 0.02])
def test_theta_roots_match_brentq(fig12, beta_hat):
    n = 2
    p = fig12.replace(n=n, beta=beta_hat * fig12.theta0 ** (2 * n - 1))
    found = sloshdyn.equilibrium_angles(p, "theta")
    roots, truncated = found.angles, found.truncated
    bound = beta_hat ** (-1 / 3)
    expected = all_roots(lambda t: np.sin(t) + beta_hat * t**3, -bound - 1e-9, bound + 1e-9)
    expected = sorted(set(np.round(expected, 12)))
    assert not truncated
    assert np.allclose(roots, expected, atol=1e-10)


@pytest.mark.parametrize("kappa_hat", [0.05, 0.3, 0.9, 1.3])
def test_phi_roots_match_brentq(fig12, kappa_hat):
    p = fig12.replace(kappa=kappa_hat * fig12.s1)
    roots = sloshdyn.equilibrium_angles(p, "phi").angles
    expected = all_roots(lambda x: np.sin(x) - kappa_hat * x, -1 / kappa_hat - 1e-9, 1 / kappa_hat + 1e-9)
    expected = sorted(set(np.round(expected, 12)))
    assert np.allclose(roots, expected, atol=1e-10)


def test_equilibria_pitchfork_and_routh(fig12):
    above = sloshdyn.equilibria(fig12)
    assert len(above) == 1 and above.trivial.stable and above.routh_stable
    below = sloshdyn.equilibria(fig12.replace(kappa=0.9 * fig12.s1))
    verdicts = [e.verdict for e in below]
    assert verdicts == ["stable", "unstable", "stable"]   # Fig 6: supercritical pitchfork
    assert not below.routh_stable
    # Routh-Hurwitz delta3 of eq (20) in closed form: c^2 mu1/(1 - mu1), c = gamma/(1 - mu1)
    c = fig12.gamma / (1 - fig12.mu1)
    assert math.isclose(above.routh_delta3, c**2 * fig12.mu1 / (1 - fig12.mu1), rel_tol=1e-9)
