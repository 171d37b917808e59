"""A real tank in SI units (`Tank`: circular or rectangular, on supports, with its roof) and
the design codes' sloshing parameters beside sloshdyn's (`DesignCodes`). A value type at the
bottom of the package: it imports no analysis (docs/architecture.md, "Python layers"); the
analyses take a Tank (seismic_response, design_check, wall_pressure, studies). Every number
comes from the Fortran core (sloshdyn_vessel); &tank is the same object (docs/namelist.md)."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from . import _checks, _core, _tables
from ._tables import column_name
from ._errors import InputError, check_status
from ._settings import convert_fields
from .ground import DesignSpectrum, ground_arrays
from .parameters import Parameters

_bridge = _core.sloshdyn_bridge_seismic
_TANK_DEFAULTS = _tables.defaults("tank")



@dataclass(frozen=True, kw_only=True)
class Tank:
    """A cylindrical or rectangular tank on supports, SI units (the namelist group &tank, the
    same variables and defaults). A cylinder by its radius; shape="rectangular" by its length
    (along the motion) and width. Give the liquid by liquid_density or liquid_mass, and the
    supports by support_frequency [Hz] with support_damping (ratio), or by support_stiffness
    [N m/rad] with support_damping_coefficient [N m s/rad]. modes = N takes the sloshing modes
    1..N (N <= 10; modes 2..N linear, docs/model.md "Rectangular tanks and higher modes"). The
    fields are in the order of the core's layout."""

    radius: float = float(_TANK_DEFAULTS["radius"])    #: R [m] (circular)
    liquid_depth: float                 #: h [m]
    freeboard: float                    #: liquid surface to the roof [m]
    liquid_density: float = float(_TANK_DEFAULTS["liquid_density"])      #: [kg/m^3]
    liquid_mass: float = float(_TANK_DEFAULTS["liquid_mass"])         #: [kg]
    tank_mass: float                    #: shell and roof [kg]
    support_frequency: float = float(_TANK_DEFAULTS["support_frequency"])   #: [Hz]
    support_damping: float = float(_TANK_DEFAULTS["support_damping"])     #: ratio of critical
    support_stiffness: float = float(_TANK_DEFAULTS["support_stiffness"])   #: [N m/rad]
    support_damping_coefficient: float = float(
        _TANK_DEFAULTS["support_damping_coefficient"])   #: [N m s/rad]
    #: rod length L [m]; 0: h + freeboard
    support_height: float = float(_TANK_DEFAULTS["support_height"])
    #: ratio of critical (linear)
    sloshing_damping: float = float(_TANK_DEFAULTS["sloshing_damping"])
    #: beta (dimensionless, eq 4)
    impact_stiffness: float = float(_TANK_DEFAULTS["impact_stiffness"])
    #: delta (dimensionless, eq 5)
    impact_damping: float = float(_TANK_DEFAULTS["impact_damping"])
    n: int = int(_TANK_DEFAULTS["n"])                      #: exponent of eq (4)
    p: int = int(_TANK_DEFAULTS["p"])                      #: exponent of eq (5)
    gravity: float = float(_TANK_DEFAULTS["gravity"])            #: [m/s^2]
    #: a cone roof's slope [degrees] (0: not a cone; at most one of roof_slope, roof_radius)
    roof_slope: float = float(_TANK_DEFAULTS["roof_slope"])
    #: a dome roof's radius [m] (0: not a dome; neither: a flat roof)
    roof_radius: float = float(_TANK_DEFAULTS["roof_radius"])
    #: "circular" or "rectangular" (the core's list 'tank_shapes')
    shape: str = _tables.codes("tank_shapes")[int(_TANK_DEFAULTS["shape"])]
    length: float = float(_TANK_DEFAULTS["length"])   #: L along the motion [m] (rectangular)
    width: float = float(_TANK_DEFAULTS["width"])     #: W across the motion [m] (rectangular)
    modes: int = int(_TANK_DEFAULTS["modes"])         #: sloshing modes 1..N taken, N <= 10
    #: "none" (the tank without contact below its roof, restricted sloshing above it) or
    #: "impact" (also the paper's impact model, eq 4-5, for its impact force only; the core's
    #: list 'roof_contacts')
    roof_contact: str = _tables.codes("roof_contacts")[int(_TANK_DEFAULTS["roof_contact"])]

    def __post_init__(self):
        convert_fields(self)
        for name, codes in (("shape", "tank_shapes"), ("roof_contact", "roof_contacts")):
            if getattr(self, name) not in _tables.codes(codes).values():
                raise InputError(f"{name} = {getattr(self, name)!r} is not known; allowed: "
                                 + ", ".join(_tables.codes(codes).values()))
        row, modes, rpar, ipar, status, message = _bridge.tank_properties(self.array())
        check_status(status, message)
        object.__setattr__(self, "_row", row.copy())
        object.__setattr__(self, "_modes", modes[:, :self.modes].copy())
        object.__setattr__(self, "_model", (rpar.copy(), ipar.copy()))

    def array(self):
        """The flat array of the core's layout 'tank' (shape as its code)."""
        values = {name: getattr(self, name) for name in _tables.layout("tank")}
        values["shape"] = _tables.code("tank_shapes", self.shape)
        values["roof_contact"] = _tables.code("roof_contacts", self.roof_contact)
        return _tables.pack("tank", values)

    @classmethod
    def from_array(cls, array):
        """The tank of a flat array in the core's layout 'tank'."""
        kinds = {f.name: f.type for f in dataclasses.fields(cls)}
        values = {name: (int(x) if kinds[name] == "int" else float(x))
                  for name, x in _tables.unpack("tank", array).items()}
        values["shape"] = _tables.codes("tank_shapes")[int(values["shape"])]
        values["roof_contact"] = _tables.codes("roof_contacts")[int(values["roof_contact"])]
        return cls(**values)

    @property
    def properties(self):
        """Everything the core derives from the tank ({name: value}, the columns of tank.csv
        without their units): masses, pendulum, heights, supports, theta0, the groups."""
        return {column_name(c): float(v) for c, v in zip(_tables.columns("tank_si"), self._row)}

    @property
    def sloshing_period(self):
        """Period of the first sloshing mode in a rigid tank, 2 pi sqrt(l/g) [s]."""
        return self.properties["sloshing_period"]

    @property
    def convective_mass(self):
        """The sloshing (pendulum) mass m of eq (2) [kg]."""
        return self.properties["sloshing_mass"]

    @property
    def impulsive_mass(self):
        """The rigid liquid mass m0 = m_F - m of eq (3) [kg] (with modes = N: m_F minus the N
        modal masses)."""
        return self.properties["rigid_mass"]

    @property
    def convective_height(self):
        """Height of the convective wall-pressure resultant above the bottom [m]."""
        return self.properties["convective_height"]

    @property
    def impulsive_height(self):
        """Height of the impulsive wall-pressure resultant above the bottom [m]."""
        return self.properties["impulsive_height"]

    def _modal(self, column):
        return self._modes[_tables.columns("tank_modes").index(column)].copy()

    @property
    def sloshing_periods(self):
        """Periods of the sloshing modes 1..modes in a rigid tank [s] (mode 1: sloshing_period)."""
        return self._modal("period [s]")

    @property
    def convective_masses(self):
        """The modal (convective) masses of modes 1..modes [kg] (mode 1: convective_mass)."""
        return self._modal("convective_mass [kg]")

    @property
    def convective_heights(self):
        """Heights above the bottom of the modes' wall-pressure resultants [m]."""
        return self._modal("convective_height [m]")

    @property
    def theta0(self):
        """The pendulum angle at which the linear wave reaches the roof [rad]."""
        return self.properties["theta0"]

    def parameters(self, ground_motion=None) -> Parameters:
        """The dimensionless model (Parameters) of the tank; with harmonic ground motion, its
        excitation A, rho as well."""
        A = rho = 0.0
        if ground_motion is not None:
            A, rho, status, message = _bridge.tank_excitation(self.array(),
                                                              ground_arrays(ground_motion)[0])
            check_status(status, message)
            A, rho = float(A), float(rho)
        return Parameters.from_array(*self._model, A=A, rho=rho)

    def design_codes(self, ground_motion=None) -> DesignCodes:
        """The tank's sloshing parameters by sloshdyn and by API 650 Annex E, EN 1998-4 Annex A
        and ACI 350.3 side by side (DesignCodes); wave heights from the ground motion's
        pseudo-spectral acceleration when one is given, or from a code design spectrum
        (sloshdyn.design.DesignSpectrum: its Sa at the tank's sloshing damping)."""
        if isinstance(ground_motion, DesignSpectrum):
            codes, status, message = _bridge.design_codes_spectrum(self.array(),
                                                                   ground_motion.design.array())
        else:
            ground, samples = ground_arrays(ground_motion)
            codes, status, message = _bridge.design_codes(self.array(),
                                                          int(ground_motion is not None),
                                                          ground, samples)
        check_status(status, message)
        # the modal sums (the last two sources) only for a tank with modes > 1
        return DesignCodes(codes[:, :None if self.modes > 1 else -2].copy())


@dataclass(frozen=True)
class DesignCodes:
    """Rows: sloshdyn, API 650, EC8-4, ACI 350.3 (and for a tank with modes > 1 sloshdyn's
    sums over the modes, 'modes SRSS' and 'modes ABS'); columns: convective_period [s],
    convective_mass [kg], impulsive_mass [kg], convective_height [m], impulsive_height [m],
    wave_height [m] (NaN where a source gives none)."""

    table: np.ndarray   #: (6, 4) or (6, 6), the core's 'design_codes' layout

    @property
    def sources(self):
        return list(_tables.names("source")[0])[:self.table.shape[1]]

    @property
    def columns(self):
        return [column_name(c) for c in _tables.columns("design_codes")[1:]]

    def value(self, source, column):
        return float(self.table[self.columns.index(column), self.sources.index(source)])

    def difference(self, source, column):
        """(source - sloshdyn)/sloshdyn in %."""
        ours = self.value("sloshdyn", column)
        return 100 * (self.value(source, column) - ours) / ours

    def __str__(self):
        """The table the executable prints (the core writes it): values, and each code's
        difference from sloshdyn in %."""
        full = np.full((self.table.shape[0], len(_tables.names("source")[0])), np.nan)
        full[:, :self.table.shape[1]] = self.table
        text = _bridge.design_codes_text(full)
        return (text.decode() if isinstance(text, bytes) else str(text)).rstrip()
