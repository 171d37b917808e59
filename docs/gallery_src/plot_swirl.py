"""
Swirl: the band, the swirling branch and the boundary in (ρ, A)
===============================================================

A circular tank forced along x near resonance (the forced spherical pendulum limit: stiff rods,
small amplitude, no impacts; docs/model.md "Spatial model and swirl"). Left: the planar
branches from both ends of the range (``swirl_band(..., from_end='both')``), solid where the
planar orbit is stable out of its plane, red where it swirls, and the swirling orbits born at
the band's edge (``swirling_branch``), their max|x1| and swirl amplitude max|y1|, dashed where
unstable: the branch leaves the edge subcritically, folds (square) and comes back stable,
down to a Neimark-Sacker point (square) near ρ = 1.0007 below which the swirl is
quasi-periodic. Right: the swirl boundary in (ρ, A) continued as one curve
(``swirl_boundary_curve``: pseudo-arclength on det(M_b − I) = 0 from an edge at A = 2.5·10⁻⁴),
through the band's low and high edges, solid where the onset of swirl is supercritical (the
edge's criticality c < 0: stable swirling orbits are born inside the band) and dashed where it
is subcritical (c > 0: entering the band the motion jumps to swirl), with its codimension-2
points: where damping closes the band (star: the least A with swirl) and the degenerate
pitchfork where c = 0 (diamond), the single-A edges of ``swirl_boundary`` (circles) on it,
beside Miles' scaling ρ − 1 ∝ A^(2/3).
"""

import matplotlib.pyplot as plt
import numpy as np

import sloshdyn
from sloshdyn import spatial
from sloshdyn.options import Continuation

params = sloshdyn.Parameters(s1=1.0, mu1=0.01, kappa=1e3, theta0=1.4, beta=0.0, gamma=0.0,
                             delta=0.0, A=1e-3, rho=1.02, zeta=5e-4, n=6, p=2)
band = spatial.swirl_band(params, (0.98, 1.02), from_end="both")
resonant = spatial.swirl_band(params, (0.98, 1.02), from_end="high")
steps = Continuation(ds=0.01, ds_min=1e-9, ds_max=0.05, x_scale=1.0, max_points=400)
swirling = spatial.swirling_branch(resonant, 0, (0.99, 1.1), params=params, ds=0.01,
                                   continuation=steps)
A_values = np.array([2.5e-4, 5e-4, 1e-3, 2e-3])
boundary = spatial.swirl_boundary(params, (0.98, 1.03), A_values, from_end="high")
curve = spatial.swirl_boundary_curve(params.replace(A=2.5e-4), (0.98, 1.03), (4e-5, 2e-3),
                                     ds=0.2, from_end="high")
closing = curve.folds[0]
print("edges of the band at A = 1e-3:", resonant.edges["rho"], resonant.edges["kind"])
print("closing of the band:", closing["kind"], closing["rho"], closing["A"])
print("degenerate pitchforks:", [(p["rho"], p["A"]) for p in curve.degenerate])
print("fold of the swirling branch:", [(p.kind, round(p.rho, 6)) for p in swirling.special_points])

fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4.2))
table = band.table
for b in set(table["branch"]):
    on = table["branch"] == b
    rho, x1, swirl = table["rho"][on], table["max_x1"][on], table["swirl"][on]
    left.plot(rho, x1, color="0.6", lw=1)
    left.plot(np.where(swirl, rho, np.nan), np.where(swirl, x1, np.nan), color="r", lw=2)
t = swirling.table
for name, color, label in (("max_x1", "b", "swirling: max|x1|"),
                           ("swirl_amplitude", "g", "swirling: max|y1|")):
    stable = t["stable"] == 1
    left.plot(np.where(stable, t["rho"], np.nan), np.where(stable, t[name], np.nan), color=color,
              label=label)
    left.plot(np.where(~stable, t["rho"], np.nan), np.where(~stable, t[name], np.nan),
              color=color, ls="--")
for p in swirling.special_points:
    left.plot(p.rho, p.max_x1, "ks", mfc="none")
left.plot(resonant.edges["rho"], resonant.edges["max_x1"], "ko", label="swirl edge")
left.plot([], [], color="r", lw=2, label="planar, swirls")
left.plot([], [], color="0.6", label="planar")
left.set_xlabel(r"$\rho$")
left.set_ylabel(r"tilt / $\theta_0$")
left.legend(fontsize=8)
left.set_title(r"A = $10^{-3}$, $\zeta = 5\cdot10^{-4}$", fontsize=9)

edges = boundary.edges
c = curve.table["c"]
for sign, style, label in ((-1, "-", "boundary, supercritical onset"),
                           (1, "--", "boundary, subcritical onset")):
    # each point's segment to the next drawn in its own style, so the two styles meet
    on = np.sign(c) == sign
    on[1:] |= on[:-1]
    right.plot(np.where(on, curve.table["rho"], np.nan), np.where(on, curve.table["A"], np.nan),
               style, color="C0", label=label)
right.plot(edges["rho"], edges["A"], "o", color="C1", mfc="none", label="edges (one band per A)")
right.plot(closing["rho"], closing["A"], "k*", ms=10, label="closing (fold in A)")
for point in curve.degenerate:
    right.plot(point["rho"], point["A"], "kD", ms=6, mfc="none", label="degenerate pitchfork")
upper = np.array([edges["rho"][edges["A"] == a].max() for a in A_values])
scale = (upper[A_values == 1e-3][0] - 1) * (A_values / 1e-3) ** (2 / 3)
right.plot(1 + scale, A_values, "k:", label=r"$\rho - 1 \propto A^{2/3}$")
right.text(0.9995, 3e-4, "swirl", fontsize=9, ha="center")
right.set_yscale("log")
right.set_xlabel(r"$\rho$")
right.set_ylabel("A")
right.set_title(r"$\zeta = 5\cdot10^{-4}$", fontsize=9)
right.legend(fontsize=8)
fig.tight_layout()
