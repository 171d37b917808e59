"""
The wave around the wall under two horizontal components
========================================================

The example input ``data/examples/tank_two_components.nml``: the tank of ``tank_seismic.nml``
(R = 5 m, 6 m of water, 1 m of freeboard) in the spatial model, under the project's synthetic
record along azimuth 30° and its companion ``synthetic_kt_y.AT2`` across it (both synthetic,
not recorded earthquakes), scaled by one factor, read by the executable's own reader and run
by ``sloshdyn.spatial.seismic_response_2d``: the numbers of ``sloshdyn
data/examples/tank_two_components.nml``. Drawn: the peak wave height at the wall over time at
each azimuth ψ (η_x cos ψ + η_y sin ψ, ``wave_height_at``), beside the codes' SRSS and 100/30
combinations of the two planar runs, one per component.
"""

import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import sloshdyn
from sloshdyn import spatial

# the repository's example inputs, found from this script's place (docs/...)
DATA = Path(sys.argv[0]).resolve().parents[2] / "data" / "examples"

inp = sloshdyn.read_namelist(DATA / "tank_two_components.nml")
both = spatial.seismic_response_2d(inp.tank, inp.ground_motion, inp.ground_motion_y,
                                   azimuth=inp.spatial["azimuth"],
                                   ellipticity=inp.spatial["ellipticity"],
                                   integration=inp.integration)
peaks = both.peaks
for key in ("wave_height", "wave_height_run_1", "wave_height_run_2", "wave_height_srss",
            "wave_height_100_30"):
    print(f"{key:20s} {peaks[key]:.4f} m")

psi = np.radians(np.arange(0.0, 360.5, 1.0))
rise = np.array([both.wave_height_at(a).max() for a in psi])       # [m], the crest
fig, ax = plt.subplots(figsize=(7, 3.8))
ax.plot(np.degrees(psi), rise, color="k", label="both components together (spatial model)")
ax.axhline(peaks["wave_height_srss"], ls="--", color="tab:blue", label="SRSS of the planar runs")
ax.axhline(peaks["wave_height_100_30"], ls="-.", color="tab:green",
           label="100/30 of the planar runs")
ax.axhspan(inp.tank.freeboard, 10 * inp.tank.freeboard, color="r", alpha=0.12, lw=0,
           label="above the roof (freeboard)")
azimuth = inp.spatial["azimuth"]
for a, name in ((azimuth, "record 1"), (azimuth + np.pi / 2, "record 2")):
    ax.axvline(np.degrees(a), color="0.6", lw=0.8)
    ax.annotate(name, (np.degrees(a), 0.02), xycoords=("data", "axes fraction"),
                rotation=90, fontsize=8, color="0.4", ha="right")
ax.set_xlim(0, 360)
ax.set_ylim(0, 1.3 * max(peaks["wave_height_srss"], inp.tank.freeboard))
ax.set_xticks(range(0, 361, 45))
ax.set_xlabel("azimuth on the wall ψ [°] (from the x axis)")
ax.set_ylabel("peak wave height\nat the wall [m]")
ax.legend(fontsize=8, loc="lower right")
fig.tight_layout()
