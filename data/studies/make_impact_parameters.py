"""Run the (beta, delta) study of the paper's continuation in A (issue 15; sloshdyn.studies.
impact_parameters) and write its summary, data/reference/impact_parameters.csv, which the
reproduce report draws (so the report needs no re-run). The Zarr store is resumable: rerun
after an interruption. Run from the repository root after a build:
    python data/studies/make_impact_parameters.py [workers]"""

import csv
import pathlib
import sys
import time

import numpy as np

from sloshdyn import figures, studies

HERE = pathlib.Path(__file__).parent
#: log grids, half a decade apart; the defaults beta = 10, delta = 0.1 lie on them
BETAS = np.logspace(-1, 3, 9)
DELTAS = np.logspace(-3, 1, 9)
#: (transient, measured) forcing periods of the Lyapunov exponent at A = 2, as `check` uses
LYAPUNOV_PERIODS = (100, 2000)
SUMMARY = HERE.parent / "reference" / "impact_parameters.csv"


def main(workers=2):
    p, values, steady = figures.continuation_path(quick=False)
    start = time.time()
    ds = studies.impact_parameters(p, BETAS, DELTAS, values, HERE / "impact_parameters.zarr",
                                   steady=steady, lyapunov_periods=LYAPUNOV_PERIODS,
                                   workers=workers)
    print(f"{ds.attrs['points_computed']} points computed in {time.time() - start:.0f} s "
          f"(tasks {ds.attrs['compute_seconds']:.0f} s summed over workers)")
    with open(SUMMARY, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["beta", "delta", "max_x1_A_0.00075", "max_x1_A_1.0475", "motion_A_1.0475",
                         "max_x1_A_2", "motion_A_2", "lyapunov_A_2", "fig15_holds",
                         "fig16_holds", "fig17_holds", "all_hold"])
        for b in ds.beta.values:
            for d in ds.delta.values:
                pt = ds.sel(beta=b, delta=d)
                x = [float(pt.max_x1.sel(A=A, method="nearest")) for A in (0.00075, 1.0475, 2.0)]
                m = [studies.MOTIONS.get(int(pt.motion.sel(A=A, method="nearest")), "failed")
                     for A in (1.0475, 2.0)]
                writer.writerow([repr(float(b)), repr(float(d)), x[0], x[1], m[0], x[2], m[1],
                                 float(pt.lyapunov)] + [int(pt[k]) for k in (
                                     "fig15_holds", "fig16_holds", "fig17_holds", "all_hold")])
    print(f"wrote {SUMMARY}; all three statements hold at {int(ds.all_hold.sum())} of "
          f"{ds.all_hold.size} points")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 2)
