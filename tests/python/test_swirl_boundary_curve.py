"""The swirl boundary in (rho, A) continued as one curve, and its codimension-2 point where
damping closes the band (issue 41, item 4).

Independent sources: the single-A swirl edges of ``swirl_band`` (the core's continuation in rho
with Brent's method on det(M_b - I), a separate code path from the curve's pseudo-arclength in
(rho, A) with its quasi-Newton corrector, sloshdyn_swirl_curve); and, for the closing point, a bisection on the damping
zeta at the closing amplitude, each step asking whether swirl exists at all: the largest
out-of-plane multiplier modulus, maximized over rho by scipy's bounded scalar search, above 1.
The executable's curve (kind = 'swirl', &response curve_at) against Python's, row by row.
"""

import functools

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

import sloshdyn
from sloshdyn import spatial
from conftest import read_csv, run, write

PARAMS = sloshdyn.Parameters(s1=1.0, mu1=0.01, kappa=1e3, theta0=1.4, beta=0.0, gamma=0.0,
                             delta=0.0, A=2.5e-4, rho=1.02, zeta=5e-4, n=6, p=2)
RHO_RANGE, A_RANGE = (0.98, 1.03), (5e-5, 5e-4)
A_VALUES = (1e-4, 2.5e-4, 4e-4)


@functools.lru_cache(maxsize=1)
def _curve():
    return spatial.swirl_boundary_curve(PARAMS, RHO_RANGE, A_RANGE, A_values=A_VALUES,
                                        from_end="high")


def test_the_curve_passes_through_the_edges_of_each_single_A_band():
    curve = _curve()
    assert curve.complete and curve.kind == "branch_point"
    at = curve.at
    for A in A_VALUES:
        band = spatial.swirl_band(PARAMS.replace(A=A), RHO_RANGE, from_end="high")
        edges = np.sort(band.edges["rho"][band.edges["kind"] == "branch_point"])
        # both edges of the band, the low and the high one, are on the one curve
        on_curve = np.sort(at["rho"][at["A"] == A])
        assert len(edges) == 2 and len(on_curve) == 2
        assert np.abs(on_curve - edges).max() <= 1e-8
    # and every point of the curve is an edge: an out-of-plane multiplier at +1
    for j in range(0, len(curve.table["rho"]), 7):
        params = PARAMS.replace(rho=curve.table["rho"][j], A=curve.table["A"][j])
        y0 = [curve.table[f"y{i}"][j] for i in range(1, 5)]
        nu = spatial.out_of_plane_multipliers(params, y0)
        assert np.abs(nu - 1).min() <= 1e-9


def _swirl_margin(zeta, A, rho_guess, y0, half_width=6e-4):
    """max over rho of |nu| - 1 for the out-of-plane multipliers nu near +1 (a complex pair
    inside the unit circle, or two real ones) on the planar branch through y0 (scipy's bounded
    search within half_width of rho_guess)."""
    guess = [np.asarray(y0, float)]

    def minus_modulus(rho):
        params = PARAMS.replace(zeta=zeta, A=A, rho=rho)
        orbit = sloshdyn.periodic_orbit(params, guess[0])
        nu = spatial.out_of_plane_multipliers(params, orbit.y0)
        return -np.abs(nu[np.abs(nu - 1) < 0.1]).max()

    best = minimize_scalar(minus_modulus, bounds=(rho_guess - half_width, rho_guess + half_width),
                           method="bounded", options={"xatol": 1e-10})
    return -best.fun - 1


def test_the_closing_point_is_where_a_bisection_on_zeta_closes_the_band():
    curve = _curve()
    closing = [f for f in curve.folds if f["kind"] == "closing"]
    assert len(closing) == 1 and len(curve.folds) == 1
    fold = closing[0]
    # the band exists above the closing amplitude and not below it
    assert A_RANGE[0] < fold["A"] < min(A_VALUES)
    zeta0 = PARAMS.zeta
    low, high = 0.9 * zeta0, 1.1 * zeta0
    assert _swirl_margin(low, fold["A"], fold["rho"], fold["y0"]) > 0
    assert _swirl_margin(high, fold["A"], fold["rho"], fold["y0"]) < 0
    while high - low > 1e-8 * zeta0:
        mid = 0.5 * (low + high)
        if _swirl_margin(mid, fold["A"], fold["rho"], fold["y0"]) > 0:
            low = mid
        else:
            high = mid
    assert 0.5 * (low + high) == pytest.approx(zeta0, rel=1e-6)


@pytest.mark.parametrize("options, name", [
    ({"A_range": (1e-3, 2e-3)}, "A_range"),
    ({"edge": 5}, "edge")])
def test_bad_input_is_named(options, name):
    kwargs = {"A_range": A_RANGE, "from_end": "high", **options}
    A_range = kwargs.pop("A_range")
    with pytest.raises(sloshdyn.InputError, match=name):
        spatial.swirl_boundary_curve(PARAMS, RHO_RANGE, A_range, **kwargs)


def test_a_curve_stopped_early_raises_with_the_curve_so_far():
    with pytest.raises(sloshdyn.ConvergenceError, match="max_points = 3") as info:
        spatial.swirl_boundary_curve(PARAMS, RHO_RANGE, A_RANGE, max_points=3, from_end="high")
    partial = info.value.partial
    assert not partial.complete and len(partial.table["rho"]) == 5    # 3 each way, one shared
    # its points are edges all the same: an out-of-plane multiplier at +1
    for j in range(5):
        params = PARAMS.replace(rho=partial.table["rho"][j], A=partial.table["A"][j])
        nu = spatial.out_of_plane_multipliers(params, [partial.table[f"y{i}"][j]
                                                       for i in range(1, 5)])
        assert np.abs(nu - 1).min() <= 1e-9


CURVE_NML = ("&model s1 = 1.0, mu1 = 0.01, kappa = 1000, theta0 = 1.4, beta = 0, gamma = 0, "
             "delta = 0, zeta = 5e-4, n = 6, p = 2, planar = .false. /\n"
             "&excitation A = 0.001, rho = 1.0 /\n&analysis kind = 'swirl' /\n"
             "&response parameter = 'rho', start = 1.0, stop = 1.02, curve_at = {edge}, "
             "curve_start = {low}, curve_stop = 1.2e-3 /\n&output directory = 'out' /\n")


def test_the_namelists_curve_at_is_the_python_swirl_boundary_curve(exe, tmp_path):
    path = write(tmp_path, CURVE_NML.format(edge=1, low=5e-5))
    result = run(exe, path.name, tmp_path)
    assert result.returncode == 0, result.stderr
    rows = read_csv(tmp_path / "out" / "swirl_boundary_curve.csv")
    folds = read_csv(tmp_path / "out" / "swirl_curve_folds.csv")
    inp = sloshdyn.read_namelist(path)
    r = inp.response_range
    curve = spatial.swirl_boundary_curve(inp.params, (r["start"], r["stop"]),
                                         (r["curve_start"], r["curve_stop"]),
                                         max_points=inp.response.max_points,
                                         continuation=inp.response, integration=inp.integration)
    assert len(rows) == len(curve.table["rho"]) > 5
    for name in ("rho", "A", "y1", "y4", "max_x1", "c"):
        assert [row[name] for row in rows] == list(curve.table[name]), name
    # the one fold is the closing point, the same as the test case's above (only A differs)
    assert len(folds) == len(curve.folds) == 1 and folds[0]["closing"] == 1
    assert curve.folds[0]["kind"] == "closing"
    assert (folds[0]["rho"], folds[0]["A"]) == (curve.folds[0]["rho"], curve.folds[0]["A"])
    assert folds[0]["A"] == pytest.approx(_curve().folds[0]["A"], rel=1e-8)
    # and its one degenerate pitchfork, where the edge's criticality c changes sign, is the
    # test case's too (test_swirl_criticality.py checks it against single-A edges)
    degenerate = read_csv(tmp_path / "out" / "swirl_curve_degenerate.csv")
    assert len(degenerate) == len(curve.degenerate) == len(_curve().degenerate) == 1
    assert ((degenerate[0]["rho"], degenerate[0]["A"])
            == (curve.degenerate[0]["rho"], curve.degenerate[0]["A"]))
    assert degenerate[0]["A"] == pytest.approx(_curve().degenerate[0]["A"], rel=1e-8)


@pytest.mark.parametrize("edge, low, name", [(5, 5e-5, "curve_at = 5"),
                                             (1, 1.1e-3, "curve_start, curve_stop")])
def test_the_namelists_bad_curve_values_are_named(exe, tmp_path, edge, low, name):
    path = write(tmp_path, CURVE_NML.format(edge=edge, low=low))
    result = run(exe, path.name, tmp_path)
    assert result.returncode == 3 and name in result.stderr, result.stderr
