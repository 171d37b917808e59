"""Accuracy of the Lyapunov spectrum's two averages (issue 42, item 4): the plain time average
of the QR method's log growths against the weighted Birkhoff average (Lyapunov(average=
'weighted'); Das, Saiki, Sander and Yorke, Nonlinearity 30 (2017) 4111), on the stable planar
orbit of tests/python/test_spatial_lyapunov.py, whose exponents are known exactly: log|mu|/T of
its four in-plane Floquet multipliers (the planar shooting's monodromy) and its four
out-of-plane ones. Each run gives both: the exponents (weighted) and the history's last column
(the plain running average of the same run). Prints the largest error over the eight exponents
for each transient and measured length, and the processor model.

    python benchmarks/lyapunov_average.py            # ~40 s on one core
"""

import math
import platform
import time

import numpy as np

import sloshdyn
from sloshdyn import Lyapunov, spatial

P = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=math.pi / 4, gamma=0.05,
                        A=0.05, rho=0.513)
INTEGRATION = sloshdyn.Integration(rtol=1e-11, atol=1e-13)
RUNS = ((3000, 250), (3000, 500), (3000, 1000), (1000, 1000))   # (transient, measured) periods


def processor():
    try:
        with open("/proc/cpuinfo") as info:
            return next(line.split(":", 1)[1].strip() for line in info
                        if line.startswith("model name"))
    except (OSError, StopIteration):
        return platform.processor() or "unknown"


def main():
    orbit = sloshdyn.periodic_orbit(P, sloshdyn.steady_state(P).y_end)
    nu = spatial.out_of_plane_multipliers(P, orbit.y0)
    period = 2 * math.pi / P.rho
    floquet = np.sort(np.log(np.abs(np.concatenate([orbit.multipliers, nu]))) / period)[::-1]
    y0 = np.concatenate([orbit.y0, np.zeros(4)])
    print("| transient periods | measured periods | weighted error | plain error | CPU s |")
    print("|---:|---:|---:|---:|---:|")
    for transient, measured in RUNS:
        start = time.process_time()
        spectrum = sloshdyn.lyapunov_spectrum(
            P, y0, spatial=True, integration=INTEGRATION,
            lyapunov=Lyapunov(transient_periods=transient, n_periods=measured,
                              renormalise_every=1, average="weighted"))
        cpu = time.process_time() - start
        weighted = np.max(np.abs(spectrum.exponents - floquet))
        plain = np.max(np.abs(np.sort(spectrum.history[:, -1])[::-1] - floquet))
        print(f"| {transient} | {measured} | {weighted:.1e} | {plain:.1e} | {cpu:.1f} |")
    print(f"\nprocessor: {processor()}")


if __name__ == "__main__":
    main()
