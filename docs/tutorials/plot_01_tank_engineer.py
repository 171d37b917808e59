"""
The tank engineer's tutorial
============================

A steel tank of water on a flexible support, an earthquake record, and the questions asked of
them in design: how high does the wave rise, does it reach the roof, what base shear and
overturning moment does the liquid put on the tank, how do these compare with what the design
codes give, and how likely is a roof impact as the shaking grows. Everything is in SI units;
the relations (tank to pendulum, loads back to SI) are in :doc:`../model`, the same objects as
namelist groups (``&tank``, ``&ground_motion``, ``kind = 'seismic'``) in :doc:`../namelist`.

The script runs as it is (``python docs/tutorials/plot_01_tank_engineer.py``) and needs the
``plot`` and ``studies`` extras.
"""

# %%
# The tank
# --------
# ``sloshdyn.Tank`` has the fields of ``&tank``: a cylinder of radius R = 5 m holding
# h = 6 m of water under a roof 1 m above the still surface, a 50 t shell, on supports whose
# first mode is at 2 Hz with 2 % damping. From these the core computes the equivalent pendulum
# of the first sloshing mode (Abramson's parameters, eq (2)-(3) of the paper) and the
# convective and impulsive masses the codes use.

import sys
from pathlib import Path

import numpy as np

import sloshdyn

# the repository's example inputs, found from this script's place (docs/...)
DATA = Path(sys.argv[0]).resolve().parents[2] / "data" / "examples"

tank = sloshdyn.Tank(radius=5.0, liquid_depth=6.0, freeboard=1.0, liquid_density=1000,
                     tank_mass=5e4, support_frequency=2.0, support_damping=0.02)
print(f"sloshing period   {tank.sloshing_period:.3f} s")
print(f"convective mass   {tank.convective_mass / 1e3:.1f} t at {tank.convective_height:.2f} m")
print(f"impulsive mass    {tank.impulsive_mass / 1e3:.1f} t at {tank.impulsive_height:.2f} m")
print(f"wall angle theta0 {tank.theta0:.3f} rad (where the pendulum meets the roof)")

# %%
# The record and its response spectrum
# ------------------------------------
# ``GroundMotion.from_file`` reads PEER ``.AT2`` files and two-column (time, acceleration)
# files, in g unless told. The record here is the project's synthetic example (Kanai-Tajimi
# noise, *not* a recorded earthquake, ``data/examples/records/make_synthetic_record.py``), 30 s
# at 0.01 s, peak 0.30 g. Sloshing responds at the long convective period with about 0.5 %
# damping (the value the design codes use for sloshing, ``sloshdyn.ground.CONVECTIVE_DAMPING``),
# so that is where the spectrum matters; here the record is scaled so that its
# pseudo-spectral acceleration at the sloshing period is 0.2 g.

quake = sloshdyn.GroundMotion.from_file(DATA / "records" / "synthetic_kt.AT2")
quake = quake.scaled(sa=0.2, period=tank.sloshing_period, damping=0.005, units="g")
print(quake)
periods = np.geomspace(0.05, 8.0, 60)
spectrum = quake.response_spectrum(periods, damping=0.005)
sloshdyn.plotting.response_spectrum(spectrum, marks=[tank.sloshing_period])

# %%
# The response to the record
# --------------------------
# ``seismic_response`` integrates the full nonlinear model from rest to the end of the record
# plus five sloshing periods and returns every load as an SI time history, with its peak and
# the time of the peak. The wave height is measured at the wall; the roof is reached when the
# pendulum reaches theta0.

r = sloshdyn.seismic_response(tank, quake)
for load, unit, factor in [("wave_height", "m", 1), ("base_shear", "kN", 1e-3),
                           ("overturning_moment", "kN m", 1e-3)]:
    peak, when = r.peaks[load]
    print(f"{load:20s} {peak * factor:10.4g} {unit:5s} at t = {when:.3f} s")
print("roof reached:", r.roof_reached)
fig = sloshdyn.plotting.seismic(r)

# %%
# The design-code table
# ---------------------
# ``Tank.design_codes`` puts sloshdyn's sloshing parameters beside those of API 650 Annex E,
# EN 1998-4 (EC8-4) Annex A and ACI 350.3, each code's difference from sloshdyn in %. With a
# ground motion, the wave heights come from its pseudo-spectral acceleration at the
# convective period (the codes' spectral formulas), so the last row is the codes' estimate of
# the peak wave for this record, to compare with the time-history peak above.

codes = tank.design_codes(quake)
print(codes)
print(f"time history: {r.peaks['wave_height'][0]:.3f} m;"
      f" EC8-4 spectral estimate: {codes.value('EC8-4', 'wave_height'):.3f} m")

# %%
# The same with harmonic shaking
# ------------------------------
# A sweep of harmonic ground motion of 0.02 g peak acceleration over frequency, each point its
# steady state, the sweep carrying the state from one frequency to the next, first up, then
# down. The cubic terms of the model alone would soften the sloshing (c11 < 0 for this tank,
# ``sloshdyn.modal_coefficients(tank.parameters())``), but the smooth wall of eq (4), whose
# moment grows as x1^11 (n = 6, β = 10), stiffens it as the wave nears the roof: the
# resonance bends to higher frequencies. Going up, the large wave persists far beyond the
# linear sloshing frequency and then drops; going down, the small wave persists until it
# jumps up. Between the two jumps both motions exist (hysteresis).

import matplotlib.pyplot as plt

quick = sloshdyn.Steady(transient_periods=100, settle_tol=0, window_periods=20)
frequencies = sloshdyn.sweep_values(0.24, 0.56, 33, "both")     # [Hz], up then down
h = sloshdyn.harmonic_sweep(tank, 0.02, frequencies, units="g", steady=quick)
turn = int(np.argmax(h.frequency))
fig, ax = plt.subplots(figsize=(7, 3.6))
ax.plot(h.frequency[:turn + 1], h.wave_height[:turn + 1], "o-", ms=3, color="k",
        label="frequency up")
ax.plot(h.frequency[turn:], h.wave_height[turn:], "s--", ms=3, mfc="none", color="b",
        label="frequency down")
ax.axhline(tank.freeboard, ls="--", color="r", lw=0.8, label="roof (freeboard)")
ax.axvline(1 / tank.sloshing_period, ls=":", color="0.5", lw=0.8, label="sloshing frequency")
ax.set_xlabel("ground motion frequency [Hz]")
ax.set_ylabel("largest wave height\nat the wall [m]")
ax.legend(fontsize=8)
fig.tight_layout()

# %%
# Fragility: how likely is a roof impact?
# ---------------------------------------
# A fragility study (incremental dynamic analysis) scales every record of a suite to a series
# of intensities and runs ``seismic_response`` for each, on Dask (here two threads of this
# process). The suite below is synthetic too: six records of filtered noise with ground
# frequencies from 0.8 to 5 Hz and strong phases of 5 to 14 s.
#
# The intensity measure matters. Scaled to the spectral acceleration at the sloshing period,
# the records hardly differ: sloshing is a nearly linear oscillator at that period, so Sa(T_c)
# fixes the wave, every record reaches the roof at the same intensity and the runs separate
# perfectly (no lognormal fit exists; the study says so in its attributes). Scaled to the
# spectral acceleration at 0.5 s with 5 % damping (a short-period measure, as for the
# impulsive mode), the records' different frequency contents spread the intensity at which
# the roof is reached, and the lognormal fit gives a median and a dispersion.

import tempfile

rng = np.random.default_rng(20261125)
dt = 0.01
t = np.arange(0.0, 30.0, dt)
omega = 2 * np.pi * np.linspace(0.1, 10.0, 300)           # [rad/s]
records = []
for f_ground, strong in zip([0.8, 1.2, 1.8, 2.5, 3.5, 5.0], [6, 14, 8, 12, 5, 10]):
    wg, zg = 2 * np.pi * f_ground, 0.6                     # Kanai-Tajimi soil filter
    psd = (wg**4 + (2 * zg * wg * omega) ** 2) / ((wg**2 - omega**2) ** 2
                                                   + (2 * zg * wg * omega) ** 2)
    phases = rng.uniform(0, 2 * np.pi, omega.size)
    a = (np.sqrt(psd) * np.cos(np.outer(t, omega) + phases)).sum(axis=1)
    envelope = np.where(t < 2, (t / 2) ** 2, np.where(t < strong, 1.0, np.exp(-0.5 * (t - strong))))
    a *= envelope
    records.append(sloshdyn.GroundMotion(dt=dt, acceleration=0.2 * a / np.abs(a).max(), units="g"))

engine = dict(worker_kind="threads", workers=2, progress=False)
with tempfile.TemporaryDirectory() as folder:
    at_tc = sloshdyn.fragility_study(tank, records, [0.15, 0.2, 0.25, 0.3, 0.35],
                                     store=f"{folder}/sa_tc.zarr", **engine)
    print("Sa(T_c):", at_tc.attrs["fragility_fit"])
    print(at_tc.roof_impact.values)

    intensities = np.geomspace(0.3, 3.0, 9)
    ds = sloshdyn.fragility_study(tank, records, intensities, period=0.5, damping=0.05,
                                  store=f"{folder}/sa_05.zarr", **engine)
    print(ds.roof_impact.values)

# %%
# The fit is stored with the runs (``fragility_median``, ``fragility_dispersion`` and their
# standard errors); ``fit_fragility`` computes it from any list of runs, and
# ``sloshdyn.plotting.fragility`` draws it with the runs.

x = np.broadcast_to(ds.intensity.values, ds.roof_impact.shape).ravel()
failed = ds.roof_impact.values.ravel()
fit = sloshdyn.fit_fragility(x, failed)
print(f"median Sa(0.5 s) = {fit.median:.3g} g (standard error {fit.median_se:.2g} g),"
      f" dispersion {fit.beta:.3f}")
fig = sloshdyn.plotting.fragility(fit, x, failed, units="g",
                                  label="pseudo-spectral acceleration Sa(0.5 s, 5 %)")
