"""Basins of attraction at fixed forcing: a grid of initial states, each run to its attractor,
the attractors told apart by their orbits (the shooting code) and listed."""

from __future__ import annotations

import dataclasses
import json
import time

import numpy as np

from .. import _checks, _core
from .._errors import InputError
from ..parameters import Parameters
from ..options import Integration, Steady
from .engine import SECONDS, Plan, Variable, positive_int, run_plan, version
from .points import (MAX_PERIOD, MOTIONS, SUMMARY_COLUMNS, common_attrs, orbit_rows,
                     point_messages, settings_arrays, summary_variables, unpack)

_bridge = _core.sloshdyn_bridge_studies

#: Initial states of a task handed to the core's ensemble integrator together (attractor_points'
#: block): each point is its steady state alone, bit for bit, whatever the block
#: (tests/python/test_steady_blocks.py); the size by measurement (benchmarks/README.md,
#: "Steady states in blocks").
ENSEMBLE_BLOCK = 16


def _basin_task(rpar, ipar, y0, integration, steady):
    """One task of a basin study: the block's initial states (4, n1, n2) to their attractors."""
    start = time.perf_counter()
    shape = y0.shape[1:]
    n = int(np.prod(shape))
    flat = np.asfortranarray(y0.reshape(4, n))
    summaries, y_end, orbit, points, status, messages, _, _ = _bridge.attractor_points(
        rpar, ipar, flat, integration, steady, ENSEMBLE_BLOCK)
    impact = (summaries[SUMMARY_COLUMNS.index("max_x1")] >= 1).astype(np.int32)
    out = unpack(summaries, orbit, impact, status, shape)
    out["message"] = point_messages(status, messages).reshape(shape)
    out["transient_periods"] = summaries[SUMMARY_COLUMNS.index("transient_periods")].reshape(shape)
    rows = orbit_rows(orbit)
    out["orbit_found"] = np.where(status == 0, rows["found"], -1).astype(np.int8).reshape(shape)
    out["max_multiplier"] = rows["max_mu"].reshape(shape)
    out["orbit_state"] = np.stack([rows[f"y{i}"].reshape(shape) for i in range(1, 5)], axis=-1)
    out["orbit_points"] = points.reshape((4, MAX_PERIOD) + shape).transpose(2, 3, 1, 0)
    out["final_state"] = y_end.reshape((4,) + shape).transpose(1, 2, 0)
    out[SECONDS] = time.perf_counter() - start
    return out


def basins(params: Parameters, x1_range, dx1_range, n=50, store=None, *, x2=0.0, dx2=0.0,
           client=None, scheduler=None, workers=None, worker_kind=None, min_workers=None,
           grace_time=None,
           steady: Steady = Steady(), integration: Integration = Integration(), tol=1e-3,
           points_per_task=None, progress=True):
    """Basins of attraction at fixed forcing (params' rho and A): an n x n grid of initial
    states (x1, x1') over x1_range x dx1_range with x2 = x2, x2' = dx2, each run to its steady
    state and classified by the attractor it reaches. Periodic attractors are identified by
    their orbit through the shooting code (Newton on the orbit of period k T, Floquet
    multipliers); two runs share an attractor when their orbits' Poincare points coincide
    within tol (relative); quasi-periodic, irregular and settling runs form one class each.

    Returns a Dataset with dimensions (x1, dx1) [the initial states], the variable 'attractor'
    (label 1.. per point), and the attractors listed along dimension 'attractor_id' with their
    kind, period, stability (largest Floquet multiplier), share of the grid and orbit state."""
    if not isinstance(params, Parameters):
        raise InputError(f"params = {type(params).__name__} is not valid: give sloshdyn.Parameters")
    if store is None:
        raise InputError("store is missing: give the path of a Zarr store for the study")
    n = positive_int("n", n, 2)
    ranges = []
    _checks.output_size("n", n * n, 4 * (MAX_PERIOD + 3) + len(SUMMARY_COLUMNS))
    for name, r in (("x1_range", x1_range), ("dx1_range", dx1_range)):
        lo, hi = _checks.interval(name, r)
        if not lo < hi:
            raise InputError(f"{name} = {r!r} is not valid: low < high")
        ranges.append(np.linspace(lo, hi, n))
    x2, dx2, tol = _checks.real("x2", x2), _checks.real("dx2", dx2), _checks.real("tol", tol)
    if not 0 < tol < 1:
        raise InputError(f"tol = {tol!r} is not valid: it must lie in (0, 1)")
    if not params.rho > 0:
        raise InputError(f"rho = {params.rho} is not valid: basins need a forcing frequency rho > 0")
    steady_array, integration_array = settings_arrays(steady, integration)
    ppt = None if points_per_task is None else positive_int("points_per_task", points_per_task)

    def chunking(ppt):
        b1 = min(n, ppt)
        return b1, max(1, min(n, ppt // b1))
    x1, dx1 = ranges
    grid = np.zeros((4, n, n))
    grid[0], grid[1] = np.meshgrid(x1, dx1, indexing="ij")
    grid[2], grid[3] = x2, dx2
    rpar, ipar = params.array()

    def task(block):
        return _basin_task, (rpar, ipar, np.ascontiguousarray(grid[(slice(None),) + block]),
                             integration_array, steady_array)

    dims = ("x1", "dx1")
    variables = summary_variables(dims, what="steady state from the initial state")
    variables["transient_periods"] = Variable(dims, "f8", np.nan, {
        "units": "forcing periods", "long_name": "transient integrated before measuring"})
    variables["orbit_found"] = Variable(dims, "i1", -1, {
        "units": "1", "flag_values": [-1, 0, 1, 2],
        "flag_meanings": "not_computed none jumped_by_shooting refined_by_shooting",
        "long_name": "how the periodic orbit reached was found by the shooting code"})
    variables["max_multiplier"] = Variable(dims, "f8", np.nan, {
        "units": "1", "long_name": "largest Floquet multiplier modulus of the orbit reached"})
    variables["orbit_state"] = Variable(dims + ("state",), "f8", np.nan, {
        "units": "1", "long_name": "state (x1, x1', x2, x2') of the orbit reached at forcing "
                                   "phase 0, by shooting"})
    variables["orbit_points"] = Variable(dims + ("orbit_point", "state"), "f8", np.nan, {
        "units": "1", "long_name": "Poincare points of the orbit reached over one orbit period "
                                   "(NaN beyond its period and for other motions)"})
    variables["final_state"] = Variable(dims + ("state",), "f8", np.nan, {
        "units": "1", "long_name": "state at the end of the measuring window (forcing phase 0)"})
    spec = {"kind": "basins", "parameters": dataclasses.asdict(params), "x1": x1.tolist(),
            "dx1": dx1.tolist(), "x2": float(x2), "dx2": float(dx2),
            "steady": dataclasses.asdict(steady), "integration": dataclasses.asdict(integration),
            "version": version()}
    attrs = common_attrs("basins", params, steady, integration, {
        "x2": float(x2), "dx2": float(dx2), "tol": float(tol),
        "study_spec": json.dumps(spec, sort_keys=True)})
    plan = Plan("basins", dims, {
        "x1": (x1, {"units": "1", "long_name": "initial x1 = theta/theta0 (pendulum)"}),
        "dx1": (dx1, {"units": "1", "long_name": "initial x1' = dx1/dtau, tau = omega t"}),
        "state": (np.array(["x1", "dx1", "x2", "dx2"]), {"long_name": "state component"}),
        "orbit_point": (np.arange(1, MAX_PERIOD + 1), {
            "units": "1", "long_name": "Poincare point of the orbit, in time order"})},
        variables, attrs, spec, None, task, chunking, ppt)
    return run_plan(plan, store, client=client, scheduler=scheduler, workers=workers,
                    worker_kind=worker_kind, min_workers=min_workers,
                    grace_time=grace_time, progress=progress,
                    derive=lambda ds: _label_basins(ds, tol))


def _label_basins(ds, tol):
    """The attractor of every run (Fortran label_attractors) and the attractor list."""
    n1, n2 = ds.sizes["x1"], ds.sizes["dx1"]
    motion = ds["motion"].values.astype(np.float64).ravel()
    motion[motion <= 0] = np.nan
    period = ds["period"].values.astype(np.float64).ravel()
    points = np.asfortranarray(ds["orbit_points"].values.reshape(n1 * n2, MAX_PERIOD, 4)
                               .transpose(2, 1, 0))
    label, count, first = _bridge.label_attractors(motion, period, points, float(tol))
    ds["attractor"] = (("x1", "dx1"), label.reshape(n1, n2).astype(np.int16), {
        "units": "1", "long_name": "attractor reached (1.. as listed along attractor_id; 0: "
                                   "failed run)"})
    first = first[:count] - 1
    flat = {name: ds[name].values.reshape(n1 * n2, *ds[name].shape[2:])
            for name in ("motion", "period", "max_multiplier", "orbit_state", "max_x1")}
    kinds = [MOTIONS.get(int(flat["motion"][i]), "failed") for i in first]
    share = np.array([(label == j + 1).sum() for j in range(count)]) / max(1, label.size)
    mu = flat["max_multiplier"][first]
    stability = np.array(["stable" if (k == "periodic" and m < 1) else
                          "unstable" if (k == "periodic" and m >= 1) else
                          "unknown" if k == "periodic" else "n/a"
                          for k, m in zip(kinds, mu)])
    ids = np.arange(1, count + 1)
    ds = ds.assign_coords(attractor_id=("attractor_id", ids, {"long_name": "attractor label"}))
    ds["attractor_kind"] = ("attractor_id", np.array(kinds, dtype=object).astype(str),
                            {"long_name": "kind of motion of the attractor"})
    ds["attractor_period"] = ("attractor_id", flat["period"][first].astype(np.int16),
                              {"units": "forcing periods", "long_name": "period (0: not periodic)"})
    ds["attractor_stability"] = ("attractor_id", stability, {
        "long_name": "Floquet stability of a periodic attractor (largest |multiplier| < 1)"})
    ds["attractor_max_multiplier"] = ("attractor_id", mu, {
        "units": "1", "long_name": "largest Floquet multiplier modulus (NaN: not periodic)"})
    ds["attractor_share"] = ("attractor_id", share, {
        "units": "1", "long_name": "fraction of the grid's initial states that reach it"})
    ds["attractor_max_x1"] = ("attractor_id", flat["max_x1"][first], {
        "units": "1", "long_name": "max |x1| of the attractor (first run reaching it)"})
    ds["attractor_state"] = (("attractor_id", "state"), flat["orbit_state"][first], {
        "units": "1", "long_name": "orbit state at forcing phase 0 (shooting; NaN if not periodic)"})
    return ds
