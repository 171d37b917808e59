"""A real tank under ground motion, in SI units: the tank (`Tank`), the ground motion
(`GroundMotion`: a record or harmonic motion, scaled, with its response spectrum), the seismic
response (`seismic_response`: time histories and peaks of the physical loads) and the design-code
cross-check (`Tank.design_codes`). Every number comes from the Fortran core (sloshdyn_vessel,
sloshdyn_ground, sloshdyn_seismic); the namelist groups &tank, &ground_motion and &seismic are
the same objects (README, "Namelist reference"), and docs/model.md gives the relations.
"""

from __future__ import annotations

import dataclasses
import math
import os
import stat
from dataclasses import dataclass

import numpy as np

from ._cancel import cancellable
from . import _checks, _core, _tables
from ._errors import InputError, SloshdynError, check_status
from ._settings import convert_fields
from .parameters import Parameters
from .design import Design, DesignCheck, DesignSpectrum, design_check
from .simulation import Integration, Steady

_bridge = _core.sloshdyn_bridge_seismic
_TANK_DEFAULTS = _tables.defaults("tank")
#: the damping ratio of a spectral acceleration when none is given: the convective 0.5 % of
#: the design codes, the core's one default (sloshdyn_vessel convective_damping, a tank's
#: sloshing_damping; &ground_motion target_damping, &study spectral_damping)
CONVECTIVE_DAMPING = float(_TANK_DEFAULTS["sloshing_damping"])
#: the largest record file the core reads (sloshdyn_records max_record_bytes, 1 GiB)
_MAX_RECORD_BYTES = 1 << 30


def _name(column):
    """The attribute name of a column: its name without the unit, 't [s]' -> 't'."""
    return column.split(" [")[0]


_real = _checks.real


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

    def __post_init__(self):
        convert_fields(self)
        if self.shape not in _tables.codes("tank_shapes").values():
            raise InputError(f"shape = {self.shape!r} is not known; allowed: "
                             + ", ".join(_tables.codes("tank_shapes").values()))
        row, modes, rpar, ipar, status, message = _bridge.tank_properties(self.array())
        check_status(status, message)
        object.__setattr__(self, "_row", row.copy())
        object.__setattr__(self, "_modes", modes[:, :self.modes].copy())
        object.__setattr__(self, "_model", (rpar.copy(), ipar.copy()))

    def array(self):
        """The flat array of the core's layout 'tank' (shape as its code)."""
        values = {name: getattr(self, name) for name in _tables.layout("tank")}
        values["shape"] = _tables.code("tank_shapes", self.shape)
        return _tables.pack("tank", values)

    @classmethod
    def from_array(cls, array):
        """The tank of a flat array in the core's layout 'tank'."""
        kinds = {f.name: f.type for f in dataclasses.fields(cls)}
        values = {name: (int(x) if kinds[name] == "int" else float(x))
                  for name, x in _tables.unpack("tank", array).items()}
        values["shape"] = _tables.codes("tank_shapes")[int(values["shape"])]
        return cls(**values)

    @property
    def properties(self):
        """Everything the core derives from the tank ({name: value}, the columns of tank.csv
        without their units): masses, pendulum, heights, supports, theta0, the groups."""
        return {_name(c): float(v) for c, v in zip(_tables.columns("tank_si"), self._row)}

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

    def wall_pressure(self, impulsive_acceleration, convective_accelerations=(), heights=None,
                      angle=0.0, *, radii=None, combination="srss"):
        """The hydrodynamic pressure on the wall and base under the impulsive acceleration and
        the convective accelerations of modes 1..N [m/s^2] (pressure.wall_pressure)."""
        from .pressure import wall_pressure
        return wall_pressure(self, impulsive_acceleration, convective_accelerations,
                             heights=heights, radii=radii, angle=angle, combination=combination)

    def parameters(self, ground_motion=None) -> Parameters:
        """The dimensionless model (Parameters) of the tank; with harmonic ground motion, its
        excitation A, rho as well."""
        A = rho = 0.0
        if ground_motion is not None:
            A, rho, status, message = _bridge.tank_excitation(self.array(),
                                                              _ground_arrays(ground_motion)[0])
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
            ground, samples = _ground_arrays(ground_motion)
            codes, status, message = _bridge.design_codes(self.array(),
                                                          int(ground_motion is not None),
                                                          ground, samples)
        check_status(status, message)
        # the modal sums (the last two sources) only for a tank with modes > 1
        return DesignCodes(codes[:, :None if self.modes > 1 else -2].copy())

    def design_check(self, motion=None, *, design: Design | None = None,
                     response=None) -> DesignCheck:
        """Each code's seismic loads and freeboard check beside sloshdyn's (DesignCheck):
        sloshdyn.design_check(tank, motion, design=..., response=...)."""
        return design_check(self, motion, design=design, response=response)


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
        return [_name(c) for c in _tables.columns("design_codes")[1:]]

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


class GroundMotion:
    """Horizontal ground acceleration in SI units: a record sampled at a uniform step dt [s]
    (piecewise linear between samples, at rest after the last one), or harmonic motion
    u'' = -peak_acceleration sin(2 pi frequency t).

    GroundMotion(dt=0.01, acceleration=a)                 a record, a in `units` (g)
    GroundMotion.from_file('x.AT2')                       PEER NGA .AT2 (in g)
    GroundMotion.from_file('x.csv', units='cm/s^2')       two columns: time [s], acceleration
    GroundMotion.harmonic(0.2, 0.3)                       peak 0.2 g at 0.3 Hz

    Accelerations given to sloshdyn are in `units`, 'g' unless told (as in &ground_motion);
    the attributes and every result are in SI units (m/s^2).
    """

    def __init__(self, dt=None, acceleration=None, *, units="g", peak_acceleration=None,
                 frequency=None):
        factor = acceleration_factor(units)
        if acceleration is not None or dt is not None:
            if peak_acceleration is not None or frequency is not None:
                raise InputError("give a record (dt, acceleration) or harmonic motion "
                                 "(peak_acceleration, frequency), not both")
            if acceleration is None or dt is None:
                raise InputError("a record needs both dt [s] and acceleration (an array)")
            samples = _checks.reals("acceleration", acceleration, ndim=1, finite=False).copy()
            self.kind, self.dt = "record", _real("dt", dt)
            self.acceleration = samples * factor
            self.peak_acceleration = self.frequency = 0.0
        else:
            if peak_acceleration is None or frequency is None:
                raise InputError("harmonic motion needs peak_acceleration and frequency [Hz]")
            self.kind, self.dt, self.acceleration = "harmonic", 0.0, np.zeros(0)
            self.peak_acceleration = _real("peak_acceleration", peak_acceleration) * factor
            self.frequency = _real("frequency", frequency)
        self.acceleration.flags.writeable = False
        status, message = _bridge.check_ground(*self._arrays())
        check_status(status, message)

    @classmethod
    def harmonic(cls, peak_acceleration, frequency, units="g"):
        """u'' = -peak_acceleration sin(2 pi frequency t), frequency in Hz."""
        return cls(peak_acceleration=peak_acceleration, frequency=frequency, units=units)

    @classmethod
    def from_file(cls, path, format="auto", units="g"):
        """A record file: 'at2' (PEER NGA, values in g), 'columns' (time [s], acceleration in
        `units`; commas, semicolons or blanks; # comments; one first line of column names) or
        'auto' (by the .AT2 extension). Only a regular file of at most 1 GiB is read (a FIFO,
        a device or a directory is refused before it is opened); it is never modified. Its
        errors are input errors (exit code 3 in sloshdyn-py)."""
        path = _checks.path("path", path)
        format, units = _checks.text("format", format), _checks.text("units", units)
        try:
            dt, samples, n, status, message = _bridge.read_record(
                os.fsencode(path), format, units, _fields_in(path))
            check_status(status, message)
            ground = cls(dt=float(dt), acceleration=samples[:n].copy(), units="m/s^2")
            ground.name = os.path.basename(os.fsdecode(path))
            return ground
        except SloshdynError as exc:
            exc.reading = True
            raise

    def _arrays(self):
        """The flat arrays of the bridge: the core's layout 'ground' and the samples [m/s^2]."""
        ground = _tables.pack("ground", {"kind": _tables.code("ground_kinds", self.kind),
                                         "peak_acceleration": self.peak_acceleration,
                                         "frequency": self.frequency, "dt": self.dt,
                                         "scale_factor": self.scale_factor})
        return ground, np.asarray(self.acceleration, dtype=np.float64)

    @classmethod
    def _from_arrays(cls, ground, samples):
        """The ground motion of the bridge's arrays (SI units)."""
        values = _tables.unpack("ground", ground)
        if _tables.codes("ground_kinds")[int(values["kind"])] == "record":
            ground = cls(dt=float(values["dt"]), acceleration=samples, units="m/s^2")
        else:
            ground = cls(peak_acceleration=float(values["peak_acceleration"]),
                         frequency=float(values["frequency"]), units="m/s^2")
        ground.scale_factor = float(values["scale_factor"])
        return ground

    @property
    def duration(self):
        """Length of a record [s] (0 for harmonic motion)."""
        return self.dt * (len(self.acceleration) - 1) if self.kind == "record" else 0.0

    @property
    def time(self):
        """The times of a record's samples [s]."""
        return self.dt * np.arange(len(self.acceleration))

    @property
    def pga(self):
        """Peak ground acceleration [m/s^2]."""
        if self.kind == "record":
            return float(np.max(np.abs(self.acceleration)))
        return self.peak_acceleration

    def scaled(self, factor=None, *, pga=None, sa=None, period=None,
               damping=CONVECTIVE_DAMPING, units="g"):
        """A copy scaled by a factor, to a peak ground acceleration pga, or to a pseudo-spectral
        acceleration sa at period [s] for the damping ratio (default 0.5 %, the convective
        damping, as &ground_motion target_damping); give one; pga and sa in `units` (default
        g, as &ground_motion). The copy's `scale_factor` is the factor applied and `scaling`
        says to what, with the damping and units (its repr shows them)."""
        to_si = acceleration_factor(units)
        if sa is not None and period is None:
            raise InputError("sa needs the period [s] at which it applies")
        ground, samples = self._arrays()
        factor = 1.0 if factor is None else _real("factor", factor)
        damping = _real("damping", damping)
        scaled, scaled_samples, status, message = cancellable(
            _bridge.scale_ground, ground, samples, factor,
            0.0 if pga is None else _real("pga", pga) * to_si,
            0.0 if sa is None else _real("sa", sa) * to_si,
            0.0 if period is None else _real("period", period), damping)
        check_status(status, message)
        copy = GroundMotion._from_arrays(scaled, scaled_samples.copy())
        copy.name = self.name
        copy.scale_factor = copy.pga / self.pga if (pga or sa) and self.pga > 0 else factor
        if pga is not None:
            copy.scaling = f"PGA = {pga:g} {units}"
        elif sa is not None:
            copy.scaling = f"Sa({period:g} s, {100 * damping:g} % damping) = {sa:g} {units}"
        else:
            copy.scaling = f"factor {factor:g}"
        return copy

    def response_spectrum(self, periods, damping=CONVECTIVE_DAMPING, tail_duration=None,
                          duration=None):
        """Peak responses of linear oscillators (exact for the piecewise linear record) at
        `periods` [s] for the damping ratio (default 0.5 %, the convective damping, as scaled):
        Spectrum(periods, sd [m], sv [m/s], psa [m/s^2]). A free-vibration tail
        of tail_duration [s] (default 5 times the longest period) follows the record; harmonic
        motion is sampled over `duration` [s] (default: the core's, 40 forcing periods)."""
        periods = np.atleast_1d(_checks.reals("periods", periods))
        if periods.ndim != 1:
            raise InputError(f"periods has shape {periods.shape}: give a number or a 1-D array")
        _checks.output_size("periods", periods.size, 3)
        if tail_duration is None:
            tail_duration = 5 * float(np.max(periods)) if periods.size else 0.0
        sd, sv, psa, status, message = cancellable(
            _bridge.ground_spectrum, *self._arrays(), periods, _real("damping", damping),
            _real("tail_duration", tail_duration),
            _checks.optional_real("duration", duration, 0.0))
        check_status(status, message)
        return Spectrum(periods, sd.copy(), sv.copy(), psa.copy(), float(damping))

    #: the factor `scaled` applied (1 unscaled) and to what, with the damping and units
    scale_factor, scaling = 1.0, ""
    #: the record's file name (from_file; a scaled copy keeps it), '' when not from a file
    name = ""

    def __repr__(self):
        scaled = (f", scaled by {self.scale_factor:.6g} ({self.scaling})" if self.scaling
                  else "")
        if self.kind == "record":
            return (f"GroundMotion(record: {len(self.acceleration)} samples, dt = {self.dt} s, "
                    f"PGA = {self.pga:.4g} m/s^2{scaled})")
        return (f"GroundMotion(harmonic: peak {self.peak_acceleration:.4g} m/s^2 at "
                f"{self.frequency:.4g} Hz{scaled})")


def _fields_in(path):
    """The number of fields (separated by blanks, commas or semicolons) of a regular file of at most _MAX_RECORD_BYTES (a
    bound on its samples), counted in blocks; 2 for anything else, which the core refuses with
    its message without reading it (a FIFO would block, /dev/zero never ends)."""
    try:
        info = os.stat(path)
    except OSError:
        return 2
    if not stat.S_ISREG(info.st_mode) or info.st_size > _MAX_RECORD_BYTES:
        return 2
    count, tail = 0, b""
    try:
        with open(path, "rb") as f:
            for block in iter(lambda: f.read(1 << 20), b""):
                block = block.replace(b",", b" ").replace(b";", b" ")   # the core's separators
                fields = (tail + block).split()
                tail = fields.pop() if fields and not block[-1:].isspace() else b""
                count += len(fields)
    except OSError:
        return 2
    return max(2, count + bool(tail))


def acceleration_factor(units) -> float:
    """The factor that turns an acceleration in units 'g' (9.80665 m/s^2), 'm/s^2' or
    'cm/s^2' into m/s^2."""
    factor, status, message = _bridge.acceleration_units(_checks.text("units", units))
    check_status(status, message)
    return float(factor)


@dataclass(frozen=True)
class Spectrum:
    """A response spectrum: at each period [s], peak relative displacement sd [m],
    pseudo-velocity sv [m/s] and pseudo-acceleration psa [m/s^2], for the damping ratio."""

    periods: np.ndarray
    sd: np.ndarray
    sv: np.ndarray
    psa: np.ndarray
    damping: float


def _ground_arrays(ground_motion):
    if ground_motion is None:
        return np.zeros(len(_tables.layout("ground"))), np.zeros(0)
    if not isinstance(ground_motion, GroundMotion):
        _checks.instance("ground_motion", ground_motion, GroundMotion)
    return ground_motion._arrays()


@dataclass(frozen=True)
class SeismicResponse:
    """The response of a tank to ground motion from rest, SI units. One array per quantity
    over the output times `t` [s]: ground_acceleration [m/s^2], sloshing_displacement [m] (of
    the sloshing mass relative to the tank), wave_height [m] (at the wall), pendulum_angle
    [rad], tank_drift [m] (relative to the ground), impact_force [N] (roof/walls on the
    liquid), base_shear [N] and overturning_moment [N m] (about the tank bottom), x1, x2,
    free_wave_height [m] (the wave at the wall of the tank without a roof, summed over the
    modes, what the roof verdict judges) (the columns of seismic.csv, `table` holds them in order); `peak_table` (the columns
    of seismic_peaks.csv: also the free wave's peak free_wave_height, roof_excess, the roof loads
    roof_head, roof_uplift_force, confined_convective_mass, and the run's scale_factor,
    sa_sloshing_period [m/s^2] and beta_sensitive), `peaks` {quantity: (largest |value|, its
    time [s])}, roof_reached, first_roof_time [s], roof_impacts (of the free wave, without a
    roof: independent of beta and delta), beta_sensitive (the model's loads depend on beta and
    delta; `warnings` says so); t_end [s], the end of the run as asked (the output times are
    computed in the model's time, so t[-1] can differ from it in the last bit); `method`, the
    integration method used ('auto' resolved)."""

    tank: Tank
    ground_motion: GroundMotion
    t: np.ndarray
    ground_acceleration: np.ndarray
    sloshing_displacement: np.ndarray
    wave_height: np.ndarray
    pendulum_angle: np.ndarray
    tank_drift: np.ndarray
    impact_force: np.ndarray
    base_shear: np.ndarray
    overturning_moment: np.ndarray
    x1: np.ndarray
    x2: np.ndarray
    free_wave_height: np.ndarray
    table: np.ndarray = dataclasses.field(repr=False)
    peak_table: dict = dataclasses.field(repr=False)
    peaks: dict = dataclasses.field(repr=False)
    roof_reached: bool
    first_roof_time: float
    roof_impacts: int
    beta_sensitive: bool
    t_end: float
    method: str

    @classmethod
    def _from_tables(cls, tank, ground_motion, table, peaks, t_end, method):
        """The response from the core's 'seismic' table and 'seismic_peaks' row."""
        peak_table = {_name(c): float(v) for c, v in zip(_tables.columns("seismic_peaks"),
                                                          peaks)}
        return cls(tank=tank, ground_motion=ground_motion, table=table,
                   **{_name(column): row for column, row in zip(_tables.columns("seismic"),
                                                                 table)},
                   peak_table=peak_table,
                   peaks={name[len("peak_"):]: (value, peak_table["time_" + name[5:]])
                          for name, value in peak_table.items() if name.startswith("peak_")},
                   roof_reached=bool(peak_table["roof_reached"]),
                   first_roof_time=peak_table["first_roof_time"],
                   roof_impacts=int(peak_table["roof_impacts"]),
                   beta_sensitive=bool(peak_table["beta_sensitive"]), t_end=float(t_end),
                   method=method)

    @property
    def columns(self):
        return [_name(c) for c in _tables.columns("seismic")]

    @property
    def warnings(self):
        """What the numbers should be read with: ['...'] when the model's loads are sensitive
        to beta and delta (its wall force reaches 0.001 m g; docs/model.md, "Choice of beta
        and delta"), else []."""
        if not self.beta_sensitive:
            return []
        return ["the model's impact force, base shear and overturning moment are sensitive to "
                "impact_stiffness (beta) and impact_damping (delta): its wall acts (impact force "
                ">= 0.001 m g); the roof verdict and roof loads are not"]

    def __repr__(self):
        wave = self.peaks["wave_height"]
        return (f"SeismicResponse({len(self.t)} outputs to t = {self.t[-1]:.4g} s; peak wave "
                f"height {wave[0]:.4g} m at {wave[1]:.4g} s, freeboard {self.tank.freeboard} m, "
                f"roof {'reached' if self.roof_reached else 'not reached'}"
                f"{'; sensitive to beta and delta' if self.beta_sensitive else ''})")


@dataclass(frozen=True)
class SeismicTimes:
    """The output times of a seismic response: n_out evenly spaced from 0 to t_end [s]."""

    t_end: float
    n_out: int


def seismic_defaults(tank: Tank, ground_motion: GroundMotion, t_end=None,
                     n_out=None) -> SeismicTimes:
    """t_end [s] and n_out as seismic_response chooses them: t_end = the record plus 5 sloshing
    periods (harmonic: 40 forcing periods); outputs at the finest of the record's step, 50 per
    sloshing (or forcing) period and 20 per period of the tank on its supports."""
    _checks.instance("tank", tank, Tank)
    ground, samples = _ground_arrays(ground_motion)
    chosen, status, message = _bridge.seismic_defaults(
        tank.array(), ground, samples, 0.0 if t_end is None else _real("t_end", t_end),
        0 if n_out is None else _checks.integer("n_out", n_out))
    check_status(status, message)
    return SeismicTimes(float(chosen[0]), int(chosen[1]))


def seismic_response(tank: Tank, ground_motion: GroundMotion, t_end=None, n_out=None, *,
                     integration: Integration = Integration()) -> SeismicResponse:
    """The tank at rest at t = 0 under the ground motion, to t_end [s] (default: the record
    plus 5 sloshing periods), at n_out evenly spaced times (default: seismic_defaults): a
    SeismicResponse. Its peaks are those of the integrated solution, located between the
    integrator's steps (independent of n_out); the roof contact is judged on the free wave
    (no roof), so it does not depend on impact_stiffness or impact_damping."""
    _checks.instance("tank", tank, Tank)
    _checks.instance("integration", integration, Integration)
    times = seismic_defaults(tank, ground_motion, t_end, n_out)
    t_end, n_out = times.t_end, times.n_out
    _checks.output_size("n_out", n_out, len(_tables.columns("seismic")))
    ground, samples = _ground_arrays(ground_motion)
    table, peaks, status, message = cancellable(_bridge.seismic_response,
        tank.array(), ground, samples, t_end, n_out, integration.array())
    check_status(status, message)
    return SeismicResponse._from_tables(tank, ground_motion, table.copy(), peaks.copy(), t_end,
                                       integration.method_used)


@dataclass(frozen=True)
class HarmonicSweep:
    """Steady states of a tank under harmonic ground motion of one peak acceleration at each
    frequency: `points` (SteadyState, dimensionless, as frequency_sweep gives) and one SI array
    per column of harmonic_sweep.csv (`table` holds them in order): frequency [Hz],
    peak_ground_acceleration [m/s^2], wave_height [m], sloshing_displacement [m],
    pendulum_angle [rad], tank_drift [m] (their largest values over the measuring window),
    roof_reached (1/0: the free wave's, as seismic_response judges it), motion (code), period
    [forcing periods], free_wave_height [m] (the largest wave at the wall of the steady state of
    the tank without a roof, from rest, independent of beta and delta); y_final, the final state
    (None for independent points); `method`, the integration method used ('auto' resolved)."""

    tank: Tank
    points: list
    frequency: np.ndarray
    peak_ground_acceleration: np.ndarray
    wave_height: np.ndarray
    sloshing_displacement: np.ndarray
    pendulum_angle: np.ndarray
    tank_drift: np.ndarray
    roof_reached: np.ndarray
    motion: np.ndarray
    period: np.ndarray
    free_wave_height: np.ndarray
    table: np.ndarray = dataclasses.field(repr=False)
    y_final: np.ndarray
    method: str

    @classmethod
    def _from_table(cls, tank, points, table, y_final, method):
        """The sweep from the core's 'harmonic_sweep' table."""
        return cls(tank=tank, points=points, table=table, y_final=y_final, method=method,
                   **{_name(column): row for column, row in zip(
                       _tables.columns("harmonic_sweep"), table)})


def harmonic_sweep(tank: Tank, peak_acceleration, frequencies, y0=None, *, units="g",
                   steady: Steady = Steady(), integration: Integration = Integration(),
                   progress=False, threads=1, start_from="previous") -> HarmonicSweep:
    """Steady states of the tank under harmonic ground motion of constant peak_acceleration (in
    `units`) at each of the frequencies [Hz], in the given order (ascending = up); start_from,
    threads and steady as for sloshdyn.frequency_sweep. A HarmonicSweep."""
    from .simulation import run_sweep

    _checks.instance("tank", tank, Tank)
    _checks.instance("integration", integration, Integration)
    _checks.instance("steady", steady, Steady)
    frequencies = _checks.reals("frequencies", frequencies)
    if frequencies.ndim != 1 or frequencies.size == 0:
        raise InputError(f"frequencies has shape {frequencies.shape}: give a 1-D array of "
                         "frequencies [Hz]")
    ground = GroundMotion.harmonic(peak_acceleration, float(frequencies[0]), units=units)
    ground_array, _ = ground._arrays()

    def run(chunk, y, carry):
        summaries, table, y_final, n_done, status, message = cancellable(_bridge.harmonic_sweep,
            tank.array(), ground_array, chunk, y, integration.array(), steady.array(),
            int(carry), int(threads))
        return summaries, table, (y_final if carry else y), status, message

    method = integration.method_used
    points, table, y = run_sweep("frequency", frequencies, y0, progress, threads, start_from,
                                 run, lambda points, y: None, method)
    return HarmonicSweep._from_table(tank, points, table, y, method)
