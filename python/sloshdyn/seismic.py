"""A real tank under ground motion, in SI units: the seismic response (`seismic_response`:
time histories and peaks of the physical loads) and the steady states under harmonic ground
motion (`harmonic_sweep`) of a `Tank` (sloshdyn.tank) under a `GroundMotion` (sloshdyn.ground).
Every number comes from the Fortran core (sloshdyn_vessel, sloshdyn_ground, sloshdyn_seismic);
the namelist groups &tank, &ground_motion and &seismic are the same objects (README, "Namelist
reference"), and docs/model.md gives the relations.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from ._cancel import cancellable
from . import _checks, _core, _tables
from ._tables import column_name
from ._errors import InputError, check_status
from .ground import GroundMotion, ground_arrays
from .options import Integration, Steady
from .simulation import run_sweep
from .tank import Tank

_bridge = _core.sloshdyn_bridge_seismic


@dataclass(frozen=True)
class SeismicResponse:
    """The response of a tank to ground motion from rest, SI units: the tank without contact
    below its roof, and above it the restricted-sloshing method (the confined convective mass
    moves with the tank from the first contact on; docs/model.md, "Loads"). One array per
    quantity over the output times `t` [s]: ground_acceleration [m/s^2],
    sloshing_displacement [m] (of the sloshing mass relative to the tank), wave_height [m] (at
    the wall, capped at the roof), pendulum_angle [rad], tank_drift [m] (relative to the
    ground), tank_acceleration and convective_acceleration [m/s^2] (absolute, of the tank and
    of the convective mass), base_shear [N], overturning_moment and overturning_moment_ibp
    [N m] (about the tank bottom, excluding and including the base pressure), x1, x2,
    free_wave_height [m] (the wave at the wall of the tank without a roof, summed over the
    modes, what the roof verdict judges) (the columns of seismic.csv; `table` holds them in
    order); `peak_table` (the columns of seismic_peaks.csv: also the free wave's peak
    free_wave_height, roof_excess, the roof loads roof_head, roof_uplift_force,
    confined_convective_mass, and the run's scale_factor and sa_sloshing_period [m/s^2]),
    `peaks` {quantity: (largest |value|, its time [s])}, roof_reached, first_roof_time [s],
    roof_impacts (of the free wave); `peak_instants` {load: (t [s], tank acceleration, the
    modes' accelerations [m/s^2])} at the peaks of base_shear, overturning_moment and
    overturning_moment_ibp (what seismic_pressures takes); t_end [s], the end of the run as
    asked (the output times are computed in the model's time, so t[-1] can differ from it in
    the last bit); `method`, the integration method used ('auto' resolved). None of these
    depends on impact_stiffness or impact_damping. With Tank(roof_contact="impact") also the
    paper's impact model (eq 4-5): impact_force [N] at the outputs, its peak, and
    beta_sensitive (its loads would depend on beta and delta; `warnings` says so); without it
    these are None."""

    tank: Tank
    ground_motion: GroundMotion
    t: np.ndarray
    ground_acceleration: np.ndarray
    sloshing_displacement: np.ndarray
    wave_height: np.ndarray
    pendulum_angle: np.ndarray
    tank_drift: np.ndarray
    tank_acceleration: np.ndarray
    convective_acceleration: np.ndarray
    base_shear: np.ndarray
    overturning_moment: np.ndarray
    overturning_moment_ibp: np.ndarray
    x1: np.ndarray
    x2: np.ndarray
    free_wave_height: np.ndarray
    impact_force: np.ndarray | None
    table: np.ndarray = dataclasses.field(repr=False)
    peak_table: dict = dataclasses.field(repr=False)
    peaks: dict = dataclasses.field(repr=False)
    peak_instants: dict = dataclasses.field(repr=False)
    roof_reached: bool
    first_roof_time: float
    roof_impacts: int
    beta_sensitive: bool | None
    t_end: float
    method: str

    @classmethod
    def _from_tables(cls, tank, ground_motion, table, peaks, instants, t_end, method):
        """The response from the core's 'seismic' table and 'seismic_peaks' row (their
        '_impact' layouts with roof_contact = 'impact') and the 'seismic_peak_instants'."""
        suffix = _impact_suffix(tank)
        columns = _tables.columns("seismic" + suffix)
        table = table[:len(columns)]
        peak_table = {column_name(c): float(v) for c, v in
                      zip(_tables.columns("seismic_peaks" + suffix), peaks)}
        rows = {column_name(column): row for column, row in zip(columns, table)}
        return cls(tank=tank, ground_motion=ground_motion, table=table,
                   **{"impact_force": None, **rows},
                   peak_table=peak_table,
                   peaks={name[len("peak_"):]: (value, peak_table["time_" + name[5:]])
                          for name, value in peak_table.items() if name.startswith("peak_")},
                   peak_instants={load: (float(instants[0, k]), float(instants[1, k]),
                                         instants[2:2 + tank.modes, k].copy())
                                  for k, load in enumerate(PEAK_LOADS)},
                   roof_reached=bool(peak_table["roof_reached"]),
                   first_roof_time=peak_table["first_roof_time"],
                   roof_impacts=int(peak_table["roof_impacts"]),
                   beta_sensitive=(bool(peak_table["beta_sensitive"]) if suffix else None),
                   t_end=float(t_end), method=method)

    @property
    def columns(self):
        return [column_name(c) for c in _tables.columns("seismic" + _impact_suffix(self.tank))]

    @property
    def warnings(self):
        """What the numbers should be read with: with roof_contact = 'impact', ['...'] when the
        paper's impact model is sensitive to beta and delta (its wall force reaches 0.001 m g;
        docs/model.md, "Choice of beta and delta"), else []."""
        if not self.beta_sensitive:
            return []
        return ["the paper's impact model (roof_contact = 'impact') is sensitive to "
                "impact_stiffness (beta) and impact_damping (delta) here: its wall acts (impact "
                "force >= 0.001 m g); no load of the run depends on it"]

    def __repr__(self):
        return (f"SeismicResponse({len(self.t)} outputs to t = {self.t[-1]:.4g} s; free wave "
                f"{self.peak_table['free_wave_height']:.4g} m at the wall, freeboard "
                f"{self.tank.freeboard} m, roof {'reached' if self.roof_reached else 'not reached'}"
                f"; peak base shear {self.peaks['base_shear'][0]:.4g} N)")


#: the loads whose peaks a seismic response keeps the accelerations of ('seismic_peak_instants')
PEAK_LOADS = ("base_shear", "overturning_moment", "overturning_moment_ibp")


def _impact_suffix(tank):
    """'_impact' for the tables of a tank with the paper's impact model, else ''."""
    return "_impact" if tank.roof_contact == "impact" else ""


@dataclass(frozen=True)
class SeismicTimes:
    """The output times of a seismic response: n_out evenly spaced from 0 to t_end [s]."""

    t_end: float
    n_out: int


def seismic_defaults(tank: Tank, ground_motion: GroundMotion, t_end=None, n_out=None, *,
                     ground_motion_2=None) -> SeismicTimes:
    """t_end [s] and n_out as seismic_response chooses them: t_end = the record plus 5 sloshing
    periods (harmonic: 40 forcing periods; with ground_motion_2, a record across the first,
    the longer record's end); outputs at the finest of the record's step, 50 per sloshing (or
    forcing) period and 20 per period of the tank on its supports."""
    _checks.instance("tank", tank, Tank)
    ground, samples = ground_arrays(ground_motion)
    ground_y, samples_y = ground_arrays(ground_motion_2)
    chosen, status, message = _bridge.seismic_defaults(
        tank.array(), ground, samples, int(ground_motion_2 is not None), ground_y, samples_y,
        0.0 if t_end is None else _checks.real("t_end", t_end),
        0 if n_out is None else _checks.integer("n_out", n_out))
    check_status(status, message)
    return SeismicTimes(float(chosen[0]), int(chosen[1]))


def seismic_response(tank: Tank, ground_motion: GroundMotion, t_end=None, n_out=None, *,
                     integration: Integration = Integration()) -> SeismicResponse:
    """The tank at rest at t = 0 under the ground motion, to t_end [s] (default: the record
    plus 5 sloshing periods), at n_out evenly spaced times (default: seismic_defaults): a
    SeismicResponse. Its peaks are those of the integrated solution, located between the
    integrator's steps (independent of n_out); the loads are the tank's without contact below
    its roof and by the restricted-sloshing method above it, so none depends on
    impact_stiffness or impact_damping."""
    _checks.instance("tank", tank, Tank)
    _checks.instance("integration", integration, Integration)
    times = seismic_defaults(tank, ground_motion, t_end, n_out)
    t_end, n_out = times.t_end, times.n_out
    _checks.output_size("n_out", n_out, len(_tables.columns("seismic")))
    ground, samples = ground_arrays(ground_motion)
    table, peaks, instants, status, message = cancellable(_bridge.seismic_response,
        tank.array(), ground, samples, t_end, n_out, integration.array())
    check_status(status, message)
    return SeismicResponse._from_tables(tank, ground_motion, table.copy(), peaks.copy(),
                                        instants.copy(), t_end, integration.method_used)


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
                   **{column_name(column): row for column, row in zip(
                       _tables.columns("harmonic_sweep"), table)})


def harmonic_sweep(tank: Tank, peak_acceleration, frequencies, y0=None, *, units="g",
                   steady: Steady = Steady(), integration: Integration = Integration(),
                   progress=False, threads=1, start_from="previous") -> HarmonicSweep:
    """Steady states of the tank under harmonic ground motion of constant peak_acceleration (in
    `units`) at each of the frequencies [Hz], in the given order (ascending = up); start_from,
    threads and steady as for sloshdyn.frequency_sweep. A HarmonicSweep."""
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
