"""
The frequency ratio of the two modes (Fig 7)
============================================

ω2/ω1, the ratio of the linear natural frequencies (eq (28)), over the stiffness parameter
σ̃ = κ - s1 for several mass ratios μ̃ = 1 - μ1, as in Fig 7 of the paper; the dotted line is
the 3:1 ratio of the internal resonance, which ``kappa_for_detuning`` solves for (eq (51)).
"""

import matplotlib.pyplot as plt
import numpy as np

import sloshdyn

sigma = np.linspace(0.01, 6.0, 300)
fig, ax = plt.subplots(figsize=(6.5, 4))
for mu_tilde in (0.2, 0.5, 0.8):
    ax.plot(sigma, sloshdyn.frequency_ratio(sigma, mu_tilde), label=rf"$\tilde\mu$ = {mu_tilde}")
ax.axhline(3.0, ls=":", color="k", lw=0.8, label="3:1")
kappa = sloshdyn.kappa_for_detuning(1.5, 0.5, 0.0)        # s1 = 1.5, mu1 = 0.5: mu~ = 0.5
ax.plot(kappa - 1.5, [3.0] * len(kappa), "o", color="r", mfc="none",
        label=r"$\kappa$ of eq (51), $\tilde\mu$ = 0.5")
print("kappa for an exact 3:1 ratio:", kappa)
ax.set_xlabel(r"$\tilde\sigma = \kappa - s_1$")
ax.set_ylabel(r"$\omega_2/\omega_1$")
ax.legend(fontsize=8)
fig.tight_layout()
