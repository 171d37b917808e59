"""
Time history, phase plane and spectrum
======================================

A direct simulation of the full equations of motion (eq (15)) at the Fig 12 parameters inside
the band between the Hopf points (ρ = 0.509615): the steady motion is not periodic but beats,
a slow modulation of both modes (Fig 14). Shown: the pendulum x1 = θ/θ0 and the tank x2
against time τ = ωt; the steady part in the phase plane of the pendulum (x1, dx1/dτ) with its
Poincaré points, one per forcing period T = 2π/ρ, which lie on a closed curve (a
quasi-periodic motion); and the amplitude spectrum of x1, with the forcing frequency ρ and 3ρ
marked.
"""

import math

import matplotlib.pyplot as plt

import sloshdyn

p = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=math.pi / 4, gamma=0.001,
                        A=0.00075, rho=0.509615)
y0 = [0.01, 0, 0, 0]
sim = sloshdyn.simulate(p, t_end=40000.0, y0=y0, n_out=160001)      # output every 0.25 in tau
print(f"{sim.n_accepted} steps accepted, {sim.n_rejected} rejected ({sim.method})")
fig = sloshdyn.plotting.time_history(sim, ("x1", "x2"))

# %%
# The steady part: after 20000 in τ (about 1600 forcing periods) the transient has died out.

steady = sim.tau > 20000.0
section = sloshdyn.poincare_section(p, 1600, y0=y0, skip_periods=1650)
fig, ax = plt.subplots(figsize=(5, 4.5))
ax.plot(sim.y[0, steady], sim.y[1, steady], lw=0.3, color="0.6")
ax.plot(section.y[0], section.y[1], ".", ms=2, color="r", label="Poincaré section")
ax.set_xlabel(r"$x_1 = \theta/\theta_0$")
ax.set_ylabel(r"$dx_1/d\tau$")
ax.legend(loc="upper right")
fig.tight_layout()

# %%
# The spectrum of the steady part: the pendulum answers at the forcing frequency ρ and at 3ρ,
# where the 3:1 internal resonance with the tank's mode puts energy.

line = sloshdyn.spectrum(sim.x1[steady], dt=sim.tau[1] - sim.tau[0])
fig = sloshdyn.plotting.spectrum(line.omega, line.amplitude, marks=(p.rho, 3 * p.rho),
                                 label="amplitude of $x_1$", xmax=2.0)
