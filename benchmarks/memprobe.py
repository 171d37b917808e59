"""Peak memory of one frequency sweep in a fresh process (called by benchmarks/run.py).

usage: python memprobe.py N_POINTS THREADS TRANSIENT_PERIODS WINDOW_PERIODS
Prints one JSON line: the peak resident set size (KiB) after import and a warm-up, after the
sweep, and the tracemalloc peak (bytes, Python-side allocations only) during the sweep.

The peak is VmHWM of /proc/self/status where it exists: on Linux, getrusage's ru_maxrss keeps
the parent's high-water mark across fork and exec, so in a child of a large process (run.py
with numba and scipy loaded, about 250 MiB) it would hide the sweep entirely.
"""

import json
import resource
import sys
import time
import tracemalloc

import numpy as np

import sloshdyn
from peers import fig14_parameters


def peak_kib():
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]), "VmHWM"
    except OSError:
        pass
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, "ru_maxrss"


def main():
    n, threads, transient, window = (int(sys.argv[1]), int(sys.argv[2]), float(sys.argv[3]),
                                     int(sys.argv[4]))
    p = fig14_parameters()
    steady = sloshdyn.Steady(transient_periods=transient, settle_tol=0, window_periods=window)
    # warm-up: one point, so libraries, OpenMP threads and the bridge are loaded before measuring
    sloshdyn.frequency_sweep(p, np.array([0.49, 0.50]), steady=sloshdyn.Steady(
        transient_periods=1, settle_tol=0, window_periods=16), threads=threads, start_from="y0")
    before, source = peak_kib()
    tracemalloc.start()
    t = time.perf_counter()
    sweep = sloshdyn.frequency_sweep(p, np.linspace(0.49, 0.53, n), steady=steady,
                                     threads=threads, start_from="y0")
    seconds = time.perf_counter() - t
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    after, _ = peak_kib()
    print(json.dumps({"n": n, "threads": threads, "peak_before_kib": before,
                      "peak_after_kib": after, "source": source, "tracemalloc_peak_bytes": peak,
                      "seconds": seconds, "points": len(sweep.points)}))


if __name__ == "__main__":
    main()
