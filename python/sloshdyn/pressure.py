"""The hydrodynamic pressure on the wall and the base of a rigid circular tank under a horizontal
acceleration (`wall_pressure`): impulsive and convective (modes 1..N)
closed forms of potential flow (EN 1998-4 Annex A.2.1, Veletsos), the hoop force per unit
height, and the resultants of each component. Every number comes from the Fortran core
(sloshdyn_wall_pressure, the tables 'wall_pressure', 'base_pressure' and
'pressure_resultants'); docs/model.md, "Hydrodynamic wall and base pressure", gives the
formulas and their sources.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from . import _checks, _core, _tables
from ._tables import column_name
from ._errors import check_status
from .seismic import PEAK_LOADS, SeismicResponse
from .tank import Tank

_bridge = _core.sloshdyn_bridge_pressure
#: points of the default profiles: evenly spaced heights on the wall and radii on the base
DEFAULT_HEIGHTS = 41
DEFAULT_RADII = 21



def _units(table):
    return {column_name(c): c.split(" [")[1].rstrip("]") for c in _tables.columns(table) if " [" in c}


@dataclass(frozen=True)
class _Profiles:
    """The pressure on the wall at the heights z [m] and on the base at the radii r [m], at the
    angle [rad] (the 'wall_pressure' and 'base_pressure' tables)."""

    angle: float
    z: np.ndarray
    impulsive_pressure: np.ndarray
    convective_pressure: np.ndarray
    total_pressure: np.ndarray
    hoop_force: np.ndarray
    r: np.ndarray
    base_impulsive_pressure: np.ndarray
    base_convective_pressure: np.ndarray
    base_total_pressure: np.ndarray


@dataclass(frozen=True)
class WallPressure(_Profiles):
    """The hydrodynamic pressure of a rigid circular tank under the impulsive acceleration A_g
    and the convective accelerations A_1..A_N [m/s^2], at the angle `angle` [rad] around the
    axis from the direction of the inertia force (every pressure is its value at angle 0
    times cos(angle)), modes combined by `combination` ('srss': the modes and then impulsive
    and convective by the square root of the sum of squares; 'sum': algebraic sums).

    On the wall, at the heights `z` [m] above the bottom: impulsive_pressure,
    convective_pressure, total_pressure [Pa] and hoop_force [N/m] (total pressure times R);
    on the base, at the radii `r` [m]: base_impulsive_pressure, base_convective_pressure,
    base_total_pressure [Pa]. Resultants (the table 'pressure_resultants', one row per
    component, impulsive first): impulsive_mass [kg], impulsive_height and
    impulsive_height_ibp [m] (of the resultant excluding and including the base pressure),
    convective_masses, convective_heights, convective_heights_ibp (modes 1..N). `units`
    names the unit of each attribute; wall_table, base_table, resultant_table hold the core's
    tables (one column per point or component)."""

    tank: object
    impulsive_acceleration: float
    convective_accelerations: np.ndarray
    combination: str
    impulsive_mass: float
    impulsive_height: float
    impulsive_height_ibp: float
    convective_masses: np.ndarray
    convective_heights: np.ndarray
    convective_heights_ibp: np.ndarray
    wall_table: np.ndarray = dataclasses.field(repr=False)
    base_table: np.ndarray = dataclasses.field(repr=False)
    resultant_table: np.ndarray = dataclasses.field(repr=False)

    @property
    def units(self):
        """{attribute: unit} of the profiles (the core's column units)."""
        units = _units("wall_pressure")
        units.update({f"base_{k}" if k != "r" else k: v
                      for k, v in _units("base_pressure").items()})
        units.update(impulsive_acceleration="m/s^2", convective_accelerations="m/s^2",
                     angle="rad", impulsive_mass="kg", impulsive_height="m",
                     impulsive_height_ibp="m", convective_masses="kg", convective_heights="m",
                     convective_heights_ibp="m")
        return units

    def plot(self):
        """The pressure profile on the wall: impulsive, convective and total [kPa] against the
        height [m] (a matplotlib Figure)."""
        from . import plotting   # noqa: F401  the plot extra; sets the Agg backend when headless
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(5, 5))
        for name, style in (("impulsive_pressure", "-"), ("convective_pressure", "--"),
                            ("total_pressure", "-")):
            ax.plot(getattr(self, name)/1e3, self.z, style, label=name.replace("_", " "),
                    lw=2.2 if name == "total_pressure" else 1.4)
        ax.set_xlabel("hydrodynamic pressure on the wall [kPa]")
        ax.set_ylabel("height above the bottom z [m]")
        ax.set_ylim(0, self.tank.liquid_depth)
        ax.axvline(0, color="0.6", lw=0.8)
        modes = len(self.convective_accelerations)
        ax.set_title(f"R = {self.tank.radius:g} m, H = {self.tank.liquid_depth:g} m: "
                     f"A_g = {self.impulsive_acceleration:.4g} m/s$^2$, {modes} convective "
                     f"mode{'s' if modes != 1 else ''} ({self.combination}), "
                     f"θ = {self.angle:.3g} rad", fontsize=9)
        ax.legend()
        ax.grid(alpha=0.3)
        fig.tight_layout()
        return fig


def wall_pressure(tank, impulsive_acceleration, convective_accelerations=(), *, heights=None,
                  radii=None, angle=0.0, combination="srss") -> WallPressure:
    """The hydrodynamic pressure of a rigid circular `tank` (a sloshdyn.Tank) under the
    impulsive acceleration A_g [m/s^2] (the tank's, e.g. the impulsive spectral acceleration)
    and the convective accelerations A_1..A_N [m/s^2] of sloshing modes 1..N (N <= 10, e.g.
    their convective spectral accelerations; independent of tank.modes), on the wall at
    `heights` [m] (default 41 evenly spaced from the bottom to the surface) and on the base
    at `radii` [m] (default 21 from the axis to the wall), at `angle` [rad] (WallPressure)."""
    _checks.instance("tank", tank, Tank)
    a_g = _checks.real("impulsive_acceleration", impulsive_acceleration)
    a_n = _checks.reals("convective_accelerations", convective_accelerations, ndim=1)
    theta = _checks.real("angle", angle)
    combination = _checks.choice("combination", combination,
                                 list(_tables.codes("pressure_combinations").values()))
    z = (np.linspace(0.0, tank.liquid_depth, DEFAULT_HEIGHTS) if heights is None
         else _checks.reals("heights", heights, ndim=1))
    r = (np.linspace(0.0, tank.radius, DEFAULT_RADII) if radii is None
         else _checks.reals("radii", radii, ndim=1))
    wall, base, resultants, status, message = _bridge.pressure_tables(
        tank.array(), a_g, a_n, theta, _tables.code("pressure_combinations", combination), z, r)
    check_status(status, message)
    profile = {column_name(c): row.copy() for c, row in zip(_tables.columns("wall_pressure"), wall)}
    floor = {("base_" + column_name(c) if column_name(c) != "r" else "r"): row.copy()
             for c, row in zip(_tables.columns("base_pressure"), base)}
    parts = {column_name(c): row for c, row in zip(_tables.columns("pressure_resultants"), resultants)}
    return WallPressure(
        tank=tank, impulsive_acceleration=a_g, convective_accelerations=a_n.copy(), angle=theta,
        combination=combination, **profile, **floor,
        impulsive_mass=float(parts["mass"][0]), impulsive_height=float(parts["height_ebp"][0]),
        impulsive_height_ibp=float(parts["height_ibp"][0]),
        convective_masses=parts["mass"][1:].copy(),
        convective_heights=parts["height_ebp"][1:].copy(),
        convective_heights_ibp=parts["height_ibp"][1:].copy(),
        wall_table=wall, base_table=base, resultant_table=resultants)


@dataclass(frozen=True)
class SeismicPressures(_Profiles):
    """The hydrodynamic pressure at instants of a seismic run (`seismic_pressures`): at its
    load peaks exactly (the accelerations the run kept), or at the run's output time `t` [s]
    nearest each requested time: the tank's absolute acceleration tank_acceleration [m/s^2]
    and the sloshing modes' mode_accelerations [m/s^2] (shape (instants, modes)), the
    base_shear [N], overturning_moment and overturning_moment_ibp [N m] (excluding and
    including the base pressure) that the pressures and the shell's inertia give; on the wall
    at `z` [m] and the base at `r` [m], arrays of shape (instants, points):
    impulsive_pressure (the part moving with the tank), convective_pressure (the modes'),
    total_pressure [Pa], hoop_force [N/m], base_impulsive_pressure, base_convective_pressure,
    base_total_pressure [Pa], at `angle` [rad]; `method`, the integration method of the run
    ('auto' resolved)."""

    times: np.ndarray
    t: np.ndarray
    tank_acceleration: np.ndarray
    mode_accelerations: np.ndarray
    base_shear: np.ndarray
    overturning_moment: np.ndarray
    overturning_moment_ibp: np.ndarray
    method: str


def seismic_pressures(response, *, times=None, heights=None, radii=None,
                      angle=0.0) -> SeismicPressures:
    """The pressure on the wall and base at instants of a seismic run (a SeismicResponse of
    seismic_response): by default at the peaks of its base shear and overturning moments
    (excluding and including the base pressure), from the accelerations the run kept there;
    at given `times` [s], at the output time nearest each (from the run's table; modes 2..N as
    the run computed them). Nothing is integrated again."""
    _checks.instance("response", response, SeismicResponse)
    tank = response.tank
    z = (np.linspace(0.0, tank.liquid_depth, DEFAULT_HEIGHTS) if heights is None
         else _checks.reals("heights", heights, ndim=1))
    r = (np.linspace(0.0, tank.radius, DEFAULT_RADII) if radii is None
         else _checks.reals("radii", radii, ndim=1))
    theta = _checks.real("angle", angle)
    rows = len(_tables.columns("seismic_peak_instants"))
    if times is None:
        instants = np.zeros((rows, len(PEAK_LOADS)))
        for k, load in enumerate(PEAK_LOADS):
            t, a_t, a_n = response.peak_instants[load]
            instants[:2, k] = t, a_t
            instants[2:2 + len(a_n), k] = a_n
        times = instants[0].copy()
    else:
        times = _checks.reals("times", times, ndim=1)
        instants, status, message = _bridge.output_instants(
            tank.array(), response.t, response.tank_acceleration,
            response.convective_acceleration, times)
        check_status(status, message)
    loads, wall, base, status, message = _bridge.instant_pressures(tank.array(), instants, z, r,
                                                                   theta)
    check_status(status, message)
    columns = {column_name(c): row.copy() for c, row in zip(_tables.columns("pressure_instants"),
                                                            loads)}
    profile = {column_name(c): wall[j].T.copy()
               for j, c in enumerate(_tables.columns("wall_pressure")) if column_name(c) != "z"}
    floor = {"base_" + column_name(c): base[j].T.copy()
             for j, c in enumerate(_tables.columns("base_pressure")) if column_name(c) != "r"}
    return SeismicPressures(times=times.copy(),
                            mode_accelerations=instants[2:2 + tank.modes].T.copy(),
                            angle=theta, z=z.copy(), r=r.copy(), **columns, **profile, **floor,
                            method=response.method)
