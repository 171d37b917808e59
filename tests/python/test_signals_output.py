"""SIGTERM is honoured within a second in every long phase (issue 22, item 13: output, chart
grid, reading), and standard output that takes no writes is a failed write, exit 5 (item 14).
The runs are stopped early, so each case costs a few seconds; the timeouts are guards against
a run that ignores the signal (on the old code these ran for minutes after it)."""

import signal
import subprocess
import sys

import pytest

from conftest import EXAMPLES
from test_faults import _start_and_signal, first_line, handlers_installed, writing


def terminate_when(cmd, cwd, ready):
    """Start cmd, send SIGTERM once ready(proc) holds (a readiness marker, not a delay):
    (exit code, stderr)."""
    code, stderr, _ = _start_and_signal(cmd, cwd, signal.SIGTERM, ready)
    return code, stderr


def test_sigterm_stops_the_output_of_a_long_seismic_response(exe, tmp_path):
    """2e6 output times: the integration is short, the loads and the CSV rows are the long
    phase (minutes); SIGTERM there ends the run with 143 and no result file."""
    text = (EXAMPLES / "tank_seismic.nml").read_text().replace(
        "records/", str(EXAMPLES / "records") + "/").replace(
        "sloshdyn_output/tank_seismic", "out") + "&seismic n_out = 2000000 /\n"
    (tmp_path / "input.nml").write_text(text)
    code, stderr = terminate_when([exe, "input.nml"], tmp_path, writing(tmp_path / "out"))
    assert code == 143, stderr
    assert not list(tmp_path.glob("out/*.csv"))


def test_sigterm_stops_a_stability_chart_on_a_large_grid(exe, tmp_path):
    """10000 x 200 cells: 200 one-parameter runs and 2e6 cells to mark near the curves."""
    text = (EXAMPLES / "fig12_stability_chart.nml").read_text().replace(
        "n_x = 41, n_y = 9", "n_x = 10000, n_y = 200").replace(
        "sloshdyn_output/fig12_stability_chart", "out")
    (tmp_path / "input.nml").write_text(text)
    code, stderr = terminate_when([exe, "input.nml"], tmp_path, first_line)
    assert code == 143, stderr
    assert not list(tmp_path.glob("out/*.csv"))


def test_sigterm_ends_a_run_waiting_for_its_input(exe, tmp_path):
    """An input read from standard input (-) that never comes (a pipe whose writer waits): the
    read waits; the first SIGTERM ends the run, 143, as while it reads a long record. (A FIFO
    as the input file is refused before it is opened: test_run_directory.py.)"""
    code, stderr, _ = _start_and_signal([exe, "-"], tmp_path, signal.SIGTERM,
                                        handlers_installed(signal.SIGTERM),
                                        stdin=subprocess.PIPE)
    assert code == 143, stderr


@pytest.mark.parametrize("door", ["executable", "sloshdyn-py"])
def test_standard_output_on_a_full_device_is_exit_5(exe, tmp_path, door):
    """> /dev/full lost the summary and exited 0; now a failed write before anything runs."""
    (tmp_path / "input.nml").write_text((EXAMPLES / "tank_linear.nml").read_text().replace(
        "sloshdyn_output/tank_linear", "out"))
    cmd = [exe] if door == "executable" else [sys.executable, "-m", "sloshdyn", "run"]
    with open("/dev/full", "w") as full:
        run = subprocess.run(cmd + ["input.nml"], cwd=tmp_path, stdout=full,
                             stderr=subprocess.PIPE, text=True, timeout=120)
    assert run.returncode == 5, run.stderr
    assert "standard output" in run.stderr and "Traceback" not in run.stderr
    assert not (tmp_path / "out").exists()
