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
from ._tables import column_name
from ._errors import InputError, check_status
from .ground import SPECTRUM_FIELDS, DesignSpectrum, GroundMotion, ground_arrays
from .options import Design
from .seismic import SeismicResponse
from .tank import Tank

_bridge = _core.sloshdyn_bridge_seismic


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
            columns = [column_name(c) for c in _tables.columns(name)[1:]]
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
                out[column_name(c)] = c.split(" [")[1].rstrip("]") if " [" in c else ""
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
    ground, samples = ground_arrays(ground_motion)
    columns = _tables.columns("seismic_peaks_impact")      # the core's whole peaks array
    peaks = np.zeros(len(columns))
    if response is not None:
        _checks.instance("response", response, SeismicResponse)
        peaks = np.array([response.peak_table.get(column_name(c), np.nan) for c in columns])
    loads, freeboard, status, message = _bridge.design_check(
        tank.array(), design.array(), ground, samples, int(response is not None), peaks)
    check_status(status, message)
    return DesignCheck._from_tables(loads.copy(), freeboard.copy())
