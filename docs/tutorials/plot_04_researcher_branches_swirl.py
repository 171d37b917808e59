"""
The researcher's tutorial, continued: branch switching and swirl
================================================================

Two bifurcations of the full equations of motion that the first tutorial did not reach. The
periodic orbits of the planar model lose their Z2 symmetry at a branch point and then double
their period, and ``PeriodicBranch.switch`` follows the branches born there: a
period-doubling cascade. The spatial model (the sloshing mass a spherical pendulum) lets the
liquid leave the plane of the forcing: ``sloshdyn.spatial.swirl_band`` finds where the planar
orbit is unstable to out-of-plane motion (swirl). :doc:`../model` ("Branch switching",
"Spatial model and swirl") has the theory and the independent checks.

The script runs as it is (``python docs/tutorials/plot_04_researcher_branches_swirl.py``) and
needs the ``plot`` extra.
"""

# %%
# A period-doubling cascade
# -------------------------
# Fig 12's tank (s1 = 1.5, μ1 = 0.5, κ = 1.804897259, θ0 = π/4, β and δ the defaults) with
# γ = 0.001, forced at ρ = 1 in the impact regime (the wall at ``|x1| = 1``). The symmetric orbit,
# y(τ + T/2) = −y(τ), is continued down in A from A = 1.04518, where its state at phase 0 is
# known (:doc:`../model`, "Branch switching"). A symmetric orbit cannot double its period (Swift
# & Wiesenfeld 1984); it first breaks its symmetry at a branch point (a Floquet multiplier
# crosses +1).

import math

import matplotlib.pyplot as plt
import numpy as np

import sloshdyn
from sloshdyn import spatial

q = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=math.pi / 4,
                        gamma=0.001, rho=1.0, A=1.0451820685183326)
symmetric = sloshdyn.periodic_response(
    q, A_range=(0.9, q.A), from_end="high",
    y0=[-0.7309371728027403, 0.7465831246171408, 0.730688906743233, -2.7171951275930177])
print("symmetric: ", [(s.kind, round(s.A, 5)) for s in symmetric.special_points])

# %%
# ``switch`` starts the new branch from the special point along the critical Floquet
# eigenvector (the null vector of M − I at a branch point, of M + I at a period doubling) and
# continues it over the same range with the same steps. At the branch point the asymmetric
# orbits are born (period T); on them a multiplier crosses −1, and switching there gives the
# orbits of period 2T, which double again (2T → 4T), and switching once more gives the orbits
# of period 4T. The first three special points are those of :doc:`../model`'s table, checked
# independently with scipy in ``tests/python/test_branch_switching.py``; the doubling the 4T
# branch reports next (4T → 8T) has no such check.

asymmetric = symmetric.switch(symmetric.special_points[0])
print("asymmetric:", asymmetric.periods, "T,",
      [(s.kind, round(s.A, 5)) for s in asymmetric.special_points])
doubling = [s for s in asymmetric.special_points if s.kind == "period_doubling"][0]
doubled = asymmetric.switch(doubling)
print("doubled:   ", doubled.periods, "T,",
      [(s.kind, round(s.A, 5)) for s in doubled.special_points])
quadrupled = doubled.switch(doubled.special_points[0])
print("quadrupled:", quadrupled.periods, "T,",
      [(s.kind, round(s.A, 5)) for s in quadrupled.special_points])


def largest_multiplier(branch):
    """max |mu| over the Floquet multipliers of each orbit of the branch."""
    return np.max(np.abs([branch.table[f"mu{i}"] for i in range(1, 5)]), axis=0)


print("largest |multiplier| on the doubled branch:",
      f"{largest_multiplier(doubled).min():.1f} .. {largest_multiplier(doubled).max():.1f}"
      " (all these orbits are unstable)")

# %%
# The three branches in the (A, ``max|x1|``) plane, each orbit's largest ``|x1|`` over its
# period; the branch point is a cross, the period doublings triangles.

fig, ax = plt.subplots(figsize=(7, 3.8))
for branch, style, label in ((symmetric, "-", "symmetric, period T"),
                             (asymmetric, "--", "asymmetric, period T"),
                             (doubled, "-.", "period 2T"), (quadrupled, ":", "period 4T")):
    ax.plot(branch.table["A"], branch.table["max_x1"], style, label=label)
marker = {"branch_point": "x", "period_doubling": "^"}
for branch in (symmetric, asymmetric, doubled, quadrupled):
    for s in branch.special_points:
        ax.plot(s.A, s.max_x1, marker.get(s.kind, "o"), color="k", mfc="none", ms=8)
ax.set_xlabel("forcing amplitude A")
ax.set_ylabel(r"max $|x_1|$ over the orbit")
ax.set_title(r"$\rho$ = 1, $\gamma$ = 0.001 (all orbits unstable)", fontsize=10)
ax.legend(fontsize=8)
fig.tight_layout()

# %%
# The swirl band
# --------------
# A pendulum-like tank (s1 = 1, μ1 = 0.01, stiff rods κ = 1000, no wall: β = δ = 0) forced near
# its sloshing frequency with A = 0.001 and sloshing damping ζ = 5e-4. ``swirl_band`` continues
# the planar periodic response in ρ (here from the high end down) and computes along it the
# four out-of-plane Floquet multipliers ν of the spatial model's variational equations; where
# ``max|ν| > 1`` a small out-of-plane motion grows and the liquid swirls. The band's edge, where
# ``max|ν| = 1``, is located by Brent's method.

pendulum = sloshdyn.Parameters(s1=1.0, mu1=0.01, kappa=1e3, theta0=1.4, beta=0.0, delta=0.0,
                               A=1e-3, rho=1.02, zeta=5e-4)
band = spatial.swirl_band(pendulum, (0.995, 1.02), from_end="high")
print(f"complete: {band.complete}; band edge at rho = {band.edges['rho']}"
      f" (refined: {band.edges['refined']})")

# %%
# An independent look at one orbit: ``out_of_plane_multipliers`` integrates the out-of-plane
# variational equations over the planar orbit at the branch's last point, ρ = 0.995, below the
# edge.

last = [band.table[f"y{i}"][-1] for i in range(1, 5)]
nu = spatial.out_of_plane_multipliers(pendulum.replace(rho=0.995), last)
print(f"rho = {band.table['rho'][-1]:.4f}: |nu| = {np.round(np.abs(nu), 4)}")

rho, nu_max, swirl = band.table["rho"], band.table["max_abs_nu"], band.table["swirl"] == 1
fig, axes = plt.subplots(2, 1, sharex=True, figsize=(7, 5))
axes[0].plot(rho, band.table["max_x1"], "k.-", ms=3)
axes[0].set_ylabel(r"planar max $|x_1|$")
axes[1].plot(rho, nu_max, "k.-", ms=3)
axes[1].plot(rho[swirl], nu_max[swirl], "o", color="tab:red", mfc="none", label="swirl")
axes[1].axhline(1.0, color="0.5", lw=0.8)
for ax in axes:
    for edge in band.edges["rho"]:
        ax.axvline(edge, ls=":", color="tab:red", lw=1, label="band edge")
axes[1].set_ylabel(r"max $|\nu|$ (out of plane)")
axes[1].set_xlabel(r"forcing frequency $\rho = \Omega/\omega$")
axes[1].legend(fontsize=8)
fig.tight_layout()
