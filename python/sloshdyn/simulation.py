"""Direct simulation of the full equations (eq 15 with 29-31) by the Fortran integrators:
time histories, Poincare sections, steady states and sweeps, and amplitude spectra."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from . import _checks, _core, _tables
from ._cancel import cancellable
from ._errors import InputError, IntegrationError, check_status
from .options import Integration, Steady
from .parameters import Parameters

_bridge = _core.sloshdyn_bridge_simulation
MOTIONS = _tables.codes("motion")
METHODS = {name: code for code, name in _tables.codes("methods").items()}
SUMMARY_COLUMNS = _tables.columns("summary")


@dataclass(frozen=True)
class Simulation:
    """A time history. Arrays run over the output times tau."""

    tau: np.ndarray
    y: np.ndarray               #: (4, n): x1, x1', x2, x2'
    u: np.ndarray               #: (2, n): modal coordinates u = P^-1 x (eq 34); NaN if kappa <= s1
    impact_force: np.ndarray    #: beta x1^(2n-1) (eq 4)
    theta: np.ndarray           #: theta0 x1 [rad]
    phi: np.ndarray             #: theta0 x2 [rad]
    n_rhs: int
    n_accepted: int
    n_rejected: int
    tau_reached: float
    method: str                 #: the integration method used ('auto' resolved)

    @property
    def x1(self):
        return self.y[0]

    @property
    def x2(self):
        return self.y[2]


def _counts(counts):
    return int(counts[0]), int(counts[1]), int(counts[2]), float(counts[3])


def _state(y0):
    """A state (x1, x1', x2, x2'): 4 finite reals (None: rest)."""
    return np.zeros(4) if y0 is None else _checks.reals("y0", y0, (4,))


def _settings(params, integration, steady=None):
    """The common arguments checked: params, the Integration and the Steady settings."""
    _checks.instance("params", params, Parameters)
    _checks.instance("integration", integration, Integration)
    if steady is not None:
        _checks.instance("steady", steady, Steady)


def _output_times(params, t_end, t_start, n_out, tau_out, rows=9):
    """The output times of a simulation: tau_out, or n_out evenly spaced times over [t_start,
    t_end] (default: 20 per forcing or natural period), checked (rows: of the history)."""
    t_end, t_start = _checks.real("t_end", t_end), _checks.real("t_start", t_start)
    if tau_out is None:
        if n_out is None:
            period = 2 * math.pi / (params.rho if params.rho > 0 else 1.0)
            periods = max(0.0, (t_end - t_start) / period)
            n_out = max(2, math.ceil(20 * min(periods, 2.0**60)) + 1)
            if n_out > _checks.C_INT_MAX:
                raise InputError(f"t_end = {_checks.show(t_end)} is out of range: 20 outputs "
                                 f"per period make {n_out}, more than {_checks.C_INT_MAX}; give "
                                 "n_out or tau_out")
        n_out = _checks.output_size("n_out", _checks.integer("n_out", n_out, 0), rows)
        tau_out = np.linspace(t_start, t_end, n_out)
    return _checks.reals("tau_out", tau_out, ndim=1)


def simulate(params: Parameters, t_end, y0=None, *, n_out=None, tau_out=None, t_start=0.0,
             integration: Integration = Integration()) -> Simulation:
    """Integrate from y0 (default: rest) at t_start to t_end; output at tau_out, or at n_out
    evenly spaced times (default: 20 per forcing or natural period); tolerances and method in
    `integration`: simulate(p, 100, integration=Integration(rtol=1e-10, atol=1e-13)).

    On failure raises IntegrationError whose ``partial`` attribute holds the history up to
    where the integration stopped (later columns are NaN)."""
    _settings(params, integration)
    tau_out = _output_times(params, t_end, t_start, n_out, tau_out)
    history, counts, status, message = cancellable(
        _bridge.simulate, *params.array(), t_start, _state(y0), tau_out, integration.array())
    result = Simulation(tau_out, history[0:4], history[4:6], history[6], history[7], history[8],
                        *_counts(counts), method=integration.method_used)
    if status:
        try:
            check_status(status, message, "simulation")
        except IntegrationError as exc:
            exc.partial = result
            raise
    return result


@dataclass(frozen=True)
class Ensemble:
    """Time histories of K trajectories integrated together (simulate_ensemble). Arrays run
    over the members first, then as Simulation's; member i equals simulate's run of it bit
    for bit (``ensemble.member(i)`` is that Simulation)."""

    tau: np.ndarray             #: (K, n) output times
    y: np.ndarray               #: (K, 4, n): x1, x1', x2, x2'
    u: np.ndarray               #: (K, 2, n): modal coordinates (eq 34)
    impact_force: np.ndarray    #: (K, n)
    theta: np.ndarray           #: (K, n)
    phi: np.ndarray             #: (K, n)
    n_rhs: np.ndarray           #: (K,) work counts per member
    n_accepted: np.ndarray
    n_rejected: np.ndarray
    tau_reached: np.ndarray
    status: np.ndarray          #: (K,) 0 = finished; else the core's status of that member
    method: str

    def __len__(self):
        return len(self.tau)

    def member(self, i) -> Simulation:
        """Member i as a Simulation."""
        return Simulation(self.tau[i], self.y[i], self.u[i], self.impact_force[i],
                          self.theta[i], self.phi[i], int(self.n_rhs[i]),
                          int(self.n_accepted[i]), int(self.n_rejected[i]),
                          float(self.tau_reached[i]), self.method)


def simulate_ensemble(params, t_end, y0=None, *, n_out=None, tau_out=None, t_start=0.0,
                      integration: Integration = Integration()) -> Ensemble:
    """K trajectories at once (issue 43), each with its own step control, exactly as K calls
    of simulate would give them: params is one Parameters or a sequence of K (e.g. a rho
    sweep); y0 None (rest), one state (4,) or K states (K, 4); t_end and t_start a number or K
    numbers; tau_out None (n_out evenly spaced times per member: default the most any member
    gets from simulate's rule), one ascending array for all, or (K, n). K is the longest of
    params, y0, t_end, t_start and a 2-D tau_out; the others must have that length or one
    entry. Faster per trajectory than a loop over simulate (benchmarks/README.md, "Ensembles").

    On failure of any member raises IntegrationError naming the first (0-based) member, whose
    ``partial`` attribute holds the whole Ensemble (status per member; NaN where a member
    stopped)."""
    _checks.instance("integration", integration, Integration)
    members = list(params) if isinstance(params, (list, tuple)) else [params]
    for i, p in enumerate(members):
        _checks.instance(f"params[{i}]", p, Parameters)
    y0 = np.zeros(4) if y0 is None else _checks.reals("y0", y0)
    if y0.ndim not in (1, 2) or y0.shape[-1] != 4:
        raise InputError(f"y0 has shape {y0.shape}: it must be (4,) or (K, 4)")
    t_end = _checks.reals("t_end", t_end)
    t_start = _checks.reals("t_start", t_start)
    if tau_out is not None:
        tau_out = _checks.reals("tau_out", tau_out)
        if tau_out.ndim not in (1, 2):
            raise InputError(f"tau_out has shape {tau_out.shape}: it must be (n,) or (K, n)")
    sizes = {"params": len(members), "y0": len(y0) if y0.ndim == 2 else 1,
             "t_end": t_end.size, "t_start": t_start.size,
             "tau_out": len(tau_out) if tau_out is not None and tau_out.ndim == 2 else 1}
    k = max(sizes.values())
    for name, size in sizes.items():
        if size not in (1, k):
            raise InputError(f"{name} has {size} members: it must have 1 or K = {k} (the "
                             "longest of params, y0, t_end, t_start and tau_out)")
    members = members * k if len(members) == 1 else members
    y0 = np.broadcast_to(y0, (k, 4))
    t_end = np.broadcast_to(t_end.ravel(), (k,))
    t_start = np.broadcast_to(t_start.ravel(), (k,))
    if tau_out is None:
        if n_out is None:
            n_out = max(len(_output_times(p, e, s, None, None))
                        for p, e, s in zip(members, t_end, t_start))
        tau_out = np.stack([_output_times(p, e, s, n_out, None)
                            for p, e, s in zip(members, t_end, t_start)])
    tau_out = np.ascontiguousarray(np.broadcast_to(tau_out, (k, tau_out.shape[-1])))
    _checks.output_size("n_out", tau_out.shape[1] * k, 9)
    arrays = [p.array() for p in members]
    rpar = np.stack([a[0] for a in arrays], axis=1)
    ipar = np.stack([a[1] for a in arrays], axis=1)
    history, counts, status, message = cancellable(
        _bridge.simulate_ensemble, rpar, ipar, np.ascontiguousarray(t_start),
        np.ascontiguousarray(y0.T), tau_out.T, integration.array())
    h = np.moveaxis(history, 2, 0)
    result = Ensemble(tau_out, h[:, 0:4], h[:, 4:6], h[:, 6], h[:, 7], h[:, 8],
                      counts[0].astype(int), counts[1].astype(int), counts[2].astype(int),
                      counts[3].copy(), np.asarray(status, dtype=int),
                      method=integration.method_used)
    first = np.flatnonzero(status)
    if len(first):
        try:
            check_status(int(status[first[0]]), message, "ensemble simulation")
        except IntegrationError as exc:
            exc.partial = result
            raise
    return result


@dataclass(frozen=True)
class SteadyState:
    """Steady response at one (rho, A): amplitudes over the window and the kind of motion."""

    rho: float
    A: float
    max_x1: float
    max_x2: float
    max_u1: float
    max_u2: float
    motion: str                 #: 'periodic', 'quasi-periodic', 'irregular' (heuristic), or
                                #: 'settling' (transient too short to judge)
    period: int                 #: forcing periods per cycle if periodic, else 0
    transient_periods: float    #: transient actually integrated
    spread: float               #: largest distance of a Poincare point from the first, relative
    settled: bool               #: the settle test passed (always True without settle_tol)
    method: str                 #: the integration method used ('auto' resolved)
    poincare: np.ndarray = field(repr=False, default=None)   #: (4, window) points at tau = k T
                                #: (None in a sweep: only summaries are kept)
    y_end: np.ndarray = field(repr=False, default=None)      #: final state, forcing phase 0


def _summary(row, method, poincare=None, y_end=None):
    """A SteadyState from one column of the core's 'summary' table (its names are the fields)."""
    values = dict(zip(SUMMARY_COLUMNS, row))
    kinds = {"motion": lambda x: MOTIONS[int(x)], "period": int, "settled": bool}
    return SteadyState(**{name: kinds.get(name, float)(x) for name, x in values.items()},
                       method=method, poincare=poincare, y_end=y_end)


def steady_state(params: Parameters, y0=None, *, steady: Steady = Steady(),
                 integration: Integration = Integration()) -> SteadyState:
    """Integrate through a transient, then measure max|x1|, max|x2|, max|u1|, max|u2| and the
    Poincare points over a window, and judge the motion from them."""
    _settings(params, integration, steady)
    window = _checks.output_size("window_periods", max(steady.window_periods, 1), 4)
    summary, poincare, y_end, counts, status, message = cancellable(_bridge.steady_state,
        *params.array(), _state(y0), integration.array(), steady.array(), window)
    check_status(status, message, "steady state")
    return _summary(summary, integration.method_used, poincare, y_end)


def poincare_section(params: Parameters, n_points, y0=None, *, skip_periods=0,
                     integration: Integration = Integration()) -> Simulation:
    """Stroboscopic Poincare section: the motion at tau = k 2 pi/rho, k = skip_periods + 1
    ... skip_periods + n_points (dense output, steps never shortened); its states `y` have
    shape (4, n_points)."""
    _settings(params, integration)
    if not params.rho > 0:
        raise InputError(f"rho = {params.rho} is out of range: a Poincare section needs rho > 0")
    period = 2 * math.pi / params.rho
    k0 = _checks.integer("skip_periods", skip_periods, 0)
    n_points = _checks.output_size("n_points", _checks.integer("n_points", n_points, 1), 9)
    tau = period * np.arange(k0 + 1, k0 + n_points + 1)
    return simulate(params, tau[-1], y0, tau_out=tau, integration=integration)


@dataclass(frozen=True)
class Sweep:
    """Steady states along a sweep (only per-point summaries are kept)."""

    parameter: str              #: 'rho' or 'A'
    points: list                #: SteadyState per value, in sweep order
    y_final: np.ndarray         #: None for independent points (start_from='y0')
    method: str                 #: the integration method used ('auto' resolved)

    def column(self, name):
        return np.array([getattr(p, name) for p in self.points])

    @property
    def values(self):
        return self.column(self.parameter)


def sweep_values(start, stop, n, direction="up") -> np.ndarray:
    """Sweep values from start to stop ('up'), back ('down'), or up then down ('both')."""
    start, stop = _checks.real("start", start), _checks.real("stop", stop)
    n = _checks.output_size("n", _checks.integer("n", n, 1))
    _checks.choice("direction", direction, _tables.names("directions")[0])
    values = np.linspace(min(start, stop), max(start, stop), n)
    if direction == "up":
        return values
    if direction == "down":
        return values[::-1]
    return np.concatenate([values, values[-2::-1]])


def _sweep(params, parameter, values, y0, steady, integration, progress, threads, start_from):
    _settings(params, integration, steady)
    which = {"rho": 1, "A": 2}[parameter]

    def run(chunk, y, carry):
        if carry:
            summaries, y, n_done, status, message = cancellable(_bridge.parameter_sweep,
                *params.array(), which, chunk, y, integration.array(), steady.array())
        else:
            summaries, n_done, status, message = cancellable(_bridge.independent_sweep,
                *params.array(), which, chunk, y, integration.array(), steady.array(),
                int(threads), 0)
        return summaries, None, y, status, message

    method = integration.method_used
    points, _, y = run_sweep(parameter, values, y0, progress, threads, start_from, run,
                             lambda points, y: Sweep(parameter, points, y, method), method)
    return Sweep(parameter, points, y, method)


def run_sweep(label, values, y0, progress, threads, start_from, run, partial, method):
    """The points of a sweep by run(chunk, y, carry) -> (summaries, extra, y_final, status,
    message), a chunk at a time so that progress shows: the SteadyStates (integrated by
    `method`), the extras stacked as columns (or None), and the final state (None for
    independent points). On failure the exception carries `partial(points, y)`, the points
    done."""
    _checks.choice("start_from", start_from, ("previous", "y0"))
    threads = _checks.integer("threads", threads)
    carry = start_from == "previous"
    status, message = _bridge.sweep_threads(threads, int(carry))
    check_status(status, message)
    values = _checks.reals({"rho": "rho_values", "A": "A_values"}.get(label, "frequencies"),
                           values, ndim=1)
    y = _state(y0)
    points, extras = [], []
    bar = None
    if progress:
        from tqdm.auto import tqdm    # deferred: it adds ~0.1 s to `import sloshdyn`
        bar = tqdm(total=len(values), desc=f"sweep in {label}", unit="point")
    try:
        # one point per Fortran call when the state is carried, so progress shows; independent
        # points in one call, or a block (the core's default size) per thread when progress
        # is shown
        step = (1 if carry else _bridge.default_sweep_block() * int(threads) if bar
                else max(len(values), 1))
        for first in range(0, len(values), step):
            chunk = values[first:first + step]
            summaries, extra, y, status, message = run(chunk, y, carry)
            if status:
                try:
                    check_status(status, message, f"sweep in {label}")
                except Exception as exc:
                    exc.partial = partial(points, y if carry else None)
                    raise
            points.extend(_summary(summaries[:, k], method) for k in range(len(chunk)))
            if extra is not None:
                extras.append(extra)
            if bar:
                bar.update(len(chunk))
    finally:
        if bar:
            bar.close()
    return points, (np.hstack(extras) if extras else None), (y if carry else None)


def frequency_sweep(params: Parameters, rho_values, y0=None, *, steady: Steady = Steady(),
                    integration: Integration = Integration(), progress=False, threads=1,
                    start_from="previous") -> Sweep:
    """Steady states along rho_values (ascending = up, descending = down).

    start_from='previous' (default): each point starts from the previous point's final state,
    so jumps and hysteresis show; the points depend on each other and run on one thread
    (threads > 1 is refused: it would change the answer). start_from='y0': every point starts
    from y0; the points are independent, go to the core's ensemble integrator in blocks of
    up to its default_sweep_block and `threads` threads share the blocks out (OpenMP in
    the core); the results are the same for any number of threads and any block, bit for bit
    (y_final is None)."""
    return _sweep(params, "rho", rho_values, y0, steady, integration, progress, threads,
                  start_from)


def amplitude_sweep(params: Parameters, A_values, y0=None, *, steady: Steady = Steady(),
                    integration: Integration = Integration(), progress=False, threads=1,
                    start_from="previous") -> Sweep:
    """Steady states along A_values at fixed rho, carrying the state (the paper's numerical
    continuation, sec 4.2); start_from and threads as for frequency_sweep."""
    return _sweep(params, "A", A_values, y0, steady, integration, progress, threads, start_from)


@dataclass(frozen=True)
class AmplitudeSpectrum:
    """A one-sided amplitude spectrum."""

    omega: np.ndarray           #: angular frequencies [rad per unit time of the signal]
    amplitude: np.ndarray       #: amplitude at each


def spectrum(signal, dt, window="hann") -> AmplitudeSpectrum:
    """One-sided amplitude spectrum of an evenly sampled signal (angular frequencies [rad per
    unit time], amplitudes). The mean is removed; the window ('hann' or None) is normalised so a
    sinusoid of amplitude a shows a peak of height about a."""
    x = _checks.reals("signal", signal, ndim=1, min_size=4)
    dt = _checks.real("dt", dt)
    if not dt > 0:
        raise InputError(f"dt = {dt} is out of range: it must be > 0")
    x = x - x.mean()
    if window == "hann":
        w = np.hanning(x.size)
    elif window is None:
        w = np.ones(x.size)
    else:
        raise InputError(f"window = {window!r} is not valid: it must be 'hann' or None")
    amplitude = 2 * np.abs(np.fft.rfft(x * w)) / w.sum()
    omega = 2 * np.pi * np.fft.rfftfreq(x.size, dt)
    return AmplitudeSpectrum(omega, amplitude)


def beat_period(poincare) -> float:
    """The beat period of a quasi-periodic motion, in forcing periods, from its Poincare points
    (rows x1, x1' of a (>= 2, n) array, one point per forcing period): the points turn about
    their closed curve, so their angle about the centroid, unwrapped, counts the turns; the
    mean time between successive whole turns (each interpolated linearly between two points)
    is the period of the envelope. Needs at least two whole turns."""
    points = np.asarray(poincare, dtype=np.float64)
    if points.ndim != 2 or points.shape[0] < 2 or points.shape[1] < 4:
        raise InputError(f"poincare has shape {points.shape}: give (>= 2, n >= 4) Poincare points")
    z = (points[0] - points[0].mean()) + 1j * (points[1] - points[1].mean())
    turns = np.unwrap(np.angle(z)) / (2 * math.pi)
    turns = (turns - turns[0]) * np.sign(turns[-1] - turns[0])
    whole = np.arange(1, math.floor(turns[-1]) + 1)
    if whole.size < 2 or np.any(np.diff(turns) <= 0):
        raise InputError(f"the Poincare points make {turns[-1]:.3g} turns about their centroid, "
                         "not steadily: a beat period needs at least two whole turns of a closed "
                         "curve around it (a longer window, or quasi-periodic motion)")
    times = np.interp(whole, turns, np.arange(turns.size))
    return float((times[-1] - times[0]) / (whole.size - 1))
