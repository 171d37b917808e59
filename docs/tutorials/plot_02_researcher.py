"""
The researcher's tutorial
=========================

The nonlinear dynamics of the paper's model: the 3:1 internal resonance between the sloshing
pendulum and the tank on its rods, seen through the multiple-scales slow flow (frequency
response, stability chart, the beats between the Hopf points) and through the full equations
of motion (periodic orbits by shooting, basins of attraction, Lyapunov spectrum). Quantities
are the paper's dimensionless ones: time τ = ωt, forcing frequency ρ = Ω/ω, amplitude A,
coordinates x1 = θ/θ0 (the pendulum, 1 at the wall) and x2 (the tank), modal coordinates u1,
u2 (:doc:`../model` has every definition and equation).

The script runs as it is (``python docs/tutorials/plot_02_researcher.py``) and needs the
``plot`` and ``studies`` extras.
"""

# %%
# The system of Fig 12
# --------------------
# s1 = 1.5, μ1 = 0.5, θ0 = π/4, forcing A = 0.00075 and damping γ = 0.001, with κ chosen by
# eq (51) so that the second natural frequency is three times the first (detuning 0.005).

import math

import matplotlib.pyplot as plt
import numpy as np

import sloshdyn

kappa = sloshdyn.kappa_for_detuning(1.5, 0.5, 0.005)[0]
p = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=kappa, theta0=math.pi / 4, gamma=0.001,
                        A=0.00075)
modes = sloshdyn.linear_modes(p)
print(f"kappa = {kappa:.9f}; omega1 = {modes.omega1:.5f}, omega2 = {modes.omega2:.5f},"
      f" ratio {modes.omega2 / modes.omega1:.4f}")

# %%
# Frequency response of the slow flow
# -----------------------------------
# ``frequency_response`` finds every steady state of the 3:1 slow flow (eq (52)-(53)) on a grid
# of starts, continues each branch in ρ by pseudo-arclength, and classifies its stability by
# the eigenvalues of the Jacobian (LAPACK dgeev) and the Routh-Hurwitz coefficients of eq (55).
# Stable branches are solid, unstable dashed; folds are circles and Hopf points squares. The
# paper quotes the Hopf points at ρ = 0.50925 and 0.50998.

r = sloshdyn.frequency_response(p, (0.49, 0.53))
for s in r.special_points:
    print(f"{s.kind:5s} rho = {s.rho:.5f}")
fig = sloshdyn.plotting.frequency_response(r)

# %%
# Stability chart
# ---------------
# The fold and Hopf curves of the slow flow in the (ρ, A) plane, traced from the special points
# of the frequency responses, with their codimension-2 points; each cell is shaded by the
# number of stable steady states it holds.

chart = sloshdyn.stability_chart(p, (0.49, 0.53), (0.0, 0.002),
                                 chart=sloshdyn.Chart(n_x=21, n_y=5))
for c in chart.curves:
    print(f"{c.kind:5s} curve of {len(c.rho)} points, complete: {c.complete}")
for q in chart.codim2_points:
    print(f"{q.kind}: rho = {q.rho:.5f}, A = {q.A:.6f}")
fig = sloshdyn.plotting.stability_chart(chart)

# %%
# Beats: the limit cycles of the slow flow
# ----------------------------------------
# Between the two Hopf points the slow flow has no stable steady state: it settles on a limit
# cycle, a periodic modulation of the sloshing amplitude (the beats of Fig 14). The cycle is
# found by shooting on the slow flow and continued in ρ from one Hopf point to the other; the
# bands show min..max of ``|B1|`` and ``|B2|`` over each cycle, the lowest panel its period in forcing
# periods.

cycles = sloshdyn.slow_flow_cycles(p.replace(rho=0.509615), (0.49, 0.53))
print(f"{len(cycles.rho)} cycles from rho = {cycles.rho.min():.5f} to {cycles.rho.max():.5f},"
      f" ends: {cycles.ends}")
k = int(np.argmin(np.abs(cycles.rho - 0.509615)))
print(f"at rho = {cycles.rho[k]:.5f} the beat lasts {cycles.beat_periods[k]:.1f} forcing periods")
fig = sloshdyn.research.plot_beats(r, cycles)

# %%
# Periodic orbits of the full equations
# -------------------------------------
# The slow flow is an approximation. The full equations of motion have periodic orbits too:
# ``periodic_response`` finds one by simulation and Newton shooting (the monodromy matrix from
# the variational equations), then continues it in ρ, with Floquet multipliers (LAPACK dgeev)
# for stability, and marks folds, period doublings and Neimark-Sacker points (where a pair of
# multipliers leaves the unit circle: the full model's counterpart of a Hopf point of the slow
# flow: compare the Hopf points above). Folds are circles, Neimark-Sacker points squares.

branch = sloshdyn.periodic_response(p.replace(rho=0.50), (0.50, 0.52))
for s in branch.special_points:
    print(f"{s.kind:15s} rho = {s.rho:.5f}")
rho, max_x1, stable = (np.asarray(branch.table[c]) for c in ("rho", "max_x1", "stable"))
fig, ax = plt.subplots(figsize=(7, 3.6))
ax.plot(rho, np.where(stable == 1, max_x1, np.nan), "-", color="k", label="full model, stable")
ax.plot(rho, np.where(stable == 1, np.nan, max_x1), "--", color="k", label="full model, unstable")
markers = {"fold": "o", "neimark_sacker": "s", "period_doubling": "^", "branch_point": "x"}
for s in branch.special_points:
    ax.plot(s.rho, s.max_x1, markers[s.kind], mfc="none", color="r")
ax.set_xlabel(r"forcing frequency $\rho = \Omega/\omega$")
ax.set_ylabel(r"max $|x_1|$ over a period")
ax.set_xlim(0.50, 0.52)
ax.legend(fontsize=8)
fig.tight_layout()

# %%
# Basins of attraction
# --------------------
# At ρ = 0.52 two periodic motions coexist. ``basins`` runs an n × n grid of initial states
# (x1, x1'), with x2, x2' fixed, each to its steady state on Dask, and classifies the attractor
# it reaches (periodic ones by shooting and their Floquet multipliers). A coarse 12 × 12 grid
# keeps the build fast; the studies guide (:doc:`../studies`) runs finer ones.

import tempfile

with tempfile.TemporaryDirectory() as folder:
    b = sloshdyn.basins(p.replace(rho=0.52), (-0.3, 0.3), (-0.3, 0.3), n=12,
                        store=f"{folder}/basins.zarr", x2=-0.206, dx2=0.140,
                        workers=2, progress=False)
    print(b.attractor_kind.values, b.attractor_share.values)
    fig = sloshdyn.plotting.basins(b)

# %%
# Lyapunov spectrum
# -----------------
# At a strong forcing (A = 2, ρ = 0.513) the pendulum hits the walls and the motion is
# irregular. ``lyapunov_spectrum`` computes the four exponents by the QR method on the
# variational equations; the running estimates converge, the largest is positive (chaos),
# their sum is the mean trace of the Jacobian (the phase-space contraction by damping), and
# the Kaplan-Yorke dimension follows from the sorted exponents.

spectrum = sloshdyn.lyapunov_spectrum(p.replace(rho=0.513, A=2.0),
                                      lyapunov=sloshdyn.Lyapunov(transient_periods=100,
                                                                 n_periods=300))
print("exponents (per unit tau):", np.array2string(spectrum.exponents, precision=5))
print(f"sum {spectrum.sum:.5f}; Kaplan-Yorke dimension {spectrum.kaplan_yorke:.3f}")
fig, ax = plt.subplots(figsize=(7, 3.6))
for i, history in enumerate(spectrum.history):
    ax.plot(spectrum.periods, history, label=rf"$\lambda_{i + 1}$")
ax.axhline(0.0, color="0.5", lw=0.6)
ax.set_xlabel("forcing periods integrated")
ax.set_ylabel(r"running estimate (per unit $\tau$)")
ax.legend(fontsize=8, ncol=4)
fig.tight_layout()
