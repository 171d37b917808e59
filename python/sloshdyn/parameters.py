"""Model parameters and the namelist input file.

The namelist groups and variables are the same for the Fortran executable and for Python
(README.md, "Namelist reference"); both apply the same rules, so one file gives the same
numbers through either front door.
"""

from __future__ import annotations

import dataclasses
import math
import os
from dataclasses import dataclass, field

import numpy as np

from . import _core
from ._errors import FileError, InputError, check_status
from ._files import atomic_path

REQUIRED = object()

# group -> variable (lower case, as f90nml reports it) -> (display name, type, default)
NAMELIST_SCHEMA = {
    "model": {
        "s1": ("s1", float, REQUIRED),
        "mu1": ("mu1", float, REQUIRED),
        "kappa": ("kappa", float, REQUIRED),
        "theta0": ("theta0", float, REQUIRED),
        "beta": ("beta", float, 10.0),
        "gamma": ("gamma", float, 0.0),
        "delta": ("delta", float, 0.1),
        "n": ("n", int, 6),
        "p": ("p", int, 2),
    },
    "tank": {
        "r": ("R", float, REQUIRED),
        "h": ("h", float, REQUIRED),
        "rho_liquid": ("rho_liquid", float, 0.0),
        "m_liquid": ("m_liquid", float, 0.0),
    },
    "structure": {
        "m": ("M", float, REQUIRED),
        "l": ("L", float, REQUIRED),
        "k": ("k", float, REQUIRED),
        "c": ("c", float, 0.0),
        "b": ("b", float, 0.0),
        "d": ("d", float, 0.0),
        "g": ("g", float, 9.81),
        "theta0": ("theta0", float, REQUIRED),
        "n": ("n", int, 6),
        "p": ("p", int, 2),
    },
    "excitation": {
        "a": ("A", float, 0.0),
        "rho": ("rho", float, 0.0),
    },
    "analysis": {
        "kind": ("kind", str, "linear"),
        "sigma1": ("sigma1", float, 0.0),
        "kappa_min": ("kappa_min", float, 0.0),
        "kappa_max": ("kappa_max", float, None),
    },
    "output": {
        "directory": ("directory", str, "sloshdyn_output"),
    },
    "integration": {
        "rtol": ("rtol", float, 1e-9),
        "atol": ("atol", float, 1e-12),
        "h_initial": ("h_initial", float, 0.0),
        "h_max": ("h_max", float, 0.0),
        "h_min": ("h_min", float, 0.0),
        "max_steps": ("max_steps", int, 10**8),
        "method": ("method", str, "rk45"),
    },
    "simulation": {
        "t_end": ("t_end", float, None),
        "n_out": ("n_out", int, 2001),
        "y0": ("y0", "state", [0.0, 0.0, 0.0, 0.0]),
    },
    "steady": {
        "transient_periods": ("transient_periods", float, 1000.0),
        "settle_tol": ("settle_tol", float, 1e-7),
        "max_transient_periods": ("max_transient_periods", float, 20000.0),
        "window_periods": ("window_periods", int, 200),
        "samples_per_period": ("samples_per_period", int, 128),
        "periodic_tol": ("periodic_tol", float, 1e-4),
    },
    "sweep": {
        "parameter": ("parameter", str, "rho"),
        "start": ("start", float, None),
        "stop": ("stop", float, None),
        "n_points": ("n_points", int, 0),
        "direction": ("direction", str, "up"),
    },
    "response": {
        "resonance": ("resonance", str, "3:1"),
        "parameter": ("parameter", str, "rho"),
        "start": ("start", float, None),
        "stop": ("stop", float, None),
        "n_scan": ("n_scan", int, 5),
        "n_amplitudes": ("n_amplitudes", int, 6),
        "n_phases": ("n_phases", int, 6),
        "amplitude_min": ("amplitude_min", float, 1e-4),
        "amplitude_max": ("amplitude_max", float, 1.0),
        "ds": ("ds", float, 0.002),
        "ds_min": ("ds_min", float, 1e-9),
        "ds_max": ("ds_max", float, 0.01),
        "x_scale": ("x_scale", float, 1.0),
    },
    "lyapunov": {
        "transient_periods": ("transient_periods", float, 1000.0),
        "n_periods": ("n_periods", int, 2000),
        "renormalise_every": ("renormalise_every", int, 1),
    },
}
ANALYSES = ("linear", "simulate", "steady_state", "sweep", "frequency_response",
            "periodic_response", "lyapunov")
_TYPE_WORDS = {float: "a real number", int: "an integer", str: "a quoted string",
               "state": "four real numbers (x1, x1', x2, x2')"}


@dataclass(frozen=True)
class Parameters:
    """The dimensionless model of eq (9)-(11) and the excitation X = A sin(rho tau).

    Field names are the paper's symbols and the namelist's variable names.
    """

    s1: float
    mu1: float
    kappa: float
    theta0: float
    beta: float = 10.0     #: the paper gives none; see README "Impact and dissipation defaults"
    gamma: float = 0.0
    delta: float = 0.1     #: the paper gives none; see README
    n: int = 6
    p: int = 2
    A: float = 0.0
    rho: float = 0.0

    def __post_init__(self):
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if f.type == "int":
                if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
                    raise InputError(f"{f.name} = {value!r} is not valid: {f.name} must be an integer")
            elif isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
                raise InputError(f"{f.name} = {value!r} is not valid: {f.name} must be a real number")
        self.coefficients()  # validates in the Fortran core

    def arrays(self):
        """The flat arrays of the f2py bridge: rpar(9), ipar(2)."""
        rpar = np.array([self.s1, self.mu1, self.kappa, self.theta0, self.beta, self.gamma,
                         self.delta, self.A, self.rho], dtype=np.float64)
        ipar = np.array([self.n, self.p], dtype=np.int32)
        return rpar, ipar

    def coefficients(self):
        """a1..a6 and b1..b6 of eq (11) as two arrays."""
        a, b, status, message = _core.sloshdyn_bridge.model_coefficients(*self.arrays())
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
    def from_physical(cls, *, M, L, k, theta0, R=None, h=None, rho_liquid=None, m_liquid=None,
                      l=None, m=None, c=0.0, b=0.0, d=0.0, g=9.81, n=6, p=2, A=0.0, rho=0.0):
        """Dimensionless groups of eq (9) from SI values. The pendulum (l, m) is given directly or
        computed from a cylindrical tank (R, h and rho_liquid or m_liquid, eq 2)."""
        if l is None or m is None:
            if R is None or h is None:
                raise InputError("give the pendulum (l, m) or the tank (R, h with rho_liquid or m_liquid)")
            pendulum = tank_pendulum(R, h, rho_liquid=rho_liquid, m_liquid=m_liquid)
            l, m = pendulum.l, pendulum.m
        physical = np.array([M, L, k, c, b, d, g, theta0, l, m], dtype=np.float64)
        groups, status, message = _core.sloshdyn_bridge.dimensionless_groups(physical)
        check_status(status, message)
        s1, mu1, kappa, beta, gamma, delta = (float(x) for x in groups)
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
                      ("s1", "mu1", "kappa", "theta0", "beta", "gamma", "delta", "n", "p")},
            "excitation": {"A": self.A, "rho": self.rho},
        }
        nml = f90nml.Namelist(groups)
        nml.float_format = ".17g"
        with atomic_path(path) as tmp:
            nml.write(tmp, force=True)


@dataclass(frozen=True)
class TankPendulum:
    """Equivalent pendulum of a cylindrical tank (eq 2-3), SI units."""

    l: float    #: pendulum length [m]
    m: float    #: sloshing mass [kg]
    d1: float   #: pendulum distance d1 [m]
    m0: float   #: rigid (non-sloshing) liquid mass [kg]
    d0: float   #: rigid mass distance below the free surface [m]
    m_F: float  #: total liquid mass [kg]


def tank_pendulum(R, h, rho_liquid=None, m_liquid=None):
    """Pendulum of the first sloshing mode of a cylindrical tank of radius R and liquid depth h,
    from the liquid density rho_liquid or the liquid mass m_liquid (give one), eq (2)-(3)."""
    pendulum, status, message = _core.sloshdyn_bridge.tank_pendulum(
        R, h, rho_liquid or 0.0, m_liquid or 0.0)
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
    tank: TankPendulum | None = None
    structure: dict = field(default_factory=dict)
    integration: dict = field(default_factory=dict)   #: &integration, for simulation.Integration
    simulation: dict = field(default_factory=dict)    #: &simulation: t_end, n_out, y0
    steady: dict = field(default_factory=dict)        #: &steady, for simulation.Steady
    sweep: dict = field(default_factory=dict)         #: &sweep: parameter, start, stop, ...
    response: dict = field(default_factory=dict)      #: &response: resonance, parameter, ...
    lyapunov: dict = field(default_factory=dict)      #: &lyapunov


def read_namelist(path):
    """Read and validate a namelist input file (same rules and messages as the executable)."""
    import f90nml

    path = os.fspath(path)
    if not os.path.isfile(path):
        raise FileError(f"cannot open input file '{path}': no such file")
    try:
        raw = f90nml.read(path)
    except Exception as exc:  # f90nml raises several types for malformed text
        raise InputError(f"'{path}' is not a readable namelist file: {exc}") from exc
    if not raw:
        raise InputError(f"no namelist group found in '{path}' (expected &model ... /)")
    values = {}
    for group, content in raw.items():
        if group not in NAMELIST_SCHEMA:
            known = ", &".join(NAMELIST_SCHEMA)
            raise InputError(f"unknown namelist group &{group} in '{path}'; known groups: &{known}")
        if isinstance(content, list):
            raise InputError(f"namelist group &{group} appears twice in '{path}'")
        values[group] = _group_values(group, content, path)
    given = set(values)

    if "model" in given and given & {"tank", "structure"}:
        raise InputError("give either &model (dimensionless) or &tank with &structure "
                         "(dimensional), not both")
    if "model" not in given and not given & {"tank", "structure"}:
        raise InputError("missing group &model (or &tank with &structure): the system is not described")
    if ("tank" in given) != ("structure" in given):
        missing = "structure" if "tank" in given else "tank"
        raise InputError(f"&tank and &structure go together: group &{missing} is missing")

    excitation = values.get("excitation", _group_values("excitation", {}, path))
    tank = None
    structure = {}
    if "tank" in given:
        t, s = values["tank"], values["structure"]
        try:
            tank = tank_pendulum(t["r"], t["h"], t["rho_liquid"], t["m_liquid"])
        except InputError as exc:
            raise InputError(f"&tank: {exc}") from exc
        structure = {NAMELIST_SCHEMA["structure"][k][0]: v for k, v in s.items()}
        try:
            params = Parameters.from_physical(
                M=s["m"], L=s["l"], k=s["k"], c=s["c"], b=s["b"], d=s["d"], g=s["g"],
                theta0=s["theta0"], l=tank.l, m=tank.m, n=s["n"], p=s["p"],
                A=excitation["a"], rho=excitation["rho"])
        except InputError as exc:
            raise InputError(f"&structure: {exc}") from exc
    else:
        mdl = values["model"]
        try:
            params = Parameters(A=excitation["a"], rho=excitation["rho"],
                                **{k: v for k, v in mdl.items()})
        except InputError as exc:
            raise InputError(f"&model: {exc}") from exc

    analysis = values.get("analysis", _group_values("analysis", {}, path))
    kind = analysis["kind"].strip()
    if kind not in ANALYSES:
        raise InputError(f"&analysis: kind = '{kind}' is not known; allowed: {', '.join(ANALYSES)}")
    kappa_max = analysis["kappa_max"]
    if kappa_max is None:
        kappa_max = params.s1 + 1000
    if not math.isfinite(analysis["sigma1"]):
        raise InputError(f"&analysis: sigma1 = {analysis['sigma1']} is out of range: sigma1 must be finite")
    if not (math.isfinite(kappa_max) and kappa_max > params.s1):
        raise InputError(f"&analysis: kappa_max = {kappa_max} is out of range: kappa_max must be "
                         f"> s1 = {params.s1}")
    if not analysis["kappa_min"] < kappa_max:
        raise InputError(f"&analysis: kappa_min = {analysis['kappa_min']} is out of range: "
                         f"kappa_min must be < kappa_max = {kappa_max}")
    directory = values.get("output", {"directory": "sloshdyn_output"})["directory"]
    if not directory.strip():
        raise InputError("&output: directory = '' is empty: give a directory name")
    group = {name: values.get(name, _group_values(name, {}, path))
             for name in ("integration", "simulation", "steady", "sweep", "response", "lyapunov")}
    named = {name: {NAMELIST_SCHEMA[name][k][0]: v for k, v in g.items()} for name, g in group.items()}
    named["integration"]["method"] = named["integration"]["method"].strip()
    if named["integration"]["method"] not in ("rk45", "dop853"):
        raise InputError(f"&integration: method = '{named['integration']['method']}' is not known; "
                         "allowed: rk45, dop853")
    if kind in ("linear", "frequency_response", "periodic_response"):
        from .model import linear_modes
        linear_modes(params)              # needs kappa_hat > 1, checked before any output
    _check_analysis(kind, params, named, path)
    return Input(params=params, analysis=kind, sigma1=analysis["sigma1"],
                 kappa_min=analysis["kappa_min"], kappa_max=kappa_max,
                 directory=directory.strip(), tank=tank, structure=structure,
                 integration=named["integration"], simulation=named["simulation"],
                 steady=named["steady"], sweep=named["sweep"], response=named["response"],
                 lyapunov=named["lyapunov"])


def _check_analysis(kind, params, named, path):
    """The rules of &simulation and &sweep (the integrator and steady-state settings are
    checked by the core when they are used, with the same messages)."""
    sim, sweep, response = named["simulation"], named["sweep"], named["response"]
    if kind == "simulate":
        if sim["t_end"] is None:
            raise InputError("&simulation: required variable t_end is missing")
        if not (math.isfinite(sim["t_end"]) and sim["t_end"] > 0):
            raise InputError(f"&simulation: t_end = {sim['t_end']} is out of range: t_end must be > 0 "
                             "(the simulation starts at tau = 0)")
        if not 2 <= sim["n_out"] <= 10_000_000:
            raise InputError(f"&simulation: n_out = {sim['n_out']} is out of range: it must lie in "
                             "[2, 10000000]")
    if kind == "sweep":
        if sweep["parameter"].strip() not in ("rho", "A", "a"):
            raise InputError(f"&sweep: parameter = '{sweep['parameter'].strip()}' is not known; "
                             "allowed: rho, A")
        if sweep["direction"].strip() not in ("up", "down", "both"):
            raise InputError(f"&sweep: direction = '{sweep['direction'].strip()}' is not known; "
                             "allowed: up, down, both")
        for name in ("start", "stop"):
            if sweep[name] is None:
                raise InputError(f"&sweep: required variable {name} is missing")
        if not 1 <= sweep["n_points"] <= 100_000:
            raise InputError(f"&sweep: n_points = {sweep['n_points']} is out of range: it must lie "
                             "in [1, 100000]")
    if kind in ("frequency_response", "periodic_response"):
        if response["resonance"].strip() not in ("3:1", "none"):
            raise InputError(f"&response: resonance = '{response['resonance'].strip()}' is not "
                             "known; allowed: 3:1, none")
        if response["parameter"].strip() not in ("rho", "A", "a"):
            raise InputError(f"&response: parameter = '{response['parameter'].strip()}' is not "
                             "known; allowed: rho, A")
        for name in ("start", "stop"):
            if response[name] is None:
                raise InputError(f"&response: required variable {name} is missing")
    if kind == "lyapunov":
        lyap = named["lyapunov"]
        if lyap["n_periods"] < 1 or lyap["renormalise_every"] < 1 or lyap["transient_periods"] < 0:
            raise InputError("&lyapunov: transient_periods >= 0, n_periods >= 1 and "
                             "renormalise_every >= 1 are needed")
        if lyap["n_periods"] % lyap["renormalise_every"]:
            raise InputError(f"&lyapunov: n_periods = {lyap['n_periods']} is out of range: it must "
                             f"be a multiple of renormalise_every = {lyap['renormalise_every']}")


def _group_values(group, content, path):
    """Check names and types of one group's variables; fill defaults; require required ones."""
    schema = NAMELIST_SCHEMA[group]
    values = {}
    for key, value in content.items():
        if key not in schema:
            raise InputError(f"&{group} in '{path}': unknown variable '{key}' "
                             "(see the namelist reference in README.md)")
        name, kind, _ = schema[key]
        if kind == "state":
            value = list(value) if isinstance(value, list) else [value]
            ok = all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value)
            if ok:
                # Fortran fills a partly given array from the start and keeps the defaults
                value = [float(v) for v in value] + [0.0] * (4 - len(value))
                ok = len(value) == 4
            if not ok:
                raise InputError(f"&{group} in '{path}': {name} = {value!r} is not valid: "
                                 f"{name} must be {_TYPE_WORDS[kind]}")
            values[key] = value
            continue
        ok = (isinstance(value, str) if kind is str else
              isinstance(value, int) and not isinstance(value, bool) if kind is int else
              isinstance(value, (int, float)) and not isinstance(value, bool))
        if not ok:
            raise InputError(f"&{group} in '{path}': {name} = {value!r} is not valid: "
                             f"{name} must be {_TYPE_WORDS[kind]}")
        values[key] = float(value) if kind is float else value
    for key, (name, _, default) in schema.items():
        if key not in values:
            if default is REQUIRED:
                raise InputError(f"&{group}: required variable {name} is missing")
            values[key] = default
    return values
