"""The command line: `python -m sloshdyn` (or `sloshdyn-py`) run | reproduce | check."""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

from . import __version__, figures, plotting, reference
from ._errors import SloshdynError
from ._files import atomic_path, save_figure, write_csv
from .asymptotics import Continuation, frequency_response
from .model import equilibria, kappa_for_detuning, linear_modes
from .parameters import read_namelist
from .periodic import lyapunov_exponent, periodic_orbit, periodic_response
from .simulation import (Integration, Steady, amplitude_sweep, frequency_sweep, simulate,
                         steady_state, sweep_values)

SUMMARY_COLUMNS = ["rho", "A", "max_x1", "max_x2", "max_u1", "max_u2", "motion", "period",
                   "transient_periods", "spread", "settled"]
MOTION_CODES = {"periodic": 1, "quasi-periodic": 2, "irregular": 3, "settling": 4}


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
    except (SloshdynError, FileNotFoundError) as exc:
        print(f"sloshdyn-py: error: {exc}", file=sys.stderr)
        return 3
    except KeyboardInterrupt:
        print("sloshdyn-py: interrupted; files already complete are kept, none is half-written",
              file=sys.stderr)
        return 130


def run_input(path):
    inp = read_namelist(path)
    p = inp.params
    out = Path(inp.directory)
    integration = Integration(**inp.integration)
    steady = Steady(**inp.steady)
    print(f"sloshdyn: {inp.analysis}\n\n{p}")
    params = {name: [getattr(p, name)] for name in
              ("s1", "mu1", "kappa", "theta0", "beta", "gamma", "delta", "n", "p", "A", "rho")}
    a, b = p.coefficients()
    params.update({f"a{i + 1}": [a[i]] for i in range(6)})
    params.update({f"b{i + 1}": [b[i]] for i in range(6)})
    files = {"parameters.csv": params}
    figure = None
    if inp.analysis == "linear":
        modes = linear_modes(p)
        eq = equilibria(p)
        kappas = kappa_for_detuning(p.s1, p.mu1, inp.sigma1, inp.kappa_min, inp.kappa_max)
        print(f"omega1 = {modes.omega1:.10g}, omega2 = {modes.omega2:.10g} (eq 28); "
              f"kappa for sigma1 = {inp.sigma1}: {', '.join(f'{k:.10g}' for k in kappas)}")
        k = modes.stiffness
        files["frequencies.csv"] = {
            "omega1": [modes.omega1], "omega2": [modes.omega2], "omega1_dgeev": [modes.omega1_dgeev],
            "omega2_dgeev": [modes.omega2_dgeev], "ratio": [modes.ratio], "k11": [k[0, 0]],
            "k12": [-k[0, 1]], "k21": [-k[1, 0]], "k22": [k[1, 1]]}
        cols = {"theta": [], "phi": [], "x1": [], "x2": [], "physical": [], "verdict": []}
        for i in range(1, 5):
            cols[f"re{i}"], cols[f"im{i}"] = [], []
        for e in eq:
            for key, value in (("theta", e.theta), ("phi", e.phi), ("x1", e.theta / p.theta0),
                               ("x2", e.phi / p.theta0), ("physical", int(e.physical)),
                               ("verdict", e.verdict)):
                cols[key].append(value)
            for i, lam in enumerate(e.eigenvalues, 1):
                cols[f"re{i}"].append(lam.real)
                cols[f"im{i}"].append(lam.imag)
        files["equilibria.csv"] = cols
        files["routh_hurwitz.csv"] = {
            **{f"c{i + 1}": [eq.routh_coefficients[i]] for i in range(4)},
            "delta2": [eq.routh_delta2], "delta3": [eq.routh_delta3],
            "routh_stable": [int(eq.routh_stable)], "eigenvalue_verdict": [eq.trivial.verdict]}
        files["kappa_31.csv"] = {"sigma1": [inp.sigma1] * len(kappas), "kappa": kappas}
    elif inp.analysis == "simulate":
        sim = simulate(p, inp.simulation["t_end"], inp.simulation["y0"],
                       n_out=inp.simulation["n_out"], integration=integration)
        print(f"steps accepted {sim.n_accepted}, rejected {sim.n_rejected}, right-hand sides "
              f"{sim.n_rhs}; max|x1| = {np.max(np.abs(sim.x1)):.10g}")
        files["history.csv"] = {"tau": sim.tau, "x1": sim.y[0], "dx1": sim.y[1], "x2": sim.y[2],
                                "dx2": sim.y[3], "u1": sim.u[0], "u2": sim.u[1],
                                "impact_force": sim.impact_force, "theta": sim.theta, "phi": sim.phi}
        files["simulation.csv"] = {"n_rhs": [sim.n_rhs], "n_accepted": [sim.n_accepted],
                                   "n_rejected": [sim.n_rejected], "tau_reached": [sim.tau_reached]}
        figure = ("history.png", plotting.time_history(sim, ("x1", "x2", "impact_force")))
    elif inp.analysis == "steady_state":
        st = steady_state(p, inp.simulation["y0"], steady=steady, integration=integration)
        print(f"max|x1| = {st.max_x1:.10g}, max|u1| = {st.max_u1:.10g}, motion: {st.motion}")
        files["steady_state.csv"] = _summary_columns([st])
        period = 2 * math.pi / p.rho
        k = np.arange(1, st.poincare.shape[1] + 1)
        files["poincare.csv"] = {"tau": (st.transient_periods + k) * period, "x1": st.poincare[0],
                                 "dx1": st.poincare[1], "x2": st.poincare[2], "dx2": st.poincare[3]}
    elif inp.analysis == "sweep":
        sw = inp.sweep
        values = sweep_values(sw["start"], sw["stop"], sw["n_points"], sw["direction"].strip())
        run_sweep = frequency_sweep if sw["parameter"].strip() == "rho" else amplitude_sweep
        result = run_sweep(p, values, inp.simulation["y0"], steady=steady, integration=integration,
                           progress=True)
        files["sweep.csv"] = _summary_columns(result.points)
        figure = ("sweep.png", plotting.sweep(result))
    elif inp.analysis == "periodic_response":
        r = inp.response
        span = (min(r["start"], r["stop"]), max(r["start"], r["stop"]))
        first = p.replace(**{r["parameter"].strip().replace("a", "A"): span[0]})
        start = steady_state(first, inp.simulation["y0"], steady=steady, integration=integration).y_end
        y0 = periodic_orbit(first, start, integration=integration).y0
        kwargs = {"rho_range": span} if r["parameter"].strip() == "rho" else {"A_range": span}
        branch = periodic_response(p, y0=y0, ds=r["ds"], ds_min=r["ds_min"], ds_max=r["ds_max"],
                                   x_scale=r["x_scale"], max_points=4000, integration=integration,
                                   **kwargs)
        t = branch.table
        for s in branch.special_points:
            print(f"{s.kind:15s} {branch.parameter} = {s.rho if branch.parameter == 'rho' else s.A:.10g}"
                  f"  max|x1| = {s.max_x1:.10g}")
        files["periodic_branch.csv"] = {
            "lambda": t["lambda"], **{f"y{i}": t[f"y{i}"] for i in range(1, 5)},
            "max_x1": t["max_x1"], "stable": t["stable"],
            **{f"re_mu{i}": t[f"mu{i}"].real for i in range(1, 5)},
            **{f"im_mu{i}": t[f"mu{i}"].imag for i in range(1, 5)}}
        files["periodic_special_points.csv"] = {
            "kind": [s.kind for s in branch.special_points],
            "lambda": [s.rho if branch.parameter == "rho" else s.A for s in branch.special_points],
            **{f"y{i + 1}": [s.y0[i] for s in branch.special_points] for i in range(4)},
            "max_x1": [s.max_x1 for s in branch.special_points]}
    elif inp.analysis == "lyapunov":
        ly = inp.lyapunov
        exponent, history = lyapunov_exponent(
            p, inp.simulation["y0"], transient_periods=int(round(ly["transient_periods"])),
            n_periods=ly["n_periods"], renormalise_every=ly["renormalise_every"],
            integration=integration)
        print(f"largest Lyapunov exponent = {exponent:.10g} per unit tau")
        files["lyapunov.csv"] = {"periods": [(i + 1) * ly["renormalise_every"] for i in range(len(history))],
                                 "estimate": history}
    else:
        r = inp.response
        span = (min(r["start"], r["stop"]), max(r["start"], r["stop"]))
        kwargs = {"rho_range": span} if r["parameter"].strip() == "rho" else {"A_range": span}
        response = frequency_response(p, resonance=r["resonance"].strip(),
                                      settings=Continuation.from_namelist(r), **kwargs)
        for s in response.special_points:
            print(f"{s.kind:5s} rho = {s.rho:.10g}  A = {s.A:.10g}  |u1| = {s.a1:.6g}  "
                  f"|u2| = {s.a2:.6g}" + (f"  frequency = {s.frequency:.6g}" if s.kind == "hopf" else ""))
        files["response.csv"] = response.table
        files["special_points.csv"] = {
            "kind": [s.kind for s in response.special_points],
            "branch": [s.branch for s in response.special_points],
            "lambda": [s.rho if response.parameter == "rho" else s.A for s in response.special_points],
            "rho": [s.rho for s in response.special_points], "A": [s.A for s in response.special_points],
            "a1": [s.a1 for s in response.special_points], "a2": [s.a2 for s in response.special_points],
            "frequency": [s.frequency for s in response.special_points]}
        figure = ("response.png", plotting.frequency_response(response))
    for name, columns in files.items():
        write_csv(out / name, columns)
    if figure:
        save_figure(figure[1], out / figure[0])
    print(f"\nResults written to {out}/")
    return 0


def _summary_columns(points):
    columns = {name: [] for name in SUMMARY_COLUMNS}
    for pt in points:
        for name in SUMMARY_COLUMNS:
            value = getattr(pt, name)
            columns[name].append(MOTION_CODES[value] if name == "motion" else float(value))
    return columns


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
