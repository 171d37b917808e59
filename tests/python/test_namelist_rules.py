"""The same rules in every group and through both front doors (issue 22, item 9): a ground motion
is a record or harmonic motion, not both (as Python's GroundMotion says), and a stability chart's
box lies where &model and &excitation allow its parameters (the one check of model_from_arrays).
Each test failed on the main before the fix: the executable ran with exit code 0 and
read_namelist returned."""

import pytest

import sloshdyn
from conftest import EXAMPLES, run, write

MODEL = ("&model s1 = 1.5, mu1 = 0.5, kappa = 1.804897259, theta0 = 0.7853981633974483, "
         "gamma = 0.001 /\n")
TANK = ("&tank radius = 5.0, liquid_depth = 6.0, freeboard = 1.0, liquid_density = 1000, "
        "tank_mass = 5.0e4, "
        "support_frequency = 2.0, support_damping = 0.02 /\n")
RECORD = EXAMPLES / "records" / "synthetic_kt.AT2"


def refused_by_both_doors(exe, tmp_path, text, *names):
    """Exit code 3 (bad input) from the executable and InputError from read_namelist, each
    message naming every one of `names`; nothing written."""
    path = write(tmp_path, text + "&output directory = 'out' /\n")
    result = run(exe, path, tmp_path)
    assert result.returncode == 3, (result.returncode, result.stdout, result.stderr)
    for name in names:
        assert name in result.stderr, (name, result.stderr)
    assert not (tmp_path / "out").exists()
    with pytest.raises(sloshdyn.InputError) as error:
        sloshdyn.read_namelist(path)
    for name in names:
        assert name in str(error.value), (name, str(error.value))
    return str(error.value)


@pytest.mark.parametrize("harmonic, named", [
    ("peak_acceleration = 0.1", ["peak_acceleration"]),
    ("frequency = 0.3", ["frequency"]),
    ("peak_acceleration = 0.1, frequency = 0.3", ["peak_acceleration", "frequency"]),
])
def test_a_record_and_harmonic_motion_are_refused_together(exe, tmp_path, harmonic, named):
    """Python's GroundMotion refuses a record with peak_acceleration or frequency ("not both");
    the reader did not (it used the record and dropped the rest)."""
    with pytest.raises(sloshdyn.InputError, match="not both"):
        sloshdyn.GroundMotion(dt=0.01, acceleration=[0.0, 1.0], peak_acceleration=0.1)
    text = (TANK + f"&ground_motion record = '{RECORD}', {harmonic} /\n"
            "&analysis kind = 'seismic' /\n")
    message = refused_by_both_doors(exe, tmp_path, text, "&ground_motion", "record", *named)
    assert "not both" in message


def test_a_record_alone_and_harmonic_motion_alone_still_read(tmp_path):
    """The rule refuses only the mixture: each kind alone reads as before."""
    record = sloshdyn.read_namelist(write(tmp_path, TANK + f"&ground_motion record = '{RECORD}' /\n"
                                          "&analysis kind = 'seismic' /\n", "record.nml"))
    assert record.ground_motion.kind == "record"
    harmonic = sloshdyn.read_namelist(write(tmp_path, TANK + "&ground_motion "
                                            "peak_acceleration = 0.1, frequency = 0.3 /\n",
                                            "harmonic.nml"))
    assert harmonic.ground_motion.kind == "harmonic"


def excitation_refusal(tmp_path, A):
    """What &excitation says of the amplitude A (the rule the chart's box must follow)."""
    try:
        sloshdyn.read_namelist(write(tmp_path, MODEL + f"&excitation A = {A}, rho = 0.51 /\n",
                                     "excitation.nml"))
    except sloshdyn.InputError as error:
        return str(error)
    return None


@pytest.mark.parametrize("y_max", ["1e300", "1001"])
def test_a_chart_box_beyond_the_excitation_bounds_is_refused(exe, tmp_path, y_max):
    """&chart y = A, y_max = 1e300 ran and reported '0 steady states' at A = 5e299 although
    &excitation A is limited to [0, 1000]: the box is held to the same rule, and the message
    says the rule &excitation states (its upper bound)."""
    rule = excitation_refusal(tmp_path, y_max)
    assert rule is not None and "1000" in rule
    text = (MODEL + "&excitation A = 0.00075, rho = 0.51 /\n&analysis kind = 'stability_chart' /\n"
            f"&chart x_min = 0.49, x_max = 0.53, y_min = 0, y_max = {y_max}, n_x = 3, n_y = 2 /\n")
    message = refused_by_both_doors(exe, tmp_path, text, "&chart", "y_max", "A")
    assert rule.split(": ", 1)[1] in message


@pytest.mark.parametrize("axis, value, bound", [("gamma", "1e300", "y_max"),
                                                ("kappa", "0", "y_min")])
def test_a_chart_box_in_gamma_and_kappa_follows_the_model_rules(exe, tmp_path, axis, value,
                                                                bound):
    """The other axes follow &model's rules for their parameter (gamma at most 1000, kappa
    > 0): the message is the one &model gives for that value."""
    model = MODEL.replace("gamma = 0.001", f"gamma = {value}") if axis == "gamma" \
        else MODEL.replace("kappa = 1.804897259", f"kappa = {value}")
    with pytest.raises(sloshdyn.InputError) as error:
        sloshdyn.read_namelist(write(tmp_path, model + "&excitation A = 0.00075, rho = 0.51 /\n",
                                     "model.nml"))
    rule = str(error.value)
    assert rule.startswith("&model: " + axis)
    (tmp_path / "chart").mkdir()
    text = (MODEL + "&excitation A = 0.00075, rho = 0.51 /\n&analysis kind = 'stability_chart' /\n"
            f"&chart x_min = 0.49, x_max = 0.53, y = '{axis}', {bound} = {value}, "
            f"{'y_max = 2' if bound == 'y_min' else 'y_min = 0'}, n_x = 3, n_y = 2 /\n")
    message = refused_by_both_doors(exe, tmp_path / "chart", text, "&chart", bound, axis)
    assert rule.split(": ", 1)[1] in message


def test_the_example_chart_still_reads(tmp_path):
    """A box inside the bounds reads as before (the Fig 11-12 chart)."""
    inp = sloshdyn.read_namelist(EXAMPLES / "fig12_stability_chart.nml")
    assert inp.analysis == "stability_chart"


SIMULATE = "&excitation A = 0.001, rho = 0.5 /\n&analysis kind = 'simulate' /\n"


def spatial_model(planar):
    return MODEL if planar else MODEL.replace(" /", ", planar = .false. /")


@pytest.mark.parametrize("planar, values", [(False, 7), (False, 4), (False, 1),
                                            (True, 1), (True, 3), (True, 8)])
def test_a_y0_list_has_one_value_per_state_as_in_python(exe, tmp_path, planar, values):
    """Issue 44 item 4: `y0 = ` seven values for the spatial model was read with the eighth
    state 0, while Python's spatial.simulate refuses seven: now one rule, a list of as many
    values as the model has states (4 planar, 8 spatial), in both doors and in Python."""
    states = 4 if planar else 8
    simulate = sloshdyn.simulate if planar else sloshdyn.spatial.simulate
    p = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.8049, theta0=0.785, gamma=0.001, A=0.001,
                            rho=0.5)
    y0 = [0.1] + [0] * (values - 1)     # planar with 8: the out-of-plane states 0
    with pytest.raises(sloshdyn.InputError, match="y0"):
        simulate(p, 1.0, y0)
    text = (spatial_model(planar) + SIMULATE +
            f"&simulation t_end = 1, y0 = {', '.join(map(str, y0))} /\n")
    message = refused_by_both_doors(exe, tmp_path, text, "&simulation", "y0",
                                    f"{values} value", f"{states} states")
    assert "y0(i) = value" in message


@pytest.mark.parametrize("planar, y0", [(True, "0.1, 0, 0.2, 0"), (True, "4*0.1"),
                                        (True, "y0(2) = 0.5"),
                                        (False, "0.1, 0, 0.2, 0, 0.1, 0.05, 0, 0"),
                                        (False, "2*0.1, 6*0"), (False, "y0(5) = 0.1")])
def test_a_y0_of_every_state_or_of_single_entries_reads_as_python_takes_it(exe, tmp_path,
                                                                             planar, y0):
    """What the rule keeps: a whole list (repeat counts r*v count r) or single entries
    y0(i) = v; the run gives the time history Python gives from the state read."""
    assignment = y0 if y0.startswith("y0(") else f"y0 = {y0}"
    text = (spatial_model(planar) + SIMULATE +
            f"&simulation t_end = 1, n_out = 3, {assignment} /\n&output directory = 'out' /\n")
    path = write(tmp_path, text)
    inp = sloshdyn.read_namelist(path)
    assert len(inp.simulation["y0"]) == (4 if planar else 8)
    simulate = sloshdyn.simulate if planar else sloshdyn.spatial.simulate
    simulate(inp.params, 1.0, inp.simulation["y0"], n_out=3)   # Python takes the state read
    result = run(exe, path, tmp_path)
    assert result.returncode == 0, result.stderr
