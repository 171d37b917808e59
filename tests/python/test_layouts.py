"""The core publishes the layout of every flat array that crosses the bridge (its field names)
and the codes of every enumerated option; Python builds and decodes the arrays by name
(issue 21). These tests walk every layout and code list the core gives and check Python's
classes and the namelist reader's results against them; the expected values of the namelist
tests are the text of the files they write (an independent source)."""

import dataclasses
import re

import numpy as np
import pytest

import sloshdyn
from conftest import ROOT
from sloshdyn import _core, _tables, charts
from sloshdyn.options import Chart, Continuation, Integration, Lyapunov, Shooting, Steady
from sloshdyn.parameters import Parameters, TankPendulum
from sloshdyn.simulation import METHODS
from sloshdyn.tank import Tank

_model, _seismic, _input = (_core.sloshdyn_bridge_model, _core.sloshdyn_bridge_seismic,
                           _core.sloshdyn_bridge_input)

MODEL = ("&model s1 = 1.5, mu1 = 0.5, kappa = 1.804897259, theta0 = 0.7853981633974483, "
         "gamma = 0.001 /\n&excitation A = 0.00075, rho = 0.51 /\n")
#: a range of each chart axis around the paper's Fig 12 point
AXIS_RANGE = {"rho": (0.49, 0.53), "A": (0.0, 0.002), "gamma": (0.0, 0.01),
              "kappa": (1.7, 1.9)}


def _read(tmp_path, text):
    path = tmp_path / "input.nml"
    path.write_text(text)
    return sloshdyn.read_namelist(path)


def test_every_layout_names_distinct_fields():
    for name in _tables.layouts():
        fields = _tables.layout(name)
        assert fields and all(fields), name
        assert len(set(fields)) == len(fields), name


def test_an_unknown_layout_or_code_list_is_an_error():
    with pytest.raises(sloshdyn.SloshdynError, match="no names for 'layout:nothing'"):
        _tables.layout("nothing")
    with pytest.raises(sloshdyn.SloshdynError, match="no names for 'nothing'"):
        _tables.names("nothing")


def test_the_core_arrays_have_the_sizes_of_their_layouts(tmp_path):
    """Every array the core returns has as many entries as its layout has names."""
    arrays = {name: _core.sloshdyn_bridge_tables.layout_defaults(name, len(_tables.layout(name)))[0]
              for name in ("model", "model_integers", "integration", "steady", "response",
                           "lyapunov", "shooting", "tank", "chart")}
    path = tmp_path / "input.nml"
    path.write_text(MODEL + "&analysis kind = 'stability_chart' /\n")
    (rpar, ipar, _, analysis, _, _, tank, _, ground, _, seismic, integration, steady, response,
     lyapunov, simulation, sweep, response_range, chart, chart_range, study,
     *rest) = _input.read_input(str(path))
    for name, array in (("model", rpar), ("model_integers", ipar), ("tank", tank),
                        ("integration", integration), ("steady", steady),
                        ("response", response), ("lyapunov", lyapunov), ("chart", chart)):
        assert len(array) == len(arrays[name]), name
    arrays.update(analysis=analysis, ground=ground, seismic=seismic, simulation=simulation,
                  sweep=sweep, response_range=response_range, chart_range=chart_range,
                  study=study, design=rest[-4], tank_structure=rest[-3])
    # (..., has_design, design, tank_structure, status, message)
    pendulum, status, _ = _model.tank_pendulum(1.0, 1.0, 1000.0, 0.0)
    groups, status, _ = _model.dimensionless_groups(np.ones(len(_tables.layout("physical"))))
    *_, routh, _, _ = _model.equilibria(*Parameters(s1=1.5, mu1=0.5, kappa=2.0,
                                                     theta0=0.5).array(), 4)
    arrays.update(pendulum=pendulum, groups=groups, routh=routh)
    for name, array in arrays.items():
        assert len(array) == len(_tables.layout(name)), name
    # (the others: test_bridge_result_arrays_have_the_sizes_of_their_layouts_and_tables;
    # physical is dimensionless_groups' input, refused at another size below)
    assert set(_tables.layouts()) - set(arrays) <= {"physical", "continuation", "orbit_info",
                                                    "modal_scalars", "chart_sizes", "spatial", "natural_frequencies",
                                                    "swirl_orbit_info"}


def test_a_layout_without_defaults_or_of_another_size_is_refused():
    with pytest.raises(sloshdyn.SloshdynError, match="no defaults for 'pendulum'"):
        _tables.defaults("pendulum")
    _, status, message = _core.sloshdyn_bridge_tables.layout_defaults("steady", 3)
    assert status != 0 and "has 7 fields, not 3" in _tables._text(message)


def test_an_input_array_of_another_size_is_refused():
    """f2py sizes the bridge's arrays by the layouts: one entry more or less does not pass."""
    for n in (len(_tables.layout("physical")) - 1, len(_tables.layout("physical")) + 1):
        with pytest.raises(ValueError):
            _model.dimensionless_groups(np.ones(n))


#: every settings class and the layout it is made from
SETTINGS = [(Integration, "integration"), (Steady, "steady"), (Continuation, "response"),
            (Lyapunov, "lyapunov"), (Shooting, "shooting"), (Chart, "chart")]


@pytest.mark.parametrize("cls, layout", SETTINGS + [(Tank, "tank"), (TankPendulum, "pendulum")])
def test_settings_classes_have_the_fields_of_their_layouts(cls, layout):
    assert tuple(f.name for f in dataclasses.fields(cls)) == _tables.layout(layout)


def test_every_settings_class_is_made_from_a_layout():
    """Every public settings class (a dataclass built from its defaults alone) is one of
    SETTINGS, so none keeps its own copy of a layout's fields."""
    public = {c for c in vars(sloshdyn).values() if isinstance(c, type)
              and dataclasses.is_dataclass(c) and all(
                  f.default is not dataclasses.MISSING for f in dataclasses.fields(c))}
    assert public == {cls for cls, _ in SETTINGS}
    assert all(cls.layout == layout for cls, layout in SETTINGS)


@pytest.mark.parametrize("cls, layout", SETTINGS)
def test_settings_classes_have_the_cores_kinds_defaults_and_docs(cls, layout):
    """The type, default and help of every field are the core's, and the array of the defaults
    is the core's array of its option type's defaults, entry for entry."""
    kinds, docs = _tables.kinds(layout), _tables.docs(layout)
    types = {"real": "float", "integer": "int", "flag": "bool"}
    for f in dataclasses.fields(cls):
        assert f.type == types.get(kinds[f.name], "str"), f.name
        assert f.kw_only, f.name
        if docs[f.name]:
            assert docs[f.name] in " ".join(cls.__doc__.split()), f.name
    assert cls.__dataclass_params__.frozen
    core, status, _ = _core.sloshdyn_bridge_tables.layout_defaults(layout, len(kinds))
    assert status == 0 and cls().array().tolist() == core.tolist()
    assert cls.from_array(core) == cls()


def test_a_settings_field_of_a_code_list_takes_its_names_only():
    with pytest.raises(sloshdyn.InputError, match="method = 'rk4' is not valid: it must be one "
                       "of 'rk45', 'dop853', 'vern9', 'auto'"):
        Integration(method="rk4")
    with pytest.raises(TypeError):
        Integration(1e-6)           # keyword-only


def test_tank_has_the_cores_defaults():
    tank = _tables.defaults("tank")
    for f in dataclasses.fields(Tank):
        if f.default is not dataclasses.MISSING:
            codes = {"shape": "tank_shapes", "roof_contact": "roof_contacts"}
            default = (_tables.code(codes[f.name], f.default) if f.name in codes
                       else f.default)
            assert default == tank[f.name], f.name
    model = Parameters(s1=1.5, mu1=0.5, kappa=2.0, theta0=0.5)
    defaults = {**_tables.defaults("model"), **_tables.defaults("model_integers")}
    for name in ("beta", "gamma", "delta", "zeta", "n", "p"):
        assert getattr(model, name) == defaults[name], name


def test_parameters_carry_the_model_layouts():
    params = Parameters(s1=1.5, mu1=0.5, kappa=2.0, theta0=0.5, beta=3.0, gamma=0.01,
                        delta=0.2, n=4, p=3, zeta=0.01, A=0.001, rho=0.5)
    rpar, ipar = params.array()
    assert dict(zip(_tables.layout("model"), rpar)) == {
        name: getattr(params, name) for name in _tables.layout("model")}
    assert list(ipar) == [getattr(params, name) for name in _tables.layout("model_integers")]
    assert {f.name for f in dataclasses.fields(Parameters)} == (
        set(_tables.layout("model")) | set(_tables.layout("model_integers")))
    assert Parameters.from_array(rpar, ipar) == params


def test_every_code_list_of_the_core_is_named_and_used_by_python():
    for list_name in _tables.code_lists():
        items, _ = _tables.names(list_name)
        assert items and all(items) and len(set(items)) == len(items), list_name
    assert charts.AXES == _tables.names("chart_axes")[0]
    assert "kappa" in charts.AXES
    assert charts.MODELS == _tables.names("chart_models")[0]
    assert set(METHODS) == set(_tables.names("methods")[0])
    assert {name: code for code, name in _tables.codes("methods").items()} == METHODS


def _chart_nml(model, x, y):
    return (MODEL + "&analysis kind = 'stability_chart' /\n"
            f"&chart model = '{model}', x = '{x}', y = '{y}', x_min = {AXIS_RANGE[x][0]}, "
            f"x_max = {AXIS_RANGE[x][1]}, y_min = {AXIS_RANGE[y][0]}, "
            f"y_max = {AXIS_RANGE[y][1]}, n_x = 5, n_y = 6 /\n")


def test_chart_kappa_reads_through_python(tmp_path):
    """The defect of issue 21: a valid file with &chart y = 'kappa' made read_namelist raise
    IndexError (Python kept its own list of axes without kappa)."""
    chart = _read(tmp_path, _chart_nml("slow_flow_3:1", "rho", "kappa")).chart_range
    assert chart["x"] == "rho" and chart["y"] == "kappa"
    assert chart["y_range"] == AXIS_RANGE["kappa"]


@pytest.mark.parametrize("x", ["rho", "A"])
@pytest.mark.parametrize("y", sorted(AXIS_RANGE))
def test_every_chart_axis_reads_through_python(tmp_path, x, y):
    assert set(AXIS_RANGE) == set(_tables.names("chart_axes")[0])
    if x == y:
        return
    inp = _read(tmp_path, _chart_nml("slow_flow_3:1", x, y))
    chart = inp.chart_range
    assert (chart["x"], chart["y"]) == (x, y)
    assert (chart["x_range"], chart["y_range"]) == (AXIS_RANGE[x], AXIS_RANGE[y])
    assert inp.chart == Chart(n_x=5, n_y=6)


@pytest.mark.parametrize("model", _tables.names("chart_models")[0])
def test_every_chart_model_reads_through_python(tmp_path, model):
    assert _read(tmp_path, _chart_nml(model, "rho", "A")).chart_range["model"] == model


@pytest.mark.parametrize("method", _tables.names("methods")[0])
def test_every_method_reads_through_python(tmp_path, method):
    inp = _read(tmp_path, MODEL + f"&integration method = '{method}' /\n")
    assert inp.integration == Integration(method=method)


@pytest.mark.parametrize("direction", _tables.names("directions")[0])
@pytest.mark.parametrize("parameter", ["rho", "A"])
def test_every_sweep_direction_and_parameter_reads_through_python(tmp_path, direction,
                                                                  parameter):
    inp = _read(tmp_path, MODEL + "&analysis kind = 'sweep' /\n"
                f"&sweep parameter = '{parameter}', start = 0.5, stop = 0.52, n_points = 3, "
                f"direction = '{direction}', start_from = 'y0', threads = 2 /\n")
    assert inp.sweep == {"parameter": parameter, "start": 0.5, "stop": 0.52, "n_points": 3,
                         "direction": direction, "start_from": "y0", "threads": 2}


def test_the_sweep_in_frequency_reads_through_python(tmp_path):
    from conftest import EXAMPLES
    assert "frequency" in _tables.names("excitation_parameters")[0]
    inp = sloshdyn.read_namelist(EXAMPLES / "tank_frequency_sweep.nml")
    assert inp.sweep["parameter"] == "frequency" and inp.ground_motion.kind == "harmonic"


@pytest.mark.parametrize("resonance", _tables.names("resonances")[0])
@pytest.mark.parametrize("parameter", ["rho", "A"])
def test_every_resonance_reads_through_python(tmp_path, resonance, parameter):
    inp = _read(tmp_path, MODEL + f"&response resonance = '{resonance}', "
                f"parameter = '{parameter}', start = 0.49, stop = 0.53, n_scan = 7, "
                "n_amplitudes = 5, n_phases = 3, amplitude_min = 1e-4, amplitude_max = 2.0, "
                "ds = 0.002, ds_min = 1e-9, ds_max = 0.02, x_scale = 2.0, max_points = 900 /\n")
    assert inp.response_range == {"resonance": resonance, "parameter": parameter,
                                  "start": 0.49, "stop": 0.53, "switch_at": 0, "curve_at": 0,
                                  "curve_start": 0.0, "curve_stop": 0.0}
    assert inp.response == Continuation(n_scan=7, n_amplitudes=5, n_phases=3,
                                        amplitude_min=1e-4, amplitude_max=2.0, ds=0.002,
                                        ds_min=1e-9, ds_max=0.02, x_scale=2.0, max_points=900)


@pytest.mark.parametrize("continuation", _tables.names("continuations")[0])
@pytest.mark.parametrize("worker_kind", _tables.names("worker_kinds")[0])
def test_every_study_code_reads_through_python(tmp_path, continuation, worker_kind):
    inp = _read(tmp_path, MODEL + "&study kind = 'response_map', store = 'map.zarr', "
                "frequency_start = 0.505, frequency_stop = 0.52, n_frequencies = 3, "
                "amplitude_start = 0.0005, amplitude_stop = 0.00075, n_amplitudes = 2, "
                f"workers = 2, worker_kind = '{worker_kind}', continuation = '{continuation}' /\n")
    assert inp.study["worker_kind"] == worker_kind
    assert inp.study["continuation"] == continuation
    assert (inp.study["frequency_start"], inp.study["n_amplitudes"]) == (0.505, 2)


def test_every_study_kind_reads_through_python(tmp_path):
    assert set(_tables.names("study_kinds")[0]) == {"response_map", "basins", "fragility"}
    basins = _read(tmp_path, MODEL + "&study kind = 'basins', store = 'b.zarr', x1_start = -0.5, "
                   "x1_stop = 0.5, dx1_start = -0.2, dx1_stop = 0.2, n_grid = 7, tol = 2e-3 /\n")
    assert {k: basins.study[k] for k in ("kind", "x1_start", "x1_stop", "dx1_start",
                                         "dx1_stop", "n_grid", "tol")} == {
        "kind": "basins", "x1_start": -0.5, "x1_stop": 0.5, "dx1_start": -0.2,
        "dx1_stop": 0.2, "n_grid": 7, "tol": 2e-3}
    from conftest import EXAMPLES
    tank = (EXAMPLES / "tank_harmonic.nml").read_text().split("&analysis")[0]
    fragility = _read(tmp_path, tank + "&study kind = 'fragility', store = 'f.zarr', "
                      "records = 'rec/*.csv', intensity_start = 1.0, intensity_stop = 4.0, "
                      "n_intensities = 4, spectral_damping = 0.02 /\n")
    assert {k: fragility.study[k] for k in ("kind", "records", "intensity_start",
                                            "intensity_stop", "n_intensities",
                                            "spectral_damping")} == {
        "kind": "fragility", "records": "rec/*.csv", "intensity_start": 1.0,
        "intensity_stop": 4.0, "n_intensities": 4, "spectral_damping": 0.02}


def test_every_analysis_is_named_by_the_core(tmp_path):
    from conftest import EXAMPLES
    analyses = _tables.names("analyses")[0]
    read = {sloshdyn.read_namelist(path).analysis for path in EXAMPLES.glob("*.nml")}
    assert read <= set(analyses) and len(read) >= len(analyses) - 1


def test_settings_groups_read_through_python_by_name(tmp_path):
    """Every &integration, &steady, &lyapunov, &simulation and &seismic variable, each with a
    value of its own, comes back under its own name."""
    inp = _read(tmp_path, MODEL + (
        "&integration rtol = 1.5e-7, atol = 2.5e-9, h_initial = 0.03, h_max = 0.4, "
        "h_min = 5e-12, max_steps = 123456, method = 'vern9' /\n"
        "&steady transient_periods = 11, settle_tol = 2e-6, max_transient_periods = 333, "
        "window_periods = 17, samples_per_period = 41, periodic_tol = 3e-5, shooting = .false. /\n"
        "&lyapunov transient_periods = 21, n_periods = 303, renormalise_every = 3, "
        "spectrum = .true., average = 'weighted' /\n"
        "&simulation t_end = 12.5, n_out = 77, y0 = 0.1, 0.2, 0.3, 0.4 /\n"))
    assert inp.integration == Integration(rtol=1.5e-7, atol=2.5e-9, h_initial=0.03, h_max=0.4,
                                          h_min=5e-12, max_steps=123456, method="vern9")
    assert inp.steady == Steady(transient_periods=11.0, settle_tol=2e-6,
                                max_transient_periods=333.0, window_periods=17,
                                samples_per_period=41, periodic_tol=3e-5, shooting=False)
    assert inp.lyapunov == Lyapunov(transient_periods=21, n_periods=303, renormalise_every=3,
                                    spectrum=True, average="weighted")
    assert inp.simulation == {"t_end": 12.5, "n_out": 77, "y0": [0.1, 0.2, 0.3, 0.4]}
    assert inp.steady.array().tolist() == [11, 2e-6, 333, 17, 41, 3e-5, 0]


def test_an_unknown_lyapunov_average_is_named(tmp_path):
    with pytest.raises(sloshdyn.InputError, match="average = 'mean' is not known; allowed: plain"):
        _read(tmp_path, MODEL + "&lyapunov average = 'mean' /\n")


def test_a_tank_and_its_ground_motion_read_through_python_by_name(tmp_path):
    from conftest import EXAMPLES
    inp = sloshdyn.read_namelist(EXAMPLES / "tank_seismic.nml")
    assert Tank.from_array(inp.tank.array()) == inp.tank
    ground, samples = inp.ground_motion._arrays()
    again = sloshdyn.GroundMotion._from_arrays(ground, samples)
    assert again.kind == inp.ground_motion.kind == "record"
    assert again.dt == inp.ground_motion.dt and np.array_equal(again.acceleration, samples)


def test_result_tables_have_the_columns_the_core_names():
    """The bridge's result arrays are sized by the core's tables (a build that kept an old size
    in f2py's wrapper would give another number of rows, or corrupt memory)."""
    tank = Tank(radius=5.0, liquid_depth=6.0, freeboard=1.0, liquid_density=1000.0,
                tank_mass=5.0e4, support_frequency=2.0, support_damping=0.02)
    ground, samples = sloshdyn.GroundMotion.harmonic(0.05, 0.3)._arrays()
    table, peaks, instants, status, _ = _seismic.seismic_response(
        tank.array(), ground, samples, 2.0, 3, Integration().array())
    assert status == 0
    # the core's arrays carry the impact model's rows last ('..._impact' layouts)
    assert table.shape == (len(_tables.columns("seismic_impact")), 3)
    assert peaks.shape == (len(_tables.columns("seismic_peaks_impact")),)
    assert instants.shape == (len(_tables.columns("seismic_peak_instants")), 3)
    assert _tables.columns("seismic_impact")[:-1] == _tables.columns("seismic")
    assert _tables.columns("seismic_peaks_impact")[:-3] == _tables.columns("seismic_peaks")
    row, *_ = _seismic.tank_properties(tank.array())
    assert row.shape == (len(_tables.columns("tank_si")),)


def test_seismic_results_are_named_by_the_cores_tables():
    """SeismicResponse, its peaks, the tank's properties and the design-code table take their
    names from the core's tables, in the core's order."""
    tank = Tank(radius=5.0, liquid_depth=6.0, freeboard=1.0, liquid_density=1000.0,
                tank_mass=5.0e4, support_frequency=2.0, support_damping=0.02)
    ground = sloshdyn.GroundMotion.harmonic(0.05, 0.3)
    response = sloshdyn.seismic_response(tank, ground, t_end=2.0, n_out=3)
    names = [c.split(" [")[0] for c in _tables.columns("seismic")]
    assert response.columns == names
    for name, row in zip(names, response.table):
        assert np.array_equal(getattr(response, name), row, equal_nan=True), name
    peaks = [c.split(" [")[0] for c in _tables.columns("seismic_peaks")]
    assert list(response.peak_table) == peaks
    assert set(response.peaks) == {p[len("peak_"):] for p in peaks if p.startswith("peak_")}
    assert list(tank.properties) == [c.split(" [")[0] for c in _tables.columns("tank_si")]
    codes = tank.design_codes(ground)
    assert codes.sources == list(_tables.names("source")[0])[:4]   # modal sums: modes > 1
    assert codes.columns == [c.split(" [")[0] for c in _tables.columns("design_codes")[1:]]
    assert codes.table.shape == (len(codes.columns), len(codes.sources))


def test_bridge_result_arrays_have_the_sizes_of_their_layouts_and_tables():
    """The bridge arrays that Python now reads by name (they were read by position): the
    studies' orbit rows, the modal scalars, the chart's table sizes, a branch of slow-flow
    cycles and its special points have exactly as many rows as the core's names."""
    params = Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=0.7853981633974483,
                        gamma=0.001, A=0.00075, rho=0.51)
    _, _, orbit, _, _, _, status, _ = _core.sloshdyn_bridge_studies.steady_path(
        *params.array(), np.array([0.51]), np.array([0.00075]), np.zeros((4, 1), order="F"), 0,
        Integration().array(), Steady(transient_periods=20, settle_tol=0,
                                      window_periods=16).array(), 1)
    assert status == 0 and orbit.shape == (len(_tables.columns("study_orbit")), 1)
    scalars, *_, status, _ = _core.sloshdyn_bridge_asymptotics.modal_expansion(*params.array())
    assert status == 0 and len(scalars) == len(_tables.layout("modal_scalars"))
    modes = sloshdyn.linear_modes(params)
    assert _tables.unpack("modal_scalars", scalars)["omega1"] == pytest.approx(modes.omega1)
    omegas, *_, status, _ = _model.natural_frequencies(*params.array())
    assert status == 0 and len(omegas) == len(_tables.layout("natural_frequencies"))
    # LinearModes takes the layout's fields by name, in the layout's order
    assert [f.name for f in dataclasses.fields(sloshdyn.LinearModes)][:len(omegas)] == \
        list(_tables.layout("natural_frequencies"))
    chart = Chart(n_x=3, n_y=2)
    *_, sizes, _, _, status, _ = _core.sloshdyn_bridge_charts.stability_chart(
        *params.array(), chart.array(), _tables.pack("chart_range", {
            "model": 1, "x": _tables.code("chart_axes", "rho"),
            "y": _tables.code("chart_axes", "A"), "x_min": 0.49, "x_max": 0.53, "y_min": 0.0,
            "y_max": 0.002, "threads": 1}), Continuation().array(), 20000, 100, 50, 6)
    assert status == 0 and len(sizes) == len(_tables.layout("chart_sizes"))
    assert _tables.unpack("chart_sizes", sizes)["cells"] == 6          # n_x n_y
    points, multipliers, amplitudes, *_, special, _, _, _, _ = (
        _core.sloshdyn_bridge_research.slow_flow_cycle_branch(
            *params.array(), 1, np.zeros(4), 1.0, 0.5, 0.52,
            np.zeros(len(_tables.layout("continuation"))), Integration().array(), 2, 3))
    assert (len(points) + len(multipliers) + len(amplitudes)
            == len(_tables.columns("cycle_branch")))
    assert len(special) == len(_tables.columns("cycle_special_points"))


def test_a_new_field_of_a_layout_reaches_its_settings_class(monkeypatch):
    """A settings class follows its layout with no Python edit: a layout with one field more
    (as the core would give it) makes a class with that field, its kind, default and doc."""
    from sloshdyn._settings import settings
    fields = _tables.layout("shooting") + ("damping",)
    core = {"layout:shooting": ",".join(fields), "kinds:shooting": "real,integer,real",
            "docs:shooting": "tolerance\niterations\nNewton's damping factor"}
    real = _tables._names_text
    monkeypatch.setattr(_tables, "_names_text",
                        lambda name: (core[name], 1) if name in core else real(name))
    monkeypatch.setattr(_tables, "defaults", lambda name: dict(zip(fields, (1e-10, 30, 0.5))))

    @settings("shooting")
    class Scratch:
        """A scratch copy of Shooting."""
    assert [f.name for f in dataclasses.fields(Scratch)] == list(fields)
    assert Scratch().damping == 0.5 and "Newton's damping factor" in Scratch.__doc__
    assert Scratch(damping=0.25).array().tolist() == [1e-10, 30, 0.25]


#: every code list the core names, by its names (the test below looks for copies of these)
CODE_NAMES = {name: set(_tables.names(name)[0]) for name in _tables.code_lists()}


def _hand_lists(path):
    """(line, code list) of every literal list of strings in `path` that is used as the allowed
    values of an option (_checks.choice(name, value, <list>), value in / not in <list>) and is
    a copy of a core code list (its names, or all but one of them)."""
    import ast
    found = []
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        choices = []
        if isinstance(node, ast.Call) and getattr(node.func, "attr", "") == "choice":
            choices = node.args[2:3]
        elif isinstance(node, ast.Compare) and isinstance(node.ops[0], (ast.In, ast.NotIn)):
            choices = node.comparators[:1]
        for literal in choices:
            if isinstance(literal, (ast.Tuple, ast.List, ast.Set)) and all(
                    isinstance(e, ast.Constant) and isinstance(e.value, str)
                    for e in literal.elts):
                values = {e.value for e in literal.elts}
                found += [(node.lineno, name) for name, names in CODE_NAMES.items()
                          if len(values) >= 2 and values <= names
                          and len(values) >= len(names) - 1]
    return found


def test_python_keeps_no_copy_of_a_code_list():
    """An option whose values are the names of a core code list takes them from the core
    (the issue-21 defect: a hand copy of the chart axes without kappa)."""
    import pathlib
    root = pathlib.Path(sloshdyn.__file__).parent
    copies = {f"{path.relative_to(root)}:{line} ({name})": None
              for path in sorted(root.rglob("*.py")) for line, name in _hand_lists(path)}
    assert list(copies) == []


def test_the_hand_list_finder_finds_a_copy(tmp_path):
    source = tmp_path / "copy.py"
    source.write_text('_checks.choice("continuation", c, ("none", "up", "down", "both"))\n'
                      'if kind not in ("processes", "threads"):\n    pass\n'
                      'if (x, y) != ("rho", "A"):\n    pass\n')
    assert _hand_lists(source) == [(1, "continuations"), (2, "worker_kinds")]


def test_enumerated_options_name_the_value_and_the_cores_codes(tmp_path):
    """Stringly options are checked against the core's code lists, naming the value and every
    allowed code."""
    params = Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=0.7853981633974483,
                        A=0.00075)
    allowed = ", ".join(repr(c) for c in _tables.names("continuations")[0])
    with pytest.raises(sloshdyn.InputError, match=f"continuation = 'sideways' is not valid: it "
                       f"must be one of {allowed}"):
        sloshdyn.response_map(params, [0.5], [0.001], tmp_path / "y.zarr",
                              continuation="sideways")
    with pytest.raises(sloshdyn.InputError, match="resonance = '1:3' is not valid: it must be "
                       "one of 'none', '3:1'"):
        sloshdyn.frequency_response(params, (0.49, 0.53), resonance="1:3")
    with pytest.raises(sloshdyn.InputError, match="direction = 'sideways' is not valid: it must "
                       "be one of 'up', 'down', 'both'"):
        sloshdyn.sweep_values(0.5, 0.52, 3, "sideways")
    with pytest.raises(sloshdyn.InputError, match="worker_kind = 'fibres' is not valid: it "
                       "must be one of 'processes', 'threads'"):
        sloshdyn.response_map(params, [0.5], [0.001], tmp_path / "z.zarr", worker_kind="fibres")


def test_every_continuation_takes_the_same_settings_object():
    """Every continuation call takes its steps, limits and Newton's tolerances from one
    keyword-only Continuation (the core's 'response' layout), whose continuation fields are
    the core's 'continuation' layout's (no loose x_tol, f_tol, max_iter)."""
    import inspect
    for function in (sloshdyn.frequency_response, sloshdyn.periodic_response,
                     sloshdyn.slow_flow_cycles, sloshdyn.stability_chart):
        parameters = inspect.signature(function).parameters
        assert parameters["continuation"].kind is inspect.Parameter.KEYWORD_ONLY
        assert isinstance(parameters["continuation"].default, Continuation), function
        assert not {"ds", "x_tol", "f_tol", "max_iter", "max_points"} & set(parameters)
    assert set(_tables.layout("continuation")) - {"direction"} <= set(_tables.layout("response"))
    cycles = inspect.signature(sloshdyn.slow_flow_cycles).parameters["continuation"].default
    assert (cycles.x_tol, cycles.f_tol, cycles.max_iter) == (1e-10, 1e-9, 20)


def test_response_reads_newtons_settings(tmp_path):
    """&response's x_tol, f_tol, max_iter (the example of a new namelist variable: layout,
    reader, documentation only) reach Continuation by name, and their rules are the core's
    (checked when the continuation runs, as ds and the other steps are)."""
    inp = _read(tmp_path, MODEL + "&response start = 0.49, stop = 0.53, x_tol = 1e-9, "
                "f_tol = 2e-10, max_iter = 7 /\n")
    assert (inp.response.x_tol, inp.response.f_tol, inp.response.max_iter) == (1e-9, 2e-10, 7)
    assert inp.response == Continuation(x_tol=1e-9, f_tol=2e-10, max_iter=7)
    with pytest.raises(sloshdyn.InputError, match="max_iter = 0 is out of range: it must be "
                       ">= 1"):
        sloshdyn.frequency_response(inp.params, (0.49, 0.53),
                                    continuation=Continuation(max_iter=0))


#: bridge arrays still read by number: the spatial model's two settings (azimuth, ellipticity),
#: whose bridge another branch is changing (issue 26); to be named when it lands
NUMBERED_ELSEWHERE = {("sloshdyn_bridge_spatial.f90", "spatial")}


def test_the_bridge_reads_and_fills_layout_arrays_by_field_name():
    """DESIGN.md: no literal index in the bridge. Every array of the bridge dimensioned by a
    layout's size (NAME_SIZE) is reached through field_index('layout', 'field') (the layout's
    own names), never as array(3) (tank_pendulum, dimensionless_groups and natural_frequencies
    unpacked by position before); and every field_index names a field its layout has."""
    numbered, unknown = [], []
    for path in sorted((ROOT / "fortran" / "bridge").glob("*.f90")):
        text = path.read_text()
        arrays = {m.group(1) for decl in re.findall(r"::([^!\n]*)", text)
                  for m in re.finditer(r"(\w+)\(\s*[A-Z_]+_SIZE\s*\)", decl)}
        for name in sorted(arrays):
            if (path.name, name) not in NUMBERED_ELSEWHERE and re.search(
                    rf"\b{name}\(\s*\d+\s*\)", text):
                numbered.append(f"{path.name}: {name}")
        for layout, field in re.findall(r"field_index\('(\w+)', '(\w+)'\)", text):
            if field not in _tables.layout(layout):
                unknown.append(f"{path.name}: {layout}.{field}")
    assert numbered == [] and unknown == []
    uses = sum(text.count("field_index(") for text in
               (p.read_text() for p in (ROOT / "fortran" / "bridge").glob("*.f90")))
    assert uses >= 6 + 16 + 4           # pendulum, physical + groups, natural_frequencies
