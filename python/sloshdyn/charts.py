"""Stability charts in two parameters: the fold and Hopf curves of the slow flow's steady states
with their codimension-2 points, and the number of stable steady states in each cell of a grid
(optionally found again by brute-force integration). The Fortran core computes everything
(sloshdyn_stability_chart); the namelist's `kind = 'stability_chart'` with `&chart` is the
same computation.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from . import _checks, _core, _tables
from ._errors import CapacityError, check_status
from .ground import acceleration_factor
from .options import Chart, Continuation
from .parameters import Parameters

_bridge = _core.sloshdyn_bridge_charts
AXES = _tables.names("chart_axes")[0]             #: the chart parameters: rho, A, gamma, kappa
MODELS = _tables.names("chart_models")[0]         #: 'slow_flow_3:1', 'slow_flow_nonresonant'
CURVE_KINDS = _tables.codes("curve")              #: {1: 'fold', 2: 'hopf', ...}
CODIM2_KINDS = _tables.codes("codim2")            #: {0: 'none', 1: 'bogdanov_takens', ...}
CURVE_ENDS = _tables.codes("curve_end")


@dataclass(frozen=True)
class Curve:
    """A fold or Hopf curve, point by point along it (rho, A, gamma and kappa at every point; two
    of them vary). state: (4, n) slow-flow state (Re B1, Im B1, Re B2, Im B2; the last two 0 without the
    internal resonance); omega: Hopf frequency (slow time; negative on a neutral-saddle part, 0
    for folds); l1: first Lyapunov coefficient along a Hopf curve (< 0 supercritical);
    codim2: the kind of each point ('none' for a regular one)."""

    kind: str
    rho: np.ndarray
    A: np.ndarray
    gamma: np.ndarray
    kappa: np.ndarray
    state: np.ndarray
    omega: np.ndarray
    l1: np.ndarray
    codim2: list
    complete: bool
    ends: tuple                 #: how the curve ends at its first and last point
    note: str                   #: why an incomplete curve stopped ('' if complete)


@dataclass(frozen=True)
class Codim2Point:
    """A codimension-2 point: 'cusp', 'bogdanov_takens', 'fold_hopf', 'generalised_hopf'."""

    kind: str
    rho: float
    A: float
    gamma: float
    kappa: float
    omega: float
    curve: int                  #: index into StabilityChart.curves


@dataclass(frozen=True)
class StabilityChart:
    """A chart in (x, y) = two of rho, A, gamma, kappa: its curves, codimension-2 points and
    grid (arrays over the cells: rho, A, gamma, kappa, n_stable, n_steady, near_curve (1/0),
    brute_force_stable (-1: not computed))."""

    x: str
    y: str
    model: str
    curves: list
    codim2_points: list
    grid: dict
    complete: bool
    params: Parameters = field(repr=False)   #: None for a chart read from files

    def frequency_and_acceleration(self, tank, rho, A, *, units="g"):
        """(frequency [Hz], peak ground acceleration [units]) of chart points of a tank's model:
        f = rho omega/(2 pi), a = A rho^2 L omega^2 (harmonic ground motion)."""
        p = tank.properties
        rho, A = np.asarray(rho, dtype=float), np.asarray(A, dtype=float)
        acceleration = A * rho**2 * p["support_height"] * p["omega"] ** 2
        # 'g' is the tank's gravity, as before (acceleration_factor's g is standard gravity)
        scale = tank.gravity if units == "g" else acceleration_factor(units)
        return rho * p["omega"] / (2 * math.pi), acceleration / scale


def stability_chart(params: Parameters, x_range, y_range, *, x="rho", y="A",
                    model="slow_flow_3:1", chart: Chart = Chart(),
                    continuation: Continuation = Continuation(), threads=1,
                    capacity=200_000) -> StabilityChart:
    """The stability chart of the slow flow of `params` (model 'slow_flow_3:1' or
    'slow_flow_nonresonant') for x in x_range and y in y_range: x is rho or A (it is varied by
    the one-parameter runs at chart.n_y values of y, which seed the curves), y any other of
    rho, A, gamma, kappa; the values of the others come from params. A curve that stops early
    is kept up to where it stopped (complete False, with its note) and a warning is issued.
    threads share out the runs and cells (same result on any number); capacity: room for the
    curves' points. The one-parameter runs search and continue steady states with the settings
    of `continuation` (as frequency_response; its n_scan is chart.n_scan)."""
    _checks.instance("params", params, Parameters)
    _checks.instance("chart", chart, Chart)
    _checks.instance("continuation", continuation, Continuation)
    _checks.choice("model", model, MODELS)
    _checks.choice("x", x, AXES)
    _checks.choice("y", y, AXES)
    (x_min, x_max), (y_min, y_max) = (_checks.interval("x_range", x_range),
                                      _checks.interval("y_range", y_range))
    threads, capacity = _checks.integer("threads", threads), _checks.integer("capacity", capacity)
    n_x, n_y, max_curves = chart.n_x, chart.n_y, chart.max_curves
    _checks.output_size("capacity", max(capacity, 1), len(_tables.columns("chart_curves")))
    _checks.output_size("max_curves", 10 * max(max_curves, 1), len(_tables.columns("chart_codim2")))
    _checks.output_size("n_x * n_y", max(n_x, 1) * max(n_y, 1), len(_tables.columns("chart_grid")))
    chart_range = _tables.pack("chart_range", {
        "model": _tables.code("chart_models", model), "x": _tables.code("chart_axes", x),
        "y": _tables.code("chart_axes", y), "x_min": x_min, "x_max": x_max, "y_min": y_min,
        "y_max": y_max, "threads": threads})
    n_cells = max(n_x, 1) * max(n_y, 1)
    (curves, codim2, ends, grid, sizes, complete, notes, status,
     message) = _bridge.stability_chart(*params.array(), chart.array(), chart_range,
                                        continuation.array(), max(capacity, 1),
                                        10 * max(max_curves, 1), max(max_curves, 1), n_cells)
    used = _tables.unpack("chart_sizes", sizes)
    if status == CapacityError.status:   # name the Python argument that sets the room
        message = (_tables._text(message) + f"; give capacity >= {int(used['curve_points'])} "
                   f"(now {int(capacity)})")
    check_status(status, message)
    chart = _chart(x, y, model, curves[:, :used["curve_points"]],
                   codim2[:, :used["codim2_points"]], ends[:, :used["curves"]],
                   grid[:, :used["cells"]], bool(complete), _tables._text(notes), params)
    if not chart.complete:
        warnings.warn("stability chart: not every curve could be continued to its ends:\n"
                      + _tables._text(notes), stacklevel=2)
    return chart


def _chart(x, y, model, curves, codim2, ends, grid, complete, notes, params):
    """A StabilityChart from the core's tables (the columns of the chart CSV files)."""
    note_of = {}
    for line in notes.splitlines():
        head, _, text = line.partition(": ")
        note_of[int(head.split()[1])] = text
    columns = _tables.columns("chart_curves")
    table = dict(zip(columns, curves))
    curve_list = []
    for k, column in enumerate(ends.T, start=1):
        end = dict(zip(_tables.columns("chart_ends"), column))
        on = table["curve"] == k
        curve_list.append(Curve(
            kind=CURVE_KINDS[int(end["kind"])], rho=table["rho"][on], A=table["A"][on],
            gamma=table["gamma"][on], kappa=table["kappa"][on],
            state=np.array([table[f"x{i}"][on] for i in range(1, 5)]),
            omega=table["omega"][on], l1=table["l1"][on],
            codim2=[CODIM2_KINDS[int(c)] for c in table["codim2"][on]],
            complete=bool(end["complete"]),
            ends=(CURVE_ENDS[int(end["first_end"])], CURVE_ENDS[int(end["last_end"])]),
            note=note_of.get(k, "")))
    points = []
    for column in codim2.T:
        point = dict(zip(_tables.columns("chart_codim2"), column))
        points.append(Codim2Point(CODIM2_KINDS[int(point["kind"])],
                                  *(float(point[name]) for name in ("rho", "A", "gamma", "kappa",
                                                                    "omega")),
                                  int(point["curve"]) - 1))
    grid_table = {name: values.copy() for name, values in zip(_tables.columns("chart_grid"), grid)}
    return StabilityChart(x, y, model, curve_list, points, grid_table, complete, params)


def chart_from_files(directory, x="rho", y="A", model="slow_flow_3:1", params=None):
    """A StabilityChart from the CSV files of the executable (chart_curves.csv, chart_codim2.csv,
    chart_ends.csv, chart_grid.csv in directory)."""
    import csv
    from pathlib import Path

    def read(name, table):
        with open(Path(directory) / name, newline="") as f:
            rows = list(csv.reader(f))[1:]
        codes = {"k": {v: c for c, v in CURVE_KINDS.items()},
                 "d": {v: c for c, v in CODIM2_KINDS.items()},
                 "e": {v: c for c, v in CURVE_ENDS.items()}}
        formats = _tables.names(f"formats:{table}")[0][0]
        data = np.array([[codes[f][v] if f in codes else float(v) for f, v in zip(formats, row)]
                         for row in rows], dtype=float).reshape(len(rows), len(formats))
        return data.T

    ends = read("chart_ends.csv", "chart_ends")
    table = dict(zip(_tables.columns("chart_ends"), ends))
    notes = "\n".join(f"curve {int(curve)}: stopped ({CURVE_ENDS[int(last)]})" for curve, last, done
                      in zip(table["curve"], table["last_end"], table["complete"]) if not done)
    return _chart(x, y, model, read("chart_curves.csv", "chart_curves"),
                  read("chart_codim2.csv", "chart_codim2"), ends,
                  read("chart_grid.csv", "chart_grid"), bool(np.all(table["complete"] > 0)), notes,
                  params)
