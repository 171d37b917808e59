"""The two front doors read, check and run a namelist file with the same code: each defect the
review found where they disagreed has a test here (each failed before the one reader)."""

import shutil
import subprocess
import sys

import numpy as np
import pytest

import sloshdyn
from conftest import EXAMPLES, directory_tree, run, write

MODEL = ("&model s1 = 1.5, mu1 = 0.5, kappa = 1.804897259, theta0 = 0.7853981633974483, "
         "gamma = 0.001 /\n")


def cli(*args, cwd):
    return subprocess.run([sys.executable, "-m", "sloshdyn", *args], cwd=cwd, capture_output=True,
                          text=True, timeout=600)


def both_front_doors(tmp_path, text):
    """Run the same file through the executable and `sloshdyn-py run`; return the two output
    directories (exe/out, py/out) and the two processes."""
    results = []
    for door in ("exe", "py"):
        (tmp_path / door).mkdir()
        write(tmp_path / door, text)
    results.append(run(sys_exe(), "input.nml", tmp_path / "exe"))
    results.append(cli("run", "input.nml", cwd=tmp_path / "py"))
    return tmp_path / "exe" / "out", tmp_path / "py" / "out", results


def sys_exe():
    import pathlib
    import sysconfig
    return str(pathlib.Path(sysconfig.get_path("scripts")) / "sloshdyn")


def same_csv_files(a, b):
    names = sorted(p.name for p in a.glob("*.csv"))
    assert names and names == sorted(p.name for p in b.glob("*.csv"))
    for name in names:
        assert (a / name).read_bytes() == (b / name).read_bytes(), name


def test_steady_and_lyapunov_keep_their_own_transient(tmp_path):
    """&steady and &lyapunov both have transient_periods; each group has its own."""
    text = (MODEL + "&excitation A = 0.00075, rho = 0.509615 /\n&analysis kind = 'lyapunov' /\n"
            "&steady transient_periods = 300 /\n"
            "&lyapunov transient_periods = 20, n_periods = 40, renormalise_every = 2 /\n"
            "&output directory = 'out' /\n")
    inp = sloshdyn.read_namelist(write(tmp_path, text))
    assert inp.steady.transient_periods == 300 and inp.lyapunov.transient_periods == 20
    exe_out, py_out, (exe, py) = both_front_doors(tmp_path, text)
    assert exe.returncode == 0 and py.returncode == 0, (exe.stderr, py.stderr)
    same_csv_files(exe_out, py_out)
    result = sloshdyn.lyapunov_exponent(inp.params, lyapunov=sloshdyn.Lyapunov(
        transient_periods=20, n_periods=40, renormalise_every=2))
    exponent, history = result.exponent, result.history
    estimates = np.loadtxt(exe_out / "lyapunov.csv", delimiter=",", skiprows=1)[:, 1]
    assert list(estimates) == list(history) and estimates[-1] == exponent


def test_sweep_and_response_keep_their_own_range(tmp_path):
    text = (MODEL + "&analysis kind = 'sweep' /\n&sweep start = 0.50, stop = 0.51, n_points = 3 /\n"
            "&response start = 0.2, stop = 0.3 /\n&output directory = 'out' /\n")
    inp = sloshdyn.read_namelist(write(tmp_path, text))
    assert (inp.sweep["start"], inp.sweep["stop"]) == (0.50, 0.51)
    assert (inp.response_range["start"], inp.response_range["stop"]) == (0.2, 0.3)


def test_a_branch_cut_by_max_points_is_an_error_in_both(tmp_path):
    """frequency_response reports a branch that reached max_points instead of truncating it,
    with the same per-branch limit and the same message by both front doors."""
    text = (MODEL + "&excitation A = 0.00075 /\n&analysis kind = 'frequency_response' /\n"
            "&response start = 0.49, stop = 0.53, max_points = 40 /\n&output directory = 'out' /\n")
    exe_out, py_out, (exe, py) = both_front_doors(tmp_path, text)
    assert exe.returncode == 4 and py.returncode == exe.returncode
    assert "max_points = 40" in exe.stderr
    assert exe.stderr.split("error: ", 1)[1] == py.stderr.split("error: ", 1)[1]
    assert not exe_out.exists() and not py_out.exists()
    inp = sloshdyn.read_namelist(tmp_path / "exe" / "input.nml")
    with pytest.raises(sloshdyn.CapacityError) as info:
        sloshdyn.frequency_response(inp.params, (0.49, 0.53),
                                    continuation=inp.response)
    assert not info.value.partial.complete and len(info.value.partial.table["a1"]) > 0


@pytest.mark.parametrize("kind, extra", [
    ("lyapunov", "&lyapunov transient_periods = 10, n_periods = 20 /\n"),
    ("periodic_response", "&response start = 0.50, stop = 0.501 /\n"
                          "&steady transient_periods = 200, settle_tol = 0 /\n"),
    ("simulate", "&simulation t_end = 50, n_out = 11 /\n"),
])
def test_every_analysis_honours_the_method(tmp_path, kind, extra):
    """method = 'dop853' is used (and reported) by every analysis that integrates."""
    outputs = {}
    for method in ("rk45", "dop853"):
        text = (MODEL + "&excitation A = 0.00075, rho = 0.50 /\n"
                f"&analysis kind = '{kind}' /\n&integration method = '{method}' /\n" + extra +
                f"&output directory = '{method}' /\n")
        result = run(sys_exe(), write(tmp_path, text, f"{method}.nml").name, tmp_path)
        assert result.returncode == 0, result.stderr
        assert method in result.stdout.split("Results written")[0].split("\n", 6)[-1]
        outputs[method] = {p.name: p.read_bytes() for p in (tmp_path / method).glob("*.csv")
                           if p.name != "parameters.csv"}
    assert outputs["rk45"].keys() == outputs["dop853"].keys()
    assert outputs["rk45"] != outputs["dop853"]


def test_shooting_does_not_depend_on_earlier_calls(fig12):
    """Shots are functions of their inputs: no cache carries results between calls."""
    p = fig12.replace(rho=0.50)
    first = sloshdyn.periodic_orbit(p, np.zeros(4))
    sloshdyn.periodic_orbit(p.replace(rho=0.52), np.zeros(4))
    again = sloshdyn.periodic_orbit(p, np.zeros(4))
    assert np.array_equal(first.y0, again.y0) and np.array_equal(first.multipliers, again.multipliers)


def test_one_set_of_integration_defaults():
    """rtol, atol and max_steps have one default each: the core's, used by the namelist reader,
    Python's Integration and every analysis (periodic ones included)."""
    import inspect
    defaults = sloshdyn.Integration()
    assert (defaults.rtol, defaults.atol, defaults.max_steps) == (1e-9, 1e-12, 10**8)
    for function in (sloshdyn.periodic_orbit, sloshdyn.periodic_response, sloshdyn.lyapunov_exponent):
        assert inspect.signature(function).parameters["integration"].default == defaults
    assert sloshdyn.Lyapunov().transient_periods == 1000


def test_namelist_defaults_are_the_python_defaults(tmp_path):
    inp = sloshdyn.read_namelist(write(tmp_path, MODEL))
    assert inp.integration == sloshdyn.Integration()
    assert inp.steady == sloshdyn.Steady()
    assert inp.response == sloshdyn.Continuation()
    assert inp.params == sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259,
                                             theta0=0.7853981633974483, gamma=0.001)
    study = sloshdyn.read_namelist(write(tmp_path, MODEL + (
        "&excitation A = 0.001, rho = 0.5 /\n&study kind = 'basins', store = 'b.zarr', "
        "x1_start = -1, x1_stop = 1, dx1_start = -1, dx1_stop = 1 /\n"), "study.nml")).study
    assert study["worker_kind"] == sloshdyn.studies.WORKER_KIND == "threads"


@pytest.mark.parametrize("text, words", [
    # a malformed line: the executable gave raw gfortran text, Python accepted it
    (MODEL + "&output directoryoutput directory = 'x' /\n",
     ["&output", "unexpected text 'directoryoutput'"]),
    # a missing required count was reported as out of range
    (MODEL + "&excitation rho = 0.5 /\n&analysis kind = 'sweep' /\n&sweep start = 0.5, stop = 0.6 /\n",
     ["&sweep", "required variable n_points is missing"]),
    # a group after '/' on the same line
    (MODEL + "&analysis kind = 'simulate' / &simulation t_end = -1 /\n", ["t_end = -1"]),
    # an array index in Python and the executable alike
    (MODEL + "&analysis kind = 'simulate' /\n&simulation t_end = 1, y0(5) = 1 /\n", ["y0"]),
])
def test_both_front_doors_give_the_same_clear_error(tmp_path, monkeypatch, text, words):
    path = write(tmp_path, text)
    before = directory_tree(tmp_path)
    result = run(sys_exe(), path.name, tmp_path)
    assert result.returncode == 3
    monkeypatch.chdir(tmp_path)
    with pytest.raises(sloshdyn.InputError) as info:
        sloshdyn.read_namelist(path.name)
    assert result.stderr.strip() == f"sloshdyn: error: {info.value}"
    for word in words:
        assert word in str(info.value), (word, str(info.value))
    assert "Fortran runtime" not in result.stderr and "At line" not in result.stderr
    assert directory_tree(tmp_path) == before


def test_array_index_means_the_same_in_both(tmp_path):
    path = write(tmp_path, MODEL + "&simulation y0(2) = 0.5 /\n")
    assert sloshdyn.read_namelist(path).simulation["y0"] == [0.0, 0.5, 0.0, 0.0]


def test_run_writes_the_executables_files(tmp_path):
    """`sloshdyn-py run` and the executable write byte-identical CSV files."""
    text = (EXAMPLES / "fig12_response.nml").read_text().replace(
        "directory = 'sloshdyn_output/fig12_response'", "directory = 'out'")
    exe_out, py_out, (exe, py) = both_front_doors(tmp_path, text)
    assert exe.returncode == 0 and py.returncode == 0
    same_csv_files(exe_out, py_out)
    assert (py_out / "response.png").stat().st_size > 1000
    shutil.rmtree(tmp_path / "exe")
