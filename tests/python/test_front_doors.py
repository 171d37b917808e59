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
        assert {name.split(" [")[0]: value for name, value in tank.items()} == inp.tank.properties
        assert inp.tank.parameters() == params


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
    p = sloshdyn.Parameters.from_physical(M=100, L=2, k=7848, theta0=0.5, l=0.5, m=10, b=49.05,
                                          g=9.81)
    assert math.isclose(p.s1, 0.25) and math.isclose(p.mu1, 0.1)
    assert math.isclose(p.kappa, 1.0, rel_tol=1e-12) and math.isclose(p.beta, 1.0, rel_tol=1e-12)


def test_tank_pendulum_hand_values():
    # R = h = 1 m, water (worked in tests/fortran/test_model.f90)
    t = sloshdyn.tank_pendulum(1.0, 1.0, liquid_density=1000.0)
    assert np.allclose([t.pendulum_length, t.sloshing_mass, t.d1, t.rigid_mass, t.d0],
                       [0.571604, 1357.73, 0.0137169, 1783.86, -0.445500], rtol=1e-5)
    assert math.isclose(t.liquid_mass, 1000 * math.pi)


def _analysis_case(tmp_path, analysis, extra):
    text = ("&model s1 = 1.5, mu1 = 0.5, kappa = 1.804897259, theta0 = 0.7853981633974483, "
            "gamma = 0.001 /\n&excitation A = 0.00075, rho = 0.513 /\n"
            f"&analysis kind = '{analysis}' /\n&output directory = 'out' /\n"
            "&integration rtol = 1e-8, atol = 1e-11 /\n" + extra)
    (tmp_path / "case.nml").write_text(text)
    return sloshdyn.read_namelist(tmp_path / "case.nml")


def test_simulate_same_numbers(exe, tmp_path):
    inp = _analysis_case(tmp_path, "simulate", "&simulation t_end = 200, n_out = 51, y0 = 0.1, 0, 0, 0 /\n")
    result = run(exe, "case.nml", tmp_path)
    assert result.returncode == 0, result.stderr
    rows = read_csv(tmp_path / "out" / "history.csv")
    sim = sloshdyn.simulate(inp.params, inp.simulation["t_end"], inp.simulation["y0"],
                            n_out=inp.simulation["n_out"],
                            integration=inp.integration)
    assert [r["x1"] for r in rows] == list(sim.x1)
    assert [r["u1"] for r in rows] == list(sim.u[0])
    assert [r["impact_force"] for r in rows] == list(sim.impact_force)
    counts = read_csv(tmp_path / "out" / "simulation.csv")[0]
    assert counts["n_accepted"] == sim.n_accepted and counts["n_rhs"] == sim.n_rhs


def test_steady_state_and_sweep_same_numbers(exe, tmp_path):
    steady = "&steady transient_periods = 50, settle_tol = 0, window_periods = 20 /\n"
    inp = _analysis_case(tmp_path, "steady_state", steady)
    assert run(exe, "case.nml", tmp_path).returncode == 0
    row = read_csv(tmp_path / "out" / "steady_state.csv")[0]
    st = sloshdyn.steady_state(inp.params, steady=inp.steady,
                               integration=inp.integration)
    assert (row["max_x1"], row["max_u2"], row["spread"]) == (st.max_x1, st.max_u2, st.spread)
    points = read_csv(tmp_path / "out" / "poincare.csv")
    assert [p["x2"] for p in points] == list(st.poincare[2])

    inp = _analysis_case(tmp_path, "sweep", steady + "&sweep parameter = 'A', start = 0.0005, "
                         "stop = 0.001, n_points = 3, direction = 'down' /\n")
    assert run(exe, "case.nml", tmp_path).returncode == 0
    rows = read_csv(tmp_path / "out" / "sweep.csv")
    sweep = sloshdyn.amplitude_sweep(inp.params, [0.001, 0.00075, 0.0005],
                                     steady=inp.steady,
                                     integration=inp.integration)
    assert [r["A"] for r in rows] == [0.001, 0.00075, 0.0005]
    assert [r["max_x1"] for r in rows] == list(sweep.column("max_x1"))


def test_examples_are_valid():
    for path in sorted(EXAMPLES.glob("*.nml")):
        sloshdyn.read_namelist(path)


def test_failed_integration_writes_nothing(exe, tmp_path):
    _analysis_case(tmp_path, "simulate", "&simulation t_end = 2000 /\n")
    text = (tmp_path / "case.nml").read_text().replace("atol = 1e-11", "atol = 1e-11, max_steps = 10")
    (tmp_path / "case.nml").write_text(text)
    result = run(exe, "case.nml", tmp_path)
    assert result.returncode == 4
    assert "max_steps = 10" in result.stderr and "tau = " in result.stderr
    assert not (tmp_path / "out").exists()


def test_frequency_response_same_numbers(exe, tmp_path):
    shutil.copy(EXAMPLES / "fig12_response.nml", tmp_path)
    result = run(exe, "fig12_response.nml", tmp_path)
    assert result.returncode == 0, result.stderr
    inp = sloshdyn.read_namelist(tmp_path / "fig12_response.nml")
    r = inp.response_range
    response = sloshdyn.frequency_response(inp.params, (r["start"], r["stop"]),
                                           resonance=r["resonance"], continuation=inp.response)
    rows = read_csv(tmp_path / inp.directory / "response.csv")
    assert [row["a1"] for row in rows] == list(response.table["a1"])
    assert [row["delta3"] for row in rows] == list(response.table["delta3"])
    special = read_csv(tmp_path / inp.directory / "special_points.csv")
    assert [(s["kind"], s["rho"]) for s in special] == \
           [(s.kind, s.rho) for s in response.special_points]
    assert "Hopf  rho = 0.5092" in result.stdout
