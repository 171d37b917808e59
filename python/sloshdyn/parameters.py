"""The dimensionless model of the paper (`Parameters`, eq 9-11) and the equivalent pendulum of
a cylindrical tank (`tank_pendulum`, eq 2-3). Value types at the bottom of the package: they
import no analysis (docs/architecture.md, "Python layers")."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from . import _checks, _core, _input, _tables
from ._errors import InputError, check_status
from ._files import atomic_path
from ._settings import convert_fields

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
        """The parameters described by a namelist file (either front door's input; the whole
        file is read and validated, as sloshdyn.read_namelist does)."""
        arrays = _input.read_arrays(path)
        return cls.from_array(arrays.rpar, arrays.ipar)

    def to_namelist(self, path):
        """Write &model and &excitation groups (written to a temporary name, then renamed)."""
        import f90nml    # deferred: only writing needs it, and it adds ~30 ms to `import sloshdyn`

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
