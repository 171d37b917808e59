"""The calc sheet of a tank (issues 25 and 39): `sloshdyn-py report INPUT.nml --out DIR` and
`sloshdyn.design_report(input, out)`.

The input runs exactly as `sloshdyn-py run` runs it (the one reader, the same driver and writers,
through the bridge), its files written into a directory of the sheet's own; the sheet is then
built from that directory's files only, so every number in it is one of theirs, rounded for
print, and no file of an earlier run can enter it. The sheet's order is a checker's: the title
block (with the fields a checker signs), the summary of every check, the inputs with their
units, each code's calculation, the wall pressure, the nonlinear run, the assumptions
(docs/design.md), and an appendix with the model's research parameters and the input file.
One document (report_layout) is written as report.md, a self-contained report.html with print
CSS, and report.pdf (WeasyPrint). The directory, run and sheet together, then replaces DIR as
a whole, or nothing is replaced (docs/python.md, "The calc sheet")."""

from __future__ import annotations

import contextlib
import datetime
import hashlib
import os
import re
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

from . import _tables
from ._errors import FileError, InputError, SloshdynError
from ._files import file_error, run_directory, write_csv, write_text
from ._version import __version__
from .ground import SPECTRUM_FIELDS
from .namelist import read_namelist
from .report_figures import draw_figures
from .report_layout import (INPUT_DIGITS, PAPERS, Bullets, Figure, Paragraph, Section,
                            Table, number, plain_number, to_html, to_markdown)
from .report_pdf import write_pdf
from .report_tables import (cell, display_unit, inputs_table, motion_table, one_row, read_table,
                            render_table, spectrum_table, split_name)
from .runner import run_input

#: the analyses the sheet reports: a tank (&tank) under ground motion (&ground_motion), or a
#: tank's design check (&design) against a code spectrum in any analysis of the tank
SUPPORTED = "&analysis kind = 'seismic' with &tank and &ground_motion (planar, or two components " \
            "with &tank planar = .false.), or a &tank with &design (the design check against its " \
            "code spectrum)"
#: quantities of the paper's impact model (eq 4-5: the smooth wall, beta, delta): never on the
#: sheet, whose loads rest on the tank's physics and the codes (DESIGN.md, "Two models")
IMPACT_MODEL = ("peak_impact_force", "time_impact_force", "impact_force", "beta_sensitive",
                "impact_stiffness", "impact_damping", "impact_coefficient", "beta", "delta",
                "n", "p")
#: the model's dimensionless (research) quantities of tank.csv: in the appendix only
RESEARCH = ("d1", "d0", "omega", "theta0", "wave_factor", "s1", "mu1", "kappa", "gamma", "zeta")
#: the &design fields of each spectrum (docs/namelist.md, &design; the others are not shown)
SPECTRUM_INPUTS = {"asce7": ("s_ds", "s_d1", "t_l", "k"), "aci350": ("s_ds", "s_d1", "t_l"),
                   "ec8": ("a_gr", "gamma_i", "ground_type", "spectrum_type", "q", "beta"),
                   "ground_motion": ()}
#: what a 0 of a &tank or &seismic input means (docs/namelist.md; &design's and
#: &tank_structure's say it in the core's layout descriptions)
ZERO_MEANS = {"support_height": "0: liquid_depth + freeboard",
              "roof_slope": "0: not a cone roof", "roof_radius": "0: not a dome roof",
              "t_end": "0: the run's default", "n_out": "0: the run's default"}
#: docs/design.md as the package installs it (beside the reference tables; meson.build)
DESIGN_PAGE = Path(__file__).parent / "reference" / "design.md"


@dataclass(frozen=True)
class CalcSheet:
    """The files of a calc sheet (design_report): report.md, report.html, report.pdf, the
    figures (PNG) and the CSV files whose numbers it shows, in its order."""

    markdown: Path
    html: Path
    pdf: Path
    figures: tuple
    tables: tuple


def design_report(input, out, *, project="", prepared_by="", paper="a4") -> CalcSheet:
    """Run a namelist file as `sloshdyn-py run` does and write its calc sheet: out/report.md,
    out/report.html (self-contained, print CSS for `paper`, 'a4' or 'letter'), out/report.pdf,
    the figures (PNG) and the run's CSV files. project and prepared_by fill the title block
    (checked by and its date are left for the checker). Everything is written into a new
    directory beside `out` and replaces `out` as a whole when complete; a failure or an
    interruption leaves `out` as it was (a directory not written by sloshdyn is refused).
    Only a tank under ground motion, or a tank with &design, is reported (SUPPORTED); other
    inputs raise InputError."""
    if paper not in PAPERS:
        raise InputError(f"paper = {paper!r} is not valid: give one of {', '.join(PAPERS)}")
    path = Path(os.fsdecode(input))
    out = Path(os.fsdecode(out))
    if os.fsdecode(input) == "-":
        raise InputError("the calc sheet shows and hashes its input file: give a file, not "
                         "standard input (-)")
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
    if inp.tank.roof_contact != "none":
        error = InputError(f"{path}: &tank roof_contact = '{inp.tank.roof_contact}' is the "
                           "paper's impact model (eq 4-5), a research model whose loads rest on "
                           "its contact stiffness beta; the calc sheet reports the codes' "
                           "restricted-sloshing loads: give roof_contact = 'none' (the default)")
        error.reading = True
        raise error
    source = _input_file(path)
    sheet = {"path": path, "source": source, "version": __version__, "paper": paper,
             "project": str(project), "prepared_by": str(prepared_by), "out": out,
             "when": datetime.datetime.now(datetime.timezone.utc).strftime(
                 "%Y-%m-%d %H:%M:%S UTC")}
    with run_directory(out) as run:
        with _captured_output():
            run_input(path, os.path.abspath(out), run.path)
        names = write_sheet(run.path, inp, sheet)
    return CalcSheet(out / "report.md", out / "report.html", out / "report.pdf",
                     tuple(out / name for name in names["figures"]),
                     tuple(out / name for name in names["tables"]))


def write_sheet(directory, inp, sheet):
    """The sheet step: the sheet's own tables and figures, then report.md, report.html and
    report.pdf, all from the files in `directory` (the run's); {'figures', 'tables': names}."""
    seismic = inp.analysis == "seismic" and inp.ground_motion is not None
    write_csv(directory / "inputs.csv", inputs_table(inp))
    if inp.ground_motion is not None:        # also a design check on the motion's spectrum
        run = one_row(directory / "run_info.csv") if (directory / "run_info.csv").exists() else {}
        write_csv(directory / "motion.csv", motion_table(inp, {"records": sheet["source"][
            "records"], "run": run}))
        write_csv(directory / "spectrum.csv", spectrum_table(inp))
    figures = draw_figures(directory, not inp.planar, inp.tank.freeboard, seismic,
                           inp.ground_motion is not None)
    title = f"{'Seismic' if seismic else 'Design'} calc sheet: {sheet['path'].name}"
    sections = _sections(directory, inp, sheet, figures, seismic)
    page = to_html(title, sections, directory, sheet["paper"])
    write_text(directory / "report.md", to_markdown(title, sections))
    write_text(directory / "report.html", page)
    write_pdf(page, directory / "report.pdf")
    return {"figures": [name for name, _ in figures],
            "tables": [block.source for section in sections for block in section.blocks
                       if isinstance(block, Table) and block.source]}


# ---- the input file, read as the executable reads it ----------------------------------------

def _input_file(path):
    """The input file as bytes (hashed), as text for the sheet (UTF-8; any other byte shown as
    a \\xNN escape: the executable reads bytes, and a comment may hold any), and its record
    files (&ground_motion record, record_y: paths of bytes, relative to the input's folder)
    with their hashes."""
    import f90nml    # deferred: only the sheet needs it, and it adds ~30 ms to `import sloshdyn`
    with file_error(path, "read"):
        data = path.read_bytes()
    group = f90nml.reads(data.decode("utf-8", "surrogateescape")).get("ground_motion", {})
    folder = path.resolve().parent
    records = [folder / group[name] for name in ("record", "record_y")
               if str(group.get(name) or "").strip()]
    return {"bytes": data, "text": data.decode("utf-8", "backslashreplace"),
            "hashes": [(path.name, hashlib.sha256(data).hexdigest())]
            + [(p.name, _sha256(p)) for p in records],
            "records": records}


def _sha256(path):
    digest = hashlib.sha256()
    with file_error(path, "read"), open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def _shown(name):
    """A file name as the sheet prints it (bytes that are not UTF-8 as \\xNN escapes)."""
    return os.fsencode(name).decode("utf-8", "backslashreplace")


@contextlib.contextmanager
def _captured_output():
    """The core's summary (printed on file descriptor 1) passed on to sys.stdout, so that a
    caller that captures sys.stdout (a notebook, pytest's capsys) gets it."""
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
            sys.stdout.write(f.read().decode("utf-8", errors="replace"))
            sys.stdout.flush()


# ---- the sections -----------------------------------------------------------------------------

def _sections(directory, inp, sheet, figures, seismic):
    placement = {"ground_motion.png": "Inputs", "spectrum.png": "Inputs",
                 "design_spectrum.png": "Design codes", "wave.png": "Nonlinear run",
                 "loads.png": "Nonlinear run", "wall_pressure.png": "Wall pressure"}
    sections = [_title_block(directory, sheet), _summary(directory, seismic),
                _inputs(directory, inp, seismic)]
    sections += _code_sections(directory)
    sections += [_wall_pressure(directory), _nonlinear_run(directory, seismic),
                 _assumptions()]
    by_title = {section.title: section for section in sections}
    for name, caption in figures:
        by_title[placement[name]].blocks.append(Figure(name, caption))
    sections += _appendix(directory, sheet)
    return [section for section in sections if section.blocks]


def _title_block(directory, sheet):
    """Project, tank, who prepared and who checks (left blank for the checker), the codes and
    editions, the program and the input file (SHA-256; the records' in Appendix B)."""
    tank = one_row(directory / "tank.csv")
    size = (f"circular, radius {number(tank['radius [m]'])} m" if "radius [m]" in tank else
            "rectangular")
    editions = _editions(directory)
    source = sheet["source"]
    rows = [["Project", sheet["project"]],
            ["Tank", f"{_shown(sheet['path'].name)}: {size}, liquid depth "
                     f"{number(tank['liquid_depth [m]'])} m, freeboard "
                     f"{number(tank['freeboard [m]'])} m"],
            ["Prepared by", sheet["prepared_by"]], ["Date prepared", sheet["when"]],
            ["Checked by", ""], ["Date checked", ""],
            ["Codes", "; ".join(editions) or "—"],
            ["Program", f"sloshdyn {sheet['version']}"],
            ["Input file", _shown(sheet["path"])],
            [f"SHA-256 of {_shown(source['hashes'][0][0])}", source["hashes"][0][1]]]
    return Section("Title block", [Table(["item", "entry"], rows, form=True)])


#: a code and its edition as the core's clauses name them ("API 650 13th ed. E.6.1-1")
_EDITION = re.compile(r"API 650 \w+ ed\.|ACI 350\.3-\d+|ASCE 7-\d+|EN 1998-\d:\d{4}")


def _editions(directory):
    """The codes and editions the hand calculation and the checks cite, in order of first
    citation (design_calc.csv, design_checks.csv)."""
    found = []
    for name in ("design_calc.csv", "design_checks.csv"):
        if (directory / name).exists():
            names, rows = read_table(directory / name)
            for row in rows:
                for edition in _EDITION.findall(str(row[names.index("clause")])):
                    if edition not in found:
                        found.append(edition)
    return found


def _summary(directory, seismic):
    """Every check: demand, capacity, ratio and verdict, as the core wrote them
    (design_checks.csv), and the nonlinear run's roof verdict (seismic_peaks.csv)."""
    blocks, codes = [], set()
    checks = directory / "design_checks.csv"
    if checks.exists():
        blocks.append(_checks_table(checks, info=False))
        codes = {row[0] for row in blocks[-1].rows}
    if seismic and (directory / "seismic_peaks.csv").exists() and \
            "sloshdyn nonlinear" not in codes:
        peaks = one_row(directory / "seismic_peaks.csv")
        blocks.append(Table(
            ["code", "check", "demand", "capacity", "unit", "verdict"],
            [["sloshdyn nonlinear", "roof: the free wave's peak at the wall against the "
              "freeboard", number(peaks["free_wave_height [m]"]),
              number(one_row(directory / "tank.csv")["freeboard [m]"]), "m",
              "NOT OK" if peaks["roof_reached"] > 0 else "OK"]],
            "seismic_peaks.csv", "The nonlinear run's roof verdict (free_wave_height, "
                                 "roof_reached; the freeboard from tank.csv)."))
    if checks.exists():          # the values without a capacity after the verdicts
        blocks.append(_checks_table(checks, info=True))
    blocks = [b for b in blocks if b.rows]
    if not blocks:
        blocks = [Paragraph("No check with a verdict: this run writes none (a design check "
                            "needs &design; the spatial run's peaks have no roof verdict).")]
    return Section("Summary of checks", blocks)


def _checks_table(path, info):
    """design_checks.csv's checks with a verdict (OK, NOT OK), or with info its values without
    a capacity (INFO): a row per check, demand and capacity in the row's unit shown (kN or MN
    for N, kPa for Pa, ...), the ratio and the verdict as the core wrote them."""
    names, rows = read_table(path)
    col = {name: k for k, name in enumerate(names)}
    shown = []
    for row in rows:
        if (row[col["verdict"]] == "INFO") != info:
            continue
        unit, factor = display_unit(row[col["unit"]], [row[col["demand"]], row[col["capacity"]]])
        shown.append([row[col["code"]], row[col["check"]], row[col["clause"]],
                      cell(row[col["demand"]], factor), cell(row[col["capacity"]], factor) or "—",
                      unit, cell(row[col["ratio"]]) or "—", row[col["verdict"]]])
    return Table(["code", "check", "clause", "demand", "capacity", "unit", "ratio", "verdict"],
                 shown, path.name,
                 "The values the codes give without a capacity to check them against (INFO)."
                 if info else "Each check of the codes: demand against capacity, ratio = "
                              "demand/capacity, verdict.", wide=True)


def _inputs(directory, inp, seismic):
    """The tank's and the design's inputs with their units and what a 0 means; the ground
    motion as scaled."""
    names, rows = read_table(directory / "inputs.csv")
    blocks = []
    design_shown = set(SPECTRUM_INPUTS.get(inp.design.spectrum, ())) if inp.design else set()
    meaning = {**(_tables.docs("design") if inp.design else {}),
               **_structure_docs(inp)}
    for group, caption in (("&tank", "The tank (SI units, as read; defaults included)."),
                           ("&tank_structure", "The tank's structure (the courses bottom "
                                               "first)."),
                           ("&design", "The design check's inputs for its spectrum "
                                       f"('{inp.design.spectrum if inp.design else ''}') and "
                                       "the codes' factors."),
                           ("&seismic", "The nonlinear run's span."),
                           ("&ground_motion", "The direction of the ground motion.")):
        shown = []
        for g, variable, value, unit in rows:
            if g != group or variable in IMPACT_MODEL:
                continue
            if group == "&design" and variable in SPECTRUM_FIELDS[1:] and \
                    variable not in design_shown:
                continue
            note = ZERO_MEANS.get(variable, "") if value == 0.0 else ""
            unit = unit or _unit_of(meaning.get(variable, ""))
            # the description without a leading unit (the unit column shows it)
            described = re.sub(r"^\[[^\]]*\][;,]?\s*", "", meaning.get(variable, ""))
            shown.append([variable, cell(value, 1.0, INPUT_DIGITS), unit,
                          note or _plain(described)])
        if shown:
            blocks.append(Table(["variable", "value", "unit", "note"], shown, "inputs.csv",
                                caption))
    if (directory / "motion.csv").exists():
        blocks.append(render_table(directory / "motion.csv", "The ground motion as the reader "
                                   "scaled it, and its pseudo-spectral acceleration at the "
                                   "first sloshing period (0.5 % damping)."))
    return Section("Inputs", blocks)


def _structure_docs(inp):
    """The descriptions of &tank_structure's fields by the names inputs.csv gives them
    (course_height_1, ...: the layout's own names)."""
    if getattr(inp, "tank_structure", None) is None:
        return {}
    return _tables.docs("tank_structure")


def _unit_of(text):
    """The unit a layout's description ends its name with, e.g. '... S_DS [g]' -> 'g'."""
    match = re.search(r"\[([^\]]+)\]", text)
    return match.group(1) if match else ""


def _plain(text):
    """A documentation string without Markdown: `code` and [text](link) as plain text."""
    return re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text).replace("`", "")


def _code_sections(directory):
    """Each code's hand calculation (design_calc.csv) where the core writes it; the design
    codes' values and loads."""
    blocks = []
    calc = directory / "design_calc.csv"
    sections = []
    if calc.exists():
        sections += _hand_calculation(calc)
    for name, caption in (
            ("design_codes.csv", "Each design code's periods, masses and heights for this tank, "
                                 "and the wave height from the motion's spectrum (— where a "
                                 "code gives no value)."),
            ("design_loads.csv", "Code-format seismic loads. The codes' rows are at design "
                                 "level (their I, R or q); sloshdyn linear is elastic (no "
                                 "factor): a comparison, not a design load. An "
                                 "impulsive_period of 0 s: the impulsive acceleration taken "
                                 "on the spectrum's plateau (docs/design.md).")):
        if (directory / name).exists():
            blocks.append(render_table(directory / name, caption, hidden=IMPACT_MODEL))
    return sections + [Section("Design codes", blocks)]


def _hand_calculation(path):
    """design_calc.csv, a section per code: each formula as a line of the hand calculation,
    'symbol = formula = numbers = value unit', with its clause, in the core's order."""
    names, rows = read_table(path)
    col = {name: k for k, name in enumerate(names)}
    by_code = {}
    for row in rows:
        by_code.setdefault(row[col["code"]], []).append(row)
    sections = []
    for code, lines in by_code.items():
        shown = []
        for row in lines:
            symbol, formula, numbers = (row[col[k]] for k in ("symbol", "formula",
                                                              "substituted"))
            steps = ([] if str(formula).startswith(f"{symbol} =") else [symbol]) + [formula] \
                + ([numbers] if numbers not in ("", formula) else [])
            shown.append([cell(row[col["step"]], 1.0, 12), row[col["quantity"]],
                          " = ".join(str(s) for s in steps if s != ""),
                          plain_number(row[col["value"]]), row[col["unit"]],
                          row[col["clause"]]])
        sections.append(Section(f"{code}: hand calculation", [Table(
            ["step", "quantity", "formula and numbers", "value", "unit", "clause"], shown,
            path.name, f"{code}: each formula with the numbers put in (5 significant digits) "
                       "and its result.", style="calc")]))
    return sections


def _wall_pressure(directory):
    blocks = []
    for name, caption in (
            ("wall_pressure.csv", "Hydrodynamic wall pressure at theta = 0 (times cos theta "
                                  "around the wall) and the hoop force per unit height "
                                  "(docs/design.md)."),
            ("pressure_resultants.csv", "Resultants of the pressure: impulsive (component 0) "
                                        "and first convective mode (1).")):
        if (directory / name).exists():
            blocks.append(render_table(directory / name, caption))
    return Section("Wall pressure", blocks)


def _nonlinear_run(directory, seismic):
    """The nonlinear run's peaks and what it rests on, without the paper's impact model."""
    blocks = []
    if not seismic:
        return Section("Nonlinear run", blocks)
    for name, caption in (
            ("seismic_peaks.csv", "Peaks of the nonlinear run (largest |value| over the run, at "
                                  "time t) and the roof contact of the free wave."),
            ("seismic_spatial_peaks.csv", "Peaks of the spatial run (two components), beside "
                                          "the codes' SRSS and 100/30 combinations of the two "
                                          "planar runs."),
            ("run_info.csv", "What the run rests on (record, scaling)."),
            ("pressure_at_peaks.csv", "The nonlinear run at its base shear and overturning "
                                      "moment peaks (the output times nearest them)."),
            ("wall_pressure_at_shear_peak.csv", "Hydrodynamic wall pressure of the nonlinear "
                                                "run at its base shear peak, theta = 0."),
            ("wall_pressure_at_moment_peak.csv", "Hydrodynamic wall pressure of the nonlinear "
                                                 "run at its overturning moment peak, "
                                                 "theta = 0.")):
        if (directory / name).exists():
            blocks.append(render_table(directory / name, caption, hidden=IMPACT_MODEL))
    return Section("Nonlinear run", blocks)


def _assumptions():
    """The assumptions of docs/design.md (its section 'Assumptions', installed with the
    package), as they stand there."""
    text = DESIGN_PAGE.read_text(encoding="utf-8")
    return Section("Assumptions", [Bullets(assumptions(text)), Paragraph(
        "From docs/design.md, \"Assumptions\"; each code's clauses and what was verified "
        "against the codes' texts: docs/design.md.")])


def assumptions(page):
    """The bullets of a Markdown page's '## Assumptions' section, as plain text."""
    part = page.split("\n## Assumptions\n", 1)[1].split("\n## ", 1)[0]
    items = re.split(r"\n- ", part)[1:]           # the first piece is the introduction
    return [_plain(" ".join(item.split())) for item in items]


def _appendix(directory, sheet):
    """The model's research quantities (none of the sheet's loads rests on them), the
    values as read in full, and the input file as given."""
    tank = one_row(directory / "tank.csv")
    research = [[name, cell(tank[column], 1.0), split_name(column)[1]]
                for column in tank for name in [split_name(column)[0]] if name in RESEARCH]
    blocks = [Table(["quantity", "value", "unit"], research, "tank.csv",
                    "The equivalent mechanical model's quantities for this tank (docs/model.md): "
                    "the pendulum's offsets d1, d0, its frequency, the angle theta0 at which "
                    "the wave reaches the roof and the wave per sin(theta), and the "
                    "dimensionless groups of eq 9. For research; the sheet's checks do not "
                    "use them (nor the paper's impact model).")]
    return [Section("Appendix A: the model's research quantities", blocks, page_break=True),
            Section("Appendix B: the input file", [
                Table(["item", "value"], [["Output directory", _shown(sheet["out"])]]
                      + [[f"SHA-256 of {_shown(name)}", digest] for name, digest in
                         sheet["source"]["hashes"]]),
                Paragraph("The input file as given (read by the executable's namelist reader, "
                          "&output directory replaced by the output directory above):"),
                Paragraph(sheet["source"]["text"], code=True)])]
