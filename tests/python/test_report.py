"""The calc sheet (`sloshdyn-py report`, sloshdyn.design_report; issue 25 item 5) on the three
tank examples under records and the one under harmonic motion (whose wave reaches the roof):
every number of report.md is the one of the CSV file it names, to the printed precision (the
CSV files re-read here with the csv module; units converted with the factors below, typed from
their definitions), the verdict lines agree with the CSV numbers they summarise, report.html
holds the same tables and lines, the hashes are hashlib's, the figures are PNG files; failures
leave no sheet, bad inputs are refused with a message naming the kinds supported."""

import csv
import hashlib
import html.parser
import math
import re
from pathlib import Path

import f90nml
import pytest

import sloshdyn
from sloshdyn import cli, report

EXAMPLES = Path(__file__).resolve().parents[2] / "data" / "examples"
TANKS = ("tank_seismic", "tank_rectangular_seismic", "tank_two_components", "tank_harmonic")
#: engineering unit -> SI factor (1 kN = 1e3 N, 1 t = 1e3 kg, 1 g = 9.80665 m/s^2 standard)
FACTORS = {"kN": 1e3, "MN": 1e6, "kN·m": 1e3, "MN·m": 1e6, "kPa": 1e3, "kN/m": 1e3, "t": 1e3,
           "g": 9.80665, "MN·m/rad": 1e6, "MN·m·s/rad": 1e6}
PNG = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def sheets(tmp_path_factory):
    """{example: output directory} after one report of each tank example."""
    out = {}
    for name in TANKS:
        out[name] = tmp_path_factory.mktemp(name)
        sheet = sloshdyn.design_report(EXAMPLES / f"{name}.nml", out[name])
        assert (sheet.markdown, sheet.html) == (out[name] / "report.md", out[name] / "report.html")
        assert all(p.exists() for p in sheet.figures + sheet.tables)
    return out


def read_csv(path):
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def significant(text):
    """Significant digits printed in a number's text."""
    mantissa = re.sub(r"[eE].*", "", text.lstrip("-"))
    if "." not in mantissa:
        mantissa = mantissa.rstrip("0")                  # 105630: the zero only places
    return len(mantissa.replace(".", "").lstrip("0"))


def check_number(text, csv_text, factor, digits, where):
    """A printed number is the CSV value / factor rounded to `digits` significant digits (or
    fewer when the rest are zeros); NaN prints as a dash."""
    value = float(csv_text)
    if math.isnan(value):
        assert text == "—", where
        return
    shown, exact = float(text), value / factor
    assert significant(text) <= digits, where
    if exact != 0:
        ulp = 10.0 ** (math.floor(math.log10(abs(exact))) - digits + 1)
        assert abs(shown - exact) <= 0.5 * ulp * (1 + 1e-9), (where, text, exact)
    else:
        assert shown == 0, where


def check_cell(text, csv_text, factor, digits, where):
    try:
        float(csv_text)
    except ValueError:
        assert text == csv_text, where
        return
    check_number(text, csv_text, factor, digits, where)


def markdown_tables(text):
    """[(source CSV name or '', header, rows)] of the Markdown tables."""
    lines, tables = text.splitlines(), []
    k = 0
    while k < len(lines):
        if lines[k].startswith("|") and k + 1 < len(lines) and lines[k + 1].startswith("|---"):
            source = re.search(r"Source: (\S+\.csv)", lines[k - 2]) if k >= 2 else None
            header = [c.strip() for c in lines[k].strip("|").split("|")]
            rows, k = [], k + 2
            while k < len(lines) and lines[k].startswith("|"):
                rows.append([c.strip() for c in lines[k].strip("|").split("|")])
                k += 1
            tables.append((source.group(1) if source else "", header, rows))
        k += 1
    return tables


def split_unit(column):
    match = re.fullmatch(r"(.*?) \[(.*)\]", column)
    return (match.group(1), match.group(2)) if match else (column, "")


def factor(shown_unit, csv_column):
    """SI per unit shown (1 where the CSV column is in that unit already, e.g. [g])."""
    return 1.0 if split_unit(csv_column)[1] == shown_unit else FACTORS.get(shown_unit, 1.0)


def check_table(out, source, header, rows):
    """Every cell of a sheet table against its CSV file; every CSV column is shown."""
    columns, csv_rows = read_csv(out / source)
    names = {split_unit(c)[0]: k for k, c in enumerate(columns)}
    digits = 12 if source == "inputs.csv" else 5
    shown = set()
    if header[:3] == ["quantity", "value", "unit"]:          # one CSV row, one line per column
        assert len(csv_rows) == 1
        row = csv_rows[0]
        for line in rows:
            quantity, value, unit = line[:3]
            k = names[quantity]
            shown.add(k)
            check_cell(value, row[k], factor(unit, columns[k]), digits, (source, quantity))
            if unit not in FACTORS:
                assert unit == split_unit(columns[k])[1], (source, quantity)
            if len(line) > 3 and line[3]:                     # the time of this peak
                base = quantity.removeprefix("peak_")
                candidates = [f"time_{base}", f"{quantity}_time", f"{base.split('_')[0]}_time"]
                t = next(names[c] for c in candidates if c in names)
                shown.add(t)
                check_number(line[3], row[t], 1.0, digits, (source, quantity, "time"))
    else:                                                     # one column per CSV column
        ks = [names[split_unit(h)[0]] for h in header]
        shown.update(ks)
        if len(rows) == len(csv_rows):
            selected = csv_rows
        else:                                                 # a long table: rows it shows
            assert len(rows) <= 25 and rows[0] and len(csv_rows) > 25
            selected = None
        for i, line in enumerate(rows):
            for h, k, text in zip(header, ks, line):
                unit = split_unit(h)[1]
                if selected is not None:
                    check_cell(text, selected[i][k], factor(unit, columns[k]), digits,
                               (source, i, h))
    assert shown == set(range(len(columns))), (source, "columns not shown")


def test_every_number_is_the_csv_one(sheets):
    for name, out in sheets.items():
        text = (out / "report.md").read_text()
        tables = markdown_tables(text)
        sources = [t[0] for t in tables if t[0]]
        expected = {"inputs.csv", "motion.csv", "tank.csv", "design_codes.csv"}
        expected |= ({"seismic_spatial_peaks.csv"} if name == "tank_two_components" else
                     {"seismic_peaks.csv", "run_info.csv"})
        if name == "tank_rectangular_seismic":
            expected.add("tank_modes.csv")
        else:      # a circular tank's planar run: the pressure at its peaks
            expected |= set() if name == "tank_two_components" else {
                "pressure_at_peaks.csv", "wall_pressure_at_shear_peak.csv",
                "wall_pressure_at_moment_peak.csv"}
        assert set(sources) == expected, name
        for source, header, rows in tables:
            if source:
                check_table(out, source, header, rows)
        # outside the tables, the verdicts (test_verdicts_agree_with_the_csv) and the input
        # file, only the captions' constants: "0.5 % damping", "modes 2..N", "100/30", "0 where"
        rest = re.sub(r"```.*?```", "", text, flags=re.S)
        rest = "\n".join(line for line in rest.splitlines() if not line.startswith(("|", "- ")))
        assert set(re.findall(r"\d+(?:\.\d+)?", rest)) <= {"0", "0.5", "2", "100", "30"}, name


def test_head_version_hashes_and_input(sheets):
    for name, out in sheets.items():
        text = (out / "report.md").read_text()
        head = {row[0]: row[1] for row in markdown_tables(text)[0][2]}
        assert head["sloshdyn version"] == sloshdyn.__version__
        assert re.fullmatch(r"\d{4}-\d\d-\d\d \d\d:\d\d:\d\d UTC", head["date"])
        nml = EXAMPLES / f"{name}.nml"
        assert head[f"SHA-256 of {nml.name}"] == hashlib.sha256(nml.read_bytes()).hexdigest()
        group = f90nml.read(nml)["ground_motion"]
        for key in ("record", "record_y"):
            if key in group:
                record = EXAMPLES / group[key]
                assert head[f"SHA-256 of {record.name}"] == \
                    hashlib.sha256(record.read_bytes()).hexdigest()
        # the input file itself, verbatim
        assert f"```\n{nml.read_text().rstrip()}\n```" in text


def test_inputs_as_read_equal_the_file(sheets):
    """The values the sheet lists as read equal those the file gives (f90nml reads the file
    here, independently of the core's reader)."""
    for name, out in sheets.items():
        nml = f90nml.read(EXAMPLES / f"{name}.nml")
        rows = next(t[2] for t in markdown_tables((out / "report.md").read_text())
                    if t[0] == "inputs.csv")
        listed = {(group, variable): value for group, variable, value, _ in rows}
        for group in ("tank", "seismic", "integration"):
            for variable, value in nml.get(group, {}).items():
                if variable == "planar":
                    assert listed[(f"&{group}", variable)] == (".true." if value else ".false.")
                elif isinstance(value, str):
                    assert listed[(f"&{group}", variable)] == value
                else:
                    assert float(listed[(f"&{group}", variable)]) == pytest.approx(value,
                                                                                    rel=1e-11)
        if "azimuth" in nml["ground_motion"]:
            assert float(listed[("&ground_motion", "azimuth")]) == pytest.approx(
                nml["ground_motion"]["azimuth"], rel=1e-11)


def test_motion_is_the_target_and_the_run_info(sheets):
    """The Sa at the sloshing period is the namelist's target_sa (the reader scaled the record
    to it); for planar runs motion.csv's numbers are run_info.csv's (the executable's)."""
    for name, out in sheets.items():
        given = f90nml.read(EXAMPLES / f"{name}.nml")["ground_motion"]
        columns, rows = read_csv(out / "motion.csv")
        motion = dict(zip(columns, rows[0]))
        if "target_sa" in given:
            assert float(motion["sa_sloshing_period [m/s^2]"]) / 9.80665 == pytest.approx(
                given["target_sa"], rel=1e-6)
        else:                                                    # harmonic motion
            assert motion["kind"] == "harmonic"
            assert float(motion["peak_ground_acceleration [m/s^2]"]) / 9.80665 == \
                pytest.approx(given["peak_acceleration"], rel=1e-12)
            assert float(motion["frequency [Hz]"]) == given["frequency"]
        tank = dict(zip(*[row for rows in [read_csv(out / "tank.csv")] for row in
                          (rows[0], rows[1][0])]))
        assert float(motion["sloshing_period [s]"]) == float(tank["sloshing_period [s]"])
        if (out / "run_info.csv").exists():
            columns, rows = read_csv(out / "run_info.csv")
            info = dict(zip(columns, rows[0]))
            assert motion["record"] == info["record"]
            for column in ("scale_factor", "peak_ground_acceleration [m/s^2]",
                           "sa_sloshing_period [m/s^2]"):
                assert float(motion[column]) == pytest.approx(float(info[column]), rel=1e-9)


def test_verdicts_agree_with_the_csv(sheets):
    for name, out in sheets.items():
        text = (out / "report.md").read_text()
        lines = [line[2:] for line in text.split("Verdicts, as the executable prints them:")[1]
                 .splitlines() if line.startswith("- ")]
        assert lines, name
        tank = dict(zip(*(lambda c, r: (c, r[0]))(*read_csv(out / "tank.csv"))))
        if name == "tank_two_components":
            columns, rows = read_csv(out / "seismic_spatial_peaks.csv")
        else:
            columns, rows = read_csv(out / "seismic_peaks.csv")
        peaks = dict(zip(columns, rows[0]))
        for line in lines:
            if m := re.fullmatch(r"the free wave does not reach the roof: its peak (?:around the "
                                 r"wall )?is (\S+) % of the freeboard \((\S+) m\)", line):
                assert peaks["roof_reached"] == "0"
                check_number(m[1], 100 * float(peaks["free_wave_height [m]"]), 1, 3, line)
                assert float(m[2]) == float(tank["freeboard [m]"])
            elif m := re.fullmatch(r"the free wave reaches the roof: first at t = (\S+) s(?: at "
                                   r"azimuth (\S+) rad)?, (\d+) time\(s\); it rises to (\S+) m at "
                                   r"the wall(?: \(the wave height above is capped at the "
                                   r"roof\))?", line):
                assert peaks["roof_reached"] == "1"
                check_number(m[1], float(peaks["first_roof_time [s]"]), 1, 5, line)
                if m[2]:
                    check_number(m[2], float(peaks["first_contact_azimuth [rad]"]), 1, 5, line)
                assert int(m[3]) == int(peaks["roof_impacts"])
                check_number(m[4], float(peaks["free_wave_height [m]"]), 1, 5, line)
            elif m := re.fullmatch(r"flat roof, restricted sloshing: head (\S+) m, uplift (\S+) "
                                   r"MN, confined convective mass (\S+) kg, moving with the "
                                   r"tank from the first contact on.*", line):
                check_number(m[1], float(peaks["roof_head [m]"]), 1, 5, line)
                check_number(m[2], float(peaks["roof_uplift_force [N]"]), 1e6, 5, line)
                check_number(m[3], float(peaks["confined_convective_mass [kg]"]), 1, 5, line)
            elif m := re.fullmatch(r"ground motion (.+): scale factor (\S+), PGA (\S+) g, "
                                   r"Sa\((\S+) s, 0.5 %\) (\S+) g", line):
                info = dict(zip(*(lambda c, r: (c, r[0]))(*read_csv(out / "run_info.csv"))))
                assert m[1] == (f"'{info['record']}'" if info["record"] else "harmonic")
                check_number(m[2], float(info["scale_factor"]), 1, 5, line)
                check_number(m[3], float(info["peak_ground_acceleration [m/s^2]"]), 9.80665,
                             5, line)
                check_number(m[4], float(info["sloshing_period [s]"]), 1, 4, line)
                check_number(m[5], float(info["sa_sloshing_period [m/s^2]"]), 9.80665, 5, line)
            elif m := re.fullmatch(r"codes' combinations of the two planar runs \(SRSS, "
                                   r"100/30\): wave height (\S+), (\S+) m; base shear (\S+), "
                                   r"(\S+) MN", line):
                for text, column, factor in zip(m.groups(), (
                        "wave_height_srss [m]", "wave_height_100_30 [m]",
                        "base_shear_srss [N]", "base_shear_100_30 [N]"), (1, 1, 1e6, 1e6)):
                    check_number(text, float(peaks[column]), factor, 5, line)
            elif m := re.fullmatch(r"wall pressure at the (base shear|overturning moment|"
                                   r"overturning moment including base pressure) peak "
                                   r"\(t = (\S+) s\): largest (\S+) kPa at z = (\S+) m \((\S+)\)",
                                   line):
                _, instants = read_csv(out / "pressure_at_peaks.csv")
                k = ["base shear", "overturning moment",
                     "overturning moment including base pressure"].index(m[1])
                check_number(m[2], instants[k][0], 1, 5, line)
                _, wall = read_csv(out / m[5])
                top = max(wall, key=lambda row: abs(float(row[3])))
                check_number(m[3], top[3], 1e3, 5, line)
                check_number(m[4], top[0], 1, 5, line)
            else:
                # the examples run without the paper's impact model: nothing else is printed
                raise AssertionError(f"{name}: an unexpected verdict line: {line}")


class _Html(html.parser.HTMLParser):
    """Table cells, list items and embedded images of report.html."""

    def __init__(self):
        super().__init__()
        self.tables, self.items, self.images, self._text = [], [], [], None

    def handle_starttag(self, tag, attrs):
        if tag == "table":
            self.tables.append([])
        elif tag == "tr":
            self.tables[-1].append([])
        elif tag in ("td", "th", "li"):
            self._text = ""
        elif tag == "img":
            self.images.append(dict(attrs)["src"])

    def handle_data(self, data):
        if self._text is not None:
            self._text += data

    def handle_endtag(self, tag):
        if tag in ("td", "th"):
            self.tables[-1][-1].append(self._text.strip())
            self._text = None
        elif tag == "li":
            self.items.append(self._text.strip())
            self._text = None


def test_html_holds_the_same_tables_lines_and_figures(sheets):
    import base64
    for name, out in sheets.items():
        text = (out / "report.md").read_text()
        page = _Html()
        page.feed((out / "report.html").read_text())
        md = [[header] + rows for _, header, rows in markdown_tables(text)]
        assert page.tables == md, name
        assert page.items == [line[2:] for line in text.splitlines() if line.startswith("- ")]
        figures = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", text)
        assert len(page.images) == len(figures) >= 4
        for src, figure in zip(page.images, figures):
            assert src.startswith("data:image/png;base64,")
            assert base64.b64decode(src.split(",", 1)[1]) == (out / figure).read_bytes()
            assert (out / figure).read_bytes().startswith(PNG)
        assert {"ground_motion.png", "spectrum.png", "wave.png", "loads.png"} <= set(figures)


@pytest.mark.parametrize("example, sources", [
    ("tank_design", ["API 650", "ACI 350.3", "sloshdyn linear"]),
    ("tank_slender_design", ["EC8-4", "sloshdyn linear"])])
def test_a_design_check_sheet(tmp_path, example, sources):
    """A tank with &design and no ground motion (kind = 'linear'): the design sheet holds the
    inputs with &design, the tank, the codes' values, loads, freeboard checks and wall
    pressure, every number equal to its CSV; the design spectrum and the pressure profile as
    figures (in the HTML too); no motion."""
    import base64
    sheet = sloshdyn.design_report(EXAMPLES / f"{example}.nml", tmp_path)
    text = sheet.markdown.read_text()
    assert text.startswith(f"# Design calc sheet: {example}.nml")
    tables = markdown_tables(text)
    assert {t[0] for t in tables if t[0]} == {
        "inputs.csv", "tank.csv", "design_codes.csv", "design_loads.csv", "freeboard_check.csv",
        "wall_pressure.csv", "pressure_resultants.csv"}
    for source, header, rows in tables:
        if source:
            check_table(tmp_path, source, header, rows)
    loads = next(rows for source, _, rows in tables if source == "design_loads.csv")
    assert [row[0] for row in loads] == sources
    inputs = next(rows for source, _, rows in tables if source == "inputs.csv")
    design = f90nml.read(EXAMPLES / f"{example}.nml")["design"]
    shown = {row[1]: row[2] for row in inputs if row[0] == "&design"}
    for name, value in design.items():
        if isinstance(value, str):
            assert shown[name] == value
        else:
            assert float(shown[name]) == pytest.approx(value, rel=1e-12)
    assert not (tmp_path / "motion.csv").exists()
    figures = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", text)
    assert figures == ["design_spectrum.png", "wall_pressure.png"]
    page = _Html()
    page.feed(sheet.html.read_text())
    for src, figure in zip(page.images, figures):
        assert base64.b64decode(src.split(",", 1)[1]) == (tmp_path / figure).read_bytes()


def test_any_table_renders_by_its_units(tmp_path):
    """The generic renderer on tables such as the coming design_loads.csv and
    wall_pressure.csv: engineering units from the column names, every value to 5 digits, a long
    table shown by evenly spaced rows with its first and last."""
    loads = tmp_path / "design_loads.csv"
    loads.write_text("code,base_shear [N],overturning_moment [N m],mass [kg],p [Pa],"
                     "hoop_force [N/m],a [m/s^2],ratio\n"
                     "API 650,1234567.89,98765.4321,289000.5,12345.678,2.5e5,1.96133,0.123456\n"
                     "EC8-4,2345.6,nan,1,0,-3.5,9.80665,7\n")
    table = report.render_table(loads)
    assert table.header == ["code", "base_shear [MN]", "overturning_moment [kN·m]", "mass [t]",
                            "p [kPa]", "hoop_force [kN/m]", "a [g]", "ratio"]
    check_table(tmp_path, "design_loads.csv", table.header, table.rows)
    assert table.rows[1][2] == "—"
    pressure = tmp_path / "wall_pressure.csv"
    pressure.write_text("z [m],p_impulsive [Pa]\n"
                        + "".join(f"{6 * k / 99},{1000.0 * k}\n" for k in range(100)))
    table = report.render_table(pressure)
    assert len(table.rows) == 25
    assert table.rows[0] == ["0", "0"] and table.rows[-1] == ["6", "99"]
    check_table(tmp_path, "wall_pressure.csv", table.header, table.rows)
    one = tmp_path / "freeboard_check.csv"
    one.write_text("required_freeboard [m],available_freeboard [m],sufficient\n"
                   "0.8765432,1.0,1\n")
    table = report.render_table(one)
    check_table(tmp_path, "freeboard_check.csv", table.header, table.rows)


def test_a_failure_leaves_no_sheet(tmp_path, monkeypatch):
    """A sheet that fails while written leaves neither report.md nor report.html (not even
    one from an earlier report in the directory) and no temporary file."""
    (tmp_path / "report.md").write_text("an earlier sheet")

    def fail(*args):
        raise RuntimeError("disk on fire")
    monkeypatch.setattr(report, "to_html", fail)
    with pytest.raises(RuntimeError, match="disk on fire"):
        sloshdyn.design_report(EXAMPLES / "tank_seismic.nml", tmp_path)
    names = {p.name for p in tmp_path.iterdir()}
    assert "report.md" not in names and "report.html" not in names
    assert not [n for n in names if ".partial" in n]
    assert "seismic_peaks.csv" in names           # the run's files are complete


@pytest.mark.parametrize("example, kind", [("fig12_linear.nml", "linear"),
                                           ("tank_linear.nml", "linear"),
                                           ("tank_frequency_sweep.nml", "sweep")])
def test_inputs_it_cannot_report(tmp_path, capsys, example, kind):
    assert f90nml.read(EXAMPLES / example)["analysis"]["kind"] == kind
    code = cli.main(["report", str(EXAMPLES / example), "--out", str(tmp_path / "sheet")])
    err = capsys.readouterr().err
    assert code == 3, err
    assert f"kind = '{kind}'" in err and "kind = 'seismic' with &tank and &ground_motion" in err
    assert not (tmp_path / "sheet").exists()


def test_command_line_writes_the_sheet(tmp_path, capsys):
    assert cli.main(["report", str(EXAMPLES / "tank_seismic.nml"), "--out",
                     str(tmp_path)]) == 0
    printed = capsys.readouterr().out
    assert "the free wave does not reach the roof" in printed      # the run's summary, passed on
    assert f"calc sheet: {tmp_path / 'report.md'}" in printed
    assert (tmp_path / "report.html").exists()


def test_an_output_directory_that_is_a_file(tmp_path, capsys):
    """--out naming a file: the run cannot write there, a file error (exit 5) naming it."""
    (tmp_path / "calc").write_text("not a directory")
    code = cli.main(["report", str(EXAMPLES / "tank_seismic.nml"), "--out",
                     str(tmp_path / "calc")])
    err = capsys.readouterr().err
    assert code == 5, err
    assert "calc" in err and "internal error" not in err
