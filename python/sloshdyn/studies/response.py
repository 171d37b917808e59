"""Response maps: steady states on a grid of forcing frequency x amplitude, from rest and,
optionally, along the sweeps in frequency that carry the state (hysteresis, jumps)."""

from __future__ import annotations

import dataclasses
import json
import time

import numpy as np

from .. import _checks, _core, _tables
from .._errors import InputError
from ..ground import GroundMotion
from ..options import Integration, Steady
from ..parameters import Parameters
from ..tank import Tank
from .engine import SECONDS, Plan, Variable, axis, positive_int, run_plan, version
from .points import (SUMMARY_COLUMNS, common_attrs, orbit_rows, point_messages,
                     settings_arrays, summary_variables, unpack)

_bridge = _core.sloshdyn_bridge_studies

#: Independent points of a task handed to the core's ensemble integrator together (steady_path's
#: block): each point is its steady state alone, bit for bit, whatever the block
#: (tests/python/test_steady_blocks.py); the size by measurement (benchmarks/README.md,
#: "Steady states in blocks").
ENSEMBLE_BLOCK = 16


def _response_task(rpar, ipar, rho, A, integration, steady, continuation, with_grid=False):
    """One task of a response map: the block's points from rest, and (continuation) each
    amplitude column swept up and/or down in frequency carrying the state. Runs on a worker."""
    start = time.perf_counter()
    shape = rho.shape
    n = rho.size
    flat_rho = np.ascontiguousarray(rho.ravel())
    flat_a = np.ascontiguousarray(A.ravel())
    summaries, y_end, orbit, impact, status, messages, _, _ = _bridge.steady_path(
        rpar, ipar, flat_rho, flat_a, np.zeros((4, n), order="F"), 0, integration, steady,
        ENSEMBLE_BLOCK)
    out = unpack(summaries, orbit, impact, status, shape)
    out["message"] = point_messages(status, messages).reshape(shape)
    out["transient_periods"] = summaries[SUMMARY_COLUMNS.index("transient_periods")].reshape(shape)
    rows = orbit_rows(orbit)
    out["shooting"] = np.where(status == 0, rows["found"], -1).astype(np.int8).reshape(shape)
    out["max_multiplier"] = rows["max_mu"].reshape(shape)
    for direction in continuation:
        parts = []
        for j in range(shape[1]):
            order = slice(None) if direction == "up" else slice(None, None, -1)
            r = np.ascontiguousarray(rho[order, j])
            a = np.ascontiguousarray(A[order, j])
            s, _, o, imp, st, texts, _, _ = _bridge.steady_path(
                rpar, ipar, r, a, np.zeros((4, len(r)), order="F"), 1, integration, steady, 1)
            part = unpack(s, o, imp, st, (len(r), 1), suffix=f"_{direction}")
            part[f"message_{direction}"] = point_messages(st, texts, carried=True)[:, None]
            parts.append({k: v[order] for k, v in part.items()})
        for k in parts[0]:
            out[k] = np.concatenate([p[k] for p in parts], axis=1)
    if with_grid:
        out["rho"], out["A"] = rho, A
    out[SECONDS] = time.perf_counter() - start
    return out


def _tank_grid(tank, f, a, units):
    """(rho, A) at every (frequency [Hz], peak ground acceleration [units]) of a tank at
    constant acceleration, as Tank.parameters gives them for harmonic ground motion."""
    rho = np.empty((len(f), len(a)))
    amplitude = np.empty_like(rho)
    for i, fi in enumerate(f):
        for j, aj in enumerate(a):
            # A is linear in the acceleration: at a = 0 it is 0 (the rho of any a)
            p = tank.parameters(GroundMotion.harmonic(aj if aj > 0 else 1.0, fi, units=units))
            rho[i, j], amplitude[i, j] = p.rho, (p.A if aj > 0 else 0.0)
    tank.parameters().replace(rho=float(rho.max()), A=float(amplitude.max()))   # range rules
    return rho, amplitude


def response_map(params_or_tank, frequencies, amplitudes, store, *, client=None, scheduler=None,
                 workers=None, worker_kind=None, min_workers=None, grace_time=None,
                 steady: Steady = Steady(),
                 integration: Integration = Integration(), continuation="none",
                 points_per_task=None, progress=True, units="g"):
    """Steady states on a grid of forcing frequency x amplitude, as an xarray Dataset with
    dimensions (frequency, amplitude) written to the Zarr store `store` as tasks finish.

    params_or_tank: sloshdyn.Parameters, with frequencies rho = Omega/omega and amplitudes the
    dimensionless A = u0/L; or a sloshdyn.Tank, with frequencies in Hz and amplitudes the peak
    ground acceleration in `units` (constant along the frequency axis: A = a/(L Omega^2)), the
    point's rho and A as variables. Every point is the steady state from rest with the given
    settings, equal bit for bit to sloshdyn.steady_state(params.replace(rho=..., A=...),
    steady=..., integration=...). continuation (a name of the core's 'continuations': 'none',
    'up', 'down' or 'both') adds, for each amplitude, the sweep
    along the frequency axis that carries the state from point to point (variables ``*_up``,
    ``*_down``): where they differ from the points from rest, the response is multi-valued
    (hysteresis, jumps).

    The study runs on `client` (a dask.distributed Client), on the scheduler at address
    `scheduler`, or (neither given) on an embedded local cluster of `workers` workers (default:
    one per core) of kind `worker_kind` ('threads' by default, 'processes'). It waits for
    `min_workers` workers able to run it (default 1) at its start, and for one whenever none
    is alive, at most `grace_time` seconds (default studies.GRACE_TIME) each time, then fails
    with ClusterError naming the cause; a worker that cannot import sloshdyn, or imports
    another version, is refused by name. A point that fails is stored with its status and
    message (attrs['points_failed'] counts them). Rerunning the same study on the same store
    resumes it; a store made by a different study is refused (InputError). See
    docs/studies.md."""
    tank = None
    f = axis("frequencies", frequencies, 0.0)
    a = axis("amplitudes", amplitudes, 0.0, lower_open=False)
    if isinstance(params_or_tank, Parameters):
        params = params_or_tank
        params.replace(rho=float(f.max()), A=float(a.max()))      # the core's range rules
    elif isinstance(params_or_tank, Tank):
        tank = params_or_tank
        params = tank.parameters()
        # the range rules at the largest rho (highest frequency) and A (lowest frequency and
        # highest acceleration: A = a/(L Omega^2))
        _tank_grid(tank, [f.min(), f.max()], [a.max()], units)
    else:
        raise InputError(f"params_or_tank = {type(params_or_tank).__name__} is not valid: give "
                         "sloshdyn.Parameters or sloshdyn.Tank")
    steady_array, integration_array = settings_arrays(steady, integration)
    _checks.choice("continuation", continuation, _tables.names("continuations")[0])
    directions = {"none": (), "both": ("up", "down")}.get(continuation, (continuation,))
    ppt = None if points_per_task is None else positive_int("points_per_task", points_per_task)
    nf, na = len(f), len(a)

    def chunking(ppt):
        if directions:                      # a task sweeps whole frequency columns
            return nf, max(1, min(na, ppt // nf))
        bf = min(nf, ppt)
        return bf, max(1, min(na, ppt // bf))
    rpar, ipar = params.array()

    def task(block):      # the block's (rho, A), made for each task: the grid may be large
        fs, amps = f[block[0]], a[block[1]]
        rho, amplitude = (np.meshgrid(fs, amps, indexing="ij") if tank is None else
                          _tank_grid(tank, fs, amps, units))
        return _response_task, (rpar, ipar, np.ascontiguousarray(rho),
                                np.ascontiguousarray(amplitude), integration_array,
                                steady_array, directions, tank is not None)

    dims = ("frequency", "amplitude")
    variables = summary_variables(dims)
    variables["transient_periods"] = Variable(dims, "f8", np.nan, {
        "units": "forcing periods", "long_name": "transient integrated before measuring"})
    variables["shooting"] = Variable(dims, "i1", -1, {
        "units": "1", "flag_values": [-1, 0, 1], "flag_meanings": "not_computed no yes",
        "long_name": "the steady state jumped to its periodic orbit by Newton shooting"})
    variables["max_multiplier"] = Variable(dims, "f8", np.nan, {
        "units": "1", "long_name": "largest Floquet multiplier modulus of the orbit found by "
                                   "shooting (NaN: no jump)"})
    for d in directions:
        variables.update(summary_variables(dims, f"_{d}", f"sweep {d} in frequency carrying "
                                                           "the state"))
    if tank is not None:
        variables["rho"] = Variable(dims, "f8", np.nan, {
            "units": "1", "long_name": "forcing frequency ratio rho = Omega/omega of the point"})
        variables["A"] = Variable(dims, "f8", np.nan, {
            "units": "1", "long_name": "dimensionless base displacement amplitude A = u0/L of "
                                      "the point (constant acceleration: A falls as 1/f^2)"})
    spec = {"kind": "response_map", "parameters": dataclasses.asdict(params),
            "tank": None if tank is None else dataclasses.asdict(tank), "units": units,
            "frequencies": f.tolist(), "amplitudes": a.tolist(),
            "steady": dataclasses.asdict(steady), "integration": dataclasses.asdict(integration),
            "continuation": list(directions), "version": version()}
    if tank is None:
        extra = {"frequency_axis": "rho = Omega/omega (forcing over pendulum frequency)",
                 "amplitude_axis": "A = u0/L (base displacement amplitude over rod length)"}
        coords = {
            "frequency": (f, {"units": "1", "long_name": "forcing frequency ratio rho = "
                                                         "Omega/omega"}),
            "amplitude": (a, {"units": "1", "long_name": "base displacement amplitude A = u0/L"})}
    else:
        extra = {"tank": json.dumps(dataclasses.asdict(tank)),
                 "frequency_axis": "ground motion frequency [Hz]",
                 "amplitude_axis": f"peak ground acceleration [{units}], constant along the "
                                   "frequency axis"}
        coords = {
            "frequency": (f, {"units": "Hz", "long_name": "ground motion frequency"}),
            "amplitude": (a, {"units": units, "long_name": "peak ground acceleration"})}
    attrs = common_attrs("response_map", params, steady, integration, {
        **extra, "continuation": ", ".join(directions) or "none",
        "study_spec": json.dumps(spec, sort_keys=True)})
    plan = Plan("response_map", dims, coords, variables, attrs, spec, None, task, chunking, ppt)
    return run_plan(plan, store, client=client, scheduler=scheduler, workers=workers,
                    worker_kind=worker_kind, min_workers=min_workers,
                    grace_time=grace_time, progress=progress)
