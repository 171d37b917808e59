"""Parameter studies on Dask: response maps in (forcing frequency, amplitude), basins of
attraction, and the lognormal fragility fit. Each study is cut into tasks of many points; each
task calls the Fortran core once (steady states, shooting and the classification stay there;
the bridge releases the GIL, so threads run at once). Results come back as an xarray Dataset
whose dimensions are the study's axes, with units and descriptions in the attributes, and are
written to a Zarr store as tasks finish: rerunning the same study on the same store resumes it
(finished points are not recomputed), a store made by other settings is refused.

Dask, xarray and Zarr are imported on first use, so `import sloshdyn` stays light.
"""

from __future__ import annotations

import contextlib
import dataclasses
import hashlib
import json
import math
import os
import shutil
import time
import uuid
from dataclasses import dataclass

import numpy as np

from . import _checks, _core, _tables
from ._errors import InputError, SloshdynError
from .parameters import Parameters
from .simulation import Integration, Steady

_bridge = _core.sloshdyn_bridge
SUMMARY_COLUMNS = _tables.columns("summary")
MOTIONS = _tables.codes("motion")
MOTION_CODES = {name: code for code, name in MOTIONS.items()}
#: points per task unless told: about 8 tasks per worker for the load balance, within these
#: bounds (measured by benchmarks/studies.py: the engine's overhead is ~20 % of the work at 8
#: points per task, ~5 % at 32, ~2 % at 128; README, "Studies")
MIN_POINTS_PER_TASK, MAX_POINTS_PER_TASK, TASKS_PER_WORKER = 8, 128, 8
#: the default worker kind of an embedded cluster, by measurement (README, "Studies")
WORKER_KIND = "processes"
#: how long a scheduler address may take to answer
CONNECT_TIMEOUT = 5.0
#: the orbit layout of sloshdyn_studies (bridge steady_path / attractor_points)
_ORBIT_FOUND, _ORBIT_PERIODS, _ORBIT_ATTEMPTS, _ORBIT_Y, _ORBIT_MAX_MU = 0, 1, 2, slice(3, 7), 15
_MAX_PERIOD = 8
#: a task's result entry (not stored) with the seconds the task computed
_SECONDS = "_compute_seconds"
#: attributes of a returned dataset that describe the call, not the study (not stored)
_RUN_ATTRS = ("points_computed", "compute_seconds", "store")

_MOTION_ATTRS = {
    "flag_values": [-1, 0] + list(MOTIONS),
    "flag_meanings": " ".join(["not_computed", "failed"] + [MOTIONS[k].replace("-", "_")
                                                            for k in MOTIONS]),
    "units": "1",
}


# ---- the engine ------------------------------------------------------------------------------

@dataclass
class _Variable:
    dims: tuple
    dtype: str
    fill: object
    attrs: dict


@dataclass
class _Plan:
    """A study in index space: its axes, variables, attributes, and tasks (blocks of the grid,
    aligned with the store's chunks). task(block) is (function, args) for Dask; the function
    returns {variable: array over the block}. chunking(points_per_task) gives the chunk shape;
    points_per_task None lets the engine choose (auto_points_per_task)."""

    kind: str
    dims: tuple
    coords: dict                 #: dim -> (values, attrs)
    variables: dict              #: name -> _Variable (the 'done' mask is added)
    attrs: dict
    spec: dict                   #: what must match to resume (JSON-able)
    chunks: tuple
    task: object                 #: block (tuple of slices) -> (function, args)
    chunking: object = None      #: points per task -> chunk shape
    points_per_task: int = None

    def blocks(self):
        ranges = [range(0, len(self.coords[d][0]), c) for d, c in zip(self.dims, self.chunks)]
        for corner in np.ndindex(*[len(r) for r in ranges]):
            yield tuple(slice(r[i], min(r[i] + c, len(self.coords[d][0])))
                        for r, i, c, d in zip(ranges, corner, self.chunks, self.dims))

    @property
    def shape(self):
        return tuple(len(self.coords[d][0]) for d in self.dims)


def auto_points_per_task(n_points, n_workers):
    """Points per task: about TASKS_PER_WORKER tasks per worker thread, within
    [MIN_POINTS_PER_TASK, MAX_POINTS_PER_TASK]."""
    wanted = math.ceil(n_points / (TASKS_PER_WORKER * max(1, n_workers)))
    return int(min(MAX_POINTS_PER_TASK, max(MIN_POINTS_PER_TASK, wanted)))


def _version():
    import sloshdyn
    return sloshdyn.__version__


def _fingerprint(spec):
    return hashlib.sha256(json.dumps(spec, sort_keys=True).encode()).hexdigest()


def _check_store(store):
    """The store path: a string or path-like whose parent directory is (or can be made)
    writable. Checked before anything is computed."""
    if not isinstance(store, (str, os.PathLike)) or not os.fspath(store):
        raise InputError(f"store = {store!r} is not valid: give the path of a Zarr store "
                         "(a directory)")
    path = os.path.abspath(os.fspath(store))
    if os.path.exists(path):
        if not os.path.isdir(path):
            raise InputError(f"store = {os.fspath(store)!r} is a file, not a Zarr store "
                             "(a directory)")
        if not os.access(path, os.W_OK):
            raise InputError(f"store = {os.fspath(store)!r} is not writable")
        return path
    parent = os.path.dirname(path)
    existing = parent
    while not os.path.exists(existing):
        existing = os.path.dirname(existing)
    if not os.path.isdir(existing) or not os.access(existing, os.W_OK | os.X_OK):
        raise InputError(f"store = {os.fspath(store)!r} cannot be created: {existing!r} is not "
                         "a writable directory")
    return path


def _template(plan):
    import xarray as xr
    coords = {d: xr.Variable(d, np.asarray(v), attrs) for d, (v, attrs) in plan.coords.items()}
    data = {}
    encoding = {}
    for name, var in plan.variables.items():
        shape = tuple(len(plan.coords[d][0]) for d in var.dims)
        chunks = tuple(dict(zip(plan.dims, plan.chunks)).get(d, len(plan.coords[d][0]))
                       for d in var.dims)
        data[name] = xr.Variable(var.dims, np.full(shape, var.fill, dtype=var.dtype), var.attrs)
        encoding[name] = {"chunks": chunks}
        if np.dtype(var.dtype).kind == "f":
            encoding[name]["_FillValue"] = np.nan
        else:
            encoding[name]["_FillValue"] = None
    ds = xr.Dataset(data, coords=coords, attrs=plan.attrs)
    return ds, encoding


def _create_store(plan, path):
    """Write the empty study (every point not done) under a temporary name, then rename it:
    a store either exists whole or not at all."""
    ds, encoding = _template(plan)
    tmp = f"{path}.creating-{uuid.uuid4().hex[:8]}"
    try:
        ds.to_zarr(tmp, mode="w-", encoding=encoding, consolidated=True, zarr_format=2,
                   compute=True)
        os.replace(tmp, path)
    except FileExistsError:
        raise InputError(f"store = {path!r} appeared while it was being created") from None
    except OSError as exc:
        raise InputError(f"store = {path!r} cannot be written: {exc}") from exc
    finally:
        if os.path.exists(tmp):
            shutil.rmtree(tmp, ignore_errors=True)


def _check_same_study(plan, path):
    import zarr
    try:
        group = zarr.open_group(path, mode="r")
        stored = json.loads(group.attrs["study_spec"])
    except Exception as exc:
        raise InputError(f"store = {path!r} exists but is not a sloshdyn study store "
                         f"({type(exc).__name__}: {exc}); give a new path") from None
    if _fingerprint(stored) != _fingerprint(plan.spec):
        differ = sorted(k for k in set(stored) | set(plan.spec) if stored.get(k) != plan.spec.get(k))
        raise InputError(f"store = {path!r} holds a different study (it differs in: "
                         f"{', '.join(differ)}); it is never mixed with this one: give another "
                         "store, or delete it to start again")
    chunks = tuple(group["done"].chunks)
    return chunks


@contextlib.contextmanager
def _client(client, scheduler, workers, worker_kind):
    """The Dask client of a study: the one given, one connected to `scheduler`, or an embedded
    local cluster sized to the machine (closed afterwards)."""
    from dask.distributed import Client, LocalCluster
    if client is not None:
        yield client
        return
    if scheduler:
        try:
            c = Client(scheduler, timeout=CONNECT_TIMEOUT)
        except (OSError, TimeoutError) as exc:
            raise InputError(f"scheduler = {scheduler!r} did not answer within "
                             f"{CONNECT_TIMEOUT:g} s ({type(exc).__name__}: {exc})") from None
        try:
            yield c
        finally:
            c.close()
        return
    if worker_kind not in ("processes", "threads"):
        raise InputError(f"worker_kind = {worker_kind!r} is not valid: it must be 'processes' "
                         "or 'threads'")
    n = workers or os.cpu_count() or 1
    processes = worker_kind == "processes"
    with contextlib.ExitStack() as stack:
        cluster = stack.enter_context(LocalCluster(
            n_workers=n if processes else 1, threads_per_worker=1 if processes else n,
            processes=processes, dashboard_address=None, silence_logs=50))
        c = stack.enter_context(Client(cluster))
        yield c


class _Writer:
    """Writes a task's results into the store: every variable's region at once (zarr's async
    API: the chunk files are written concurrently), then the task's 'done' mask, so a point is
    marked done only once its results are on disk. Zarr's LocalStore writes each chunk file
    under a temporary name and renames it, so a killed writer leaves no torn chunk."""

    def __init__(self, path, plan):
        import zarr.api.asynchronous as za
        from zarr.core.sync import sync
        self._sync = sync
        self.plan = plan
        group = sync(za.open_group(path, mode="r+"))
        self.arrays = {name: sync(group.getitem(name)) for name in plan.variables}

    def write(self, block, result):
        import asyncio
        where = dict(zip(self.plan.dims, block))

        async def write_all(items):
            await asyncio.gather(*(self.arrays[name].setitem(
                tuple(where.get(d, slice(None)) for d in self.plan.variables[name].dims),
                np.asarray(values, dtype=self.plan.variables[name].dtype))
                for name, values in items))

        self._sync(write_all([(k, v) for k, v in result.items() if k != _SECONDS]))
        self._sync(write_all([("done", np.ones([s.stop - s.start for s in block], bool))]))


def run_plan(plan, store, *, client=None, scheduler=None, workers=None, worker_kind=None,
             progress=True):
    """Run a study plan on Dask, storing each task's results in `store` as it finishes; return
    the whole study as an xarray Dataset (loaded). Already finished points are not recomputed;
    the returned dataset's attrs['points_computed'] counts the points this call computed and
    attrs['compute_seconds'] the time its tasks spent computing (summed over workers)."""
    import xarray as xr
    import zarr

    path = _check_store(store)
    if worker_kind is None:
        worker_kind = WORKER_KIND
    exists = os.path.exists(path)
    todo = None
    if exists:
        chunks = _check_same_study(plan, path)   # the store's tasks win: its chunks are its tasks
        plan = dataclasses.replace(plan, chunks=chunks)
        done = zarr.open_group(path, mode="r")["done"][...]
        todo = [b for b in plan.blocks() if not done[b].all()]
    computed = 0
    compute_seconds = 0.0
    if todo is None or todo:
        from dask.distributed import as_completed
        bar = None
        try:
            with _client(client, scheduler, workers, worker_kind) as c:
                if not exists:        # the task size needs the workers: the store comes now
                    ppt = plan.points_per_task or auto_points_per_task(
                        int(np.prod(plan.shape)), sum(c.nthreads().values()))
                    plan = dataclasses.replace(plan, chunks=tuple(plan.chunking(ppt)))
                    _create_store(plan, path)
                    todo = list(plan.blocks())
                remaining = int(sum(np.prod([s.stop - s.start for s in b]) for b in todo))
                if progress:
                    from tqdm.auto import tqdm
                    total = int(np.prod(plan.shape))
                    bar = tqdm(total=total, initial=total - remaining,
                               desc=plan.kind.replace("_", " "), unit="point", smoothing=0.1)
                writer = _Writer(path, plan)
                futures = {}
                for block in todo:
                    function, args = plan.task(block)
                    futures[c.submit(function, *args, pure=False)] = block
                try:
                    for future in as_completed(futures):
                        block = futures.pop(future)
                        result = future.result()
                        compute_seconds += result.get(_SECONDS, 0.0)
                        writer.write(block, result)
                        n = int(np.prod([s.stop - s.start for s in block]))
                        computed += n
                        if bar:
                            bar.update(n)
                finally:
                    for future in futures:
                        future.cancel()
        except KeyboardInterrupt:
            raise KeyboardInterrupt(f"study interrupted: {computed} points stored in {path} "
                                    "this run; rerun the same study on it to resume") from None
        finally:
            if bar:
                bar.close()
    ds = xr.open_zarr(path, consolidated=True, chunks=None).load()
    ds.attrs["points_computed"] = computed
    ds.attrs["compute_seconds"] = compute_seconds     #: inside the tasks, summed over workers
    ds.attrs["store"] = path
    return ds


# ---- inputs ----------------------------------------------------------------------------------

def _axis(name, values, lower, lower_open=True):
    """A study axis: 1-D, non-empty, finite, > lower (or >= lower), no repeats."""
    a = _checks.reals(name, values, finite=False).ravel()
    if a.size == 0:
        raise InputError(f"{name} is empty: give at least one value")
    for i, v in enumerate(a):
        ok = math.isfinite(v) and (v > lower if lower_open else v >= lower)
        if not ok:
            rule = f"> {lower:g}" if lower_open else f">= {lower:g}"
            raise InputError(f"{name}[{i}] = {v} is not valid: every value must be finite and {rule}")
    if len(np.unique(a)) != a.size:
        raise InputError(f"{name} has repeated values: each value must appear once")
    return a


def _positive_int(name, value, lower=1):
    return _checks.integer(name, value, lower)


def _settings(steady, integration):
    if not isinstance(steady, Steady):
        raise InputError(f"steady = {steady!r} is not valid: give a sloshdyn.Steady")
    if not isinstance(integration, Integration):
        raise InputError(f"integration = {integration!r} is not valid: give a sloshdyn.Integration")
    return steady.array(), integration.array()


def _common_attrs(kind, params, steady, integration, extra):
    return {
        "title": f"sloshdyn {kind.replace('_', ' ')}",
        "study": kind,
        "sloshdyn_version": _version(),
        "parameters": json.dumps(dataclasses.asdict(params)),
        "steady": json.dumps(dataclasses.asdict(steady)),
        "integration": json.dumps(dataclasses.asdict(integration)),
        "method_used": integration.method_used,   # 'auto' resolved by rtol
        **extra,
    }


def _summary_variables(dims, suffix="", what="steady state from rest"):
    v = {}
    desc = {"max_x1": "max |x1| = max |theta|/theta0 over the measuring window (pendulum)",
            "max_x2": "max |x2| = max |phi|/theta0 over the measuring window (tank)",
            "max_u1": "max |u1|, first modal coordinate (eq 34)",
            "max_u2": "max |u2|, second modal coordinate (eq 34)"}
    for name, text in desc.items():
        v[name + suffix] = _Variable(dims, "f8", np.nan,
                                     {"units": "1", "long_name": f"{text}; {what}"})
    v["motion" + suffix] = _Variable(dims, "i1", -1, {
        **_MOTION_ATTRS, "long_name": f"kind of motion judged from the Poincare points; {what}"})
    v["period" + suffix] = _Variable(dims, "i2", -1, {
        "units": "forcing periods", "long_name": f"period of periodic motion (0: not periodic); {what}"})
    v["roof_impact" + suffix] = _Variable(dims, "i1", -1, {
        "units": "1", "flag_values": [-1, 0, 1], "flag_meanings": "not_computed no yes",
        "long_name": f"the liquid reaches the roof: max|x1| >= 1, the pendulum at theta0 "
                     f"(eq 3-4); {what}"})
    v["status" + suffix] = _Variable(dims, "i2", -1, {
        "units": "1", "long_name": f"core status of the point (0 ok, -1 not computed; else "
                                   f"sloshdyn_status codes); {what}"})
    return v


def _unpack(summaries, orbit, impact, status, shape, suffix="", order="C"):
    """{variable: array of `shape`} from the bridge's point arrays."""
    def grid(x):
        return np.asarray(x).reshape(shape, order=order)
    col = {name: summaries[k] for k, name in enumerate(SUMMARY_COLUMNS)}
    ok = np.asarray(status) == 0
    out = {name + suffix: grid(col[name]) for name in ("max_x1", "max_x2", "max_u1", "max_u2")}
    out["motion" + suffix] = grid(np.where(ok, np.nan_to_num(col["motion"]), 0).astype(np.int8))
    out["period" + suffix] = grid(np.where(ok, np.nan_to_num(col["period"]), 0).astype(np.int16))
    out["roof_impact" + suffix] = grid(np.where(ok, impact, 0).astype(np.int8))
    out["status" + suffix] = grid(np.asarray(status).astype(np.int16))
    return out


# ---- response map ----------------------------------------------------------------------------

def _response_task(rpar, ipar, rho, A, integration, steady, continuation, with_grid=False):
    """One task of a response map: the block's points from rest, and (continuation) each
    amplitude column swept up and/or down in frequency carrying the state. Runs on a worker."""
    start = time.perf_counter()
    shape = rho.shape
    n = rho.size
    flat_rho = np.ascontiguousarray(rho.ravel())
    flat_a = np.ascontiguousarray(A.ravel())
    summaries, y_end, orbit, impact, status, _, _ = _bridge.steady_path(
        rpar, ipar, flat_rho, flat_a, np.zeros((4, n), order="F"), 0, integration, steady)
    out = _unpack(summaries, orbit, impact, status, shape)
    out["transient_periods"] = summaries[SUMMARY_COLUMNS.index("transient_periods")].reshape(shape)
    out["shooting"] = np.where(status == 0, orbit[_ORBIT_FOUND], -1).astype(np.int8).reshape(shape)
    out["max_multiplier"] = orbit[_ORBIT_MAX_MU].reshape(shape)
    for direction in continuation:
        parts = []
        for j in range(shape[1]):
            order = slice(None) if direction == "up" else slice(None, None, -1)
            r = np.ascontiguousarray(rho[order, j])
            a = np.ascontiguousarray(A[order, j])
            s, _, o, imp, st, _, _ = _bridge.steady_path(
                rpar, ipar, r, a, np.zeros((4, len(r)), order="F"), 1, integration, steady)
            part = _unpack(s, o, imp, st, (len(r), 1), suffix=f"_{direction}")
            parts.append({k: v[order] for k, v in part.items()})
        for k in parts[0]:
            out[k] = np.concatenate([p[k] for p in parts], axis=1)
    if with_grid:
        out["rho"], out["A"] = rho, A
    out[_SECONDS] = time.perf_counter() - start
    return out


def _tank_grid(tank, f, a, units):
    """(rho, A) at every (frequency [Hz], peak ground acceleration [units]) of a tank at
    constant acceleration, as Tank.parameters gives them for harmonic ground motion."""
    from .seismic import GroundMotion
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
                 workers=None, worker_kind=None, steady: Steady = Steady(),
                 integration: Integration = Integration(), continuation=None,
                 points_per_task=None, progress=True, units="g"):
    """Steady states on a grid of forcing frequency x amplitude, as an xarray Dataset with
    dimensions (frequency, amplitude) written to the Zarr store `store` as tasks finish.

    params_or_tank: sloshdyn.Parameters, with frequencies rho = Omega/omega and amplitudes the
    dimensionless A = u0/L; or a sloshdyn.Tank, with frequencies in Hz and amplitudes the peak
    ground acceleration in `units` (constant along the frequency axis: A = a/(L Omega^2)), the
    point's rho and A as variables. Every point is the steady state from rest with the given
    settings, equal bit for bit to sloshdyn.steady_state(params.replace(rho=..., A=...),
    steady=..., integration=...). continuation = 'up', 'down' or 'both' adds, for each amplitude, the sweep
    along the frequency axis that carries the state from point to point (variables *_up,
    *_down): where they differ from the points from rest, the response is multi-valued
    (hysteresis, jumps).

    The study runs on `client` (a dask.distributed Client), on the scheduler at address
    `scheduler`, or (neither given) on an embedded local cluster of `workers` workers (default:
    one per core) of kind `worker_kind` ('processes' by default, 'threads'). Rerunning the same
    study on the same store resumes it; a store made by a different study is refused
    (InputError). See README, "Studies"."""
    from .seismic import Tank
    tank = None
    f = _axis("frequencies", frequencies, 0.0)
    a = _axis("amplitudes", amplitudes, 0.0, lower_open=False)
    if isinstance(params_or_tank, Parameters):
        params = params_or_tank
        params.replace(rho=float(f.max()), A=float(a.max()))      # the core's range rules
        rho_grid, a_grid = np.meshgrid(f, a, indexing="ij")
    elif isinstance(params_or_tank, Tank):
        tank = params_or_tank
        params = tank.parameters()
        rho_grid, a_grid = _tank_grid(tank, f, a, units)
    else:
        raise InputError(f"params_or_tank = {type(params_or_tank).__name__} is not valid: give "
                         "sloshdyn.Parameters or sloshdyn.Tank")
    steady_array, integration_array = _settings(steady, integration)
    continuation = "none" if continuation is None else continuation
    directions = {"none": (), "up": ("up",), "down": ("down",), "both": ("up", "down")}[
        _checks.choice("continuation", continuation, ("none", "up", "down", "both"))]
    ppt = None if points_per_task is None else _positive_int("points_per_task", points_per_task)
    nf, na = len(f), len(a)

    def chunking(ppt):
        if directions:                      # a task sweeps whole frequency columns
            return nf, max(1, min(na, ppt // nf))
        bf = min(nf, ppt)
        return bf, max(1, min(na, ppt // bf))
    rpar, ipar = params.array()

    def task(block):
        return _response_task, (rpar, ipar, np.ascontiguousarray(rho_grid[block]),
                                np.ascontiguousarray(a_grid[block]), integration_array,
                                steady_array, directions, tank is not None)

    dims = ("frequency", "amplitude")
    variables = _summary_variables(dims)
    variables["transient_periods"] = _Variable(dims, "f8", np.nan, {
        "units": "forcing periods", "long_name": "transient integrated before measuring"})
    variables["shooting"] = _Variable(dims, "i1", -1, {
        "units": "1", "flag_values": [-1, 0, 1], "flag_meanings": "not_computed no yes",
        "long_name": "the steady state jumped to its periodic orbit by Newton shooting"})
    variables["max_multiplier"] = _Variable(dims, "f8", np.nan, {
        "units": "1", "long_name": "largest Floquet multiplier modulus of the orbit found by "
                                   "shooting (NaN: no jump)"})
    for d in directions:
        variables.update(_summary_variables(dims, f"_{d}", f"sweep {d} in frequency carrying "
                                                           "the state"))
    variables["done"] = _Variable(dims, "bool", False, {
        "long_name": "the point is computed and stored (resumable studies)"})
    if tank is not None:
        variables["rho"] = _Variable(dims, "f8", np.nan, {
            "units": "1", "long_name": "forcing frequency ratio rho = Omega/omega of the point"})
        variables["A"] = _Variable(dims, "f8", np.nan, {
            "units": "1", "long_name": "dimensionless base displacement amplitude A = u0/L of "
                                      "the point (constant acceleration: A falls as 1/f^2)"})
    spec = {"kind": "response_map", "parameters": dataclasses.asdict(params),
            "tank": None if tank is None else dataclasses.asdict(tank), "units": units,
            "frequencies": f.tolist(), "amplitudes": a.tolist(),
            "steady": dataclasses.asdict(steady), "integration": dataclasses.asdict(integration),
            "continuation": list(directions), "version": _version()}
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
    attrs = _common_attrs("response_map", params, steady, integration, {
        **extra, "continuation": ", ".join(directions) or "none",
        "study_spec": json.dumps(spec, sort_keys=True)})
    plan = _Plan("response_map", dims, coords, variables, attrs, spec, None, task, chunking, ppt)
    return run_plan(plan, store, client=client, scheduler=scheduler, workers=workers,
                    worker_kind=worker_kind, progress=progress)


# ---- basins of attraction --------------------------------------------------------------------

def _basin_task(rpar, ipar, y0, integration, steady):
    """One task of a basin study: the block's initial states (4, n1, n2) to their attractors."""
    start = time.perf_counter()
    shape = y0.shape[1:]
    n = int(np.prod(shape))
    flat = np.asfortranarray(y0.reshape(4, n))
    summaries, y_end, orbit, points, status, _, _ = _bridge.attractor_points(
        rpar, ipar, flat, integration, steady)
    impact = (summaries[SUMMARY_COLUMNS.index("max_x1")] >= 1).astype(np.int32)
    out = _unpack(summaries, orbit, impact, status, shape)
    out["transient_periods"] = summaries[SUMMARY_COLUMNS.index("transient_periods")].reshape(shape)
    out["orbit_found"] = np.where(status == 0, orbit[_ORBIT_FOUND], -1).astype(np.int8).reshape(shape)
    out["max_multiplier"] = orbit[_ORBIT_MAX_MU].reshape(shape)
    out["orbit_state"] = orbit[_ORBIT_Y].reshape((4,) + shape).transpose(1, 2, 0)
    out["orbit_points"] = points.reshape((4, _MAX_PERIOD) + shape).transpose(2, 3, 1, 0)
    out["final_state"] = y_end.reshape((4,) + shape).transpose(1, 2, 0)
    out[_SECONDS] = time.perf_counter() - start
    return out


def basins(params: Parameters, x1_range, dx1_range, n=50, store=None, *, x2=0.0, dx2=0.0,
           client=None, scheduler=None, workers=None, worker_kind=None,
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
    n = _positive_int("n", n, 2)
    ranges = []
    _checks.output_size("n", n * n, 4 * (_MAX_PERIOD + 3) + len(SUMMARY_COLUMNS))
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
    steady_array, integration_array = _settings(steady, integration)
    ppt = None if points_per_task is None else _positive_int("points_per_task", points_per_task)

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
    variables = _summary_variables(dims, what="steady state from the initial state")
    variables["transient_periods"] = _Variable(dims, "f8", np.nan, {
        "units": "forcing periods", "long_name": "transient integrated before measuring"})
    variables["orbit_found"] = _Variable(dims, "i1", -1, {
        "units": "1", "flag_values": [-1, 0, 1, 2],
        "flag_meanings": "not_computed none jumped_by_shooting refined_by_shooting",
        "long_name": "how the periodic orbit reached was found by the shooting code"})
    variables["max_multiplier"] = _Variable(dims, "f8", np.nan, {
        "units": "1", "long_name": "largest Floquet multiplier modulus of the orbit reached"})
    variables["orbit_state"] = _Variable(dims + ("state",), "f8", np.nan, {
        "units": "1", "long_name": "state (x1, x1', x2, x2') of the orbit reached at forcing "
                                   "phase 0, by shooting"})
    variables["orbit_points"] = _Variable(dims + ("orbit_point", "state"), "f8", np.nan, {
        "units": "1", "long_name": "Poincare points of the orbit reached over one orbit period "
                                   "(NaN beyond its period and for other motions)"})
    variables["final_state"] = _Variable(dims + ("state",), "f8", np.nan, {
        "units": "1", "long_name": "state at the end of the measuring window (forcing phase 0)"})
    variables["done"] = _Variable(dims, "bool", False, {
        "long_name": "the point is computed and stored (resumable studies)"})
    spec = {"kind": "basins", "parameters": dataclasses.asdict(params), "x1": x1.tolist(),
            "dx1": dx1.tolist(), "x2": float(x2), "dx2": float(dx2),
            "steady": dataclasses.asdict(steady), "integration": dataclasses.asdict(integration),
            "version": _version()}
    attrs = _common_attrs("basins", params, steady, integration, {
        "x2": float(x2), "dx2": float(dx2), "tol": float(tol),
        "study_spec": json.dumps(spec, sort_keys=True)})
    plan = _Plan("basins", dims, {
        "x1": (x1, {"units": "1", "long_name": "initial x1 = theta/theta0 (pendulum)"}),
        "dx1": (dx1, {"units": "1", "long_name": "initial x1' = dx1/dtau, tau = omega t"}),
        "state": (np.array(["x1", "dx1", "x2", "dx2"]), {"long_name": "state component"}),
        "orbit_point": (np.arange(1, _MAX_PERIOD + 1), {
            "units": "1", "long_name": "Poincare point of the orbit, in time order"})},
        variables, attrs, spec, None, task, chunking, ppt)
    ds = run_plan(plan, store, client=client, scheduler=scheduler, workers=workers,
                  worker_kind=worker_kind, progress=progress)
    ds = _label_basins(ds, tol)
    # the labels and the attractor list join the store (recomputed alike by every rerun)
    derived = [name for name in ds.data_vars if name.startswith("attractor")]
    import xarray as xr
    kept = {k: v for k, v in ds.attrs.items() if k not in _RUN_ATTRS}   # the store's own
    xr.Dataset({name: ds[name] for name in derived}, attrs=kept).to_zarr(
        ds.attrs["store"], mode="a", consolidated=True)
    return ds


def _label_basins(ds, tol):
    """The attractor of every run (Fortran label_attractors) and the attractor list."""
    n1, n2 = ds.sizes["x1"], ds.sizes["dx1"]
    motion = ds["motion"].values.astype(np.float64).ravel()
    motion[motion <= 0] = np.nan
    period = ds["period"].values.astype(np.float64).ravel()
    points = np.asfortranarray(ds["orbit_points"].values.reshape(n1 * n2, _MAX_PERIOD, 4)
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


# ---- impact parameters (beta, delta) ---------------------------------------------------------

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
    from .periodic import Lyapunov, lyapunov_exponent
    from .simulation import amplitude_sweep
    start = time.perf_counter()
    shape, n_a = (len(betas), len(deltas)), len(A_values)
    out = {"max_x1": np.full(shape + (n_a,), np.nan), "motion": np.zeros(shape + (n_a,), np.int8),
           "lyapunov": np.full(shape, np.nan), "status": np.zeros(shape, np.int16)}
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
                continue
            out["max_x1"][i, j] = [q.max_x1 for q in sweep.points]
            out["motion"][i, j] = [MOTION_CODES[q.motion] for q in sweep.points]
    out[_SECONDS] = time.perf_counter() - start
    return out


def impact_parameters(params: Parameters, betas, deltas, A_values, store, *,
                      client=None, scheduler=None, workers=None, worker_kind=None,
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
    b = _axis("betas", betas, 0.0)
    d = _axis("deltas", deltas, 0.0)
    a = _axis("A_values", A_values, 0.0, lower_open=False)
    for A in (0.00075, 1.0475, 2.0):
        if not np.any(np.isclose(a, A, rtol=1e-12, atol=0)):
            raise InputError(f"A_values lacks A = {A}: the paper's statements are tested there")
    params.replace(beta=float(b.max()), delta=float(d.max()), A=float(a.max()))   # range rules
    _settings(steady, integration)
    try:
        transient, measured = (int(v) for v in lyapunov_periods)
    except (TypeError, ValueError):
        raise InputError(f"lyapunov_periods = {lyapunov_periods!r} is not valid: give "
                         "(transient, measured) forcing periods") from None
    lyapunov = {"transient_periods": _positive_int("lyapunov_periods[0]", transient, 0),
                "n_periods": _positive_int("lyapunov_periods[1]", measured)}
    ppt = None if points_per_task is None else _positive_int("points_per_task", points_per_task)
    nb, nd = len(b), len(d)

    def chunking(ppt):
        bd = min(nd, ppt)
        return max(1, min(nb, ppt // bd)), bd

    def task(block):
        return _impact_task, (params, b[block[0]], d[block[1]], a, steady, integration, lyapunov)

    dims = ("beta", "delta")
    variables = {
        "max_x1": _Variable(dims + ("A",), "f8", np.nan, {
            "units": "1", "long_name": "max |x1| = max |theta|/theta0 over the measuring window "
                                       "at each A of the continuation"}),
        "motion": _Variable(dims + ("A",), "i1", -1, {
            **_MOTION_ATTRS, "long_name": "kind of motion at each A of the continuation"}),
        "lyapunov": _Variable(dims, "f8", np.nan, {
            "units": "1 per unit tau", "long_name": f"largest Lyapunov exponent at A = {a[-1]:g}"}),
        "status": _Variable(dims, "i2", -1, {
            "units": "1", "long_name": "core status of the point (0 ok, -1 not computed)"}),
        "done": _Variable(dims, "bool", False, {
            "long_name": "the point is computed and stored (resumable studies)"})}
    spec = {"kind": "impact_parameters", "parameters": dataclasses.asdict(params),
            "betas": b.tolist(), "deltas": d.tolist(), "A_values": a.tolist(),
            "steady": dataclasses.asdict(steady), "integration": dataclasses.asdict(integration),
            "lyapunov": lyapunov, "version": _version()}
    attrs = _common_attrs("impact_parameters", params, steady, integration, {
        "study_spec": json.dumps(spec, sort_keys=True)})
    plan = _Plan("impact_parameters", dims, {
        "beta": (b, {"units": "1", "long_name": "impact coefficient beta (eq 4, "
                                                "dimensionless)"}),
        "delta": (d, {"units": "1", "long_name": "sloshing dissipation delta (dimensionless)"}),
        "A": (a, {"units": "1", "long_name": "base displacement amplitude A = u0/L along the "
                                             "continuation"})},
        variables, attrs, spec, None, task, chunking, ppt)
    ds = run_plan(plan, store, client=client, scheduler=scheduler, workers=workers,
                  worker_kind=worker_kind, progress=progress)
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


# ---- fragility (incremental dynamic analysis) ------------------------------------------------

_PEAKS = [c.split(" [")[0] for c in _tables.columns("seismic_peaks")]
_FRAGILITY_LOADS = {
    "peak_wave_height": ("m", "largest wave height at the wall over the run"),
    "peak_sloshing_displacement": ("m", "largest displacement of the sloshing mass relative to "
                                        "the tank"),
    "peak_base_shear": ("N", "largest base shear (about the tank bottom)"),
    "peak_overturning_moment": ("N m", "largest overturning moment about the tank bottom"),
    "peak_tank_drift": ("m", "largest drift of the tank relative to the ground"),
    "peak_impact_force": ("N", "largest impact force of the roof/walls on the liquid"),
    "first_roof_time": ("s", "first time the wave reached the roof (NaN: never)"),
}


def _fragility_task(tank, records, intensities, sa_factor, period, damping, integration):
    """One task of a fragility study: every (record, intensity) of the block, each record
    scaled to the spectral acceleration at `period`, then the seismic response from rest.
    Runs on a worker; every number comes from the core (scale_ground, seismic_response)."""
    start = time.perf_counter()
    shape = (len(records), len(intensities))
    out = {name: np.full(shape, np.nan) for name in _FRAGILITY_LOADS}
    out["scale_factor"] = np.full(shape, np.nan)
    out["roof_impact"] = np.full(shape, 0, np.int8)
    out["roof_impacts"] = np.full(shape, -1, np.int32)
    out["status"] = np.zeros(shape, np.int16)
    for i, (ground, samples) in enumerate(records):
        for j, sa in enumerate(intensities):
            scaled, scaled_samples, status, _ = _bridge.scale_ground(
                ground, samples, 1.0, 0.0, sa * sa_factor, period, damping)
            if status == 0:
                chosen, status, _ = _bridge.seismic_defaults(tank, scaled, scaled_samples, 0.0, 0)
            if status == 0:
                _, peaks, status, _ = _bridge.seismic_response(
                    tank, scaled, scaled_samples, float(chosen[0]), int(chosen[1]), integration)
            out["status"][i, j] = status
            if status != 0:
                out["roof_impact"][i, j] = -1
                continue
            values = dict(zip(_PEAKS, peaks))
            for name in _FRAGILITY_LOADS:
                out[name][i, j] = values[name]
            out["roof_impact"][i, j] = int(values["roof_reached"] != 0)
            out["roof_impacts"][i, j] = int(values["roof_impacts"])
            peak_in = np.max(np.abs(samples)) if samples.size else ground[1]
            peak_out = np.max(np.abs(scaled_samples)) if scaled_samples.size else scaled[1]
            out["scale_factor"][i, j] = peak_out / peak_in
    out[_SECONDS] = time.perf_counter() - start
    return out


def _record_name(record, k):
    if isinstance(record, (str, os.PathLike)):
        return os.path.basename(os.fspath(record))
    return f"record_{k}"


def fragility_study(tank, records, intensities, store, *, units="g", period=None,
                    damping=0.005, client=None, scheduler=None, workers=None, worker_kind=None,
                    integration: Integration = Integration(), points_per_task=None,
                    progress=True, names=None):
    """Incremental dynamic analysis of a tank (sloshdyn.Tank) over a suite of ground-motion
    records: every record scaled to each intensity -- the pseudo-spectral acceleration Sa at
    `period` (default: the tank's sloshing period) for the damping ratio `damping` (default
    0.5 %, the convective damping of the design codes), in `units` -- and the seismic response
    from rest (sloshdyn.seismic_response) with its peaks: wave height, base shear, overturning
    moment, roof impact (the wave reaches the roof: |x1| >= 1) per run. The lognormal fragility
    curve of roof impact is fitted by maximum likelihood over all runs (fit_fragility):
    variables fragility_median [units] and fragility_dispersion with their standard errors
    (NaN where no run, or every run, reached the roof).

    records: GroundMotion objects or record files (PEER .AT2 or two columns, read with
    GroundMotion.from_file). Returns a Dataset with dimensions (record, intensity), written to
    the Zarr store `store` as tasks finish; engine, resumption and errors as response_map."""
    from .seismic import GroundMotion, Tank, acceleration_factor
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
    x = _axis("intensities", intensities, 0.0)
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
    ppt = None if points_per_task is None else _positive_int("points_per_task", points_per_task)
    n_r, n_x = len(motions), len(x)

    def chunking(ppt):
        return (max(1, min(n_r, ppt // n_x)), n_x) if n_x <= ppt else (1, ppt)
    arrays = [m._arrays() for m in motions]
    tank_array = tank.array()

    def task(block):
        return _fragility_task, (tank_array, arrays[block[0]], x[block[1]], sa_factor, period,
                                 float(damping), integration_array)

    dims = ("record", "intensity")
    variables = {name: _Variable(dims, "f8", np.nan, {"units": unit, "long_name": text})
                 for name, (unit, text) in _FRAGILITY_LOADS.items()}
    variables["scale_factor"] = _Variable(dims, "f8", np.nan, {
        "units": "1", "long_name": "factor applied to the record to reach the intensity"})
    variables["roof_impact"] = _Variable(dims, "i1", -1, {
        "units": "1", "flag_values": [-1, 0, 1], "flag_meanings": "not_computed_or_failed no yes",
        "long_name": "the wave reached the roof during the run (|x1| >= 1)"})
    variables["roof_impacts"] = _Variable(dims, "i4", -1, {
        "units": "1", "long_name": "number of strikes on the roof during the run"})
    variables["status"] = _Variable(dims, "i2", -1, {
        "units": "1", "long_name": "core status of the run (0 ok, -1 not computed)"})
    variables["done"] = _Variable(dims, "bool", False, {
        "long_name": "the run is computed and stored (resumable studies)"})
    digests = [hashlib.sha256(np.ascontiguousarray(a[1]).tobytes() + a[0].tobytes()).hexdigest()
               for a in arrays]
    spec = {"kind": "fragility", "tank": dataclasses.asdict(tank), "records": digests,
            "names": labels, "intensities": x.tolist(), "units": units, "period": period,
            "damping": float(damping), "integration": dataclasses.asdict(integration),
            "version": _version()}
    attrs = {"title": "sloshdyn fragility study (incremental dynamic analysis)",
             "study": "fragility", "sloshdyn_version": _version(),
             "tank": json.dumps(dataclasses.asdict(tank)),
             "integration": json.dumps(dataclasses.asdict(integration)),
             "intensity_measure": f"pseudo-spectral acceleration Sa({period:.6g} s, "
                                  f"{100 * damping:g} %) [{units}]",
             "spectral_period": period, "spectral_damping": float(damping),
             "record_sha256": json.dumps(dict(zip(labels, digests))),
             "study_spec": json.dumps(spec, sort_keys=True)}
    plan = _Plan("fragility", dims, {
        "record": (np.array(labels), {"long_name": "ground-motion record"}),
        "intensity": (x, {"units": units, "long_name": f"spectral acceleration Sa at "
                                                      f"T = {period:.4g} s, {100 * damping:g} % "
                                                      "damping"})},
        variables, attrs, spec, None, task, chunking, ppt)
    ds = run_plan(plan, store, client=client, scheduler=scheduler, workers=workers,
                  worker_kind=worker_kind, progress=progress)
    return _fit_study(ds, units)


def _fit_study(ds, units):
    """The lognormal fit of roof impact over every run, as 0-d variables."""
    hit = ds["roof_impact"].values
    ok = hit >= 0
    xs = np.broadcast_to(ds["intensity"].values, hit.shape)[ok]
    values = dict(median=np.nan, beta=np.nan, median_se=np.nan, beta_se=np.nan)
    try:
        fit = fit_fragility(xs, hit[ok].astype(float))
        values = dict(median=fit.median, beta=fit.beta, median_se=fit.median_se,
                      beta_se=fit.beta_se)
        ds.attrs["fragility_fit"] = "lognormal, maximum likelihood over every run"
    except InputError as exc:     # no run or every run reached the roof, or they separate
        ds.attrs["fragility_fit"] = f"not fitted: {exc}"
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
