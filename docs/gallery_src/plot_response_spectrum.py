"""
Response spectra of a record
============================

The pseudo-spectral acceleration and the spectral displacement of the example record
(``data/examples/records/synthetic_kt.AT2``, synthetic: not a recorded earthquake) at the
damping ratio of sloshing (0.5 %, the convective damping of the design codes) and at the 5 %
of structures, with the sloshing periods of three tanks of 6 m of water marked. The spectra are
computed by the core (the exact piecewise-linear recurrence of an oscillator under the sampled
record).
"""

import sys
from pathlib import Path

import numpy as np

import sloshdyn

# the repository's example inputs, found from this script's place (docs/...)
DATA = Path(sys.argv[0]).resolve().parents[2] / "data" / "examples"

quake = sloshdyn.GroundMotion.from_file(DATA / "records" / "synthetic_kt.AT2")   # in g
periods = np.geomspace(0.05, 10.0, 80)                                             # [s]
tanks = [sloshdyn.Tank(radius=R, liquid_depth=6.0, freeboard=1.0, liquid_density=1000,
                       tank_mass=5e4, support_frequency=2.0, support_damping=0.02)
         for R in (2.5, 5.0, 10.0)]
marks = [t.sloshing_period for t in tanks]
print("sloshing periods [s]:", np.round(marks, 3))
sloshdyn.plotting.response_spectrum(quake.response_spectrum(periods, damping=0.005), marks=marks)

# %%
# The damping ratio matters most near the record's dominant periods: at 0.5 % the
# pseudo-spectral acceleration is several times the 5 % value there.

import matplotlib.pyplot as plt

fig, ax = plt.subplots(figsize=(7, 3.4))
for damping, style in ((0.005, "-"), (0.05, "--")):
    s = quake.response_spectrum(periods, damping=damping)
    ax.plot(s.periods, s.psa / 9.80665, style, color="k", label=f"{100 * damping:g} % damping")
for T in marks:
    ax.axvline(T, ls=":", color="0.5", lw=0.8)
ax.set_xscale("log")
ax.set_xlabel("period T [s]")
ax.set_ylabel("pseudo-spectral\nacceleration [g]")
ax.legend(fontsize=8)
fig.tight_layout()
