"""Every numerical figure of the paper, recomputed: each function computes its data with the
core, writes figNN.csv and figNN.png into a directory, and returns the numbers the paper quotes
next to it (for the report and for `check`)."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from . import plotting
from ._files import save_figure, write_csv
from .asymptotics import frequency_response, modal_coefficients, slow_flow_cycle
from ._errors import SloshdynError
from .model import equilibria, equilibrium_angles, frequency_ratio, kappa_for_detuning, linear_modes
from .periodic import PERIODIC_CONTINUATION, Lyapunov, lyapunov_exponent, periodic_response
from .parameters import Parameters
from .simulation import Steady, amplitude_sweep, beat_period, simulate, spectrum, steady_state
from matplotlib.ticker import MaxNLocator  # after plotting, which names the 'plot' extra

plt = plotting.plt

THETA0 = math.pi / 4
#: the Fig 12 / Fig 14 system (sec 4.2); beta, delta: docs/namelist.md, "Impact and dissipation defaults"
FIG12 = Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=THETA0, gamma=0.001, A=0.00075,
                   rho=0.509615)
FIG9 = dict(s1=1.5, mu1=0.5, theta0=THETA0, gamma=0.0025, A=0.0005)


@dataclass(frozen=True)
class Figure:
    """One reproduced figure: its files, the paper's caption, and the numbers computed."""

    number: str
    caption: str
    files: list = field(default_factory=list)
    values: dict = field(default_factory=dict)
    notes: str = ""


def _save(fig, out, name, columns):
    write_csv(Path(out) / f"{name}.csv", columns)
    save_figure(fig, Path(out) / f"{name}.png")
    return [f"{name}.png", f"{name}.csv"]


def fig03(out, quick=False):
    x = np.linspace(-1.3, 1.3, 521)
    styles = {1: (":", "m"), 3: ("-.", "b"), 6: ("--", "r"), 10: ("-", "k")}
    fig, ax = plt.subplots(figsize=(6, 4))
    columns = {"theta_over_theta0": x}
    for n, (ls, color) in styles.items():
        force = x ** (2 * n - 1)                      # eq (4): F/b = (theta/theta0)^(2n-1)
        columns[f"F_over_b_n{n}"] = force
        ax.plot(x, force, ls, color=color, label=f"n = {n}")
    ax.set_ylim(-3, 3)
    ax.set_xlabel(r"$\theta/\theta_0$")
    ax.set_ylabel(r"$F_{impact}/b$")
    ax.legend()
    return Figure("3", "The interaction force between the tank walls and the pendulum vs. the "
                  "pendulum angle for n=1 (dotted pink), n=3 (dashed-dotted blue), n=6 (dashed "
                  "red) and n=10 (solid black).", _save(fig, out, "fig03", columns))


def _beta_hat_bifurcation():
    """Bisection on the number of roots of eq (17), n = 2 (Fig 4)."""
    low, high = 0.005, 0.08
    for _ in range(50):
        mid = 0.5 * (low + high)
        roots = equilibrium_angles(_with_beta_hat(mid), "theta").angles
        low, high = (mid, high) if len(roots) > 1 else (low, mid)
    return low


def _with_beta_hat(beta_hat, n=2):
    return Parameters(s1=1.5, mu1=0.5, kappa=1.8, theta0=THETA0, n=n,
                      beta=beta_hat * THETA0 ** (2 * n - 1))


def _equilibria_plot(x, name, symbol, family, ylim):
    """sin x (solid blue) beside a family of curves (solid black, dashed red, dotted magenta),
    with circles at the roots sloshdyn finds for each (eq 17): the equilibria of `name`
    ("theta" or "phi", written `symbol` in TeX). `family` holds per curve (column, values,
    label, parameters, key of the number of roots). Returns the figure, its columns and the
    numbers of roots."""
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(x, np.sin(x), "-", color="b", label=rf"$\sin{symbol}$")
    columns = {name: x, f"sin_{name}": np.sin(x)}
    values = {}
    styles = (("-", "k"), ("--", "r"), (":", "m"))
    for (column, curve, label, params, key), (ls, color) in zip(family, styles):
        columns[column] = curve
        ax.plot(x, curve, ls, color=color, label=label)
        roots = equilibrium_angles(params, name).angles
        ax.plot(roots, np.sin(roots), "o", color=color, mfc="none")
        values[key] = len(roots)
    ax.set_ylim(*ylim)
    ax.set_xlabel(rf"${symbol}$ [rad]")
    ax.legend(fontsize=8)
    return fig, columns, values


def fig04(out, quick=False):
    theta = np.linspace(-6, 6, 1201)
    fig, columns, values = _equilibria_plot(theta, "theta", r"\theta", [
        (f"minus_beta_hat_theta3_{beta_hat}", -beta_hat * theta**3,
         rf"$-\hat\beta\theta^3$, $\hat\beta$ = {beta_hat}", _with_beta_hat(beta_hat),
         f"fig4_equilibria_beta_hat_{beta_hat}") for beta_hat in (0.005, 0.012, 0.08)], (-2, 2))
    values["fig4_beta_hat_b"] = _beta_hat_bifurcation()
    return Figure("4", "Equilibrium points of θ represented by intersection between sin θ (solid "
                  "blue) and -β̂θ^(2n-1) for n=2, β̂=0.005 (solid black), β̂=0.012 (dashed red) "
                  "and β̂=0.08 (dotted magenta).", _save(fig, out, "fig04", columns), values,
                  f"Circles: the roots found by sloshdyn (eq 17). β̂_b = {values['fig4_beta_hat_b']:.6f} "
                  "(tangency tan θ = θ/3 at θ ≈ 4.07); the paper reads 0.012 off the graph.")


def _with_kappa_hat(kappa_hat, gamma=0.01):
    return Parameters(s1=1.5, mu1=0.5, kappa=kappa_hat * 1.5, theta0=THETA0, gamma=gamma, beta=10.0)


def fig05(out, quick=False):
    phi = np.linspace(-3.5, 3.5, 701)
    fig, columns, values = _equilibria_plot(phi, "phi", r"\varphi", [
        (f"kappa_hat_phi_{kappa_hat}", kappa_hat * phi,
         rf"$\hat\kappa\varphi$, $\hat\kappa$ = {kappa_hat}", _with_kappa_hat(kappa_hat),
         f"fig5_equilibria_kappa_hat_{kappa_hat}") for kappa_hat in (1.3, 1.0, 0.9)], (-1.5, 1.5))
    return Figure("5", "Equilibrium points for variable φ represented by intersection between "
                  "sin φ (solid blue) and κ̂φ for κ̂=1.3 (solid black), κ̂=1 (dashed red) and "
                  "κ̂=0.9 (dotted magenta).", _save(fig, out, "fig05", columns), values)


def _pitchfork():
    low, high = 0.5, 1.5
    for _ in range(50):
        mid = 0.5 * (low + high)
        roots = equilibrium_angles(_with_kappa_hat(mid), "phi").angles
        low, high = (low, mid) if len(roots) == 1 else (mid, high)
    return high


def fig06(out, quick=False):
    kappa_hats = np.linspace(0.6, 1.4, 41 if quick else 161)
    rows = {"kappa_hat": [], "phi": [], "stable": []}
    for kh in kappa_hats:
        for e in equilibria(_with_kappa_hat(kh)):
            if e.theta == 0 and abs(e.phi) < math.pi / 2:
                rows["kappa_hat"].append(kh)
                rows["phi"].append(e.phi)
                rows["stable"].append(1 if e.stable else 0)
    data = {k: np.array(v) for k, v in rows.items()}
    fig, ax = plt.subplots(figsize=(6, 4))
    for sign in (-1, 0, 1):
        for stable, ls in ((1, "-"), (0, "--")):
            mask = (np.sign(np.round(data["phi"], 12)) == sign) & (data["stable"] == stable)
            if mask.any():
                ax.plot(data["kappa_hat"][mask], data["phi"][mask], ls, color="k")
    ax.set_xlabel(r"$\hat\kappa$")
    ax.set_ylabel(r"$\varphi$ [rad]")
    values = {"fig6_pitchfork_kappa_hat": _pitchfork()}
    return Figure("6", "Stable (solid) and unstable (dashed) equilibrium solutions of φ versus κ̂.",
                  _save(fig, out, "fig06", data), values,
                  "Stability from the eigenvalues of the 4x4 Jacobian (LAPACK dgeev), γ = 0.01.")


def _ratio_map(out, name, x, x_label, curves, curve_label, symbol, ratio_of, ylim, zoom_x):
    """omega2/omega1 along x for three values of the other group (Fig 7, 8): full and zoom."""
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    columns = {x_label: x}
    for value, ls in zip(curves, ("-", "--", "-.")):
        ratio = ratio_of(value)
        columns[f"ratio_{curve_label}_{value}"] = ratio
        for ax in axes:
            ax.plot(x, ratio, ls, color="k", label=rf"$\tilde\{symbol}$ = {value}")
    axes[0].set_ylim(0, ylim)
    axes[1].set_xlim(*zoom_x)
    axes[1].set_ylim(0, 10)
    for ax in axes:
        ax.set_xlabel(r"$\tilde\sigma = \kappa - s_1$" if x_label == "sigma_tilde"
                      else r"$\tilde\mu = 1 - \mu_1$")
        ax.set_ylabel(r"$\omega_2/\omega_1$")
        ax.legend()
    return _save(fig, out, name, columns)


def fig07(out, quick=False):
    sigma = np.linspace(0.01, 10, 1000)
    files = _ratio_map(out, "fig07", sigma, "sigma_tilde", (0.1, 0.5, 1.0), "mu_tilde", "mu",
                       lambda mu_t: frequency_ratio(sigma, mu_t), 20, (0, 2))
    sigma31 = float(kappa_for_detuning(1.5, 0.5, 0.0)[0] - 1.5)
    return Figure("7", "a) Natural frequencies ratio vs σ̃ for μ̃=0.1 (solid), μ̃=0.5 (dashed) and "
                  "μ̃=1 (dashed-dotted), b) Zoom-in for 0<σ̃<2.", files,
                  {"sec32_sigma_tilde_31": sigma31})


def fig08(out, quick=False):
    mu = np.linspace(0.01, 1.0, 500)
    files = _ratio_map(out, "fig08", mu, "mu_tilde", (0.1, 0.5, 1.0), "sigma_tilde", "sigma",
                       lambda sigma_t: frequency_ratio(sigma_t, mu), 30, (0.4, 1))
    return Figure("8", "a) Natural frequencies ratio vs. μ̃ for σ̃=0.1 (solid), σ̃=0.5 (dashed) and "
                  "σ̃=1 (dashed-dotted), b) Zoom-in for 0.4<μ̃<1.", files)


def _response_columns(response):
    return {k: response.table[k] for k in ("branch", "rho", "A", "a1", "a2", "stable", "special", "delta3")}


def _fig9(out, kappa, letter, kind):
    p = Parameters(kappa=kappa, **FIG9)
    m = modal_coefficients(p)
    w1 = m.omega1
    response = frequency_response(p, (w1 - 0.04, w1 + 0.04), resonance="none")
    fig = plotting.frequency_response(response, columns=("a1",))
    folds = sorted(s.rho for s in response.special_points if s.kind == "fold")
    values = {f"fig9{letter}_c11": m.coefficients["c11"]}
    return Figure(f"9{letter}", f"Frequency response graph of |u1| for s1=1.5, μ1=0.5, θ0=π/4, "
                  f"γ=0.0025, A=0.0005: κ={kappa} and c11 ≈ {'-0.03188' if letter == 'a' else '0.30585'}, "
                  f"{kind} effect.", _save(fig, out, f"fig09{letter}", _response_columns(response)),
                  values, f"c11 = {m.coefficients['c11']:.6f}; ω1 = {w1:.6f}; folds at ρ = "
                  + ", ".join(f"{f:.6f}" for f in folds)
                  + f" ({'below' if kind == 'softening' else 'above'} ω1).")


def fig09a(out, quick=False):
    return _fig9(out, 4.7, "a", "softening")


def fig09b(out, quick=False):
    return _fig9(out, 4.5, "b", "hardening")


def fig10(out, quick=False):
    kappa = np.linspace(1.55, 6.0, 90 if quick else 446)
    c11 = np.array([modal_coefficients(Parameters(kappa=k, **FIG9)).coefficients["c11"]
                    for k in kappa])
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(kappa, c11, "-", color="k")
    ax.axhline(0, color="0.6", lw=0.6)
    ax.set_ylim(-5, 5)
    ax.set_xlabel(r"$\kappa$")
    ax.set_ylabel(r"$c_{11}$")
    sign_change = kappa[np.nonzero(np.diff(np.sign(c11)))[0]]
    return Figure("10", "Coefficient c11 vs. parameter κ for s1=1.5, μ1=0.5, θ0=π/4, γ=0.0025, "
                  "A=0.0005", _save(fig, out, "fig10", {"kappa": kappa, "c11": c11}), {},
                  "c11 changes sign at κ ≈ " + ", ".join(f"{k:.3f}" for k in sign_change)
                  + " (hardening where c11 > 0).")


def _simulation_points(p, rhos, quick):
    """Harmonic amplitudes of u1 (rho) and u2 (3 rho) in direct simulation at steady state."""
    a1, a2, motion = [], [], []
    steady = Steady(max_transient_periods=3000 if quick else 20000)
    for rho in rhos:
        q = p.replace(rho=float(rho))
        st = steady_state(q, steady=steady)
        period = 2 * math.pi / q.rho
        tau = np.arange(200 * 64 + 1) * period / 64
        sim = simulate(q, tau[-1], st.y_end, tau_out=tau)
        t = tau[:-1]
        a1.append(2 * abs(np.mean(sim.u[0][:-1] * np.exp(-1j * q.rho * t))))
        a2.append(2 * abs(np.mean(sim.u[1][:-1] * np.exp(-3j * q.rho * t))))
        motion.append(st.motion)
    return np.array(a1), np.array(a2), motion


def _overlay(fig, rhos, a1, a2):
    for ax, values in zip(fig.axes, (a1, a2)):
        ax.plot(rhos, values, "x", color="b", ms=5, label="direct simulation")
        ax.legend(fontsize=8)


def fig11(out, quick=False):
    kappa = float(kappa_for_detuning(1.5, 0.5, 0.0)[0])
    p = FIG12.replace(kappa=kappa, gamma=0.0025)
    fig, axes = plt.subplots(2, 1, sharex=True, figsize=(7, 6))
    columns = {k: [] for k in ("A", "branch", "rho", "a1", "a2", "stable")}
    values = {}
    for A, color in ((0.00025, "k"), (0.0005, "b"), (0.00075, "g"), (0.001, "r")):
        r = frequency_response(p.replace(A=A), (0.48, 0.54))
        for b in r.branches:
            for ax, col in zip(axes, ("a1", "a2")):
                _styled(ax, b["rho"], b[col], b["stable"], color)
        for k in columns:
            columns[k].extend(r.table[k])
        values[f"fig11_folds_A_{A}"] = sum(s.kind == "fold" for s in r.special_points)
    rhos = np.linspace(0.50, 0.525, 4 if quick else 8)
    a1, a2, _ = _simulation_points(p.replace(A=0.00075), rhos, quick)
    _overlay(fig, rhos, a1, a2)
    axes[0].set_ylabel(r"$|u_1|$")
    axes[1].set_ylabel(r"$|u_2|$")
    axes[1].set_xlabel(r"$\rho$")
    fig.tight_layout()
    files = _save(fig, out, "fig11", {k: np.array(v) for k, v in columns.items()})
    write_csv(Path(out) / "fig11_simulation.csv", {"rho": rhos, "a1": a1, "a2": a2})
    return Figure("11", "Frequency response curves of |u1| and |u2| for s1=1.5, θ0=π/4, μ1=0.5, "
                  "γ=0.0025, ε²σ1=0, i.e. κ=1.81, under different harmonic excitation amplitudes.",
                  files + ["fig11_simulation.csv"], values,
                  f"κ = {kappa:.9f} (σ1 = 0); A = 0.00025 (black), 0.0005 (blue), 0.00075 (green), "
                  "0.001 (red); crosses: direct simulation at A = 0.00075 (amplitude of the ρ "
                  "harmonic of u1 and the 3ρ harmonic of u2).")


def _styled(ax, x, y, stable, color):
    start = 0
    for k in range(1, len(x) + 1):
        if k == len(x) or stable[k] != stable[start]:
            end = min(k + 1, len(x))
            ax.plot(x[start:end], y[start:end], "-" if stable[start] else "--", color=color, lw=1)
            start = k


def fig12(out, quick=False):
    r = frequency_response(FIG12, (0.49, 0.53))
    fig = plotting.frequency_response(r)
    rhos = np.array([0.50, 0.505, 0.508, 0.5105, 0.511, 0.515, 0.52, 0.525])[: 4 if quick else 8]
    a1, a2, motion = _simulation_points(FIG12, rhos, quick)
    _overlay(fig, rhos, a1, a2)
    files = _save(fig, out, "fig12", _response_columns(r))
    write_csv(Path(out) / "fig12_simulation.csv", {"rho": rhos, "a1": a1, "a2": a2, "motion": motion})
    hopf = sorted(s.rho for s in r.special_points if s.kind == "hopf")
    values = {f"fig13_hopf_rho_{i + 1}": h for i, h in enumerate(hopf)}
    return Figure("12", "Frequency response curves of |u1| and |u2| for s1=1.5, θ0=π/4, μ1=0.5, "
                  "γ=0.001, ε²σ1=0.005, A=0.00075, i.e. κ=1.8049", files + ["fig12_simulation.csv"],
                  values, "Circles: folds; squares: Hopf points; crosses: direct simulation "
                  "(harmonic amplitudes; from rest, so on the lower branch where three solutions "
                  "coexist).")


def fig13(out, quick=False):
    r = frequency_response(FIG12, (0.49, 0.53))
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.5))
    for ax, zoom in zip(axes, (None, (0.5085, 0.5105))):
        for b in r.branches:
            ax.plot(b["rho"], b["delta3"], "-", color="k", lw=1)
        for s in r.special_points:
            if s.kind == "hopf":
                ax.axvline(s.rho, ls=":", color="r")
        ax.axhline(0, color="0.6", lw=0.6)
        ax.set_xlabel(r"$\rho$")
        ax.set_ylabel(r"$\Delta_3$")
        if zoom:
            ax.set_xlim(*zoom)
            inside = (r.table["rho"] > zoom[0]) & (r.table["rho"] < zoom[1])
            span = np.max(np.abs(r.table["delta3"][inside]))
            ax.set_ylim(-1.1 * span, 1.1 * span)
        ax.xaxis.set_major_locator(MaxNLocator(5))   # five-digit labels side by side
    fig.tight_layout()
    return Figure("13", "a) Routh coefficient Δ3 vs. external forcing frequency, b) zoom-in.",
                  _save(fig, out, "fig13", _response_columns(r)))


def fig14_beats(quick=False):
    """The Fig 14 steady motion, a simulation of it, and its beat period in forcing periods
    measured two ways: from the full equations (the Poincare points' whole turns about their
    closed curve over a 3000-period window, ~12 turns; beat_period) and from the slow flow
    (the period of its limit cycle, by shooting; slow_flow_cycle). The transient (5000
    periods) is long enough that doubling it moves the first by 1e-7 (relative)."""
    p = FIG12
    st = steady_state(p, steady=Steady(settle_tol=0, transient_periods=5000, window_periods=3000))
    period = 2 * math.pi / p.rho
    n_periods = 800 if quick else 3000
    sim = simulate(p, n_periods * period, st.y_end, n_out=n_periods * 32 + 1)
    return st, sim, beat_period(st.poincare), slow_flow_cycle(p).beat_periods


def fig14(out, quick=False):
    st, sim, beat, slow_beat = fig14_beats(quick)
    fig, axes = plt.subplots(1, 3, figsize=(14, 4))
    axes[0].plot(sim.tau, sim.u[0], lw=0.3, color="k", label=r"$u_1$")
    axes[0].plot(sim.tau, sim.u[1], lw=0.3, color="r", label=r"$u_2$")
    axes[0].set_xlabel(r"$\tau$")
    axes[0].legend()
    for ax, row in zip(axes[1:], (0, 1)):
        du = np.gradient(sim.u[row], sim.tau)
        ax.plot(sim.u[row], du, lw=0.2, color="0.6")
        ax.plot(sim.u[row][::32], du[::32], ".", color="r", ms=2)
        ax.set_xlabel(rf"$u_{row + 1}$")
        ax.set_ylabel(rf"$u_{row + 1}'$")
    fig.tight_layout()
    files = _save(fig, out, "fig14", {"tau": sim.tau, "u1": sim.u[0], "u2": sim.u[1]})
    return Figure("14", "a) Time history for signals u1 and u2. Beating signals take place. b) "
                  "State-plane and Poincare sections of u1, c) State-plane and Poincare sections of "
                  "u2. μ1=0.5, s1=1.5, σ1=0.005, κ=1.804897259, γ=0.001, A=0.00075, ρ=0.509615",
                  files, {"beat_fig14_simulation": beat, "beat_fig14_slow_flow": slow_beat,
                          "beat_fig14_ratio": beat / slow_beat},
                  f"Steady motion: {st.motion}; beat period {beat:.2f} forcing periods (the "
                  "Poincaré points' turns about their closed curve), against "
                  f"{slow_beat:.2f} from the slow flow's limit cycle (shooting); red dots: "
                  "Poincaré points (every forcing period).")


def continuation_path(quick=False):
    """The settings of the paper's numerical continuation in A at rho = 0.513 (sec 4.2): the
    parameters, the A values (0.00075 -> 1.0475 -> 2.0) and the steady-state settings."""
    values = np.concatenate([np.geomspace(0.00075, 1.0475, 12 if quick else 30),
                             np.linspace(1.0475, 2.0, 6 if quick else 20)[1:]])
    return (FIG12.replace(rho=0.513), values,
            Steady(max_transient_periods=3000 if quick else 10000))


def _continuation(quick):
    """The paper's numerical continuation in A at rho = 0.513 (sec 4.2), carrying the state."""
    p, values, steady = continuation_path(quick)
    states = {}
    y = None
    for A in values:
        sweep = amplitude_sweep(p, [A], y, steady=steady)
        y = sweep.y_final
        states[float(A)] = (y.copy(), sweep.points[0])
    return p, states


def fig15_17(out, quick=False):
    p, states = _continuation(quick)
    results = []
    for number, A in (("15", 0.00075), ("16", 1.0475), ("17", 2.0)):
        y0, point = states[min(states, key=lambda a: abs(a - A))]
        q = p.replace(A=A)
        period = 2 * math.pi / q.rho
        n_periods, per = (128, 32) if quick else (512, 32)
        tau = np.arange(n_periods * per + 1) * period / per
        sim = simulate(q, tau[-1], y0, tau_out=tau)
        fig, axes = plt.subplots(3, 1, figsize=(8, 8))
        axes[0].plot(sim.tau, sim.x1, lw=0.5, color="k")
        axes[0].set_ylabel(r"$x_1$")
        axes[1].plot(sim.tau, sim.x2, lw=0.5, color="k")
        axes[1].set_ylabel(r"$x_2$")
        axes[1].set_xlabel(r"$\tau$")
        columns = {"tau": sim.tau, "x1": sim.x1, "x2": sim.x2}
        lines = []
        for signal, ls, label in ((sim.x1, "-", r"$x_1$"), (sim.x2, "--", r"$x_2$")):
            line = spectrum(signal[:-1], period / per, window=None)
            omega, amp = line.omega, line.amplitude
            axes[2].plot(omega, amp, ls, lw=0.8, label=label)
            lines.append((omega, amp))
        axes[2].set_xlim(0, 8 * q.rho)
        axes[2].set_yscale("log")
        axes[2].set_ylim(1e-8, None)
        axes[2].set_xlabel("angular frequency")
        axes[2].set_ylabel("FFT amplitude")
        axes[2].legend()
        fig.tight_layout()
        omega, amp = lines[0]
        top = omega[np.argsort(amp)[::-1][:2]] / q.rho
        values = {f"fig{number}_max_x1": float(np.max(np.abs(sim.x1)))}
        if number == "15":
            values["fig15_first_line_over_rho"] = float(min(top))
            values["fig15_second_line_over_rho"] = float(max(top))
        # spectral breadth: share of the x1 spectrum outside the harmonics of rho
        harmonic = np.zeros_like(omega, dtype=bool)
        for k in range(1, 40):
            harmonic |= np.abs(omega - k * q.rho) < 1.5 * (omega[1] - omega[0])
        broad = float(np.sum(amp[~harmonic] ** 2) / np.sum(amp**2))
        values[f"fig{number}_broadband_share"] = broad
        captions = {"15": "Periodic response given for small excitation amplitude A=0.00075; a) time "
                          "history of x1, b) time history of x2, c) Fast Fourier transform (FFT) of both signals.",
                    "16": "Periodic response given for intermediate excitation amplitude A=1.0475; a) time "
                          "history of x1, b) time history of x2, c) FFT for x1 time history (up), and for x2 "
                          "time history (down).",
                    "17": "periodic response given for large excitation amplitude A=2.0; a) time history of "
                          "x1, b) time history of x2, c) FFT for x1 time history (up), and for x2 time "
                          "history (down)."}
        results.append(Figure(number, captions[number], _save(fig, out, f"fig{number}", columns),
                              values, f"Reached by raising A at ρ = 0.513 from 0.00075, carrying the "
                              f"state (β = 10, δ = 0.1); steady motion {point.motion}; max|x1| = "
                              f"{values[f'fig{number}_max_x1']:.4f}; share of the x1 spectrum off the "
                              f"harmonics of ρ: {broad:.2e}."))
    return results


def slow_flow_max_x1(params, b1, b2):
    """max|x1| over a forcing period of the slow-flow steady states (B1, B2) (arrays): x1 from
    u1 = Re(B1 e^{i rho tau}), u2 = Re(B2 e^{3 i rho tau}) (eq 42, 45) through the modal
    matrix (eq 34)."""
    modal = linear_modes(params).modal
    phase = np.linspace(0, 2 * math.pi, 721)[:, None]
    return np.max(np.abs(modal[0, 0] * np.real(np.asarray(b1) * np.exp(1j * phase))
                         + modal[0, 1] * np.real(np.asarray(b2) * np.exp(3j * phase))), axis=0)


def full_model_fig12(out, quick=False):
    """Periodic orbits of the full equations (shooting) over the slow-flow curves of Fig 12."""
    slow = frequency_response(FIG12, (0.49, 0.53))
    full = periodic_response(FIG12.replace(rho=0.50), (0.50, 0.52))
    t = slow.table
    slow_x1 = slow_flow_max_x1(FIG12, t["re_B1"] + 1j * t["im_B1"], t["re_B2"] + 1j * t["im_B2"])
    fig, axes = plt.subplots(2, 1, sharex=True, figsize=(7, 7))
    for b in np.unique(t["branch"]):
        mask = t["branch"] == b
        _styled(axes[0], t["rho"][mask], slow_x1[mask], t["stable"][mask], "0.6")
    _styled(axes[0], full.table["rho"], full.table["max_x1"], full.table["stable"], "k")
    for sp in full.special_points:
        axes[0].plot(sp.rho, sp.max_x1, "o" if sp.kind == "fold" else "s", mfc="none", color="r")
    axes[0].set_ylabel(r"max $|x_1|$")
    mu = np.array([np.abs(full.table[f"mu{i}"]) for i in range(1, 5)])
    axes[1].plot(full.table["rho"], mu.max(axis=0), "-", color="k")
    axes[1].axhline(1, color="r", ls=":")
    axes[1].set_ylabel(r"max $|\mu|$ (Floquet)")
    axes[1].set_xlabel(r"$\rho$")
    fig.tight_layout()
    ns = sorted(sp.rho for sp in full.special_points if sp.kind == "neimark_sacker")
    folds = sorted(sp.rho for sp in full.special_points if sp.kind == "fold")
    values = {f"full_ns_rho_{i + 1}": r for i, r in enumerate(ns)}
    columns = {"rho": full.table["rho"], "max_x1": full.table["max_x1"], "stable": full.table["stable"],
               "max_abs_mu": mu.max(axis=0)}
    slow_hopf = sorted(sp.rho for sp in slow.special_points if sp.kind == "hopf")
    return Figure("12 (full model)", "Not in the paper: the periodic orbits of the full equations "
                  "(black; shooting, Floquet stability) over the slow-flow curves of Fig 12 (grey), "
                  "and the largest Floquet multiplier modulus.", _save(fig, out, "full_fig12", columns),
                  values, "Full-model folds at ρ = " + ", ".join(f"{f:.6f}" for f in folds)
                  + "; Neimark–Sacker points at ρ = " + ", ".join(f"{r:.6f}" for r in ns)
                  + " (the slow flow's Hopf points: " + ", ".join(f"{r:.6f}" for r in slow_hopf) + ").")


def impact_route(out, quick=False):
    """The route from small sloshing to impacts at rho = 0.513 (sec 4.2): periodic orbits
    continued in A, Poincare points of simulations carried along A, Lyapunov exponents."""
    p = FIG12.replace(rho=0.513)
    lower = periodic_response(p.replace(A=0.00075), A_range=(0.00075, 0.002))
    try:
        upper = periodic_response(p.replace(A=0.0011), A_range=(0.0011, 2.0),
                                  continuation=dataclasses.replace(
                                      PERIODIC_CONTINUATION, ds_max=0.05, max_points=3000))
    except SloshdynError as exc:          # a special point that could not be located
        upper = exc.partial
    a_values = np.concatenate([np.geomspace(0.00075, 1.0, 10 if quick else 30),
                               np.linspace(1.0, 2.0, 6 if quick else 21)[1:]])
    poincare_a, poincare_x1, lyap, sim_max = [], [], [], []
    y = np.zeros(4)
    steady = Steady(max_transient_periods=2000 if quick else 5000, window_periods=50 if quick else 100)
    for A in a_values:
        st = steady_state(p.replace(A=float(A)), y, steady=steady)
        y = st.y_end
        sim_max.append(st.max_x1)
        poincare_a.extend([A] * st.poincare.shape[1])
        poincare_x1.extend(st.poincare[0])
        lyap.append(lyapunov_exponent(p.replace(A=float(A)), y, lyapunov=Lyapunov(
            transient_periods=0, n_periods=200 if quick else 800)).exponent)
    fig, axes = plt.subplots(3, 1, sharex=True, figsize=(8, 9))
    for branch in (lower, upper):
        _styled(axes[0], branch.table["A"], branch.table["max_x1"], branch.table["stable"], "k")
        for sp in branch.special_points:
            marker = {"fold": "o", "neimark_sacker": "s", "period_doubling": "^", "branch_point": "d"}[sp.kind]
            axes[0].plot(sp.A, sp.max_x1, marker, mfc="none", color="r", ms=6)
    axes[0].plot(a_values, sim_max, "x", color="b", ms=4, label="simulation carried along A")
    axes[0].set_xscale("log")
    axes[0].set_ylabel(r"max $|x_1|$")
    axes[0].legend(fontsize=8)
    axes[1].plot(poincare_a, poincare_x1, ".", color="b", ms=1.5)
    axes[1].set_ylabel(r"$x_1$ at $\tau = kT$ (Poincaré)")
    axes[2].plot(a_values, lyap, "o-", color="k", ms=3)
    axes[2].axhline(0, color="0.6", lw=0.6)
    axes[2].set_ylabel("largest Lyapunov exponent")
    axes[2].set_xlabel("A")
    fig.tight_layout()
    first_loss = next((sp for sp in upper.special_points if sp.kind != "fold"), None)
    lower_fold = next((sp for sp in lower.special_points if sp.kind == "fold"), None)
    values = {"impact_route_lower_fold_A": lower_fold.A if lower_fold else float("nan")}
    if first_loss is not None:
        values["impact_route_first_ns_A"] = first_loss.A
    notes = ("At ρ = 0.513 the periodic response from small A loses stability at a fold at A = "
             f"{lower_fold.A:.6f} (max|x1| = {lower_fold.max_x1:.4f}) and jumps to the upper branch; "
             "along the upper branch: " + "; ".join(f"{sp.kind} at A = {sp.A:.4g} (max|x1| = "
                                                    f"{sp.max_x1:.3f})" for sp in upper.special_points)
             + (" (branch incomplete: " + upper.message + ")" if not upper.complete else "")
             + f". Lyapunov exponents along the carried simulation: largest {max(lyap):.3g} at A = "
             f"{a_values[int(np.argmax(lyap))]:.3g}.")
    files = _save(fig, out, "impact_route", {"A": a_values, "simulation_max_x1": sim_max,
                                             "lyapunov": lyap})
    write_csv(Path(out) / "impact_route_poincare.csv", {"A": poincare_a, "x1": poincare_x1})
    return Figure("15-17 (route to impacts)", "Not in the paper: the periodic orbits of the full "
                  "equations continued in A at ρ = 0.513 (solid stable, dashed unstable; circles "
                  "folds, squares Neimark–Sacker points), Poincaré points of simulations carried "
                  "along A, and the largest Lyapunov exponent.", files + ["impact_route_poincare.csv"],
                  values, notes)


#: the (beta, delta) study's summary (data/studies/make_impact_parameters.py writes it)
IMPACT_PARAMETERS = Path(__file__).parent / "reference" / "impact_parameters.csv"


def impact_parameters(out, quick=False):
    """Which impact coefficient and dissipation reproduce Fig 15-17 together: the stored
    (beta, delta) study of the continuation in A at rho = 0.513 (read, not recomputed)."""
    import csv
    with open(IMPACT_PARAMETERS, newline="") as f:
        rows = list(csv.DictReader(f))
    betas = np.unique([float(r["beta"]) for r in rows])
    deltas = np.unique([float(r["delta"]) for r in rows])

    def grid(name):
        g = np.full((len(betas), len(deltas)), np.nan)
        for r in rows:
            i, j = np.searchsorted(betas, float(r["beta"])), np.searchsorted(deltas, float(r["delta"]))
            g[i, j] = float(r[name])
        return g
    x16, x17, lyap = grid("max_x1_A_1.0475"), grid("max_x1_A_2"), grid("lyapunov_A_2")
    held = grid("fig15_holds") + grid("fig16_holds") + grid("fig17_holds")
    fig, axes = plt.subplots(2, 2, figsize=(11, 9), sharex=True, sharey=True)
    panels = ((axes[0, 0], x16, "max|x1| at A = 1.0475 (Fig 16: close to 1)", "viridis", None),
              (axes[0, 1], x17, "max|x1| at A = 2 (Fig 17: reaches 1)", "viridis", None),
              (axes[1, 0], lyap, "largest Lyapunov exponent at A = 2 [1/τ]", "coolwarm",
               np.nanmax(np.abs(lyap))),
              (axes[1, 1], held, "statements of the paper that hold (of 3)", "Greens", None))
    for ax, values, title, cmap, span in panels:
        mesh = ax.pcolormesh(deltas, betas, values, cmap=cmap, shading="nearest",
                             vmin=-span if span else (0 if values is held else None),
                             vmax=span if span else (3 if values is held else None))
        fig.colorbar(mesh, ax=ax)
        ax.set_title(title, fontsize=10)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.plot(0.1, 10.0, "*", color="r", ms=12, mfc="none", label="defaults β = 10, δ = 0.1")
    for ax in axes[1]:
        ax.set_xlabel("sloshing dissipation δ (dimensionless)")
    for ax in axes[:, 0]:
        ax.set_ylabel("impact coefficient β (dimensionless)")
    axes[0, 0].contour(deltas, betas, x16, levels=[0.8, 1.0], colors=["w", "r"], linewidths=1)
    axes[0, 1].contour(deltas, betas, x17, levels=[1.0], colors="r", linewidths=1)
    axes[1, 0].contour(deltas, betas, lyap, levels=[0.0], colors="k", linewidths=1)
    axes[0, 0].legend(fontsize=8, loc="lower left")
    fig.tight_layout()
    all_hold = grid("all_hold") == 1
    ib, jd = np.nonzero(all_hold)
    axes[1, 1].plot(deltas[jd], betas[ib], "o", color="k", mfc="none", label="all three hold")
    n_all = int(all_hold.sum())
    periodic16 = np.zeros_like(x16, dtype=bool)
    for r in rows:
        if r["motion_A_1.0475"] == "periodic":
            periodic16[np.searchsorted(betas, float(r["beta"])),
                       np.searchsorted(deltas, float(r["delta"]))] = True
    best = np.unravel_index(np.nanargmax(np.where((x16 < 1) & periodic16, x16, -1)), x16.shape)
    files = ["impact_parameters.png"]
    save_figure(fig, Path(out) / files[0])
    return Figure("15-17 (impact parameters)", "Not in the paper: the continuation in A at ρ = "
                  "0.513 (A = 0.00075 → 1.0475 → 2.0, state carried) over a log grid of the impact "
                  "coefficient β and the dissipation δ, which the paper does not give; white/red "
                  "contours: max|x1| = 0.8 and 1, black: Lyapunov exponent 0; star: the defaults.",
                  files, {"impact_parameters_all_hold": n_all},
                  f"All three statements (Fig 15: max|x1| of order 0.01; Fig 16: 0.8 ≤ max|x1| < 1 "
                  f"and periodic; Fig 17: max|x1| ≥ 1 and a positive Lyapunov exponent) hold at "
                  f"{n_all} of {len(rows)} grid points. The largest max|x1| of a periodic response "
                  f"without impact at A = 1.0475 is {x16[best]:.3f} (β = {betas[best[0]]:g}, "
                  f"δ = {deltas[best[1]]:g}), where max|x1| at A = 2 is {x17[best]:.3f}. "
                  "Data: data/reference/impact_parameters.csv (study: data/studies/"
                  "make_impact_parameters.py, Zarr store data/studies/impact_parameters.zarr).")


#: in the paper's order; each entry gives one Figure or a list of them
FIGURES = {"3": fig03, "4": fig04, "5": fig05, "6": fig06, "7": fig07, "8": fig08,
           "9a": fig09a, "9b": fig09b, "10": fig10, "11": fig11, "12": fig12, "13": fig13,
           "14": fig14, "15-17": fig15_17, "full-12": full_model_fig12, "impact-route": impact_route,
           "impact-parameters": impact_parameters}
