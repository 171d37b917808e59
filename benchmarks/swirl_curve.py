"""Cost of the swirl boundary curve (issue 41, item 4): the curve of
tests/python/test_swirl_boundary_curve.py (the damped spherical pendulum on stiff rods, rho
0.98-1.03, A 5e-5 to 5e-4), its points, its closing fold and the CPU time it takes, for this
build and, with --before DIR, for another installation of sloshdyn (e.g. main's, installed with
`pip install --no-build-isolation --no-deps --target DIR .` from a checkout of main) measured
in the same run, each in a fresh process.

    python benchmarks/swirl_curve.py [--before DIR] [--repeats 3]
"""

import argparse
import json
import os
import subprocess
import sys

MEASURE = r"""
import json, time
import sloshdyn
from sloshdyn import spatial
params = sloshdyn.Parameters(s1=1.0, mu1=0.01, kappa=1e3, theta0=1.4, beta=0.0, gamma=0.0,
                             delta=0.0, A=2.5e-4, rho=1.02, zeta=5e-4, n=6, p=2)
start = time.process_time()
curve = spatial.swirl_boundary_curve(params, (0.98, 1.03), (5e-5, 5e-4), from_end="high")
cpu = time.process_time() - start
folds = [(float(f["rho"]), float(f["A"])) for f in curve.folds]
print(json.dumps({"cpu": cpu, "points": len(curve.table["rho"]), "folds": folds,
                  "where": sloshdyn.__file__}))
"""


def measure(site, repeats):
    env = dict(os.environ)
    if site:
        env["PYTHONPATH"] = site
    runs = [json.loads(subprocess.run([sys.executable, "-c", MEASURE], env=env, check=True,
                                      capture_output=True, text=True).stdout)
            for _ in range(repeats)]
    best = min(runs, key=lambda r: r["cpu"])
    return best, sorted(r["cpu"] for r in runs)[len(runs) // 2]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", help="site directory of the sloshdyn to compare with")
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    rows = [("this build", None)] + ([("before", args.before)] if args.before else [])
    results = {name: measure(site, args.repeats) for name, site in rows}
    print("| build | points | closing fold (rho, A) | CPU s (median) |")
    print("|---|---:|---|---:|")
    for name, (run, median) in results.items():
        folds = ", ".join(f"({r:.10f}, {a:.10e})" for r, a in run["folds"])
        print(f"| {name} | {run['points']} | {folds} | {median:.2f} |")
    if args.before:
        print(f"\nratio before/this: {results['before'][1] / results['this build'][1]:.2f}")
    with open("/proc/cpuinfo") as info:
        model = next((l.split(":", 1)[1].strip() for l in info if l.startswith("model name")),
                     "unknown")
    print(f"processor: {model}; load {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
