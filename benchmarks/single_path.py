"""The single path side by side with another build (issue 43's "single trajectories not slower"):
`sloshdyn.simulate` looped over the 64 trajectories of ensemble.py (the Fig 14 case from 64
initial states, and a 64-point rho sweep from (0.01, 0, 0.01, 0); dop853, 100 forcing periods,
atol = 1e-3 rtol, end state only), this build and the other (a site directory made by
`pip install --target PATH`, loaded as a second package) alternated round by round; CPU time,
medians, and the largest difference of the end states relative to their largest component.

    python benchmarks/single_path.py --before /tmp/main-site --rounds 5
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import sloshdyn                                              # noqa: E402
from ensemble import load_before, problems                   # noqa: E402


def loop(package, params, states, t_end, rtol):
    """CPU seconds and end states of package.simulate over the trajectories."""
    integration = package.Integration(method="dop853", rtol=rtol, atol=1e-3 * rtol)
    params = [package.Parameters.from_array(*p.array()) for p in params]
    start = time.process_time()
    ends = [package.simulate(p, t_end, y0, n_out=2, integration=integration).y[:, -1]
            for p, y0 in zip(params, states)]
    return time.process_time() - start, np.array(ends)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--before", required=True, help="site directory of another sloshdyn build")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--periods", type=float, default=100.0)
    args = ap.parse_args()
    before = load_before(args.before)
    print("| problem | rtol | this build CPU s | before CPU s | before / this | max rel. difference |")
    print("|---|---:|---:|---:|---:|---:|")
    for name, params, states, t_end in problems(args.periods):
        for rtol in (1e-6, 1e-9, 1e-12):
            this, other = [], []
            for _ in range(args.rounds):
                seconds, ends = loop(sloshdyn, params, states, t_end, rtol)
                this.append(seconds)
                seconds, ends_before = loop(before, params, states, t_end, rtol)
                other.append(seconds)
            difference = np.max(np.abs(ends - ends_before)) / np.max(np.abs(ends_before))
            a, b = np.median(this), np.median(other)
            print(f"| {name} | {rtol:.0e} | {a:.3f} | {b:.3f} | {b / a:.2f}x | {difference:.1e} |",
                  flush=True)
    print(f"\nload average {os.getloadavg()[0]:.2f} at the end; {sloshdyn.__file__} against "
          f"{before.__file__}")


if __name__ == "__main__":
    main()
