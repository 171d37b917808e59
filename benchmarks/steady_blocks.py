"""Steady states in ensemble blocks (issue 43, item 2): the CPU time of a --n x --n basin of
attraction at the Fig 17 parameters (rho = 0.513, A = 2.0, impacts; the core's
attractor_points, one basin task) and of a 64-point independent rho sweep of Fig 12 (the core's
independent_sweep, one thread), with the points handed to the ensemble integrator
(steady_state_block) in blocks of K, against K = 1 (each point alone through the same state
machine, equal to steady_state). Every block size's results are checked equal to K = 1's, bit
for bit.

Timing as benchmarks/ensemble.py: one warm-up round of the sweep, then --repeats interleaved
rounds, medians of the CPU time of the process (time.process_time) and of the wall clock;
prints the processor model and the load. The basin's transient is --periods forcing periods
(max_transient_periods too: the Fig 17 motion is irregular and never settles) plus a window
of 32. With --before PATH (a site directory holding another build, e.g. main's) the single
path, a loop of sloshdyn.steady_state over the basin's first 64 initial states, is timed on
both builds side by side (and checked equal, bit for bit).

    python benchmarks/steady_blocks.py --n 20 --periods 100 --repeats 2 --before /tmp/main-site
    python benchmarks/steady_blocks.py --shooting --n 10 --repeats 1   # shooting's share
"""

from __future__ import annotations

import argparse
import math
import os
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import sloshdyn                                            # noqa: E402
from sloshdyn import _core                                 # noqa: E402
from ensemble import load_before, timed                    # noqa: E402
from run import cpu_model                                  # noqa: E402

BLOCKS = (1, 4, 16, 64)
FIG12 = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=math.pi / 4,
                            gamma=0.001, A=0.00075, rho=0.50)


def basin(n, periods, shooting=True):
    """The Fig 17 basin's task: run(K) -> the core's outputs (summaries, y_end, orbit, Poincare
    points, status)."""
    p = FIG12.replace(rho=0.513, A=2.0)
    steady = sloshdyn.Steady(transient_periods=periods, max_transient_periods=periods,
                             window_periods=32, shooting=shooting).array()
    x1, dx1 = np.meshgrid(np.linspace(-0.9, 0.9, n), np.linspace(-0.9, 0.9, n), indexing="ij")
    y0 = np.zeros((4, n * n), order="F")
    y0[0], y0[1] = x1.ravel(), dx1.ravel()
    integration = sloshdyn.Integration().array()
    return lambda k: _core.sloshdyn_bridge_studies.attractor_points(
        *p.array(), y0, integration, steady, k)[:5]


def sweep():
    """64 independent points rho in [0.49, 0.53] of Fig 12 from rest: run(K) -> summaries."""
    steady = sloshdyn.Steady(max_transient_periods=600, window_periods=32).array()
    values = np.linspace(0.49, 0.53, 64)
    integration = sloshdyn.Integration().array()
    return lambda k: _core.sloshdyn_bridge_simulation.independent_sweep(
        *FIG12.array(), 1, values, np.zeros(4), integration, steady, 1, k)[:3]


def single_loop(package, n, periods):
    """steady_state of the basin's first 64 initial states, one call each, by `package`."""
    p = package.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=math.pi / 4,
                           gamma=0.001, A=2.0, rho=0.513)
    steady = package.Steady(transient_periods=periods, max_transient_periods=periods,
                            window_periods=32)
    x1, dx1 = np.meshgrid(np.linspace(-0.9, 0.9, n), np.linspace(-0.9, 0.9, n), indexing="ij")
    starts = list(zip(x1.ravel(), dx1.ravel()))[:64]
    return lambda: [package.steady_state(p, (a, b, 0.0, 0.0), steady=steady).y_end
                    for a, b in starts]


def same(a, b):
    return all(np.array_equal(x, y, equal_nan=True) for x, y in zip(a, b))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", type=int, default=20)
    ap.add_argument("--periods", type=float, default=100)
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--before", help="site directory of another sloshdyn build")
    ap.add_argument("--shooting", action="store_true",
                    help="only the basin with and without shooting attempts (K = 16)")
    args = ap.parse_args()
    print(f"Machine: {cpu_model()}, {os.cpu_count()} cores; load average "
          f"{os.getloadavg()[0]:.2f} at start")
    if args.shooting:
        return shooting_cost(args)
    problems = {f"Fig 17 basin {args.n} x {args.n}, {args.periods:g} + 32 periods":
                basin(args.n, args.periods),
                "Fig 12 sweep, 64 independent rho": sweep()}
    sweep()(1)                  # warm-up
    for name, run in problems.items():
        cpu = {k: [] for k in BLOCKS}
        wall = {k: [] for k in BLOCKS}
        reference = None
        for _ in range(args.repeats):
            for k in BLOCKS:
                c, w, out = timed(lambda: run(k))
                cpu[k].append(c)
                wall[k].append(w)
                if reference is None:
                    reference = out
                assert same(out, reference), f"{name}: block {k} differs from block 1"
        base = float(np.median(cpu[1]))
        print(f"\n{name} (median of {args.repeats}; every block equal to K = 1 bit for bit)")
        print("| block K | CPU s | wall s | K = 1 / K (CPU) |")
        print("|---:|---:|---:|---:|")
        for k in BLOCKS:
            c, w = float(np.median(cpu[k])), float(np.median(wall[k]))
            print(f"| {k} | {c:.3f} | {w:.3f} | {base / c:.2f}x |")
    if args.before:
        loops = {"this build": single_loop(sloshdyn, args.n, args.periods),
                 "before": single_loop(load_before(args.before), args.n, args.periods)}
        cpu = {k: [] for k in loops}
        results = {}
        for _ in range(args.repeats):
            for name, run in loops.items():
                c, _, results[name] = timed(run)
                cpu[name].append(c)
        assert same(results["this build"], results["before"]), "the single path changed"
        print(f"\nSingle path: steady_state of 64 basin points, one call each (median of "
              f"{args.repeats}; both builds equal bit for bit)")
        print("| build | CPU s |")
        print("|---|---:|")
        for name in loops:
            print(f"| {name} | {float(np.median(cpu[name])):.3f} |")
    print(f"\nload average {os.getloadavg()[0]:.2f} at the end")


def shooting_cost(args):
    """The Fig 17 basin with Steady(shooting=True), the default, and shooting=False: the CPU
    time, and whether the points' results (all but the orbit rows, which count the attempts)
    are equal bit for bit."""
    runs = {flag: basin(args.n, args.periods, flag) for flag in (True, False)}
    cpu, out = {flag: [] for flag in runs}, {}
    for _ in range(args.repeats):
        for flag, run in runs.items():
            c, _, out[flag] = timed(lambda: run(16))
            cpu[flag].append(c)
    equal = same([out[True][i] for i in (0, 1, 3, 4)], [out[False][i] for i in (0, 1, 3, 4)])
    print(f"\nFig 17 basin {args.n} x {args.n}, {args.periods:g} + 32 periods, K = 16 (median of "
          f"{args.repeats})\n| shooting | CPU s |\n|---|---:|")
    for flag in runs:
        print(f"| {flag} | {float(np.median(cpu[flag])):.3f} |")
    print(f"\nsummaries, end states, Poincare points and status equal bit for bit: {equal}")


if __name__ == "__main__":
    main()
