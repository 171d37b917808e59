"""The command line: help on every subcommand, run = the executable's numbers, reproduce writes
figures and a report, check passes and fails (naming the quantity) on a perturbed reference."""

import csv
import json
import shutil
import subprocess
import sys

import pytest

import sloshdyn
from sloshdyn import reference
from conftest import EXAMPLES, read_csv, run


def cli(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "sloshdyn", *args], cwd=cwd, capture_output=True,
                          text=True, timeout=600)


@pytest.mark.parametrize("command", [[], ["run"], ["reproduce"], ["check"], ["examples"]])
def test_help(command):
    result = cli(*command, "--help")
    assert result.returncode == 0 and "usage" in result.stdout


@pytest.mark.parametrize("example,files", [
    ("fig12_linear.nml", ["frequencies.csv", "equilibria.csv", "kappa_31.csv"]),
    ("fig12_response.nml", ["response.csv", "special_points.csv"]),
    ("fig12_periodic.nml", ["periodic_branch.csv", "periodic_special_points.csv"]),
    ("fig17_lyapunov.nml", ["lyapunov.csv"]),
    ("tank_two_components.nml", ["seismic_spatial.csv", "seismic_spatial_peaks.csv"]),
    ("swirl_sweep.nml", ["swirl_branch.csv", "swirl_edges.csv"]),
])
def test_run_gives_the_executables_numbers(exe, tmp_path, example, files):
    for sub in ("exe", "py"):
        (tmp_path / sub).mkdir()
        shutil.copy(EXAMPLES / example, tmp_path / sub)
        shutil.copytree(EXAMPLES / "records", tmp_path / sub / "records")
    assert run(exe, example, tmp_path / "exe").returncode == 0
    result = cli("run", example, cwd=tmp_path / "py")
    assert result.returncode == 0, result.stderr
    out = sloshdyn.read_namelist(tmp_path / "py" / example).directory
    for name in files + ["parameters.csv"]:
        ours, theirs = read_csv(tmp_path / "py" / out / name), read_csv(tmp_path / "exe" / out / name)
        assert ours == theirs, name
    if example == "fig12_response.nml":
        assert (tmp_path / "py" / out / "response.png").stat().st_size > 1000


def test_run_reports_bad_input(tmp_path):
    (tmp_path / "bad.nml").write_text("&model s1 = -1, mu1 = 0.5, kappa = 1.8, theta0 = 0.7 /\n")
    result = cli("run", "bad.nml", cwd=tmp_path)
    assert result.returncode == 3 and "s1 = -1" in result.stderr


@pytest.fixture(scope="module")
def reproduced(tmp_path_factory):
    out = tmp_path_factory.mktemp("reproduce")
    result = cli("reproduce", "--out", str(out), "--quick", "--only", "3", "4", "9a")
    assert result.returncode == 0, result.stderr
    return out


def test_reproduce_writes_figures_report_and_values(reproduced):
    for name in ("fig03.png", "fig03.csv", "fig04.png", "fig09a.png", "report.md", "values.json"):
        assert (reproduced / name).stat().st_size > 0, name
    report = (reproduced / "report.md").read_text()
    assert "![Fig 4](fig04.png)" in report and "| fig9a_c11 |" in report and "Errata" in report
    assert not list(reproduced.glob(".*partial*"))       # nothing half-written
    values = json.loads((reproduced / "values.json").read_text())
    assert {row["quantity"] for row in reference.load()} <= set(values)


def test_check_passes_and_fails_on_a_perturbed_reference(reproduced, tmp_path):
    assert cli("check", str(reproduced)).returncode == 0
    shutil.copytree(reference.PACKAGE_REFERENCE, tmp_path / "ref")
    path = tmp_path / "ref" / "paper_values.csv"
    rows = list(csv.DictReader(open(path, newline="")))
    for row in rows:
        if row["quantity"] == "fig9a_c11":
            row["reference"] = str(float(row["reference"]) + 3 * float(row["tolerance"]))
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    result = cli("check", str(reproduced), "--reference", str(tmp_path / "ref"))
    assert result.returncode == 1
    assert "fig9a_c11" in result.stdout.splitlines()[-1]


def test_reference_tables_are_the_repository_copy():
    from conftest import ROOT
    sources = {"paper_values.csv": ROOT / "data" / "reference" / "paper_values.csv",
               "computed_values.csv": ROOT / "data" / "reference" / "computed_values.csv",
               "impact_parameters.csv": ROOT / "data" / "reference" / "impact_parameters.csv",
               "errata.md": ROOT / "docs" / "errata.md"}
    for name, source in sources.items():
        assert (reference.PACKAGE_REFERENCE / name).read_text() == source.read_text()


def test_every_tolerance_has_its_reason_and_bounds_only_where_the_paper_states_one():
    for row in reference.load():
        assert row["reason"].strip(), row["quantity"]
        if row["kind"] in ("at_least", "at_most", "factor"):
            assert row["reason"].startswith("a bound the paper states"), row["quantity"]
