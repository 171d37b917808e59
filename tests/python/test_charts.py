"""Stability charts (issue 14): the curves against the one-parameter continuation and the
eigenvalues (numpy), the Fig 11 cusp against the fold count of one-parameter runs, the grid's
counts against brute-force integration, the two front doors, bad input."""

import math
import shutil

import numpy as np
import pytest

import sloshdyn
from conftest import read_csv, run, write

FIG12 = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=math.pi / 4, gamma=0.001,
                            A=0.00075, rho=0.51)
FIG11 = FIG12.replace(kappa=1.807915943, gamma=0.0025, A=0.0005)
RHO, A_RANGE = (0.49, 0.53), (0.0, 0.002)


@pytest.fixture(scope="module")
def fig12_chart():
    return sloshdyn.stability_chart(FIG12, RHO, A_RANGE, chart=sloshdyn.Chart(n_x=11, n_y=5))


def one_parameter(params, A, rho_range=RHO, n_scan=41, ds_max=None):
    settings = sloshdyn.Continuation(n_scan=n_scan)
    if ds_max:
        settings = sloshdyn.Continuation(n_scan=n_scan, ds_max=ds_max, ds=min(0.002, ds_max))
    return sloshdyn.frequency_response(params.replace(A=A), rho_range, resonance="3:1",
                                       continuation=settings)


def rho_crossings(curves, y, level):
    """The rho where the curves cross y = level (y: "A" or "kappa"), by linear interpolation
    between their points."""
    crossings = []
    for c in curves:
        values = getattr(c, y)
        s = np.sign(values - level)
        for j in np.nonzero(s[:-1] * s[1:] < 0)[0]:
            t = (level - values[j]) / (values[j + 1] - values[j])
            crossings.append(c.rho[j] + t * (c.rho[j + 1] - c.rho[j]))
    return crossings


def slow_flow_jacobian(params, rho, A, state):
    f, jacobian, status, message = sloshdyn._core.sloshdyn_bridge_charts.slow_flow_field(
        *params.replace(rho=rho, A=A).array(), 1, state)
    assert status == 0, message
    return f, jacobian


def test_fig12_chart_is_complete_with_its_known_points(fig12_chart):
    kinds = [c.kind for c in fig12_chart.curves]
    assert fig12_chart.complete and kinds.count("hopf") >= 1 and kinds.count("fold") >= 2
    # one Hopf curve carries both Hopf points of Fig 12 (sec 4.2: rho = 0.50925 and 0.50998)
    hopf = [c for c in fig12_chart.curves if c.kind == "hopf"]
    crossings = rho_crossings(hopf, "A", 0.00075)
    hopf_points = sorted(s.rho for s in one_parameter(FIG12, 0.00075).special_points
                         if s.kind == "hopf")
    assert len(hopf_points) == 2
    assert np.allclose(sorted(crossings), hopf_points, atol=2e-6)     # linear interpolation
    assert np.allclose(hopf_points, [0.50925, 0.50998], atol=5e-5)    # the paper's


def test_every_sampled_fold_point_is_a_fold_of_the_one_parameter_run(fig12_chart):
    rng = np.random.default_rng(1)
    checked = 0
    for curve in (c for c in fig12_chart.curves if c.kind == "fold"):
        inside = np.nonzero((curve.A > 2e-4) & (curve.rho > 0.495) & (curve.rho < 0.525))[0]
        for j in rng.choice(inside, size=min(2, len(inside)), replace=False):
            r = one_parameter(FIG12, curve.A[j], (curve.rho[j] - 0.004, curve.rho[j] + 0.004),
                              n_scan=21)
            folds = [s.rho for s in r.special_points if s.kind == "fold"]
            assert min(abs(np.array(folds) - curve.rho[j])) < 1e-7, (curve.rho[j], folds)
            checked += 1
    assert checked >= 4


def test_every_hopf_point_has_a_pair_on_the_imaginary_axis(fig12_chart):
    for curve in (c for c in fig12_chart.curves if c.kind == "hopf"):
        for j in range(0, len(curve.rho), 25):
            if curve.omega[j] <= 0:
                continue        # a neutral-saddle part (real pair), not a Hopf point
            f, jac = slow_flow_jacobian(FIG12, curve.rho[j], curve.A[j], curve.state[:, j])
            assert np.max(np.abs(f)) < 1e-12
            eig = np.linalg.eigvals(jac)
            pair = eig[np.argmin(np.abs(eig.real))]
            assert abs(pair.real) < 1e-9 and abs(abs(pair.imag) - curve.omega[j]) < 1e-9


def fold_count(A, rho_range):
    r = one_parameter(FIG11, A, rho_range, n_scan=5, ds_max=2e-4)
    return sum(s.kind == "fold" for s in r.special_points)


def test_fig11_fold_pair_is_born_at_the_cusp():
    chart = sloshdyn.stability_chart(FIG11, RHO, (0.0002, 0.0006), chart=sloshdyn.Chart(n_x=5, n_y=3))
    cusps = [q for q in chart.codim2_points if q.kind == "cusp"]
    assert len(cusps) == 1
    cusp = cusps[0]
    assert 0.00025 < cusp.A < 0.0005          # sec 4.2: between the Fig 11 curves
    window = (cusp.rho - 0.01, cusp.rho + 0.01)
    assert fold_count(cusp.A * (1 - 1e-3), window) == 0
    assert fold_count(cusp.A * (1 + 1e-3), window) == 2


def test_brute_force_finds_the_stable_states_the_grid_counts():
    chart = sloshdyn.stability_chart(FIG12, RHO, A_RANGE, chart=sloshdyn.Chart(
        n_x=5, n_y=3, brute_force_starts=200), threads=2)
    g = chart.grid
    away = g["near_curve"] == 0
    assert away.sum() >= 5
    assert np.all(g["brute_force_stable"][away] == g["n_stable"][away])
    assert np.all(g["brute_force_stable"] <= g["n_steady"])


def test_threads_do_not_change_the_chart():
    one = sloshdyn.stability_chart(FIG12, RHO, A_RANGE, chart=sloshdyn.Chart(n_x=5, n_y=3), threads=1)
    two = sloshdyn.stability_chart(FIG12, RHO, A_RANGE, chart=sloshdyn.Chart(n_x=5, n_y=3), threads=2)
    for a, b in zip(one.curves, two.curves):
        assert np.array_equal(a.rho, b.rho) and np.array_equal(a.A, b.A)
    for name in one.grid:
        assert np.array_equal(one.grid[name], two.grid[name])


CHART_NML = """&model s1 = 1.5, mu1 = 0.5, kappa = 1.804897259, theta0 = 0.7853981633974483,
  gamma = 0.001 /
&excitation A = 0.00075, rho = 0.51 /
&analysis kind = 'stability_chart' /
&chart x_min = 0.49, x_max = 0.53, y_min = 0.0, y_max = 0.002, n_x = 11, n_y = 5 /
&output directory = 'out' /
"""


def test_both_front_doors_give_the_same_chart(exe, tmp_path, fig12_chart):
    write(tmp_path, CHART_NML)
    result = run(exe, "input.nml", tmp_path)
    assert result.returncode == 0, result.stderr
    curves = read_csv(tmp_path / "out" / "chart_curves.csv")
    rho = np.array([r["rho"] for r in curves])
    assert np.array_equal(rho, np.concatenate([c.rho for c in fig12_chart.curves]))
    grid = read_csv(tmp_path / "out" / "chart_grid.csv")
    assert [r["n_stable"] for r in grid] == list(fig12_chart.grid["n_stable"])
    again = sloshdyn.charts.chart_from_files(tmp_path / "out")
    assert [q.kind for q in again.codim2_points] == [q.kind for q in fig12_chart.codim2_points]
    assert sloshdyn.read_namelist(tmp_path / "input.nml").chart_range["x_range"] == RHO


def test_the_runs_take_the_continuation_settings_by_both_front_doors(exe, tmp_path,
                                                                   fig12_chart):
    """The chart's one-parameter runs take &response's numbers (Python: continuation=), n_scan
    from &chart: the executable with a &response of its own and Python with that Continuation
    give the same chart, and it is not the chart of the default settings (the settings reach
    the runs)."""
    write(tmp_path, CHART_NML + "&response n_amplitudes = 4, ds = 0.001, ds_max = 0.004 /\n")
    result = run(exe, "input.nml", tmp_path)
    assert result.returncode == 0, result.stderr
    inp = sloshdyn.read_namelist(tmp_path / "input.nml")
    assert inp.response == sloshdyn.Continuation(n_amplitudes=4, ds=0.001, ds_max=0.004)
    chart = sloshdyn.stability_chart(FIG12, RHO, A_RANGE, chart=inp.chart,
                                     continuation=inp.response)
    curves = read_csv(tmp_path / "out" / "chart_curves.csv")
    rho = np.array([r["rho"] for r in curves])
    assert np.array_equal(rho, np.concatenate([c.rho for c in chart.curves]))
    assert not np.array_equal(rho, np.concatenate([c.rho for c in fig12_chart.curves]))


@pytest.mark.parametrize("change,words", [
    ("x = 'kappa'", ["x = 'kappa'", "rho or A"]),
    ("x = 'sigma'", ["x = 'sigma'", "rho, A, gamma, kappa"]),
    ("y = 'rho'", ["y = 'rho'", "another of"]),
    ("x_max = 0.48", ["x_max = 0.48", "x_min = 0.49"]),
    ("n_x = 0", ["n_columns = 0"]),
    ("model = 'full_model'", ["model = 'full_model'", "slow_flow_3:1"]),
    ("threads = 0", ["threads = 0"]),
])
def test_bad_chart_input(exe, tmp_path, change, words):
    write(tmp_path, CHART_NML.replace("n_x = 11", change + ", n_x = 11")
          if "n_x" not in change else CHART_NML.replace("n_x = 11", change))
    result = run(exe, "input.nml", tmp_path)
    assert result.returncode == 3
    for word in words:
        assert word in result.stderr, (word, result.stderr)
    with pytest.raises(sloshdyn.InputError) as info:
        sloshdyn.read_namelist(tmp_path / "input.nml")
    assert words[0] in str(info.value)


def test_full_model_neimark_sacker_curve_meets_the_periodic_response():
    # rows at A = 0.000675 and 0.000825: the curves cross A = 0.00075 between their points
    chart = sloshdyn.stability_chart(FIG12, (0.505, 0.515), (0.0006, 0.0009), model="full",
                                     chart=sloshdyn.Chart(n_x=5, n_y=2), threads=2)
    ns = [c for c in chart.curves if c.kind == "neimark_sacker"]
    assert ns and all(c.complete for c in ns)
    crossings = rho_crossings(ns, "A", 0.00075)
    branch = sloshdyn.periodic_response(FIG12.replace(rho=0.505), (0.505, 0.515))
    located = sorted(s.rho for s in branch.special_points if s.kind == "neimark_sacker")
    assert len(located) == 2 and len(crossings) == 2
    assert np.allclose(sorted(crossings), located, atol=3e-5)     # the bound


def test_kappa_chart_crosses_the_fig12_kappa_at_its_hopf_points():
    # kappa as the second parameter: the modal coefficients are expanded again at every kappa
    chart = sloshdyn.stability_chart(FIG12, RHO, (1.79, 1.82), y="kappa",
                                     chart=sloshdyn.Chart(n_x=11, n_y=5))
    crossings = rho_crossings([c for c in chart.curves if c.kind == "hopf"], "kappa",
                              FIG12.kappa)
    hopf_points = sorted(s.rho for s in one_parameter(FIG12, 0.00075).special_points
                         if s.kind == "hopf")
    assert np.allclose(sorted(crossings), hopf_points, atol=2e-6)
    assert all(np.all(c.A == FIG12.A) for c in chart.curves)
