"""The spatial model (issue 26): the tank on rods that tilt in x and y, the sloshing mass as a
spherical pendulum, ground motion in two horizontal components, and swirl. Computed by the
Fortran core (sloshdyn_spatial); docs/model.md, "Spatial model and swirl", derives it.

The state is y = (x1, x1', x2, x2', y1, y1', y2, y2'): x1 = theta_x/theta0 and x2 = phi_x/theta0
in the xz plane as in the planar model, y1 = theta_y/theta0 and y2 = phi_y/theta0 out of it.
The second component of harmonic ground motion is set by keywords: ``azimuth`` (rad, the
direction of the motion A sin(rho tau) from the x axis) and ``ellipticity`` (the ellipse's
minor over major axis; the minor axis moves as ellipticity A cos(rho tau)).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from . import _checks, _core, _tables
from ._cancel import cancellable
from ._errors import (ConvergenceError, InputError, SloshdynError, check_status, message_text,
                      with_partial)
from .ground import GroundMotion
from .options import Continuation, Integration, Shooting
from .parameters import Parameters
from .asymptotics import continuation_array
from .periodic import (KINDS, PERIODIC_CONTINUATION, PeriodicSpecialPoint, branch_start,
                       periodic_orbit)
from .seismic import seismic_defaults
from .simulation import _counts, _output_times
from .tank import Tank

_bridge = _core.sloshdyn_bridge_spatial

#: max|nu| beyond 1 + this is swirl (sloshdyn_swirl's stability_margin: undamped, the stable
#: multipliers sit on the unit circle to rounding)
SWIRL_MARGIN = 1e-6


def _spatial_array(azimuth, ellipticity):
    return _tables.pack("spatial", {"azimuth": _checks.real("azimuth", azimuth),
                                    "ellipticity": _checks.real("ellipticity", ellipticity)})


@dataclass(frozen=True)
class SpatialMotion:
    """The spatial equations at one state (docs/model.md, eq S7)."""

    mass: np.ndarray              #: inertia matrix M (4x4; unknowns x1'', x2'', y1'', y2'')
    dydt: np.ndarray              #: (x1', x1'', x2', x2'', y1', y1'', y2', y2'')
    jacobian: np.ndarray          #: analytic d(dydt)/dy, 8x8
    energy: float                 #: T + V relative to the ground [M L^2 omega^2]
    angular_momentum: float       #: about the vertical, relative to the ground [M L^2 omega]


def equations_of_motion(params: Parameters, tau, y, *, azimuth=0.0,
                        ellipticity=0.0) -> SpatialMotion:
    """Evaluate the spatial equations (eq S7) with the ground motion of params (A, rho) along
    ``azimuth`` and ``ellipticity`` times it across, at state y (8 entries)."""
    _checks.instance("params", params, Parameters)
    y, tau = _checks.reals("y", y, (8,)), _checks.real("tau", tau)
    mass, dydt, jac, invariants, status, message = _bridge.spatial_equations(
        *params.array(), _spatial_array(azimuth, ellipticity), tau, y)
    check_status(status, message)
    return SpatialMotion(mass, dydt, jac, float(invariants[0]), float(invariants[1]))


@dataclass(frozen=True)
class SpatialSimulation:
    """A time history of the spatial model (docs/model.md, "Spatial model and swirl"). Arrays
    run over the output times tau."""

    tau: np.ndarray
    y: np.ndarray               #: (8, n): x1, x1', x2, x2', y1, y1', y2, y2'
    tilt: np.ndarray            #: the pendulum's tilt from the vertical over theta0 (1 at the
                                #: wall, at any azimuth; |x1| in the plane)
    tilt_azimuth: np.ndarray    #: the azimuth towards which it tilts [rad, from x]
    n_rhs: int
    n_accepted: int
    n_rejected: int
    tau_reached: float
    method: str                 #: the integration method used ('auto' resolved)


def simulate(params: Parameters, t_end, y0=None, *, azimuth=0.0, ellipticity=0.0, n_out=None,
             tau_out=None, t_start=0.0,
             integration: Integration = Integration()) -> SpatialSimulation:
    """Integrate the spatial model under the harmonic base motion of params along ``azimuth``
    (and ``ellipticity`` times it across) from y0 (8 states; default: rest) at t_start to
    t_end; output times as ``sloshdyn.simulate``'s. On failure raises IntegrationError whose
    ``partial`` attribute holds the history up to where the integration stopped."""
    _checks.instance("params", params, Parameters)
    _checks.instance("integration", integration, Integration)
    spatial = _spatial_array(azimuth, ellipticity)
    tau_out = _output_times(params, t_end, t_start, n_out, tau_out,
                            len(_tables.columns("spatial_history")))
    y0 = np.zeros(8) if y0 is None else _checks.reals("y0", y0, (8,))
    history, counts, status, message = cancellable(
        _bridge.simulate, *params.array(), spatial, _checks.real("t_start", t_start), y0,
        tau_out, integration.array())
    result = SpatialSimulation(tau_out, history[0:8], history[8], history[9], *_counts(counts),
                               method=integration.method_used)
    return with_partial(result, status, message, "simulation of the spatial model")


def out_of_plane_multipliers(params: Parameters, y_orbit, *, periods=1,
                             integration: Integration = Integration()) -> np.ndarray:
    """The four out-of-plane Floquet multipliers nu (complex) of the planar periodic orbit of
    period `periods` T through y_orbit (x1, x1', x2, x2' at tau = 0, e.g.
    ``periodic_orbit(params).y0``): max|nu| > 1 means the planar response is unstable to swirl."""
    _checks.instance("params", params, Parameters)
    _checks.instance("integration", integration, Integration)
    nu, status, message = cancellable(_bridge.out_of_plane_multipliers, *params.array(),
                                      _checks.reals("y_orbit", y_orbit, (4,)),
                                      _checks.integer("periods", periods, 1), integration.array())
    check_status(status, message, "out-of-plane multipliers")
    return nu[0] + 1j * nu[1]


@dataclass(frozen=True)
class EdgeCriticality:
    """The criticality of a swirl edge (``swirl_edge_criticality``)."""

    c: float                     #: the cubic coefficient of the map on the centre manifold
    nu: float                    #: the critical out-of-plane multiplier (+1 or -1)
    size_of_terms: float         #: |<p, C(q,q,q)>|/6 + |<p, B(q, w)>|/2: the scale of c
    q: np.ndarray                #: the critical eigenvector (8 states, out of the plane)
    supercritical: bool          #: swirling orbits born stable where the planar orbit is
                                 #: unstable (gentle onset); False: subcritical (a jump)


def swirl_edge_criticality(params: Parameters, y_orbit, *, kind="branch_point", periods=1,
                           integration: Integration = Integration()) -> EdgeCriticality:
    """The criticality of the swirl edge at params (rho, A on the edge) through the planar
    orbit y_orbit (x1, x1', x2, x2' at tau = 0, e.g. an edge of ``swirl_band``): the cubic
    coefficient c of the spatial stroboscopic map on its centre manifold (the core's
    sloshdyn_map_normal_form; Kuznetsov, Elements of Applied Bifurcation Theory, 3rd ed. 2004,
    sec 5.4 and 8.7), at a 'branch_point' edge (nu = +1, the symmetric pitchfork eta ->
    (1 + beta) eta + c eta^3: swirling orbits at eta^2 = -beta/c, supercritical for c < 0) or a
    'period_doubling' one (nu = -1, the flip: supercritical for c > 0)."""
    _checks.instance("params", params, Parameters)
    _checks.instance("integration", integration, Integration)
    if kind not in ("branch_point", "period_doubling"):
        raise InputError(f"kind = {kind!r}: the criticality is of a 'branch_point' or a "
                         "'period_doubling' edge")
    c, nu, size, q, status, message = cancellable(
        _bridge.swirl_edge_criticality, *params.array(), _tables.code("special", kind),
        _checks.reals("y_orbit", y_orbit, (4,)), _checks.integer("periods", periods, 1),
        integration.array())
    check_status(status, message, "swirl edge criticality")
    return EdgeCriticality(float(c), float(nu), float(size), np.array(q),
                           bool(c < 0) if kind == "branch_point" else bool(c > 0))


@dataclass(frozen=True)
class SwirlBand:
    """A branch of planar periodic responses with their out-of-plane Floquet multipliers nu, and
    the edges of the swirl band (max|nu| = 1) on it."""

    parameter: str               #: 'rho' or 'A'
    table: dict                  #: lambda, rho, A, y1..y4, max_x1, planar_stable (in-plane
                                 #: Floquet stability), max_abs_nu, nu1..nu4 (complex), swirl
                                 #: (max|nu| > 1 + SWIRL_MARGIN)
    edges: dict                  #: lambda, rho, A, y1..y4, max_x1, refined (1: located by
                                 #: Brent's method; 0: interpolated across a fold), kind
                                 #: ('branch_point': an out-of-plane multiplier through +1,
                                 #: the pitchfork onto the swirling orbits; 'period_doubling':
                                 #: through -1; 'neimark_sacker': a complex pair)
    complete: bool
    message: str                 #: why an incomplete branch stopped ('' if complete)
    method: str                  #: the integration method used ('auto' resolved)
    skipped: dict = None         #: the tests not run: name -> why ({} if all ran)
    followed: tuple = ()         #: the branches followed (table["branch"] indexes them)
    others: str = ""             #: another branch found and not followed ('' if none)


def swirl_band(params: Parameters, rho_range=None, *, A_range=None, y0=None, periods=1,
               start="simulation", from_end="low", max_edges=100,
               continuation: Continuation = PERIODIC_CONTINUATION,
               integration: Integration = Integration()) -> SwirlBand:
    """Follow the planar periodic response in rho over rho_range (or in A over A_range) as
    ``periodic_response`` does, with the out-of-plane multipliers at every point and the edges
    of the band of swirl (planar response unstable out of its plane). from_end 'low' or 'high':
    the branch through the orbit at that end (y0, or found from ``start``); ``.others`` says
    whether the orbit found from ``start`` at the other end lies on another branch. 'both':
    the branches through the orbits found from ``start`` at both ends (one if they are the
    same), their points and edges told apart by the column ``branch``. Raises ConvergenceError
    (with ``partial``) if a branch stops before the end of the range."""
    _checks.choice("from_end", from_end, ("low", "high", "both"))
    if from_end == "both" and y0 is not None:
        raise InputError("y0: from_end = 'both' starts at both ends from `start`; give y0 "
                         "with from_end = 'low' or 'high'")
    max_edges = _checks.output_size("max_edges", _checks.integer("max_edges", max_edges, 1),
                                    len(_tables.columns("swirl_edges")))

    def starting(end, guess):
        return branch_start(params, rho_range, A_range, guess, periods, start, end,
                            continuation, integration, "swirl_branch")

    first = starting("high" if from_end == "high" else "low", y0)
    bands = [_follow_band(params, first, max_edges, integration)]
    other_end = "low" if from_end == "high" else "high"
    try:
        other = starting(other_end, None)
    except SloshdynError as error:
        if from_end == "both":
            raise
        # undamped, a simulation from rest never settles: no orbit there to compare
        return _merged(bands, f"not checked: no planar orbit found from start = '{start}' at "
                              f"the {other_end} end ({error}); other branches may exist")
    separate = not _reaches(bands[0], other)
    others = ""
    if from_end == "both" and separate:
        bands.append(_follow_band(params, other, max_edges, integration))
    elif separate:
        others = (f"the planar orbit found from start = '{start}' at the {other_end} end "
                  f"({other.parameter} = {getattr(other.first, other.parameter):.6g}) "
                  "is on another branch: from_end = 'both' follows it too")
    return _merged(bands, others)


def _follow_band(params, b, max_edges, integration):
    """One SwirlBand: the branch of the BranchStart b (raises with ``partial`` if it stops)."""
    parameter = b.parameter
    points, n, edges, n_edges, complete, conservative, status, message = cancellable(
        _bridge.swirl_branch, *b.first.array(), _tables.code("excitation_parameters", parameter),
        b.y0, b.periods, b.low, b.high, b.settings, integration.array(), b.max_points, max_edges)
    rows = dict(zip(_tables.columns("swirl_branch"), points[:, :n]))
    edge_rows = dict(zip(_tables.columns("swirl_edges"), edges[:, :n_edges]))

    def with_parameters(source, count):
        lam = source["lambda"]
        return {"lambda": lam,
                "rho": lam if parameter == "rho" else np.full(count, params.rho),
                "A": lam if parameter == "A" else np.full(count, params.A)}

    table = with_parameters(rows, n)
    for name in ("y1", "y2", "y3", "y4", "max_x1", "planar_stable", "max_abs_nu"):
        table[name] = rows[name]
    for i in range(1, 5):
        table[f"nu{i}"] = rows[f"re_nu{i}"] + 1j * rows[f"im_nu{i}"]
    table["swirl"] = rows["max_abs_nu"] > 1 + SWIRL_MARGIN
    table["branch"] = np.zeros(n, int)
    edge_table = with_parameters(edge_rows, n_edges)
    for name in ("y1", "y2", "y3", "y4", "max_x1", "refined"):
        edge_table[name] = edge_rows[name]
    edge_table["kind"] = np.array([KINDS[int(k)] for k in edge_rows["kind"]], dtype=object)
    edge_table["branch"] = np.zeros(n_edges, int)
    skipped = {}
    if conservative:
        why = ("no damping: the monodromy preserves volume, its stable multipliers sit on the "
               "unit circle, where the complex pairs' test vanishes identically")
        skipped = {"neimark_sacker (in the plane)": why, "neimark_sacker (out of it)": why}
    followed = (f"the branch through the planar orbit at {parameter} = "
                f"{getattr(b.first, parameter):.6g}",)
    band = SwirlBand(parameter, table, edge_table, bool(complete), message_text(message),
                     integration.method_used, skipped, followed)
    return with_partial(band, status, message, "swirl band")


def _reaches(band, b):
    """Whether the band's branch passes through the start orbit of BranchStart b (at b's
    end of the range): the same planar orbit to 1e-6."""
    lam, end = band.table["lambda"], getattr(b.first, band.parameter)
    y = np.stack([band.table[f"y{i}"] for i in range(1, 5)])
    at_end = np.flatnonzero(np.abs(lam - end) <= 1e-12 * max(1.0, abs(end)))
    scale = 1e-6 * max(1.0, np.abs(b.y0).max())
    return any(np.abs(y[:, j] - b.y0).max() <= scale for j in at_end)


def _merged(bands, others):
    """The SwirlBand of one or more branches (column ``branch``: the index in ``followed``)."""
    if len(bands) == 1:
        return replace(bands[0], others=others)
    table = {k: np.concatenate([band.table[k] for band in bands]) for k in bands[0].table}
    edges = {k: np.concatenate([band.edges[k] for band in bands]) for k in bands[0].edges}
    table["branch"] = np.concatenate([np.full(len(band.table["lambda"]), i)
                                      for i, band in enumerate(bands)])
    edges["branch"] = np.concatenate([np.full(len(band.edges["lambda"]), i)
                                      for i, band in enumerate(bands)])
    skipped = {k: v for band in bands for k, v in band.skipped.items()}
    return SwirlBand(bands[0].parameter, table, edges, all(band.complete for band in bands),
                     "; ".join(band.message for band in bands if band.message),
                     bands[0].method, skipped, sum((band.followed for band in bands), ()),
                     others)


@dataclass(frozen=True)
class SwirlBoundary:
    """The edges of the swirl band in (rho, A): the band along rho at each A of ``A``."""

    A: np.ndarray                #: the forcing amplitudes
    bands: tuple                 #: the SwirlBand in rho at each A
    edges: dict                  #: one row per edge: A, rho, y1..y4, max_x1, refined, kind,
                                 #: branch (the index in its band's followed)
    complete: bool               #: every band complete


def swirl_boundary(params: Parameters, rho_range, A_values, **band_options) -> SwirlBoundary:
    """The two-parameter boundary of the swirl band: ``swirl_band(params with A, rho_range,
    **band_options)`` at each A of A_values (keywords as swirl_band's: y0, periods, start,
    from_end, max_edges, continuation, integration)."""
    _checks.instance("params", params, Parameters)
    A_values = _checks.reals("A_values", A_values, ndim=1, min_size=1)
    bands = tuple(swirl_band(params.replace(A=float(a)), rho_range, **band_options)
                  for a in A_values)
    names = ("A", "rho", "y1", "y2", "y3", "y4", "max_x1", "refined", "kind", "branch")
    edges = {name: np.concatenate([band.edges[name] for band in bands]) for name in names}
    return SwirlBoundary(A_values, bands, edges, all(band.complete for band in bands))


@dataclass(frozen=True)
class SwirlBoundaryCurve:
    """The swirl boundary in (rho, A) continued as one curve: the points where an out-of-plane
    multiplier of the planar orbit is +1 (det(M_b - I) = 0; -1 for a period-doubling edge)."""

    kind: str                    #: the edge's kind: 'branch_point' or 'period_doubling'
    table: dict                  #: rho, A, y1..y4 (the planar orbit at tau = 0), max_x1, c
                                 #: (the edge's criticality, swirl_edge_criticality) along
                                 #: the curve (arclength order)
    at: dict                     #: the curve's points at the A of A_values, same columns
    folds: list                  #: the codimension-2 points, folds of the curve in A: dicts
                                 #: rho, A, y0, max_x1, c, kind ('closing': a least A of the
                                 #: band, where damping closes it; 'opening': a greatest A)
    degenerate: list             #: the codimension-2 points where c changes sign: dicts rho,
                                 #: A, y0, max_x1, c (~0), kind ('degenerate_pitchfork' on a
                                 #: branch_point curve, 'degenerate_flip'): on one side the
                                 #: onset of swirl is supercritical, on the other subcritical
    complete: bool               #: both ends left the box rho_range x A_range
    message: str                 #: why the continuation stopped early ('' if complete)


def swirl_boundary_curve(params: Parameters, rho_range, A_range, *, edge=0, A_values=(),
                         ds=0.1, max_points=400, tol=1e-12, shooting: Shooting = Shooting(),
                         integration: Integration = Integration(),
                         **band_options) -> SwirlBoundaryCurve:
    """Continue swirl edge number ``edge`` of ``swirl_band(params, rho_range, **band_options)``
    (at params.A) as a curve in (rho, A) (the core's sloshdyn_swirl_curve): pseudo-arclength in
    (rho, A/params.A) on g(rho, A) = det(M_b - I) = 0 (det(M_b + I) for a period-doubling edge;
    M_b the out-of-plane 4x4 block of the planar orbit's monodromy, rods included), the planar
    orbit followed by Newton shooting (``shooting``), both ways from the edge until the curve
    leaves rho_range x A_range (steps at most ``ds``, the first ds/4, at most max_points each
    way), a chord corrector to ``tol``. The curve's points at each A of A_values are located
    exactly (Newton in rho), and its folds in A, the codimension-2 points where the band closes
    (damped: the least A with swirl) or opens, where the curve's tangent turns in A; the
    edge's criticality c at every point (swirl_edge_criticality) and, where it changes sign,
    the degenerate pitchforks (flips) between super- and subcritical onset, located by
    Brent's method along the arclength. Raises
    ConvergenceError (with ``partial``) if the curve stops early."""
    _checks.instance("params", params, Parameters)
    _checks.instance("shooting", shooting, Shooting)
    _checks.instance("integration", integration, Integration)
    rho_range = sorted(_checks.real("rho_range", x) for x in rho_range)
    A_range = sorted(_checks.real("A_range", x) for x in A_range)
    A_values = (_checks.reals("A_values", A_values, ndim=1) if len(A_values) else np.zeros(0))
    ds, tol = _checks.real("ds", ds), _checks.real("tol", tol)
    max_points = _checks.integer("max_points", max_points, 2)
    band = swirl_band(params, rho_range, integration=integration, **band_options)
    n_edges = len(band.edges["rho"])
    edge = _checks.integer("edge", edge, 0)
    if edge >= n_edges or band.edges["kind"][edge] not in ("branch_point", "period_doubling"):
        raise InputError(f"edge = {edge}: the band at A = {params.A:g} has {n_edges} edge(s) "
                         f"of kinds {list(band.edges['kind'])}; the curve follows a "
                         "'branch_point' or 'period_doubling' edge")
    kind = band.edges["kind"][edge]
    y_edge = np.array([band.edges[f"y{i}"][edge] for i in range(1, 5)])
    capacity = _checks.output_size("max_points", 2 * max_points - 1,
                                   len(_tables.columns("swirl_boundary_curve")))
    (points, n, at, n_at, folds, n_folds, degenerate, n_degenerate, complete, status,
     message) = cancellable(
        _bridge.swirl_boundary_curve, *params.array(), _tables.code("special", kind),
        band.edges["rho"][edge], y_edge, 1, rho_range, A_range, A_values, ds, max_points, tol,
        shooting.newton_tol, shooting.max_iter, integration.array(), capacity,
        max(len(A_values) * (capacity - 1), 1), capacity)
    fold_rows = dict(zip(_tables.columns("swirl_curve_folds"), folds[:, :n_folds]))
    rows = dict(zip(_tables.columns("swirl_curve_degenerate"), degenerate[:, :n_degenerate]))
    curve = SwirlBoundaryCurve(
        kind, _curve_table(points[:, :n]), _curve_table(at[:, :n_at]),
        [{"rho": float(fold_rows["rho"][j]), "A": float(fold_rows["A"][j]),
          "y0": np.array([fold_rows[f"y{i}"][j] for i in range(1, 5)]),
          "max_x1": float(fold_rows["max_x1"][j]), "c": float(fold_rows["c"][j]),
          "kind": "closing" if fold_rows["closing"][j] else "opening"} for j in range(n_folds)],
        [{"rho": float(rows["rho"][j]), "A": float(rows["A"][j]),
          "y0": np.array([rows[f"y{i}"][j] for i in range(1, 5)]),
          "max_x1": float(rows["max_x1"][j]), "c": float(rows["c"][j]),
          "kind": "degenerate_pitchfork" if kind == "branch_point" else "degenerate_flip"}
         for j in range(n_degenerate)],
        bool(complete), message_text(message))
    return with_partial(curve, status, message, "swirl boundary curve")


def _curve_table(rows):
    return {name: rows[i].copy() for i, name in enumerate(_tables.columns("swirl_boundary_curve"))}


@dataclass(frozen=True)
class SwirlingBranch:
    """The swirling periodic orbits born at a swirl edge (a pitchfork of the planar orbit,
    multiplier +1 out of its plane), continued in rho or A on the 8 states."""

    parameter: str               #: 'rho' or 'A'
    table: dict                  #: lambda, rho, A, y1..y8 (states at tau = 0), max_x1,
                                 #: swirl_amplitude (max|y1|), angular_momentum (mean L_z),
                                 #: stable, mu1..mu8 (complex Floquet multipliers)
    special_points: list         #: PeriodicSpecialPoint (kind, rho, A, max_x1, y0: 8 states):
                                 #: fold, branch_point, period_doubling, neimark_sacker
    complete: bool
    message: str                 #: why an incomplete branch stopped ('' if complete)
    method: str                  #: the integration method used ('auto' resolved)


def swirling_branch(band: SwirlBand, edge=0, lambda_range=None, *, ds=None,
                    continuation: Continuation = PERIODIC_CONTINUATION,
                    integration: Integration = Integration(), params: Parameters = None,
                    periods=1) -> SwirlingBranch:
    """Switch at edge number ``edge`` of ``band`` (a 'branch_point' edge: an out-of-plane
    multiplier through +1) onto the swirling orbits and continue them over lambda_range (the
    band's parameter; default: the band's range) with their 8 Floquet multipliers, folds,
    branch points, period doublings and Neimark-Sacker points. ``ds``: the first step off the
    edge along the critical eigenvector (default continuation.ds); its sign picks one of the two
    mirror-image branches. ``params``: the band's parameters (needed for the fixed one and the
    model). Raises ConvergenceError (with ``partial``) if the branch stops early."""
    _checks.instance("band", band, SwirlBand)
    _checks.instance("params", params, Parameters)
    _checks.instance("continuation", continuation, Continuation)
    _checks.instance("integration", integration, Integration)
    n_edges = len(band.edges["lambda"])
    edge = _checks.integer("edge", edge, 0)
    if edge >= n_edges or band.edges["kind"][edge] != "branch_point":
        raise InputError(f"edge = {edge}: the band has {n_edges} edge(s) of kinds "
                         f"{list(band.edges['kind'])}; swirling orbits are born at a "
                         "'branch_point' edge")
    parameter = band.parameter
    at = params.replace(**{parameter: float(band.edges["lambda"][edge])})
    if lambda_range is None:
        lambda_range = (band.table["lambda"].min(), band.table["lambda"].max())
    low, high = (_checks.real("lambda_range", x) for x in lambda_range)
    step = continuation.ds if ds is None else _checks.real("ds", ds)
    settings = continuation_array(replace(continuation, ds=step), 1.0)
    max_points = _checks.output_size("max_points", _checks.integer(
        "max_points", continuation.max_points, 1), len(_tables.columns("swirling_branch")))
    y_edge = np.array([band.edges[f"y{i}"][edge] for i in range(1, 5)])
    points, n, special, n_special, complete, status, message = cancellable(
        _bridge.swirling_branch, *at.array(), _tables.code("excitation_parameters", parameter),
        y_edge, _checks.integer("periods", periods, 1), low, high, settings,
        integration.array(), max_points, 4 * max_points)
    rows = dict(zip(_tables.columns("swirling_branch"), points[:, :n]))
    lam = rows["lambda"]
    table = {"lambda": lam, "rho": lam if parameter == "rho" else np.full(n, params.rho),
             "A": lam if parameter == "A" else np.full(n, params.A)}
    for i in range(1, 9):
        table[f"y{i}"] = rows[f"y{i}"]
    for name in ("max_x1", "swirl_amplitude", "angular_momentum", "stable"):
        table[name] = rows[name]
    for i in range(1, 9):
        table[f"mu{i}"] = rows[f"re_mu{i}"] + 1j * rows[f"im_mu{i}"]
    specials = []
    for column in special[:, :n_special].T:
        point = dict(zip(_tables.columns("swirling_special_points"), column))
        value = float(point["lambda"])
        specials.append(PeriodicSpecialPoint(
            KINDS[int(point["kind"])], value if parameter == "rho" else params.rho,
            value if parameter == "A" else params.A, float(point["max_x1"]),
            np.array([point[f"y{i}"] for i in range(1, 9)])))
    branch = SwirlingBranch(parameter, table, specials, bool(complete), message_text(message),
                            integration.method_used)
    return with_partial(branch, status, message, "swirling branch")


@dataclass(frozen=True)
class SwirlOrbit:
    """A periodic orbit of period k T (T = 2 pi/rho) of the spatial model under the ground
    motion of params along x, through y0 at forcing phase 0: a swirling orbit (liquid rotating
    about the vertical) when it leaves the plane."""

    y0: np.ndarray                #: the 8 states at tau = 0
    multipliers: np.ndarray       #: its 8 Floquet multipliers (complex)
    max_x1: float                 #: max|x1| over the orbit (in-plane tilt / theta0)
    swirl_amplitude: float        #: max|y1| over the orbit (out-of-plane tilt / theta0)
    angular_momentum: float       #: L_z about the vertical averaged over the orbit [M L^2 omega]
    iterations: int               #: Newton iterations
    periods: int                  #: k
    method: str                   #: the integration method used ('auto' resolved)

    @property
    def direction(self) -> str:
        """'counter-clockwise' (L_z > 0, seen from above), 'clockwise' (L_z < 0) or 'planar'."""
        if self.angular_momentum > 0:
            return "counter-clockwise"
        return "clockwise" if self.angular_momentum < 0 else "planar"

    @property
    def stable(self) -> bool:
        """All its Floquet multipliers inside the unit circle."""
        return bool(np.abs(self.multipliers).max() < 1)


def swirl_orbit(params: Parameters, y0=None, *, periods=1, transient=None, perturbation=0.05,
                azimuth=0.0, ellipticity=0.0, shooting: Shooting = Shooting(),
                integration: Integration = Integration()) -> SwirlOrbit:
    """The periodic orbit of the spatial model near y0 (8 states at tau = 0), found by Newton
    shooting on the 8-dimensional system after ``transient`` periods k T of integration from y0
    (default 0), the ground moving along ``azimuth`` (and ``ellipticity`` times it across, as
    in ``simulate``). With y0 None: from the planar periodic orbit (``periodic_orbit(params)``,
    in the xz plane) with y1 = ``perturbation`` max|x1| out of its plane, after ``transient`` =
    400 periods by default, so that inside the swirl band the orbit found is the (stable)
    swirling one. The namelist's door is kind = 'steady_state' with planar = .false."""
    _checks.instance("params", params, Parameters)
    _checks.instance("shooting", shooting, Shooting)
    _checks.instance("integration", integration, Integration)
    spatial = _spatial_array(azimuth, ellipticity)
    periods = _checks.integer("periods", periods, 1)
    if y0 is None:
        planar = periodic_orbit(params, periods=periods, shooting=shooting,
                                integration=integration)
        push = _checks.real("perturbation", perturbation) * planar.max_x1
        y0 = np.concatenate([planar.y0, [push, 0.0, 0.0, 0.0]])
        transient = 400 if transient is None else transient
    y0 = _checks.reals("y0", y0, (8,))
    transient = _checks.integer("transient", 0 if transient is None else transient, 0)
    y, multipliers, info, status, message = cancellable(
        _bridge.swirl_orbit, *params.array(), spatial, y0, periods, transient, integration.array(),
        shooting.newton_tol, shooting.max_iter)
    check_status(status, message, "swirl orbit")
    info = _tables.unpack("swirl_orbit_info", info)
    return SwirlOrbit(y, multipliers[0] + 1j * multipliers[1], float(info["max_x1"]),
                      float(info["swirl_amplitude"]), float(info["angular_momentum"]),
                      int(info["iterations"]), periods, integration.method_used)


@dataclass(frozen=True)
class SeismicResponse2D:
    """A tank at rest under ground motion in two horizontal components, SI units
    (docs/model.md, "Spatial model and swirl"). ``table``: one array per column of the core's
    'seismic_spatial' table (names without units): t [s], ground_acceleration_x and _y
    [m/s^2], wave_height_x and _y [m] (the wall's wave height is
    wave_height_x cos(psi) + wave_height_y sin(psi) at azimuth psi: the free wave's), wave_height
    [m] (its maximum over the wall, capped at the roof) and wave_azimuth [rad] (where),
    base_shear_x, _y and the resultant base_shear [N], overturning_moment_x, _y (of the forces
    along x and y) and the resultant [N m], x1, x2, y1, y2, free_wave_height [m] (the largest
    over the wall of the tank without a roof). As the planar run: the tank without contact
    below its roof, the restricted-sloshing method above it. ``peaks``: the
    'seismic_spatial_peaks' (the spatial peaks over the output times with their azimuth and
    times; the peaks of the two planar runs, one per component, and the codes' SRSS and 100/30
    combinations of them; the roof's verdict on the free wave around the wall, roof_reached,
    first_roof_time [s] and first_contact_azimuth [rad], roof_impacts, free_wave_height,
    roof_excess, and its loads roof_head, roof_uplift_force, confined_convective_mass)."""

    table: dict
    peaks: dict
    method: str                  #: the integration method used ('auto' resolved)

    def wave_height_at(self, azimuth):
        """The wave height at the wall at azimuth [rad] (from the x axis) over time [m]."""
        a = _checks.real("azimuth", azimuth)
        return self.table["wave_height_x"] * np.cos(a) + self.table["wave_height_y"] * np.sin(a)


def seismic_response_2d(tank, ground_motion, ground_motion_2=None, t_end=None, n_out=None, *,
                        azimuth=0.0, ellipticity=0.0,
                        integration: Integration = Integration()) -> SeismicResponse2D:
    """The tank (sloshdyn.Tank) at rest at t = 0 under ground_motion along ``azimuth`` [rad,
    from the x axis] and ground_motion_2 across it: two records with one dt (scale both by one
    factor, as FEMA P695 does, before passing them), or (ground_motion harmonic,
    ground_motion_2 None) harmonic motion with ``ellipticity`` (the minor axis of the ellipse
    over the major). t_end and n_out default as for ``seismic_response``, to the longer
    record's end."""
    _checks.instance("tank", tank, Tank)
    _checks.instance("ground_motion", ground_motion, GroundMotion)
    _checks.instance("integration", integration, Integration)
    if ground_motion_2 is not None:
        _checks.instance("ground_motion_2", ground_motion_2, GroundMotion)
    times = seismic_defaults(tank, ground_motion, t_end, n_out, ground_motion_2=ground_motion_2)
    _checks.output_size("n_out", times.n_out, len(_tables.columns("seismic_spatial")))
    ground, samples = ground_motion._arrays()
    ground_2, samples_2 = (ground_motion_2._arrays() if ground_motion_2 is not None
                           else (np.zeros_like(ground), np.zeros(0)))
    table, peaks, status, message = cancellable(
        _bridge.seismic_response_spatial, tank.array(), ground, samples, ground_2, samples_2,
        _spatial_array(azimuth, ellipticity), times.t_end, times.n_out, integration.array())
    check_status(status, message)
    name = lambda column: column.split(" [")[0]   # noqa: E731
    return SeismicResponse2D(
        {name(c): row.copy() for c, row in zip(_tables.columns("seismic_spatial"), table)},
        {name(c): float(v) for c, v in zip(_tables.columns("seismic_spatial_peaks"), peaks)},
        integration.method_used)
