"""The run of a namelist input file, exactly as the executable runs it (the same reader, driver
and writers, through the bridge), then the figure of its analysis drawn from the files written.
The command line (`sloshdyn-py run`) and the calc sheet (sloshdyn.report) both run inputs here;
it stands above the namelist reader and the analyses (docs/architecture.md, "Python layers")."""

from __future__ import annotations

import csv
import os
import sys
from pathlib import Path

import numpy as np

from ._cancel import app_call
from . import _core, _tables
from ._errors import FileError, SloshdynError, check_status
from ._files import run_directory, save_figure
from .asymptotics import FrequencyResponse, SpecialPoint
from .charts import chart_from_files
from .namelist import read_namelist
from .seismic import PEAK_LOADS, HarmonicSweep, SeismicResponse, seismic_defaults
from .simulation import Simulation, Sweep, _summary


def run_input(path, directory=None, staging=None):
    """Run a namelist file exactly as the executable does (the same reader, driver and writers,
    through the bridge), then draw the figure of the analysis from the files written. The files
    go to `directory` if given (sloshdyn.design_report), else to the file's &output directory,
    by the run-directory rule (sloshdyn._files.run_directory: a new directory swapped into
    place whole); with `staging`, into that new directory instead, which the caller swaps into
    place. Returns the input as read."""
    try:
        inp = read_namelist(path)
    except SloshdynError as exc:
        exc.reading = True
        raise
    out = Path(inp.directory if directory is None else directory)
    if staging is not None:
        _run(path, inp, out, Path(staging), directory, None)
        return inp
    with run_directory(out) as run:
        _run(path, inp, out, run.path, directory, run)
    return inp


def _run(path, inp, out, staging, directory, run):
    """The core's run into `staging`, then the figure; the core's files are kept if only the
    figure fails, and so are a failed run's files the core kept (a sweep's finished rows), as
    the executable keeps them."""
    status, message = app_call(_core.sloshdyn_bridge_input.run_input, os.fsencode(path),
                               os.fsencode("" if directory is None else directory),
                               os.fsencode(staging))
    sys.stdout.flush()
    if status != 0 and run is not None and any(staging.iterdir()):
        run.keep_on_failure()                   # the rows a failed sweep finished
    check_status(status, message)
    figure = _figure(inp, staging)
    if figure:
        try:
            save_figure(figure[1], staging / figure[0])
        except FileError as exc:
            if run is not None:
                run.keep_on_failure()           # the core's files, complete
            raise FileError(f"the result files in {out} are complete, the figure "
                            f"{figure[0]} is not: {exc}", exc.status) from exc


def _table(path):
    """A result CSV as {column: array} (text columns kept as lists of strings)."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    columns = {}
    for k, name in enumerate(rows[0]):
        values = [row[k] for row in rows[1:]]
        try:
            columns[name] = np.array([float(v) for v in values])
        except ValueError:
            columns[name] = values
    return columns


def _figure(inp, out):
    """(file name, Figure) for the analyses that have one, from their result files."""
    from . import plotting     # the plot extra (matplotlib): only where a figure is drawn
    method = inp.integration.method_used
    if inp.analysis == "simulate" and inp.planar:
        t = _table(out / "history.csv")
        sim = Simulation(t["tau"], np.array([t[k] for k in ("x1", "dx1", "x2", "dx2")]),
                         np.array([t["u1"], t["u2"]]), t["impact_force"], t["theta"], t["phi"],
                         0, 0, 0, float(t["tau"][-1]), method)
        return "history.png", plotting.time_history(sim, ("x1", "x2", "impact_force"))
    if inp.analysis == "seismic" and inp.planar:
        t, peaks = _table(out / "seismic.csv"), _table(out / "seismic_peaks.csv")
        with open(out / "run_info.csv", newline="", encoding="utf-8") as info:
            inp.ground_motion.name = next(csv.DictReader(info))["record"]
        # the figure needs no peak instants (the pressure files have them)
        response = SeismicResponse._from_tables(
            inp.tank, inp.ground_motion, np.array(list(t.values())),
            np.array([column[0] for column in peaks.values()]),
            np.full((len(_tables.columns("seismic_peak_instants")), len(PEAK_LOADS)), np.nan),
            seismic_defaults(inp.tank, inp.ground_motion, inp.seismic["t_end"] or None,
                             inp.seismic["n_out"] or None).t_end, method)
        return "seismic.png", plotting.seismic(response)
    if inp.analysis == "stability_chart":
        axes = inp.chart_range
        chart = chart_from_files(out, axes["x"], axes["y"], axes["model"])
        return "stability_chart.png", plotting.stability_chart(
            chart, tank=inp.tank if inp.tank is not None and axes["x"] == "rho"
            and axes["y"] == "A" else None)
    if inp.analysis == "sweep" and inp.sweep["parameter"] == "frequency":
        t = _table(out / "harmonic_sweep.csv")
        return "harmonic_sweep.png", plotting.harmonic_sweep(
            HarmonicSweep._from_table(inp.tank, [], np.array(list(t.values())), None, method))
    if inp.analysis == "sweep":
        t = _table(out / "sweep.csv")
        points = [_summary(np.array([column[k] for column in t.values()]), method)
                  for k in range(len(t["rho"]))]
        return "sweep.png", plotting.sweep(Sweep(inp.sweep["parameter"], points, None, method))
    if inp.analysis == "frequency_response":
        t = _table(out / "response.csv")
        s = _table(out / "special_points.csv")
        special = [SpecialPoint(kind, int(b), rho, A, a1, a2, f) for kind, b, rho, A, a1, a2, f
                   in zip(s["kind"], s["branch"], s["rho"], s["A"], s["a1"], s["a2"],
                          s["frequency"])]
        response = FrequencyResponse(inp.response_range["parameter"],
                                     inp.response_range["resonance"], t,
                                     special, True, "")
        return "response.png", plotting.frequency_response(response)
    return None
