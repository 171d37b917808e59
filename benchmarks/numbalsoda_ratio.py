"""sloshdyn against numbalsoda's dop853 on issue 28's problem: the Fig 14 parameters from rest,
tau = 0 ... 20 000, output at the end, atol = 1e-3 rtol, at rtol 1e-6, 1e-9 and 1e-12. CPU
time (time.process_time, so other jobs on the machine count less), median of N interleaved
runs in one process; the processor, the load and the end states are printed with the table.

    python benchmarks/numbalsoda_ratio.py [N]      # N = 7 by default

Needs numba and numbalsoda (pip install numba numbalsoda)."""
import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import peers  # noqa: E402
from run import cpu_model  # noqa: E402
import sloshdyn  # noqa: E402


class FromRest:
    params = peers.fig14_parameters()
    y0 = [0.0, 0.0, 0.0, 0.0]
    t_end = 20000.0


def main():
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 7
    numba = peers.Numba()
    if not numba.available:
        sys.exit(f"numbalsoda peer not available: {numba.reason}")
    problem = FromRest()
    print(f"{cpu_model()}; sloshdyn {sloshdyn.__version__}, {numba.versions}; load {os.getloadavg()}")
    print("| rtol | sloshdyn dop853 | sloshdyn auto | numbalsoda dop853 | speed-up dop853 | "
          "speed-up auto | rhs evaluations | end states differ by |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for rtol in (1e-6, 1e-9, 1e-12):
        atol = 1e-3 * rtol
        runs = {"dop853": lambda: peers.run_sloshdyn(problem, rtol, atol, "dop853").y_end,
                "auto": lambda: peers.run_sloshdyn(problem, rtol, atol, "auto").y_end,
                "numbalsoda": lambda: numba.integrate(problem.params, problem.y0,
                                                      problem.t_end, rtol, atol)[0]}
        times = {name: [] for name in runs}
        ends = {name: run() for name, run in runs.items()}     # warm-up
        for _ in range(repeats):
            for name, run in runs.items():
                start = time.process_time()
                run()
                times[name].append(time.process_time() - start)
        ms = {name: 1e3 * statistics.median(t) for name, t in times.items()}
        n_rhs = peers.run_sloshdyn(problem, rtol, atol, "dop853").n_rhs
        differ = float(np.max(np.abs(ends["dop853"] - ends["numbalsoda"])))
        print(f"| {rtol:g} | {ms['dop853']:.1f} ms | {ms['auto']:.1f} ms | "
              f"{ms['numbalsoda']:.1f} ms | {ms['numbalsoda'] / ms['dop853']:.2f}x | "
              f"{ms['numbalsoda'] / ms['auto']:.2f}x | {n_rhs} | {differ:.1e} |", flush=True)
    print(f"load at the end {os.getloadavg()}")


if __name__ == "__main__":
    main()
