"""The criticality of a period doubling (issue 42, item 2): PeriodicBranch.criticality's flip
coefficient c against the same normal-form formula (Kuznetsov 2004, eq 8.24) evaluated
independently on scipy's stroboscopic map of eq (10) (DOP853 on test_model's numpy equations;
the multilinear forms by finite differences of the map itself at three steps, Richardson-
extrapolated), and against the doubled orbits of the switched branch (an independent
continuation of period-2T orbits): supercritical (c > 0), they lie where the period-T orbit's
critical multiplier is beyond -1, at a distance growing as the square root of the distance past
the point.

The case is the cascade of test_branch_switching (Fig 12's tank at rho = 1, gamma = 0.001):
the period doubling at A = 0.96828 of the asymmetric branch. Its orbits have other multipliers
outside the unit circle, so a direct simulation cannot show the doubled orbit as an attractor
there; test_criticality_simulation does, at a period doubling of stable orbits."""

import math

import numpy as np
import pytest

import sloshdyn
from test_branch_switching import P, Y_SYMMETRIC, flow


@pytest.fixture(scope="module")
def cascade():
    symmetric = sloshdyn.periodic_response(P, A_range=(0.9, P.A), y0=Y_SYMMETRIC,
                                           from_end="high")
    asymmetric = symmetric.switch([s for s in symmetric.special_points
                                   if s.kind == "branch_point"][0])
    doubling = [s for s in asymmetric.special_points if s.kind == "period_doubling"][0]
    return asymmetric, doubling


def scipy_flip_coefficient(p, y, h):
    """c = <p, C(q,q,q)>/6 - <p, B(q, (M - I)^-1 B(q,q))>/2 on scipy's map, step h."""
    period = 2 * math.pi / p.rho
    strobe = lambda z: flow(p, z, period)                                    # noqa: E731
    m = np.column_stack([(strobe(y + 1e-5 * e) - strobe(y - 1e-5 * e)) / 2e-5
                         for e in np.eye(4)])
    w, right = np.linalg.eig(m)
    q = right[:, np.argmin(abs(w + 1))].real
    q /= np.linalg.norm(q)
    w, left = np.linalg.eig(m.T)
    pv = left[:, np.argmin(abs(w + 1))].real
    pv /= pv @ q
    f = {k: strobe(y + k * h * q) for k in (-2, -1, 0, 1, 2)}
    b = (f[1] - 2 * f[0] + f[-1]) / h**2
    c3 = (f[2] - 2 * f[1] + 2 * f[-1] - f[-2]) / (2 * h**3)
    v = np.linalg.solve(m - np.eye(4), b)
    s = np.linalg.norm(v)
    u = v / s
    bqv = s * (strobe(y + h * q + h * u) - strobe(y + h * q - h * u)
               - strobe(y - h * q + h * u) + strobe(y - h * q - h * u)) / (4 * h * h)
    return pv @ c3 / 6 - pv @ bqv / 2


def test_flip_coefficient_agrees_with_scipys_normal_form(cascade):
    asymmetric, doubling = cascade
    critical = asymmetric.criticality(doubling)
    assert critical.kind == "period_doubling" and critical.supercritical
    assert abs(critical.multiplier + 1) < 1e-6
    p = P.replace(A=doubling.A)
    c1, c2 = (scipy_flip_coefficient(p, doubling.y0, h) for h in (2e-3, 1e-3))
    richardson = c2 + (c2 - c1) / 3                   # the differences' error is O(h^2)
    assert critical.coefficient == pytest.approx(richardson, rel=2e-4)   # measured 7e-5


def test_doubled_orbits_lie_on_the_supercritical_side(cascade):
    asymmetric, doubling = cascade
    critical = asymmetric.criticality(doubling)
    doubled = asymmetric.switch(doubling)
    period = 2 * math.pi / P.rho
    ratios = []
    for i in range(4):                                 # the doubled orbits nearest the point
        p = P.replace(A=float(doubled.table["A"][i]))
        y0 = np.array([doubled.table[f"y{k}"][i] for k in range(1, 5)])
        y1 = flow(p, y0, period)                       # scipy: the orbit's other point
        eta = np.linalg.norm(y1 - y0) / 2
        # the period-T orbit between them: its critical multiplier is beyond -1 (beta > 0)
        orbit = sloshdyn.periodic_orbit(p, (y0 + y1) / 2)
        mu = orbit.multipliers[np.argmin(abs(orbit.multipliers + 1))]
        assert -mu.real - 1 > 0 and critical.coefficient > 0
        ratios.append(eta**2 / abs(doubling.A - p.A))
    # eta ~ sqrt(distance past the point): eta^2 / |A - A*| the same at every point
    assert np.ptp(ratios) < 0.01 * np.mean(ratios), ratios
