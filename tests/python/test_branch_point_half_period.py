"""The symmetry-breaking branch point to 1e-10 (issue 42, item 3): the core locates it again on
the half-period map P(y) = -phi(T/2; y) of the symmetric orbits (sloshdyn_half_period), where
it is regular. The independent computation here: scipy's DOP853 on eq (10) (numpy, test_model's
eq10_numpy) with the variational equations Phi' = J Phi (J the analytic Jacobian, checked
against central differences of eq10_numpy in test_model), the symmetric orbit by Newton on
phi(y) + y = 0 (Jacobian Phi + I) and the branch point by Brent's method on
g(A) = det(Phi(T/2) - I) along them.

The case is test_branch_switching's (Fig 12's tank at rho = 1, gamma = 0.001)."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

import sloshdyn
from test_branch_switching import P, Y_SYMMETRIC
from test_model import eq10_numpy


def half_map(p, y0):
    """phi(T/2; y0) and Phi(T/2) by scipy's DOP853."""
    def field(tau, z):
        jac = sloshdyn.equations_of_motion(p, tau, z[:4]).jacobian
        return np.concatenate([eq10_numpy(p, tau, z[:4]),
                               (jac @ z[4:].reshape(4, 4)).reshape(-1)])
    z0 = np.concatenate([y0, np.eye(4).reshape(-1)])
    run = solve_ivp(field, (0, math.pi / p.rho), z0, method="DOP853", rtol=1e-13, atol=1e-14)
    return run.y[:4, -1], run.y[4:, -1].reshape(4, 4)


def symmetric_orbit(p, y):
    for _ in range(20):
        end, phi = half_map(p, y)
        step = np.linalg.solve(phi + np.eye(4), -(end + y))
        y = y + step
        if np.max(np.abs(step)) < 1e-13:
            return y, half_map(p, y)[1]
    raise AssertionError("scipy's symmetric orbit did not converge")


def test_branch_point_agrees_with_scipy_on_the_half_period_map():
    symmetric = sloshdyn.periodic_response(P, A_range=(0.9, P.A), y0=Y_SYMMETRIC,
                                           from_end="high")
    points = [s for s in symmetric.special_points if s.kind == "branch_point"]
    assert len(points) == 1
    core = points[0]
    guess = {"y": np.array(core.y0)}

    def g(A):
        y, phi = symmetric_orbit(P.replace(A=A), guess["y"])
        guess["y"] = y
        return np.linalg.det(phi - np.eye(4))

    a_bp = brentq(g, core.A - 1e-6, core.A + 1e-6, xtol=1e-14, rtol=1e-15)
    assert abs(core.A - a_bp) < 1e-10                     # measured: see the report
    y_bp, phi = symmetric_orbit(P.replace(A=a_bp), guess["y"])
    assert np.max(np.abs(core.y0 - y_bp)) < 1e-8
    # at the branch point Phi(T/2) has the eigenvalue +1 (M = Phi^2: a multiplier +1 whose
    # eigenvector is antisymmetric) and the symmetric orbit's M - I is singular
    assert np.min(np.abs(np.linalg.eigvals(phi) - 1)) < 1e-8
    print("core", repr(core.A), "scipy", repr(a_bp), "difference", core.A - a_bp)
