"""
The tank engineer's tutorial, continued: modes, roofs, two components
=====================================================================

Three questions the first tutorial left open. A rectangular basin: how much do its higher
sloshing modes add to the wave, and how do the design codes combine them? A tank whose wave
does reach the roof: what does a cone or dome roof carry, and can the numbers be trusted? An
earthquake in two horizontal components: where on the wall is the wave highest, and how do the
codes' SRSS and 100/30 combinations compare with the two components run together? The relations
are in :doc:`../model` ("Rectangular tanks and higher sloshing modes", "Roof loads", "Spatial
model and swirl"); the namelist forms in :doc:`../namelist`.

The script runs as it is (``python docs/tutorials/plot_03_tank_modes_roofs_two_components.py``)
and needs the ``plot`` extra.
"""

# %%
# A rectangular basin with three sloshing modes
# ---------------------------------------------
# The tank of ``data/examples/tank_rectangular_seismic.nml``: 12 m long in the direction of
# the ground motion, 6 m wide, 4 m of water and 1 m of freeboard, on a stiff foundation.
# ``modes=3`` takes the first three antisymmetric sloshing modes (k_n = (2n − 1)π/L, Abramson,
# NASA SP-106, ch. 2 and 6); mode 1 is the model's nonlinear pendulum, modes 2 and 3 are linear
# oscillators driven by the tank's motion. ``sloshing_periods``, ``convective_masses`` and
# ``convective_heights`` hold one value per mode.

import dataclasses
import sys
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import sloshdyn
from sloshdyn import spatial

# the repository's example inputs, found from this script's place (docs/...)
DATA = Path(sys.argv[0]).resolve().parents[2] / "data" / "examples"

basin = sloshdyn.Tank(shape="rectangular", length=12.0, width=6.0, liquid_depth=4.0,
                      freeboard=1.0, liquid_density=1000, tank_mass=3e5,
                      support_frequency=8.0, support_damping=0.05, modes=3)
liquid = 12.0 * 6.0 * 4.0 * 1000                     # m_F [kg]
print("mode  period [s]  convective mass [t]  share of the liquid  height [m]")
for n, (T, m, h) in enumerate(zip(basin.sloshing_periods, basin.convective_masses,
                                  basin.convective_heights), start=1):
    print(f"{n:4d}  {T:10.3f}  {m / 1e3:19.1f}  {100 * m / liquid:18.1f} %  {h:10.3f}")
print(f"impulsive (rigid) mass {basin.impulsive_mass / 1e3:.1f} t"
      f" at {basin.impulsive_height:.3f} m")

# %%
# The record is the project's synthetic example (Kanai-Tajimi noise, *not* a recorded
# earthquake), scaled so that its pseudo-spectral acceleration at the first sloshing period is
# 0.15 g at 0.5 % damping, as the namelist does. ``seismic_response`` adds the linear modes 2
# and 3 to the wave height at the wall, the base shear and the overturning moment of mode 1.

record = sloshdyn.GroundMotion.from_file(DATA / "records" / "synthetic_kt.AT2")
quake = record.scaled(sa=0.15, period=basin.sloshing_period, units="g")
r = sloshdyn.seismic_response(basin, quake)
print(r)

# %%
# The summed wave and what the higher modes add: the same basin with ``modes=1``
# (``dataclasses.replace``) is the model's pendulum alone.

one = sloshdyn.seismic_response(dataclasses.replace(basin, modes=1), quake)
print(f"peak wave at the wall: mode 1 alone {one.peaks['wave_height'][0]:.4f} m,"
      f" modes 1-3 summed {r.peaks['wave_height'][0]:.4f} m")
fig, ax = plt.subplots(figsize=(7, 3.4))
ax.plot(r.t, r.wave_height, lw=0.8, color="k", label="modes 1-3 summed")
ax.plot(one.t, one.wave_height, lw=0.8, color="tab:orange", label="mode 1 alone")
ax.axhline(basin.freeboard, ls="--", color="r", lw=0.8, label="roof (freeboard)")
ax.set_xlim(5, 30)
ax.set_ylim(-0.9, 1.35)
ax.set_xlabel("time t [s]")
ax.set_ylabel("wave height\nat the wall [m]")
ax.legend(fontsize=8, loc="upper center", ncol=3)
fig.tight_layout()

# %%
# The design-code table of a tank with several modes has two more rows, sloshdyn's sums over
# the modes: ``modes SRSS`` (each mode's spectral wave combined as the root of the sum of
# squares, the usual rule for well-separated modes) and ``modes ABS`` (the absolute sum, an
# upper bound). API 650 covers cylinders only; ACI 350.3's rectangular wave is (L/2) S_a/g.
# For this record the time history's summed wave lies between the SRSS and the ABS estimates.

codes = basin.design_codes(quake)
print(codes)
for source in ("sloshdyn", "modes SRSS", "modes ABS", "ACI 350.3"):
    print(f"{source:10s} wave height {codes.value(source, 'wave_height'):.4f} m")
print(f"time history (modes summed) {r.peaks['wave_height'][0]:.4f} m")

# %%
# Roof loads: cone and dome roofs
# -------------------------------
# The cylinder of the first tutorial (R = 5 m, h = 6 m, 1 m of freeboard) under the same
# record at twice the intensity (Sa = 0.4 g at its sloshing period): the free wave (the wave of
# the tank without a roof) rises past the freeboard. ``roof_slope`` [degrees] makes the roof a
# cone, ``roof_radius`` [m] a dome, neither a flat roof. From the free wave's peak the core
# computes the roof's loads by cutting the wave at the roof (sloshdyn's own derivation of the
# ASCE 7 / API 650 provisions, :doc:`../model` "Roof loads"): the equivalent hydrostatic head
# at the wall, the uplift force on the roof and the part of the convective mass the roof
# confines (to be added to the impulsive mass).

base = dict(radius=5.0, liquid_depth=6.0, freeboard=1.0, liquid_density=1000, tank_mass=5e4,
            support_frequency=2.0, support_damping=0.02)
roofs = {"flat": sloshdyn.Tank(**base),
         "cone 10 deg": sloshdyn.Tank(**base, roof_slope=10.0),
         "dome R_d = 10 m": sloshdyn.Tank(**base, roof_radius=10.0)}
strong = record.scaled(sa=0.4, period=roofs["flat"].sloshing_period, units="g")
print("roof             free wave [m]  head [m]  uplift [kN]  confined convective mass [t]")
for name, tank in roofs.items():
    peaks = sloshdyn.seismic_response(tank, strong).peak_table
    print(f"{name:16s} {peaks['free_wave_height']:13.3f}  {peaks['roof_head']:8.3f}"
          f"  {peaks['roof_uplift_force'] / 1e3:11.2f}"
          f"  {peaks['confined_convective_mass'] / 1e3:28.2f}")

# %%
# What the run rests on. ``peak_table`` also gives the record's ``scale_factor`` and its
# pseudo-spectral acceleration at the sloshing period, as run (both front doors write them to
# ``run_info.csv`` with the record's name and the scaling in words). The loads are the tank's
# without contact below the roof and the restricted-sloshing method's above it: the confined
# convective mass moves with the tank from the first contact on, and no load depends on the
# paper's roof/wall stiffness β and damping δ of eq (4)-(5). ``roof_contact="impact"`` adds the
# paper's impact model beside the run, for its impact force alone; ``beta_sensitive`` then says
# whether that model depends on β and δ.

r = sloshdyn.seismic_response(roofs["cone 10 deg"], strong)
print(f"record {strong.name}, {strong.scaling}")
print(f"scale factor {r.peak_table['scale_factor']:.4f},"
      f" Sa(T_c) = {r.peak_table['sa_sloshing_period'] / 9.80665:.3f} g,"
      f" PGA {r.peaks['ground_acceleration'][0] / 9.80665:.3f} g")
print("roof reached:", r.roof_reached, f"({r.roof_impacts} impacts of the free wave)")
print(f"peak base shear {r.peaks['base_shear'][0] / 1e6:.4g} MN, confined convective mass "
      f"{r.peak_table['confined_convective_mass'] / 1e3:.4g} t")
impact = sloshdyn.seismic_response(dataclasses.replace(roofs["cone 10 deg"],
                                                       roof_contact="impact"), strong)
print(f"the paper's impact model: impact force {impact.peaks['impact_force'][0] / 1e6:.4g} MN,"
      f" beta_sensitive: {impact.beta_sensitive}; base shear unchanged: "
      f"{impact.peaks['base_shear'][0] == r.peaks['base_shear'][0]}")
for warning in impact.warnings:
    print("warning:", warning)

# %%
# Two horizontal components
# -------------------------
# The spatial model (the rods tilt in x and y, the sloshing mass is a spherical pendulum) under
# the example record along azimuth 30 degrees and its companion
# ``data/examples/records/synthetic_kt_y.AT2`` (the same synthetic process, another seed)
# across it, both scaled by the one factor that brings the first to Sa = 0.2 g (FEMA P695
# scales a pair as one), as ``data/examples/tank_two_components.nml`` does. The wave at the
# wall at azimuth ψ is η_x cos ψ + η_y sin ψ (``wave_height_at``); its peak over time, against
# ψ, shows where on the wall the wave is highest.

tank = roofs["flat"]
factor = record.scaled(sa=0.2, period=tank.sloshing_period, units="g").scale_factor
companion = sloshdyn.GroundMotion.from_file(DATA / "records" / "synthetic_kt_y.AT2")
both = spatial.seismic_response_2d(tank, record.scaled(factor), companion.scaled(factor),
                                   azimuth=np.radians(30))
peaks = both.peaks
print(f"largest wave {peaks['wave_height']:.3f} m at azimuth"
      f" {np.degrees(peaks['wave_azimuth']):.1f} deg, t = {peaks['wave_time']:.2f} s")
print(f"planar runs: {peaks['wave_height_run_1']:.3f} m and {peaks['wave_height_run_2']:.3f} m;"
      f" SRSS {peaks['wave_height_srss']:.3f} m, 100/30 {peaks['wave_height_100_30']:.3f} m")

# Drawn as a plan of the tank: the crest's peak height at each point of the wall is the
# distance from the centre; the circles are the codes' combinations and the roof (the gallery
# example :doc:`../auto_gallery/plot_two_components` draws the same against ψ).

azimuths = np.radians(np.arange(0, 361, 2))
rise = np.array([both.wave_height_at(a).max() for a in azimuths])
circle = np.linspace(0, 2 * np.pi, 181)
fig, ax = plt.subplots(figsize=(8, 5), subplot_kw={"projection": "polar"})
ax.plot(azimuths, rise, color="k", lw=1.5, label="both components, spatial model")
for value, style, colour, label in (
        (peaks["wave_height_srss"], "--", "tab:blue", "SRSS of the planar runs"),
        (peaks["wave_height_100_30"], "-.", "tab:green", "100/30 of the planar runs"),
        (tank.freeboard, ":", "r", "roof (freeboard)")):
    ax.plot(circle, np.full_like(circle, value), style, color=colour, lw=1, label=label)
for direction, name in ((np.radians(30), "record 1"), (np.radians(120), "record 2")):
    ax.annotate(name, (direction, 0.88), ha="center", fontsize=8, color="0.4")
    ax.plot([direction, direction], [0, 0.83], color="0.6", lw=0.8)
ax.set_rmax(1.2)
ax.set_rticks([0.25, 0.5, 0.75, 1.0])
ax.set_rlabel_position(250)
ax.yaxis.set_major_formatter(lambda r, _: f"{r:g} m")
ax.set_title("peak wave height at the wall [m] around the tank (azimuth from x)", fontsize=10)
ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.05, 1.0))
fig.tight_layout()

# %%
# Both combinations of the two planar runs lie above the spatial run's peak for this pair of
# records (the 100/30 circle falls almost on the roof's): they assume the two components' peaks act together, and the spatial run, which
# integrates both at once, shows that they do not here. The base shear and overturning moment
# are combined the same way (``peaks`` holds ``base_shear_srss``, ``base_shear_100_30`` and
# the rest).
