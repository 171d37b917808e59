"""Property-based tests of the two front doors (hypothesis): for valid input files drawn over
every group and analysis, the executable and `sloshdyn-py run` write byte-identical result
files; for malformed text, both give the same clear error (exit code 3 / InputError, the same
words, no compiler runtime text) and write nothing.

Examples per test: SLOSHDYN_FUZZ_EXAMPLES (default 15; set it high for a nightly run)."""

import os
import pathlib
import subprocess
import sysconfig

import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

import sloshdyn
from sloshdyn import cli

EXAMPLES = int(os.environ.get("SLOSHDYN_FUZZ_EXAMPLES", "15"))
FUZZ = settings(max_examples=EXAMPLES, deadline=None, derandomize=True,
                suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
EXE = str(pathlib.Path(sysconfig.get_path("scripts")) / "sloshdyn")


def group(name, values):
    body = ", ".join(f"{k} = {v}" for k, v in values.items())
    return f"&{name} {body} /\n"


def real(lo, hi):
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False).map(lambda x: f"{x!r}")


MODEL = st.fixed_dictionaries({
    "s1": real(1.0, 2.0), "mu1": real(0.2, 0.7), "kappa": real(2.1, 6.0),
    "theta0": real(0.3, 1.2), "gamma": real(0.0, 0.01)},
    optional={"beta": real(0.0, 20.0), "delta": real(0.0, 0.5), "n": st.sampled_from(["2", "6"]),
              "p": st.sampled_from(["1", "2"])})
TANK = st.fixed_dictionaries({"R": real(0.5, 5.0), "h": real(0.3, 5.0), "rho_liquid": real(500, 2000)})
STRUCTURE = st.fixed_dictionaries({
    "M": real(1e6, 2e6), "L": real(1.0, 5.0), "k": real(1e8, 1e9), "theta0": real(0.3, 1.0)},
    optional={"c": real(0.0, 1e4), "b": real(0.0, 1e4), "d": real(0.0, 1e3)})
EXCITATION = st.fixed_dictionaries({"A": real(0.0, 0.002), "rho": real(0.3, 1.5)})
INTEGRATION = st.fixed_dictionaries({}, optional={
    "rtol": real(1e-10, 1e-6), "atol": real(1e-13, 1e-9),
    "method": st.sampled_from(["'rk45'", "'dop853'"])})
STEADY = st.fixed_dictionaries({
    "transient_periods": st.integers(0, 20).map(str), "settle_tol": st.just("0"),
    "window_periods": st.integers(16, 24).map(str)},
    optional={"samples_per_period": st.integers(4, 64).map(str),
              "periodic_tol": real(1e-6, 1e-2)})

ANALYSES = {
    "linear": st.just(""),
    "simulate": st.fixed_dictionaries({"t_end": real(1.0, 60.0), "n_out": st.integers(2, 50).map(str)},
                                      optional={"y0": st.just("0.01, 0, 0.02, 0")})
                  .map(lambda d: group("simulation", d)),
    "steady_state": STEADY.map(lambda d: group("steady", d)),
    "sweep": st.tuples(STEADY, st.fixed_dictionaries({
        "parameter": st.sampled_from(["'rho'", "'A'"]), "start": real(0.4, 0.6),
        "stop": real(0.6, 0.8), "n_points": st.integers(1, 3).map(str),
        "direction": st.sampled_from(["'up'", "'down'", "'both'"])}))
             .map(lambda t: group("steady", t[0]) + group("sweep", t[1])),
    "frequency_response": st.fixed_dictionaries({
        "resonance": st.sampled_from(["'3:1'", "'none'"]), "parameter": st.just("'rho'"),
        "start": real(0.3, 0.6), "stop": real(0.6, 0.9), "n_scan": st.integers(1, 3).map(str),
        "n_amplitudes": st.integers(1, 3).map(str), "n_phases": st.integers(1, 3).map(str)})
        .map(lambda d: group("response", d)),
    "lyapunov": st.fixed_dictionaries({
        "transient_periods": st.integers(0, 5).map(str), "n_periods": st.just("10"),
        "renormalise_every": st.sampled_from(["1", "2", "5"])})
        .map(lambda d: group("lyapunov", d)),
}


@st.composite
def valid_input(draw):
    analysis = draw(st.sampled_from(sorted(ANALYSES)))
    if draw(st.booleans()):
        system = group("model", draw(MODEL))
    else:
        system = group("tank", draw(TANK)) + group("structure", draw(STRUCTURE))
    parts = [system, group("excitation", draw(EXCITATION)),
             f"&analysis kind = '{analysis}' /\n", draw(ANALYSES[analysis]),
             group("integration", draw(INTEGRATION)) if draw(st.booleans()) else "",
             "&output directory = 'out' /\n"]
    return "".join(draw(st.permutations(parts)))


def run_both(tmp_path, text):
    """Exit code and output files of the executable and of sloshdyn-py run (in this process)."""
    outcomes = []
    for door in ("exe", "py"):
        folder = tmp_path / door
        folder.mkdir(parents=True, exist_ok=True)
        for old in folder.rglob("*"):
            if old.is_file():
                old.unlink()
        (folder / "input.nml").write_text(text)
        if door == "exe":
            result = subprocess.run([EXE, "input.nml"], cwd=folder, capture_output=True,
                                    text=True, timeout=300)
            code, error = result.returncode, result.stderr
        else:
            cwd = os.getcwd()
            os.chdir(folder)
            try:
                code = cli.main(["run", "input.nml"])
            finally:
                os.chdir(cwd)
            error = ""
        files = {p.relative_to(folder).as_posix(): p.read_bytes()
                 for p in sorted(folder.rglob("*.csv"))}
        outcomes.append((code, error, files))
    return outcomes


@FUZZ
@given(text=valid_input())
def test_valid_inputs_give_identical_files(tmp_path_factory, text):
    tmp_path = tmp_path_factory.mktemp("valid")
    (exe_code, exe_error, exe_files), (py_code, _, py_files) = run_both(tmp_path, text)
    assert exe_code == py_code, (text, exe_error)
    assert exe_files == py_files, text
    if exe_code == 0:
        assert "out/parameters.csv" in exe_files


BASE = ("&model s1 = 1.5, mu1 = 0.5, kappa = 1.8, theta0 = 0.7, gamma = 0.001 /\n"
        "&excitation A = 0.00075, rho = 0.5 /\n&analysis kind = 'linear' /\n"
        "&integration rtol = 1e-9, method = 'rk45' /\n&output directory = 'out' /\n")
NOISE = st.sampled_from(["&", "/", "=", ",", "'", '"', "!", "$", "(", ")", "(7)", "&end", "&modell",
                         "nan", "1e999", "-", ".", "x", "kind", "rtol", " ", "\n", "&model",
                         "y0(2)", "*", "3*1.0", "True", ".t.", "\t", "é"])


@st.composite
def malformed_input(draw):
    text = BASE
    for _ in range(draw(st.integers(1, 3))):
        at = draw(st.integers(0, len(text)))
        if draw(st.booleans()):
            text = text[:at] + draw(NOISE) + text[at:]
        else:
            text = text[:at] + text[at + draw(st.integers(1, 8)):]
    return text


@FUZZ
@given(text=malformed_input())
def test_malformed_inputs_give_the_same_clear_error(tmp_path_factory, text):
    tmp_path = tmp_path_factory.mktemp("malformed")
    (tmp_path / "input.nml").write_text(text, encoding="utf-8")
    result = subprocess.run([EXE, "input.nml"], cwd=tmp_path, capture_output=True, text=True,
                            timeout=60)
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        try:
            sloshdyn.read_namelist("input.nml")
            python_error = None
        except sloshdyn.SloshdynError as exc:
            python_error = str(exc)
    finally:
        os.chdir(cwd)
    if python_error is None:
        assert result.returncode == 0, (text, result.stderr)
        return
    assert result.returncode == 3, (text, result.stderr)
    assert result.stderr.strip() == f"sloshdyn: error: {python_error}", text
    for raw in ("Fortran runtime", "At line", "Cannot match namelist", "namelist read:"):
        assert raw not in python_error, (text, python_error)
    assert not (tmp_path / "out").exists()
