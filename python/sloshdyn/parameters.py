"""Model parameters and the namelist input file.

A namelist file is read by the Fortran reader of the executable, through the bridge: the groups,
variables, defaults, rules and messages are the same for both front doors by construction
(README.md, "Namelist reference").
"""

from __future__ import annotations

import dataclasses
import os
from dataclasses import dataclass, field

import numpy as np

from . import _checks, _core, _tables
from ._cancel import app_call
from ._errors import InputError, check_status
from ._files import atomic_path

_MODEL_DEFAULTS = _tables.defaults()["model"]   # the core's model_t defaults, by name


def convert_fields(settings):
    """Check and convert every field of a settings dataclass by its annotation (int: a C int,
    float: a finite real, bool: True or False, str: text), in place (frozen or not)."""
    kinds = {"int": _checks.integer, "float": _checks.real, "bool": _checks.flag,
             "str": _checks.text}
    for f in dataclasses.fields(settings):
        check = kinds.get(f.type)
        if check is not None:
            object.__setattr__(settings, f.name, check(f.name, getattr(settings, f.name)))


@dataclass(frozen=True)
class Parameters:
    """The dimensionless model of eq (9)-(11) and the excitation X = A sin(rho tau).

    Field names are the paper's symbols and the namelist's variable names.
    """

    s1: float
    mu1: float
    kappa: float
    theta0: float
    beta: float = float(_MODEL_DEFAULTS["beta"])   #: the paper gives none; see README "Impact and
                                              #: dissipation defaults"
    gamma: float = float(_MODEL_DEFAULTS["gamma"])
    delta: float = float(_MODEL_DEFAULTS["delta"])  #: the paper gives none; see README
    n: int = int(_MODEL_DEFAULTS["n"])
    p: int = int(_MODEL_DEFAULTS["p"])
    zeta: float = float(_MODEL_DEFAULTS["zeta"])   #: linear sloshing damping ratio (0: the paper)
    A: float = 0.0
    rho: float = 0.0

    def __post_init__(self):
        convert_fields(self)
        self.coefficients()  # validates in the Fortran core

    def array(self):
        """The flat arrays of the f2py bridge: rpar, ipar in the core's layouts 'model' and
        'model_integers'."""
        rpar = _tables.pack("model", {name: getattr(self, name)
                                      for name in _tables.layout("model")})
        ipar = _tables.pack("model_integers", {name: getattr(self, name) for name in
                                               _tables.layout("model_integers")}, dtype=np.int32)
        return rpar, ipar

    @classmethod
    def from_array(cls, rpar, ipar, **changes):
        """The parameters of the bridge's arrays rpar, ipar (with some fields changed)."""
        fields = {name: float(x) for name, x in _tables.unpack("model", rpar).items()}
        fields.update({name: int(x) for name, x in _tables.unpack("model_integers", ipar).items()})
        return cls(**{**fields, **changes})

    def coefficients(self):
        """a1..a6 and b1..b6 of eq (11) as two arrays."""
        a, b, status, message = _core.sloshdyn_bridge_model.model_coefficients(*self.array())
        check_status(status, message)
        return a, b

    def replace(self, **changes):
        """A copy with some fields changed (validated again)."""
        return dataclasses.replace(self, **changes)

    @property
    def kappa_hat(self):
        """kappa/s1 (eq 18): the trivial equilibrium is stable for kappa_hat > 1."""
        return self.kappa / self.s1

    @classmethod
    def from_physical(cls, *, M, L, k, theta0, radius=None, liquid_depth=None,
                      liquid_density=None, liquid_mass=None, l=None, m=None, c=0.0, b=None,
                      d=None, g=9.80665, n=6, p=2, A=0.0, rho=0.0):
        """Dimensionless groups of eq (9) from SI values. The pendulum (l, m) is given directly or
        computed from a cylindrical tank (radius, liquid_depth and liquid_density or
        liquid_mass, eq 2; the names of sloshdyn.Tank). Without the
        impact coefficient b [N m] or the dissipation d [N m s], beta and delta take the same
        defaults as Parameters and &model (README, "Impact and dissipation defaults"). For a
        whole tank in SI units (freeboard, supports by frequency, damping ratios) see
        sloshdyn.Tank."""
        M, L, k, theta0, c, g, A, rho = (_checks.real(name, value) for name, value in (
            ("M", M), ("L", L), ("k", k), ("theta0", theta0), ("c", c), ("g", g), ("A", A),
            ("rho", rho)))
        b, d = _checks.optional_real("b", b, None), _checks.optional_real("d", d, None)
        if l is None or m is None:
            if radius is None or liquid_depth is None:
                raise InputError("give the pendulum (l, m) or the tank (radius, liquid_depth with "
                                 "liquid_density or liquid_mass)")
            pendulum = tank_pendulum(radius, liquid_depth, liquid_density=liquid_density,
                                     liquid_mass=liquid_mass)
            l, m = pendulum.pendulum_length, pendulum.sloshing_mass
        l, m = _checks.real("l", l), _checks.real("m", m)
        physical = np.array([M, L, k, c, b or 0.0, d or 0.0, g, theta0, l, m], dtype=np.float64)
        groups, status, message = _core.sloshdyn_bridge_model.dimensionless_groups(physical)
        check_status(status, message)
        s1, mu1, kappa, beta, gamma, delta = (float(x) for x in groups)
        beta = float(_MODEL_DEFAULTS["beta"]) if b is None else beta
        delta = float(_MODEL_DEFAULTS["delta"]) if d is None else delta
        return cls(s1=s1, mu1=mu1, kappa=kappa, theta0=theta0, beta=beta, gamma=gamma,
                   delta=delta, n=n, p=p, A=A, rho=rho)

    @classmethod
    def from_namelist(cls, path):
        """The parameters described by a namelist file (either front door's input)."""
        return read_namelist(path).params

    def to_namelist(self, path):
        """Write &model and &excitation groups (written to a temporary name, then renamed)."""
        import f90nml

        groups = {
            "model": {name: getattr(self, name) for name in
                      ("s1", "mu1", "kappa", "theta0", "beta", "gamma", "delta", "zeta", "n",
                       "p")},
            "excitation": {"A": self.A, "rho": self.rho},
        }
        nml = f90nml.Namelist(groups)
        nml.float_format = ".17g"
        with atomic_path(_checks.path("path", path)) as tmp:
            nml.write(tmp, force=True)


@dataclass(frozen=True)
class TankPendulum:
    """Equivalent pendulum of a cylindrical tank (eq 2-3), SI units; the names of the tank's
    table (tank.csv, Tank.properties)."""

    pendulum_length: float  #: l [m]
    sloshing_mass: float    #: m [kg]
    d1: float               #: pendulum distance d1 [m]
    rigid_mass: float       #: m0, the rigid (non-sloshing) liquid mass [kg]
    d0: float               #: rigid mass distance below the free surface [m]
    liquid_mass: float      #: m_F, the total liquid mass [kg]


def tank_pendulum(radius, liquid_depth, *, liquid_density=None,
                  liquid_mass=None) -> TankPendulum:
    """Pendulum of the first sloshing mode of a cylindrical tank of a radius and liquid depth
    [m], from the liquid density [kg/m^3] or the liquid mass [kg] (give one), eq (2)-(3)."""
    pendulum, status, message = _core.sloshdyn_bridge_model.tank_pendulum(
        _checks.real("radius", radius), _checks.real("liquid_depth", liquid_depth),
        _checks.optional_real("liquid_density", liquid_density, 0.0),
        _checks.optional_real("liquid_mass", liquid_mass, 0.0))
    check_status(status, message)
    return TankPendulum(**{name: float(x)
                           for name, x in _tables.unpack("pendulum", pendulum).items()})


@dataclass(frozen=True)
class Input:
    """A validated namelist input file."""

    params: Parameters
    analysis: str = "linear"
    sigma1: float = 0.0
    kappa_min: float = 0.0
    kappa_max: float | None = None
    directory: str = "sloshdyn_output"
    tank: object = None            #: seismic.Tank (from &tank), or None (&model)
    ground_motion: object = None   #: seismic.GroundMotion (from &ground_motion, scaled), or None
    seismic: dict = field(default_factory=dict)       #: &seismic: t_end [s], n_out (0: default)
    chart: dict = field(default_factory=dict)         #: &chart, as stability_chart's arguments
    integration: dict = field(default_factory=dict)   #: &integration, for simulation.Integration
    simulation: dict = field(default_factory=dict)    #: &simulation: t_end, n_out, y0
    steady: dict = field(default_factory=dict)        #: &steady, for simulation.Steady
    sweep: dict = field(default_factory=dict)         #: &sweep: parameter, start, stop, ...
    response: dict = field(default_factory=dict)      #: &response: resonance, parameter, ...
    lyapunov: dict = field(default_factory=dict)      #: &lyapunov
    study: dict = field(default_factory=dict)         #: &study (empty if none): kind, store, ...


def read_namelist(path) -> Input:
    """Read and validate a namelist input file with the executable's reader (same rules, defaults
    and messages)."""
    from .seismic import GroundMotion, Tank

    path = _checks.path("path", path)
    (rpar, ipar, analysis, values, directory, has_tank, tank_array, has_ground, ground, n_samples,
     seismic, integration, steady, response, lyapunov, simulation, sweep, response_range, chart,
     study, store, figure, scheduler, study_records, status,
     message) = app_call(_core.sloshdyn_bridge_input.read_input, os.fsencode(path))
    check_status(status, message)
    tank = ground_motion = None
    if has_tank:
        tank = Tank.from_array(tank_array)
    if has_ground:
        samples = np.zeros(0)
        if n_samples > 0:
            samples, status, message = app_call(_core.sloshdyn_bridge_input.input_record,
                                                os.fsencode(path), n_samples)
            check_status(status, message)
        ground_motion = GroundMotion._from_arrays(ground, samples.copy())
    excitation_parameters = _tables.codes("excitation_parameters")
    sweep = _tables.unpack("sweep", sweep)
    response_range = _tables.unpack("response_range", response_range)
    simulation = _tables.unpack("simulation", simulation)
    return Input(
        params=Parameters.from_array(rpar, ipar),
        analysis=_tables.codes("analyses")[int(analysis)],
        **{name: float(x) for name, x in _tables.unpack("analysis", values).items()},
        directory=_tables._text(directory), tank=tank, ground_motion=ground_motion,
        seismic=_typed(_tables.unpack("seismic", seismic), integers=("n_out",)),
        chart=_chart_settings(chart),
        integration=_integration_settings(integration),
        simulation={"t_end": float(simulation["t_end"]), "n_out": int(simulation["n_out"]),
                    "y0": [float(simulation[f"y0_{i}"]) for i in range(1, 5)]},
        steady=_steady_settings(steady),
        sweep={"parameter": excitation_parameters[int(sweep["parameter"])],
               "start": float(sweep["start"]), "stop": float(sweep["stop"]),
               "n_points": int(sweep["n_points"]),
               "direction": _tables.codes("directions")[int(sweep["direction"])],
               "start_from": "previous" if sweep["carry_state"] else "y0",
               "threads": int(sweep["threads"])},
        response={"resonance": _tables.codes("resonances")[int(response_range["resonance"])],
                  "parameter": excitation_parameters[int(response_range["parameter"])],
                  "start": float(response_range["start"]), "stop": float(response_range["stop"]),
                  "switch_at": int(response_range["switch_at"]),
                  **_response_settings(response)},
        lyapunov=_typed(_tables.unpack("lyapunov", lyapunov),
                        integers=("transient_periods", "n_periods", "renormalise_every"),
                        flags=("spectrum",)),
        study=_study(study, store, figure, scheduler, study_records))


def _typed(values, integers=(), flags=()):
    """{field: value} with Python floats, ints for the fields in integers, bools for flags."""
    return {name: (int(x) if name in integers else bool(x) if name in flags else float(x))
            for name, x in values.items()}


def _integration_settings(array):
    """The integration layout as simulation.Integration's fields (the method by name)."""
    values = _typed(_tables.unpack("integration", array), integers=("max_steps", "method"))
    values["method"] = _tables.codes("methods")[values["method"]]
    return values


def _steady_settings(array):
    """The steady layout as simulation.Steady's fields."""
    return _typed(_tables.unpack("steady", array),
                  integers=("window_periods", "samples_per_period"), flags=("shooting",))


def _response_settings(array):
    """The response layout (the numbers of &response)."""
    return _typed(_tables.unpack("response", array),
                  integers=("n_scan", "n_amplitudes", "n_phases", "max_points"))


def _study(values, store, figure, scheduler, records):
    """&study as a dict (empty when the file has none)."""
    values = _tables.unpack("study", values)
    if not values["given"]:
        return {}
    kind = _tables.codes("study_kinds")[int(values["kind"])]
    study = {"kind": kind, "store": _tables._text(store), "figure": _tables._text(figure),
             "scheduler": _tables._text(scheduler), "workers": int(values["workers"]),
             "worker_kind": _tables.codes("worker_kinds")[int(values["worker_kind"])],
             "points_per_task": int(values["points_per_task"])}
    integers = ("n_frequencies", "n_amplitudes", "n_grid", "n_intensities")
    fields = {"response_map": ("frequency_start", "frequency_stop", "n_frequencies",
                               "amplitude_start", "amplitude_stop", "n_amplitudes"),
              "basins": ("x1_start", "x1_stop", "dx1_start", "dx1_stop", "n_grid", "tol"),
              "fragility": ("intensity_start", "intensity_stop", "n_intensities",
                            "spectral_damping")}[kind]
    study.update(_typed({name: values[name] for name in fields}, integers=integers))
    if kind == "response_map":
        study["continuation"] = _tables.codes("continuations")[int(values["continuation"])]
    elif kind == "fragility":
        study["records"] = _tables._text(records)
    return study


def _chart_settings(chart):
    """&chart as the arguments of sloshdyn.stability_chart (the core's layout 'chart', the model
    and axes by their codes)."""
    values = _tables.unpack("chart", chart)
    axes = _tables.codes("chart_axes")
    return {"model": _tables.codes("chart_models")[int(values["model"])],
            "x": axes[int(values["x"])], "y": axes[int(values["y"])],
            "x_range": (float(values["x_min"]), float(values["x_max"])),
            "y_range": (float(values["y_min"]), float(values["y_max"])),
            **{name: int(values[name]) for name in ("n_x", "n_y", "n_scan", "max_points",
                                                    "max_curves", "brute_force_starts",
                                                    "threads")}}
