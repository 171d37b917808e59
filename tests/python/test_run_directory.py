"""An output directory belongs to a run (issue 44, items 1-3, 6, 7; docs/failure.md): a run
writes into a new directory of its own beside its output directory and swaps it into place
whole; a directory holding anything that no run wrote is refused by name, so a run never
writes through a planted symbolic link nor over a file it reads; two runs at once leave one
whole run; input from standard input (-); every path of an input file relative to its folder.
Each case in both front doors, the executable and sloshdyn-py."""

import os
import shutil
import signal
import subprocess
import sys

import pytest

from conftest import EXAMPLES, read_csv
from sloshdyn._files import MARKER, MARKER_HEADER

DOORS = ["executable", "sloshdyn-py"]
EXIT_IO = 5
SWEEP = """&model s1 = 1.5, mu1 = 0.5, kappa = 1.804897259, theta0 = 0.7853981633974483, gamma = 0.001 /
&excitation A = 0.00075, rho = 0.5 /
&analysis kind = 'sweep' /
&sweep parameter = 'A', start = {start}, stop = {stop}, n_points = {n} /
&steady max_transient_periods = 300, window_periods = 16 /
&output directory = '{out}' /
"""
LINEAR = """&model s1 = 1.5, mu1 = 0.5, kappa = 1.8049, theta0 = 0.785, gamma = 0.001 /
&excitation A = 0.001, rho = 0.5 /
&analysis kind = 'linear' /
&output directory = '{out}' /
"""
SIMULATE = LINEAR.replace("'linear'", "'simulate'") + "&simulation t_end = 20, n_out = 50 /\n"


def door_command(door, exe):
    return [exe] if door == "executable" else [sys.executable, "-m", "sloshdyn", "run"]


def run(door, exe, args, cwd, **kwargs):
    return subprocess.run(door_command(door, exe) + args, cwd=cwd, capture_output=True,
                          text=True, timeout=kwargs.pop("timeout", 300), **kwargs)


def marked(directory):
    """The names the marker of a run's directory lists (it must be sloshdyn's marker)."""
    text = (directory / MARKER).read_text()
    assert text.startswith(MARKER_HEADER)
    return set(text[len(MARKER_HEADER):].splitlines())


def hidden_beside(directory):
    """The run's hidden directories left beside `directory` (none after a run that ended)."""
    return [p.name for p in directory.parent.iterdir() if p.name.startswith(f".{directory.name}.")]


# ---- item 1: nothing is written through a planted symbolic link -----------------------------

@pytest.mark.parametrize("door", DOORS)
def test_a_symbolic_link_planted_in_the_output_directory_is_refused(exe, tmp_path, door):
    """A sweep's partial file was opened by a fixed name with status='replace': a symbolic link
    planted there made a normal sweep overwrite a file outside the directory. Now the directory
    (a run's, with its marker, which even lists the name) holds an entry that is no regular
    file a run wrote: refused by name, exit 5, the file outside untouched, nothing written."""
    (tmp_path / "input.nml").write_text(SWEEP.format(start=0.00075, stop=0.001, n=2, out="out"))
    assert run(door, exe, ["input.nml"], tmp_path).returncode == 0
    victim = tmp_path / "victim.txt"
    victim.write_text("precious\n")
    out = tmp_path / "out"
    before = sorted(p.name for p in out.iterdir())
    if (out / MARKER).exists():        # even listed by the marker, a link is no run's file
        (out / MARKER).write_text((out / MARKER).read_text() + "sweep.partial.csv\n")
    (out / "sweep.partial.csv").symlink_to(victim)
    result = run(door, exe, ["input.nml"], tmp_path)
    assert result.returncode == EXIT_IO, result.stderr
    assert "sweep.partial.csv" in result.stderr and "no sloshdyn run wrote" in result.stderr
    assert "Traceback" not in result.stderr
    assert victim.read_text() == "precious\n" and (out / "sweep.partial.csv").is_symlink()
    assert sorted(p.name for p in out.iterdir()) == sorted(before + ["sweep.partial.csv"])
    assert hidden_beside(out) == []


def test_python_writers_create_every_file_new(tmp_path):
    """atomic_path creates its temporary exclusively (never an existing file, never through a
    symbolic link): a link planted at the name it will use is not followed."""
    from sloshdyn import FileError
    from sloshdyn import _files
    victim = tmp_path / "victim.txt"
    victim.write_text("precious\n")
    planted = tmp_path / ".a.planted.partial.csv"
    planted.symlink_to(victim)
    original = _files.temporary_name
    _files.temporary_name = lambda path: str(planted)
    try:
        with pytest.raises(FileError, match="a.csv"):
            _files.write_csv(tmp_path / "a.csv", {"x": [1.0]})
    finally:
        _files.temporary_name = original
    assert victim.read_text() == "precious\n" and not (tmp_path / "a.csv").exists()


# ---- item 2: two runs into one directory leave one whole run --------------------------------

def _start_and_stop_when_writing(command, cwd):
    """Start a sweep and stop it (SIGSTOP) once it says where its points go: it is then
    inside its sweep, its partial file begun (the readiness marker is that line)."""
    proc = subprocess.Popen(command, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    for line in proc.stdout:
        if "points are written to" in line:
            break
    else:
        pytest.fail(f"the sweep never started: {proc.stderr.read()}")
    proc.send_signal(signal.SIGSTOP)
    return proc


@pytest.mark.parametrize("door", DOORS)
def test_two_sweeps_into_one_directory_leave_one_whole_sweep(exe, tmp_path, door):
    """Run A begins its sweep and is held; run B begins its own into the same directory; then
    both go on. Both exit 0 and the directory holds one run's sweep.csv whole: the rows that
    run gives alone (computed here into directories of their own, the independent source)."""
    cases = {"a": dict(start=0.00075, stop=0.001, n=6), "b": dict(start=0.0011, stop=0.0014, n=8)}
    alone = {}
    for name, case in cases.items():
        (tmp_path / f"{name}.nml").write_text(SWEEP.format(**case, out="shared"))
        (tmp_path / f"{name}_alone.nml").write_text(SWEEP.format(**case, out=f"alone_{name}"))
        assert run(door, exe, [f"{name}_alone.nml"], tmp_path).returncode == 0
        alone[name] = read_csv(tmp_path / f"alone_{name}" / "sweep.csv")
    procs = [_start_and_stop_when_writing(door_command(door, exe) + [f"{name}.nml"], tmp_path)
             for name in cases]
    for proc in procs:
        proc.send_signal(signal.SIGCONT)
    results = [proc.communicate(timeout=300) for proc in procs]
    assert [proc.returncode for proc in procs] == [0, 0], [err for _, err in results]
    shared = read_csv(tmp_path / "shared" / "sweep.csv")
    assert shared in (alone["a"], alone["b"])
    assert marked(tmp_path / "shared") == {p.name for p in (tmp_path / "shared").iterdir()
                                           if p.name != MARKER}
    assert hidden_beside(tmp_path / "shared") == []


@pytest.mark.parametrize("door", DOORS)
def test_a_reused_directory_holds_only_the_new_runs_files(exe, tmp_path, door):
    """A simulation, then a linear analysis into the same directory: the previous run's files
    are gone (they once stayed beside the new ones), the marker lists what is there, the
    executable's marker is Python's (one rule), and nothing is left beside."""
    out = tmp_path / "out"
    (tmp_path / "sim.nml").write_text(SIMULATE.format(out="out"))
    (tmp_path / "lin.nml").write_text(LINEAR.format(out="out"))
    assert run(door, exe, ["sim.nml"], tmp_path).returncode == 0
    assert (out / "history.csv").exists()
    result = run(door, exe, ["lin.nml"], tmp_path)
    assert result.returncode == 0, result.stderr
    names = {p.name for p in out.iterdir()} - {MARKER}
    assert {"parameters.csv", "frequencies.csv", "equilibria.csv", "routh_hurwitz.csv"} <= names
    assert not names & {"history.csv"}
    assert marked(out) == names
    assert hidden_beside(out) == []


# ---- item 3: a run never writes over a file it reads -----------------------------------------

@pytest.mark.parametrize("door", DOORS)
def test_a_record_named_like_a_result_in_the_output_directory_is_refused(exe, tmp_path, door):
    """A record out/seismic.csv with the output directory out: it was replaced by the result
    (exit 0) and the next run failed reading it. Now out holds a file no run wrote: refused by
    name, exit 5, the record as it was."""
    out = tmp_path / "out"
    out.mkdir()
    record = out / "seismic.csv"
    shutil.copy(EXAMPLES / "records" / "synthetic_kt.AT2", record)
    text = (EXAMPLES / "tank_seismic.nml").read_text().replace(
        "'records/synthetic_kt.AT2'", "'out/seismic.csv', format = 'at2'").replace("sloshdyn_output/tank_seismic",
                                                               "out")
    (tmp_path / "input.nml").write_text(text)
    before = record.read_bytes()
    result = run(door, exe, ["input.nml"], tmp_path)
    assert result.returncode == EXIT_IO, result.stderr
    assert "'seismic.csv'" in result.stderr and str(out.name) in result.stderr
    assert record.read_bytes() == before and sorted(os.listdir(out)) == ["seismic.csv"]


@pytest.mark.parametrize("door", DOORS)
def test_an_input_file_in_its_own_output_directory_is_refused(exe, tmp_path, door):
    """here/input.nml with directory = '../here': the folder holds the input file itself;
    refused by name (it was written into, beside the input)."""
    (tmp_path / "here").mkdir()
    (tmp_path / "here" / "input.nml").write_text(LINEAR.format(out="../here"))
    result = run(door, exe, ["here/input.nml"], tmp_path)
    assert result.returncode == EXIT_IO, result.stderr
    assert "'input.nml'" in result.stderr
    assert sorted(os.listdir(tmp_path / "here")) == ["input.nml"]


def test_the_calc_sheet_never_writes_over_its_record(tmp_path):
    """`sloshdyn-py report --out ../here` run in here/, beside a record named motion.csv (a
    file of the sheet): refused by name, exit 5, the record as it was (`--out .` is refused
    as a directory that cannot be replaced whole)."""
    tmp_path = tmp_path / "here"
    tmp_path.mkdir()
    shutil.copy(EXAMPLES / "records" / "synthetic_kt.AT2", tmp_path / "motion.csv")
    text = (EXAMPLES / "tank_seismic.nml").read_text().replace(
        "'records/synthetic_kt.AT2'", "'motion.csv', format = 'at2'")
    (tmp_path / "input.nml").write_text(text)
    before = (tmp_path / "motion.csv").read_bytes()
    result = subprocess.run([sys.executable, "-m", "sloshdyn", "report", "input.nml", "--out",
                             "../here"], cwd=tmp_path, capture_output=True, text=True,
                            timeout=300)
    assert result.returncode == EXIT_IO, result.stderr
    assert "no sloshdyn run wrote" in result.stderr and "Traceback" not in result.stderr
    assert (tmp_path / "motion.csv").read_bytes() == before
    assert sorted(os.listdir(tmp_path)) == ["input.nml", "motion.csv"]


# ---- item 6: standard input, and no FIFO ------------------------------------------------------

@pytest.mark.parametrize("door", DOORS)
def test_an_input_from_standard_input_runs_relative_to_the_current_directory(exe, tmp_path,
                                                                             door):
    """`-` reads the input from standard input (a pipe): it was refused as 'no namelist group
    found'. Its paths are relative to the current directory: the record and the output
    directory. The results equal those of the same input given as a file (the source)."""
    shutil.copytree(EXAMPLES / "records", tmp_path / "records")
    text = (EXAMPLES / "tank_seismic.nml").read_text().replace("sloshdyn_output/tank_seismic",
                                                               "piped")
    (tmp_path / "file.nml").write_text(text.replace("'piped'", "'from_file'"))
    assert run(door, exe, ["file.nml"], tmp_path).returncode == 0
    result = run(door, exe, ["-"], tmp_path, input=text)
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "piped" / "seismic_peaks.csv").read_text() == \
        (tmp_path / "from_file" / "seismic_peaks.csv").read_text()


@pytest.mark.parametrize("door", DOORS)
def test_a_fifo_as_the_input_file_is_refused_at_once_with_its_reason(exe, tmp_path, door):
    """A FIFO with no writer: the run waited for one (or, given one, said 'no namelist group
    found'); now it is refused before it is opened, exit 3, saying it is no regular file."""
    os.mkfifo(tmp_path / "input.nml")
    result = run(door, exe, ["input.nml"], tmp_path, timeout=60)
    assert result.returncode == 3, result.stderr
    assert "not a regular file" in result.stderr and "Traceback" not in result.stderr


# ---- item 7: every path of an input file is relative to its folder ---------------------------

@pytest.mark.parametrize("door", DOORS)
def test_the_output_directory_is_relative_to_the_input_files_folder(exe, tmp_path, door):
    """sub/input.nml with directory = 'out', run from tmp_path: the files go to sub/out, as its
    record goes beside it (they went to ./out, relative to the current directory)."""
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "input.nml").write_text(LINEAR.format(out="out"))
    result = run(door, exe, ["sub/input.nml"], tmp_path)
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "sub" / "out" / "parameters.csv").exists()
    assert not (tmp_path / "out").exists()
    assert "sub/out" in result.stdout


def test_the_calc_sheets_out_is_relative_to_the_current_directory(tmp_path):
    """--out on the command line: relative to the current directory, not the input's."""
    (tmp_path / "sub").mkdir()
    shutil.copy(EXAMPLES / "tank_design.nml", tmp_path / "sub" / "tank_design.nml")
    result = subprocess.run([sys.executable, "-m", "sloshdyn", "report", "sub/tank_design.nml",
                             "--out", "sheet"], cwd=tmp_path, capture_output=True, text=True,
                            timeout=300)
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "sheet" / "report.md").exists() and not (tmp_path / "sub" / "sheet").exists()


def test_both_doors_refuse_a_directory_with_one_message(exe, tmp_path):
    """The refusal is the same rule in the core and in Python (one message, one exit code)."""
    (tmp_path / "input.nml").write_text(LINEAR.format(out="../" + tmp_path.name))
    texts = []
    for door in DOORS:
        result = run(door, exe, ["input.nml"], tmp_path)
        assert result.returncode == EXIT_IO
        texts.append(result.stderr.split("error: ", 1)[1].strip())
    assert texts[0] == texts[1] and "which no sloshdyn run wrote" in texts[0]


@pytest.mark.parametrize("door", DOORS)
@pytest.mark.parametrize("where", [".", "..", "/"])
def test_a_directory_that_cannot_be_replaced_whole_is_refused(exe, tmp_path, door, where):
    """`.`, `..` and `/` cannot be swapped for a run's directory: refused by name in both doors
    (the executable once wrote into them, among whatever was there)."""
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "input.nml").write_text(LINEAR.format(out=where))
    before = sorted(os.listdir(tmp_path))
    result = run(door, exe, ["-"], tmp_path / "sub", input=LINEAR.format(out=where))
    assert result.returncode == EXIT_IO, result.stderr
    assert "must be named" in result.stderr
    assert sorted(os.listdir(tmp_path)) == before
