"""Each input rule: the executable exits non-zero, names the variable, its value and the rule,
and writes nothing; Python raises InputError with the same information."""

import math
import re

import pytest

import sloshdyn
from conftest import directory_tree, run, write

MODEL = "&model s1 = 1.5, mu1 = 0.5, kappa = 1.8, theta0 = 0.7853981633974483, gamma = 0.001 /\n"
OUTPUT = "&output directory = 'out' /\n"
TANK = ("&tank radius = 5, liquid_depth = 6, freeboard = 1, liquid_density = 1000, "
        "tank_mass = 5e4, support_frequency = 2 /\n")
GROUND = "&ground_motion peak_acceleration = 0.05, frequency = 0.3 /\n"
SEISMIC = "&analysis kind = 'seismic' /\n"


def tank_with(**changes):
    text = TANK
    for name, value in changes.items():
        text = text.replace(" /\n", f", {name} = {value} /\n") if f" {name} =" not in text else \
            text.replace(f"{name} = " + text.split(f"{name} = ")[1].split(",")[0].split(" /")[0],
                         f"{name} = {value}")
    return text


def ground_with(**changes):
    return "&ground_motion " + ", ".join(
        f"{k} = {v}" for k, v in {"peak_acceleration": 0.05, "frequency": 0.3, **changes}.items()
        if v is not None) + " /\n"


def model_with(**changes):
    values = dict(s1=1.5, mu1=0.5, kappa=1.8, theta0=0.7853981633974483, gamma=0.001)
    values.update(changes)
    body = ", ".join(f"{k} = {v}" for k, v in values.items() if v is not None)
    return f"&model {body} /\n"


CASES = {
    # name: (namelist text, words the message must contain)
    "unknown group": (MODEL + "&modell s1 = 1 /\n" + OUTPUT, ["&modell"]),
    "unknown variable": (MODEL.replace("gamma", "gama") + OUTPUT, ["gama"]),
    "wrong type real": (model_with(s1="'abc'") + OUTPUT, ["s1", "real number"]),
    "wrong type integer": (model_with(n=1.5) + OUTPUT, ["n", "integer"]),
    "required value absent": (model_with(kappa=None) + OUTPUT, ["kappa", "missing"]),
    "mu1 = 0": (model_with(mu1=0.0) + OUTPUT, ["mu1 = 0", "(0, 1)"]),
    "mu1 = 1": (model_with(mu1=1.0) + OUTPUT, ["mu1 = 1", "(0, 1)"]),
    "theta0 = 0": (model_with(theta0=0.0) + OUTPUT, ["theta0 = 0", "(0, pi/2)"]),
    "theta0 = 1.6": (model_with(theta0=1.6) + OUTPUT, ["theta0 = 1.6", "(0, pi/2)"]),
    "s1 = 0": (model_with(s1=0.0) + OUTPUT, ["s1 = 0", "> 0"]),
    "n = 0": (model_with(n=0) + OUTPUT, ["n = 0", ">= 1"]),
    "p = -1": (model_with(p=-1) + OUTPUT, ["p = -1", ">= 0"]),
    "gamma < 0": (model_with(gamma=-0.1) + OUTPUT, ["gamma = -0.1", ">= 0"]),
    "delta < 0": (model_with(delta=-0.1) + OUTPUT, ["delta = -0.1", ">= 0"]),
    "beta < 0": (model_with(beta=-1.0) + OUTPUT, ["beta = -1", ">= 0"]),
    "kappa_hat <= 1": (model_with(kappa=1.4) + OUTPUT, ["kappa = 1.4", "kappa_hat"]),
    "radius <= 0": (tank_with(radius=-5) + OUTPUT, ["radius = -5", "> 0"]),
    "liquid_depth = 0": (tank_with(liquid_depth=0) + OUTPUT, ["liquid_depth = 0", "> 0"]),
    "freeboard = 0": (tank_with(freeboard=0) + OUTPUT, ["freeboard = 0", "> 0"]),
    # a freeboard beyond the linear wave is no longer refused (issue 38: the code check runs,
    # theta0 capped; test_design_check_inputs.py)
    "tank_mass < 0": (tank_with(tank_mass=-1) + OUTPUT, ["tank_mass = -1", ">= 0"]),
    # the roof methods' range (sloshdyn_roof check_roof; API 650 5.10.5 and 5.10.6)
    "cone roof too steep": (tank_with(roof_slope=40) + OUTPUT,
                            ["roof_slope = 40", "(0, 37] degrees"]),
    "dome roof too small": (tank_with(roof_radius=5) + OUTPUT,
                            ["roof_radius = 5", "[0.8 D, 1.2 D] = [8, 12] m"]),
    "cone and dome roof": (tank_with(roof_slope=10, roof_radius=10) + OUTPUT,
                           ["roof_slope = 10", "roof_radius = 10", "at most one"]),
    "support_damping = 1": (tank_with(support_damping=1.0) + OUTPUT,
                            ["support_damping = 1", "[0, 1)"]),
    "sloshing_damping < 0": (tank_with(sloshing_damping=-0.01) + OUTPUT,
                             ["sloshing_damping = -0.01", "[0, 1)"]),
    "liquid twice": (tank_with(liquid_mass=1e5) + OUTPUT,
                     ["liquid_density = 1000", "liquid_mass = 100000", "exactly one"]),
    "supports twice": (tank_with(support_stiffness=1e9) + OUTPUT,
                       ["support_frequency = 2", "support_stiffness = 1e9", "exactly one"]),
    "support coefficient < 0": (
        tank_with(support_frequency=0, support_stiffness=1e9, support_damping_coefficient=-1)
        + OUTPUT, ["support_damping_coefficient = -1", ">= 0"]),
    "impact_stiffness < 0": (tank_with(impact_stiffness=-1) + OUTPUT, ["impact_stiffness", "-1"]),
    "tank without tank_mass": (TANK.replace("tank_mass = 5e4, ", "") + OUTPUT,
                               ["tank_mass", "missing"]),
    "both descriptions": (MODEL + TANK + OUTPUT, ["&model", "not both"]),
    "old &structure": (TANK + "&structure M = 20000 /\n" + OUTPUT,
                       ["&structure", "support_frequency"]),
    "excitation with a tank": (TANK + "&excitation A = 0.001, rho = 0.5 /\n" + OUTPUT,
                               ["&excitation", "&ground_motion"]),
    "ground motion with a model": (MODEL + GROUND + OUTPUT, ["&ground_motion", "&tank"]),
    "seismic without ground motion": (TANK + SEISMIC + OUTPUT, ["seismic", "&ground_motion"]),
    "seismic with a model": (MODEL + SEISMIC + OUTPUT, ["seismic", "&tank"]),
    "unknown units": (TANK + ground_with(units="'furlongs'") + OUTPUT,
                      ["furlongs", "g, m/s^2 or cm/s^2"]),
    "peak_acceleration < 0": (TANK + ground_with(peak_acceleration=-0.1) + OUTPUT,
                              ["peak_acceleration = -0.1", ">= 0 [g]"]),
    "frequency = 0": (TANK + ground_with(frequency=0) + OUTPUT, ["frequency = 0", "> 0"]),
    "frequency missing": (TANK + ground_with(frequency=None) + OUTPUT, ["frequency", "missing"]),
    "two scalings": (TANK + ground_with(scale_factor=2, target_pga=0.1) + OUTPUT,
                     ["scale_factor = 2", "target_pga = 0.98", "at most one"]),
    "target_damping = 1.5": (TANK + ground_with(target_sa=0.1, target_damping=1.5) + OUTPUT,
                             ["target_damping = 1.5", "[0, 1)"]),
    "unknown record format": (TANK + "&ground_motion record = 'x.txt', format = 'xml' /\n" + OUTPUT,
                              ["format = 'xml'", "auto, at2 or columns"]),
    "seismic t_end < 0": (TANK + GROUND + SEISMIC + "&seismic t_end = -1 /\n" + OUTPUT,
                          ["t_end = -1"]),
    "seismic n_out = 1": (TANK + GROUND + SEISMIC + "&seismic n_out = 1 /\n" + OUTPUT,
                          ["n_out = 1"]),
    "frequency sweep of a model": (MODEL + "&excitation A = 0.001 /\n&analysis kind = 'sweep' /\n"
                                   "&sweep parameter = 'frequency', start = 0.2, stop = 0.3, "
                                   "n_points = 3 /\n" + OUTPUT, ["'frequency'", "&tank"]),
    "frequency sweep at 0 Hz": (TANK + ground_with(frequency=None) + "&analysis kind = 'sweep' /\n"
                                "&sweep parameter = 'frequency', start = 0, stop = 0.3, "
                                "n_points = 3 /\n" + OUTPUT, ["start = 0", "> 0 [Hz]"]),
    "unknown analysis": (MODEL + "&analysis kind = 'nonsense' /\n" + OUTPUT, ["nonsense", "linear"]),
    "simulate without t_end": (MODEL + "&analysis kind = 'simulate' /\n" + OUTPUT, ["t_end", "missing"]),
    "t_end <= 0": (MODEL + "&analysis kind = 'simulate' /\n&simulation t_end = -5 /\n" + OUTPUT,
                   ["t_end = -5", "> 0"]),
    "n_out < 2": (MODEL + "&analysis kind = 'simulate' /\n&simulation t_end = 5, n_out = 1 /\n"
                  + OUTPUT, ["n_out = 1"]),
    "y0 not numbers": (MODEL + "&analysis kind = 'simulate' /\n&simulation t_end = 5, y0 = 'a' /\n"
                       + OUTPUT, ["y0", "four real numbers"]),
    "sweep parameter": (MODEL + "&analysis kind = 'sweep' /\n&sweep parameter = 'kappa', start = 0.5, "
                        "stop = 0.6, n_points = 3 /\n" + OUTPUT, ["kappa", "rho, A, frequency"]),
    "sweep direction": (MODEL + "&analysis kind = 'sweep' /\n&sweep start = 0.5, stop = 0.6, "
                        "n_points = 3, direction = 'sideways' /\n" + OUTPUT, ["sideways"]),
    "sweep n_points": (MODEL + "&analysis kind = 'sweep' /\n&sweep start = 0.5, stop = 0.6, "
                       "n_points = 0 /\n" + OUTPUT, ["n_points = 0"]),
    "response resonance": (MODEL + "&analysis kind = 'frequency_response' /\n&response "
                           "resonance = '2:1', start = 0.5, stop = 0.6 /\n" + OUTPUT, ["2:1", "3:1, none"]),
    "response range": (MODEL + "&analysis kind = 'frequency_response' /\n&response start = 0.5 /\n"
                       + OUTPUT, ["stop", "missing"]),
    # rules of the settings that depend on the analysis: both front doors apply them when reading

    "rtol <= 0": (MODEL + "&excitation rho = 0.5 /\n&analysis kind = 'steady_state' /\n"
                  "&integration rtol = -1 /\n" + OUTPUT, ["rtol = -1"]),
    "steady without rho": (MODEL + "&analysis kind = 'steady_state' /\n" + OUTPUT,
                           ["rho = 0", "rho > 0"]),
    "window too short": (MODEL + "&excitation rho = 0.5 /\n&analysis kind = 'steady_state' /\n"
                         "&steady window_periods = 3 /\n" + OUTPUT, ["window_periods = 3"]),
}


@pytest.mark.parametrize("case", CASES)
def test_executable_rejects(exe, tmp_path, case):
    text, words = CASES[case]
    write(tmp_path, text)
    before = directory_tree(tmp_path)
    result = run(exe, "input.nml", tmp_path)
    assert result.returncode != 0
    for word in words:
        assert word in result.stderr, (word, result.stderr)
    assert result.stdout == ""
    assert directory_tree(tmp_path) == before   # nothing written


@pytest.mark.parametrize("case", CASES)
def test_python_rejects(tmp_path, case):
    text, words = CASES[case]
    path = write(tmp_path, text)
    with pytest.raises(sloshdyn.InputError) as info:
        inp = sloshdyn.read_namelist(path)
        sloshdyn.linear_modes(inp.params)   # the linear analysis needs kappa_hat > 1
    for word in words:
        assert word in str(info.value), (word, str(info.value))


def test_missing_file(exe, tmp_path):
    result = run(exe, "nowhere.nml", tmp_path)
    assert result.returncode != 0 and "nowhere.nml" in result.stderr
    with pytest.raises(sloshdyn.FileError, match="nowhere.nml"):
        sloshdyn.read_namelist(tmp_path / "nowhere.nml")


def test_no_argument(exe, tmp_path):
    result = run(exe, "--help", tmp_path)
    assert result.returncode == 0 and "usage" in result.stdout


@pytest.mark.parametrize("field,value,words", [
    ("mu1", 1.2, ["mu1 = 1.2", "(0, 1)"]),
    ("theta0", -0.1, ["theta0 = -0.1"]),
    ("n", 0, ["n = 0"]),
    ("s1", float("nan"), ["s1 = NaN"]),
])
def test_parameters_validate(fig12, field, value, words):
    with pytest.raises(sloshdyn.InputError) as info:
        fig12.replace(**{field: value})
    for word in words:
        assert word in str(info.value)


def test_kappa_hat_rule_names_kappa(fig12):
    with pytest.raises(sloshdyn.InputError, match=r"kappa = 1.4.*kappa_hat"):
        sloshdyn.linear_modes(fig12.replace(kappa=1.4))


def _variables_and_types():
    """(group, variable, type) of every variable the reader has, its type told by the value
    gfortran's namelist write gives its default (not by the reader's messages)."""
    text = sloshdyn._core.sloshdyn_bridge_input.namelist_defaults().decode().strip()
    cases = []
    for match in re.finditer(r"&(\w+)(.*?)/\s*$", text, re.M):
        group = match.group(1).lower()
        for name, default in re.findall(r"(\w+)=\s*(\"[^\"]*\"|[^,]*?)\s*,", match.group(2)):
            name, default = name.lower(), default.strip()
            if default.startswith('"') or default == "":      # record_y is written blank
                kind = "a quoted string"
            elif default in ("T", "F"):
                kind = ".true. or .false."
            elif all(c in "0123456789-*" for c in default):
                kind = "an integer"
            else:
                kind = "a real number"
            cases.append((group, name, kind))
    return cases


@pytest.mark.parametrize("group, name, kind", _variables_and_types(),
                         ids=lambda v: v if isinstance(v, str) and " " not in v else "")
def test_a_value_of_the_wrong_type_names_the_variable_and_its_type(tmp_path, group, name, kind):
    """Issue 44 item 5: `radius = 'abc'` in &tank_structure, &design, &chart (and planar,
    switch_at, min_workers, ...) was "unknown variable": every known variable given a value of
    another type is named with the type it must be."""
    wrong = ".true." if kind == "a quoted string" else "'abc'"
    context = {"model": "", "tank": "", "ground_motion": TANK}.get(group, MODEL)
    path = write(tmp_path, context + f"&{group} {name} = {wrong} /\n")
    with pytest.raises(sloshdyn.InputError) as error:
        sloshdyn.read_namelist(path)
    message = str(error.value)
    assert f"&{group} in" in message and f"{name} = {wrong} is not valid" in message, message
    assert "unknown variable" not in message
    if name == "y0":
        assert "y0 must be four real numbers" in message
    else:
        assert f"{name} must be {kind}" in message, message


def test_an_unknown_variable_is_named_with_its_group_in_both_doors(exe, tmp_path):
    path = write(tmp_path, MODEL + "&analysis kind = 'linear', knd = 'linear' /\n" + OUTPUT)
    result = run(exe, path, tmp_path)
    assert result.returncode == 3
    assert "knd = 'linear' is not valid: unknown variable 'knd' (not one of &analysis" in \
        result.stderr
    with pytest.raises(sloshdyn.InputError, match="unknown variable 'knd'"):
        sloshdyn.read_namelist(path)
    path = write(tmp_path, TANK.replace("radius = 5", "radius = 'abc'") + OUTPUT)
    result = run(exe, path, tmp_path)
    assert result.returncode == 3
    assert "radius = 'abc' is not valid: radius must be a real number" in result.stderr
