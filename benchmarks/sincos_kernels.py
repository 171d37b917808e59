"""Own sine and cosine kernels against libm (issue 43, 2026-12-03): benchmarks/sincos_kernels.f90
as on that day (-DFULL_REDUCTION) with the program sincos_bench.f90, built with gfortran four
ways (-O0; -O3 portable, i.e. SSE2; -O3 -mavx2 -mno-fma; -O3 -march=native), all with
-ffp-contract=off. For each build: whether its vectorised and scalar calls give the same
bits, and a fingerprint of its values on the test arguments (the same fingerprint for every
build = the same bits on every vector width); the worst error against mpmath at 40 digits in units in the last place; and the CPU time per (sine, cosine) pair of the
kernels and of libm's sin and cos in the same process, for 192 pendulum-sized angles per call and
for the three angles of one right-hand side (two small, one forcing phase). Prints the processor
model and the load. Builds that the processor cannot run (e.g. -mavx2 without AVX2) are reported
as such.

    python benchmarks/sincos_kernels.py               # about 30 s (mpmath on 100 000 arguments)
    python benchmarks/sincos_kernels.py --accuracy 20000
"""

from __future__ import annotations

import argparse
import hashlib
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from run import cpu_model                                  # noqa: E402

#: the kernels (their 2026-12-03 form: -DFULL_REDUCTION) and the program that checks and times them
SOURCES = [Path(__file__).resolve().parent / name for name in ("sincos_kernels.f90", "sincos_bench.f90")]
BUILDS = {"-O0": ["-O0"], "-O3 (portable: SSE2)": ["-O3"],
          "-O3 -mavx2 -mno-fma": ["-O3", "-mavx2", "-mno-fma"],
          "-O3 -march=native": ["-O3", "-march=native"]}


def test_arguments(n, rng):
    """n arguments: uniform on [-pi/4, pi/4], [-10, 10], [-2000, 2000] and up to the kernels'
    reduction limit 1.6e6, and next to multiples of pi/2 (where the reduction cancels most)."""
    k = np.arange(-n // 10, n // 10)
    return np.concatenate([rng.uniform(-np.pi / 4, np.pi / 4, n // 5),
                           rng.uniform(-10, 10, n // 5), rng.uniform(-2000, 2000, n // 5),
                           rng.uniform(-1.6e6, 1.6e6, n // 5),
                           k * (np.pi / 2) + rng.uniform(-1e-9, 1e-9, k.size),
                           [0.0, 1e-300, 2e6, -3e7, np.inf, np.nan]])


def worst_ulp(x, s, c):
    import mpmath
    mpmath.mp.dps = 40
    worst, where = 0.0, None
    for xi, si, ci in zip(x, s, c):
        if not np.isfinite(xi):
            continue
        xm = mpmath.mpf(float(xi))
        for value, exact in ((si, mpmath.sin(xm)), (ci, mpmath.cos(xm))):
            err = float(abs(mpmath.mpf(float(value)) - exact)
                        / mpmath.mpf(np.spacing(abs(float(exact)))))
            if err > worst:
                worst, where = err, float(xi)
    return worst, where


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--accuracy", type=int, default=100000, help="arguments checked by mpmath")
    args = ap.parse_args()
    x = test_arguments(args.accuracy, np.random.default_rng(43))
    print(f"# Own sine and cosine kernels against libm, {x.size} test arguments")
    print(f"Machine: {cpu_model()}, {os.cpu_count()} cores; load average "
          f"{os.getloadavg()[0]:.2f} at start")
    print("\n| build | vectorised = scalar | fingerprint | kernels, 192 per call | libm, 192 | "
          "kernels, 3 per call | kernels, 3 scalar calls | libm, 3 |")
    print("|---|---|---|---:|---:|---:|---:|---:|")
    values = None
    with tempfile.TemporaryDirectory() as tmp:
        data = Path(tmp) / "x.bin"
        with open(data, "wb") as f:
            np.array([x.size], np.int32).tofile(f)
            x.tofile(f)
        for name, flags in BUILDS.items():
            exe = Path(tmp) / "bench"
            subprocess.run(["gfortran", "-cpp", "-DFULL_REDUCTION", *flags, "-ffp-contract=off",
                            *map(str, SOURCES), "-o", str(exe)],
                           check=True, cwd=tmp)
            run = subprocess.run([str(exe), "values", str(data)], capture_output=True, text=True)
            if run.returncode != 0:
                print(f"| {name} | cannot run here ({run.stderr.strip()[:60]}) | | | | | | |")
                continue
            out = np.fromfile(str(data) + ".out")
            values = out
            timing = subprocess.run([str(exe), "time"], capture_output=True, text=True,
                                    check=True).stdout.split("\n")
            ns = [line.split(":")[1].strip() for line in timing if ":" in line]
            print(f"| {name} | {run.stdout.strip().split()[-1]} | "
                  f"{hashlib.sha1(out.tobytes()).hexdigest()[:12]} | " + " | ".join(ns) + " |")
    print("\n(ns of CPU time per sine-cosine pair)")
    s, c = values[:x.size], values[x.size:]
    worst, where = worst_ulp(x, s, c)
    print(f"Worst error against mpmath (40 digits): {worst:.3f} ulp, at x = {where!r}")
    print(f"Machine: {cpu_model()}, {os.cpu_count()} cores; load average "
          f"{os.getloadavg()[0]:.2f} at the end")


if __name__ == "__main__":
    main()
