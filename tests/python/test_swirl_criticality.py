"""The criticality of the swirl onset and its degenerate pitchfork on the swirl boundary curve
(issue 41, item 4).

Independent sources: the swirling orbits themselves (spatial.swirling_branch: branch switching
at the edge and pseudo-arclength continuation of the 8-state orbits, a code path that never
touches the normal form), on which side of the edge they lie (the planar orbit's out-of-plane
multipliers there) and their amplitude law eta^2 ~ -beta/c, beta the critical multiplier's
distance from +1 (by central differences of the planar orbit's multipliers in rho); and, for
the located degenerate pitchfork, scipy's brentq in A on the sign of c at the single-A edges of
spatial.swirl_band (Brent in rho on det(M_b - I) at fixed A, not the curve's continuation in
(rho, A) with its arclength Brent).
"""

import functools

import numpy as np
import pytest
from scipy.optimize import brentq

import sloshdyn
from sloshdyn import spatial
from sloshdyn.options import Continuation

# the swirl boundary curve's test case (test_swirl_boundary_curve.py)
PARAMS = sloshdyn.Parameters(s1=1.0, mu1=0.01, kappa=1e3, theta0=1.4, beta=0.0, gamma=0.0,
                             delta=0.0, A=2.5e-4, rho=1.02, zeta=5e-4, n=6, p=2)
RHO_RANGE = (0.98, 1.03)


@functools.lru_cache(maxsize=1)
def _band():
    return spatial.swirl_band(PARAMS, RHO_RANGE, from_end="high")


def _edge(band, j, params=PARAMS):
    y = np.array([band.edges[f"y{i}"][j] for i in range(1, 5)])
    return params.replace(rho=float(band.edges["rho"][j])), y


def _critical_nu(params, y_guess):
    """The out-of-plane multiplier nearest +1 of the planar orbit at params (real near it)."""
    orbit = sloshdyn.periodic_orbit(params, y_guess)
    nu = spatial.out_of_plane_multipliers(params, orbit.y0)
    return nu[np.argmin(np.abs(nu - 1))].real, np.abs(nu).max()


@pytest.mark.parametrize("j, expected", [(1, "supercritical"), (0, "subcritical")])
def test_the_sign_of_c_is_the_side_and_c_the_amplitude_of_the_swirling_orbits(j, expected):
    band = _band()
    at_edge, y_edge = _edge(band, j)
    rho_edge = at_edge.rho
    criticality = spatial.swirl_edge_criticality(at_edge, y_edge)
    assert abs(criticality.nu - 1) < 1e-8
    # the critical eigenvector is out of the plane: the mirror y -> -y flips it
    assert np.abs(criticality.q[:4]).max() < 1e-6 < np.abs(criticality.q[4:]).max()
    # the band's low edge (j = 1) is supercritical, its high one subcritical (measured c =
    # -13.7 and +5.6, the terms' sizes 47 and 8)
    assert criticality.supercritical == (expected == "supercritical")
    assert abs(criticality.c) > 0.1 * criticality.size_of_terms

    # the swirling orbits near the edge, by branch switching and continuation
    steps = Continuation(ds=2e-3, ds_min=1e-9, ds_max=2e-3, x_scale=1.0, max_points=40)
    branch = spatial.swirling_branch(band, j, (rho_edge - 3e-5, rho_edge + 3e-5), params=PARAMS,
                                     continuation=steps)
    table = branch.table
    offset = table["rho"][:3] - rho_edge
    assert np.all(offset != 0) and np.all(np.sign(offset) == np.sign(offset[0]))
    # supercritical <=> they lie where the planar orbit is unstable (an out-of-plane |nu| > 1)
    _, largest = _critical_nu(PARAMS.replace(rho=float(table["rho"][2])), y_edge)
    assert (largest > 1 + 1e-6) == (expected == "supercritical")
    # ... and are born stable (the switched branch's own Floquet multipliers)
    assert np.all(table["stable"][:3] == (1 if expected == "supercritical" else 0))

    # the amplitude law: on the centre manifold eta -> (1 + beta) eta + c eta^3, the fixed
    # points eta^2 = -beta/c; eta = |out-of-plane state| (q unit, out of the plane, the
    # centre manifold's quadratic part in the plane), beta = nu - 1 ~ (d beta/d rho) (rho -
    # rho_edge)
    # (the other real multiplier of the slow out-of-plane pair is 0.9937, so nu(rho) curves
    # sharply: central differences at h = 1e-6 are 1.1e-3 off, at 1e-7 1e-5)
    h = 1e-7
    dbeta = (_critical_nu(at_edge.replace(rho=rho_edge + h), y_edge)[0]
             - _critical_nu(at_edge.replace(rho=rho_edge - h), y_edge)[0]) / (2 * h)
    eta2 = sum(table[f"y{i}"][:3] ** 2 for i in range(5, 9))
    ratio = eta2 / offset
    # eta^2/(rho - rho_edge) is linear in rho - rho_edge near the edge: extrapolated to it
    limit = np.polyval(np.polyfit(offset, ratio, 1), 0.0)
    # measured: 8.14585 against 8.14621 (supercritical), 4.19666 against 4.19670
    assert limit == pytest.approx(-dbeta / criticality.c, rel=3e-4)


@functools.lru_cache(maxsize=1)
def _curve():
    # the closing end of the curve, where the onset turns from super- to subcritical
    return spatial.swirl_boundary_curve(PARAMS.replace(A=1e-4), (0.99, 1.01), (5e-5, 1.5e-4),
                                        ds=0.2, from_end="high")


def test_the_degenerate_pitchfork_is_where_c_at_the_single_A_edges_changes_sign():
    curve = _curve()
    assert curve.complete and len(curve.folds) == 1
    [point] = curve.degenerate
    assert point["kind"] == "degenerate_pitchfork"
    # c changes sign along the curve once, from the low edges' supercritical onset round the
    # closing fold to the high edges' subcritical one, past the fold
    c = curve.table["c"]
    assert np.count_nonzero(np.diff(np.sign(c))) == 1
    assert c[0] * c[-1] < 0
    fold = curve.folds[0]
    assert point["A"] > fold["A"] and point["rho"] > fold["rho"]

    def c_at_the_high_edge(A):
        band = spatial.swirl_band(PARAMS.replace(A=A), (0.99, 1.01), from_end="high")
        j = int(np.argmax(band.edges["rho"]))
        at_edge, y = _edge(band, j, PARAMS.replace(A=A))
        c_at_the_high_edge.rho[A] = at_edge.rho
        return spatial.swirl_edge_criticality(at_edge, y).c

    c_at_the_high_edge.rho = {}
    A_zero = brentq(c_at_the_high_edge, 7.5e-5, 1.4e-4, xtol=1e-13, rtol=1e-12)
    c_at_the_high_edge(A_zero)
    assert point["A"] == pytest.approx(A_zero, rel=1e-6)
    assert point["rho"] == pytest.approx(c_at_the_high_edge.rho[A_zero], abs=1e-6)
    # on either side the onset is as c says: subcritical above A_zero, supercritical below
    assert c_at_the_high_edge(1.05 * A_zero) > 0 > c_at_the_high_edge(0.95 * A_zero)


@pytest.mark.parametrize("call, name", [
    (lambda band: spatial.swirl_edge_criticality(*_edge(band, 0), kind="neimark_sacker"),
     "kind"),
    (lambda band: spatial.swirl_edge_criticality(_edge(band, 0)[0], [0.0, 0.0, 0.0]),
     "y_orbit"),
    # off the edge, on the planar orbit there: no out-of-plane multiplier at +1
    (lambda band: spatial.swirl_edge_criticality(
        PARAMS.replace(rho=1.02), sloshdyn.periodic_orbit(PARAMS.replace(rho=1.02),
                                                          _edge(band, 0)[1]).y0),
     r"multiplier nearest \+1 is .*: not a pitchfork")])
def test_bad_input_is_named(call, name):
    with pytest.raises(sloshdyn.InputError, match=name):
        call(_band())


def test_an_undamped_edge_is_refused_not_given_a_coefficient():
    """Without damping the out-of-plane map preserves volume: its multipliers at the edge come
    in a pair (nu, 1/nu) that reaches +1 together, the one-dimensional centre manifold of the
    cubic normal form does not exist, and the coefficient is refused by name (before the check
    it came back as -7.4e4 at one undamped edge and 330 at another: artefacts of the
    near-Jordan block)."""
    undamped = PARAMS.replace(zeta=0.0, A=1e-3)
    band = spatial.swirl_band(undamped, RHO_RANGE, from_end="high")
    at_edge, y = _edge(band, 0, undamped)
    nu = spatial.out_of_plane_multipliers(at_edge, sloshdyn.periodic_orbit(at_edge, y).y0)
    assert abs(np.prod(np.abs(nu)) - 1) < 1e-6        # volume preserving (measured 1.05e-8)
    with pytest.raises(sloshdyn.InputError, match="preserves volume"):
        spatial.swirl_edge_criticality(at_edge, y)
