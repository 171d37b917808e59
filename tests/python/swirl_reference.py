"""Independent references for the swirl tests (issue 41): scipy shooting of the spatial model's
equations, and the forced spherical pendulum on a rigid support derived here by sympy.

Neither uses the core's shooting, continuation, root finders or Floquet code: the tank model's
right-hand side and Jacobian come from ``spatial.equations_of_motion`` (checked against an
independent sympy derivation in test_spatial.py), the orbits from scipy's DOP853 with the
variational equations, Newton's method written here and scipy's brentq.
"""

import functools

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from sloshdyn import spatial

RTOL, ATOL = 1e-12, 1e-14


def _shot(field, n, period, y0):
    """y(T) and the monodromy matrix Phi(T) of y' = f(tau, y), Phi' = J Phi (field(tau, y) ->
    (f, J)), by DOP853."""

    def rhs(tau, z):
        f, jac = field(tau, z[:n])
        return np.concatenate([f, (jac @ z[n:].reshape(n, n)).ravel()])

    z0 = np.concatenate([y0, np.eye(n).ravel()])
    sol = solve_ivp(rhs, (0.0, period), z0, method="DOP853", rtol=RTOL, atol=ATOL)
    assert sol.success, sol.message
    return sol.y[:n, -1], sol.y[n:, -1].reshape(n, n)


def _planar_orbit(field, n, period, guess, planar):
    """Newton's method on y(T) - y0 = 0 over the in-plane states `planar` (the others 0)."""
    y = np.zeros(n)
    y[planar] = guess
    for _ in range(30):
        y_end, monodromy = _shot(field, n, period, y)
        residual = y_end[planar] - y[planar]
        step = np.linalg.solve(monodromy[np.ix_(planar, planar)] - np.eye(len(planar)),
                               -residual)
        y[planar] += step
        if np.abs(step).max() < 1e-13:       # the last monodromy is the orbit's to 1e-13
            return y, monodromy
    raise AssertionError("scipy shooting did not converge")


class Swirl:
    """A planar orbit's out-of-plane test det(M_b - sign I) as a function of rho, the planar
    orbit continued from `guess` by warm starts."""

    def __init__(self, field_at, n, planar, out_of_plane, guess):
        self.field_at, self.n, self.planar, self.out = field_at, n, planar, out_of_plane
        self.guess = np.asarray(guess, float)

    def test(self, rho, sign=1.0):
        y, monodromy = _planar_orbit(self.field_at(rho), self.n, 2 * np.pi / rho, self.guess,
                                     self.planar)
        self.guess = y[self.planar]
        block = monodromy[np.ix_(self.out, self.out)]
        return np.linalg.det(block - sign * np.eye(len(self.out)))

    def multipliers(self, rho):
        y, monodromy = _planar_orbit(self.field_at(rho), self.n, 2 * np.pi / rho, self.guess,
                                     self.planar)
        return np.linalg.eigvals(monodromy[np.ix_(self.out, self.out)])

    def edge(self, rho_a, rho_b, sign=1.0):
        """The zero of the test in [rho_a, rho_b] (brentq, xtol 1e-12); asserts the bracket."""
        ga, gb = self.test(rho_a, sign), self.test(rho_b, sign)
        assert ga * gb < 0, (ga, gb)
        return brentq(lambda r: self.test(r, sign), rho_a, rho_b, xtol=1e-12, rtol=1e-15)


def tank_swirl(params, guess):
    """The tank model (spatial equations, rods included): states x1, x1', x2, x2' in the plane,
    y1, y1', y2, y2' out of it."""

    def field_at(rho):
        p = params.replace(rho=rho)

        def field(tau, y):
            m = spatial.equations_of_motion(p, tau, y)
            return m.dydt, m.jacobian
        return field

    return Swirl(field_at, 8, [0, 1, 2, 3], [4, 5, 6, 7], guess)


@functools.lru_cache(maxsize=1)
def _pendulum_equations():
    """The forced spherical pendulum (unit length, unit small-oscillation frequency, no damping)
    with its pivot at (epsilon sin(rho tau), 0, 0): the bob at r = (x, y, z) relative to the
    pivot, z = -sqrt(1 - x^2 - y^2), obeys r'' = -a_p e_x - e_z + lam r with the tension
    lam = a_p x + z - |r'|^2 (from r . r'' = -|r'|^2), a_p the pivot's acceleration; state
    (x, x', y, y'); the field and its Jacobian (by sympy) as numerical functions."""
    tau, eps, rho = sp.symbols("tau epsilon rho")
    x, vx, y, vy = sp.symbols("x vx y vy")
    z = -sp.sqrt(1 - x**2 - y**2)
    vz = -(x * vx + y * vy) / z
    a_p = -eps * rho**2 * sp.sin(rho * tau)
    lam = a_p * x + z - (vx**2 + vy**2 + vz**2)
    state = sp.Matrix([x, vx, y, vy])
    field = sp.Matrix([vx, -a_p + lam * x, vy, lam * y])
    args = (tau, state, eps, rho)
    return (sp.lambdify(args, list(field), "numpy", cse=True),
            sp.lambdify(args, field.jacobian(state), "numpy", cse=True))


def pendulum_swirl(epsilon, guess):
    """The rigid-support spherical pendulum with pivot amplitude epsilon: in-plane (x, x'),
    out-of-plane (y, y')."""
    f, jac = _pendulum_equations()

    def field_at(rho):
        def field(tau, s):
            return np.array(f(tau, s, epsilon, rho), float), np.array(jac(tau, s, epsilon, rho),
                                                                       float)
        return field

    return Swirl(field_at, 4, [0, 1], [2, 3], guess)
