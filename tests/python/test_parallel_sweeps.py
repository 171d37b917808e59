"""Threads never change the answer of a sweep (issue 17). A sweep that carries the state is
sequential and refuses threads > 1, by both front doors with the same message; a sweep of
independent points (each from y0) gives the same results, bit for bit, on 1, 2 or 3 threads, by
both front doors -- on a single-valued case and between the folds of Fig 12, where two steady
motions coexist and a carried sweep and points from rest end on different branches."""

import numpy as np
import pytest

import sloshdyn
from conftest import run, write
from test_one_reader import sys_exe

FAST = sloshdyn.Steady(transient_periods=60, settle_tol=0, window_periods=16)
MODEL = ("&model s1 = 1.5, mu1 = 0.5, kappa = 1.804897259, theta0 = 0.7853981633974483, "
         "gamma = 0.001 /\n&excitation A = 0.00075, rho = 0.5 /\n")
STEADY = "&steady transient_periods = 60, settle_tol = 0, window_periods = 16 /\n"
CASES = {
    # multi-valued: between the Fig 12 folds (rho ~ 0.509-0.5123) the response has two stable
    # branches; single-valued: far below resonance
    "multi-valued rho": ("rho", np.linspace(0.5095, 0.5122, 7)),
    "single-valued rho": ("rho", np.linspace(0.40, 0.44, 5)),
    "amplitude": ("A", np.linspace(0.0002, 0.0012, 5)),
}


@pytest.mark.parametrize("case", CASES)
def test_threads_give_identical_results(fig12, case):
    parameter, values = CASES[case]
    sweep = sloshdyn.frequency_sweep if parameter == "rho" else sloshdyn.amplitude_sweep
    p = fig12.replace(rho=0.513) if parameter == "A" else fig12
    results = [sweep(p, values, steady=FAST, start_from="y0", threads=t) for t in (1, 2, 3)]
    for r in results[1:]:
        for name in ("max_x1", "max_x2", "max_u1", "max_u2", "spread", "transient_periods"):
            assert list(r.column(name)) == list(results[0].column(name)), (case, name)
        assert list(r.column("motion")) == list(results[0].column("motion"))
    # each point is the steady state from y0, exactly
    k = len(values) // 2
    alone = sloshdyn.steady_state(p.replace(**{parameter: float(values[k])}), steady=FAST)
    assert results[0].points[k].max_x1 == alone.max_x1


def test_independent_points_differ_from_the_carried_sweep_where_branches_coexist(fig12):
    """The case above is really multi-valued: carried from below, the sweep stays on the other
    branch at some points (so 'independent' and 'carried' are different questions)."""
    values = list(np.linspace(0.505, 0.5122, 9))
    carried = sloshdyn.frequency_sweep(fig12, values, steady=FAST)
    independent = sloshdyn.frequency_sweep(fig12, values, steady=FAST, start_from="y0", threads=2)
    assert list(carried.column("max_u1")) != list(independent.column("max_u1"))


@pytest.mark.parametrize("threads", [2, 3])
def test_a_carried_sweep_refuses_threads(fig12, tmp_path, threads):
    with pytest.raises(sloshdyn.InputError) as info:
        sloshdyn.frequency_sweep(fig12, [0.50, 0.51], steady=FAST, threads=threads)
    assert f"threads = {threads}" in str(info.value) and "start_from = 'y0'" in str(info.value)
    text = (MODEL + "&analysis kind = 'sweep' /\n" + STEADY +
            f"&sweep start = 0.5, stop = 0.51, n_points = 2, threads = {threads} /\n"
            "&output directory = 'out' /\n")
    result = run(sys_exe(), write(tmp_path, text).name, tmp_path)
    assert result.returncode == 3
    assert result.stderr.strip() == f"sloshdyn: error: &sweep: {info.value}"
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("direction", ["up", "down", "both"])
def test_both_front_doors_on_1_2_3_threads(tmp_path, direction):
    files = []
    for threads in (1, 2, 3):
        text = (MODEL + "&analysis kind = 'sweep' /\n" + STEADY +
                f"&sweep start = 0.5095, stop = 0.5122, n_points = 4, direction = '{direction}', "
                f"start_from = 'y0', threads = {threads} /\n&output directory = 'out{threads}' /\n")
        result = run(sys_exe(), write(tmp_path, text, f"t{threads}.nml").name, tmp_path)
        assert result.returncode == 0, result.stderr
        files.append((tmp_path / f"out{threads}" / "sweep.csv").read_bytes())
    assert files[0] == files[1] == files[2]
    inp = sloshdyn.read_namelist(tmp_path / "t2.nml")
    python = sloshdyn.frequency_sweep(inp.params, sloshdyn.sweep_values(0.5095, 0.5122, 4, direction),
                                      steady=inp.steady, start_from="y0",
                                      threads=inp.sweep["threads"])
    rows = np.loadtxt(tmp_path / "out1" / "sweep.csv", delimiter=",", skiprows=1, ndmin=2)
    assert list(rows[:, 2]) == list(python.column("max_x1"))
