"""
The 3:1 internal resonance (Fig 12) against direct simulation
=============================================================

The multiple-scales slow flow (eq (52)-(53)) gives the response curves of Fig 12: stable
branches solid, unstable dashed, folds as circles, Hopf points as squares. Each cross is a
direct simulation of the full equations of motion (eq (15)), swept up and then down in ρ and
carrying its state from one frequency to the next, with the steady amplitude of the modal
coordinates u1 and u2 measured after the transient. Started from rest below the resonance,
the sweep climbs the upper branch and stays on it on the way back. Between the Hopf points no
steady state is stable: there the simulation beats (see the time-history example). The slow
flow is a first-order approximation in the amplitude: along the upper branch the simulated
``|u2|`` grows away from it.
"""

import math

import sloshdyn

p = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=math.pi / 4, gamma=0.001,
                        A=0.00075)
r = sloshdyn.frequency_response(p, (0.49, 0.53))
print([(s.kind, round(s.rho, 5)) for s in r.special_points])

quick = sloshdyn.Steady(transient_periods=2000, settle_tol=0, window_periods=50)
sweep = sloshdyn.frequency_sweep(p, sloshdyn.sweep_values(0.495, 0.525, 16, "both"), steady=quick)
fig = sloshdyn.plotting.frequency_response(r, simulation=sweep)
