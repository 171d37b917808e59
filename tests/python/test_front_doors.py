"""The executable and Python give the same numbers for the same namelist."""

import math
import shutil

import numpy as np
import pytest

import sloshdyn
from conftest import EXAMPLES, read_csv, run


@pytest.mark.parametrize("example", ["fig12_linear.nml", "tank_linear.nml"])
def test_same_numbers_from_executable_and_python(exe, tmp_path, example):
    shutil.copy(EXAMPLES / example, tmp_path / example)
    result = run(exe, example, tmp_path)
    assert result.returncode == 0, result.stderr
    inp = sloshdyn.read_namelist(tmp_path / example)
    out = tmp_path / inp.directory
    params = inp.params

    row = read_csv(out / "parameters.csv")[0]
    for name in ("s1", "mu1", "kappa", "theta0", "beta", "gamma", "delta", "A", "rho"):
        assert row[name] == getattr(params, name), name    # bit for bit through the CSV
    a, b = params.coefficients()
    assert [row[f"a{i}"] for i in range(1, 7)] == list(a)
    assert [row[f"b{i}"] for i in range(1, 7)] == list(b)

    modes = sloshdyn.linear_modes(params)
    freq = read_csv(out / "frequencies.csv")[0]
    assert freq["omega1"] == modes.omega1 and freq["omega2"] == modes.omega2
    assert freq["omega1_dgeev"] == modes.omega1_dgeev and freq["omega2_dgeev"] == modes.omega2_dgeev

    eq = sloshdyn.equilibria(params)
    rows = read_csv(out / "equilibria.csv")
    assert len(rows) == len(eq)
    for r, e in zip(rows, eq):
        assert (r["theta"], r["phi"], r["verdict"], bool(r["physical"])) == \
               (e.theta, e.phi, e.verdict, e.physical)
        assert [r[f"re{i}"] for i in range(1, 5)] == list(e.eigenvalues.real)

    kappas = [r["kappa"] for r in read_csv(out / "kappa_31.csv")]
    expected = sloshdyn.kappa_for_detuning(params.s1, params.mu1, inp.sigma1,
                                           inp.kappa_min, inp.kappa_max)
    assert kappas == list(expected)

    rh = read_csv(out / "routh_hurwitz.csv")[0]
    assert [rh[f"c{i}"] for i in range(1, 5)] == list(eq.routh_coefficients)
    assert bool(rh["routh_stable"]) == eq.routh_stable

    if inp.tank is not None:
        tank = read_csv(out / "tank.csv")[0]
        assert (tank["l"], tank["m"], tank["d1"], tank["m0"], tank["d0"]) == \
               (inp.tank.l, inp.tank.m, inp.tank.d1, inp.tank.m0, inp.tank.d0)


def test_summary_reports_the_paper_numbers(exe, tmp_path):
    shutil.copy(EXAMPLES / "fig12_linear.nml", tmp_path)
    result = run(exe, "fig12_linear.nml", tmp_path)
    assert "omega1 = 0.50936" in result.stdout and "omega2 = 1.53308" in result.stdout
    assert "kappa = 1.80489" in result.stdout


def test_namelist_round_trip(tmp_path, fig12):
    fig12.to_namelist(tmp_path / "p.nml")
    assert sloshdyn.Parameters.from_namelist(tmp_path / "p.nml") == fig12
    assert not list(tmp_path.glob(".*.tmp"))


def test_physical_route_matches_the_groups_of_eq_9():
    # worked by hand: g = 9.81, l = 0.5 -> omega^2 = 19.62; L = 2, M = 100, m = 10, k = 7848
    p = sloshdyn.Parameters.from_physical(M=100, L=2, k=7848, theta0=0.5, l=0.5, m=10, b=49.05)
    assert math.isclose(p.s1, 0.25) and math.isclose(p.mu1, 0.1)
    assert math.isclose(p.kappa, 1.0, rel_tol=1e-12) and math.isclose(p.beta, 1.0, rel_tol=1e-12)


def test_tank_pendulum_hand_values():
    # R = h = 1 m, water (worked in tests/fortran/test_model.f90)
    t = sloshdyn.tank_pendulum(1.0, 1.0, rho_liquid=1000.0)
    assert np.allclose([t.l, t.m, t.d1, t.m0, t.d0], [0.571604, 1357.73, 0.0137169, 1783.86, -0.445500],
                       rtol=1e-5)
    assert math.isclose(t.m_F, 1000 * math.pi)
