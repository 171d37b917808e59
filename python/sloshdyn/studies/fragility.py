"""Fragility studies (incremental dynamic analysis of a tank over a suite of ground-motion
records) and the maximum-likelihood lognormal fragility fit."""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import os
import time
from dataclasses import dataclass

import numpy as np

from .. import _checks, _core, _tables
from .._errors import InputError, message_text
from .._extras import require
from ..ground import GroundMotion, acceleration_factor
from ..options import Integration
from ..tank import Tank
from .engine import (SECONDS, Plan, Variable, axis, failed_points, positive_int, run_plan,
                     version)
from .points import message_variable

_bridge = _core.sloshdyn_bridge_seismic


_PEAKS = [c.split(" [")[0] for c in _tables.columns("seismic_peaks")]
_FRAGILITY_LOADS = {
    "peak_wave_height": ("m", "largest wave height at the wall over the run (capped at the "
                               "roof)"),
    "free_wave_height": ("m", "largest wave height at the wall of the tank without a roof"),
    "peak_sloshing_displacement": ("m", "largest displacement of the sloshing mass relative to "
                                        "the tank"),
    "peak_base_shear": ("N", "largest base shear (about the tank bottom)"),
    "peak_overturning_moment": ("N m", "largest overturning moment about the tank bottom "
                                       "(excluding the base pressure)"),
    "peak_overturning_moment_ibp": ("N m", "largest overturning moment about the tank bottom "
                                           "including the base pressure"),
    "peak_tank_drift": ("m", "largest drift of the tank relative to the ground"),
    "confined_convective_mass": ("kg", "the convective mass the roof confines (restricted "
                                       "sloshing; 0 below the roof)"),
    "first_roof_time": ("s", "first time the wave reached the roof (NaN: never)"),
}


#: Runs of one record integrated together by the ensemble integrator (the core's
#: seismic_responses) at most: chosen by measurement (benchmarks/README.md, "Ensembles",
#: "The fragility study in blocks", and "A run that reaches the roof observed again"): 1
#: since each run keeps its recorded steps, megabytes, which glibc's allocator hands a block
#: of runs afresh every block while one run's are reused from the last.
ENSEMBLE_BLOCK = 1
#: ... and outputs (n_out x runs) in a block at most, for a larger block: a member of a tank
#: of several modes holds its tables, about 32 numbers an output (256 MB for the block at this
#: cap; a block of 10 runs reaches it only past 100 000 outputs a run)
ENSEMBLE_OUTPUTS = 1_000_000


def _fragility_task(tank, records, intensities, sa_factor, period, damping, integration):
    """One task of a fragility study: every (record, intensity) of the block, each record
    scaled to the spectral acceleration at `period`, then the seismic response from rest.
    Runs on a worker; every number comes from the core (scale_ground, seismic_peaks).
    Per record, its spectral acceleration and the run's length and output count (which depend
    on the record's step and duration only) are computed once: scaling to Sa is then the
    factor Sa/psa of the core's scale_to_sa, applied by scale_ground, so each run is that of
    the record scaled to Sa alone, to the bit (the response spectrum of the record was most of
    a run's cost when recomputed per intensity). The runs of one record share its time grid:
    they are handed to the core's ensemble integrator ENSEMBLE_BLOCK at a time, each equal to
    its seismic_response alone, bit for bit (tests/python/test_fragility_ensemble.py)."""
    start = time.perf_counter()
    shape = (len(records), len(intensities))
    out = {name: np.full(shape, np.nan) for name in _FRAGILITY_LOADS}
    out["scale_factor"] = np.full(shape, np.nan)
    out["roof_impact"] = np.full(shape, 0, np.int8)
    out["roof_impacts"] = np.full(shape, -1, np.int32)
    out["status"] = np.zeros(shape, np.int16)
    out["message"] = np.full(shape, "", dtype=object)
    for i, (ground, samples) in enumerate(records):
        psa = chosen = None
        runs = []       # (intensity index, scaled ground, scaled samples) ready to run
        for j, sa in enumerate(intensities):
            if psa is None:
                # the first intensity as a single run would scale it (checks and messages
                # included), then the record's Sa at `period` as scale_to_sa computes it
                scaled, scaled_samples, status, message = _bridge.scale_ground(
                    ground, samples, 1.0, 0.0, sa * sa_factor, period, damping)
                if status == 0:
                    _, _, spectrum, spectrum_status, _ = _bridge.ground_spectrum(
                        ground, samples, [period], damping, 5 * period, 20 * period)
                    if spectrum_status == 0 and spectrum[0] > 0:
                        psa = float(spectrum[0])
            else:
                scaled, scaled_samples, status, message = _bridge.scale_ground(
                    ground, samples, (sa * sa_factor) / psa, 0.0, 0.0, period, damping)
            if status == 0 and chosen is None:
                chosen, status, message = _bridge.seismic_defaults(
                    tank, scaled, scaled_samples, 0, scaled, scaled_samples[:0], 0.0, 0)
                if status != 0:
                    chosen = None
            if status == 0:
                runs.append((j, scaled, scaled_samples))
            else:
                out["status"][i, j] = status
                out["roof_impact"][i, j] = -1
                out["message"][i, j] = message_text(message)
        if not runs:
            continue
        block = max(1, min(ENSEMBLE_BLOCK, ENSEMBLE_OUTPUTS // int(chosen[1])))
        for first in range(0, len(runs), block):
            _run_block(tank, ground, samples, runs[first:first + block], chosen,
                       integration, out, i)
    out[SECONDS] = time.perf_counter() - start
    return out


def _run_block(tank, ground, samples, runs, chosen, integration, out, i):
    """The seismic runs of record i (ground, samples) at the intensities of `runs` together
    (the core's seismic_peaks, which returns every run's status and message: a failed run is
    not run again), into out[...][i, j]."""
    t_end, n_out = float(chosen[0]), int(chosen[1])
    grounds = np.asfortranarray(np.stack([scaled for _, scaled, _ in runs], axis=1))
    scaled_samples = np.asfortranarray(np.stack([s for _, _, s in runs], axis=1))
    peaks, status, messages = _bridge.seismic_peaks(tank, grounds, scaled_samples, t_end,
                                                    n_out, integration)
    for k, (j, scaled, member_samples) in enumerate(runs):
        out["status"][i, j] = status[k]
        if status[k] != 0:
            out["roof_impact"][i, j] = -1
            out["message"][i, j] = message_text(messages[k])
            continue
        _store_run(out, (i, j), peaks[:, k], (ground, samples), (scaled, member_samples))


def _store_run(out, where, peaks, record, scaled):
    """The results of one run that succeeded (its 'seismic_peaks' row) into out[...][where];
    record and scaled: (ground, samples) of the record and of the run."""
    values = dict(zip(_PEAKS, peaks))
    for name in _FRAGILITY_LOADS:
        out[name][where] = values[name]
    out["roof_impact"][where] = int(values["roof_reached"] != 0)
    out["roof_impacts"][where] = int(values["roof_impacts"])
    (ground, samples), (scaled_ground, scaled_samples) = record, scaled
    peak_in = np.max(np.abs(samples)) if samples.size else ground[1]
    peak_out = np.max(np.abs(scaled_samples)) if scaled_samples.size else scaled_ground[1]
    out["scale_factor"][where] = peak_out / peak_in


def _record_name(record, k):
    if isinstance(record, (str, os.PathLike)):
        return os.path.basename(os.fspath(record))
    return f"record_{k}"


def fragility_study(tank, records, intensities, store, *, units="g", period=None,
                    damping=0.005, client=None, scheduler=None, workers=None, worker_kind=None,
                    min_workers=None, grace_time=None,
                    integration: Integration = Integration(), points_per_task=None,
                    progress=True, names=None):
    """Incremental dynamic analysis of a tank (sloshdyn.Tank) over a suite of ground-motion
    records: every record scaled to each intensity -- the pseudo-spectral acceleration Sa at
    `period` (default: the tank's sloshing period) for the damping ratio `damping` (default
    0.5 %, the convective damping of the design codes), in `units` -- and the seismic response
    from rest (sloshdyn.seismic_response) with its peaks: wave height, base shear, overturning
    moment, roof impact (the free wave reaches the roof: |x1| >= 1) per run. The lognormal fragility
    curve of roof impact is fitted by maximum likelihood over all runs (fit_fragility):
    variables fragility_median [units] and fragility_dispersion with their standard errors
    (NaN where no run, or every run, reached the roof).

    records: GroundMotion objects or record files (PEER .AT2 or two columns, read with
    GroundMotion.from_file). Returns a Dataset with dimensions (record, intensity), written to
    the Zarr store `store` as tasks finish; engine, resumption and errors as response_map."""
    if not isinstance(tank, Tank):
        raise InputError(f"tank = {type(tank).__name__} is not valid: give a sloshdyn.Tank")
    if isinstance(records, (str, os.PathLike, GroundMotion)):
        records = [records]
    try:
        records = list(records)
    except TypeError:
        raise InputError(f"records = {records!r:.60} is not valid: give a list of GroundMotion "
                         "objects or record files") from None
    if not records:
        raise InputError("records is empty: give at least one ground-motion record")
    motions = []
    for k, r in enumerate(records):
        if isinstance(r, (str, os.PathLike)):
            r = GroundMotion.from_file(r)
        if not isinstance(r, GroundMotion) or r.kind != "record":
            raise InputError(f"records[{k}] = {r!r:.60} is not valid: give a recorded ground "
                             "motion (GroundMotion with dt and acceleration) or a record file")
        motions.append(r)
    labels = ([_record_name(r, k) for k, r in enumerate(records)] if names is None else
              [_checks.text(f"names[{k}]", n) for k, n in enumerate(
                  names if isinstance(names, (list, tuple)) else [names])])
    if len(labels) != len(motions) or len(set(labels)) != len(labels):
        raise InputError(f"names = {labels!r:.80} is not valid: one distinct name per record")
    x = axis("intensities", intensities, 0.0)
    sa_factor = acceleration_factor(units)
    period = tank.sloshing_period if period is None else _checks.real("period", period)
    damping = _checks.real("damping", damping)
    if not period > 0:
        raise InputError(f"period = {period} is not valid: it must be > 0 [s]")
    if not 0 <= damping < 1:
        raise InputError(f"damping = {damping} is not valid: it must lie in [0, 1)")
    if not isinstance(integration, Integration):
        raise InputError(f"integration = {integration!r} is not valid: give a sloshdyn.Integration")
    integration_array = integration.array()
    ppt = None if points_per_task is None else positive_int("points_per_task", points_per_task)
    n_r, n_x = len(motions), len(x)

    def chunking(ppt):
        return (max(1, min(n_r, ppt // n_x)), n_x) if n_x <= ppt else (1, ppt)
    arrays = [m._arrays() for m in motions]
    tank_array = tank.array()

    def cost(block):
        # a run's time follows the record's number of samples, not its duration (measured on
        # the 44 records of benchmarks/run.py: correlation 0.98 against 0.46)
        return sum(arrays[k][1].size for k in range(*block[0].indices(n_r))) * len(x[block[1]])

    def task(block):
        return _fragility_task, (tank_array, arrays[block[0]], x[block[1]], sa_factor, period,
                                 float(damping), integration_array)

    dims = ("record", "intensity")
    variables = {name: Variable(dims, "f8", np.nan, {"units": unit, "long_name": text})
                 for name, (unit, text) in _FRAGILITY_LOADS.items()}
    variables["scale_factor"] = Variable(dims, "f8", np.nan, {
        "units": "1", "long_name": "factor applied to the record to reach the intensity"})
    variables["roof_impact"] = Variable(dims, "i1", -1, {
        "units": "1", "flag_values": [-1, 0, 1], "flag_meanings": "not_computed_or_failed no yes",
        "long_name": "the wave reached the roof during the run (|x1| >= 1)"})
    variables["roof_impacts"] = Variable(dims, "i4", -1, {
        "units": "1", "long_name": "number of strikes on the roof during the run"})
    variables["status"] = Variable(dims, "i2", -1, {
        "units": "1", "long_name": "core status of the run (0 ok, -1 not computed)"})
    variables["message"] = message_variable(dims, "the run")
    digests = [hashlib.sha256(np.ascontiguousarray(a[1]).tobytes() + a[0].tobytes()).hexdigest()
               for a in arrays]
    spec = {"kind": "fragility", "tank": dataclasses.asdict(tank), "records": digests,
            "names": labels, "intensities": x.tolist(), "units": units, "period": period,
            "damping": float(damping), "integration": dataclasses.asdict(integration),
            "version": version()}
    attrs = {"title": "sloshdyn fragility study (incremental dynamic analysis)",
             "study": "fragility", "sloshdyn_version": version(),
             "tank": json.dumps(dataclasses.asdict(tank)),
             "integration": json.dumps(dataclasses.asdict(integration)),
             "intensity_measure": f"pseudo-spectral acceleration Sa({period:.6g} s, "
                                  f"{100 * damping:g} %) [{units}]",
             "spectral_period": period, "spectral_damping": float(damping),
             "record_sha256": json.dumps(dict(zip(labels, digests))),
             "study_spec": json.dumps(spec, sort_keys=True)}
    plan = Plan("fragility", dims, {
        "record": (np.array(labels), {"long_name": "ground-motion record"}),
        "intensity": (x, {"units": units, "long_name": f"spectral acceleration Sa at "
                                                      f"T = {period:.4g} s, {100 * damping:g} % "
                                                      "damping"})},
        variables, attrs, spec, None, task, chunking, ppt, cost)
    return run_plan(plan, store, client=client, scheduler=scheduler, workers=workers,
                    worker_kind=worker_kind, min_workers=min_workers,
                    grace_time=grace_time, progress=progress,
                    derive=lambda ds: _fit_study(ds, units))


def _fit_study(ds, units):
    """The lognormal fit of roof impact over the runs that succeeded, as 0-d variables; the
    runs that failed are no outcome: they are left out, counted and named (attrs
    'fragility_fit'), and the fit says how many runs it rests on (fragility_runs)."""
    hit = ds["roof_impact"].values
    ok = (ds["status"].values == 0) & (hit >= 0)
    named, n_failed = failed_points(ds)
    basis = f"over {int(ok.sum())} of {ok.size} runs" + (
        f" ({n_failed} failed and left out: {named})" if n_failed else "")
    xs = np.broadcast_to(ds["intensity"].values, hit.shape)[ok]
    values = dict(median=np.nan, beta=np.nan, median_se=np.nan, beta_se=np.nan)
    try:
        fit = fit_fragility(xs, hit[ok].astype(float))
        values = dict(median=fit.median, beta=fit.beta, median_se=fit.median_se,
                      beta_se=fit.beta_se)
        ds.attrs["fragility_fit"] = f"lognormal, maximum likelihood {basis}"
    except InputError as exc:     # no run or every run reached the roof, or they separate
        ds.attrs["fragility_fit"] = f"not fitted ({basis}): {exc}"
    ds["fragility_runs"] = ((), int(ok.sum()), {
        "units": "1", "long_name": "runs the fit rests on (failed runs are left out)"})
    ds["fragility_median"] = ((), values["median"], {
        "units": units, "long_name": "median of the lognormal fragility curve of roof impact "
                                     "(maximum likelihood)"})
    ds["fragility_median_se"] = ((), values["median_se"], {
        "units": units, "long_name": "standard error of the median"})
    ds["fragility_dispersion"] = ((), values["beta"], {
        "units": "1", "long_name": "dispersion beta (log standard deviation) of the fragility "
                                   "curve"})
    ds["fragility_dispersion_se"] = ((), values["beta_se"], {
        "units": "1", "long_name": "standard error of the dispersion"})
    return ds


# ---- fragility fit ---------------------------------------------------------------------------

@dataclass(frozen=True)
class FragilityFit:
    """Lognormal fragility curve P(failure | IM = x) = Phi(ln(x/median)/beta), fitted by
    maximum likelihood to binary outcomes (Baker 2015), with standard errors from the inverse
    observed information."""

    median: float
    beta: float                  #: dispersion (logarithmic standard deviation)
    median_se: float
    beta_se: float
    log_likelihood: float
    n: int

    def probability(self, x):
        from scipy.stats import norm
        return norm.cdf(np.log(np.asarray(x, dtype=float) / self.median) / self.beta)


def fit_fragility(intensities, failures, counts=None) -> FragilityFit:
    """Maximum-likelihood lognormal fragility fit (the incremental dynamic analysis and FEMA
    P695 practice). intensities: intensity measure per observation (> 0); failures: 0/1 per
    observation, or the number of failures out of counts at each intensity."""
    require("studies", "scipy")
    from scipy.optimize import minimize
    from scipy.stats import norm
    x = _checks.reals("intensities", intensities, finite=False).ravel()
    y = _checks.reals("failures", failures, finite=False).ravel()
    m = np.ones_like(y) if counts is None else _checks.reals("counts", counts).ravel()
    if x.size == 0:
        raise InputError("intensities is empty: give at least one value")
    bad = np.nonzero(~np.isfinite(x) | (x <= 0))[0]
    if bad.size:
        raise InputError(f"intensities[{bad[0]}] = {x[bad[0]]} is not valid: every intensity "
                         "must be finite and > 0")
    if y.shape != x.shape or m.shape != x.shape:
        raise InputError(f"failures has shape {y.shape}: it must match intensities {x.shape}")
    if np.any((y < 0) | (y > m)) or not np.all(np.isfinite(y)):
        raise InputError("failures must lie in [0, counts] (0/1 per run)")
    if y.sum() == 0 or y.sum() == m.sum():
        raise InputError("failures are all 0 or all 1: the fragility curve cannot be fitted")
    survived, failed = x[y < m], x[y > 0]
    if survived.max() < failed.min():
        raise InputError(f"the runs separate perfectly (no failure up to {survived.max():g}, "
                         f"all from {failed.min():g}): the maximum-likelihood dispersion is 0 "
                         "and the fit does not exist; add intensities between them or records")
    lx = np.log(x)

    def nll(theta):
        mu, log_beta = theta
        z = (lx - mu) / math.exp(log_beta)
        return -(y * norm.logcdf(z) + (m - y) * norm.logsf(z)).sum()

    start = np.array([np.average(lx, weights=np.maximum(m, 1e-12)), math.log(max(lx.std(), 0.1))])
    result = minimize(nll, start, method="Nelder-Mead",
                      options={"xatol": 1e-10, "fatol": 1e-12, "maxiter": 20000})
    mu, log_beta = result.x
    beta = math.exp(log_beta)
    # observed information in (mu, beta) by central differences of the log-likelihood
    def nll_mb(mb):
        return nll([mb[0], math.log(mb[1])])
    h = np.array([1e-4 * max(abs(mu), 1.0), 1e-4 * beta])
    hess = np.zeros((2, 2))
    theta0 = np.array([mu, beta])
    for i in range(2):
        for j in range(2):
            ei, ej = np.eye(2)[i] * h[i], np.eye(2)[j] * h[j]
            hess[i, j] = (nll_mb(theta0 + ei + ej) - nll_mb(theta0 + ei - ej)
                          - nll_mb(theta0 - ei + ej) + nll_mb(theta0 - ei - ej)) / (4 * h[i] * h[j])
    try:
        cov = np.linalg.inv(hess)
    except np.linalg.LinAlgError:
        cov = np.full((2, 2), np.nan)
    median = math.exp(mu)
    return FragilityFit(median=median, beta=beta, median_se=median * math.sqrt(cov[0, 0]),
                        beta_se=math.sqrt(cov[1, 1]), log_likelihood=-float(result.fun),
                        n=int(m.sum()))
