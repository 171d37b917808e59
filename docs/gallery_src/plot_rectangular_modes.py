"""
Modal wave heights of a rectangular tank
========================================

The basin of ``data/examples/tank_rectangular_seismic.nml`` (12 m along the motion, 6 m wide,
4 m of water, three sloshing modes) under the project's synthetic record, scaled to
Sa = 0.15 g at its first sloshing period, read by the executable's own reader. Modes 2 and 3
are linear and added to mode 1's wave after the model's run, so the runs with ``modes`` = 1, 2
and 3 differ by exactly one mode each: their differences are the modal waves at the wall.
Below them, each mode's peak beside its spectral estimate η_n = w_n S_a(T_n, ζ)/g with
w_n = 4L/((2n − 1)² π²) (:doc:`../model`, "Rectangular tanks and higher sloshing modes"),
whose root sum of squares and absolute sum are the design-code table's ``modes SRSS`` and
``modes ABS`` rows.
"""

import dataclasses
import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import sloshdyn

# the repository's example inputs, found from this script's place (docs/...)
DATA = Path(sys.argv[0]).resolve().parents[2] / "data" / "examples"

inp = sloshdyn.read_namelist(DATA / "tank_rectangular_seismic.nml")
basin, quake = inp.tank, inp.ground_motion
runs = [sloshdyn.seismic_response(dataclasses.replace(basin, modes=n), quake)
        for n in range(1, basin.modes + 1)]
waves = [runs[0].wave_height] + [b.wave_height - a.wave_height for a, b in zip(runs, runs[1:])]

n = np.arange(1, basin.modes + 1)
w = 4 * basin.length / ((2 * n - 1) ** 2 * np.pi ** 2)                   # [m]
psa = quake.response_spectrum(basin.sloshing_periods, damping=basin.sloshing_damping).psa
spectral = w * psa / basin.gravity                                        # [m]
codes = basin.design_codes(quake)
print(f"SRSS {np.sqrt(np.sum(spectral ** 2)):.4f} m"
      f" (table: {codes.value('modes SRSS', 'wave_height'):.4f} m),"
      f" ABS {np.sum(spectral):.4f} m (table: {codes.value('modes ABS', 'wave_height'):.4f} m),"
      f" time history of the sum {runs[-1].peaks['wave_height'][0]:.4f} m")

fig, axes = plt.subplots(2, 1, figsize=(7, 6), gridspec_kw={"height_ratios": [3, 2]})
t = runs[-1].t
for k, wave in enumerate(waves):
    axes[0].plot(t, wave, lw=0.8, label=f"mode {k + 1}, T = {basin.sloshing_periods[k]:.2f} s")
axes[0].set_xlim(0, 35)
axes[0].set_xlabel("time t [s]")
axes[0].set_ylabel("modal wave height\nat the wall [m]")
axes[0].legend(fontsize=8, loc="upper left")
peaks = [np.abs(wave).max() for wave in waves]
axes[1].bar(n - 0.2, peaks, width=0.4, color="0.3", label="time history, peak")
axes[1].bar(n + 0.2, spectral, width=0.4, color="tab:blue",
            label=r"spectral: $w_n S_a(T_n)/g$")
axes[1].set_xticks(n, [f"mode {k}" for k in n])
axes[1].set_ylabel("peak wave height [m]")
axes[1].legend(fontsize=8)
fig.tight_layout()
