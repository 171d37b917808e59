"""The whole fragility study of issue 43's target, on this build and, with --before PATH, on
another (a site directory made by `pip install --target PATH`, e.g. main's), alternated round by
round: `sloshdyn.fragility_study(peers.fragility_tank(), peers.synthetic_records(44),
linspace(0.05, 0.5, 20), workers=N)` at the default task size, each measurement in a fresh
process (a small study first, so imports and the cluster's start are not counted). Prints the
wall time, the CPU time of the process (the workers are threads: theirs is in it), the load,
and whether the builds' peaks (wave height, base shear, overturning moment) are equal bit for
bit.

    python benchmarks/fragility_study.py --before /tmp/main-site --workers 2 --rounds 2
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
PEAKS = ("peak_wave_height", "peak_base_shear", "peak_overturning_moment")


def measure(workers, peaks_file):
    """One study in this process; prints 'wall cpu' and saves the peaks to peaks_file."""
    import shutil
    import time
    sys.path.insert(0, str(HERE))
    import sloshdyn
    import peers
    tank, intensities = peers.fragility_tank(), np.linspace(0.05, 0.5, 20)
    records = peers.synthetic_records(44)
    with tempfile.TemporaryDirectory() as where:
        sloshdyn.fragility_study(tank, peers.synthetic_records(2, quick=True), intensities[:2],
                                 os.path.join(where, "warm.zarr"), workers=1, progress=False)
        cpu, wall = time.process_time(), time.perf_counter()
        ds = sloshdyn.fragility_study(tank, records, intensities,
                                      os.path.join(where, "f.zarr"), workers=workers,
                                      progress=False)
        wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
        np.save(peaks_file, np.stack([ds[name].values for name in PEAKS]))
        shutil.rmtree(os.path.join(where, "f.zarr"))
    print(f"{wall:.3f} {cpu:.3f}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--before", help="site directory of another sloshdyn build")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--measure", help=argparse.SUPPRESS)     # the child process's peaks file
    args = ap.parse_args()
    if args.measure:
        return measure(args.workers, args.measure)
    from run import cpu_model
    print(f"Machine: {cpu_model()}, {os.cpu_count()} cores; load average "
          f"{os.getloadavg()[0]:.2f} at start")
    builds = {"this build": None}
    if args.before:
        builds["before"] = args.before
    rows, peaks = [], {}
    with tempfile.TemporaryDirectory() as where:
        for r in range(args.rounds):
            for name, site in builds.items():
                env = dict(os.environ)
                if site:
                    env["PYTHONPATH"] = os.pathsep.join([site, env.get("PYTHONPATH", "")])
                peaks_file = os.path.join(where, f"{r}-{len(peaks)}.npy")
                out = subprocess.run([sys.executable, __file__, "--workers", str(args.workers),
                                      "--measure", peaks_file], env=env, check=True,
                                     capture_output=True, text=True).stdout.split()
                peaks.setdefault(name, np.load(peaks_file))
                rows.append(f"| {r + 1} | {name} | {float(out[-2]):.2f} | {float(out[-1]):.2f} "
                            f"| {os.getloadavg()[0]:.2f} |")
    print(f"\nFragility study 44 records x 20 intensities, {args.workers} worker(s)")
    print("| round | build | wall s | CPU s | load |\n|---:|---|---:|---:|---:|")
    print("\n".join(rows))
    if args.before:
        same = np.array_equal(peaks["this build"], peaks["before"], equal_nan=True)
        print(f"\npeaks of the two builds equal bit for bit: {same}")


if __name__ == "__main__":
    main()
