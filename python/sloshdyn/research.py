"""Research toolkit (issue 27): the Lyapunov spectrum of the full equations of motion (QR method
on the variational equations, Kaplan-Yorke dimension) and the continuation of the beats, the
limit cycles of the 3:1 slow flow, between their Hopf points. Computed by the Fortran core
(sloshdyn_lyapunov, sloshdyn_tank_lyapunov, sloshdyn_cycle_branch, sloshdyn_slowflow_cycles)."""

from __future__ import annotations

import dataclasses

from dataclasses import dataclass

import numpy as np

from . import _checks, _core, _tables
from ._cancel import cancellable
from ._errors import ConvergenceError, InputError, SloshdynError, check_status, message_text
from .asymptotics import (continuation_array, continuation_range, frequency_response,
                          slow_flow_cycle)
from .options import Continuation, Integration, Lyapunov
from .parameters import Parameters
from .spatial import _spatial_array

_bridge = _core.sloshdyn_bridge_research
KINDS = _tables.codes("special")
#: why a continuation stopped (sloshdyn_continuation's STOP_* codes)
_STOPS = {1: "lambda_min", 2: "lambda_max", 3: "max_points", 4: "closed", 5: "x_max", 6: "failed"}


@dataclass(frozen=True)
class LyapunovSpectrum:
    """The Lyapunov exponents of the full equations (per unit tau) from one start: four for the
    planar model, eight for the spatial one."""

    exponents: np.ndarray        #: l1 >= l2 >= ... (sorted in decreasing order)
    history: np.ndarray          #: (n, blocks): running estimates after each renormalisation
                                 #: (rows in the order of exponents)
    periods: np.ndarray          #: forcing periods measured at the end of each block
    kaplan_yorke: float          #: Kaplan-Yorke dimension of the sorted exponents
    method: str                  #: the integration method used ('auto' resolved)

    @property
    def sum(self):
        """l1 + .. + ln: the mean phase-space contraction rate (mean trace of the Jacobian)."""
        return float(np.sum(self.exponents))


def lyapunov_spectrum(params: Parameters, y0=None, *, lyapunov: Lyapunov = Lyapunov(),
                      integration: Integration = Integration(), spatial=False, azimuth=0.0,
                      ellipticity=0.0) -> LyapunovSpectrum:
    """All Lyapunov exponents per unit tau from y0 (default rest) by the QR method, sorted in
    decreasing order: the orbit and n tangent vectors of the variational equations,
    orthonormalised by modified Gram-Schmidt every renormalise_every forcing periods. The planar
    model (n = 4, y0 = x1, x1', x2, x2') or, with spatial=True, the spatial
    model (n = 8, y0 = x1, x1', x2, x2', y1, y1', y2, y2'; the ground motion along ``azimuth``
    and ``ellipticity`` times it across, as in sloshdyn.spatial.simulate), whose spectrum on a
    planar orbit holds the in-plane and the out-of-plane exponents. The first exponent is that
    of lyapunov_exponent (Benettin's method: the same start direction) once converged."""
    _checks.instance("params", params, Parameters)
    _checks.instance("lyapunov", lyapunov, Lyapunov)
    _checks.instance("integration", integration, Integration)
    n = 8 if _checks.flag("spatial", spatial) else 4
    y0 = np.zeros(n) if y0 is None else _checks.reals("y0", y0, (n,))
    blocks = max(lyapunov.n_periods // max(lyapunov.renormalise_every, 1), 1)
    exponents, history, dimension, status, message = cancellable(
        _bridge.lyapunov_spectrum, *params.array(), _spatial_array(azimuth, ellipticity), y0,
        lyapunov.array(), integration.array(), blocks)
    check_status(status, message, "Lyapunov spectrum")
    periods = lyapunov.renormalise_every * np.arange(1, blocks + 1, dtype=float)
    return LyapunovSpectrum(exponents, history, periods, float(dimension),
                            integration.method_used)


@dataclass(frozen=True)
class CycleSpecialPoint:
    """A bifurcation on the branch of slow-flow cycles: 'hopf' (an end: the cycle shrinks onto
    a steady state of the slow flow; beat_periods = rho/omega of the Hopf pair), 'fold' (of
    cycles), 'period_doubling' or 'neimark_sacker' (a torus of the slow flow: a 3-frequency
    motion of the full model)."""

    kind: str
    rho: float
    A: float
    beat_periods: float          #: the cycle's period in forcing periods T = 2 pi/rho
    x: np.ndarray                #: (Re B1, Im B1, Re B2, Im B2) on the cycle (at a Hopf point:
                                 #: the steady state)


@dataclass(frozen=True)
class SlowFlowCycles:
    """The branch of limit cycles of the 3:1 slow flow (the beats of the full motion, Fig 14),
    from one Hopf point towards the other, one row per point in the order of the parameter."""

    parameter: str               #: 'rho' or 'A'
    rho: np.ndarray
    A: np.ndarray
    period: np.ndarray           #: the cycle's period in tau
    beat_periods: np.ndarray     #: the same in forcing periods T = 2 pi/rho
    x: np.ndarray                #: (n, 4): (Re B1, Im B1, Re B2, Im B2) where Re B1 is largest
    multipliers: np.ndarray      #: (n, 4) complex Floquet multipliers (one is 1)
    stable: np.ndarray           #: bool: all but the trivial multiplier inside the unit circle
    amplitudes: np.ndarray       #: (n, 4): min|B1|, max|B1|, min|B2|, max|B2| over the cycle
    special_points: list         #: CycleSpecialPoint: the Hopf ends and what lies between
    ends: tuple                  #: (low end, high end): 'hopf', 'range end' or why the branch
                                 #: stopped ('failed: <the core's message>', 'max_points')
    method: str                         #: the integration method used ('auto' resolved)


def slow_flow_cycles(params: Parameters, rho_range=None, *, A_range=None,
                     continuation: Continuation = Continuation(ds=0.01, ds_max=0.05,
                                                               max_points=500, x_tol=1e-10,
                                                               f_tol=1e-9),
                     hopf_gap=1e-3,
                     integration: Integration = Integration(rtol=1e-10, atol=1e-13)
                     ) -> SlowFlowCycles:
    """The beats continued: the limit cycles of the 3:1 slow flow between two consecutive Hopf
    points of its steady states in rho_range (or A_range; a range end stands in for a missing
    Hopf point): the cycle is found at params' rho (or A) if that lies between them, else
    midway (sloshdyn.slow_flow_cycle), then followed
    both ways by pseudo-arclength continuation (single shooting, the period unknown, phase
    condition d(Re B1)/dtau = 0) with its Floquet multipliers, folds of cycles, period
    doublings and Neimark-Sacker points, up to hopf_gap times the Hopf interval before each
    Hopf point (at the Hopf point the cycle has shrunk to the steady state). continuation:
    ds, ds_min, ds_max, x_scale, max_points (per direction), x_tol, f_tol and max_iter are used;
    the arclength norm has the four amplitudes and the period relative to the start's. Newton
    (start, corrector, special points) stops at a step <= x_tol (1 + max|x|) and a residual
    max|y(T) - y0| <= f_tol, within max_iter iterations: f_tol must lie above the integration's
    error over a period (a shot of ~5000 tau at rtol 1e-10 leaves ~1e-11, so the
    continuation's default 1e-11 would make Newton miss by noise and the steps shrink).

    Raises ConvergenceError saying "no cycle" when the steady states have no Hopf point in the
    range (the slow flow settles to an equilibrium there) or no cycle is found between them."""
    _checks.instance("params", params, Parameters)
    _checks.instance("continuation", continuation, Continuation)
    _checks.instance("integration", integration, Integration)
    parameter, (lo, hi) = continuation_range(rho_range, A_range)
    hopf_gap = _checks.real("hopf_gap", hopf_gap)
    if not 0 < hopf_gap < 0.5:
        raise InputError(f"hopf_gap = {hopf_gap} is out of range: it must lie in (0, 0.5)")
    response = frequency_response(params, **{f"{parameter}_range": (lo, hi)})
    hopfs = sorted((s for s in response.special_points if s.kind == "hopf"),
                   key=lambda s: getattr(s, parameter))
    # the interval between consecutive Hopf points (or the range's ends) holding params' value,
    # else the first one bounded by two Hopf points
    here = getattr(params, parameter)
    bounds = [None] + hopfs + [None]
    value = [lo] + [getattr(h, parameter) for h in hopfs] + [hi]
    intervals = list(range(len(bounds) - 1))
    inside = [i for i in intervals if value[i] < here < value[i + 1]]
    paired = [i for i in intervals if bounds[i] is not None and bounds[i + 1] is not None]
    if not inside and not paired:
        raise ConvergenceError(
            f"no cycle: the slow flow settles to an equilibrium at {parameter} = {here} (outside "
            f"[{lo}, {hi}]) and its steady states have {len(hopfs)} Hopf point(s) in the range, "
            "no pair")
    i = (inside or paired)[0]
    low, high = bounds[i], bounds[i + 1]
    a, b = value[i], value[i + 1]
    start = params if a < here < b else params.replace(**{parameter: 0.5 * (a + b)})
    try:
        cycle = slow_flow_cycle(start, integration=integration)
    except SloshdynError as exc:
        raise ConvergenceError(
            f"no cycle: the slow flow from rest settles to an equilibrium at {parameter} = "
            f"{getattr(start, parameter)} (between the Hopf points or range ends {a} and {b}: "
            f"{exc})") from exc
    gap = hopf_gap * (b - a)
    a_end, b_end = a + (gap if low is not None else 0), b - (gap if high is not None else 0)
    halves = []
    for direction in (-1.0, 1.0):
        settings = continuation_array(continuation, direction)
        (points, multipliers, amplitudes, n, special, n_special, stop, status,
         message) = cancellable(_bridge.slow_flow_cycle_branch, *start.array(),
                                _tables.code("excitation_parameters", parameter), cycle.x,
                                cycle.period, a_end,
                                b_end, settings, integration.array(),
                                _checks.integer("max_points", continuation.max_points, 2), 50)
        if status and n == 0:
            check_status(status, message, "slow-flow cycle branch")
        text = message_text(message)
        halves.append((points[:, :n], multipliers[:, :n], amplitudes[:, :n],
                       special[:, :n_special], int(stop), text if status else ""))
    (p_lo, m_lo, a_lo, s_lo, stop_lo, why_lo), (p_hi, m_hi, a_hi, s_hi, stop_hi, why_hi) = halves
    rows = dict(zip(_tables.columns("cycle_branch"),
                    np.concatenate([np.vstack([p_lo, m_lo, a_lo])[:, ::-1],
                                    np.vstack([p_hi, m_hi, a_hi])[:, 1:]], axis=1)))
    x_names = ("re_B1", "im_B1", "re_B2", "im_B2")
    lam = rows["lambda"]
    rho = lam if parameter == "rho" else np.full(lam.shape, params.rho)
    A = lam if parameter == "A" else np.full(lam.shape, params.A)
    period = rows["period"]

    def special_point(kind, value, beat, x):
        r = value if parameter == "rho" else params.rho
        return CycleSpecialPoint(kind, float(r), float(value if parameter == "A" else params.A),
                                 float(beat), np.asarray(x, dtype=float))

    def hopf_point(h):
        value = getattr(h, parameter)
        r = value if parameter == "rho" else params.rho
        steady = response.table
        k = int(np.argmin(np.abs(steady[parameter] - value) + np.abs(steady["branch"] - h.branch)))
        x = [steady[c][k] for c in x_names]
        return special_point("hopf", value, r / h.frequency, x)

    def end(stop, bound, hopf, why):
        reason = _STOPS.get(stop, "failed")
        if reason == bound:
            return "hopf" if hopf is not None else "range end"
        return f"{reason}: {why}" if why else reason

    ends = (end(stop_lo, "lambda_min", low, why_lo), end(stop_hi, "lambda_max", high, why_hi))
    specials = [hopf_point(low)] if ends[0] == "hopf" else []
    found = sorted((dict(zip(_tables.columns("cycle_special_points"), s))
                    for s in np.concatenate([s_lo, s_hi], axis=1).T), key=lambda s: s["lambda"])
    for s in found:
        r = s["lambda"] if parameter == "rho" else params.rho
        specials.append(special_point(KINDS[int(s["kind"])], s["lambda"],
                                      s["period"] * r / (2 * np.pi), [s[c] for c in x_names]))
    if ends[1] == "hopf":
        specials.append(hopf_point(high))
    return SlowFlowCycles(parameter, rho, A, period, period * rho / (2 * np.pi),
                          np.column_stack([rows[c] for c in x_names]),
                          np.column_stack([rows[f"re_mu{i}"] + 1j * rows[f"im_mu{i}"]
                                           for i in range(1, 5)]),
                          rows["stable"] > 0.5,
                          np.column_stack([rows[c] for c in ("min_B1", "max_B1", "min_B2",
                                                             "max_B2")]),
                          specials, ends, integration.method_used)


def plot_beats(response, cycles: SlowFlowCycles):
    """The beats over the frequency response (Fig 12 with Fig 14's beat continued): the
    response curves of plotting.frequency_response (|u1|, |u2| = |B1|, |B2| of the steady
    states: modal amplitudes, x = P u, x1 = theta/theta0), the band min..max of |B1| and |B2| over each slow-flow
    cycle shaded between its Hopf points, and a third panel with the beat period in forcing
    periods T = 2 pi/rho."""
    from . import plotting    # the plot extra (matplotlib): only where a figure is drawn
    import matplotlib.pyplot as plt

    _checks.instance("cycles", cycles, SlowFlowCycles)
    base = plotting.frequency_response(response)
    fig, axes = plt.subplots(3, 1, sharex=True, figsize=(7, 8.4))
    for ax, old in zip(axes[:2], base.axes):
        for line in old.lines:
            ax.plot(line.get_xdata(), line.get_ydata(), ls=line.get_linestyle(),
                    marker=line.get_marker(), color=line.get_color(), mfc=line.get_mfc(),
                    ms=line.get_markersize(), lw=line.get_linewidth())
    plt.close(base)
    lam = cycles.rho if cycles.parameter == "rho" else cycles.A
    for ax, k, name in ((axes[0], 0, "B_1"), (axes[1], 2, "B_2")):
        ax.fill_between(lam, cycles.amplitudes[:, k], cycles.amplitudes[:, k + 1], color="C0",
                        alpha=0.35, lw=0, label=f"beat: min..max $|{name}|$ over the cycle")
        ax.set_ylabel(rf"$|{name}|$ [-] (modal, $x = P u$)")
        ax.legend(fontsize=8)
    axes[2].plot(lam, cycles.beat_periods, color="C0", lw=1.2)
    hopf = [s for s in cycles.special_points if s.kind == "hopf"]
    axes[2].plot([s.rho if cycles.parameter == "rho" else s.A for s in hopf],
                 [s.beat_periods for s in hopf], "s", mfc="none", color="r", ms=5,
                 label=r"Hopf: $\rho/\omega$")
    axes[2].set_ylabel("beat period\n[forcing periods]")
    axes[2].legend(fontsize=8)
    axes[2].set_xlabel(r"$\rho = \Omega/\omega$ [-]" if cycles.parameter == "rho"
                       else "A [-]")
    fig.tight_layout()
    return fig
