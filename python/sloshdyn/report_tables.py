"""The calc sheet's tables (issue 39): result CSV files read and rendered by their column names
and units ('base_shear [N]' shown in kN or MN, 'p [Pa]' in kPa, masses in t, accelerations in
g) at engineering precision, and the tables the sheet writes itself from the reader's values
(inputs.csv, motion.csv, spectrum.csv)."""

from __future__ import annotations

import csv
import dataclasses
import math
import re
from pathlib import Path

import numpy as np

from .report_layout import DIGITS, STANDARD_GRAVITY, Table, number

#: rows shown of a long table (evenly spaced, the first and last included)
MAX_ROWS = 25
#: a table of few rows and more columns than this is printed transposed (a row per column)
MAX_COLUMNS = 5
#: a table of more columns than this is printed in a smaller font
WIDE = 6


#: CSV unit -> (display unit, factor) choices, the first whose bound (largest |value| shown
#: below it) fits: forces and moments in kN or MN, pressures in kPa, masses in t, accelerations
#: in g. Units not listed are shown as written.
_DISPLAY = {
    "N": (("kN", 1e3, 1e6), ("MN", 1e6, math.inf)),
    "N m": (("kN·m", 1e3, 1e6), ("MN·m", 1e6, math.inf)),
    "N/m": (("kN/m", 1e3, math.inf),),
    "Pa": (("kPa", 1e3, math.inf),),
    "kg": (("t", 1e3, math.inf),),
    "m/s^2": (("g", STANDARD_GRAVITY, math.inf),),
    "N m/rad": (("MN·m/rad", 1e6, math.inf),),
    "N m s/rad": (("MN·m·s/rad", 1e6, math.inf),),
}


def split_name(column):
    """'base_shear [N]' -> ('base_shear', 'N'); 'x1' -> ('x1', '')."""
    match = re.fullmatch(r"(.*?) \[(.*)\]", column)
    return (match.group(1), match.group(2)) if match else (column, "")


def display_unit(unit, values):
    """(unit shown, factor) for a column of `values` in `unit`: values / factor are shown."""
    finite = [abs(v) for v in values if isinstance(v, float) and math.isfinite(v)]
    largest = max(finite, default=0.0)
    for shown, factor, bound in _DISPLAY.get(unit, ()):
        if largest < bound:
            return shown, factor
    return unit, 1.0


def read_table(path):
    """A CSV file as (column names, rows of values: float where the text is a number, else
    the text). Bytes that are not UTF-8 (a record's name as the executable read it) are kept
    visible as \\xNN escapes."""
    with open(path, newline="", encoding="utf-8", errors="backslashreplace") as f:
        rows = list(csv.reader(f))

    def value(text):
        try:
            return float(text)
        except ValueError:
            return text
    return rows[0], [[value(cell) for cell in row] for row in rows[1:]]


def columns(path):
    """A CSV's numeric columns as arrays (text columns as lists)."""
    names, rows = read_table(path)
    result = {}
    for k, name in enumerate(names):
        values = [row[k] for row in rows]
        result[name] = (np.array(values) if all(isinstance(v, float) for v in values)
                        else values)
    return result


def one_row(path):
    """The only row of a one-row CSV as {column: value}."""
    names, rows = read_table(path)
    return dict(zip(names, rows[0]))


def cell(value, factor=1.0, digits=DIGITS):
    """A value as a table cell: a number / factor at `digits` significant digits, a text as
    it is ('' for an empty field)."""
    return number(value / factor, digits) if isinstance(value, float) else value


def render_table(path, caption="", max_rows=MAX_ROWS, digits=DIGITS, hidden=()):
    """Any result CSV as a Table, by its column names and units, without the columns named in
    `hidden`. One row: a table of quantity, value, unit (a peak beside its time,
    'peak_X'/'time_X' or 'X'/'X_time'); a few rows of many columns (more than MAX_COLUMNS,
    the first a name): transposed, a row per quantity with its unit and a column per name;
    else one column per quantity, its unit in the header, at most MAX_ROWS rows."""
    path = Path(path)
    names, rows = read_table(path)
    kept = [k for k, c in enumerate(names) if split_name(c)[0] not in hidden]
    names, rows = [names[k] for k in kept], [[row[k] for k in kept] for row in rows]
    if len(rows) == 1:
        return _one_row_table(path.name, names, rows[0], caption, digits)
    if (len(names) > MAX_COLUMNS and len(rows) <= 6
            and all(isinstance(row[0], str) for row in rows)):
        shown = []
        for k, column in enumerate(names[1:], 1):
            name, unit = split_name(column)
            unit, factor = display_unit(unit, [row[k] for row in rows])
            shown.append([name, unit] + [cell(row[k], factor, digits) for row in rows])
        return Table([split_name(names[0])[0] + ": quantity", "unit"] + [row[0] for row in rows],
                     shown, path.name, caption)
    if max_rows and len(rows) > max_rows:
        keep = np.unique(np.linspace(0, len(rows) - 1, max_rows).round().astype(int))
        caption = (f"{caption} Evenly spaced rows, {len(keep)} of "
                   f"{len(rows)} (all in {path.name}).").strip()
        rows = [rows[k] for k in keep]
    header, factors = [], []
    for k, column in enumerate(names):
        name, unit = split_name(column)
        unit, factor = display_unit(unit, [row[k] for row in rows])
        header.append(f"{name} [{unit}]" if unit else name)
        factors.append(factor)
    return Table(header, [[cell(v, f, digits) for v, f in zip(row, factors)] for row in rows],
                 path.name, caption, wide=len(header) > WIDE)


def _one_row_table(source, names, values, caption, digits):
    row = dict(zip(names, values))
    by_name = {split_name(c)[0]: c for c in names}
    times = {}
    for name, column in by_name.items():     # time_X, X_time: the time of X or peak_X...
        peak = (name[len("time_"):] if name.startswith("time_") else
                name[:-len("_time")] if name.endswith("_time") else None)
        match = peak and next((c for n, c in by_name.items() if n != name and (
            n == peak or n.startswith((f"{peak}_", f"peak_{peak}")))), None)
        if match:
            times[match] = column
    shown = []
    for column in names:
        if column in times.values():
            continue
        name, unit = split_name(column)
        unit, factor = display_unit(unit, [row[column]])
        time = number(row[times[column]]) if column in times else ""
        shown.append([name, cell(row[column], factor, digits), unit, time])
    header = ["quantity", "value", "unit"] + (["at t [s]"] if times else [])
    return Table(header, [r if times else r[:3] for r in shown], source, caption)


def motion_table(inp, info):
    """motion.csv: the ground motion as the reader scaled it, its peak and its pseudo-spectral
    acceleration at the first sloshing period (0.5 %); the record's name and scaling as the
    run wrote them (run_info.csv) where it did."""
    ground, ground_y = inp.ground_motion, inp.ground_motion_y
    period = inp.tank.sloshing_period
    sa = ground.response_spectrum([period], 0.005, **_spectrum_span(inp)).psa[0]
    names = [p.name for p in info["records"]]
    return {"kind": [ground.kind],
            "record": [names[0] if names else ""],
            "record_y": [names[1] if len(names) > 1 else ""],
            "scaling": [info["run"].get("scaling", "")],
            "scale_factor": [ground.scale_factor],
            "frequency [Hz]": [ground.frequency if ground.kind == "harmonic" else math.nan],
            "peak_ground_acceleration [m/s^2]": [ground.pga],
            "peak_ground_acceleration_y [m/s^2]": [ground_y.pga if ground_y else math.nan],
            "sloshing_period [s]": [period],
            "sa_sloshing_period [m/s^2]": [sa]}


#: units of the input variables (docs/namelist.md); the others are ratios, counts or names
INPUT_UNITS = {"radius": "m", "liquid_depth": "m", "freeboard": "m", "liquid_density": "kg/m^3",
               "liquid_mass": "kg", "tank_mass": "kg", "support_frequency": "Hz",
               "support_stiffness": "N m/rad", "support_damping_coefficient": "N m s/rad",
               "support_height": "m", "gravity": "m/s^2", "roof_slope": "degrees",
               "roof_radius": "m", "length": "m", "width": "m", "t_end": "s", "azimuth": "rad",
               "h_initial": "tau", "h_max": "tau", "h_min": "tau"}


def inputs_table(inp):
    """inputs.csv: the values the reader read (defaults included) of &tank, &ground_motion's
    direction (two components), &seismic and &integration (with a ground motion) and &design,
    with their units; the ground motion itself is in motion.csv."""
    values = [("tank", f.name, getattr(inp.tank, f.name)) for f in dataclasses.fields(inp.tank)]
    values.append(("tank", "planar", ".true." if inp.planar else ".false."))
    if not inp.planar:
        values += [("ground_motion", name, inp.spatial[name]) for name in ("azimuth",
                                                                             "ellipticity")]
    if inp.ground_motion is not None:
        values += [("seismic", name, value) for name, value in inp.seismic.items()]
        values += [("integration", f.name, getattr(inp.integration, f.name))
                   for f in dataclasses.fields(inp.integration)]
    if inp.design is not None:
        values += [("design", f.name, getattr(inp.design, f.name))
                   for f in dataclasses.fields(inp.design)]
    structure = getattr(inp, "tank_structure", None)
    if structure is not None:               # the courses bottom first: course_height_1, ...
        for f in dataclasses.fields(structure):
            value = getattr(structure, f.name)
            values += ([("tank_structure", f"{f.name}_{k}", x) for k, x in enumerate(value, 1)]
                       if isinstance(value, tuple) else [("tank_structure", f.name, value)])
    return {"group": [f"&{group}" for group, _, _ in values],
            "variable": [name for _, name, _ in values],
            "value": [value if isinstance(value, str) else float(value)
                      for _, _, value in values],
            "unit": [INPUT_UNITS.get(name, "") for _, name, _ in values]}


def _spectrum_span(inp):
    """The time over which a spectrum is taken, as the core takes the run's Sa at the
    sloshing period T (sloshdyn_ground spectral_acceleration): a record and a free tail of
    5 T; harmonic motion over 20 T."""
    period = inp.tank.sloshing_period
    if inp.ground_motion.kind == "harmonic":
        return {"duration": 20 * period}
    return {"tail_duration": 5 * period}


def spectrum_table(inp):
    """spectrum.csv: pseudo-acceleration spectra of the scaled ground motion (the first
    component; 0.5 % and 5 % damping) from 0.05 s to beyond twice the sloshing period, the
    sloshing period included."""
    periods = np.union1d(np.geomspace(0.05, max(10.0, 2.5 * inp.tank.sloshing_period), 150),
                         [inp.tank.sloshing_period])
    span = _spectrum_span(inp)
    if "tail_duration" in span:
        span = {}                               # a record: a tail of 5 times the longest period
    columns = {"period [s]": periods}
    for damping in (0.005, 0.05):
        columns[f"sa_{100 * damping:g}% [m/s^2]"] = \
            inp.ground_motion.response_spectrum(periods, damping, **span).psa
    return columns


