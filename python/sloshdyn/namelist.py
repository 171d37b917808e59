"""The namelist input file, read by the Fortran reader of the executable through the bridge:
the groups, variables, defaults, rules and messages are the same for both front doors by
construction (docs/namelist.md). `read_namelist` gives every group as its settings object; it
stands above the analyses' value types (docs/architecture.md, "Python layers")."""

from __future__ import annotations

from dataclasses import dataclass, field

from . import _input, _tables
from ._settings import decode_all
from .ground import GroundMotion
from .options import Chart, Continuation, Design, Integration, Lyapunov, Steady
from .parameters import Parameters
from .structure import TankStructure
from .tank import Tank


@dataclass(frozen=True)
class Input:
    """A validated namelist input file: every settings group as its settings object (defaults
    where the file has no such group), the other groups as dicts of their variables."""

    params: Parameters
    analysis: str = "linear"
    sigma1: float = 0.0
    kappa_min: float = 0.0
    kappa_max: float | None = None
    directory: str = "sloshdyn_output"
    tank: object = None            #: sloshdyn.Tank (from &tank), or None (&model)
    ground_motion: object = None   #: sloshdyn.GroundMotion (from &ground_motion, scaled), or None
    seismic: dict = field(default_factory=dict)       #: &seismic: t_end [s], n_out (0: default)
    chart: object = None          #: &chart's settings: sloshdyn.Chart
    chart_range: dict = field(default_factory=dict)   #: &chart's model, x, y, x_range,
                                                      #: y_range and threads (stability_chart's
                                                      #: arguments)
    integration: object = None    #: &integration: sloshdyn.Integration
    simulation: dict = field(default_factory=dict)    #: &simulation: t_end, n_out, y0
    steady: object = None         #: &steady: sloshdyn.Steady
    sweep: dict = field(default_factory=dict)         #: &sweep: parameter, start, stop, ...
    response: object = None       #: &response's settings: sloshdyn.Continuation
    response_range: dict = field(default_factory=dict)   #: &response's resonance, parameter,
                                                         #: start, stop
    lyapunov: object = None       #: &lyapunov: sloshdyn.Lyapunov
    study: dict = field(default_factory=dict)         #: &study (empty if none): kind, store, ...
    planar: bool = True           #: &model or &tank planar (False: the spatial model, issue 26)
    spatial: dict = field(default_factory=lambda: {"azimuth": 0.0, "ellipticity": 0.0})
    #: &ground_motion's azimuth [rad] and ellipticity (sloshdyn.spatial.seismic_response_2d)
    ground_motion_y: object = None  #: &ground_motion's record_y (scaled by the first's factor)
    design: object = None         #: &design: sloshdyn.design.Design, or None (no &design)
    tank_structure: object = None  #: &tank_structure: sloshdyn.TankStructure, or None


def read_namelist(path) -> Input:
    """Read and validate a namelist input file with the executable's reader (same rules, defaults
    and messages)."""
    a = _input.read_arrays(path)
    tank = Tank.from_array(a.tank) if a.has_tank else None
    ground_motion = ground_motion_y = None
    if a.has_ground:
        ground_motion = GroundMotion._from_arrays(a.ground,
                                                  _input.record_samples(path, 1, a.n_samples))
    if a.has_ground_y:
        ground_motion_y = GroundMotion._from_arrays(a.ground_y,
                                                    _input.record_samples(path, 2, a.n_samples_y))
    sweep = decode_all("sweep", a.sweep)
    simulation = decode_all("simulation", a.simulation)
    chart_range = decode_all("chart_range", a.chart_range)
    return Input(
        params=Parameters.from_array(a.rpar, a.ipar),
        analysis=_tables.codes("analyses")[int(a.analysis)],
        **decode_all("analysis", a.values),
        directory=_tables._text(a.directory), tank=tank, ground_motion=ground_motion,
        seismic=decode_all("seismic", a.seismic),
        chart=Chart.from_array(a.chart),
        chart_range={"model": chart_range["model"], "x": chart_range["x"], "y": chart_range["y"],
                     "x_range": (chart_range["x_min"], chart_range["x_max"]),
                     "y_range": (chart_range["y_min"], chart_range["y_max"]),
                     "threads": chart_range["threads"]},
        integration=Integration.from_array(a.integration),
        simulation={"t_end": simulation["t_end"], "n_out": simulation["n_out"],
                    "y0": [simulation[f"y0_{i}"] for i in range(1, 5 if a.planar else 9)]},
        steady=Steady.from_array(a.steady),
        sweep={"start_from": "previous" if sweep.pop("carry_state") else "y0", **sweep},
        response=Continuation.from_array(a.response),
        response_range=decode_all("response_range", a.response_range),
        lyapunov=Lyapunov.from_array(a.lyapunov),
        study=_study(a.study, a.store, a.figure, a.scheduler, a.study_records),
        planar=bool(a.planar), spatial=decode_all("spatial", a.spatial),
        ground_motion_y=ground_motion_y,
        design=Design.from_array(a.design) if a.has_design else None,
        tank_structure=TankStructure.from_array(a.tank_structure))


def _study(values, store, figure, scheduler, records):
    """&study as a dict (empty when the file has none)."""
    values = decode_all("study", values)
    if not values["given"]:
        return {}
    kind = values["kind"]
    study = {"kind": kind, "store": _tables._text(store), "figure": _tables._text(figure),
             "scheduler": _tables._text(scheduler),
             **{name: values[name] for name in ("workers", "worker_kind", "points_per_task",
                                                "min_workers", "grace_time")}}
    fields = {"response_map": ("frequency_start", "frequency_stop", "n_frequencies",
                               "amplitude_start", "amplitude_stop", "n_amplitudes",
                               "continuation"),
              "basins": ("x1_start", "x1_stop", "dx1_start", "dx1_stop", "n_grid", "tol"),
              "fragility": ("intensity_start", "intensity_stop", "n_intensities",
                            "spectral_damping")}[kind]
    study.update({name: values[name] for name in fields})
    if kind == "fragility":
        study["records"] = _tables._text(records)
    return study
