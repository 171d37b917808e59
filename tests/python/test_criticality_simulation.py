"""The criticality of period doublings and Neimark-Sacker points (PeriodicBranch.criticality,
issue 42) against direct simulation (sloshdyn.simulate: the stroboscopic points y_k = y(k T) of
a time history, neither the shooting nor the normal form). Past a supercritical period doubling
the motion settles on a small stable period-2 orbit whose amplitude eta (half the distance
between consecutive stroboscopic points) grows as the square root of the distance past the
point, eta^2 = beta / c (1 + O(beta)) by the normal form eta -> -(1 + beta) eta + c eta^3
(Kuznetsov 2004, eq 8.24; beta = -mu - 1 of the period-T orbit there). Past a subcritical period
doubling, and past a subcritical Neimark-Sacker point (no small invariant circle), the motion
kicked off the orbit leaves it for a distant attractor, the chaotic impacting response (|x1|
beyond the wall at 1), far beyond any square-root-law amplitude; before each point the same
kick dies out.

The cases: Fig 12's tank (test_branch_switching's P) at other damping and frequency
(docs/model.md, "Criticality"); the orbits below are those of the branches continued in A from
rest (A = 0.01), at the low end of the short range continued here:
- gamma = 0.05, rho = 0.75: the asymmetric branch switched at the branch point A = 0.59819 has
  a supercritical period doubling at A = 0.88484, stable before it;
- gamma = 0.02, rho = 0.75: the asymmetric branch switched at the branch point A = 0.61382 has
  a subcritical period doubling at A = 1.10775, stable after it;
- gamma = 0.05, rho = 0.7: the symmetric branch has a subcritical Neimark-Sacker point at
  A = 1.48815, stable before it."""

import math

import numpy as np
import pytest

import sloshdyn
from test_branch_switching import P

SUPER_PD = (P.replace(gamma=0.05, rho=0.75, A=0.87), 0.9,
            [0.13755137475001233, 0.45776798556435655, -0.29251699039166773, 0.9994101831615438])
SUB_PD = (P.replace(gamma=0.02, rho=0.75, A=1.09), 1.12,
          [0.028074093158917936, 0.24059827923402297, -0.09180516362154394, 1.1090512546794766])
SUB_NS = (P.replace(gamma=0.05, rho=0.7, A=1.47), 1.5,
          [0.05658535096442274, -0.12424825213302139, -0.1617649042771771, 1.1259513041266702])


def critical_point(case, kind):
    """The case's parameters, its one special point of that kind and the point's criticality."""
    params, A_end, y0 = case
    branch = sloshdyn.periodic_response(params, A_range=(params.A, A_end), y0=y0)
    points = [s for s in branch.special_points if s.kind == kind]
    assert len(points) == 1
    return params, points[0], branch.criticality(points[0])


def orbit_at(params, point, A, multiplier):
    """The period-T orbit at A, the distance beta of its multiplier nearest `multiplier`
    outside the unit circle, and that multiplier's eigenvector's real part (unit length)."""
    orbit = sloshdyn.periodic_orbit(params.replace(A=A), point.y0)
    w, right = np.linalg.eig(orbit.monodromy)
    j = int(np.argmin(abs(w - multiplier)))
    q = right[:, j].real
    return orbit, abs(w[j]) - 1, q / np.linalg.norm(q)


def strobe(params, y0, n):
    """The stroboscopic points y(k T), k = 0..n, of a simulation from y0 (columns)."""
    period = 2 * math.pi / params.rho
    return sloshdyn.simulate(params, n * period, y0, tau_out=np.arange(n + 1) * period).y


def test_supercritical_period_doubling_settles_on_a_square_root_law_period_2_orbit():
    params, point, critical = critical_point(SUPER_PD, "period_doubling")
    c = critical.coefficient
    assert c > 0 and critical.supercritical
    distances, etas, ratios, slopes = (1e-3, 2e-3, 4e-3), [], [], []
    for distance in distances:
        p = params.replace(A=point.A + distance)
        orbit, beta, q = orbit_at(params, point, p.A, -1.0)
        assert beta > 0                                   # the period-T orbit is unstable here
        y = strobe(p, orbit.y0 + 1e-3 * q, int(10 / beta))
        steps = np.linalg.norm(np.diff(y[:, -201:], axis=1), axis=0) / 2
        eta = steps[-1]
        assert abs(steps[0] - eta) < 1e-4 * eta           # settled: the same over 200 periods
        assert np.max(abs(y[:, -1] - y[:, -3])) < 1e-6 * eta    # of period 2 T
        assert np.linalg.norm((y[:, -1] + y[:, -2]) / 2 - orbit.y0) < 0.1 * eta   # around it
        etas.append(eta)
        ratios.append(eta**2 * c / beta)
        slopes.append((eta**2 / distance, beta / distance))
    # eta ~ distance^(1/2): measured exponent 0.5016 (1e-3 to 2e-3), 0.5024 (fit to 4e-3)
    exponent = np.polyfit(np.log(distances), np.log(etas), 1)[0]
    assert exponent == pytest.approx(0.5, abs=0.01)
    # eta^2 c / beta = 1 + O(distance): measured 1.0113, 1.0227, 1.0458, its error halving with
    # the distance; extrapolated to the point, 2 r(1e-3) - r(2e-3) = 0.99991
    assert abs(ratios[0] - 1) < abs(ratios[1] - 1) < abs(ratios[2] - 1) < 0.06
    assert 2 * ratios[0] - ratios[1] == pytest.approx(1, abs=1e-3)
    # eta^2 / distance -> (d beta / dA) / c at the point, both extrapolated from the two nearest
    # distances: measured 0.193188 against 1.99903 / c = 0.193167 (1.1e-4)
    (s1, b1), (s2, b2) = slopes[:2]
    assert 2 * s1 - s2 == pytest.approx((2 * b1 - b2) / c, rel=1e-3)


def jumps_away(params, point, A_past, A_before, multiplier, amplitude):
    """Past the point (A_past) the motion kicked off the orbit leaves it for the chaotic
    impacting response, at distances far beyond `amplitude(beta)` (the square-root law's
    amplitude there had the point been supercritical); before it (A_before) the kick dies."""
    orbit, beta, q = orbit_at(params, point, A_past, multiplier)
    assert beta > 0
    p = params.replace(A=A_past)
    y = strobe(p, orbit.y0 + 1e-3 * q, 3000)
    distance = np.linalg.norm(y[:, -1000:] - orbit.y0[:, None], axis=0)
    assert np.median(distance) > 10 * amplitude(beta), (np.median(distance), amplitude(beta))
    period = 2 * math.pi / p.rho
    tail = sloshdyn.simulate(p, 100 * period, y[:, -1], n_out=10001)
    assert np.max(abs(tail.y[0])) > 1.05                  # impacts: the wall is at |x1| = 1
    chaos = sloshdyn.lyapunov_exponent(p, y[:, -1], lyapunov=sloshdyn.Lyapunov(
        transient_periods=0, n_periods=500))
    assert chaos.exponent > 0.05                          # measured 0.21 and 0.14 over 2000
    before, beta_before, q = orbit_at(params, point, A_before, multiplier)
    assert beta_before < 0
    y = strobe(params.replace(A=A_before), before.y0 + 1e-3 * q, 1000)
    assert np.linalg.norm(y[:, -1] - before.y0) < 1e-4


def test_subcritical_period_doubling_jumps_to_the_impacting_response():
    params, point, critical = critical_point(SUB_PD, "period_doubling")
    c = critical.coefficient
    assert c < 0 and not critical.supercritical
    # the orbit is stable above the point: past it is below
    jumps_away(params, point, point.A - 1e-3, point.A + 1e-3, -1.0,
               lambda beta: math.sqrt(beta / -c))


def test_subcritical_neimark_sacker_point_jumps_to_the_impacting_response():
    params, point, critical = critical_point(SUB_NS, "neimark_sacker")
    d = critical.coefficient
    assert d > 0 and not critical.supercritical
    # |y - y*| = |z q + conj(z q)| <= 2 |z|, |z| = sqrt(beta / d) on a supercritical circle
    jumps_away(params, point, point.A + 1e-3, point.A - 1e-3, critical.multiplier,
               lambda beta: 2 * math.sqrt(beta / d))
