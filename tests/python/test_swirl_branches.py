"""swirl_band across a range where planar branches coexist, and the maxima of a swirling orbit
(issue 41).

Independent sources: the planar orbit at the range's upper end found by shooting on its own
(periodic_orbit from a simulation), which the band must say lies on another branch; and scipy's
DOP853 with dense output sampled 2e5 times over a swirling orbit for its max|x1| and max|y1|.
"""

import functools

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import sloshdyn
from sloshdyn import spatial

PARAMS = sloshdyn.Parameters(s1=1.0, mu1=0.01, kappa=1e3, theta0=1.4, beta=0.0, gamma=0.0,
                             delta=0.0, A=1e-3, rho=1.02, zeta=5e-4, n=6, p=2)
RANGE = (0.98, 1.02)


@functools.lru_cache(maxsize=None)
def _band(from_end):
    return spatial.swirl_band(PARAMS, RANGE, from_end=from_end)


def _period_gap(params, y0):
    """max|y(T) - y0| of the spatial equations by scipy's DOP853 (planar y0 padded by zeros)."""
    y0 = np.concatenate([y0, np.zeros(4)])
    period = 2 * np.pi / params.rho
    sol = solve_ivp(lambda tau, y: spatial.equations_of_motion(params, tau, y).dydt,
                    (0, period), y0, method="DOP853", rtol=1e-12, atol=1e-14)
    assert sol.success
    return np.abs(sol.y[:, -1] - y0).max()


def test_one_end_says_the_other_ends_orbit_is_on_another_branch():
    low = _band("low")
    assert low.complete and len(low.followed) == 1 and "0.98" in low.followed[0]
    # from 0.98 the non-resonant planar branch folds (rho = 0.9954) and comes back to 0.98
    # through the planar-unstable middle branch, never reaching 1.02 and never swirling
    assert low.table["rho"][-1] == RANGE[0] and low.table["rho"].max() < 0.996
    assert not low.table["swirl"].any() and len(low.edges["rho"]) == 0
    assert "another branch" in low.others and "both" in low.others and "1.02" in low.others


def test_both_ends_follow_both_branches_and_find_the_resonant_swirl():
    both, high = _band("both"), spatial.swirl_band(PARAMS, RANGE, from_end="high")
    assert both.complete and len(both.followed) == 2 and both.others == ""
    assert set(both.table["branch"]) == {0, 1}
    # the second branch starts at a periodic orbit at 1.02 (scipy closes it)
    first = np.flatnonzero(both.table["branch"] == 1)[0]
    assert both.table["rho"][first] == RANGE[1]
    y = np.array([both.table[f"y{i}"][first] for i in range(1, 5)])
    assert _period_gap(PARAMS.replace(rho=RANGE[1]), y) < 1e-8
    # branch 1 is the one from_end = 'high' follows, edge for edge
    on_1 = both.edges["branch"] == 1
    assert np.array_equal(both.edges["rho"][on_1], high.edges["rho"])
    assert len(high.edges["rho"]) >= 1 and set(high.edges["kind"]) == {"branch_point"}
    assert both.table["swirl"][both.table["branch"] == 1].any()
    assert not both.table["swirl"][both.table["branch"] == 0].any()


def test_swirl_orbit_maxima_are_the_dense_maxima():
    params = PARAMS.replace(rho=1.003)
    orbit = spatial.swirl_orbit(params)
    period = 2 * np.pi / params.rho
    sol = solve_ivp(lambda tau, y: spatial.equations_of_motion(params, tau, y).dydt,
                    (0, period), orbit.y0, method="DOP853", rtol=1e-12, atol=1e-14,
                    dense_output=True)
    assert sol.success
    y = sol.sol(np.linspace(0, period, 200001))
    # sampled 2e5 times a period: within (2 pi/2e5)^2/2 of the true maximum, relatively
    assert orbit.max_x1 == pytest.approx(np.abs(y[0]).max(), rel=1e-8)
    assert orbit.swirl_amplitude == pytest.approx(np.abs(y[4]).max(), rel=1e-8)
