"""
Time history, phase plane and spectrum
======================================

A direct simulation of the full equations of motion (eq (15)) at the Fig 12 parameters inside
the band between the Hopf points (ρ = 0.509615): the steady motion is not periodic but beats,
a slow modulation of both modes. Shown: the pendulum x1 = θ/θ0 and the tank x2 against time
τ = ωt, the phase plane of the pendulum (x1, x1') with its Poincaré points (one per forcing
period), and the amplitude spectrum of x1 with the forcing frequency ρ and 3ρ marked.
"""

import math

import sloshdyn

p = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=math.pi / 4, gamma=0.001,
                        A=0.00075, rho=0.509615)
sim = sloshdyn.simulate(p, t_end=60000.0, y0=[0.01, 0, 0, 0], n_out=30000)
print(f"{sim.n_accepted} steps accepted, {sim.n_rejected} rejected ({sim.method})")
fig = sloshdyn.plotting.time_history(sim, ("x1", "x2"))

# one point per forcing period T = 2 pi/rho, after 2400 periods of transient
section = sloshdyn.poincare_section(p, 2400, y0=[0.01, 0, 0, 0], skip_periods=2400)
fig = sloshdyn.plotting.phase_plane(sim, "x1", poincare=section.y[:2])

half = sim.tau > 30000.0                     # the transient left out
line = sloshdyn.spectrum(sim.x1[half], dt=sim.tau[1] - sim.tau[0])
fig = sloshdyn.plotting.spectrum(line.omega, line.amplitude, marks=(p.rho, 3 * p.rho),
                                 label="amplitude of $x_1$", xmax=2.0)
