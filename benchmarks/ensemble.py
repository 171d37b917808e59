"""Ensemble throughput (issue 43): trajectories per second of sloshdyn.simulate_ensemble against
numbalsoda's dop853 looped over the same trajectories in one process, and against
sloshdyn.simulate looped (the single-trajectory path), on two sets of 64 trajectories: the
Fig 14 problem from 64 initial states, and a 64-point rho sweep (0.49 ... 0.53) of it, at
rtol 1e-6, 1e-9, 1e-12 (atol = 1e-3 rtol), output at the final time only.

With --before PATH (a site directory holding another build of sloshdyn, e.g. main's, installed
with pip --target PATH) the single path of that build is timed in the same process, side by
side, under the name sloshdyn_before.

Timing: every solver runs once before timing; then --repeats rounds, each timing every solver
once in turn (interleaved, so drifts of the machine's load hit them alike); medians. Both the
CPU time of the process (time.process_time: the measure to read on a loaded machine, where a
long call waits for the processor more than many short ones) and the wall clock are shown.
Ratios are per rtol against numbalsoda's CPU time. Prints the processor model and the load.

    python benchmarks/ensemble.py                      # 200 forcing periods, 3 rounds
    python benchmarks/ensemble.py --periods 50 --repeats 1 --before /tmp/main-site
    python benchmarks/ensemble.py --blocks --periods 50   # throughput by block size K
"""

from __future__ import annotations

import argparse
import importlib.util
import math
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import sloshdyn                                            # noqa: E402
from peers import Numba, fig14_parameters                  # noqa: E402
from run import cpu_model                                  # noqa: E402

K = 64


def load_before(site):
    """The sloshdyn package of another build (in site) as module sloshdyn_before."""
    spec = importlib.util.spec_from_file_location(
        "sloshdyn_before", Path(site) / "sloshdyn" / "__init__.py",
        submodule_search_locations=[str(Path(site) / "sloshdyn")])
    module = importlib.util.module_from_spec(spec)
    sys.modules["sloshdyn_before"] = module
    spec.loader.exec_module(module)
    return module


def problems(periods):
    """(name, params list, y0 list, t_end) of the two sets of 64 trajectories."""
    p = fig14_parameters()
    t_end = periods * 2 * math.pi / p.rho
    rng = np.random.default_rng(43)
    states = [(0.01, 0.0, 0.01, 0.0)] + [tuple(x) for x in
                                         rng.uniform(-0.02, 0.02, size=(K - 1, 4))]
    sweep = [p.replace(rho=r) for r in np.linspace(0.49, 0.53, K)]
    return [("Fig 14, 64 initial states", [p] * K, states, t_end),
            ("Fig 14, 64-point rho sweep", sweep, [(0.01, 0.0, 0.01, 0.0)] * K, t_end)]


def timed(run):
    c0, w0 = time.process_time(), time.perf_counter()
    out = run()
    return time.process_time() - c0, time.perf_counter() - w0, out


def block_sizes(periods, repeats):
    """256 trajectories of a rho sweep in blocks of K against the simulate loop (CPU time)."""
    p = fig14_parameters()
    t_end = periods * 2 * math.pi / p.rho
    integ = sloshdyn.Integration(rtol=1e-9, atol=1e-12, method="dop853")
    params = [p.replace(rho=r) for r in np.linspace(0.49, 0.53, 256)]
    y0 = (0.01, 0.0, 0.01, 0.0)

    def loop():
        for q in params:
            sloshdyn.simulate(q, t_end, y0, n_out=2, integration=integ)

    def blocks(k):
        return lambda: [sloshdyn.simulate_ensemble(params[i:i + k], t_end, y0, n_out=2,
                                                   integration=integ)
                        for i in range(0, len(params), k)]
    runs = {"loop of simulate": loop, **{str(k): blocks(k) for k in (1, 4, 16, 64, 256)}}
    for run in runs.values():
        run()
    cpu = {k: [] for k in runs}
    for _ in range(repeats):
        for k, run in runs.items():
            cpu[k].append(timed(run)[0])
    base = float(np.median(cpu["loop of simulate"]))
    print("| K | CPU s | trajectories/s | vs simulate loop |")
    print("|---|---:|---:|---:|")
    for k in runs:
        m = float(np.median(cpu[k]))
        print(f"| {k} | {m:.3f} | {len(params) / m:.0f} | {base / m:.2f}x |")
    print(f"Machine: {cpu_model()}, {os.cpu_count()} cores; load average "
          f"{os.getloadavg()[0]:.2f} at the end")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--periods", type=float, default=200.0)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--before", help="site directory of another sloshdyn build")
    ap.add_argument("--blocks", action="store_true", help="throughput by block size only")
    args = ap.parse_args()
    if args.blocks:
        return block_sizes(args.periods, args.repeats)
    before = load_before(args.before) if args.before else None
    nb = Numba()
    if not nb.available:
        print(f"numbalsoda dop853 peer SKIPPED: {nb.reason}")
    print(f"# Ensemble throughput, {K} trajectories of {args.periods:g} forcing periods, "
          f"median of {args.repeats} interleaved rounds")
    print(f"Machine: {cpu_model()}, {os.cpu_count()} cores; load average "
          f"{os.getloadavg()[0]:.2f} at start")
    print()
    print("| problem | rtol | solver | CPU s | wall s | trajectories/s (CPU) | "
          "speed-up vs numbalsoda (CPU) | vs simulate loop (CPU) | rhs evaluations |")
    print("|---|---:|---|---:|---:|---:|---:|---:|---:|")
    for name, params, states, t_end in problems(args.periods):
        for rtol in (1e-6, 1e-9, 1e-12):
            atol = rtol * 1e-3
            integ = sloshdyn.Integration(rtol=rtol, atol=atol, method="dop853")
            solvers = {}
            if nb.available:
                solvers["numbalsoda dop853, loop"] = lambda: [
                    nb.integrate(p, y, t_end, rtol, atol)[0] for p, y in zip(params, states)]
            solvers["sloshdyn simulate dop853, loop"] = lambda: [
                sloshdyn.simulate(p, t_end, y, n_out=2, integration=integ)
                for p, y in zip(params, states)]
            if before is not None:
                bint = before.Integration(rtol=rtol, atol=atol, method="dop853")
                bparams = [before.Parameters.from_array(*p.array()) for p in params]
                solvers["before: simulate dop853, loop"] = lambda: [
                    before.simulate(p, t_end, y, n_out=2, integration=bint)
                    for p, y in zip(bparams, states)]
            solvers["sloshdyn simulate_ensemble dop853"] = lambda: sloshdyn.simulate_ensemble(
                params, t_end, states, n_out=2, integration=integ)
            auto = sloshdyn.Integration(rtol=rtol, atol=atol)
            solvers[f"sloshdyn simulate_ensemble auto ({auto.method_used})"] = \
                lambda: sloshdyn.simulate_ensemble(params, t_end, states, n_out=2,
                                                   integration=auto)
            for run in solvers.values():
                run()                                   # warm-up
            times = {s: [] for s in solvers}
            for _ in range(args.repeats):
                for s, run in solvers.items():
                    times[s].append(timed(run)[:2])
            ens = sloshdyn.simulate_ensemble(params, t_end, states, n_out=2, integration=integ)
            loop = [sloshdyn.simulate(p, t_end, y, n_out=2, integration=integ)
                    for p, y in zip(params, states)]
            assert all(np.array_equal(ens.y[i], r.y) for i, r in enumerate(loop)), \
                "ensemble differs from the single path"
            n_rhs = {"sloshdyn simulate dop853, loop": int(ens.n_rhs.sum()),
                     "sloshdyn simulate_ensemble dop853": int(ens.n_rhs.sum())}
            cpu = {s: float(np.median([t[0] for t in v])) for s, v in times.items()}
            wall = {s: float(np.median([t[1] for t in v])) for s, v in times.items()}
            ref = cpu.get("numbalsoda dop853, loop")
            single = cpu["sloshdyn simulate dop853, loop"]
            for s in solvers:
                vs_nb = f"{ref / cpu[s]:.2f}x" if ref else "n/a"
                print(f"| {name} | {rtol:g} | {s} | {cpu[s]:.3f} | {wall[s]:.3f} | "
                      f"{K / cpu[s]:.0f} | {vs_nb} | {single / cpu[s]:.2f}x | "
                      f"{n_rhs.get(s, '')} |")
            sys.stdout.flush()
    print()
    print(f"Machine: {cpu_model()}, {os.cpu_count()} cores; load average "
          f"{os.getloadavg()[0]:.2f} at the end")


if __name__ == "__main__":
    main()
