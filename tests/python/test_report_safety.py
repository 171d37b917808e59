"""The calc sheet under hostile input and faults (issue 39, item 4): names and text from input
escaped in report.md as in report.html (read back by markdown-it-py and html.parser, never by
sloshdyn's renderers); a reused --out holding only the new run's files; SIGTERM and a full disk
(RLIMIT_FSIZE) during the sheet step leaving the previous sheet as it was and no partial file
(the child writes a readiness marker when its sheet step is under way: no sleep decides when
the signal comes); a byte that is not UTF-8 in a comment read as the executable reads it; every
documented &design combination a sheet or an input error."""

import hashlib
import os
import shutil
import signal
import subprocess
import sys
import time

import pytest

import sloshdyn
from conftest import EXAMPLES
from sheet_reading import Page, read_csv, rendered_markdown
from sloshdyn import cli, report
from sloshdyn._errors import EXIT_TERMINATED

#: a record name with HTML, Markdown link, emphasis, code and table syntax
CRAFTED = "<img src=x onerror=alert(1)> **b** [l](javascript:x) _u_ |c| `d` &amp; #h.AT2"
TANK = ("&tank radius = 5.0, liquid_depth = 6.0, freeboard = 1.0, liquid_density = 1000, "
        "tank_mass = 5.0e4, support_frequency = 2.0, support_damping = 0.02 /\n")
RECORD = "&ground_motion record = '{record}', target_sa = 0.2, target_damping = 0.005 /\n"


def files_of(directory):
    """{name: SHA-256} of every file in a directory (hidden ones included)."""
    return {p.name: hashlib.sha256(p.read_bytes()).hexdigest() for p in directory.iterdir()}


def test_a_crafted_record_name_is_text_in_both_files(tmp_path):
    (tmp_path / "records").mkdir()
    shutil.copy(EXAMPLES / "records" / "synthetic_kt.AT2", tmp_path / "records" / CRAFTED)
    (tmp_path / "input.nml").write_text(TANK + RECORD.format(record=f"records/{CRAFTED}")
                                        + "&analysis kind = 'seismic' /\n")
    project = "<script>alert(2)</script> *p*"
    sheet = sloshdyn.design_report(tmp_path / "input.nml", tmp_path / "sheet", project=project)
    for name, document in (("report.md", rendered_markdown(sheet.markdown.read_text())),
                           ("report.html", Page(sheet.html.read_text()))):
        tags = {tag for tag, _, verbatim in document.tags if not verbatim}
        assert not tags & {"script", "a", "em", "strong", "code"}, (name, tags)
        images = [attrs["src"] for tag, attrs, _ in document.tags if tag == "img"]
        assert images and all(src.endswith(".png") or src.startswith("data:image/png;base64,")
                              for src in images), name
        cells = [c for _, header, rows in document.tables() for row in [header] + rows
                 for c in row]
        assert f"SHA-256 of {CRAFTED}" in cells, name            # the title block
        assert CRAFTED in cells, name                            # motion.csv's record
        assert project in cells, name
        assert any(CRAFTED in text for text in document.texts("pre")), name   # the input


def test_a_reused_out_holds_only_the_new_runs_files(tmp_path):
    """A design sheet, then a seismic sheet into the same --out: the directory holds exactly
    what the seismic sheet writes into a new directory (no design_loads.csv, freeboard check or
    wall pressure of the first run), and its sheet shows none of them."""
    out = tmp_path / "calc"
    sloshdyn.design_report(EXAMPLES / "tank_design.nml", out)
    assert (out / "design_loads.csv").exists()
    sloshdyn.design_report(EXAMPLES / "tank_seismic.nml", out)
    fresh = tmp_path / "fresh"
    sloshdyn.design_report(EXAMPLES / "tank_seismic.nml", fresh)
    assert set(os.listdir(out)) == set(os.listdir(fresh))
    assert not {"design_loads.csv", "freeboard_check.csv", "wall_pressure.csv",
                "design_spectrum.png"} & set(os.listdir(out))
    sources = {t[0] for t in rendered_markdown((out / "report.md").read_text()).tables()}
    assert "design_loads.csv" not in sources and "freeboard_check.csv" not in sources
    assert sorted(os.listdir(tmp_path)) == ["calc", "fresh"]        # no directory left over


def test_a_directory_not_written_by_sloshdyn_is_refused(tmp_path, capsys):
    """--out holding the user's own file (here: the input itself) is refused by name before
    anything runs: the sheet replaces its directory whole, so it never takes one it did not
    write."""
    shutil.copy(EXAMPLES / "tank_design.nml", tmp_path / "input.nml")
    before = files_of(tmp_path)
    code = cli.main(["report", str(tmp_path / "input.nml"), "--out", str(tmp_path)])
    err = capsys.readouterr().err
    assert code == 5, err
    assert "'input.nml', which no sloshdyn run wrote" in err
    assert files_of(tmp_path) == before


#: the child: sloshdyn-py report with its sheet step held (SIGTERM) or with a file size limit
#: from the start of the sheet step (a full disk); it writes READY once the step is under way
CHILD = """
import resource, sys, time
from pathlib import Path
from sloshdyn import cli, report

ready, mode = Path(sys.argv[1]), sys.argv[2]
write_sheet, write_pdf = report.write_sheet, report.write_pdf

def sheet_step(directory, inp, sheet):
    if mode == "full":
        resource.setrlimit(resource.RLIMIT_FSIZE, (8192, resource.RLIM_INFINITY))
    return write_sheet(directory, inp, sheet)

def held_pdf(page, path):          # report.md and report.html are written by now
    ready.write_text("the sheet step is under way")
    if mode == "term":
        time.sleep(600)            # until the test's SIGTERM
    write_pdf(page, path)

report.write_sheet, report.write_pdf = sheet_step, held_pdf
sys.exit(cli.main(["report", sys.argv[3], "--out", sys.argv[4]]))
"""


def _child(tmp_path, mode, out):
    ready = tmp_path / "ready"
    return ready, subprocess.Popen(
        [sys.executable, "-c", CHILD, str(ready), mode,
         str(EXAMPLES / "tank_slender_design.nml"),
         str(out)], cwd=tmp_path, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)


@pytest.mark.parametrize("mode", ["term", "full"])
def test_sigterm_or_a_full_disk_in_the_sheet_step_leave_the_previous_sheet(tmp_path, mode):
    out = tmp_path / "sheet"
    sloshdyn.design_report(EXAMPLES / "tank_design.nml", out)
    before = files_of(out)
    ready, proc = _child(tmp_path, mode, out)
    if mode == "term":
        deadline = time.monotonic() + 300
        while not ready.exists() and proc.poll() is None and time.monotonic() < deadline:
            time.sleep(0.01)       # polling for the readiness marker, not a guess of time
        assert ready.exists(), proc.stderr.read()
        proc.send_signal(signal.SIGTERM)
    _, stderr = proc.communicate(timeout=300)
    if mode == "term":
        assert proc.returncode == EXIT_TERMINATED, stderr
        assert "terminated" in stderr
    else:
        assert proc.returncode == 5, stderr
        assert "File too large" in stderr
    assert "Traceback" not in stderr
    assert files_of(out) == before                       # the previous sheet, as it was
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        ["sheet"] + (["ready"] if ready.exists() else []))   # no new directory or partial file


def test_a_byte_that_is_not_utf8_in_a_comment(tmp_path):
    """The executable reads bytes: a Latin-1 é in a comment is accepted by both doors, and the
    sheet shows the file with that byte as an escape, its hash that of the bytes."""
    text = (EXAMPLES / "tank_design.nml").read_bytes().replace(b"! The design check",
                                                                b"! Caf\xe9: the design check")
    (tmp_path / "input.nml").write_bytes(text)
    sheet = sloshdyn.design_report(tmp_path / "input.nml", tmp_path / "sheet")
    document = rendered_markdown(sheet.markdown.read_text(encoding="utf-8"))
    assert any("! Caf\\xe9: the design check" in t for t in document.texts("pre"))
    head = {row[0]: row[1] for row in document.tables()[0][2]}
    assert head["SHA-256 of input.nml"] == hashlib.sha256(text).hexdigest()


SPECTRA = {"asce7": "s_ds = 1.0, s_d1 = 0.6, t_l = 8.0", "aci350": "s_ds = 1.0, s_d1 = 0.6",
           "ec8": "a_gr = 0.25, ground_type = 'B'", "ground_motion": ""}


@pytest.mark.parametrize("spectrum, kind, motion, shape", [
    ("asce7", "linear", False, "circular"),
    ("aci350", "linear", False, "rectangular"),
    ("ec8", "linear", False, "circular"),
    ("ground_motion", "linear", True, "circular"),
    ("ground_motion", "seismic", True, "circular"),
    ("ec8", "seismic", True, "rectangular"),
    ("ground_motion", "linear", False, "circular"),
])
def test_every_design_combination_gives_a_sheet_or_an_input_error(tmp_path, capsys, monkeypatch,
                                                                   spectrum, kind, motion, shape):
    """docs/namelist.md's &design spectra with and without a ground motion, linear and
    seismic, circular and rectangular: each gives a sheet whose summary holds every code's
    freeboard check, or exits 3 naming the variable (spectrum = 'ground_motion' without a
    ground motion), never another exit code or a traceback. (The PDF, which only lays out the
    HTML checked here, is left to test_report.py's sheets: a stand-in writes its file.)"""
    monkeypatch.setattr(report, "write_pdf", lambda page, path: path.write_bytes(b"%PDF-"))
    tank = TANK if shape == "circular" else TANK.replace(
        "radius = 5.0", "shape = 'rectangular', length = 10.0, width = 8.0")
    (tmp_path / "records").mkdir()
    shutil.copy(EXAMPLES / "records" / "synthetic_kt.AT2", tmp_path / "records")
    (tmp_path / "input.nml").write_text(
        tank + (RECORD.format(record="records/synthetic_kt.AT2") if motion else "")
        + f"&design spectrum = '{spectrum}', {SPECTRA[spectrum]} /\n"
        + f"&analysis kind = '{kind}' /\n")
    code = cli.main(["report", str(tmp_path / "input.nml"), "--out", str(tmp_path / "sheet")])
    err = capsys.readouterr().err
    if spectrum == "ground_motion" and not motion:
        assert code == 3 and "spectrum = 'ground_motion'" in err and "&ground_motion" in err
        assert not (tmp_path / "sheet").exists()
        return
    assert code == 0, err
    sheet = tmp_path / "sheet"
    summary = rendered_markdown((sheet / "report.md").read_text()).tables()[1]
    assert summary[0] in ("freeboard_check.csv", "design_checks.csv")
    codes = {row[0] for row in read_csv(sheet / "freeboard_check.csv")[1]}
    assert codes <= {row[0] for row in summary[2]}
    assert (sheet / "report.pdf").read_bytes().startswith(b"%PDF-")
