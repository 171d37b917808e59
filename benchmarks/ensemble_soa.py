"""Issue 43 prototype: a member-fastest DOP853 ensemble with the project's own vectorised sine
and cosine (benchmarks/ensemble_soa.f90, standalone Fortran) against numbalsoda's dop853 looped.

Builds ensemble_soa.f90 with gfortran into a temporary directory (portable SSE2:
-cpp -O3 -ffp-contract=off -fstack-arrays; and, where the processor has AVX2, the same with
-mavx2 -mno-fma; and for comparison each without the kernels' small-argument path
(-DFULL_REDUCTION), and SSE2 without vectorisation), then on the 64 trajectories of benchmarks/ensemble.py (Fig 14 parameters,
the paper's y0 = (0.01, 0, 0.01, 0) and 63 uniform in +-0.02, seed 43; 100 forcing periods,
output at the end only) at rtol 1e-6, 1e-9, 1e-12 (atol = 1e-3 rtol) times, interleaved,
medians of --repeats rounds of CPU time:

* numbalsoda's dop853 called once per trajectory (peers.Numba.integrate), in this process
  (time.process_time);
* the prototype with K = 64 (one block of 64 members) and with K = 1 (64 blocks of one
  member: its scalar path), each build; the CPU time is the prototype's own cpu_time around
  its integration loop (reading and printing excluded), of the last of --inner runs in the
  child (the first is a warm-up).

Checks (asserted): K = 64 gives the same bits per trajectory as K = 1, in every build, and the
builds give the same bits; the end states agree with numbalsoda's to --agree * rtol (largest
|difference| over the 4 components relative to the largest |component|, per trajectory) and
with scipy's DOP853 (solve_ivp, its own step control, on --scipy trajectories) to
--agree-scipy * rtol; the prototype's evaluation counts are numbalsoda's within 1 %.

    python benchmarks/ensemble_soa.py                 # ~1 min here
    python benchmarks/ensemble_soa.py --repeats 5 --keep /tmp/soa   # keep the binaries
"""

from __future__ import annotations

import argparse
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from ensemble import problems                                 # noqa: E402
from peers import Numba, fig14_parameters, python_rhs         # noqa: E402
from run import cpu_model                                     # noqa: E402

SOURCES = [HERE / "sincos_kernels.f90", HERE / "ensemble_soa.f90"]
BASE_FLAGS = ["-cpp", "-O3", "-ffp-contract=off", "-fstack-arrays"]
AVX2 = ["-mavx2", "-mno-fma"]
#: name: (extra flags, also timed with K = 1). FULL_REDUCTION: the kernels without the
#: small-argument path (as in sincos_kernels.f90); no SIMD: member-fastest without vectors.
BUILDS = {"SSE2": ([], True),
          "SSE2 full reduction": (["-DFULL_REDUCTION"], False),
          "SSE2 no SIMD": (["-fno-tree-vectorize", "-fno-tree-slp-vectorize"], False),
          "AVX2": (AVX2, True),
          "AVX2 full reduction": (AVX2 + ["-DFULL_REDUCTION"], False)}


def has_avx2():
    try:
        return " avx2" in Path("/proc/cpuinfo").read_text()
    except OSError:
        return False


def build(directory):
    """{build name: (path of the executable, command line)}."""
    exes = {}
    for name, (extra, _) in BUILDS.items():
        if "-mavx2" in extra and not has_avx2():
            continue
        exe = Path(directory) / f"ensemble_soa_{name.lower().replace(' ', '_')}"
        cmd = ["gfortran", *BASE_FLAGS, *extra, "-J", str(exe.parent), "-o", str(exe), *map(str, SOURCES)]
        subprocess.run(cmd, check=True, cwd=directory)
        exes[name] = (exe, " ".join(["gfortran", *BASE_FLAGS, *extra, "-o", exe.name,
                                     "benchmarks/sincos_kernels.f90", "benchmarks/ensemble_soa.f90"]))
    return exes


def run_proto(exe, d, states, t_end, rtol, atol, block, inner):
    """One child run: (end-state bits uint64 (K, 4), end states (K, 4), counts dict, cpu s)."""
    lines = [f"{len(states)} {block} {inner}", f"{rtol!r} {atol!r} {t_end!r}",
             " ".join(repr(float(x)) for x in d[:11])]
    lines += [" ".join(repr(float(v)) for v in s) for s in states]
    out = subprocess.run([str(exe)], input="\n".join(lines) + "\n", capture_output=True,
                         text=True, check=True).stdout.splitlines()
    if any(line.startswith("failed") for line in out):
        raise RuntimeError(f"{exe.name}: {out[0]}")
    rows = [line.split() for line in out if line.startswith("y ")]
    bits = np.array([[int(v, 16) for v in r[1:5]] for r in rows], dtype=np.uint64)
    y = bits.view(np.float64)
    counts = {"nfev": sum(int(r[9]) for r in rows), "accepted": sum(int(r[10]) for r in rows),
              "rejected": sum(int(r[11]) for r in rows)}
    for line in out:
        if line.startswith("evaluations_done"):
            counts["done"] = int(line.split()[1])
        if line.startswith("cpu"):
            cpu = float(line.split()[-1])
    return bits, y, counts, cpu


def rel_diff(a, b):
    """Per trajectory: max |a - b| over the components / max |b|."""
    return np.max(np.abs(a - b), axis=1) / np.max(np.abs(b), axis=1)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--periods", type=float, default=100.0)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--inner", type=int, default=2, help="runs per child (first = warm-up)")
    ap.add_argument("--scipy", type=int, default=8, help="trajectories checked against scipy")
    ap.add_argument("--agree", type=float, default=1e3)
    ap.add_argument("--agree-scipy", type=float, default=1e4)
    ap.add_argument("--keep", help="build into this directory and keep it")
    args = ap.parse_args()

    nb = Numba()
    if not nb.available:
        sys.exit(f"numbalsoda peer missing: {nb.reason}")
    p = fig14_parameters()
    _, params, states, t_end = problems(args.periods)[0]      # Fig 14, 64 initial states
    assert all(q == p for q in params)
    n = len(states)
    d = Numba.data(p)
    directory = args.keep or tempfile.mkdtemp(prefix="ensemble_soa_")
    Path(directory).mkdir(parents=True, exist_ok=True)
    exes = build(directory)
    gfortran = subprocess.run(["gfortran", "--version"], capture_output=True,
                              text=True).stdout.splitlines()[0]
    print(f"# Member-fastest DOP853 prototype vs numbalsoda dop853, {n} trajectories of "
          f"{args.periods:g} forcing periods, median of {args.repeats} interleaved rounds "
          "(CPU time)")
    print(f"Machine: {cpu_model()}, {os.cpu_count()} cores; load average "
          f"{' '.join(f'{x:.2f}' for x in os.getloadavg())} at start; {gfortran}; "
          f"{nb.versions}")
    for name, (_, cmd) in exes.items():
        print(f"build {name}: {cmd}")
    print()
    table, checks = [], []
    for rtol in (1e-6, 1e-9, 1e-12):
        atol = 1e-3 * rtol
        solvers = {"numbalsoda dop853, loop of 64": None}
        for name in exes:
            solvers[f"prototype {name}, K = 64"] = (name, n)
            if BUILDS[name][1]:
                solvers[f"prototype {name}, K = 1 x 64"] = (name, 1)
        ref = [nb.integrate(p, y, t_end, rtol, atol, count=True) for y in states]  # warm-up
        y_nb = np.array([r[0] for r in ref])
        nfev_nb = sum(r[1] for r in ref)
        cpu = {s: [] for s in solvers}
        results = {}
        for _ in range(args.repeats):
            for s, how in solvers.items():
                if how is None:
                    c0 = time.process_time()
                    for y in states:
                        nb.integrate(p, y, t_end, rtol, atol)
                    cpu[s].append(time.process_time() - c0)
                else:
                    name, block = how
                    out = run_proto(exes[name][0], d, states, t_end, rtol, atol, block,
                                    args.inner)
                    cpu[s].append(out[3])
                    results[s] = out
        med = {s: float(np.median(v)) for s, v in cpu.items()}
        base = med["numbalsoda dop853, loop of 64"]
        for s in solvers:
            counts = results[s][2] if s in results else {"nfev": nfev_nb}
            table.append((rtol, s, med[s], n / med[s], base / med[s], counts, cpu[s]))

        # --- checks
        first = next(iter(results.values()))
        for s, out in results.items():
            assert np.array_equal(out[0], first[0]), f"rtol {rtol:g}: {s} differs in bits"
        diff_nb = rel_diff(first[1], y_nb)
        sc = []
        if args.scipy:
            from scipy.integrate import solve_ivp
            rhs = python_rhs(p)
            for i in range(args.scipy):
                sol = solve_ivp(rhs, (0.0, t_end), np.array(states[i], dtype=np.float64),
                                method="DOP853", rtol=rtol, atol=atol, t_eval=[t_end])
                sc.append(sol.y[:, -1])
            diff_sc = rel_diff(first[1][:args.scipy], np.array(sc))
            diff_nb_sc = rel_diff(y_nb[:args.scipy], np.array(sc))
        c = first[2]
        checks.append((rtol, diff_nb, diff_sc if sc else None, diff_nb_sc if sc else None,
                       c, nfev_nb))
        assert diff_nb.max() < args.agree * rtol, (rtol, diff_nb.max())
        if sc:
            assert diff_sc.max() < args.agree_scipy * rtol, (rtol, diff_sc.max())
        assert abs(c["nfev"] - nfev_nb) < 0.01 * nfev_nb, (c["nfev"], nfev_nb)

    print("| rtol | solver | CPU s | trajectories/s (CPU) | vs numbalsoda (CPU) | "
          "rhs evaluations | CPU s of the rounds |")
    print("|---:|---|---:|---:|---:|---:|---|")
    for rtol, s, m, tps, ratio, counts, rounds in table:
        print(f"| {rtol:g} | {s} | {m:.4f} | {tps:.0f} | {ratio:.2f}x | {counts['nfev']} | "
              f"{' '.join(f'{x:.4f}' for x in rounds)} |")
    print()
    print("Checks (all builds and K = 64 / K = 1 gave the same bits per trajectory, asserted):")
    print("| rtol | max rel. diff vs numbalsoda | median | vs scipy DOP853 (first "
          f"{args.scipy}) | numbalsoda vs scipy | rhs evaluations: prototype (dop853.f count) "
          "/ done incl. k13 of rejected trials / numbalsoda | accepted / rejected steps |")
    print("|---:|---:|---:|---:|---:|---|---|")
    for rtol, dnb, dsc, dnbsc, c, nfev_nb in checks:
        vs_sc = (f"{dsc.max():.2e} ({dsc.max() / rtol:.1f} rtol) | {dnbsc.max():.2e}"
                 if dsc is not None else "- | -")
        print(f"| {rtol:g} | {dnb.max():.2e} ({dnb.max() / rtol:.1f} rtol) | "
              f"{np.median(dnb):.2e} | {vs_sc} | "
              f"{c['nfev']} / {c['done']} / {nfev_nb} | "
              f"{c['accepted']} / {c['rejected']} |")
    print()
    print(f"load average {' '.join(f'{x:.2f}' for x in os.getloadavg())} at the end")
    if not args.keep:
        shutil.rmtree(directory, ignore_errors=True)


if __name__ == "__main__":
    main()
