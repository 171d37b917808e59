"""The fragility study's runs in ensemble blocks (issue 43, item 2): one task of a fragility
study (sloshdyn.studies.fragility._fragility_task) over --records synthetic records
(peers.synthetic_records, 20-100 s, seeded) x 20 intensities, a 10 m tank on 2 Hz supports
(peers.fragility_tank), timed with the runs of each record handed to the core's ensemble
integrator in blocks of K (fragility.ENSEMBLE_BLOCK = K) and, side by side in the same process,
with the path before this change: every run one bridge call of seismic_response (the old
_fragility_task's loop). Every block size's results are checked equal to the old path's, bit
for bit. With --before PATH (a site directory holding another build, e.g. main's) the single
path, sloshdyn.seismic_response of one run, and the task itself at the default block size
(the other build's _fragility_task on the same inputs, its results checked equal) are timed on
both builds side by side too.

Timing as benchmarks/ensemble.py: one warm-up, then --repeats interleaved rounds, medians of
the CPU time of the process (time.process_time) and of the wall clock; prints the processor
model and the load.

    python benchmarks/fragility_blocks.py --records 6 --repeats 3 --before /tmp/main-site
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import sloshdyn                                            # noqa: E402
from sloshdyn._errors import message_text                  # noqa: E402
from sloshdyn.studies import fragility                     # noqa: E402
import peers                                               # noqa: E402
from ensemble import load_before, timed                    # noqa: E402
from run import cpu_model                                  # noqa: E402

BLOCKS = (1, 2, 5, 10, 20)


def old_run_block(tank, ground, samples, runs, chosen, integration, out, i):
    """The path before the ensemble: each run of the block one seismic_response call."""
    for j, scaled, member_samples in runs:
        _, peaks, _, status, message = fragility._bridge.seismic_response(
            tank, scaled, member_samples, float(chosen[0]), int(chosen[1]), integration)
        out["status"][i, j] = status
        if status != 0:
            out["roof_impact"][i, j] = -1
            out["message"][i, j] = message_text(message)
            continue
        fragility._store_run(out, (i, j), peaks, (ground, samples), (scaled, member_samples))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--records", type=int, default=6)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--before", help="site directory of another sloshdyn build")
    args = ap.parse_args()
    print(f"Machine: {cpu_model()}, {os.cpu_count()} cores; load average "
          f"{os.getloadavg()[0]:.2f} at start")
    tank = peers.fragility_tank()
    records = peers.synthetic_records(args.records)
    intensities = np.linspace(0.05, 0.5, 20)          # Sa(T_sloshing, 0.5 %) [g]
    integration = sloshdyn.Integration()
    task_args = (tank.array(), [r._arrays() for r in records], intensities,
                 sloshdyn.acceleration_factor("g"), tank.sloshing_period, 0.005,
                 integration.array())
    new_run_block = fragility._run_block
    task_before_name = f"task at K = {fragility.ENSEMBLE_BLOCK}, before"

    def study(block):
        def run():
            if block == "old":
                fragility._run_block = old_run_block
            else:
                fragility._run_block, fragility.ENSEMBLE_BLOCK = new_run_block, block
            try:
                return fragility._fragility_task(*task_args)
            finally:
                fragility._run_block = new_run_block
        return run

    solvers = {"before: one seismic_response call a run": study("old")}
    solvers.update({f"ensemble blocks of K = {k}": study(k) for k in BLOCKS})
    one = records[0].scaled(sa=0.3, period=tank.sloshing_period, damping=0.005, units="g")
    if args.before:
        before = load_before(args.before)
        one_before = before.GroundMotion(dt=records[0].dt, acceleration=records[0].acceleration,
                                         units="m/s^2").scaled(
            sa=0.3, period=tank.sloshing_period, damping=0.005, units="g")
        tank_before = before.Tank(**{f: getattr(tank, f) for f in (
            "radius", "liquid_depth", "freeboard", "liquid_density", "tank_mass",
            "support_frequency", "support_damping")})
        solvers["single run: seismic_response, this build"] = (
            lambda: sloshdyn.seismic_response(tank, one).peak_table)
        solvers["single run: seismic_response, before"] = (
            lambda: before.seismic_response(tank_before, one_before).peak_table)
        before_task = importlib.import_module("sloshdyn_before.studies.fragility")._fragility_task
        solvers[task_before_name] = lambda: before_task(*task_args)
    results = {name: run() for name, run in solvers.items()}        # warm-up
    reference = results["before: one seismic_response call a run"]
    for name, out in results.items():
        if name.startswith("ensemble"):
            same = all(np.array_equal(out[k], reference[k], equal_nan=True)
                       for k in reference if k not in (fragility.SECONDS, "message"))
            assert same, f"{name}: results differ from the path before"
    if args.before:
        single = [results[n] for n in solvers if n.startswith("single")]
        assert all(np.array_equal(single[0][k], single[1][k], equal_nan=True)
                   for k in single[0]), "the single run differs between the builds"
        task_before = results[task_before_name]
        assert all(np.array_equal(task_before[k], reference[k], equal_nan=True)
                   for k in reference if k not in (fragility.SECONDS, "message")), \
            "the task differs between the builds"
    times = {name: [] for name in solvers}
    for _ in range(args.repeats):
        for name, run in solvers.items():
            cpu, wall, _ = timed(run)
            times[name].append((cpu, wall))
    runs = args.records * len(intensities)
    base = np.median([c for c, _ in times["before: one seismic_response call a run"]])
    print(f"\n# Fragility task, {args.records} records x {len(intensities)} intensities "
          f"({runs} runs), median of {args.repeats} interleaved rounds\n")
    print("| path | CPU s | wall s | runs/s (CPU) | vs before (CPU) |")
    print("|---|---:|---:|---:|---:|")
    for name, t in times.items():
        cpu, wall = np.median([c for c, _ in t]), np.median([w for _, w in t])
        if name.startswith("single"):
            print(f"| {name} | {cpu:.4f} | {wall:.4f} | | |")
        else:
            print(f"| {name} | {cpu:.3f} | {wall:.3f} | {runs / cpu:.1f} | "
                  f"{base / cpu:.2f}x |")
    print(f"\nEvery block size's results equal the path before bit for bit; load average "
          f"{os.getloadavg()[0]:.2f} at the end")


if __name__ == "__main__":
    main()
