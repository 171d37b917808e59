"""The calc sheet (`sloshdyn-py report`, sloshdyn.design_report; issues 25 and 39) of the tank
examples: its order (title block, summary of checks, inputs, codes, ..., appendix), every number
of report.md the one of the CSV file its table names at the printed precision (the CSV files
re-read here with the csv module, report.md rendered by markdown-it-py; sheet_reading.py), every
verdict of the summary the one its numbers give, report.html the same document, the hashes
hashlib's, the assumptions those of docs/design.md, the paper's impact model nowhere, the
figures PNG files; the executable's tank summary at 5 significant digits."""

import base64
import hashlib
import re
import shutil
import subprocess

import f90nml
import pytest

import sloshdyn
from conftest import EXAMPLES, ROOT
from sheet_reading import (FACTORS, check_cell, check_number, factor, one_row, read_csv,
                           rendered_markdown, split_unit, Page, significant)
from sloshdyn import cli, report

SEISMIC = ("tank_seismic", "tank_rectangular_seismic", "tank_two_components", "tank_harmonic")
DESIGN = ("tank_design", "tank_slender_design")
PNG = b"\x89PNG\r\n\x1a\n"
#: the sheet's sections, in order (those without content left out)
ORDER = ["Title block", "Summary of checks", "Inputs", "Design codes", "Wall pressure",
         "Nonlinear run", "Assumptions", "Appendix A: the model's research quantities",
         "Appendix B: the input file"]


@pytest.fixture(scope="module")
def sheets(tmp_path_factory):
    """{example: output directory} after one report of each tank example."""
    out = {}
    for name in SEISMIC + DESIGN:
        out[name] = tmp_path_factory.mktemp(name) / "sheet"
        sheet = sloshdyn.design_report(EXAMPLES / f"{name}.nml", out[name])
        assert (sheet.markdown, sheet.html, sheet.pdf) == tuple(
            out[name] / f"report.{ext}" for ext in ("md", "html", "pdf"))
        assert all(p.exists() for p in sheet.figures + sheet.tables)
    return out


def page(out):
    return rendered_markdown((out / "report.md").read_text(encoding="utf-8"))


def check_table(out, source, header, rows):
    """Every cell of a sheet table against its CSV file, by the table's kind (its header)."""
    columns, csv_rows = read_csv(out / source)
    col = {split_unit(c)[0]: k for k, c in enumerate(columns)}
    units = {split_unit(c)[0]: split_unit(c)[1] for c in columns}
    if header == ["variable", "value", "unit", "note"]:              # inputs.csv, a group
        for variable, value, unit, _ in rows:
            matches = [r for r in csv_rows if r[1] == variable]
            assert matches, variable
            assert any(r[3] in (unit, "") for r in matches), variable
            check_cell(value, matches[0][2], 1.0, 12, (source, variable))
    elif header[:3] == ["quantity", "value", "unit"]:                 # one CSV row
        assert len(csv_rows) == 1
        row = csv_rows[0]
        for line in rows:
            quantity, value, unit = line[:3]
            k = col[quantity]
            check_cell(value, row[k], factor(unit, units[quantity]), 5, (source, quantity))
            assert unit == units[quantity] or unit in FACTORS, (source, quantity)
            if len(line) > 3 and line[3]:                              # the time of this peak
                base = quantity.removeprefix("peak_")
                time = next(c for c in (f"time_{base}", f"{quantity}_time",
                                        f"{base.split('_')[0]}_time") if c in col)
                check_number(line[3], row[col[time]], 1.0, 5, (source, quantity, "time"))
    elif header[0].endswith(": quantity"):                            # transposed
        labels = header[2:]
        by_label = {r[0]: r for r in csv_rows}
        for quantity, unit, *values in rows:
            for label, text in zip(labels, values):
                check_cell(text, by_label[label][col[quantity]], factor(unit, units[quantity]),
                           5, (source, quantity, label))
    elif header == ["code", "check", "demand", "capacity", "unit", "verdict"]:
        check_summary(out, source, rows)
    elif header == ["code", "check", "clause", "demand", "capacity", "unit", "ratio", "verdict"]:
        check_design_checks(out / source, rows)
    elif header == ["step", "quantity", "formula and numbers", "value", "unit", "clause"]:
        check_hand_calculation(out / source, rows)
    else:                                                             # one column per column
        ks = [col[split_unit(h)[0]] for h in header]
        selected = csv_rows if len(rows) == len(csv_rows) else None
        if selected is None:                                          # a long table's rows
            assert len(rows) <= 25 < len(csv_rows)
            assert rows[0][0] == check_first(csv_rows[0][ks[0]], header[0], columns[ks[0]])
        for i, line in enumerate(rows if selected is not None else []):
            for h, k, text in zip(header, ks, line):
                check_cell(text, selected[i][k], factor(split_unit(h)[1], split_unit(
                    columns[k])[1]), 5, (source, i, h))


def check_first(csv_text, header, column):
    return f"{float(csv_text) / factor(split_unit(header)[1], split_unit(column)[1]):.5g}"


def check_summary(out, source, rows):
    """The summary's rows: demand and capacity the CSV's, the verdict the one the numbers give
    (demand within capacity, as docs/design.md's round-off rule says)."""
    for code, check, demand, capacity, unit, verdict in rows:
        assert unit == "m"
        if source == "freeboard_check.csv":
            row = next(r for r in read_csv(out / source)[1] if r[0] == code)
            columns = read_csv(out / source)[0]
            required = row[columns.index("required_freeboard [m]")]
            available = row[columns.index("available_freeboard [m]")]
            check_number(demand, required, 1, 5, code)
            check_number(capacity, available, 1, 5, code)
            fits = float(required) <= float(available) * (1 + 1e-9)
        else:                                              # the nonlinear run's roof
            peaks = one_row(out / source)
            wave = peaks["free_wave_height [m]"]
            freeboard = one_row(out / "tank.csv")["freeboard [m]"]
            check_number(demand, wave, 1, 5, code)
            check_number(capacity, freeboard, 1, 5, code)
            fits = float(wave) < float(freeboard)
        assert verdict == ("OK" if fits else "NOT OK"), (code, check)


def check_design_checks(path, rows):
    """design_checks.csv's rows in the summary: demand and capacity the CSV's in the unit
    shown, the ratio demand/capacity (divided here), the verdict the one the numbers give
    (demand within capacity, docs/design.md's round-off rule), INFO without capacity."""
    columns, csv_rows = read_csv(path)
    by_check = {(r[0], r[1]): dict(zip(columns, r)) for r in csv_rows}
    assert len({v == "INFO" for *_, v in rows}) == 1      # verdicts, or values without one
    for code, check, clause, demand, capacity, unit, ratio, verdict in rows:
        row = by_check[(code, check)]
        assert clause == row["clause"] and verdict == row["verdict"]
        f = factor(unit, row["unit"])
        check_number(demand, row["demand"], f, 5, (code, check))
        if verdict == "INFO":
            assert capacity == ratio == "—" and row["capacity"] == row["ratio"] == ""
            continue
        check_number(capacity, row["capacity"], f, 5, (code, check))
        check_number(ratio, float(row["demand"]) / float(row["capacity"]), 1, 5, (code, check))
        fits = float(row["demand"]) <= float(row["capacity"]) * (1 + 1e-9)
        assert verdict == ("OK" if fits else "NOT OK"), (code, check)


def check_hand_calculation(path, rows):
    """A code's hand calculation: each line is a row of design_calc.csv (its step), its
    formula and the numbers put in the core's, its value the CSV's to 5 digits in its unit,
    its clause named."""
    columns, csv_rows = read_csv(path)
    by_step = {r[columns.index("step")]: dict(zip(columns, r)) for r in csv_rows}
    for step, quantity, formula, value, unit, clause in rows:
        row = by_step[step]
        assert (quantity, unit, clause) == (row["quantity"], row["unit"], row["clause"])
        assert row["formula"] in formula and row["substituted"] in formula, step
        check_number(value, row["value"], 1, 5, (path.name, step))


def test_every_number_is_the_csv_one(sheets):
    for name, out in sheets.items():
        tables = page(out).tables()
        sources = {t[0] for t in tables if t[0]}
        expected = {"inputs.csv", "tank.csv", "design_codes.csv"}
        if name in SEISMIC:
            expected |= {"motion.csv"} | ({"seismic_spatial_peaks.csv"}
                                          if name == "tank_two_components" else
                                          {"seismic_peaks.csv", "run_info.csv"})
        if name in ("tank_seismic", "tank_harmonic"):      # circular, planar: the pressures
            expected |= {"pressure_at_peaks.csv", "wall_pressure_at_shear_peak.csv",
                         "wall_pressure_at_moment_peak.csv"}
        if name in DESIGN:
            expected |= {"design_checks.csv", "design_calc.csv", "design_loads.csv",
                         "wall_pressure.csv", "pressure_resultants.csv"}
        assert sources == expected, name
        for source, header, rows in tables:
            if source:
                check_table(out, source, header, rows)


def test_the_order_of_a_calc_sheet(sheets):
    for name, out in sheets.items():
        titles = page(out).texts("h2")
        calc = [t for t in titles if t.endswith(": hand calculation")]
        order = ORDER[:3] + calc + ORDER[3:]
        assert titles == [t for t in order if t in titles], name
        if name in DESIGN:       # a section per code of design_calc.csv, in its order
            codes = list(dict.fromkeys(r[0] for r in read_csv(out / "design_calc.csv")[1]))
            assert calc == [f"{code}: hand calculation" for code in codes]
        assert titles[:3] == ["Title block", "Summary of checks", "Inputs"], name
        if name == "tank_two_components":       # no verdict in the spatial run's files
            blocks = page(out).blocks
            k = blocks.index(("h2", "Summary of checks"))
            assert blocks[k + 1][0] == "p" and "No check with a verdict" in blocks[k + 1][1]
        assert ("Nonlinear run" in titles) == (name in SEISMIC)


def test_the_summary_holds_every_check(sheets):
    """Every code's freeboard check (design sheets) and the nonlinear run's roof verdict
    (seismic sheets) stand in the summary; the harmonic example's wave reaches the roof."""
    for name, out in sheets.items():
        summary = [t for t in page(out).tables() if t[1][:2] == ["code", "check"]]
        codes = [row[0] for t in summary for row in t[2]]
        if name in DESIGN:       # every row of design_checks.csv, the verdicts first
            rows = [row for t in summary for row in t[2]]
            assert sorted((r[0], r[1]) for r in rows) == sorted(
                (r[0], r[1]) for r in read_csv(out / "design_checks.csv")[1])
            verdicts = [r[-1] != "INFO" for r in rows]
            assert verdicts == sorted(verdicts, reverse=True)
            assert set(codes) >= {r[0] for r in read_csv(out / "freeboard_check.csv")[1]}
            freeboard = [row for t in summary for row in t[2] if row[1].startswith("freeboard")]
            assert {row[0] for row in freeboard} == {"API 650", "ACI 350.3"} \
                if name == "tank_design" else {"EC8-4"}
        if name in SEISMIC and name != "tank_two_components":
            roof = next(row for t in summary for row in t[2] if row[0] == "sloshdyn nonlinear")
            assert roof[-1] == ("NOT OK" if name == "tank_harmonic" else "OK")


def test_title_block_version_hashes_and_fields_for_the_checker(sheets):
    for name, out in sheets.items():
        rows = page(out).tables()[0][2]
        head = {row[0]: row[1] for row in rows}
        assert head["Program"] == f"sloshdyn {sloshdyn.__version__}"
        assert re.fullmatch(r"\d{4}-\d\d-\d\d \d\d:\d\d:\d\d UTC", head["Date prepared"])
        assert head["Checked by"] == head["Date checked"] == head["Project"] == ""
        nml = EXAMPLES / f"{name}.nml"
        assert head[f"SHA-256 of {nml.name}"] == hashlib.sha256(nml.read_bytes()).hexdigest()
        appendix = {row[0]: row[1] for row in page(out).tables()[-1][2]}   # Appendix B
        assert appendix[f"SHA-256 of {nml.name}"] == head[f"SHA-256 of {nml.name}"]
        group = f90nml.read(nml).get("ground_motion", {})
        for key in ("record", "record_y"):
            if key in group:
                record = EXAMPLES / group[key]
                assert appendix[f"SHA-256 of {record.name}"] == \
                    hashlib.sha256(record.read_bytes()).hexdigest()
        # the input file itself, verbatim, in the appendix
        assert nml.read_text() in page(out).texts("pre")


def test_project_and_preparer_in_the_title_block(tmp_path, capsys):
    assert cli.main(["report", str(EXAMPLES / "tank_design.nml"), "--out", str(tmp_path / "s"),
                     "--project", "Tank farm 7", "--prepared-by", "A. Engineer"]) == 0
    head = {row[0]: row[1] for row in page(tmp_path / "s").tables()[0][2]}
    assert (head["Project"], head["Prepared by"]) == ("Tank farm 7", "A. Engineer")
    assert head["Checked by"] == ""
    assert head["Codes"] == "API 650 13th ed.; ASCE 7-16; ACI 350.3-06"   # the clauses'


def test_the_design_sheet_names_the_clause_of_every_formula(sheets):
    """data/examples/tank_design.nml's sheet: every line of every hand calculation names its
    clause (a code's edition and clause, or the page of docs/ that derives it), and the lines
    are design_calc.csv's, all of them, in its order."""
    out = sheets["tank_design"]
    lines = [row for source, header, rows in page(out).tables() if source == "design_calc.csv"
             for row in rows]
    steps = [r[1] for r in read_csv(out / "design_calc.csv")[1]]
    assert sorted(int(row[0]) for row in lines) == sorted(int(s) for s in steps)
    for step, quantity, formula, value, unit, clause in lines:
        assert re.match(r"(API 650 \w+ ed\.|ACI 350\.3-06|ASCE 7-16|EN 1998-\d:\d{4}) \S|"
                        r"docs/\w+\.md|the spectrum of &design", clause), (step, clause)


def test_inputs_as_read_equal_the_file(sheets):
    """The inputs the sheet lists equal those the file gives (f90nml reads the file here,
    independently of the core's reader); the design's spectrum inputs are those of its kind
    only (no EC8 input on an ASCE 7 sheet) and a 0 that means a default says so."""
    for name, out in sheets.items():
        nml = f90nml.read(EXAMPLES / f"{name}.nml")
        listed = {row[0]: row for t in page(out).tables() if t[1][0] == "variable"
                  for row in t[2]}
        for group in ("tank", "seismic", "design"):
            for variable, value in nml.get(group, {}).items():
                shown = listed[variable][1]
                if variable == "planar":
                    assert shown == (".true." if value else ".false.")
                elif isinstance(value, str):
                    assert shown == value
                else:
                    assert float(shown) == pytest.approx(value, rel=1e-11)
        if name == "tank_design":                       # ASCE 7: no EC8 input
            assert {"s_ds", "s_d1", "t_l", "k"} <= set(listed)
            assert not {"a_gr", "ground_type", "spectrum_type", "q", "beta"} & set(listed)
            assert "0: " in listed["impulsive_period"][3]          # what its 0 means
            assert "plateau" in listed["impulsive_period"][3]
            assert listed["s_ds"][2] == "g" and listed["t_l"][2] == "s"
        if name == "tank_slender_design":               # EN 1998-1: no ASCE 7 input
            assert not {"s_ds", "s_d1", "t_l"} & set(listed) and "a_gr" in listed
        assert not {"impact_stiffness", "impact_damping", "n", "p"} & set(listed)


def test_motion_is_the_target_and_the_run_info(sheets):
    """The Sa at the sloshing period is the namelist's target_sa (the reader scaled the record
    to it); for planar runs motion.csv's numbers are run_info.csv's (the executable's)."""
    for name in SEISMIC:
        out = sheets[name]
        given = f90nml.read(EXAMPLES / f"{name}.nml")["ground_motion"]
        motion = one_row(out / "motion.csv")
        if "target_sa" in given:
            assert float(motion["sa_sloshing_period [m/s^2]"]) / 9.80665 == pytest.approx(
                given["target_sa"], rel=1e-6)
        else:                                                    # harmonic motion
            assert motion["kind"] == "harmonic"
            assert float(motion["peak_ground_acceleration [m/s^2]"]) / 9.80665 == \
                pytest.approx(given["peak_acceleration"], rel=1e-12)
        tank = one_row(out / "tank.csv")
        assert float(motion["sloshing_period [s]"]) == float(tank["sloshing_period [s]"])
        if (out / "run_info.csv").exists():
            info = one_row(out / "run_info.csv")
            assert motion["record"] == info["record"]
            for column in ("scale_factor", "peak_ground_acceleration [m/s^2]",
                           "sa_sloshing_period [m/s^2]"):
                assert float(motion[column]) == pytest.approx(float(info[column]), rel=1e-9)


def test_the_papers_impact_model_is_not_on_the_sheet(sheets):
    """No quantity of the paper's smooth wall (impact force, beta, delta, their exponents) in
    any table of the sheet (DESIGN.md, "Two models in one core")."""
    for name, out in sheets.items():
        for source, header, rows in page(out).tables():
            names = header + [row[0] for row in rows]
            assert not [n for n in names if ("impact" in n and n != "roof_impacts") or n in (
                "beta", "delta", "n", "p", "beta_sensitive")], name


def test_research_quantities_only_in_the_appendix(sheets):
    research = {"d0", "d1", "kappa", "mu1", "s1", "gamma", "zeta", "theta0", "omega"}
    for name, out in sheets.items():
        blocks = page(out).blocks
        appendix = next(k for k, b in enumerate(blocks) if b[:2] == (
            "h2", "Appendix A: the model's research quantities"))
        before = [row[0] for b in blocks[:appendix] if b[0] == "table" for row in b[3]]
        assert not research & set(before), name
        listed = {row[0] for row in blocks[appendix + 2][3]}
        assert research <= listed


def test_the_assumptions_are_those_of_docs_design(sheets):
    """The sheet prints docs/design.md's "Assumptions" as they stand there (the list read here
    from the repository's page, its Markdown removed by markdown-it-py)."""
    text = (ROOT / "docs" / "design.md").read_text()
    section = text.split("\n## Assumptions\n")[1].split("\n## ")[0]
    expected = rendered_markdown(section).texts("li")
    assert len(expected) >= 5
    for out in sheets.values():
        items = page(out).texts("li")
        assert items == expected


def test_html_holds_the_same_document(sheets):
    for name, out in sheets.items():
        md = page(out)
        html_page = Page((out / "report.html").read_text(encoding="utf-8"))
        assert html_page.tables() == md.tables(), name
        assert html_page.texts("li") == md.texts("li")
        assert html_page.texts("h2") == md.texts("h2")
        figures = [b[1] for b in md.blocks if b[0] == "img"]
        images = [b[1] for b in html_page.blocks if b[0] == "img"]
        assert len(images) == len(figures) >= 2
        for src, figure in zip(images, figures):
            assert src.startswith("data:image/png;base64,")
            assert base64.b64decode(src.split(",", 1)[1]) == (out / figure).read_bytes()
            assert (out / figure).read_bytes().startswith(PNG)
        if name in SEISMIC:
            assert {"ground_motion.png", "spectrum.png", "wave.png", "loads.png"} <= set(figures)
        else:
            assert figures == ["design_spectrum.png", "wall_pressure.png"]


def test_any_table_renders_by_its_units(tmp_path):
    """The generic renderer on tables such as design_loads.csv and wall_pressure.csv:
    engineering units from the column names, every value to 5 digits, a few rows of many
    columns transposed, a long table shown by evenly spaced rows with its first and last."""
    from sloshdyn import report_tables
    loads = tmp_path / "design_loads.csv"
    loads.write_text("code,base_shear [N],overturning_moment [N m],mass [kg],p [Pa],"
                     "hoop_force [N/m],a [m/s^2],ratio\n"
                     "API 650,1234567.89,98765.4321,289000.5,12345.678,2.5e5,1.96133,0.123456\n"
                     "EC8-4,2345.6,nan,1,0,-3.5,9.80665,7\n")
    table = report_tables.render_table(loads)
    assert table.header == ["code: quantity", "unit", "API 650", "EC8-4"]
    assert [row[:2] for row in table.rows] == [
        ["base_shear", "MN"], ["overturning_moment", "kN·m"], ["mass", "t"], ["p", "kPa"],
        ["hoop_force", "kN/m"], ["a", "g"], ["ratio", ""]]
    check_table(tmp_path, "design_loads.csv", table.header, table.rows)
    assert table.rows[1][3] == "—"
    pressure = tmp_path / "wall_pressure.csv"
    pressure.write_text("z [m],p_impulsive [Pa]\n"
                        + "".join(f"{6 * k / 99},{1000.0 * k}\n" for k in range(100)))
    table = report_tables.render_table(pressure)
    assert len(table.rows) == 25
    assert table.rows[0] == ["0", "0"] and table.rows[-1] == ["6", "99"]
    one = tmp_path / "freeboard.csv"
    one.write_text("required_freeboard [m],available_freeboard [m],sufficient\n"
                   "0.8765432,1.0,1\n")
    table = report_tables.render_table(one)
    check_table(tmp_path, "freeboard.csv", table.header, table.rows)


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
    assert list(tmp_path.iterdir()) == []


def test_the_impact_model_is_refused_by_name(tmp_path, capsys):
    """roof_contact = 'impact' makes the run's loads the paper's contact model's (they rest on
    beta): the sheet would show them as the codes' method, so it refuses the input by name and
    writes nothing (before, it ran and hid only the impact columns)."""
    text = (EXAMPLES / "tank_seismic.nml").read_text().replace(
        "records/", str(EXAMPLES / "records") + "/")
    assert "roof_contact" not in text
    (tmp_path / "impact.nml").write_text(text.replace("&tank", "&tank roof_contact = 'impact',", 1))
    code = cli.main(["report", str(tmp_path / "impact.nml"), "--out", str(tmp_path / "sheet")])
    err = capsys.readouterr().err
    assert code == 3, err
    assert "roof_contact = 'impact'" in err and "roof_contact = 'none'" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["impact.nml"]


def test_command_line_writes_the_sheet(tmp_path, capsys):
    out = tmp_path / "calc"
    assert cli.main(["report", str(EXAMPLES / "tank_seismic.nml"), "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "the free wave does not reach the roof" in printed      # the run's summary, passed on
    assert (f"calc sheet: {out / 'report.md'}, {out / 'report.html'} and "
            f"{out / 'report.pdf'}") in printed
    assert (out / "report.pdf").read_bytes().startswith(b"%PDF-")


def test_an_output_directory_that_is_a_file(tmp_path, capsys):
    """--out naming a file: the run cannot write there, a file error (exit 5) naming it."""
    (tmp_path / "calc").write_text("not a directory")
    code = cli.main(["report", str(EXAMPLES / "tank_seismic.nml"), "--out",
                     str(tmp_path / "calc")])
    err = capsys.readouterr().err
    assert code == 5, err
    assert "calc" in err and "internal error" not in err
    assert (tmp_path / "calc").read_text() == "not a directory"


def test_the_tank_summary_prints_five_significant_digits(exe, tmp_path):
    """The executable prints the tank's SI summary at engineering precision (sloshdyn-py run
    prints the same text: test_front_doors.py): every number of its lines and of the
    design-code table has at most 5 significant digits, and the masses and the period are
    tank.csv's (full precision there) rounded to 5."""
    shutil.copy(EXAMPLES / "tank_design.nml", tmp_path)       # it writes beside itself
    result = subprocess.run([exe, "tank_design.nml"], cwd=tmp_path,
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.split("Tank (SI)")[1].split("\n\n")[0].splitlines()
    lines += result.stdout.split("Design-code cross-check")[1].split("\n\n")[0].splitlines()[1:]
    numbers = [n for line in lines for n in re.findall(r"(?<![\w.])-?\d+(?:\.\d+)?(?:e-?\d+)?",
                                                       line.split("(eq 2-3)")[-1])]
    assert numbers and all(significant(n) <= 5 for n in numbers), numbers
    tank = one_row(tmp_path / "sloshdyn_output" / "tank_design" / "tank.csv")
    for label, column in (("liquid ", "liquid_mass [kg]"), ("total M = ", "total_mass [kg]"),
                          ("sloshing period ", "sloshing_period [s]")):
        text = re.search(re.escape(label) + r"(\d\S*)", "\n".join(lines)).group(1)
        check_number(text, tank[column], 1, 5, label)


def pdf_pages(path):
    """The text of each page of a PDF (poppler's pdftotext, as laid out)."""
    text = subprocess.run(["pdftotext", "-layout", str(path), "-"], capture_output=True,
                          text=True, check=True, timeout=120).stdout
    return text.split("\f")[:-1]


def pdf_size(path):
    info = subprocess.run(["pdfinfo", str(path)], capture_output=True, text=True, check=True,
                          timeout=120).stdout
    return re.search(r"Page size:\s+([\d.]+) x ([\d.]+) pts", info).groups()


def test_the_pdf_numbers_its_pages_and_starts_with_the_verdicts(sheets):
    """Each page of report.pdf says 'page N of M'; page 1 holds the summary's verdicts, every
    row's numbers and verdict (its values without a capacity may follow); no page ends with
    a section heading (its table or text on the next page)."""
    for name, out in sheets.items():
        pages = pdf_pages(out / "report.pdf")
        assert len(pages) >= 2, name
        for n, text in enumerate(pages, 1):
            assert f"page {n} of {len(pages)}" in text, (name, n)
        md = page(out)
        summary = md.blocks.index(("h2", "Summary of checks"))
        end = md.blocks.index(("h2", "Inputs"))
        rows = [row for b in md.blocks[summary:end] if b[0] == "table" for row in b[3]
                if row[-1] != "INFO"]              # the verdicts (the values may follow)
        first = " ".join(pages[0].split())
        assert "Summary of checks" in first, name
        for row in rows:                      # its numbers (names may wrap in their cells)
            numbers = [c for c in row if re.fullmatch(r"-?[\d.]+(e[-+]\d+)?", c)]
            assert all(f" {number} " in first for number in numbers), (name, row)
        assert first.count("NOT OK") >= sum(row[-1] == "NOT OK" for row in rows)
        headings = set(md.texts("h2"))
        for n, text in enumerate(pages, 1):
            lines = [line.strip() for line in text.splitlines() if line.strip()]
            assert lines[-2] not in headings, (name, n, lines[-2])   # [-1]: the page number


def test_long_tables_repeat_their_header_on_every_page(tmp_path):
    """The print CSS repeats a table's header on each page it spans (WeasyPrint honours
    thead's table-header-group), on A4 and on Letter paper."""
    from sloshdyn.report_layout import Section, Table, to_html
    from sloshdyn.report_pdf import write_pdf
    rows = [[f"row {k}", f"{k * 0.25:.5g}"] for k in range(300)]
    for paper, size in (("a4", ("595.276", "841.89")), ("letter", ("612", "792"))):
        html_text = to_html("A long table", [Section("Table", [Table(
            ["quantity name", "value in units"], rows)])], tmp_path, paper)
        write_pdf(html_text, tmp_path / f"{paper}.pdf")
        pages = pdf_pages(tmp_path / f"{paper}.pdf")
        assert len(pages) >= 3
        for text in pages:
            assert "quantity name" in text and "value in units" in text
        assert pdf_size(tmp_path / f"{paper}.pdf") == size


def test_letter_paper(tmp_path):
    sheet = sloshdyn.design_report(EXAMPLES / "tank_design.nml", tmp_path / "s", paper="letter")
    assert pdf_size(sheet.pdf) == ("612", "792")
    assert "size: letter" in sheet.html.read_text()
    with pytest.raises(sloshdyn.InputError, match="paper = 'a5'"):
        sloshdyn.design_report(EXAMPLES / "tank_design.nml", tmp_path / "t", paper="a5")


def test_the_summary_names_the_output_directory(tmp_path, capsys):
    """The run's summary, passed on, says where the files are: --out, not the sheet's own
    directory that is swapped into place."""
    out = tmp_path / "calc"
    assert cli.main(["report", str(EXAMPLES / "tank_design.nml"), "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert f"Results written to {out}/" in printed and ".sheet-" not in printed
