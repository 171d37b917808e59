"""The design check of a tank (issue 25; docs/design.md): the codes' design spectra
(`DesignSpectrum`: ASCE 7-16 as API 650 Annex E uses it, ACI 350.3-06, EN 1998-1), each code's
seismic loads in its own format and its freeboard check (`design_check`, `DesignCheck`), from a
design spectrum or from a ground motion's spectrum, beside sloshdyn's own (linear: the
response-spectrum method on its model; nonlinear: a time history's peaks). The settings are
&design's (`Design`, made from the core's layout 'design'); every number comes from the Fortran
core (sloshdyn_design_spectra, sloshdyn_design_loads, sloshdyn_design_check)."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from . import _checks, _core, _tables
from ._errors import InputError, check_status
from ._settings import settings

_bridge = _core.sloshdyn_bridge_seismic


@settings("design")
class Design:
    """&design: the spectrum the design check uses (a code design spectrum, or
    'ground_motion': the ground motion's) and the codes' factors (docs/namelist.md, &design)."""


def _name(column):
    return column.split(" [")[0]


#: the fields of &design that describe the spectrum (the rest are the codes' factors)
SPECTRUM_FIELDS = ("spectrum", "s_ds", "s_d1", "t_l", "k", "a_gr", "gamma_i", "ground_type",
                   "spectrum_type", "q", "beta")


class DesignSpectrum:
    """A code design spectrum: Sa [g] at a period [s] and a damping ratio [%] (`sa`), usable
    where a record's spectrum is used (Tank.design_codes(spectrum), Tank.design_check).

    DesignSpectrum.asce7(s_ds=1.0, s_d1=0.6, t_l=8)    ASCE 7-16 11.4.6 (API 650 Annex E)
    DesignSpectrum.aci350(s_ds=1.0, s_d1=0.6)          ACI 350.3-06 9.4 (C_i 5 %, C_c 0.5 %)
    DesignSpectrum.ec8(a_gr=0.25, ground_type='B')     EN 1998-1 3.2.2.2 (and 3.2.2.5 with q)
    DesignSpectrum(design=read_namelist(path).design)  &design's spectrum

    ASCE 7 and ACI 350.3 tabulate 5 % and 0.5 % damping only (0.5 %: API 650's K times the
    5 % ordinate; ACI 350.3's own C_c); EN 1998-1's elastic spectrum takes any damping
    (eta = sqrt(10/(5 + xi)) >= 0.55) up to 4 s. Other inputs are refused with the clause.
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

    def sa(self, period, damping=5.0):
        """Sa [g] at the period(s) [s] (a scalar or an array) and damping ratio [%]."""
        periods = _checks.reals("period", np.atleast_1d(np.asarray(period, dtype=float)),
                                ndim=1)
        damping = _checks.real("damping", damping)
        values, status, message = _bridge.design_spectrum_sa(self.design.array(), periods,
                                                             damping)
        check_status(status, message)
        return float(values[0]) if np.ndim(period) == 0 else values.reshape(np.shape(period))

    def __repr__(self):
        d = self.design
        if self.kind == "ec8":
            return (f"DesignSpectrum.ec8(a_gr={d.a_gr}, ground_type={d.ground_type!r}, "
                    f"spectrum_type={d.spectrum_type}, gamma_i={d.gamma_i}, q={d.q})")
        return f"DesignSpectrum.{self.kind}(s_ds={d.s_ds}, s_d1={d.s_d1}, t_l={d.t_l})"


@dataclass(frozen=True)
class DesignCheck:
    """The design check of a tank: `loads` (the core's 'design_loads' table) and `freeboard`
    ('freeboard_check'), each {source: {column: value}} for the sources that give a row
    ('API 650', 'EC8-4', 'ACI 350.3', 'sloshdyn linear', 'sloshdyn nonlinear'); columns by
    name without their unit (units: `units`). Accelerations are each code's design
    coefficient in g (its factors applied); moments EBP exclude the base pressure (API 650's
    ringwall M_rw, ACI 350.3's M_b), IBP include it (API 650's slab M_s, ACI 350.3's M_o)."""

    loads: dict
    freeboard: dict
    loads_table: np.ndarray = dataclasses.field(repr=False)       #: (17, 5), NaN rows absent
    freeboard_table: np.ndarray = dataclasses.field(repr=False)   #: (7, 5)

    @classmethod
    def _from_tables(cls, loads, freeboard):
        sources = _tables.names("design_source")[0]

        def rows(table, name, present):
            columns = [_name(c) for c in _tables.columns(name)[1:]]
            return {s: {c: float(v) for c, v in zip(columns, table[:, j])}
                    for j, s in enumerate(sources) if present(table[:, j])}
        return cls(loads=rows(loads, "design_loads", lambda col: np.isfinite(col[14])),
                   freeboard=rows(freeboard, "freeboard_check",
                                  lambda col: np.isfinite(col[2])),
                   loads_table=loads, freeboard_table=freeboard)

    @property
    def units(self):
        """{column: unit} of both tables."""
        out = {}
        for name in ("design_loads", "freeboard_check"):
            for c in _tables.columns(name)[1:]:
                out[_name(c)] = c.split(" [")[1].rstrip("]") if " [" in c else ""
        return out

    @property
    def sufficient(self):
        """{source: whether the tank's freeboard suffices} (API 650 Table E-7, ACI 350.3 7.1,
        EN 1998-4 A.2.1; sloshdyn nonlinear: the free wave does not reach the roof)."""
        return {s: bool(row["sufficient"]) for s, row in self.freeboard.items()}


def design_check(tank, motion=None, *, design: Design | None = None,
                 response=None) -> DesignCheck:
    """Each code's seismic loads and freeboard check for the tank (DesignCheck), beside
    sloshdyn's. motion: a DesignSpectrum, a GroundMotion (its pseudo-spectral accelerations at
    each code's periods and dampings), or None (design's own spectrum); design: the codes'
    factors (importance, use_group, R factors, q, impulsive period, ...; a Design, its defaults
    when None); response: a SeismicResponse of the same tank and motion, for sloshdyn's
    nonlinear row."""
    from .seismic import GroundMotion, SeismicResponse, Tank, _ground_arrays
    _checks.instance("tank", tank, Tank)
    design = Design() if design is None else _checks.instance("design", design, Design)
    ground_motion = None
    if isinstance(motion, DesignSpectrum):
        design = dataclasses.replace(design, **{name: getattr(motion.design, name)
                                                for name in SPECTRUM_FIELDS})
    elif isinstance(motion, GroundMotion):
        design, ground_motion = dataclasses.replace(design, spectrum="ground_motion"), motion
    elif motion is not None:
        raise InputError(f"motion = {motion!r} is not valid: give a sloshdyn.DesignSpectrum, a "
                         "sloshdyn.GroundMotion or None (design's spectrum)")
    elif design.spectrum == "ground_motion":
        raise InputError("spectrum = 'ground_motion' needs the ground motion: "
                         "design_check(tank, ground_motion, design=...)")
    ground, samples = _ground_arrays(ground_motion)
    peaks = np.zeros(len(_tables.columns("seismic_peaks")))
    if response is not None:
        _checks.instance("response", response, SeismicResponse)
        peaks = np.array([response.peak_table[_name(c)]
                          for c in _tables.columns("seismic_peaks")])
    loads, freeboard, status, message = _bridge.design_check(
        tank.array(), design.array(), ground, samples, int(response is not None), peaks)
    check_status(status, message)
    return DesignCheck._from_tables(loads.copy(), freeboard.copy())
