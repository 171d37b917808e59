"""Figures of simulations and sweeps (matplotlib; the Agg backend when there is no display).
Every function returns the matplotlib Figure; save it with fig.savefig(path)."""

from __future__ import annotations

import os

from ._extras import require

require("plot", "matplotlib")
import matplotlib  # noqa: E402

if not os.environ.get("DISPLAY") and not os.environ.get("MPLBACKEND"):
    matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .ground import DesignSpectrum  # noqa: E402

_LABELS = {"x1": r"$x_1 = \theta/\theta_0$", "x2": r"$x_2 = \varphi/\theta_0$",
           "u1": r"$u_1$", "u2": r"$u_2$", "theta": r"$\theta$ [rad]", "phi": r"$\varphi$ [rad]",
           "impact_force": r"impact force $\beta x_1^{2n-1}$"}


def signal(sim, name):
    """A named signal of a Simulation: x1, dx1, x2, dx2, u1, u2, theta, phi, impact_force."""
    table = {"x1": sim.y[0], "dx1": sim.y[1], "x2": sim.y[2], "dx2": sim.y[3], "u1": sim.u[0],
             "u2": sim.u[1], "theta": sim.theta, "phi": sim.phi, "impact_force": sim.impact_force}
    if name not in table:
        raise ValueError(f"signal {name!r} is not known; choose from {', '.join(table)}")
    return table[name]


def time_history(sim, names=("x1", "x2")):
    """One panel per signal against tau."""
    fig, axes = plt.subplots(len(names), 1, sharex=True, figsize=(8, 2.2 * len(names)),
                             squeeze=False)
    for ax, name in zip(axes[:, 0], names):
        ax.plot(sim.tau, signal(sim, name), lw=0.6, color="k")
        ax.set_ylabel(_LABELS.get(name, name))
    axes[-1, 0].set_xlabel(r"$\tau$")
    fig.tight_layout()
    return fig


def phase_plane(sim, coordinate="u1", poincare=None, rho=None):
    """The trajectory in the (q, q') plane of x1, x2, u1 or u2, with Poincare points (red):
    either given (shape (2, k)) or sampled from sim at tau = k 2 pi/rho."""
    q = signal(sim, coordinate)
    dq = np.gradient(q, sim.tau)
    fig, ax = plt.subplots(figsize=(5, 4.5))
    ax.plot(q, dq, lw=0.4, color="0.5")
    if poincare is None and rho:
        period = 2 * np.pi / rho
        k = np.round(sim.tau / period)
        on_section = np.isclose(sim.tau, k * period, rtol=0, atol=1e-9 * max(1.0, sim.tau[-1]))
        poincare = np.vstack([q[on_section], dq[on_section]])
    if poincare is not None:
        ax.plot(poincare[0], poincare[1], ".", color="r", ms=3, label="Poincaré section")
        ax.legend(loc="upper right")
    ax.set_xlabel(_LABELS.get(coordinate, coordinate))
    ax.set_ylabel(_LABELS.get(coordinate, coordinate).rstrip("$") + r"'$")
    fig.tight_layout()
    return fig


def spectrum(omega, amplitude, marks=(), label="amplitude", xmax=None):
    """An amplitude spectrum against angular frequency, with dotted lines at `marks`."""
    fig, ax = plt.subplots(figsize=(7, 3))
    ax.plot(omega, amplitude, lw=0.8, color="k")
    for w in marks:
        ax.axvline(w, ls=":", color="r", lw=0.8)
    ax.set_xlabel(r"angular frequency (per unit $\tau$)")
    ax.set_ylabel(label)
    if xmax:
        ax.set_xlim(0, xmax)
    fig.tight_layout()
    return fig


def sweep(sw, columns=("max_u1", "max_u2")):
    """Steady amplitudes along a sweep; the up and down halves of a 'both' sweep are drawn
    with different markers so jumps show."""
    values = sw.values
    turn = int(np.argmax(values))          # the up half ends at the largest value
    fig, axes = plt.subplots(len(columns), 1, sharex=True, figsize=(7, 2.6 * len(columns)),
                             squeeze=False)
    for ax, column in zip(axes[:, 0], columns):
        y = sw.column(column)
        if turn > 0:
            ax.plot(values[:turn + 1], y[:turn + 1], "o-", ms=3, color="k", label="up")
        if turn < len(values) - 1:
            ax.plot(values[turn:], y[turn:], "s--", ms=3, mfc="none", color="b", label="down")
        ax.legend()
        ax.set_ylabel(column.replace("max_", "max |") + "|")
    axes[-1, 0].set_xlabel(r"$\rho$" if sw.parameter == "rho" else "A")
    fig.tight_layout()
    return fig


def frequency_response(response, columns=("a1", "a2"), simulation=None):
    """Response curves as in the paper: stable branches solid, unstable dashed; folds as
    circles, Hopf points as squares; optional direct-simulation points (a Sweep) as crosses."""
    labels = {"a1": r"$|u_1|$", "a2": r"$|u_2|$"}
    fig, axes = plt.subplots(len(columns), 1, sharex=True, figsize=(7, 2.8 * len(columns)),
                             squeeze=False)
    names = {"-": "stable", "--": "unstable", "fold": "fold", "hopf": "Hopf point"}
    for ax, column in zip(axes[:, 0], columns):
        named = set()           # each kind of curve named once in the legend

        def label(kind):
            first = kind not in named
            named.add(kind)
            return names.get(kind, kind) if first else "_nolegend_"

        for branch in response.branches:
            x, y, stable = branch["lambda"], branch[column], branch["stable"] > 0
            # split into runs of equal stability, sharing the boundary point
            start = 0
            for k in range(1, len(x) + 1):
                if k == len(x) or stable[k] != stable[start]:
                    end = min(k + 1, len(x))
                    style = "-" if stable[start] else "--"
                    ax.plot(x[start:end], y[start:end], style, color="k", lw=1.0,
                            label=label(style))
                    start = k
        for s in response.special_points:
            value = getattr(s, column)
            ax.plot(s.rho if response.parameter == "rho" else s.A, value,
                    "o" if s.kind == "fold" else "s", mfc="none", color="r", ms=5,
                    label=label(s.kind))
        if simulation is not None:
            ax.plot(simulation.values, simulation.column("max_" + column.replace("a", "u")), "x",
                    color="b", ms=4, label="direct simulation")
        ax.legend(fontsize=8)
        ax.set_ylabel(labels.get(column, column))
    axes[-1, 0].set_xlabel(r"$\rho$" if response.parameter == "rho" else "A")
    fig.tight_layout()
    return fig


def routh_delta3(response, zoom=None):
    """Delta3 of eq (55) along the branches (Fig 13); Hopf points marked. zoom = (lo, hi)
    limits the horizontal axis."""
    fig, ax = plt.subplots(figsize=(7, 3))
    for branch in response.branches:
        ax.plot(branch["lambda"], branch["delta3"], "-", color="k", lw=1.0)
    for s in response.special_points:
        if s.kind == "hopf":
            ax.axvline(s.rho if response.parameter == "rho" else s.A, ls=":", color="r")
    ax.axhline(0, color="0.6", lw=0.6)
    ax.set_xlabel(r"$\rho$" if response.parameter == "rho" else "A")
    ax.set_ylabel(r"$\Delta_3$")
    if zoom:
        ax.set_xlim(*zoom)
    ax.xaxis.set_major_locator(matplotlib.ticker.MaxNLocator(5))   # labels side by side
    fig.tight_layout()
    return fig


# ---- a tank in SI units ------------------------------------------------------------------------

_G = 9.80665   # m/s^2 per g, for axes in g


def _tank_title(tank):
    plan = (f"tank R = {tank.radius:g} m" if tank.shape == "circular" else
            f"rectangular tank L = {tank.length:g} m, W = {tank.width:g} m")
    return (f"{plan}, liquid depth {tank.liquid_depth:g} m, freeboard "
            f"{tank.freeboard:g} m; sloshing period {tank.sloshing_period:.3g} s")


def seismic(response, loads=("wave_height", "base_shear", "overturning_moment")):
    """A SeismicResponse for a report: the ground acceleration [g] on top, then each load
    against t [s] in SI units (forces in kN, moments in kN m), the roof at +-freeboard on the
    wave height, and each peak marked; the legends stand right of the panels, off the curves."""
    units = {"wave_height": ("wave height at the wall [m]", 1.0),
             "sloshing_displacement": ("sloshing displacement [m]", 1.0),
             "pendulum_angle": ("pendulum angle [rad]", 1.0),
             "tank_drift": ("tank drift [m]", 1.0),
             "tank_acceleration": ("tank acceleration [m/s^2]", 1.0),
             "convective_acceleration": ("convective acceleration [m/s^2]", 1.0),
             "impact_force": ("impact force, the paper's model [kN]", 1e-3),
             "base_shear": ("base shear [kN]", 1e-3),
             "overturning_moment": ("overturning moment [kN m]", 1e-3),
             "overturning_moment_ibp": ("moment incl. base pressure [kN m]", 1e-3)}
    for load in loads:
        if load not in units:
            raise ValueError(f"load {load!r} is not known; choose from {', '.join(units)}")
    fig, axes = plt.subplots(len(loads) + 1, 1, sharex=True,
                             figsize=(10.5, 1.9 * (len(loads) + 1) + 0.6))
    t = response.t
    axes[0].plot(t, response.ground_acceleration / _G, lw=0.6, color="0.3")
    axes[0].set_ylabel("ground\nacceleration [g]")
    for ax, load in zip(axes[1:], loads):
        label, factor = units[load]
        ax.plot(t, getattr(response, load) * factor, lw=0.7, color="k",
                label="with the roof" if load == "wave_height" else None)
        peak, when = response.peaks[load]
        k = int(np.argmin(np.abs(t - when)))
        unit = label[label.index("[") + 1:-1]
        ax.plot(when, getattr(response, load)[k] * factor, "o", mfc="none", color="r", ms=6,
                label=f"peak {peak * factor:.4g} {unit} at {when:.3g} s")
        if load == "wave_height":
            # the free wave (no roof) is what the roof verdict and the roof loads judge
            ax.plot(t, response.free_wave_height, lw=0.7, color="tab:orange", alpha=0.8,
                    label=f"free wave (no roof), peak "
                          f"{response.peak_table['free_wave_height']:.4g} m")
            for sign in (1, -1):
                ax.axhline(sign * response.tank.freeboard, ls="--", color="b", lw=0.8,
                           label="roof (freeboard)" if sign > 0 else None)
        ax.set_ylabel(label.replace(" [", "\n["))
        ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0, fontsize=8)
    axes[-1].set_xlabel("time t [s]")
    axes[0].set_title(_tank_title(response.tank) + "\n" + _ground_title(response), fontsize=9)
    fig.tight_layout()
    return fig


def _ground_title(response):
    """The run's traceability: the record, its scale factor, PGA and Sa at the sloshing
    period (0.5 %) as run, and the beta-sensitivity warning."""
    p = response.peak_table
    name = response.ground_motion.name or response.ground_motion.kind
    text = (f"{name}: scale factor {p['scale_factor']:.4g}, PGA "
            f"{p['peak_ground_acceleration'] / _G:.4g} g, Sa({response.tank.sloshing_period:.3g} s, "
            f"0.5 %) {p['sa_sloshing_period'] / _G:.4g} g\nroof "
            f"{'reached' if response.roof_reached else 'not reached'} (free wave)")
    if response.roof_reached:
        text += (f": uplift {p['roof_uplift_force'] / 1e3:.4g} kN, confined convective mass "
                 f"{p['confined_convective_mass'] / 1e3:.4g} t")
    if response.beta_sensitive:
        text += "; the paper's impact model is sensitive to beta and delta"
    return text


def response_spectrum(spectrum, marks=()):
    """A response spectrum: pseudo-spectral acceleration [g] and displacement [m] against the
    period [s]; dotted lines at the periods in `marks` (e.g. the sloshing period)."""
    fig, axes = plt.subplots(2, 1, sharex=True, figsize=(7, 5))
    axes[0].plot(spectrum.periods, spectrum.psa / _G, color="k", lw=1)
    axes[0].set_ylabel("pseudo-spectral\nacceleration [g]")
    axes[1].plot(spectrum.periods, spectrum.sd, color="k", lw=1)
    axes[1].set_ylabel("spectral\ndisplacement [m]")
    for ax in axes:
        for period in marks:
            ax.axvline(period, ls=":", color="r", lw=0.8)
    axes[1].set_xlabel("period T [s]")
    axes[0].set_title(f"response spectrum, {100 * spectrum.damping:g} % damping", fontsize=10)
    fig.tight_layout()
    return fig


# ---- studies -------------------------------------------------------------------------------

_MOTION_COLOURS = {0: "0.85", 1: "#4c72b0", 2: "#dd8452", 3: "#c44e52", 4: "#8172b3"}


def _axis_label(coord):
    """An axis label with its unit from a study coordinate's attributes."""
    name = coord.attrs.get("long_name", coord.name)
    units = coord.attrs.get("units", "1")
    return f"{name} [{'-' if units == '1' else units}]"


def response_map(ds, variable="max_x1"):
    """A response map (sloshdyn.response_map): the steady amplitude (colour, log scale) and the
    kind of motion in the (frequency, amplitude) plane, roof impacts marked (x); where the
    sweeps carried up and down in frequency (continuation) differ from the state reached from
    rest by more than 10 %, the points are marked (up: triangles up, down: down): there the
    response is multi-valued (hysteresis), the sweep having stayed on another branch."""
    from matplotlib.colors import BoundaryNorm, ListedColormap, LogNorm
    from matplotlib.patches import Patch
    f, a = ds["frequency"], ds["amplitude"]
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True)
    value = np.ma.masked_invalid(ds[variable].values.T)
    positive = value.compressed()[value.compressed() > 0]
    norm = LogNorm(positive.min(), positive.max()) if positive.size and positive.min() < positive.max() else None
    mesh = axes[0].pcolormesh(f, a, value, shading="nearest", norm=norm, cmap="viridis")
    fig.colorbar(mesh, ax=axes[0], label=f"{variable.replace('max_', 'max |')}| [-]")
    codes = sorted(_MOTION_COLOURS)
    cmap = ListedColormap([_MOTION_COLOURS[c] for c in codes])
    motion = np.where(ds["motion"].values < 0, 0, ds["motion"].values).T
    axes[1].pcolormesh(f, a, motion, shading="nearest", cmap=cmap,
                       norm=BoundaryNorm(np.arange(len(codes) + 1) - 0.5, len(codes)))
    meanings = ds["motion"].attrs.get("flag_meanings", "").split()
    flags = ds["motion"].attrs.get("flag_values", [])
    names = dict(zip(flags, meanings))
    handles = [Patch(color=_MOTION_COLOURS[c], label=names.get(c, str(c)).replace("_", "-"))
               for c in codes if (motion == c).any()]
    if "roof_impact" in ds:
        hit = ds["roof_impact"].values.T == 1
        if hit.any():
            ff, aa = np.meshgrid(f, a)
            for ax in axes:
                ax.plot(ff[hit], aa[hit], "x", color="k", ms=4)
            handles.append(plt.Line2D([], [], ls="", marker="x", color="k", label="roof impact"))
    ff, aa = np.meshgrid(f, a)
    for direction, marker in (("up", "^"), ("down", "v")):
        other = f"{variable}_{direction}"
        if other in ds:
            differs = (np.abs(ds[other].values - ds[variable].values)
                       > 0.1 * np.abs(ds[variable].values)).T
            for ax in axes:
                ax.plot(ff[differs], aa[differs], marker, mfc="none", ms=7,
                        color="w" if ax is axes[0] else "k")
            handles.append(plt.Line2D([], [], ls="", marker=marker, mfc="none", color="k",
                                      label=f"sweep {direction} on another branch"))
    axes[1].legend(handles=handles, loc="upper left", fontsize=8)
    for ax in axes:
        ax.set_xlabel(_axis_label(f))
    axes[0].set_ylabel(_axis_label(a))
    axes[0].set_title(f"steady {variable.replace('max_', 'max |')}|")
    axes[1].set_title("kind of motion")
    fig.tight_layout()
    return fig


def harmonic_sweep(sweep):
    """A HarmonicSweep: the largest wave height at the wall [m] against the frequency [Hz],
    the roof at the freeboard and the free wave (no roof) that the roof verdict judges; up and
    down halves drawn apart so jumps show."""
    f = sweep.frequency
    turn = int(np.argmax(f))
    fig, ax = plt.subplots(figsize=(7, 3.4))
    ax.plot(f[:turn + 1], sweep.wave_height[:turn + 1], "o-", ms=3, color="k",
            label="frequency up")
    if turn < len(f) - 1:
        ax.plot(f[turn:], sweep.wave_height[turn:], "s--", ms=3, mfc="none", color="b",
                label="frequency down")
    ax.plot(f[:turn + 1], sweep.free_wave_height[:turn + 1], "-", lw=0.8, color="tab:orange",
            label="free wave (no roof): the roof verdict")
    ax.axhline(sweep.tank.freeboard, ls="--", color="r", lw=0.8, label="roof (freeboard)")
    ax.axvline(1 / sweep.tank.sloshing_period, ls=":", color="0.5", lw=0.8,
               label="linear sloshing frequency")
    ax.set_xlabel("ground motion frequency [Hz]")
    ax.set_ylabel("largest wave height\nat the wall [m]")
    ax.set_title(f"{_tank_title(sweep.tank)}\nharmonic ground motion, peak "
                 f"{sweep.peak_ground_acceleration[0] / _G:.3g} g", fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def basins(ds):
    """Basins of attraction (sloshdyn.basins): the attractor reached from each initial state,
    with the attractors' orbit states (phase 0) marked and listed with kind, period,
    stability and share of the grid."""
    from matplotlib.colors import BoundaryNorm, ListedColormap
    from matplotlib.patches import Patch
    labels = ds["attractor"].values
    n = int(ds.sizes.get("attractor_id", 0))
    palette = ["0.85"] + [plt.get_cmap("tab10")(k % 10) for k in range(max(n, 1))]
    fig, ax = plt.subplots(figsize=(6.5, 5))
    ax.pcolormesh(ds["x1"], ds["dx1"], labels.T, shading="nearest",
                  cmap=ListedColormap(palette[:n + 1]),
                  norm=BoundaryNorm(np.arange(n + 2) - 0.5, n + 1))
    handles = []
    for j in range(1, n + 1):
        kind = str(ds["attractor_kind"].values[j - 1])
        period = int(ds["attractor_period"].values[j - 1])
        text = f"{j}: {kind}" + (f" {period}T, {ds['attractor_stability'].values[j - 1]}"
                                 if kind == "periodic" else "")
        text += f", {100 * float(ds['attractor_share'].values[j - 1]):.0f} %"
        handles.append(Patch(color=palette[j], label=text))
        state = ds["attractor_state"].values[j - 1]
        if np.isfinite(state[:2]).all():
            ax.plot(state[0], state[1], "*", ms=14, mec="k", mfc=palette[j])
    ax.legend(handles=handles, fontsize=8, loc="upper right", title="attractor (★ orbit at phase 0)")
    ax.set_xlabel(_axis_label(ds["x1"]))
    ax.set_ylabel(_axis_label(ds["dx1"]))
    ax.set_title(rf"basins at $\rho$ = {json_value(ds, 'rho'):g}, A = {json_value(ds, 'A'):g}")
    fig.tight_layout()
    return fig


def json_value(ds, name):
    import json
    return json.loads(ds.attrs["parameters"])[name]


def fragility(fit, intensities=None, failures=None, units="g", label="intensity measure"):
    """A lognormal fragility curve (sloshdyn.fit_fragility) with its median and dispersion,
    the runs (0/1, slightly jittered) and the observed fraction at each intensity."""
    fig, ax = plt.subplots(figsize=(6.5, 4))
    upper = fit.median * np.exp(3 * fit.beta)
    if intensities is not None:
        upper = max(upper, float(np.max(intensities)))
    x = np.linspace(upper / 500, upper, 400)
    ax.plot(x, fit.probability(x), "-", color="k",
            label=rf"lognormal fit: median {fit.median:.3g} {units}, $\beta$ = {fit.beta:.2f}")
    if intensities is not None and failures is not None:
        xi = np.asarray(intensities, float)
        yi = np.asarray(failures, float)
        jitter = (np.random.default_rng(0).random(yi.size) - 0.5) * 0.04
        ax.plot(xi, yi + jitter, "o", ms=3, mfc="none", color="0.5", label="runs (0/1)")
        levels = np.unique(xi)
        ax.plot(levels, [yi[xi == v].mean() for v in levels], "s", color="r", ms=5,
                label="fraction at each level")
    ax.axvline(fit.median, ls=":", color="k", lw=0.8)
    ax.set_xlabel(f"{label} [{units}]")
    ax.set_ylabel("probability of roof impact [-]")
    ax.set_ylim(-0.05, 1.05)
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    return fig


# ---- stability charts ----------------------------------------------------------------------------

_CURVE_STYLE = {"fold": dict(color="k", ls="-", label="fold"),
                "hopf": dict(color="r", ls="--", label="Hopf"),
                "period_doubling": dict(color="b", ls="-.", label="period doubling"),
                "neimark_sacker": dict(color="m", ls=":", label="Neimark-Sacker")}
_CODIM2_MARKER = {"cusp": "^", "bogdanov_takens": "s", "fold_hopf": "D", "generalised_hopf": "o",
                  "resonance_1_1": "v", "resonance_1_2": "P", "fold_flip": "X"}
_AXIS_LABEL = {"rho": r"$\rho = \Omega/\omega$", "A": r"$A = u_0/L$", "gamma": r"$\gamma$",
               "kappa": r"$\kappa$"}


def stability_chart(chart, tank=None):
    """A StabilityChart: the cells shaded by their number of stable steady states (the number
    printed in each), the fold / Hopf (/ period-doubling / Neimark-Sacker) curves, the
    codimension-2 points, and, where brute force was run, a red cross on every cell away from
    the curves whose brute-force count differs. With a tank (a chart in rho and A of its
    model), the axes are the ground motion's frequency [Hz] and peak acceleration [g]."""
    from matplotlib.colors import BoundaryNorm, ListedColormap

    def xy(point_or_curve):
        x, y = getattr(point_or_curve, chart.x), getattr(point_or_curve, chart.y)
        if tank is not None:
            return chart.frequency_and_acceleration(tank, point_or_curve.rho, point_or_curve.A)
        return x, y

    if tank is not None and (chart.x, chart.y) != ("rho", "A"):
        raise ValueError("a chart in Hz and g needs x = 'rho' and y = 'A'")
    grid = chart.grid
    fig, ax = plt.subplots(figsize=(8, 5.5))
    columns = np.unique(grid[chart.x])
    rows = np.unique(grid[chart.y])
    counts = grid["n_stable"].reshape(len(rows), len(columns))
    top = int(max(counts.max(), 2))
    cmap = ListedColormap(plt.cm.Blues(np.linspace(0.08, 0.55, top + 1)))
    norm = BoundaryNorm(np.arange(-0.5, top + 1.5), cmap.N)

    class Cell:          # the cell centres as points, for xy()
        pass
    for k in range(len(grid["rho"])):
        cell = Cell()
        cell.rho, cell.A, cell.gamma, cell.kappa = (grid[name][k] for name in
                                                    ("rho", "A", "gamma", "kappa"))
        gx, gy = xy(cell)
        ax.text(gx, gy, f"{int(grid['n_stable'][k])}", ha="center", va="center", fontsize=6,
                color="0.35")
        if grid["brute_force_stable"][k] >= 0 and not grid["near_curve"][k] and \
                grid["brute_force_stable"][k] != grid["n_stable"][k]:
            ax.plot(gx, gy, "x", color="r", ms=7)
    if tank is None:
        dx = (columns[1] - columns[0]) if len(columns) > 1 else 1.0
        dy = (rows[1] - rows[0]) if len(rows) > 1 else 1.0
        edges_x = np.concatenate([columns - dx / 2, [columns[-1] + dx / 2]])
        edges_y = np.concatenate([rows - dy / 2, [rows[-1] + dy / 2]])
        mesh = ax.pcolormesh(edges_x, edges_y, counts, cmap=cmap, norm=norm, shading="flat")
    else:
        cx, cy = chart.frequency_and_acceleration(tank, grid["rho"], grid["A"])
        mesh = ax.scatter(cx, cy, c=grid["n_stable"], cmap=cmap, norm=norm, marker="s", s=60)
    full = chart.model == "full"
    fig.colorbar(mesh, ax=ax, ticks=range(top + 1),
                 label="stable periodic orbits (branch from rest)" if full
                 else "stable steady states")
    shown = set()
    for curve in chart.curves:
        style = dict(_CURVE_STYLE[curve.kind])
        if curve.kind in shown:
            style.pop("label")
        shown.add(curve.kind)
        cx, cy = xy(curve)
        ax.plot(cx, cy, lw=1.2, **style)
        if not curve.complete:
            ax.plot(cx[-1], cy[-1], "*", color="orange", ms=10)
    for kind in sorted({p.kind for p in chart.codim2_points}):
        points = [p for p in chart.codim2_points if p.kind == kind]
        px = [xy(p)[0] for p in points]
        py = [xy(p)[1] for p in points]
        ax.plot(px, py, _CODIM2_MARKER.get(kind, "o"), mfc="w", mec="k", ms=7,
                label=kind.replace("_", " "))
    if any(grid["brute_force_stable"] >= 0):
        ax.plot([], [], "x", color="r", label="brute force differs")
    if tank is None:
        ax.set_xlabel(_AXIS_LABEL[chart.x])
        ax.set_ylabel(_AXIS_LABEL[chart.y])
        ax.set_title("stability chart: periodic orbits of the full model" if full else
                     f"stability chart of the slow flow ({chart.model})", fontsize=10)
    else:
        ax.set_xlabel("ground motion frequency [Hz]")
        ax.set_ylabel("peak ground acceleration [g]")
        ax.set_title(f"{_tank_title(tank)}\nstability chart ({chart.model})", fontsize=10)
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    return fig


def design_spectrum(spectra, damping_ratios=(0.05, 0.005), t_max=10.0):
    """Design spectra (a sloshdyn.DesignSpectrum or a list of them), Sa [g] against the period
    T [s] up to t_max, one curve per spectrum and damping ratio (EN 1998-1's elastic spectrum
    beyond 4 s by its informative Annex A)."""
    spectra = [spectra] if isinstance(spectra, DesignSpectrum) else list(spectra)
    fig, ax = plt.subplots(figsize=(7, 4))
    for spec in spectra:
        t = np.linspace(0, t_max, 1001)
        for ratio in damping_ratios:
            ax.plot(t, spec.sa(t, damping_ratio=ratio), label=f"{spec.label}, {100 * ratio:g} %")
    ax.set_xlabel("period T [s]")
    ax.set_ylabel("spectral acceleration Sa [g]")
    ax.set_xlim(0, t_max)
    ax.set_ylim(bottom=0)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small")
    fig.tight_layout()
    return fig
