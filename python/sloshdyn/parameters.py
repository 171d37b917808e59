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
from ._settings import convert_fields, decode_all

#: the core's model_t defaults, by name
_MODEL_DEFAULTS = {**_tables.defaults("model"), **_tables.defaults("model_integers")}


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
    """A validated namelist input file: every settings group as its settings object (defaults
    where the file has no such group), the other groups as dicts of their variables."""

    params: Parameters
    analysis: str = "linear"
    sigma1: float = 0.0
    kappa_min: float = 0.0
    kappa_max: float | None = None
    directory: str = "sloshdyn_output"
    tank: object = None            #: seismic.Tank (from &tank), or None (&model)
    ground_motion: object = None   #: seismic.GroundMotion (from &ground_motion, scaled), or None
    seismic: dict = field(default_factory=dict)       #: &seismic: t_end [s], n_out (0: default)
    chart: object = None          #: &chart's settings: charts.Chart
    chart_range: dict = field(default_factory=dict)   #: &chart's model, x, y, x_range,
                                                      #: y_range and threads (stability_chart's
                                                      #: arguments)
    integration: object = None    #: &integration: simulation.Integration
    simulation: dict = field(default_factory=dict)    #: &simulation: t_end, n_out, y0
    steady: object = None         #: &steady: simulation.Steady
    sweep: dict = field(default_factory=dict)         #: &sweep: parameter, start, stop, ...
    response: object = None       #: &response's settings: asymptotics.Continuation
    response_range: dict = field(default_factory=dict)   #: &response's resonance, parameter,
                                                         #: start, stop
    lyapunov: object = None       #: &lyapunov: periodic.Lyapunov
    study: dict = field(default_factory=dict)         #: &study (empty if none): kind, store, ...
    planar: bool = True           #: &model or &tank planar (False: the spatial model, issue 26)
    spatial: dict = field(default_factory=lambda: {"azimuth": 0.0, "ellipticity": 0.0})
    #: &ground_motion's azimuth [rad] and ellipticity (sloshdyn.spatial.seismic_response_2d)
    ground_motion_y: object = None  #: &ground_motion's record_y (scaled by the first's factor)
    design: object = None         #: &design: sloshdyn.design.Design, or None (no &design)


def read_namelist(path) -> Input:
    """Read and validate a namelist input file with the executable's reader (same rules, defaults
    and messages)."""
    from .asymptotics import Continuation
    from .charts import Chart
    from .periodic import Lyapunov
    from .seismic import GroundMotion, Tank
    from .simulation import Integration, Steady
    from .design import Design

    path = _checks.path("path", path)
    (rpar, ipar, analysis, values, directory, has_tank, tank_array, has_ground, ground, n_samples,
     seismic, integration, steady, response, lyapunov, simulation, sweep, response_range, chart,
     chart_range, study, store, figure, scheduler, study_records, planar, spatial, has_ground_y,
     ground_y, n_samples_y, has_design, design, status,
     message) = app_call(_core.sloshdyn_bridge_input.read_input, os.fsencode(path))
    check_status(status, message)
    tank = ground_motion = ground_motion_y = None
    if has_tank:
        tank = Tank.from_array(tank_array)

    def ground_of(component, array, n):
        samples = np.zeros(0)
        if n > 0:
            samples, status, message = app_call(_core.sloshdyn_bridge_input.input_record,
                                                os.fsencode(path), component, n)
            check_status(status, message)
        return GroundMotion._from_arrays(array, samples.copy())

    if has_ground:
        ground_motion = ground_of(1, ground, n_samples)
    if has_ground_y:
        ground_motion_y = ground_of(2, ground_y, n_samples_y)
    sweep = decode_all("sweep", sweep)
    simulation = decode_all("simulation", simulation)
    chart_range = decode_all("chart_range", chart_range)
    return Input(
        params=Parameters.from_array(rpar, ipar),
        analysis=_tables.codes("analyses")[int(analysis)],
        **decode_all("analysis", values),
        directory=_tables._text(directory), tank=tank, ground_motion=ground_motion,
        seismic=decode_all("seismic", seismic),
        chart=Chart.from_array(chart),
        chart_range={"model": chart_range["model"], "x": chart_range["x"], "y": chart_range["y"],
                     "x_range": (chart_range["x_min"], chart_range["x_max"]),
                     "y_range": (chart_range["y_min"], chart_range["y_max"]),
                     "threads": chart_range["threads"]},
        integration=Integration.from_array(integration),
        simulation={"t_end": simulation["t_end"], "n_out": simulation["n_out"],
                    "y0": [simulation[f"y0_{i}"] for i in range(1, 5 if planar else 9)]},
        steady=Steady.from_array(steady),
        sweep={"start_from": "previous" if sweep.pop("carry_state") else "y0", **sweep},
        response=Continuation.from_array(response),
        response_range=decode_all("response_range", response_range),
        lyapunov=Lyapunov.from_array(lyapunov),
        study=_study(study, store, figure, scheduler, study_records), planar=bool(planar),
        spatial=decode_all("spatial", spatial), ground_motion_y=ground_motion_y,
        design=Design.from_array(design) if has_design else None)


def _study(values, store, figure, scheduler, records):
    """&study as a dict (empty when the file has none)."""
    values = decode_all("study", values)
    if not values["given"]:
        return {}
    kind = values["kind"]
    study = {"kind": kind, "store": _tables._text(store), "figure": _tables._text(figure),
             "scheduler": _tables._text(scheduler),
             **{name: values[name] for name in ("workers", "worker_kind", "points_per_task")}}
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
