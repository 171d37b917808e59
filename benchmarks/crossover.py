"""The work-precision ladder behind method = 'auto' (fortran/numerics/sloshdyn_integrator.f90):
sloshdyn.simulate with each explicit pair ('rk45', 'dop853', 'vern9') on the two benchmark
problems of run.py, rtol = 1e-3 ... 1e-14 in half-decades (atol = 1e-3 rtol), output at the
final time, timed interleaved (median of --repeats, at least 5 for runs under 0.5 s); then
problem (a) again with output 8 times per forcing period (dense output on: the interpolants'
extra stages are paid, 3 per step for dop853 and 4 for vern9; the steps and errors are the same).

For every rtol it prints each method's time, rhs evaluations and error, and the time each
method needs to reach the error dop853 reaches at that rtol (log-log interpolation along its
work-precision front, as run.py's equal-accuracy table). The crossovers are the rtols below
which dop853 beats rk45 and vern9 beats dop853 at equal accuracy; where the errors saturate
(above 1e-2: problem (b), whose impacts make the final state unpredictable over 500 periods,
as run.py says), at equal tolerance.

    python benchmarks/crossover.py [--repeats N] [--quick]
"""
from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import numpy as np  # noqa: E402

import peers  # noqa: E402
import sloshdyn  # noqa: E402
from run import (ATOL_FACTOR, REF_RTOL, SATURATED, machine_info, rel_error,  # noqa: E402
                 time_at_error, timed_interleaved)

METHODS = ("rk45", "dop853", "vern9")
RK45_TIGHTEST = 1e-11     # rk45 below this takes seconds per run and is never the fastest


def run_dense(problem, rtol, method):
    """As peers.run_sloshdyn, with output 8 times per forcing period."""
    tau = np.linspace(0.0, problem.t_end, 8 * problem.periods + 1)
    sim = sloshdyn.simulate(problem.params, problem.t_end, problem.y0, tau_out=tau,
                            integration=sloshdyn.Integration(rtol=rtol, atol=rtol * ATOL_FACTOR,
                                                             method=method))
    return peers.Run(sim.y[:, -1].copy(), sim.n_rhs, sim.n_accepted + sim.n_rejected,
                     sim.n_rejected)


def ladder(problem, rtols, repeats, dense=False):
    ref = peers.run_sloshdyn(problem, REF_RTOL, REF_RTOL * ATOL_FACTOR, "vern9").y_end
    ref_853 = peers.run_sloshdyn(problem, REF_RTOL, REF_RTOL * ATOL_FACTOR, "dop853").y_end
    floor = rel_error(ref_853, ref)
    rows = {}
    for rtol in rtols:
        fns = {m: ((lambda m=m: run_dense(problem, rtol, m)) if dense else
                   (lambda m=m: peers.run_sloshdyn(problem, rtol, rtol * ATOL_FACTOR, m)))
               for m in METHODS if m != "rk45" or rtol >= RK45_TIGHTEST}
        out = timed_interleaved(fns, repeats)
        rows[rtol] = {m: (t, run.n_rhs, rel_error(run.y_end, ref)) for m, (t, run, _) in out.items()}
    return rows, floor


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--quick", action="store_true", help="200/50 periods, 1 repeat")
    args = ap.parse_args(argv)
    start = time.time()
    print(machine_info())
    rtols = [10.0 ** (-k / 2) for k in range(6, 29)]
    problems = peers.problems(*((200, 50) if args.quick else (2000, 500)))
    for problem, dense in [(problems[0], False), (problems[1], False), (problems[0], True)]:
        rows, floor = ladder(problem, rtols, 1 if args.quick else args.repeats, dense)
        print(f"\n### problem {problem.title}" + (", output 8 times per period" if dense else
                                                   ", output at the final time") + "\n")
        print(f"error = relative to sloshdyn vern9 at rtol {REF_RTOL:g}; dop853 at that rtol "
              f"differs by {floor:.1e} (errors below ~10x this are not resolved)\n")
        print("| rtol | " + " | ".join(f"{m} time | {m} rhs | {m} error" for m in METHODS)
              + " | time at dop853's error: " + " / ".join(METHODS) + " | fastest |")
        print("|---" * (2 + 3 * len(METHODS) + 1) + "|")
        fronts = {m: [(e, t) for r in rows.values() if m in r for t, _, e in [r[m]]]
                  for m in METHODS}
        for rtol, r in rows.items():
            cells = []
            for m in METHODS:
                cells += ([f"{r[m][0] * 1e3:.2f} ms", str(r[m][1]), f"{r[m][2]:.1e}"]
                          if m in r else ["—"] * 3)
            target = max(r["dop853"][2], 10 * floor)
            eq = {m: time_at_error(fronts[m], target) for m in METHODS}
            if target < SATURATED:
                best = min(eq, key=lambda m: eq[m][0])
            else:
                best = min(r, key=lambda m: r[m][0]) + " (equal tolerance)"
            cells.append(" / ".join(f"{eq[m][1]}{eq[m][0] * 1e3:.2f}" for m in METHODS) + " ms")
            print(f"| {rtol:.0e} | " + " | ".join(cells) + f" | {best} |")
    print(f"\nrun time {time.time() - start:.0f} s")


if __name__ == "__main__":
    main()
