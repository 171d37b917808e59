"""Impact parameters: which impact coefficient beta and dissipation delta reproduce the
paper's continuation in A (sec 4.2, Fig 15-17)."""

from __future__ import annotations

import dataclasses
import json
import math
import time

import numpy as np

from .._errors import InputError, SloshdynError
from ..options import Integration, Lyapunov, Steady
from ..parameters import Parameters
from ..periodic import lyapunov_exponent
from ..simulation import amplitude_sweep
from .engine import SECONDS, Plan, Variable, axis, positive_int, run_plan, version
from .points import (MOTION_ATTRS, MOTION_CODES, MOTIONS, common_attrs, message_variable,
                     settings_arrays)

#: the paper's three statements about the continuation in A at rho = 0.513 (sec 4.2), as tested
#: by impact_parameters: Fig 15 "x1 ~ O(0.01)" (within a factor 3 of 0.01: an order of
#: magnitude is a factor sqrt(10) either way); Fig 16 "x1 is close to unity" without impacts
#: ("when A = 2.0, x1 reaches unity", so at 1.0475 it does not) and periodic (its caption);
#: Fig 17 "x1 reaches unity, i.e. hydraulic impacts" and "strongly reminds chaotic motion"
#: (largest Lyapunov exponent > 0)
FIG15_ORDER, FIG16_CLOSE_TO_UNITY = (0.01 / math.sqrt(10), 0.01 * math.sqrt(10)), 0.8


def _impact_task(params, betas, deltas, A_values, steady, integration, lyapunov):
    """One task of an impact-parameter study: at each (beta, delta) of the block, the carried
    continuation along A_values from rest (amplitude_sweep) and the largest Lyapunov exponent
    at the last A from the continuation's final state. Runs on a worker."""
    start = time.perf_counter()
    shape, n_a = (len(betas), len(deltas)), len(A_values)
    out = {"max_x1": np.full(shape + (n_a,), np.nan), "motion": np.zeros(shape + (n_a,), np.int8),
           "lyapunov": np.full(shape, np.nan), "status": np.zeros(shape, np.int16),
           "message": np.full(shape, "", dtype=object)}
    for i, beta in enumerate(betas):
        for j, delta in enumerate(deltas):
            p = params.replace(beta=float(beta), delta=float(delta))
            try:
                sweep = amplitude_sweep(p, A_values, None, steady=steady, integration=integration)
                out["lyapunov"][i, j] = lyapunov_exponent(
                    p.replace(A=float(A_values[-1])), sweep.y_final, integration=integration,
                    lyapunov=Lyapunov(**lyapunov)).exponent
            except SloshdynError as exc:
                out["status"][i, j] = exc.status or 1
                out["message"][i, j] = str(exc)
                continue
            out["max_x1"][i, j] = [q.max_x1 for q in sweep.points]
            out["motion"][i, j] = [MOTION_CODES[q.motion] for q in sweep.points]
    out[SECONDS] = time.perf_counter() - start
    return out


def impact_parameters(params: Parameters, betas, deltas, A_values, store, *,
                      client=None, scheduler=None, workers=None, worker_kind=None,
                      min_workers=None, grace_time=None,
                      steady: Steady = Steady(), integration: Integration = Integration(),
                      lyapunov_periods=(100, 2000), points_per_task=None, progress=True):
    """Which impact coefficient beta and dissipation delta reproduce the paper's continuation
    in A (sec 4.2, Fig 15-17)? At every (beta, delta) of the grid: the steady states along
    A_values at params' rho, from rest, each from the previous one's final state (the paper's
    numerical continuation; sloshdyn.amplitude_sweep), and the largest Lyapunov exponent at the
    last A (lyapunov_periods = (transient, measured) forcing periods from the continuation's
    final state). Variables: max_x1 and motion at every A, lyapunov, and the three statements
    of the paper tested at the A values 0.00075, 1.0475 and 2.0 (which must be in A_values):
    fig15_holds, fig16_holds, fig17_holds, all_hold (criteria: FIG15_ORDER,
    FIG16_CLOSE_TO_UNITY). Engine, store, resumption and errors as response_map."""
    if not isinstance(params, Parameters):
        raise InputError(f"params = {type(params).__name__} is not valid: give sloshdyn.Parameters")
    b = axis("betas", betas, 0.0)
    d = axis("deltas", deltas, 0.0)
    a = axis("A_values", A_values, 0.0, lower_open=False)
    for A in (0.00075, 1.0475, 2.0):
        if not np.any(np.isclose(a, A, rtol=1e-12, atol=0)):
            raise InputError(f"A_values lacks A = {A}: the paper's statements are tested there")
    params.replace(beta=float(b.max()), delta=float(d.max()), A=float(a.max()))   # range rules
    settings_arrays(steady, integration)
    try:
        transient, measured = (int(v) for v in lyapunov_periods)
    except (TypeError, ValueError):
        raise InputError(f"lyapunov_periods = {lyapunov_periods!r} is not valid: give "
                         "(transient, measured) forcing periods") from None
    lyapunov = {"transient_periods": positive_int("lyapunov_periods[0]", transient, 0),
                "n_periods": positive_int("lyapunov_periods[1]", measured)}
    ppt = None if points_per_task is None else positive_int("points_per_task", points_per_task)
    nb, nd = len(b), len(d)

    def chunking(ppt):
        bd = min(nd, ppt)
        return max(1, min(nb, ppt // bd)), bd

    def task(block):
        return _impact_task, (params, b[block[0]], d[block[1]], a, steady, integration, lyapunov)

    dims = ("beta", "delta")
    variables = {
        "max_x1": Variable(dims + ("A",), "f8", np.nan, {
            "units": "1", "long_name": "max |x1| = max |theta|/theta0 over the measuring window "
                                       "at each A of the continuation"}),
        "motion": Variable(dims + ("A",), "i1", -1, {
            **MOTION_ATTRS, "long_name": "kind of motion at each A of the continuation"}),
        "lyapunov": Variable(dims, "f8", np.nan, {
            "units": "1 per unit tau", "long_name": f"largest Lyapunov exponent at A = {a[-1]:g}"}),
        "status": Variable(dims, "i2", -1, {
            "units": "1", "long_name": "core status of the point (0 ok, -1 not computed)"}),
        "message": message_variable(dims)}
    spec = {"kind": "impact_parameters", "parameters": dataclasses.asdict(params),
            "betas": b.tolist(), "deltas": d.tolist(), "A_values": a.tolist(),
            "steady": dataclasses.asdict(steady), "integration": dataclasses.asdict(integration),
            "lyapunov": lyapunov, "version": version()}
    attrs = common_attrs("impact_parameters", params, steady, integration, {
        "study_spec": json.dumps(spec, sort_keys=True)})
    plan = Plan("impact_parameters", dims, {
        "beta": (b, {"units": "1", "long_name": "impact coefficient beta (eq 4, "
                                                "dimensionless)"}),
        "delta": (d, {"units": "1", "long_name": "sloshing dissipation delta (dimensionless)"}),
        "A": (a, {"units": "1", "long_name": "base displacement amplitude A = u0/L along the "
                                             "continuation"})},
        variables, attrs, spec, None, task, chunking, ppt)
    ds = run_plan(plan, store, client=client, scheduler=scheduler, workers=workers,
                  worker_kind=worker_kind, min_workers=min_workers,
                    grace_time=grace_time, progress=progress)
    return paper_statements(ds)


def paper_statements(ds):
    """The paper's statements on Fig 15-17 tested at every (beta, delta) of an
    impact-parameter study (criteria in FIG15_ORDER, FIG16_CLOSE_TO_UNITY)."""
    def at(A):
        return ds["max_x1"].sel(A=A, method="nearest"), ds["motion"].sel(A=A, method="nearest")
    x15, _ = at(0.00075)
    x16, m16 = at(1.0475)
    x17, _ = at(2.0)
    periodic = [k for k, name in MOTIONS.items() if name == "periodic"][0]
    holds = {"fig15_holds": (FIG15_ORDER[0] <= x15) & (x15 <= FIG15_ORDER[1]),
             "fig16_holds": (FIG16_CLOSE_TO_UNITY <= x16) & (x16 < 1) & (m16 == periodic),
             "fig17_holds": (x17 >= 1) & (ds["lyapunov"] > 0)}
    texts = {"fig15_holds": "Fig 15: max|x1| of order 0.01 at A = 0.00075",
             "fig16_holds": f"Fig 16: {FIG16_CLOSE_TO_UNITY:g} <= max|x1| < 1 and periodic at "
                            "A = 1.0475",
             "fig17_holds": "Fig 17: max|x1| >= 1 (impacts) and Lyapunov exponent > 0 at A = 2"}
    for name, value in holds.items():
        ds[name] = value.drop_vars("A", errors="ignore").astype(bool)
        ds[name].attrs = {"units": "1", "long_name": texts[name]}
    ds["all_hold"] = ds["fig15_holds"] & ds["fig16_holds"] & ds["fig17_holds"]
    ds["all_hold"].attrs = {"units": "1", "long_name": "all three statements of the paper hold"}
    return ds

