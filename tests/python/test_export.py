"""Export of branches, curves and studies (issue 42, item 5): a branch exported to CSV and read
back is the same branch (every value bit for bit, its parameters, settings and method), the
file names the units of every column and the method, and a chart's curve and a study's Dataset
make the same round trip (xarray's `identical`: values, dimensions, coordinates, attributes)."""

import json
import math

import numpy as np
import pytest

import sloshdyn
from sloshdyn import export

FIG12 = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=math.pi / 4,
                            gamma=0.001, A=0.00075, rho=0.51)


@pytest.fixture(scope="module")
def branch():
    p = FIG12.replace(rho=0.3, A=1.55)                  # a fold and a branch point on it
    return sloshdyn.periodic_response(p, A_range=(1.55, 1.62))


def test_a_branch_round_trips_through_csv(branch, tmp_path):
    assert branch.special_points, "the case must have special points"
    path = export.write_csv(branch, tmp_path / "branch.csv")
    back = export.branch_from_dataset(export.read_csv(path))
    assert back.table.keys() == branch.table.keys()
    for name, values in branch.table.items():
        assert np.array_equal(back.table[name], values), name        # bit for bit
    assert len(back.special_points) == len(branch.special_points)
    for a, b in zip(back.special_points, branch.special_points):
        assert (a.kind, a.rho, a.A, a.max_x1) == (b.kind, b.rho, b.A, b.max_x1)
        assert np.array_equal(a.y0, b.y0)
    for name in ("parameter", "complete", "message", "method", "periods", "params",
                 "lambda_range", "continuation", "integration"):
        assert getattr(back, name) == getattr(branch, name), name
    # the file names its units, method and parameters in its header
    text = path.read_text()
    header = [json.loads(line.split(" ", 2)[2]) for line in text.splitlines()
              if line.startswith("# variable ")]
    units = {v["name"]: v["attrs"]["units"] for v in header}
    assert units["A"].startswith("1 (ground amplitude over the support height L)")
    assert units["y1"] == "theta0" and units["y2"] == "theta0 omega"
    assert set(units) >= {"lambda", "rho", "A", "max_x1", "mu1", "stable"}
    dataset = json.loads(text.splitlines()[1][len("# dataset "):])["attrs"]
    assert "single shooting" in dataset["method"]
    assert json.loads(dataset["parameters"])["kappa"] == FIG12.kappa
    # the branch switched at its branch point still round-trips (a new period count)
    ds = export.to_dataset(branch)
    assert ds["mu1"].dtype == complex and ds.sizes["point"] == len(branch.table["A"])


def test_the_csv_reads_as_a_plain_table(branch, tmp_path):
    """The first table (the points) reads with numpy's loadtxt after its header: columns as
    named, numbers in full precision."""
    path = export.write_csv(branch, tmp_path / "branch.csv")
    lines = path.read_text().splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("# table ")) + 1
    names = lines[start].split(",")
    n = len(branch.table["A"])
    rows = [line.split(",") for line in lines[start + 1:start + 1 + n]]
    assert np.array_equal([float(r[names.index("A")]) for r in rows], branch.table["A"])


def test_a_curve_round_trips(tmp_path):
    chart = sloshdyn.stability_chart(FIG12, (0.49, 0.53), (0.0, 0.002),
                                     chart=sloshdyn.Chart(n_x=5, n_y=3))
    curve = chart.curves[0]
    ds = export.to_dataset(curve, params=chart.params)
    back = export.read_csv(export.write_csv(curve, tmp_path / "curve.csv", params=chart.params))
    assert back.identical(ds)
    assert np.array_equal(back["rho"].values, curve.rho)
    assert back["state"].shape == curve.state.shape
    assert list(back["codim2"].values) == list(curve.codim2)
    assert back.attrs["kind"] == f"{curve.kind}_curve"
    assert json.loads(back.attrs["parameters"])["gamma"] == FIG12.gamma


def test_a_study_round_trips(tmp_path):
    """A response map (dimensions frequency x amplitude): its CSV grid rows start with their
    frequency and amplitude, and the Dataset reads back identical."""
    ds = sloshdyn.response_map(FIG12, [0.5, 0.51], [0.0005, 0.00075, 0.001],
                               tmp_path / "map.zarr", workers=1, worker_kind="threads",
                               steady=sloshdyn.Steady(max_transient_periods=100),
                               points_per_task=6, progress=False)
    path = export.write_csv(ds, tmp_path / "map.csv")
    back = export.read_csv(path)
    assert back.identical(ds)
    lines = path.read_text().splitlines()
    grid = next(i for i, line in enumerate(lines)
                if line.startswith('# table {"dims": ["frequency", "amplitude"]'))
    assert lines[grid + 1].startswith("frequency,amplitude,")
    assert [float(v) for v in lines[grid + 2].split(",")[:2]] == [0.5, 0.0005]
    assert [float(v) for v in lines[grid + 4].split(",")[:2]] == [0.5, 0.001]


def test_export_refuses_what_it_cannot_write(tmp_path):
    with pytest.raises(sloshdyn.InputError, match="PeriodicBranch"):
        export.to_dataset({"A": [1, 2]})
    (tmp_path / "x.csv").write_text("a,b\n1,2\n")
    with pytest.raises(sloshdyn.InputError, match="not a sloshdyn export file"):
        export.read_csv(tmp_path / "x.csv")
