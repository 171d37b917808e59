"""The calc sheet's figures (issue 39), drawn from the CSV files of the run's directory only:
the ground motion, its spectra (with the design spectrum), the wave against the freeboard, the
loads, the design spectrum of a design check and the wall pressure; every axis with its unit."""

from __future__ import annotations

from ._files import save_figure
from .report_layout import STANDARD_GRAVITY, number
from .report_tables import columns as _columns, one_row, split_name


def draw_figures(out, spatial, freeboard, seismic=True, motion=True):
    """The sheet's figures, from the CSV files in `out`: [(file, caption)]. With a ground
    motion (motion): its spectra (and the design spectrum over them); with the nonlinear run
    (seismic): the ground acceleration, the wave and the loads over time; without a ground
    motion, the design spectrum; and the wall pressure of the design check."""
    import matplotlib    # the plot extra: only where the sheet draws its figures
    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    figures = []
    if seismic:
        figures.append(_ground_motion_figure(out, spatial, plt))
    if motion:
        figures.append(_spectrum_figure(out, plt))
    elif (out / "design_spectrum.csv").exists():
        figures.append(_design_spectrum_figure(out, plt))
    if seismic:
        figures += _run_figures(out, spatial, freeboard, plt)
    if (out / "wall_pressure.csv").exists():
        figures.append(_pressure_figure(out / "wall_pressure.csv", plt))
    for name, fig, _ in figures:
        save_figure(fig, out / name)
    return [(name, caption) for name, _, caption in figures]


def _series(out, spatial):
    return _columns(out / ("seismic_spatial.csv" if spatial else "seismic.csv"))


def _ground_motion_figure(out, spatial, plt):
    """The ground acceleration [g] over t [s] (both components for the spatial run)."""
    series = _series(out, spatial)
    t = series["t [s]"]
    fig, ax = plt.subplots(figsize=(8, 3), layout="constrained")
    if spatial:
        ax.plot(t, series["ground_acceleration_x [m/s^2]"] / STANDARD_GRAVITY, lw=0.7,
                label="x component")
        ax.plot(t, series["ground_acceleration_y [m/s^2]"] / STANDARD_GRAVITY, lw=0.7,
                label="y component")
        fig.legend(loc="outside upper center", ncols=2, fontsize="small")
    else:
        ax.plot(t, series["ground_acceleration [m/s^2]"] / STANDARD_GRAVITY, lw=0.7)
    ax.set(xlabel="t [s]", ylabel="ground acceleration [g]")
    ax.grid(alpha=0.3)
    return "ground_motion.png", fig, "Ground acceleration (as scaled) over time."


def _spectrum_figure(out, plt):
    """The ground motion's pseudo-acceleration spectra with its Sa at the sloshing period, and
    the design spectrum where the run wrote one."""
    spectrum = _columns(out / "spectrum.csv")
    motion = _columns(out / "motion.csv")
    fig, ax = plt.subplots(figsize=(8, 3.5), layout="constrained")
    for column in spectrum:
        if column.startswith("sa_"):
            ax.plot(spectrum["period [s]"], spectrum[column] / STANDARD_GRAVITY,
                    label=f"{split_name(column)[0][3:]} damping")
    if (out / "design_spectrum.csv").exists():
        _plot_design_spectrum(ax, out, "--", "design, ")
    period = float(motion["sloshing_period [s]"][0])
    ax.axvline(period, color="grey", lw=0.8, ls=":")
    ax.plot(period, float(motion["sa_sloshing_period [m/s^2]"][0]) / STANDARD_GRAVITY, "ko",
            ms=4, label=f"sloshing period {number(period)} s")
    ax.set(xlabel="T [s]", ylabel="Sa [g]", xscale="log")
    ax.grid(alpha=0.3, which="both")
    fig.legend(loc="outside upper center", ncols=4, fontsize="small")
    return "spectrum.png", fig, ("Pseudo-acceleration spectra of the ground motion (first "
                                 "component, as scaled).")


def _run_figures(out, spatial, freeboard, plt):
    """The wave at the wall against the freeboard, and the loads, over time."""
    series = _series(out, spatial)
    t = series["t [s]"]
    figures = []

    fig, ax = plt.subplots(figsize=(8, 3.5), layout="constrained")
    ax.plot(t, series["wave_height [m]"], lw=0.8,
            label="wave height at the wall" + (" (largest over the wall)" if spatial else ""))
    if "free_wave_height [m]" in series:
        ax.plot(t, series["free_wave_height [m]"], lw=0.8, alpha=0.7,
                label="free wave (no roof)")
    ax.axhline(freeboard, color="r", ls="--", lw=1, label=f"freeboard {number(freeboard)} m")
    ax.set(xlabel="t [s]", ylabel="wave height [m]")
    ax.grid(alpha=0.3)
    fig.legend(loc="outside upper center", ncols=3, fontsize="small")
    figures.append(("wave.png", fig, "Wave height at the wall against the freeboard."))

    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 5), sharex=True, layout="constrained")
    top.plot(t, series["base_shear [N]"] / 1e6, lw=0.8)
    top.set(ylabel="base shear [MN]")
    bottom.plot(t, series["overturning_moment [N m]"] / 1e6, lw=0.8, color="C1")
    bottom.set(xlabel="t [s]", ylabel="overturning moment [MN m]")
    for ax in (top, bottom):
        ax.grid(alpha=0.3)
    figures.append(("loads.png", fig, "Base shear and overturning moment over time"
                                      + (" (resultants)." if spatial else ".")))
    return figures


def _pressure_figure(path, plt):
    """Every pressure column [kPa] against the height column [m] of wall_pressure.csv."""
    table = _columns(path)
    height = next(c for c in table if split_name(c)[1] == "m")
    fig, ax = plt.subplots(figsize=(6, 5), layout="constrained")
    for column in table:
        if split_name(column)[1] == "Pa":
            ax.plot(table[column] / 1e3, table[height], label=split_name(column)[0])
    ax.set(xlabel="pressure [kPa]", ylabel=f"{split_name(height)[0]} [m]")
    ax.grid(alpha=0.3)
    fig.legend(loc="outside upper center", ncols=2, fontsize="small")
    return "wall_pressure.png", fig, "Hydrodynamic wall pressure over the height."


def _plot_design_spectrum(ax, out, style, prefix):
    """design_spectrum.csv's Sa [g] columns (one per damping) over the period, on ax."""
    table = _columns(out / "design_spectrum.csv")
    for column in table:
        if split_name(column)[1] == "g":
            damping = split_name(column)[0][3:].replace("_percent", " %")
            ax.plot(table["period [s]"], table[column], style,
                    label=f"{prefix}{damping} damping")


def _design_spectrum_figure(out, plt):
    """The code spectrum of the design check (design_spectrum.csv) with the tank's first
    sloshing period (tank.csv): [(file, figure, caption)]."""
    period = one_row(out / "tank.csv")["sloshing_period [s]"]
    fig, ax = plt.subplots(figsize=(8, 3.5), layout="constrained")
    _plot_design_spectrum(ax, out, "-", "")
    ax.axvline(period, color="grey", lw=0.8, ls=":", label=f"sloshing period {number(period)} s")
    ax.set(xlabel="T [s]", ylabel="Sa [g]", xscale="log")
    ax.grid(alpha=0.3, which="both")
    fig.legend(loc="outside upper center", ncols=3, fontsize="small")
    return "design_spectrum.png", fig, "The code's elastic design spectrum of the check."
