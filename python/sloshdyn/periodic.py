"""Periodic responses of the full equations of motion (not the slow flow): orbits by shooting
with the monodromy matrix from the variational equations, Floquet multipliers and stability,
continuation in rho or A with folds, period doublings and Neimark-Sacker points, and the largest
Lyapunov exponent. Computed by the Fortran core (sloshdyn_periodic)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from . import _checks, _core, _tables
from ._cancel import cancellable
from ._errors import InputError, check_status, message_text, with_partial
from .asymptotics import continuation_array, continuation_range
from .charts import _chart
from .model import linear_modes
from .options import Chart, Continuation, Integration, Lyapunov, Shooting
from .parameters import Parameters

#: the core's curve kinds a periodic orbit's special point starts (a Hopf curve is the slow
#: flow's: charts.stability_chart)
ORBIT_CURVES = tuple(kind for kind in _tables.codes("curve").values() if kind != "hopf")

_bridge = _core.sloshdyn_bridge_periodic
_bridge_charts = _core.sloshdyn_bridge_charts
KINDS = _tables.codes("special")


@dataclass(frozen=True)
class PeriodicOrbit:
    """A periodic orbit of period k T (T = 2 pi/rho), through y0 at forcing phase 0."""

    y0: np.ndarray
    multipliers: np.ndarray     #: Floquet multipliers, eigenvalues of the monodromy matrix
    monodromy: np.ndarray
    max_x1: float               #: max |x1| over the orbit (64 samples per forcing period)
    iterations: int
    periods: int
    method: str                 #: the integration method used ('auto' resolved)

    @property
    def stable(self):
        return bool(np.all(np.abs(self.multipliers) < 1))


def periodic_orbit(params: Parameters, y0=None, *, periods=1, start="simulation",
                   shooting: Shooting = Shooting(),
                   integration: Integration = Integration()) -> PeriodicOrbit:
    """The periodic orbit near a start: y0, or (y0 None) a steady state of a direct simulation
    from rest (start='simulation') or the 3:1 slow-flow steady state of smallest |u1|
    (start='slow_flow', through eq 34 and 42)."""
    _checks.instance("params", params, Parameters)
    _checks.instance("shooting", shooting, Shooting)
    _checks.instance("integration", integration, Integration)
    periods = _checks.integer("periods", periods)
    if y0 is None:
        y0 = start_state(params, start)
    y0 = _checks.reals("y0", y0, (4,))
    y, monodromy, multipliers, info, status, message = cancellable(_bridge.periodic_orbit,
        *params.array(), y0, periods, integration.array(), shooting.newton_tol,
        shooting.max_iter)
    check_status(status, message, "periodic orbit")
    info = _tables.unpack("orbit_info", info)
    return PeriodicOrbit(y, multipliers[0] + 1j * multipliers[1], monodromy,
                         float(info["max_x1"]), int(info["iterations"]), int(periods),
                         integration.method_used)


def start_state(params: Parameters, start="simulation"):
    """A starting state at forcing phase 0 for shooting (the core's periodic_start_state): the
    steady state of a simulation from rest (start='simulation', at most 5000 forcing periods)
    or the 3:1 slow-flow steady state nearest to rho, stable ones first (start='slow_flow',
    through eq 34 and 42)."""
    _checks.instance("params", params, Parameters)
    if not isinstance(start, str):
        raise InputError(f"start = {start!r} is not valid: give 'simulation' or 'slow_flow'")
    y, status, message = cancellable(_bridge.start_state, *params.array(), start,
                                     Integration().array())
    check_status(status, message, "start state")
    return y


def slow_flow_state(params: Parameters, b1, b2):
    """The full state at tau = 0 of the slow-flow solution u1 = Re(B1 e^{i rho tau}),
    u2 = Re(B2 e^{3 i rho tau}) (eq 42, 45), mapped to x by x = P u (eq 34)."""
    p = linear_modes(params).modal
    u = np.array([b1.real, b2.real])
    du = np.array([-params.rho * b1.imag, -3 * params.rho * b2.imag])
    x, dx = p @ u, p @ du
    return np.array([x[0], dx[0], x[1], dx[1]])


@dataclass(frozen=True)
class PeriodicSpecialPoint:
    kind: str            #: 'fold', 'branch_point', 'period_doubling' or 'neimark_sacker'
    rho: float
    A: float
    max_x1: float
    y0: np.ndarray


@dataclass(frozen=True)
class Criticality:
    """The criticality of a period doubling or a Neimark-Sacker point
    (PeriodicBranch.criticality). Period doubling: the cubic normal-form coefficient c of the
    stroboscopic map on its centre manifold x = eta q, eta -> -(1 + beta) eta + c eta^3
    (mu = -(1 + beta) the critical multiplier; Kuznetsov 2004, eq 8.24). c > 0: supercritical,
    the doubled orbits are stable and born where the orbit is unstable, at |eta| =
    sqrt(beta/c); c < 0: subcritical, past the point the motion jumps away. Neimark-Sacker: the
    first Lyapunov coefficient d of the map's normal form z -> e^{i theta} z (1 + beta +
    d |z|^2) on the centre manifold x = z q + conj(z q) (Kuznetsov 2004, secs 4.7 and 5.4);
    d < 0: supercritical, a stable invariant closed curve (a torus of the flow) is born where
    the orbit is unstable; d > 0: subcritical."""

    kind: str                    #: 'period_doubling' or 'neimark_sacker'
    coefficient: float           #: c, or d (q of unit length)
    supercritical: bool          #: c > 0, or d < 0
    multiplier: complex          #: the critical multiplier (near -1, or e^{i theta}, Im > 0)
    direction: np.ndarray        #: q: the critical Floquet eigenvector (unit length; complex
    #: for a Neimark-Sacker point)


@dataclass(frozen=True)
class PeriodicBranch:
    """A branch of periodic orbits of the full equations, with Floquet stability."""

    parameter: str
    table: dict                  #: lambda, rho, A, y1..y4 (the orbit's state at phase 0),
                                 #: max_x1, stable, and mu1..mu4 (complex multipliers)
    special_points: list
    complete: bool
    message: str                 #: why an incomplete branch stopped ('' if complete)
    method: str                  #: the integration method used ('auto' resolved)
    periods: int = 1             #: the orbits' period in forcing periods (k of k T)
    params: Parameters = None    #: the parameters (the continued one at the branch's start)
    lambda_range: tuple = ()     #: the interval of the continued parameter
    continuation: Continuation = None   #: the arclength steps the branch was followed with
    integration: Integration = None

    def switch(self, special_point, *, continuation: Continuation = None) -> PeriodicBranch:
        """The branch born at special_point (one of special_points): at a 'branch_point' the
        other branch of orbits of period k T, at a 'period_doubling' the doubled orbits
        (period 2 k T), started along the critical Floquet eigenvector (multiplier +1 or -1)
        and continued over the same range (with this branch's steps unless continuation is
        given), with its own special points. Raises ConvergenceError (with ``partial``) as
        periodic_response does."""
        _checks.instance("special_point", special_point, PeriodicSpecialPoint)
        if special_point.kind not in ("branch_point", "period_doubling"):
            raise InputError(f"special_point.kind = {special_point.kind!r}: branches can be "
                             "switched at a 'branch_point' or a 'period_doubling'")
        c = self.continuation if continuation is None else continuation
        _checks.instance("continuation", c, Continuation)
        at = self.params.replace(rho=special_point.rho, A=special_point.A)
        lo, hi = self.lambda_range
        max_points = _checks.output_size("max_points",
                                         _checks.integer("max_points", c.max_points, 1),
                                         len(_tables.columns("periodic_branch")))
        (points, multipliers, n, special, n_special, complete, k_new, status,
         message) = cancellable(_bridge.switch_branch, *at.array(),
                                _tables.code("excitation_parameters", self.parameter),
                                _tables.code("special", special_point.kind),
                                _checks.reals("special_point.y0", special_point.y0, (4,)),
                                getattr(special_point, self.parameter), self.periods, lo, hi,
                                continuation_array(c, 1.0), self.integration.array(),
                                max_points, 100)
        return _branch(self.parameter, at, int(k_new), (lo, hi), c, self.integration, points,
                       multipliers, n, special, n_special, complete, status, message,
                       "switched branch")


    def criticality(self, special_point) -> Criticality:
        """The criticality of special_point, a 'period_doubling' or 'neimark_sacker' of this
        branch: the normal-form coefficient from the monodromy matrices of the variational
        equations (docs/model.md, "Criticality")."""
        _checks.instance("special_point", special_point, PeriodicSpecialPoint)
        if special_point.kind not in ("period_doubling", "neimark_sacker"):
            raise InputError(f"special_point.kind = {special_point.kind!r}: the criticality is "
                             "computed at a 'period_doubling' or a 'neimark_sacker'")
        at = self.params.replace(rho=special_point.rho, A=special_point.A)
        if special_point.kind == "neimark_sacker":
            d, q_re, q_im, mu_re, mu_im, status, message = cancellable(
                _bridge.neimark_sacker_criticality, *at.array(),
                _checks.reals("special_point.y0", special_point.y0, (4,)), self.periods,
                self.integration.array())
            check_status(status, message, "Neimark-Sacker criticality")
            return Criticality("neimark_sacker", float(d), bool(d < 0), complex(mu_re, mu_im),
                               q_re + 1j * q_im)
        c, q, mu, status, message = cancellable(
            _bridge.period_doubling_criticality, *at.array(),
            _checks.reals("special_point.y0", special_point.y0, (4,)), self.periods,
            self.integration.array())
        check_status(status, message, "period-doubling criticality")
        return Criticality("period_doubling", float(c), bool(c > 0), float(mu), q)


    def curve(self, special_point, rho_range, A_range, *, chart: Chart = Chart()):
        """The two-parameter curve in (rho, A) through special_point (a 'fold',
        'period_doubling' or 'neimark_sacker' of this branch), traced both ways inside the box
        rho_range x A_range with at most chart.max_points points (its other fields are the
        grid's, not used here; sloshdyn_orbit_chart: the
        stroboscopic map's defining systems of sloshdyn_map_bifurcation), with its
        codimension-2 points: a charts.Curve (state: the orbits at phase 0; omega: the torus'
        rotation angle on a Neimark-Sacker curve). A curve stopped early has complete False and
        its note."""
        _checks.instance("special_point", special_point, PeriodicSpecialPoint)
        if special_point.kind not in ORBIT_CURVES:
            raise InputError(f"special_point.kind = {special_point.kind!r}: a curve starts at "
                             f"one of {', '.join(map(repr, ORBIT_CURVES))}")
        (r0, r1), (a0, a1) = (_checks.interval("rho_range", rho_range),
                              _checks.interval("A_range", A_range))
        _checks.instance("chart", chart, Chart)
        max_points = _checks.output_size("chart.max_points", max(chart.max_points, 3),
                                         len(_tables.columns("chart_curves")))
        lam = getattr(special_point, self.parameter)
        special = np.concatenate([[_tables.code("special", special_point.kind), lam],
                                  _checks.reals("special_point.y0", special_point.y0, (4,)),
                                  [special_point.max_x1]])
        at = self.params.replace(rho=special_point.rho, A=special_point.A)
        curves, codim2, ends, sizes, note, status, message = cancellable(
            _bridge_charts.orbit_curve, *at.array(), 1 if self.parameter == "rho" else 2,
            special, self.periods, [r0, a0], [r1, a1], max_points, 100)
        check_status(status, message, "orbit curve")
        used = _tables.unpack("chart_sizes", sizes)
        curves = curves[:, :int(used["curve_points"])]
        chart = _chart("rho", "A", "full", curves, codim2[:, :int(used["codim2_points"])],
                       ends, np.zeros((len(_tables.columns("chart_grid")), 0)),
                       bool(ends[3, 0]), "curve 1: " + message_text(note), at)
        return chart.curves[0]


def _branch(parameter, params, periods, lambda_range, continuation, integration, points,
            multipliers, n, special, n_special, complete, status, message, what):
    """The PeriodicBranch of the bridge's arrays (layouts periodic_branch and
    periodic_special_points); raises the status's error with the branch as ``partial``."""
    rows = dict(zip(_tables.columns("periodic_branch"), np.vstack([points, multipliers])[:, :n]))
    lam = rows["lambda"]
    table = {"lambda": lam, "rho": lam if parameter == "rho" else np.full(n, params.rho),
             "A": lam if parameter == "A" else np.full(n, params.A)}
    for i in range(1, 5):
        table[f"y{i}"] = rows[f"y{i}"]
        table[f"mu{i}"] = rows[f"re_mu{i}"] + 1j * rows[f"im_mu{i}"]
    table["max_x1"] = rows["max_x1"]
    table["stable"] = rows["stable"]
    specials = []
    for column in special[:, :n_special].T:
        point = dict(zip(_tables.columns("periodic_special_points"), column))
        specials.append(PeriodicSpecialPoint(
            KINDS[int(point["kind"])], float(point["lambda"]) if parameter == "rho" else params.rho,
            float(point["lambda"]) if parameter == "A" else params.A, float(point["max_x1"]),
            np.array([point[f"y{i}"] for i in range(1, 5)])))
    branch = PeriodicBranch(parameter, table, specials, bool(complete), message_text(message),
                            integration.method_used, periods, params, tuple(lambda_range),
                            continuation, integration)
    return with_partial(branch, status, message, what)


#: the arclength steps of a periodic branch unless told (the executable takes &response's)
PERIODIC_CONTINUATION = Continuation(ds=0.002, ds_min=1e-9, ds_max=0.01, x_scale=1.0,
                                     max_points=2000)


def periodic_response(params: Parameters, rho_range=None, *, A_range=None, y0=None, periods=1,
                      start="simulation", from_end="low",
                      continuation: Continuation = PERIODIC_CONTINUATION,
                      integration: Integration = Integration()) -> PeriodicBranch:
    """Continue the periodic orbit through y0 (or found from `start`) in rho over rho_range, or
    in A over A_range, starting at the low end (from_end='low') going up, or at the high end
    going down, with the arclength steps ds, ds_min, ds_max, x_scale, Newton's x_tol, f_tol,
    max_iter and at most max_points points of `continuation` (its branch-search fields are not
    used). Raises ConvergenceError (with ``partial``) if the branch stops before the end of the
    range or a special point on it could not be located. Its .switch(special_point) follows
    the branch born at a branch point or a period doubling."""
    b = branch_start(params, rho_range, A_range, y0, periods, start, from_end, continuation,
                     integration, "periodic_branch")
    parameter = b.parameter
    points, multipliers, n, special, n_special, complete, status, message = cancellable(
        _bridge.periodic_branch, *b.first.array(),
        _tables.code("excitation_parameters", parameter), b.y0, b.periods, b.low, b.high,
        b.settings, integration.array(), b.max_points, 100)
    return _branch(parameter, b.first, b.periods, (b.low, b.high), continuation, integration,
                   points, multipliers, n, special, n_special, complete, status, message,
                   "periodic branch")


class BranchStart(NamedTuple):
    """What a continuation of periodic orbits starts from (branch_start)."""

    parameter: str           #: 'rho' or 'A'
    low: float
    high: float
    first: Parameters        #: params at the starting end
    y0: np.ndarray           #: the orbit's state there
    periods: int
    settings: np.ndarray     #: layout 'continuation'
    max_points: int


def branch_start(params, rho_range, A_range, y0, periods, start, from_end, continuation,
                 integration, table) -> BranchStart:
    """Check the arguments of a continuation of periodic orbits in rho or A whose points fill
    the result table `table`, and find its first orbit (from `start` if y0 is None)."""
    _checks.instance("params", params, Parameters)
    _checks.instance("continuation", continuation, Continuation)
    _checks.instance("integration", integration, Integration)
    parameter, (lo, hi) = continuation_range(rho_range, A_range)
    _checks.choice("from_end", from_end, ("low", "high"))
    c = continuation
    periods = _checks.integer("periods", periods)
    max_points = _checks.output_size("max_points", _checks.integer("max_points", c.max_points, 1),
                                     len(_tables.columns(table)))
    first = params.replace(**{parameter: float(lo if from_end == "low" else hi)})
    if y0 is None:
        y0 = periodic_orbit(first, start_state(first, start), periods=periods,
                            integration=integration).y0
    settings = continuation_array(c, 1.0 if from_end == "low" else -1.0)
    return BranchStart(parameter, lo, hi, first, _checks.reals("y0", y0, (4,)), periods,
                       settings, max_points)


@dataclass(frozen=True)
class LyapunovExponent:
    """The largest Lyapunov exponent per unit tau, and its running estimate after each
    renormalisation block (for a convergence check)."""

    exponent: float
    history: np.ndarray
    method: str                  #: the integration method used ('auto' resolved)


def lyapunov_exponent(params: Parameters, y0=None, *, lyapunov: Lyapunov = Lyapunov(),
                      integration: Integration = Integration()) -> LyapunovExponent:
    """Largest Lyapunov exponent per unit tau (Benettin: one tangent vector renormalised every
    renormalise_every forcing periods) from y0 (default: rest). Negative: a stable periodic
    response; about 0: quasi-periodic; positive: chaotic."""
    _checks.instance("params", params, Parameters)
    _checks.instance("lyapunov", lyapunov, Lyapunov)
    _checks.instance("integration", integration, Integration)
    y0 = np.zeros(4) if y0 is None else _checks.reals("y0", y0, (4,))
    blocks = max(lyapunov.n_periods // max(lyapunov.renormalise_every, 1), 1)
    exponent, history, status, message = cancellable(
        _bridge.lyapunov_exponent, *params.array(), y0, lyapunov.array(), integration.array(),
        blocks)
    check_status(status, message, "Lyapunov exponent")
    return LyapunovExponent(float(exponent), history, integration.method_used)
