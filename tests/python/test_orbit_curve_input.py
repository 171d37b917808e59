"""The namelist's door to the two-parameter curves from a special point of a periodic branch
(issue 42, item 1: `&response curve_at`, `curve_start`, `curve_stop` with kind =
'periodic_response'): the executable and `sloshdyn-py run` write periodic_curve.csv row for row
equal to Python's PeriodicBranch.curve on the same branch and box; the curve (the
Neimark-Sacker curve of Fig 12's tank, continued in rho at A = 0.00075) passes through the
Neimark-Sacker points that independent one-parameter branches at other values of A locate;
bad values are refused by name with exit 3."""

import numpy as np
import pytest

import sloshdyn
from conftest import read_csv, run, write
from test_one_reader import MODEL, both_front_doors, sys_exe

FIG12 = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=np.pi / 4, gamma=0.001,
                            A=0.00075, rho=0.505)
RHO, A_BOX, POINTS = (0.505, 0.515), (0.0007, 0.0008), 400
# &response's defaults for the branch (docs/namelist.md), with max_points = POINTS
CONTINUATION = sloshdyn.Continuation(ds=0.002, ds_min=1e-9, ds_max=0.01, x_scale=1.0,
                                     max_points=POINTS)


def text(response):
    return (MODEL + "&excitation A = 0.00075, rho = 0.505 /\n"
            "&analysis kind = 'periodic_response' /\n"
            f"&response parameter = 'rho', start = 0.505, stop = 0.515, {response} /\n"
            "&output directory = 'out' /\n")


def branch_at(A):
    return sloshdyn.periodic_response(FIG12.replace(A=A), RHO, continuation=CONTINUATION)


@pytest.fixture(scope="module")
def python_curve():
    branch = branch_at(FIG12.A)
    kinds = [s.kind for s in branch.special_points]
    j = kinds.index("neimark_sacker")
    return j + 1, branch.curve(branch.special_points[j], RHO, A_BOX,
                               chart=sloshdyn.Chart(max_points=POINTS))


def test_both_doors_write_pythons_curve_row_for_row(tmp_path, python_curve):
    j, curve = python_curve
    assert curve.kind == "neimark_sacker" and curve.complete and len(curve.rho) >= 5
    exe_out, py_out, results = both_front_doors(
        tmp_path, text(f"max_points = {POINTS}, curve_at = {j}, curve_start = 0.0008, "
                       "curve_stop = 0.0007"))            # either order, as start and stop
    for out, result in zip((exe_out, py_out), results):
        assert result.returncode == 0, result.stdout + result.stderr
        assert f"neimark_sacker curve through special point {j}" in result.stdout
        rows = read_csv(out / "periodic_curve.csv")
        assert len(rows) == len(curve.rho)
        for name, column in (("rho", curve.rho), ("A", curve.A), ("x1", curve.state[0]),
                             ("x4", curve.state[3]), ("omega", curve.omega)):
            np.testing.assert_allclose([r[name] for r in rows], column, rtol=1e-15, atol=0)
        assert {r["kind"] for r in rows} == {"neimark_sacker"}
        assert all(r["gamma"] == FIG12.gamma and r["kappa"] == FIG12.kappa for r in rows)
        ends = read_csv(out / "periodic_curve_ends.csv")
        assert len(ends) == 1 and ends[0]["complete"] == 1
        assert [r["codim2"] for r in rows] == list(curve.codim2)


def test_curve_passes_through_independent_neimark_sacker_points(python_curve):
    _, curve = python_curve
    for target in (0.00072, 0.00078):          # points of the curve away from its start
        k = int(np.argmin(np.abs(curve.A - target)))
        rho, A = float(curve.rho[k]), float(curve.A[k])
        assert abs(A - FIG12.A) > 2e-5
        located = [s.rho for s in branch_at(A).special_points if s.kind == "neimark_sacker"]
        assert min(abs(r - rho) for r in located) < 1e-7, (A, rho, located)


@pytest.mark.parametrize("response, words", [
    ("curve_at = -1", "curve_at = -1 is out of range: it must be >= 0"),
    ("curve_at = 9, curve_start = 0.0007, curve_stop = 0.0008",
     "curve_at = 9 is out of range: the branch has 4 special points"),
    ("curve_at = 1, curve_stop = 0.0008", "curve_start"),
    ("curve_at = 1, curve_start = -0.0007, curve_stop = 0.0008",
     "curve_start = -0.0007 is out of range"),
    ("curve_at = 1, curve_start = 0.0007, curve_stop = 0.0007", "the curve's range is empty"),
])
def test_bad_curve_values_are_named(tmp_path, response, words):
    write(tmp_path, text(f"max_points = {POINTS}, " + response))
    exe = run(sys_exe(), "input.nml", tmp_path)
    assert exe.returncode == 3, exe.stdout + exe.stderr
    assert words in exe.stdout + exe.stderr


def test_a_branch_point_has_no_curve(tmp_path):
    # test_branch_switching's branch: one special point, a branch point
    write(tmp_path, MODEL + "&excitation A = 1.55, rho = 0.3 /\n"
          "&analysis kind = 'periodic_response' /\n"
          "&response parameter = 'A', start = 1.55, stop = 1.62, curve_at = 1, "
          "curve_start = 0.29, curve_stop = 0.31 /\n&output directory = 'out' /\n")
    exe = run(sys_exe(), "input.nml", tmp_path)
    assert exe.returncode == 3, exe.stdout + exe.stderr
    assert ("curve_at = 1 is a branch_point: a curve starts at a fold, a period_doubling or a "
            "neimark_sacker") in exe.stdout + exe.stderr


def test_a_branch_in_A_takes_the_curves_range_in_rho(tmp_path):
    # the same Neimark-Sacker curve, met by a branch in A at rho = 0.50925 (A ~ 0.00074)
    text_a = (MODEL + "&excitation A = 0.0007, rho = 0.50925 /\n"
              "&analysis kind = 'periodic_response' /\n"
              f"&response parameter = 'A', start = 0.0007, stop = 0.0008, max_points = {POINTS}, "
              "curve_at = 1, curve_start = 0.5085, curve_stop = 0.5095 /\n"
              "&output directory = 'out' /\n")
    write(tmp_path, text_a)
    exe = run(sys_exe(), "input.nml", tmp_path)
    assert exe.returncode == 0, exe.stdout + exe.stderr
    branch = sloshdyn.periodic_response(FIG12.replace(rho=0.50925, A=0.0007), A_range=A_BOX,
                                        continuation=CONTINUATION)
    assert [s.kind for s in branch.special_points] == ["neimark_sacker"]
    curve = branch.curve(branch.special_points[0], (0.5085, 0.5095), A_BOX,
                         chart=sloshdyn.Chart(max_points=POINTS))
    rows = read_csv(tmp_path / "out" / "periodic_curve.csv")
    assert len(rows) == len(curve.rho) >= 5 and curve.complete
    for name, column in (("rho", curve.rho), ("A", curve.A), ("x2", curve.state[1])):
        np.testing.assert_allclose([r[name] for r in rows], column, rtol=1e-15, atol=0)
    # from edge to edge of the box in A: the branch's range, not the curve's range in rho
    assert curve.ends == ("box", "box")
    assert (curve.A.min(), curve.A.max()) == (pytest.approx(0.0007), pytest.approx(0.0008))
