"""Benchmark of the studies (issue 13), in one process run: ratios measured in this run.

    python benchmarks/studies.py [--quick] [--repeats N] [--only SECTION ...] [--map100]

Sections (medians of --repeats timed runs; every ratio compares runs made here, now):
  steady    a periodic steady state at default settings, shooting vs integration only, and
            how far each ends from the exact orbit (the shooting code's)
  sweep     the 61-point Fig 12 frequency sweep (0.50-0.52 up and back down) at defaults
  tasks     the engine's per-point overhead against a direct loop over the same points, for
            several task sizes (points per task), on a client started beforehand
  workers   2 local workers against 1 on the same response map, threads and processes,
            with the cluster start-up time
  kinds     the embedded cluster's two worker kinds on a fragility study (44 records x 20
            intensities) and a response map at defaults, 1 and 2 workers, alternated by round
  map100    (--map100) a 100 x 100 response map on this machine and its projection to 64 cores
  cluster8  an 8-worker local cluster (processes) gives the serial answer
Progress goes to stderr, tables to stdout. --quick is a smoke run (tiny sizes, 1 repeat): its
numbers mean nothing. Never run from the timed tests.
"""

from __future__ import annotations

import argparse
import math
import os
import shutil
import statistics
import sys
import tempfile
import time

import numpy as np

import sloshdyn
from sloshdyn.figures import FIG12


def log(msg):
    print(f"  .. {msg}", file=sys.stderr, flush=True)


def timed(fn, repeats):
    times, result = [], None
    for _ in range(repeats):
        t = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times), result


def orbit_distance(p, y_end):
    """|y_end - y*| / |y*| with y* the shooting code's orbit through y_end."""
    orbit = sloshdyn.periodic_orbit(p, y_end)
    return float(np.linalg.norm(y_end - orbit.y0) / np.linalg.norm(orbit.y0))


def section_steady(args):
    print("\n## Periodic steady state at default settings: shooting vs integration only\n")
    print("| rho | integration only [s] | with shooting [s] | speed-up | transient periods "
          "(only / shooting) | max_x1 rel. diff. | distance to orbit (only / shooting) |")
    print("|---|---|---|---|---|---|---|")
    ratios = []
    for rho in ((0.513,) if args.quick else (0.49, 0.505, 0.513, 0.517, 0.52)):
        p = FIG12.replace(rho=rho)
        t_off, off = timed(lambda: sloshdyn.steady_state(p, steady=sloshdyn.Steady(shooting=False)),
                           args.repeats)
        t_on, on = timed(lambda: sloshdyn.steady_state(p), max(args.repeats, 5))
        ratios.append(t_off / t_on)
        print(f"| {rho} | {t_off:.3f} | {t_on:.4f} | {t_off / t_on:.0f}x | "
              f"{off.transient_periods:.0f} / {on.transient_periods:.0f} | "
              f"{abs(on.max_x1 - off.max_x1) / off.max_x1:.1e} | "
              f"{orbit_distance(p, off.y_end):.1e} / {orbit_distance(p, on.y_end):.1e} |")
    print(f"\nmedian speed-up {statistics.median(ratios):.0f}x (target >= 20x): "
          f"{'PASS' if statistics.median(ratios) >= 20 else 'MISS'}; the shooting path ends on "
          "the orbit, the integration only approaches it (equal or better accuracy)")


def section_sweep(args):
    print("\n## The 61-point frequency sweep (Fig 12, rho 0.50-0.52, 31 up and 30 down, "
          "defaults, carrying the state)\n")
    values = sloshdyn.sweep_values(0.50, 0.52, 6 if args.quick else 31, "both")
    t_on, on = timed(lambda: sloshdyn.frequency_sweep(FIG12, values), args.repeats)
    t_off, off = timed(lambda: sloshdyn.frequency_sweep(
        FIG12, values, steady=sloshdyn.Steady(shooting=False)), 1)
    kinds = [pt.motion for pt in on.points]
    quasi = [i for i, k in enumerate(kinds) if k != "periodic"]
    t_quasi = 0.0
    if quasi:            # one non-periodic point alone, from rest: what each of them costs
        t_quasi, _ = timed(lambda: sloshdyn.steady_state(
            FIG12.replace(rho=float(values[quasi[0]]))), 1)
    print(f"| points | with shooting [s] | integration only [s] | speed-up | non-periodic points |")
    print("|---|---|---|---|---|")
    print(f"| {len(values)} | {t_on:.2f} | {t_off:.2f} | {t_off / t_on:.1f}x | {len(quasi)} "
          f"(each ~{t_quasi:.1f} s: integration to max_transient_periods by design) |")
    periodic = sum(1 for k in kinds if k == "periodic")
    print(f"\ntarget < 10 s: {'PASS' if t_on < 10 else 'MISS'} ({t_on:.1f} s for {periodic} "
          f"periodic and {len(quasi)} non-periodic points)")


def grid(args, n_f=None, n_a=None):
    n_f = n_f or (4 if args.quick else 16)
    n_a = n_a or (2 if args.quick else 8)
    return np.linspace(0.49, 0.53, n_f), np.linspace(0.0003, 0.0012, n_a)


def direct_loop(f, a, steady=sloshdyn.Steady()):
    return [[sloshdyn.steady_state(FIG12.replace(rho=x, A=y), steady=steady) for y in a] for x in f]


def balanced(args):
    """A grid of points of equal cost (fixed transient, no shooting): scaling and overhead
    measured without the load imbalance of a map's costly quasi-periodic corners."""
    steady = sloshdyn.Steady(settle_tol=0, transient_periods=100, window_periods=16,
                             shooting=False)
    return (np.linspace(0.49, 0.53, 8 if args.quick else 32),
            np.linspace(0.0003, 0.0012, 4 if args.quick else 16), steady)


def section_tasks(args):
    from dask.distributed import Client, LocalCluster
    print("\n## Engine overhead per point against a direct loop (1 worker process, 1 thread, "
          "client started beforehand; equal-cost points)\n")
    f, a, steady = balanced(args)
    n = f.size * a.size
    print("Overhead = engine wall time over the time its task spent computing the same points "
          "in the same run (a direct loop inside the worker), minus 1; 'vs loop' compares with "
          "a separate direct loop of steady_state in this process (sensitive to the machine's "
          "other load).\n")
    print("| points per task | tasks | engine [s] | computing in tasks [s] | overhead | direct "
          "loop [s] | vs loop |")
    print("|---|---|---|---|---|---|---|")
    rows = []
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                      dashboard_address=None, silence_logs=50) as cluster, Client(cluster) as c:
        c.run(lambda: __import__("sloshdyn"))
        for ppt in ((1, 8) if args.quick else (1, 8, 32, 128)):
            samples = []
            for _ in range(args.repeats):      # interleaved: loop, engine, loop, engine, ...
                t_direct, _ = timed(lambda: direct_loop(f, a, steady), 1)
                store = tempfile.mkdtemp(prefix="bench-tasks-")
                try:
                    t0 = time.perf_counter()
                    ds = sloshdyn.response_map(FIG12, f, a, os.path.join(store, "s.zarr"),
                                               client=c, steady=steady, points_per_task=ppt,
                                               progress=False)
                    t = time.perf_counter() - t0
                finally:
                    shutil.rmtree(store, ignore_errors=True)
                samples.append((t, ds.attrs["compute_seconds"], t_direct))
            t, inside, t_direct = (statistics.median(x) for x in zip(*samples))
            over = t / inside - 1
            rows.append((ppt, over))
            print(f"| {ppt} | {math.ceil(n / ppt)} | {t:.2f} | {inside:.2f} | {100 * over:.1f} % "
                  f"| {t_direct:.2f} | {100 * (t / t_direct - 1):+.1f} % |")
    chosen = sloshdyn.studies.auto_points_per_task(n, 1)
    mine = [o for p_, o in rows if p_ == chosen]
    if mine:
        print(f"\nthe engine's choice for {n} points on 1 worker: {chosen} points per task, "
              f"overhead {100 * mine[0]:.1f} % (target <= 5 %): "
              f"{'PASS' if mine[0] <= 0.05 else 'MISS'}")


def section_workers(args):
    from dask.distributed import Client, LocalCluster
    print("\n## 2 local workers against 1 on the same response map (equal-cost points, "
          "8 points per task)\n")
    f, a, steady = balanced(args)
    print("| worker kind | start-up [s] | 1 worker [s] | 2 workers [s] | speed-up |")
    print("|---|---|---|---|---|")
    results = {}
    for kind in ("threads", "processes"):
        times = {}
        for n in (1, 2):
            processes = kind == "processes"
            t0 = time.perf_counter()
            with LocalCluster(n_workers=n if processes else 1,
                              threads_per_worker=1 if processes else n, processes=processes,
                              dashboard_address=None, silence_logs=50) as cluster, \
                    Client(cluster) as c:
                c.run(lambda: __import__("sloshdyn"))
                startup = time.perf_counter() - t0

                def run():
                    store = tempfile.mkdtemp(prefix="bench-workers-")
                    try:
                        return sloshdyn.response_map(FIG12, f, a, os.path.join(store, "s.zarr"),
                                                     client=c, steady=steady, points_per_task=8,
                                                     progress=False)
                    finally:
                        shutil.rmtree(store, ignore_errors=True)
                times[n], ds = timed(run, args.repeats)
                results[(kind, n)] = ds
        speedup = times[1] / times[2]
        print(f"| {kind} | {startup:.2f} | {times[1]:.2f} | {times[2]:.2f} | {speedup:.2f}x |")
    same = all(results[("threads", 1)][v].equals(results[k][v]) for k in results
               for v in ("max_x1", "max_u2", "motion"))
    print(f"\nall four runs identical bit for bit: {same}; target >= 1.85x on 2 workers "
          f"(machine load now {os.getloadavg()[0]:.2f}: other processes take cores too)")


def section_kinds(args):
    """Issue 28's scaling target on the embedded cluster as a user starts it: each study kind
    on 1 then 2 workers of each worker kind, the kinds alternated round by round."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import peers
    print("\n## The embedded cluster's worker kinds: 1 and 2 workers, default task size\n")
    n_records, n_intensities = (2, 2) if args.quick else (44, 20)
    records = peers.synthetic_records(n_records, quick=args.quick)
    intensities = np.linspace(0.05, 0.5, n_intensities)
    f, a = grid(args, 24 // (4 if args.quick else 1), 8 // (4 if args.quick else 1))
    # each study at full size, or (warm-up) on the first two values of each axis
    studies = {
        "fragility": lambda store, n=None, **kw: sloshdyn.fragility_study(
            peers.fragility_tank(), records[:n], intensities[:n], store, **kw),
        "response map": lambda store, n=None, **kw: sloshdyn.response_map(
            FIG12, f[:n], a[:n], store, **kw)}

    def run(study, kind, workers, n=None):
        store = tempfile.mkdtemp(prefix="bench-kinds-")
        try:
            t = time.perf_counter()
            ds = studies[study](os.path.join(store, "s.zarr"), n, workers=workers,
                                worker_kind=kind, progress=False)
            return time.perf_counter() - t, ds
        finally:
            shutil.rmtree(store, ignore_errors=True)
    print(f"fragility: {n_records} records x {n_intensities} intensities; response map: "
          f"{f.size} x {a.size} points at Steady()\n")
    print("| study | round | worker kind | 1 worker [s] | 2 workers [s] | speed-up | "
          "identical | load |")
    print("|---|---|---|---|---|---|---|---|")
    for study in studies:
        for kind in ("threads", "processes"):            # warm-up: imports, first calls
            run(study, kind, 2, n=2)
        for round_ in range(args.repeats):
            for kind in ("processes", "threads"):
                load = os.getloadavg()[0]
                (t1, d1), (t2, d2) = run(study, kind, 1), run(study, kind, 2)
                same = all(np.array_equal(d1[v].values, d2[v].values, equal_nan=True)
                           for v in d1.data_vars)
                print(f"| {study} | {round_ + 1} | {kind} | {t1:.2f} | {t2:.2f} | "
                      f"{t1 / t2:.3f}x | {same} | {load:.2f} |", flush=True)
    print(f"\ndefault worker kind: {sloshdyn.studies.WORKER_KIND}; target >= 1.85x on 2 workers")


def section_map100(args):
    print("\n## A 100 x 100 response map on this machine (embedded cluster, defaults)\n")
    n = 10 if args.quick else 100
    f, a = np.linspace(0.49, 0.53, n), np.linspace(0.0002, 0.0015, n)
    store = tempfile.mkdtemp(prefix="bench-map100-")
    try:
        t = time.perf_counter()
        ds = sloshdyn.response_map(FIG12, f, a, os.path.join(store, "m.zarr"), progress=True)
        elapsed = time.perf_counter() - t
    finally:
        shutil.rmtree(store, ignore_errors=True)
    motions = {sloshdyn.simulation.MOTIONS.get(int(k), "failed"): int((ds.motion == k).sum())
               for k in np.unique(ds.motion.values)}
    cores = os.cpu_count() or 1
    work = ds.attrs["compute_seconds"]
    print(f"{n} x {n} = {n * n} points on {cores} cores: {elapsed:.0f} s "
          f"({elapsed / 60:.1f} min), {work:.0f} s of computing in the tasks; motions {motions}")
    per_task = sloshdyn.studies.auto_points_per_task(n * n, 64)
    print(f"projected on 64 workers: {work / 64:.0f} s if the work shared out perfectly, "
          f"{work / 64 / 0.79:.0f} s at the 79 % efficiency measured for 2 workers; bounded "
          f"below by the slowest task ({per_task} points per task on 64 workers; a "
          "quasi-periodic point integrates 20 000 periods, ~2.5 s)")


def section_cluster8(args):
    print("\n## An 8-worker local cluster (processes) on this 2-core machine\n")
    f, a = grid(args, 8, 2)
    steady = sloshdyn.Steady(max_transient_periods=2000)
    store = tempfile.mkdtemp(prefix="bench-cluster8-")
    try:
        t = time.perf_counter()
        ds = sloshdyn.response_map(FIG12, f, a, os.path.join(store, "c.zarr"), workers=8,
                                   worker_kind="processes", steady=steady, points_per_task=1,
                                   progress=False)
        elapsed = time.perf_counter() - t
    finally:
        shutil.rmtree(store, ignore_errors=True)
    expected = direct_loop(f, a, steady)
    same = all(float(ds.max_x1[i, j]) == expected[i][j].max_x1 for i in range(len(f))
               for j in range(len(a)))
    print(f"8 workers, {f.size * a.size} points, {elapsed:.1f} s with start-up: equals the "
          f"serial loop bit for bit: {same}")


SECTIONS = {"steady": section_steady, "sweep": section_sweep, "tasks": section_tasks,
            "workers": section_workers, "kinds": section_kinds, "map100": section_map100,
            "cluster8": section_cluster8}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--only", nargs="+", choices=list(SECTIONS))
    parser.add_argument("--map100", action="store_true", help="also the 100 x 100 map")
    args = parser.parse_args()
    if args.quick:
        args.repeats = 1
    chosen = args.only or [s for s in SECTIONS if s != "map100" or args.map100]
    print(f"# sloshdyn studies benchmark ({os.cpu_count()} cores, load "
          f"{os.getloadavg()[0]:.2f}; sloshdyn {sloshdyn.__version__})")
    for name in chosen:
        log(name)
        SECTIONS[name](args)


if __name__ == "__main__":
    main()
