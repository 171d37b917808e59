"""The calc sheet of a tank under ground motion (issue 25, item 5): `sloshdyn-py report INPUT.nml
--out DIR` and `sloshdyn.design_report(input, out)`.

The input runs exactly as `sloshdyn-py run` runs it (the one reader, the same driver and writers,
through the bridge), its CSV files written into DIR; the sheet is then built from those CSV files
only, so every number in it is one of theirs, rounded for print (docs/python.md, "The calc
sheet"). One structured document (sections of paragraphs, tables, figures, code) is written
twice: report.md and a self-contained report.html (figures embedded as base64 PNG, also written
as PNG files beside).

A result table enters the sheet by one line in TABLES: (section title, CSV file name). Any CSV
renders by its column names and units ('base_shear [N]' is shown in kN or MN, 'p [Pa]' in kPa,
masses in t, accelerations in g), with 5 significant digits.
"""

from __future__ import annotations

import base64
import contextlib
import csv
import dataclasses
import datetime
import hashlib
import html
import math
import os
import re
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ._errors import InputError, SloshdynError
from ._files import file_error, run_directory, save_figure, write_csv, write_text
from ._version import __version__
from .namelist import read_namelist
from .runner import run_input

#: significant digits of every number of the sheet computed by sloshdyn, and of the inputs
DIGITS, INPUT_DIGITS = 5, 12
#: the standard acceleration of gravity: accelerations are shown in g = 9.80665 m/s^2
STANDARD_GRAVITY = 9.80665
#: the analyses the sheet reports: a tank (&tank) under ground motion (&ground_motion), or a
#: tank's design check (&design) against a code spectrum in any analysis of the tank
SUPPORTED = "&analysis kind = 'seismic' with &tank and &ground_motion (planar, or two components " \
            "with &tank planar = .false.), or a &tank with &design (the design check against its " \
            "code spectrum)"

#: The result tables of the sheet, in order: (section, CSV file). A table whose file the run did
#: not write is left out. A new table enters the sheet by one line here.
TABLES = (
    ("Inputs", "inputs.csv"),
    ("Motion", "motion.csv"),
    ("Tank", "tank.csv"),
    ("Tank", "tank_modes.csv"),
    ("Design codes", "design_codes.csv"),
    ("Design codes", "design_loads.csv"),
    ("Design codes", "freeboard_check.csv"),
    ("Nonlinear run", "seismic_peaks.csv"),
    ("Nonlinear run", "seismic_spatial_peaks.csv"),
    ("Nonlinear run", "run_info.csv"),
    ("Wall pressure", "wall_pressure.csv"),
    ("Wall pressure", "pressure_resultants.csv"),
    ("Wall pressure", "pressure_at_peaks.csv"),
    ("Wall pressure", "wall_pressure_at_shear_peak.csv"),
    ("Wall pressure", "wall_pressure_at_moment_peak.csv"),
)
#: what each table is, printed above it
CAPTIONS = {
    "inputs.csv": "The values as read, defaults included (SI units as in the namelist; "
                  "0 where the method's default applies, docs/namelist.md).",
    "motion.csv": "The ground motion as scaled by the reader, and its pseudo-spectral "
                  "acceleration at the first sloshing period (0.5 % damping).",
    "tank.csv": "The tank and what follows from it (masses, heights, periods, supports, the "
                "model's dimensionless groups; docs/model.md).",
    "tank_modes.csv": "The sloshing modes taken (modes 2..N linear).",
    "design_codes.csv": "Each design code's periods, masses and heights for this tank, and the "
                        "wave height from the motion's spectrum (— where a code gives no value).",
    "design_loads.csv": "Code-format seismic loads.",
    "freeboard_check.csv": "Freeboard check per code.",
    "seismic_peaks.csv": "Peaks of the nonlinear run (largest |value| over the run, at time t) "
                         "and the roof contact of the free wave.",
    "seismic_spatial_peaks.csv": "Peaks of the spatial run (two components), beside the codes' "
                                 "SRSS and 100/30 combinations of the two planar runs.",
    "run_info.csv": "What the run rests on (record, scaling, impact stiffness and damping).",
    "wall_pressure.csv": "Hydrodynamic wall pressure at theta = 0 (times cos theta around the "
                         "wall) and the hoop force per unit height (docs/design.md).",
    "pressure_resultants.csv": "Resultants of the pressure: impulsive (component 0) and first "
                               "convective mode (1).",
    "pressure_at_peaks.csv": "The nonlinear run at its base shear and overturning moment peaks "
                             "(the output times nearest them): the tank's acceleration and the "
                             "loads of the hydrodynamic pressure and the shell's inertia.",
    "wall_pressure_at_shear_peak.csv": "Hydrodynamic wall pressure of the nonlinear run at its "
                                       "base shear peak, theta = 0.",
    "wall_pressure_at_moment_peak.csv": "Hydrodynamic wall pressure of the nonlinear run at its "
                                        "overturning moment peak, theta = 0.",
}
#: rows shown of a long table (evenly spaced, the first and last included)
MAX_ROWS = 25


# ---- the structured document ----------------------------------------------------------------

@dataclass(frozen=True)
class Paragraph:
    text: str
    code: bool = False    #: verbatim (a code block)


@dataclass(frozen=True)
class Bullets:
    items: list


@dataclass(frozen=True)
class Table:
    header: list
    rows: list
    source: str = ""      #: the CSV file the numbers come from
    caption: str = ""


@dataclass(frozen=True)
class Figure:
    file: str             #: a PNG in the sheet's directory
    caption: str


@dataclass(frozen=True)
class Section:
    title: str
    blocks: list = field(default_factory=list)


@dataclass(frozen=True)
class CalcSheet:
    """The files of a calc sheet (design_report): report.md, report.html, the figures (PNG)
    and the CSV files whose numbers it shows, in its order."""

    markdown: Path
    html: Path
    figures: tuple
    tables: tuple


def to_markdown(title, sections):
    lines = [f"# {title}", ""]
    for section in sections:
        lines += [f"## {section.title}", ""]
        for block in section.blocks:
            if isinstance(block, Paragraph) and block.code:
                lines += ["```", block.text.rstrip("\n"), "```", ""]
            elif isinstance(block, Paragraph):
                lines += [block.text, ""]
            elif isinstance(block, Bullets):
                lines += [f"- {item}" for item in block.items] + [""]
            elif isinstance(block, Figure):
                lines += [f"![{block.caption}]({block.file})", "", f"*{block.caption}*", ""]
            else:
                if block.caption or block.source:
                    lines += [" ".join(filter(None, (block.caption, block.source and
                                                     f"Source: {block.source}"))), ""]
                lines.append("| " + " | ".join(block.header) + " |")
                lines.append("|" + "---|" * len(block.header))
                lines += ["| " + " | ".join(row) + " |" for row in block.rows]
                lines.append("")
    return "\n".join(lines)


def to_html(title, sections, directory):
    """The same document as HTML, self-contained: figures embedded as base64 PNG."""
    e = html.escape
    parts = ["<!DOCTYPE html>", "<html lang=\"en\"><head><meta charset=\"utf-8\">",
             f"<title>{e(title)}</title>",
             "<style>body{font-family:sans-serif;max-width:60em;margin:2em auto;padding:0 1em}"
             "table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #bbb;"
             "padding:2px 8px}td{text-align:right}td:first-child{text-align:left}"
             "pre{background:#f4f4f4;padding:0.5em;overflow-x:auto}img{max-width:100%}"
             "</style></head><body>", f"<h1>{e(title)}</h1>"]
    for section in sections:
        parts.append(f"<h2>{e(section.title)}</h2>")
        for block in section.blocks:
            if isinstance(block, Paragraph):
                parts.append(f"<pre>{e(block.text)}</pre>" if block.code else
                             f"<p>{e(block.text)}</p>")
            elif isinstance(block, Bullets):
                parts.append("<ul>" + "".join(f"<li>{e(item)}</li>" for item in block.items)
                             + "</ul>")
            elif isinstance(block, Figure):
                data = base64.b64encode((Path(directory) / block.file).read_bytes()).decode()
                parts.append(f"<figure><img src=\"data:image/png;base64,{data}\" "
                             f"alt=\"{e(block.caption)}\"><figcaption>{e(block.caption)}"
                             "</figcaption></figure>")
            else:
                if block.caption or block.source:
                    parts.append("<p>" + e(" ".join(filter(None, (
                        block.caption, block.source and f"Source: {block.source}")))) + "</p>")
                parts.append("<table><tr>" + "".join(f"<th>{e(h)}</th>" for h in block.header)
                             + "</tr>")
                parts += ["<tr>" + "".join(f"<td>{e(c)}</td>" for c in row) + "</tr>"
                          for row in block.rows]
                parts.append("</table>")
    parts.append("</body></html>")
    return "\n".join(parts)


# ---- numbers and units ------------------------------------------------------------------------

def number(value, digits=DIGITS):
    """A number as the sheet prints it: `digits` significant digits, '—' for NaN."""
    value = float(value)
    if math.isnan(value):
        return "—"
    if math.isinf(value):
        return "inf" if value > 0 else "-inf"
    return f"{value:.{digits}g}"


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
    the text)."""
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))

    def value(text):
        try:
            return float(text)
        except ValueError:
            return text
    return rows[0], [[value(cell) for cell in row] for row in rows[1:]]


def _cell(value, factor, digits=DIGITS):
    return number(value / factor, digits) if isinstance(value, float) else value


def render_table(path, caption="", max_rows=MAX_ROWS, digits=DIGITS):
    """Any result CSV as a Table, by its column names and units. One row: a table of
    quantity, value, unit (a peak beside its time, 'peak_X'/'time_X' or 'X'/'X_time'); several
    rows: one column per quantity, its unit in the header, at most MAX_ROWS rows."""
    path = Path(path)
    columns, rows = read_table(path)
    if len(rows) == 1:
        row = dict(zip(columns, rows[0]))
        names = {split_name(c)[0]: c for c in columns}
        times = {}
        for name, column in names.items():     # time_X, X_time: the time of X or peak_X...
            peak = (name[len("time_"):] if name.startswith("time_") else
                    name[:-len("_time")] if name.endswith("_time") else None)
            match = peak and next((c for n, c in names.items() if n != name and (
                n == peak or n.startswith((f"{peak}_", f"peak_{peak}")))), None)
            if match:
                times[match] = column
        shown = []
        for column in columns:
            if column in times.values():
                continue
            name, unit = split_name(column)
            unit, factor = display_unit(unit, [row[column]])
            time = number(row[times[column]]) if column in times else ""
            shown.append([name, _cell(row[column], factor, digits), unit, time])
        header = ["quantity", "value", "unit"] + (["at t [s]"] if times else [])
        return Table(header, [r if times else r[:3] for r in shown], path.name, caption)
    if max_rows and len(rows) > max_rows:
        keep = np.unique(np.linspace(0, len(rows) - 1, max_rows).round().astype(int))
        caption = (f"{caption} Evenly spaced rows, {len(keep)} of "
                   f"{len(rows)} (all in {path.name}).").strip()
        rows = [rows[k] for k in keep]
    header, factors = [], []
    for k, column in enumerate(columns):
        name, unit = split_name(column)
        unit, factor = display_unit(unit, [row[k] for row in rows])
        header.append(f"{name} [{unit}]" if unit else name)
        factors.append(factor)
    return Table(header, [[_cell(v, f, digits) for v, f in zip(row, factors)] for row in rows],
                 path.name, caption)


# ---- the run ------------------------------------------------------------------------------------

@contextlib.contextmanager
def _captured_output(captured):
    """Standard output (file descriptor 1, where the core prints its summary) into a temporary
    file for the block; its text is appended to `captured` and written on to sys.stdout."""
    sys.stdout.flush()
    saved = os.dup(1)
    with tempfile.TemporaryFile() as f:
        os.dup2(f.fileno(), 1)
        try:
            yield
        finally:
            sys.stdout.flush()
            os.dup2(saved, 1)
            os.close(saved)
            f.seek(0)
            text = f.read().decode("utf-8", errors="replace")
            captured.append(text)
            sys.stdout.write(text)
            sys.stdout.flush()


def _verdicts(summary):
    """The lines the executable prints after the seismic run's table of peaks: the roof
    verdict, the force of the smooth wall, the ground motion, warnings, the codes'
    combinations (the peak lines have 'at t = ' at column 45, after the name and the value)."""
    lines, inside = [], False
    for line in summary.splitlines():
        if line.startswith("Seismic response"):
            inside = True
        elif inside and (not line.strip() or line.startswith("Results written")):
            break
        elif inside and line[44:51] != "at t = ":
            lines.append(line.strip())
    return lines


def _sha256(path):
    digest = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def _record_files(path):
    """The record files of &ground_motion (record, record_y), relative to the input's folder."""
    import f90nml    # deferred: only the sheet needs it, and it adds ~30 ms to `import sloshdyn`
    group = f90nml.read(path).get("ground_motion", {})
    folder = Path(path).resolve().parent
    return [folder / group[name] for name in ("record", "record_y")
            if str(group.get(name) or "").strip()]


def _motion_table(inp, info):
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


def _inputs_table(inp):
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


def _spectrum_table(inp):
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


# ---- figures ----------------------------------------------------------------------------------

def _figures(out, spatial, freeboard, seismic=True):
    """The sheet's figures, from the CSV files in `out`: [(file, caption)]; those of the
    seismic run when seismic, else the design spectrum's."""
    import matplotlib    # the plot extra: only where the sheet draws its figures
    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    figures = (_seismic_figures(out, spatial, freeboard, plt) if seismic else
               _design_spectrum_figure(out, plt))
    pressure = out / "wall_pressure.csv"
    if pressure.exists():
        table = _columns(pressure)
        height = next(c for c in table if split_name(c)[1] == "m")
        fig, ax = plt.subplots(figsize=(6, 5), layout="constrained")
        for column in table:
            if split_name(column)[1] == "Pa":
                ax.plot(table[column] / 1e3, table[height], label=split_name(column)[0])
        ax.set(xlabel="pressure [kPa]", ylabel=f"{split_name(height)[0]} [m]")
        ax.grid(alpha=0.3)
        fig.legend(loc="outside upper center", ncols=2, fontsize="small")
        figures.append(("wall_pressure.png", fig, "Hydrodynamic wall pressure over the height."))

    for name, fig, _ in figures:
        save_figure(fig, out / name)
    return [(name, caption) for name, _, caption in figures]


def _seismic_figures(out, spatial, freeboard, plt):
    """Ground motion, spectra (with the design spectrum when written), wave against the
    freeboard, loads: [(file, figure, caption)]."""
    series = _columns(out / ("seismic_spatial.csv" if spatial else "seismic.csv"))
    t = series["t [s]"]
    figures = []

    fig, ax = plt.subplots(figsize=(8, 3), layout="constrained")
    if spatial:
        ax.plot(t, series["ground_acceleration_x [m/s^2]"] / STANDARD_GRAVITY, lw=0.7,
                label="x component")
        ax.plot(t, series["ground_acceleration_y [m/s^2]"] / STANDARD_GRAVITY, lw=0.7,
                label="y component")
        fig.legend(loc="outside upper center", ncols=2, fontsize="small")
    else:
        ax.plot(t, series["ground_acceleration [m/s^2]"] / STANDARD_GRAVITY, lw=0.7)
    ax.set(xlabel="t [s]", ylabel="ground acceleration [g]")
    ax.grid(alpha=0.3)
    figures.append(("ground_motion.png", fig, "Ground acceleration (as scaled) over time."))

    spectrum = _columns(out / "spectrum.csv")
    motion = _columns(out / "motion.csv")
    fig, ax = plt.subplots(figsize=(8, 3.5), layout="constrained")
    for column in spectrum:
        if column.startswith("sa_"):
            ax.plot(spectrum["period [s]"], spectrum[column] / STANDARD_GRAVITY,
                    label=f"{split_name(column)[0][3:]} damping")
    if (out / "design_spectrum.csv").exists():
        _plot_design_spectrum(ax, out, "--", "design, ")
    period = float(motion["sloshing_period [s]"][0])
    ax.axvline(period, color="grey", lw=0.8, ls=":")
    ax.plot(period, float(motion["sa_sloshing_period [m/s^2]"][0]) / STANDARD_GRAVITY, "ko",
            ms=4, label=f"sloshing period {number(period)} s")
    ax.set(xlabel="T [s]", ylabel="Sa [g]", xscale="log")
    ax.grid(alpha=0.3, which="both")
    fig.legend(loc="outside upper center", ncols=4, fontsize="small")
    figures.append(("spectrum.png", fig, "Pseudo-acceleration spectra of the ground motion "
                                         "(first component, as scaled)."))

    fig, ax = plt.subplots(figsize=(8, 3.5), layout="constrained")
    ax.plot(t, series["wave_height [m]"], lw=0.8,
            label="wave height at the wall" + (" (largest over the wall)" if spatial else ""))
    if "free_wave_height [m]" in series:
        ax.plot(t, series["free_wave_height [m]"], lw=0.8, alpha=0.7,
                label="free wave (no roof)")
    ax.axhline(freeboard, color="r", ls="--", lw=1, label=f"freeboard {number(freeboard)} m")
    ax.set(xlabel="t [s]", ylabel="wave height [m]")
    ax.grid(alpha=0.3)
    fig.legend(loc="outside upper center", ncols=3, fontsize="small")
    figures.append(("wave.png", fig, "Wave height at the wall against the freeboard."))

    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 5), sharex=True, layout="constrained")
    top.plot(t, series["base_shear [N]"] / 1e6, lw=0.8)
    top.set(ylabel="base shear [MN]")
    bottom.plot(t, series["overturning_moment [N m]"] / 1e6, lw=0.8, color="C1")
    bottom.set(xlabel="t [s]", ylabel="overturning moment [MN m]")
    for ax in (top, bottom):
        ax.grid(alpha=0.3)
    figures.append(("loads.png", fig, "Base shear and overturning moment over time"
                                      + (" (resultants)." if spatial else ".")))
    return figures


def _plot_design_spectrum(ax, out, style, prefix):
    """design_spectrum.csv's Sa [g] columns (one per damping) over the period, on ax."""
    table = _columns(out / "design_spectrum.csv")
    for column in table:
        if split_name(column)[1] == "g":
            damping = split_name(column)[0][3:].replace("_percent", " %")
            ax.plot(table["period [s]"], table[column], style,
                    label=f"{prefix}{damping} damping")


def _design_spectrum_figure(out, plt):
    """The code spectrum of the design check (design_spectrum.csv) with the tank's first
    sloshing period (tank.csv): [(file, figure, caption)]."""
    period = float(_columns(out / "tank.csv")["sloshing_period [s]"][0])
    fig, ax = plt.subplots(figsize=(8, 3.5), layout="constrained")
    _plot_design_spectrum(ax, out, "-", "")
    ax.axvline(period, color="grey", lw=0.8, ls=":", label=f"sloshing period {number(period)} s")
    ax.set(xlabel="T [s]", ylabel="Sa [g]", xscale="log")
    ax.grid(alpha=0.3, which="both")
    fig.legend(loc="outside upper center", ncols=3, fontsize="small")
    return [("design_spectrum.png", fig, "The code's elastic design spectrum of the check.")]

def _columns(path):
    """A CSV's numeric columns as arrays (text columns as lists)."""
    columns, rows = read_table(path)
    result = {}
    for k, name in enumerate(columns):
        values = [row[k] for row in rows]
        result[name] = (np.array(values) if all(isinstance(v, float) for v in values)
                        else values)
    return result


# ---- the sheet --------------------------------------------------------------------------------

def design_report(input, out) -> CalcSheet:
    """Run a namelist file as `sloshdyn-py run` does, its CSV files into `out`, and write the
    calc sheet built from them: out/report.md, out/report.html (self-contained) and the
    figures (PNG); returns their paths (CalcSheet). The run's files are committed together by the
    run; the sheet's files (motion.csv, spectrum.csv, the figures, report.md, report.html)
    together afterwards, or none of them (an earlier report.md/report.html in `out` is removed
    once the run has written its files, so a sheet never disagrees with the CSV files beside
    it; a failed run writes none of its files and leaves an earlier sheet with its own). Only a
    tank under ground motion, or a tank with &design, is reported (SUPPORTED); other inputs
    raise InputError."""
    path = Path(os.fsdecode(input))
    out = Path(os.fsdecode(out))
    try:
        inp = read_namelist(path)
    except SloshdynError as exc:
        exc.reading = True
        raise
    seismic = inp.analysis == "seismic" and inp.ground_motion is not None
    if inp.tank is None or not (seismic or inp.design is not None):
        error = InputError(f"{path}: the calc sheet reports {SUPPORTED}; this file asks for "
                           f"kind = '{inp.analysis}'"
                           + ("" if inp.tank is not None else " with &model (no &tank)"))
        error.reading = True
        raise error
    records = _record_files(path)
    hashes = [(path.name, _sha256(path))] + [(p.name, _sha256(p)) for p in records]
    captured = []
    with _captured_output(captured):
        run_input(path, out)
    for name in ("report.md", "report.html"):   # an earlier sheet: not of these CSV files
        with file_error(out / name, "remove"):
            (out / name).unlink(missing_ok=True)
    when = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M:%S UTC")
    spatial = not inp.planar
    run = {}
    if (out / "run_info.csv").exists():
        columns, rows = read_table(out / "run_info.csv")
        run = dict(zip(columns, rows[0]))
    write_csv(out / "inputs.csv", _inputs_table(inp))
    if seismic:
        write_csv(out / "motion.csv", _motion_table(inp, {"records": records, "run": run}))
        write_csv(out / "spectrum.csv", _spectrum_table(inp))
    freeboard = inp.tank.freeboard
    figures = _figures(out, spatial, freeboard, seismic)
    sections = _sections(out, path, hashes, __version__, when, _verdicts(captured[0]), figures)
    title = f"{'Seismic' if seismic else 'Design'} calc sheet: {path.name}"
    with run_directory(out):        # the two renamed into place together, or neither
        write_text(out / "report.md", to_markdown(title, sections))
        write_text(out / "report.html", to_html(title, sections, out))
    return CalcSheet(out / "report.md", out / "report.html",
                     tuple(out / name for name, _ in figures),
                     tuple(out / block.source for section in sections for block in section.blocks
                           if isinstance(block, Table) and block.source))


def _sections(out, path, hashes, version, when, verdicts, figures):
    head = Section("Run", [Table(["item", "value"], [
        ["sloshdyn version", version], ["date", when], ["input file", str(path)],
        ["output directory", str(out)]] + [[f"SHA-256 of {name}", digest]
                                          for name, digest in hashes])])
    inputs = Section("Inputs", [
        Paragraph("The input file (read by the namelist reader of the executable; &output "
                  "directory is replaced by the output directory above):"),
        Paragraph(path.read_text(encoding="utf-8", errors="replace"), code=True)])
    sections = [head, inputs]
    by_title = {"Inputs": inputs}
    for title, name in TABLES:
        if (out / name).exists():
            if title not in by_title:
                by_title[title] = Section(title)
                sections.append(by_title[title])
            exact = name == "inputs.csv"       # inputs in full, results to DIGITS
            by_title[title].blocks.append(render_table(
                out / name, CAPTIONS.get(name, ""), None if exact else MAX_ROWS,
                INPUT_DIGITS if exact else DIGITS))
    if verdicts:
        by_title["Nonlinear run"].blocks.extend([Paragraph("Verdicts, as the executable "
                                                           "prints them:"), Bullets(verdicts)])
    placement = {"ground_motion.png": "Motion", "spectrum.png": "Motion",
                 "design_spectrum.png": "Design codes",
                 "wave.png": "Nonlinear run", "loads.png": "Nonlinear run",
                 "wall_pressure.png": "Wall pressure"}
    for name, caption in figures:
        section = by_title.get(placement[name])
        if section is None:
            section = by_title[placement[name]] = Section(placement[name])
            sections.append(section)
        section.blocks.append(Figure(name, caption))
    return sections
