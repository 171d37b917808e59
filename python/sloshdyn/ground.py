"""The seismic input of a tank, in SI units: a ground motion (`GroundMotion`: a record or
harmonic motion, scaled, with its response spectrum) or a code design spectrum
(`DesignSpectrum`). Value types at the bottom of the package: they import no analysis
(docs/architecture.md, "Python layers"); every number comes from the Fortran core
(sloshdyn_ground, sloshdyn_design_spectra). &ground_motion and &design are the same objects."""

from __future__ import annotations

import os
import stat
from dataclasses import dataclass

import numpy as np

from ._cancel import cancellable
from . import _checks, _core, _tables
from ._errors import InputError, SloshdynError, check_status
from .options import Design

_bridge = _core.sloshdyn_bridge_seismic
_TANK_DEFAULTS = _tables.defaults("tank")
#: the damping ratio of a spectral acceleration when none is given: the convective 0.5 % of
#: the design codes, the core's one default (sloshdyn_vessel convective_damping, a tank's
#: sloshing_damping; &ground_motion target_damping, &study spectral_damping)
CONVECTIVE_DAMPING = float(_TANK_DEFAULTS["sloshing_damping"])
#: the largest record file the core reads (sloshdyn_records max_record_bytes, 1 GiB)
_MAX_RECORD_BYTES = 1 << 30


_real = _checks.real


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


def ground_arrays(ground_motion):
    """The bridge's arrays of a ground motion (None: no motion, the layout's zeros)."""
    if ground_motion is None:
        return np.zeros(len(_tables.layout("ground"))), np.zeros(0)
    if not isinstance(ground_motion, GroundMotion):
        _checks.instance("ground_motion", ground_motion, GroundMotion)
    return ground_motion._arrays()


#: the fields of &design that describe the spectrum (the rest are the codes' factors)
SPECTRUM_FIELDS = ("spectrum", "s_ds", "s_d1", "t_l", "k", "a_gr", "gamma_i", "ground_type",
                   "spectrum_type", "q", "beta")


class DesignSpectrum:
    """A code design spectrum: Sa [g] at a period [s] and a damping ratio (`sa`), usable
    where a record's spectrum is used (Tank.design_codes(spectrum), design_check).

    DesignSpectrum.asce7(s_ds=1.0, s_d1=0.6, t_l=8)    ASCE 7-16 11.4.6 (API 650 Annex E)
    DesignSpectrum.aci350(s_ds=1.0, s_d1=0.6)          ACI 350.3-06 9.4 (C_i 5 %, C_c 0.5 %)
    DesignSpectrum.ec8(a_gr=0.25, ground_type='B')     EN 1998-1 3.2.2.2 (and 3.2.2.5 with q)
    DesignSpectrum(design=read_namelist(path).design)  &design's spectrum

    ASCE 7 and ACI 350.3 tabulate 5 % and 0.5 % damping only (damping_ratio 0.05 and 0.005;
    0.5 %: API 650's K times the 5 % ordinate; ACI 350.3's own C_c); EN 1998-1's elastic
    spectrum takes any damping (eta = sqrt(10/(5 + xi)) >= 0.55, xi in %), beyond 4 s by its
    informative Annex A. Other inputs are refused with the clause.
    `design` holds it as &design settings (sloshdyn.design.Design)."""

    def __init__(self, *, design: Design):
        _checks.instance("design", design, Design)
        if design.spectrum == "ground_motion":
            raise InputError("spectrum = 'ground_motion' is a ground motion's spectrum, not a "
                             "design spectrum: pass the GroundMotion")
        self.design = design
        self.sa(1.0)                 # the core checks the spectrum's parameters

    @classmethod
    def asce7(cls, s_ds, s_d1, t_l, k=1.5) -> DesignSpectrum:
        """ASCE 7-16 11.4.6 from S_DS, S_D1 [g] and T_L [s]; K: API 650 E.4.6.1's factor from
        5 % to 0.5 % damping."""
        return cls(design=Design(spectrum="asce7", s_ds=s_ds, s_d1=s_d1, t_l=t_l, k=k))

    @classmethod
    def aci350(cls, s_ds, s_d1, t_l=0.0) -> DesignSpectrum:
        """ACI 350.3-06 9.4 from S_DS, S_D1 [g]; T_L [s] only for API 650's rows of a design
        check (the ACI spectrum does not use it; 0: none)."""
        return cls(design=Design(spectrum="aci350", s_ds=s_ds, s_d1=s_d1, t_l=t_l))

    @classmethod
    def ec8(cls, a_gr, ground_type="A", spectrum_type=1, gamma_i=1.0, q=1.0,
            beta=0.2) -> DesignSpectrum:
        """EN 1998-1 3.2.2.2 (elastic) and 3.2.2.5 (design, behaviour factor q, lower bound
        beta a_g) from a_gR [g], the ground type A-E, the spectrum type 1 or 2 and gamma_I."""
        return cls(design=Design(spectrum="ec8", a_gr=a_gr, ground_type=ground_type,
                                 spectrum_type=spectrum_type, gamma_i=gamma_i, q=q, beta=beta))

    @property
    def kind(self):
        """'asce7', 'aci350' or 'ec8'."""
        return self.design.spectrum

    @property
    def label(self):
        """The spectrum in a few words (figures)."""
        d = self.design
        if self.kind == "ec8":
            return (f"EN 1998-1 type {d.spectrum_type}, ground {d.ground_type}, "
                    f"a_g = {d.gamma_i * d.a_gr:g} g")
        name = "ASCE 7-16" if self.kind == "asce7" else "ACI 350.3-06"
        return f"{name}, S_DS = {d.s_ds:g} g, S_D1 = {d.s_d1:g} g" + (
            f", T_L = {d.t_l:g} s" if self.kind == "asce7" else "")

    def sa(self, period, *, damping_ratio=0.05):
        """Sa [g] at the period(s) [s] (a scalar or an array) and the damping ratio (of
        critical: 0.05 for 5 %; keyword only, so that an old call passing percent fails)."""
        periods = _checks.reals("period", period)
        damping_ratio = _checks.real("damping_ratio", damping_ratio)
        values, status, message = _bridge.design_spectrum_sa(
            self.design.array(), np.atleast_1d(periods).ravel(), damping_ratio)
        check_status(status, message)
        return float(values[0]) if periods.ndim == 0 else values.reshape(periods.shape)

    def __repr__(self):
        d = self.design
        if self.kind == "ec8":
            return (f"DesignSpectrum.ec8(a_gr={d.a_gr}, ground_type={d.ground_type!r}, "
                    f"spectrum_type={d.spectrum_type}, gamma_i={d.gamma_i}, q={d.q})")
        return f"DesignSpectrum.{self.kind}(s_ds={d.s_ds}, s_d1={d.s_d1}, t_l={d.t_l})"
