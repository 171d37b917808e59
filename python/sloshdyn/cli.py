"""The command line: `python -m sloshdyn` (or `sloshdyn-py`) run | reproduce | check."""

from __future__ import annotations

import argparse
import csv
import json
import os
import sys
import time
from pathlib import Path

import numpy as np

from . import __version__, _core, figures, plotting, reference
from ._errors import SloshdynError, check_status
from ._files import atomic_path, save_figure
from .asymptotics import FrequencyResponse, SpecialPoint
from .parameters import read_namelist
from .simulation import Simulation, Sweep, _summary

def main(argv=None):
    parser = argparse.ArgumentParser(prog="sloshdyn-py", description=(
        "sloshdyn: sloshing in a partially filled tank (Farid & Gendelman's model)."))
    parser.add_argument("--version", action="version", version=f"sloshdyn {__version__}")
    commands = parser.add_subparsers(dest="command", required=True)

    run = commands.add_parser("run", help="run the analysis of a namelist file",
                              description="Run the analysis a namelist file asks for (the same "
                              "input as the Fortran executable), print a summary, and write its "
                              "CSV files and a figure into the &output directory.")
    run.add_argument("input", help="namelist file (see README.md, Namelist reference)")

    rep = commands.add_parser("reproduce", help="recompute every figure of the paper",
                              description="Recompute every numerical figure of the paper (PNG "
                              "and CSV), check the numbers the paper quotes, and write report.md.")
    rep.add_argument("--out", required=True, help="output directory")
    rep.add_argument("--only", nargs="+", metavar="FIG", choices=list(figures.FIGURES),
                     help="only these figures: " + ", ".join(figures.FIGURES))
    rep.add_argument("--quick", action="store_true",
                     help="fewer points and shorter runs (for a smoke test)")

    chk = commands.add_parser("check", help="regression against the reference data",
                              description="Compare computed values with data/reference (the "
                              "paper's numbers and the project's confirmed tables); exit status "
                              "1 if any quantity is outside its tolerance.")
    chk.add_argument("dir", nargs="?", help="a `reproduce` output directory whose values.json "
                     "is checked (default: compute the values now)")
    chk.add_argument("--reference", help="reference directory (default: the tables installed "
                     "with the package, a copy of data/reference)")

    args = parser.parse_args(argv)
    try:
        if args.command == "run":
            return run_input(args.input)
        if args.command == "reproduce":
            return reproduce(Path(args.out), args.only, args.quick)
        return check(args.dir, args.reference)
    except SloshdynError as exc:
        print(f"sloshdyn-py: error: {exc}", file=sys.stderr)
        return int(_core.sloshdyn_bridge.exit_code(exc.status or 1, getattr(exc, "reading", False)))
    except FileNotFoundError as exc:
        print(f"sloshdyn-py: error: {exc}", file=sys.stderr)
        return 3
    except KeyboardInterrupt:
        print("sloshdyn-py: interrupted; files already complete are kept, none is half-written",
              file=sys.stderr)
        return 130


def run_input(path):
    """Run a namelist file exactly as the executable does (the same reader, driver and writers,
    through the bridge), then draw the figure of the analysis from the files written."""
    try:
        inp = read_namelist(path)
    except SloshdynError as exc:
        exc.reading = True
        raise
    status, message = _core.sloshdyn_bridge.run_input(os.fspath(path))
    sys.stdout.flush()
    check_status(status, message)
    figure = _figure(inp, Path(inp.directory))
    if figure:
        save_figure(figure[1], Path(inp.directory) / figure[0])
    return 0


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
    if inp.analysis == "simulate":
        t = _table(out / "history.csv")
        sim = Simulation(t["tau"], np.array([t[k] for k in ("x1", "dx1", "x2", "dx2")]),
                         np.array([t["u1"], t["u2"]]), t["impact_force"], t["theta"], t["phi"],
                         0, 0, 0, float(t["tau"][-1]))
        return "history.png", plotting.time_history(sim, ("x1", "x2", "impact_force"))
    if inp.analysis == "seismic":
        from .seismic import SeismicResponse
        t, peaks = _table(out / "seismic.csv"), _table(out / "seismic_peaks.csv")
        response = SeismicResponse(inp.tank, inp.ground_motion, np.array(list(t.values())),
                                   np.array([column[0] for column in peaks.values()]))
        return "seismic.png", plotting.seismic(response)
    if inp.analysis == "stability_chart":
        from .charts import chart_from_files
        chart = chart_from_files(out, inp.chart["x"], inp.chart["y"], inp.chart["model"])
        return "stability_chart.png", plotting.stability_chart(
            chart, tank=inp.tank if inp.tank is not None and inp.chart["x"] == "rho"
            and inp.chart["y"] == "A" else None)
    if inp.analysis == "sweep" and inp.sweep["parameter"] == "frequency":
        from .seismic import HarmonicSweep
        t = _table(out / "harmonic_sweep.csv")
        return "harmonic_sweep.png", plotting.harmonic_sweep(
            HarmonicSweep(inp.tank, [], np.array(list(t.values())), None))
    if inp.analysis == "sweep":
        t = _table(out / "sweep.csv")
        points = [_summary(np.array([column[k] for column in t.values()]))
                  for k in range(len(t["rho"]))]
        return "sweep.png", plotting.sweep(Sweep(inp.sweep["parameter"], points, None))
    if inp.analysis == "frequency_response":
        t = _table(out / "response.csv")
        s = _table(out / "special_points.csv")
        special = [SpecialPoint(kind, int(b), rho, A, a1, a2, f) for kind, b, rho, A, a1, a2, f
                   in zip(s["kind"], s["branch"], s["rho"], s["A"], s["a1"], s["a2"],
                          s["frequency"])]
        response = FrequencyResponse(inp.response["parameter"], inp.response["resonance"], t,
                                     special, True)
        return "response.png", plotting.frequency_response(response)
    return None


def reproduce(out, only=None, quick=False):
    from tqdm.auto import tqdm
    out.mkdir(parents=True, exist_ok=True)
    selected = only or list(figures.FIGURES)
    reproduced, values = [], {}
    start = time.time()
    for key in tqdm(selected, desc="figures", unit="fig"):
        result = figures.FIGURES[key](out, quick=quick)
        for fig in (result if isinstance(result, list) else [result]):
            reproduced.append(fig)
            values.update(fig.values)
    missing = [row["quantity"] for row in reference.load() if row["quantity"] not in values]
    values.update(reference.compute(missing, quick))
    with atomic_path(out / "values.json") as tmp:
        Path(tmp).write_text(json.dumps({k: float(v) for k, v in values.items()}, indent=1))
    verdicts = reference.check(values)
    write_report(out, reproduced, verdicts, time.time() - start)
    failed = [v.quantity for v in verdicts if not v.passed]
    print(f"{len(reproduced)} figures, report: {out / 'report.md'}; "
          f"{len(verdicts) - len(failed)} of {len(verdicts)} quoted numbers within tolerance"
          + (f"; outside: {', '.join(failed)}" if failed else ""))
    return 0


def write_report(out, reproduced, verdicts, seconds):
    lines = ["# sloshdyn: the paper reproduced", "",
             "Farid & Gendelman, *Internal resonances and dynamic responses in equivalent mechanical "
             f"model of partially liquid-filled vessel*. Recomputed by sloshdyn {__version__} in "
             f"{seconds:.0f} s. Impact coefficient β = 10 and dissipation δ = 0.1 where the paper "
             "gives none (README, \"Impact and dissipation defaults\").", "",
             "## Numbers the paper quotes", "", reference.format_table(verdicts), "",
             "## Figures", ""]
    for fig in reproduced:
        lines += [f"### Fig {fig.number}", "", f"> {fig.caption}", ""]
        lines += [f"![Fig {fig.number}]({name})" for name in fig.files if name.endswith(".png")]
        if fig.notes:
            lines += ["", fig.notes]
        lines.append("")
    errata = reference.PACKAGE_REFERENCE / "errata.md"
    if errata.exists():
        lines += ["## Errata", "", errata.read_text()]
    with atomic_path(out / "report.md") as tmp:
        Path(tmp).write_text("\n".join(lines))


def check(directory=None, reference_dir=None):
    values = None
    if directory:
        path = Path(directory) / "values.json"
        if not path.exists():
            raise FileNotFoundError(f"{path} not found: run `reproduce --out {directory}` first")
        values = json.loads(path.read_text())
    verdicts = reference.check(values, reference_dir)
    print(reference.format_table(verdicts))
    failed = [v.quantity for v in verdicts if not v.passed]
    if failed:
        print(f"\n{len(failed)} of {len(verdicts)} outside tolerance: {', '.join(failed)}")
        return 1
    print(f"\nall {len(verdicts)} quantities within tolerance")
    return 0
