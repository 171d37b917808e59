"""Model parameters and the namelist input file.

A namelist file is read by the Fortran reader of the executable, through the bridge: the groups,
variables, defaults, rules and messages are the same for both front doors by construction
(README.md, "Namelist reference").
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import numpy as np

from . import _checks, _core, _tables
from ._errors import InputError, check_status
from ._files import atomic_path

_MODEL_DEFAULTS = _tables.defaults()["model"]   # beta, gamma, delta, n, p of the core


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
    beta: float = float(_MODEL_DEFAULTS[0])   #: the paper gives none; see README "Impact and
                                              #: dissipation defaults"
    gamma: float = float(_MODEL_DEFAULTS[1])
    delta: float = float(_MODEL_DEFAULTS[2])  #: the paper gives none; see README
    n: int = int(_MODEL_DEFAULTS[3])
    p: int = int(_MODEL_DEFAULTS[4])
    zeta: float = float(_MODEL_DEFAULTS[5])   #: linear sloshing damping ratio (0: the paper)
    A: float = 0.0
    rho: float = 0.0

    def __post_init__(self):
        convert_fields(self)
        self.coefficients()  # validates in the Fortran core

    def array(self):
        """The flat arrays of the f2py bridge: rpar(10), ipar(2)."""
        rpar = np.array([self.s1, self.mu1, self.kappa, self.theta0, self.beta, self.gamma,
                         self.delta, self.A, self.rho, self.zeta], dtype=np.float64)
        ipar = np.array([self.n, self.p], dtype=np.int32)
        return rpar, ipar

    def coefficients(self):
        """a1..a6 and b1..b6 of eq (11) as two arrays."""
        a, b, status, message = _core.sloshdyn_bridge.model_coefficients(*self.array())
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
        groups, status, message = _core.sloshdyn_bridge.dimensionless_groups(physical)
        check_status(status, message)
        s1, mu1, kappa, beta, gamma, delta = (float(x) for x in groups)
        beta = float(_MODEL_DEFAULTS[0]) if b is None else beta
        delta = float(_MODEL_DEFAULTS[2]) if d is None else delta
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
    pendulum, status, message = _core.sloshdyn_bridge.tank_pendulum(
        _checks.real("radius", radius), _checks.real("liquid_depth", liquid_depth),
        _checks.optional_real("liquid_density", liquid_density, 0.0),
        _checks.optional_real("liquid_mass", liquid_mass, 0.0))
    check_status(status, message)
    return TankPendulum(*(float(x) for x in pendulum))


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
     message) = _core.sloshdyn_bridge.read_input(path)
    check_status(status, message)
    s1, mu1, kappa, theta0, beta, gamma, delta, A, rho, zeta = (float(x) for x in rpar)
    params = Parameters(s1=s1, mu1=mu1, kappa=kappa, theta0=theta0, beta=beta, gamma=gamma,
                        delta=delta, n=int(ipar[0]), p=int(ipar[1]), A=A, rho=rho, zeta=zeta)
    analyses, first = _tables.names("analyses")
    methods, first_method = _tables.names("methods")
    tank = ground_motion = None
    if has_tank:
        tank = Tank(**{f.name: (int(x) if f.type == "int" else float(x))
                       for f, x in zip(dataclasses.fields(Tank), tank_array)})
    if has_ground and n_samples > 0:
        samples, status, message = _core.sloshdyn_bridge.input_record(path, n_samples)
        check_status(status, message)
        ground_motion = GroundMotion(dt=float(ground[3]), acceleration=samples.copy(),
                                     units="m/s^2")
    elif has_ground:
        ground_motion = GroundMotion(peak_acceleration=float(ground[1]),
                                     frequency=float(ground[2]), units="m/s^2")
    excitation_parameter = {1: "rho", 2: "A", 3: "frequency"}
    return Input(
        params=params, analysis=analyses[int(analysis) - first], sigma1=float(values[0]),
        kappa_min=float(values[1]), kappa_max=float(values[2]),
        directory=_tables._text(directory), tank=tank, ground_motion=ground_motion,
        seismic={"t_end": float(seismic[0]), "n_out": int(seismic[1])},
        chart=_chart_settings(chart),
        integration={**{name: float(x) for name, x in zip(
            ("rtol", "atol", "h_initial", "h_max", "h_min"), integration[:5])},
            "max_steps": int(integration[5]), "method": methods[int(integration[6]) - first_method]},
        simulation={"t_end": float(simulation[0]), "n_out": int(simulation[1]),
                    "y0": [float(x) for x in simulation[2:6]]},
        steady={"transient_periods": float(steady[0]), "settle_tol": float(steady[1]),
                "max_transient_periods": float(steady[2]), "window_periods": int(steady[3]),
                "samples_per_period": int(steady[4]), "periodic_tol": float(steady[5]),
                "shooting": bool(steady[6])},
        sweep={"parameter": excitation_parameter[int(sweep[0])], "start": float(sweep[1]),
               "stop": float(sweep[2]), "n_points": int(sweep[3]),
               "direction": ("up", "down", "both")[int(sweep[4]) - 1],
               "start_from": "previous" if sweep[5] else "y0", "threads": int(sweep[6])},
        response={"resonance": "3:1" if response_range[0] else "none",
                  "parameter": excitation_parameter[int(response_range[1])],
                  "start": float(response_range[2]), "stop": float(response_range[3]),
                  **{name: int(x) for name, x in zip(("n_scan", "n_amplitudes", "n_phases"),
                                                       response[:3])},
                  **{name: float(x) for name, x in zip(
                      ("amplitude_min", "amplitude_max", "ds", "ds_min", "ds_max", "x_scale"),
                      response[3:9])},
                  "max_points": int(response[9])},
        lyapunov={name: int(x) for name, x in zip(
            ("transient_periods", "n_periods", "renormalise_every"), lyapunov)},
        study=_study(study, store, figure, scheduler, study_records))


def _study(values, store, figure, scheduler, records):
    """&study as a dict (empty when the file has none)."""
    if not values[0]:
        return {}
    kind = ("response_map", "basins", "fragility")[int(values[1]) - 1]
    study = {"kind": kind, "store": _tables._text(store), "figure": _tables._text(figure),
             "scheduler": _tables._text(scheduler), "workers": int(values[2]),
             "worker_kind": ("processes", "threads")[int(values[3]) - 1],
             "points_per_task": int(values[4])}
    if kind == "response_map":
        study.update(frequency_start=float(values[5]), frequency_stop=float(values[6]),
                     n_frequencies=int(values[7]), amplitude_start=float(values[8]),
                     amplitude_stop=float(values[9]), n_amplitudes=int(values[10]),
                     continuation=("none", "up", "down", "both")[int(values[11]) - 1])
    elif kind == "basins":
        study.update(x1_start=float(values[12]), x1_stop=float(values[13]),
                     dx1_start=float(values[14]), dx1_stop=float(values[15]),
                     n_grid=int(values[16]), tol=float(values[17]))
    else:
        study.update(records=_tables._text(records), intensity_start=float(values[18]),
                     intensity_stop=float(values[19]), n_intensities=int(values[20]),
                     spectral_damping=float(values[21]))
    return study


def _chart_settings(chart):
    """&chart as the arguments of sloshdyn.stability_chart (the layout of the core's chart
    array: model, x, y, x_min, x_max, y_min, y_max, n_x, n_y, n_scan, max_points, max_curves,
    brute_force_starts, threads)."""
    models, axes = _tables.names("chart_models")[0], ("rho", "A", "gamma")
    values = [float(v) for v in chart]
    return {"model": models[int(values[0]) - 1], "x": axes[int(values[1]) - 1],
            "y": axes[int(values[2]) - 1], "x_range": (values[3], values[4]),
            "y_range": (values[5], values[6]),
            **{name: int(v) for name, v in zip(("n_x", "n_y", "n_scan", "max_points",
                                                 "max_curves", "brute_force_starts", "threads"),
                                                values[7:])}}
