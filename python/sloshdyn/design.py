"""The design check of a tank (issues 25 and 38; docs/design.md): the codes' design spectra
(`DesignSpectrum`: ASCE 7-16 as API 650 Annex E uses it, ACI 350.3-06, EN 1998-1), each code's
seismic loads in its own format, its freeboard check and, with the tank's structure
(`TankStructure`, &tank_structure), its structural checks (`design_check`, `DesignCheck`: the
checks with their verdicts and the hand calculation, as design_checks.csv and design_calc.csv),
from a design spectrum or from a ground motion's spectrum, beside sloshdyn's own (linear: the
response-spectrum method on its model; nonlinear: a time history's peaks). The settings are
&design's (`Design`, made from the core's layout 'design'); every number comes from the Fortran
core (sloshdyn_design_spectra, sloshdyn_design_check and the codes' modules)."""

from __future__ import annotations

import csv
import dataclasses
import io
from dataclasses import dataclass

import numpy as np

from . import _checks, _core, _tables
from ._tables import column_name
from ._errors import InputError, check_status
from .ground import SPECTRUM_FIELDS, DesignSpectrum, GroundMotion, ground_arrays
from .options import Design
from .seismic import SeismicResponse
from .structure import TankStructure
from .tank import Tank

_bridge = _core.sloshdyn_bridge_seismic


@dataclass(frozen=True)
class DesignCheck:
    """The design check of a tank: `loads` (the core's 'design_loads' table) and `freeboard`
    ('freeboard_check'), each {source: {column: value}} for the sources that give a row
    ('API 650', 'EC8-4', 'ACI 350.3', 'sloshdyn linear', 'sloshdyn nonlinear'); columns by
    name without their unit (units: `units`). Accelerations are each code's design
    coefficient in g (its factors applied); moments EBP exclude the base pressure (API 650's
    ringwall M_rw, ACI 350.3's M_b), IBP include it (API 650's slab M_s, ACI 350.3's M_o).

    `checks` and `calc` are the rows of design_checks.csv and design_calc.csv (the same text
    from the core, docs/namelist.md): lists of dicts by column. checks: code, check, clause,
    demand, capacity (None for INFO), unit, ratio (None for INFO), verdict ('OK', 'NOT OK',
    'INFO'); calc: code, step (int), quantity, symbol, formula, substituted, value, unit,
    clause. `checks_text`, `calc_text`: the CSV files' text."""

    loads: dict
    freeboard: dict
    loads_table: np.ndarray = dataclasses.field(repr=False)       #: (17, 5), NaN rows absent
    freeboard_table: np.ndarray = dataclasses.field(repr=False)   #: (7, 5)
    checks: list = dataclasses.field(default_factory=list, repr=False)
    calc: list = dataclasses.field(default_factory=list, repr=False)
    checks_text: str = dataclasses.field(default="", repr=False)
    calc_text: str = dataclasses.field(default="", repr=False)

    @classmethod
    def _from_tables(cls, loads, freeboard, checks_text="", calc_text=""):
        sources = _tables.names("design_source")[0]

        def rows(table, name, present):
            columns = [column_name(c) for c in _tables.columns(name)[1:]]
            return {s: {c: float(v) for c, v in zip(columns, table[:, j])}
                    for j, s in enumerate(sources) if present(table[:, j])}
        return cls(loads=rows(loads, "design_loads", lambda col: np.isfinite(col[14])),
                   freeboard=rows(freeboard, "freeboard_check",
                                  lambda col: np.isfinite(col[2])),
                   loads_table=loads, freeboard_table=freeboard,
                   checks=_csv_rows(checks_text, "design_checks"),
                   calc=_csv_rows(calc_text, "design_calc"),
                   checks_text=checks_text, calc_text=calc_text)

    @property
    def verdicts(self):
        """{(code, check): verdict} of every check."""
        return {(row["code"], row["check"]): row["verdict"] for row in self.checks}

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


#: the numeric columns of the report's tables (the rest are text; step an integer)
_NUMBERS = {"demand", "capacity", "ratio", "value"}


def _csv_rows(text, table):
    """The rows of a report table's CSV text (the core's, header first) as dicts: numbers as
    floats, empty fields (an INFO check's capacity and ratio) as None, step as int."""
    if not text:
        return []
    reader = csv.DictReader(io.StringIO(text))
    if reader.fieldnames != _tables.columns(table):
        raise RuntimeError(f"{table}: the core's columns {reader.fieldnames} are not the "
                           f"table's {_tables.columns(table)}")
    rows = []
    for row in reader:
        for name in _NUMBERS & row.keys():
            row[name] = float(row[name]) if row[name] != "" else None
        if "step" in row:
            row["step"] = int(row["step"])
        rows.append(row)
    return rows


def design_check(tank, motion=None, *, design: Design | None = None,
                 tank_structure: TankStructure | None = None, response=None) -> DesignCheck:
    """Each code's seismic loads and freeboard check for the tank (DesignCheck), beside
    sloshdyn's, and with its structure the codes' structural checks. motion: a DesignSpectrum,
    a GroundMotion (its pseudo-spectral accelerations at each code's periods and dampings), or
    None (design's own spectrum); design: the codes' factors (importance, use_group, R
    factors, q, impulsive period, ...; a Design, its defaults when None); tank_structure: the
    tank's structure (a TankStructure: &tank_structure) or None; response: a SeismicResponse of the
    same tank and motion, for sloshdyn's nonlinear row."""
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
    if tank_structure is None:
        structure_array = _tables.pack("tank_structure", _tables.defaults("tank_structure"))
    else:
        structure_array = _checks.instance("tank_structure", tank_structure,
                                           TankStructure).array()
    loads, freeboard, checks, calc, status, message = _bridge.design_check(
        tank.array(), design.array(), ground, samples, structure_array,
        int(response is not None), peaks)
    check_status(status, message)
    return DesignCheck._from_tables(loads.copy(), freeboard.copy(), _decoded(checks),
                                    _decoded(calc))


def _decoded(raw):
    """A text the core hands back (bytes padded with blanks) as str (UTF-8: the formulas'
    symbols)."""
    text = raw.decode("utf-8") if isinstance(raw, bytes) else str(raw)
    return text.rstrip(" \0")
