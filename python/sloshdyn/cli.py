"""The command line: `python -m sloshdyn` (or `sloshdyn-py`) run | report | reproduce | check |
study."""

from __future__ import annotations

import argparse
import glob
import json
import os
import signal
import sys
import threading
import time
import traceback
from pathlib import Path

import numpy as np
from tqdm.auto import tqdm

from . import figures, plotting, reference, studies
from ._errors import (EXIT_FAILURE, EXIT_INTERRUPTED, EXIT_POINTS_FAILED, EXIT_TERMINATED,
                      FileError, InputError, SloshdynError, exit_code)
from ._files import run_directory, save_figure, write_text
from ._shipped import NAMELIST_REFERENCE, copy_examples
from ._version import __version__
from .namelist import read_namelist
from .report import design_report
from .runner import run_input

def main(argv=None):
    # Raw epilog: argparse's wrapping breaks a path at its hyphens ("site-" / "packages"),
    # and a reader copies the reference's path from here.
    parser = argparse.ArgumentParser(prog="sloshdyn-py", description=(
        "sloshdyn: sloshing in a partially filled tank (Farid & Gendelman's model)."),
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=f"The namelist reference (every group and variable):\n  {NAMELIST_REFERENCE}\n"
        "Example inputs: sloshdyn-py examples DIR")
    parser.add_argument("--version", action="version", version=f"sloshdyn {__version__}")
    commands = parser.add_subparsers(dest="command", required=True)

    run = commands.add_parser("run", help="run the analysis of a namelist file",
                              description="Run the analysis a namelist file asks for (the same "
                              "input as the Fortran executable), print a summary, and write its "
                              "CSV files and a figure into the &output directory.")
    run.add_argument("input", help=f"namelist file (see {NAMELIST_REFERENCE}), or - for "
                     "standard input (its relative paths then relative to the current directory)")

    exm = commands.add_parser("examples", help="copy the example inputs into a directory",
                              description="Copy the example inputs (*.nml, the inputs of the "
                              "README and the tutorials) and their records into DIR, new or "
                              "without files of those names; run one with sloshdyn DIR/NAME.nml. "
                              f"The namelist reference: {NAMELIST_REFERENCE}.")
    exm.add_argument("dir", metavar="DIR", help="where to copy them")

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
                              "1 if any quantity is outside its tolerance, 3 if values.json or a "
                              "reference table is missing, corrupted or empty (a bad file).")
    chk.add_argument("dir", nargs="?", help="a `reproduce` output directory whose values.json "
                     "is checked (default: compute the values now)")
    chk.add_argument("--reference", help="reference directory (default: the tables installed "
                     "with the package, a copy of data/reference)")

    rpt = commands.add_parser("report", help="the calc sheet of a tank",
                              description="Run a namelist file of a tank under ground motion "
                              "(&analysis kind = 'seismic') or with &design as `run` does, and "
                              "write the calc sheet built from its files: report.md, a "
                              "self-contained report.html, report.pdf and the figures; DIR is "
                              "replaced as a whole when all are complete (docs/python.md, "
                              "\"The calc sheet\").")
    rpt.add_argument("input", help="namelist file with &tank and &ground_motion (&analysis "
                     "kind = 'seismic') or &design")
    rpt.add_argument("--out", required=True, metavar="DIR", help="output directory (new, or "
                     "one that sloshdyn wrote)")
    rpt.add_argument("--project", default="", help="the project, for the title block")
    rpt.add_argument("--prepared-by", default="", help="who prepared the sheet")
    rpt.add_argument("--paper", default="a4", choices=["a4", "letter"],
                     help="paper size of report.pdf and of report.html's print (default a4)")

    sty = commands.add_parser("study", help="run a parameter study (&study) on Dask",
                              description="Run the parameter study of a namelist file's &study "
                              "group (a response map, basins of attraction or a fragility study) "
                              "on Dask: results go to its Zarr store as tasks finish (rerun to "
                              "resume), then a summary and a figure. See docs/studies.md.")
    sty.add_argument("input", help="namelist file with &study, the system (&model with "
                     "&excitation, or &tank) and optionally &integration, &steady, &simulation")
    sty.add_argument("--scheduler", metavar="ADDRESS",
                     help="a running Dask scheduler (e.g. tcp://host:8786, or one started by "
                     "dask-jobqueue on SLURM) instead of the embedded local cluster; overrides "
                     "&study scheduler")
    sty.add_argument("--workers", type=int, help="workers of the embedded cluster (overrides "
                     "&study workers; default one per core)")
    sty.add_argument("--no-progress", action="store_true", help="no progress bar")

    args = parser.parse_args(argv)
    previous = _on_sigterm(_terminate)
    try:
        _check_standard_output()
        if args.command == "run":
            run_input(args.input)
            return 0
        if args.command == "examples":
            copied = copy_examples(args.dir)
            print(f"{len(copied)} example inputs in {args.dir} (with their records); "
                  f"run one with: sloshdyn {copied[0]}")
            return 0
        if args.command == "report":
            sheet = design_report(args.input, args.out, project=args.project,
                                  prepared_by=args.prepared_by, paper=args.paper)
            print(f"calc sheet: {sheet.markdown}, {sheet.html} and {sheet.pdf}")
            return 0
        if args.command == "study":
            return run_study(args.input, args.scheduler, args.workers, not args.no_progress)
        if args.command == "reproduce":
            return reproduce(Path(args.out), args.only, args.quick)
        return check(args.dir, args.reference)
    except SloshdynError as exc:
        print(f"sloshdyn-py: error: {exc}", file=sys.stderr)
        return exit_code(exc, getattr(exc, "reading", False))
    except _Terminated as exc:
        print(f"sloshdyn-py: terminated; {str(exc) or _KEPT}", file=sys.stderr)
        return EXIT_TERMINATED
    except KeyboardInterrupt as exc:
        print(f"sloshdyn-py: interrupted; {str(exc) or _KEPT}", file=sys.stderr)
        return EXIT_INTERRUPTED
    except Exception:     # a defect of sloshdyn-py itself: its traceback, and not exit 1
        traceback.print_exc()
        print("sloshdyn-py: internal error (a defect: please report it with the traceback "
              "above)", file=sys.stderr)
        return EXIT_FAILURE
    finally:
        _on_sigterm(previous)


def _check_standard_output():
    """Standard output that takes no writes (/dev/full, closed) would lose the summary: a
    failed write (FileError, exit 5) before anything runs, as the executable does. An empty
    write(2) asks the file itself."""
    if sys.stdout is None:                       # descriptor 1 closed when Python started
        raise FileError("standard output is closed: the summary would be lost")
    try:
        fd = sys.stdout.fileno()
    except (AttributeError, ValueError, OSError):     # not a file (captured): nothing to ask
        return
    try:
        sys.stdout.flush()
        os.write(fd, b"")
    except OSError as exc:
        raise FileError(f"standard output takes no writes ({exc.strerror or exc}): the "
                        "summary would be lost") from None


_KEPT = "files already complete are kept, none is half-written"


class _Terminated(KeyboardInterrupt):
    """SIGTERM, raised where Python runs next so that the writers clean up; a kind of
    KeyboardInterrupt, so whatever stops a computation on Ctrl-C stops it on SIGTERM too."""


def _terminate(signum, frame):
    raise _Terminated()


def _on_sigterm(handler):
    """Install a SIGTERM handler (main thread only; elsewhere nothing changes)."""
    if handler is None or threading.current_thread() is not threading.main_thread():
        return None
    return signal.signal(signal.SIGTERM, handler)


def run_study(path, scheduler=None, workers=None, progress=True):
    """Run the &study of a namelist file (read by the same reader as every input), print a
    summary and draw its figure (&study figure, default: beside the store)."""
    try:
        inp = read_namelist(path)
    except SloshdynError as exc:
        exc.reading = True
        raise
    st = inp.study
    if not st:
        raise InputError(f"{path}: no &study group: a study file needs one (docs/studies.md)")
    base = Path(path).resolve().parent
    store = Path(st["store"]) if os.path.isabs(st["store"]) else base / st["store"]
    figure = Path(st["figure"]) if st["figure"] else store.with_suffix(".png")
    if not figure.is_absolute() and st["figure"]:
        figure = base / figure
    from matplotlib.backend_bases import FigureCanvasBase
    formats = FigureCanvasBase.get_supported_filetypes()
    if figure.suffix[1:].lower() not in formats:   # checked before the first point
        raise InputError(f"&study: figure = {st['figure']!r} cannot be drawn: its extension "
                         f"{figure.suffix or '(none)'!r} is not one of "
                         f"{', '.join('.' + k for k in sorted(formats))}")
    common = dict(client=None, scheduler=scheduler or st["scheduler"] or None,
                  workers=workers if workers is not None else (st["workers"] or None),
                  worker_kind=st["worker_kind"], points_per_task=st["points_per_task"] or None,
                  min_workers=st["min_workers"], grace_time=st["grace_time"],
                  steady=inp.steady, integration=inp.integration,
                  progress=progress)
    if st["kind"] == "response_map":
        f = np.linspace(st["frequency_start"], st["frequency_stop"], st["n_frequencies"])
        a = np.linspace(st["amplitude_start"], st["amplitude_stop"], st["n_amplitudes"])
        ds = studies.response_map(inp.tank or inp.params, f, a, store,
                                  continuation=st["continuation"], **common)
        fig = plotting.response_map(ds)
        kinds = {studies.MOTIONS.get(int(k), "failed"): int((ds.motion == k).sum())
                 for k in np.unique(ds.motion.values)}
        print(f"response map: {ds.sizes['frequency']} frequencies x {ds.sizes['amplitude']} "
              f"amplitudes, {ds.attrs['points_computed']} points computed now; motions {kinds}; "
              f"roof impacts {int((ds.roof_impact == 1).sum())}; max |x1| = "
              f"{float(ds.max_x1.max()):.6g}")
    elif st["kind"] == "fragility":
        pattern = st["records"] if os.path.isabs(st["records"]) else str(base / st["records"])
        files = sorted(glob.glob(pattern))
        if not files:
            raise InputError(f"&study: records = {st['records']!r} matches no file")
        x = np.linspace(st["intensity_start"], st["intensity_stop"], st["n_intensities"])
        common.pop("steady")
        ds = studies.fragility_study(inp.tank, files, x, store,
                                     damping=st["spectral_damping"], **common)
        hit = ds.roof_impact.values
        levels = np.broadcast_to(ds.intensity.values, hit.shape)
        fit = studies.FragilityFit(float(ds.fragility_median), float(ds.fragility_dispersion),
                           float(ds.fragility_median_se), float(ds.fragility_dispersion_se), 0,
                           int(ds.fragility_runs))
        fig = plotting.fragility(fit, levels[hit >= 0], hit[hit >= 0],
                                 label=f"Sa({ds.attrs['spectral_period']:.3g} s, "
                                       f"{100 * st['spectral_damping']:g} %)")
        print(f"fragility: {ds.sizes['record']} records x {ds.sizes['intensity']} intensities, "
              f"{ds.attrs['points_computed']} runs computed now; roof impacts "
              f"{int((hit == 1).sum())} of the {int(ds.fragility_runs)} runs that succeeded "
              f"(of {hit.size}); fragility median "
              f"{fit.median:.4g} g (standard error {fit.median_se:.2g}), dispersion "
              f"{fit.beta:.3g} ({fit.beta_se:.2g}); {ds.attrs.get('fragility_fit', '')}")
    else:
        y0 = inp.simulation["y0"]
        ds = studies.basins(inp.params, (st["x1_start"], st["x1_stop"]),
                            (st["dx1_start"], st["dx1_stop"]), n=st["n_grid"], store=store,
                            x2=y0[2], dx2=y0[3], tol=st["tol"], **common)
        fig = plotting.basins(ds)
        print(f"basins: {ds.sizes['x1']} x {ds.sizes['dx1']} initial states, "
              f"{ds.attrs['points_computed']} computed now; attractors:")
        for j in range(ds.sizes["attractor_id"]):
            print(f"  {j + 1}: {ds.attractor_kind.values[j]}, period "
                  f"{int(ds.attractor_period.values[j])} T, {ds.attractor_stability.values[j]} "
                  f"(max |mu| = {float(ds.attractor_max_multiplier.values[j]):.6g}), share "
                  f"{float(ds.attractor_share.values[j]):.3f}, max |x1| = "
                  f"{float(ds.attractor_max_x1.values[j]):.6g}")
    if ds.attrs["points_repaired"]:
        print(f"repaired: {ds.attrs['points_repaired']} finished points of the store whose "
              f"stored data were missing or damaged ({ds.attrs['repaired']}) computed again")
    named, failed = studies.engine.failed_points(ds)
    if failed:
        print(f"failed: {failed} of {ds['status'].size} points (stored with their "
              f"status and message): {named}")
    save_figure(fig, figure)
    print(f"store: {store}\nfigure: {figure}")
    return EXIT_POINTS_FAILED if failed else 0


def reproduce(out, only=None, quick=False):
    """Every figure, values.json and report.md into `out`, renamed into place together at the
    end (a failed or interrupted run leaves none of its files)."""
    with run_directory(out) as run:
        return _reproduce(run.path, only, quick, out)


def _reproduce(out, only, quick, shown):
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
    write_text(out / "values.json", json.dumps({k: float(v) for k, v in values.items()}, indent=1))
    verdicts = reference.check(values)
    write_report(out, reproduced, verdicts, time.time() - start)
    failed = [v.quantity for v in verdicts if not v.passed]
    print(f"{len(reproduced)} figures, report: {shown / 'report.md'}; "
          f"{len(verdicts) - len(failed)} of {len(verdicts)} quoted numbers within tolerance"
          + (f"; outside: {', '.join(failed)}" if failed else ""))
    return 0


def write_report(out, reproduced, verdicts, seconds):
    lines = ["# sloshdyn: the paper reproduced", "",
             "Farid & Gendelman, *Internal resonances and dynamic responses in equivalent mechanical "
             f"model of partially liquid-filled vessel*. Recomputed by sloshdyn {__version__} in "
             f"{seconds:.0f} s. Impact coefficient β = 10 and dissipation δ = 0.1 where the paper "
             "gives none (docs/namelist.md, \"Impact and dissipation defaults\").", "",
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
    write_text(out / "report.md", "\n".join(lines))


def check(directory=None, reference_dir=None):
    """Exit 0 if every quantity is within its tolerance, 1 if one is not; a missing, corrupted
    or empty values.json or reference table is an InputError ("bad file", exit 3)."""
    values = reference.load_values(Path(directory) / "values.json") if directory else None
    verdicts = reference.check(values, reference_dir)
    print(reference.format_table(verdicts))
    failed = [v.quantity for v in verdicts if not v.passed]
    if failed:
        print(f"\n{len(failed)} of {len(verdicts)} outside tolerance: {', '.join(failed)}")
        return 1
    print(f"\nall {len(verdicts)} quantities within tolerance")
    return 0
