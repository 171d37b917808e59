"""The study engine: a study is a `Plan` (axes, variables, attributes, and the task that
computes one block of the grid); `run_plan` runs it on Dask and writes each task's results to
a Zarr store as it finishes, so that rerunning the same study on the same store resumes it.
The store's chunks are fixed when it is created (`store`); a task is one block of whole
chunks, sized from the workers there when it is handed out, and tasks are handed out in
waves, a few per worker thread, so that the client's memory stays bounded. Where the study
runs, and which workers it may use, is `cluster`. The study kinds (response maps, basins,
impact parameters, fragility) are plans built in their own modules."""

from __future__ import annotations

import concurrent.futures
import contextlib
import dataclasses
import json
import math
import os
import signal
import time
import threading
from dataclasses import dataclass

import numpy as np

from .. import _checks, _core
from .._errors import ClusterError, InputError
from .._extras import require
from . import cluster, store as stores
from .cluster import version       # the study kinds' (their specs and attributes)

#: points per task unless told: about 8 tasks per worker for the load balance, within these
#: bounds (measured by benchmarks/studies.py: the engine's overhead is ~20 % of the work at 8
#: points per task, ~5 % at 32, ~2 % at 128; docs/studies.md)
MIN_POINTS_PER_TASK, MAX_POINTS_PER_TASK, TASKS_PER_WORKER = stores.CHUNK_POINTS, 128, 8
#: tasks handed out ahead per worker thread: one running, one waiting (so a thread never idles
#: for the client), and no more, so the client holds a few futures, not one per task
TASKS_AHEAD_PER_THREAD = 2
#: a task's result entry (not stored) with the seconds the task computed
SECONDS = "_compute_seconds"
#: attributes of a returned dataset that describe the call, not the study (not stored)
RUN_ATTRS = ("points_computed", "compute_seconds", "points_repaired", "repaired", "store",
             "points_failed")

_cancel = _core.sloshdyn_bridge_input


@dataclass
class Variable:
    dims: tuple
    dtype: str                   #: a numpy dtype, or "str" (text, variable length)
    fill: object
    attrs: dict


@dataclass
class Plan:
    """A study in index space: its axes, variables, attributes, and tasks (blocks of whole
    chunks of the store). task(block) is (function, args) for Dask; the function returns
    {variable: array over the block}, one call for the whole block (the block is one unit of
    work: an ensemble of points). chunking(points) gives the shape of a block of about that
    many points that a task may be (e.g. whole frequency columns for a sweep); the store's
    chunks are one such shape, fixed at its creation; points_per_task None lets the engine
    choose (auto_points_per_task)."""

    kind: str
    dims: tuple
    coords: dict                 #: dim -> (values, attrs)
    variables: dict              #: name -> Variable (the 'done' mask is added)
    attrs: dict
    spec: dict                   #: what must match to resume (JSON-able)
    chunks: tuple
    task: object                 #: block (tuple of slices) -> (function, args)
    chunking: object = None      #: points -> block shape
    points_per_task: int = None
    cost: object = None          #: block -> its expected compute time, any unit (None: its size)

    @property
    def shape(self):
        return tuple(len(self.coords[d][0]) for d in self.dims)

    @property
    def chunk_grid(self):
        """The number of chunks along each axis."""
        return tuple(math.ceil(n / c) for n, c in zip(self.shape, self.chunks))

    def block(self, lower, upper):
        """The block of points of the chunks lower..upper-1 (chunk indices per axis)."""
        return tuple(slice(lo * c, min(hi * c, n))
                     for lo, hi, c, n in zip(lower, upper, self.chunks, self.shape))

    def chunk_blocks(self):
        """(index, block) of every chunk, in grid order."""
        for index in np.ndindex(*self.chunk_grid):
            yield index, self.block(index, [i + 1 for i in index])

    def chunks_of(self, block):
        """The chunks (blocks) that a block of whole chunks is made of."""
        ranges = [range(s.start // c, math.ceil(s.stop / c)) for s, c in zip(block, self.chunks)]
        for index in np.ndindex(*[len(r) for r in ranges]):
            lower = [r[i] for r, i in zip(ranges, index)]
            yield self.block(lower, [i + 1 for i in lower])

    def block_size(self, block):
        return math.prod(s.stop - s.start for s in block)

    def task_extent(self, points):
        """The chunks along each axis of a task of about `points` points: the plan's block
        shape for that many, rounded up to whole chunks (at least one)."""
        shape = self.chunking(points)
        return tuple(min(g, max(1, math.ceil(s / c)))
                     for s, c, g in zip(shape, self.chunks, self.chunk_grid))

    def variable_shape(self, name):
        return tuple(len(self.coords[d][0]) for d in self.variables[name].dims)

    def variable_chunks(self, name):
        """A variable's chunks: the plan's along its axes, whole along its other dimensions."""
        along = dict(zip(self.dims, self.chunks))
        return tuple(along.get(d, len(self.coords[d][0])) for d in self.variables[name].dims)

    def region(self, name, block):
        """The part of a variable that a block of the grid covers."""
        where = dict(zip(self.dims, block))
        return tuple(where.get(d, slice(None)) for d in self.variables[name].dims)

    def chunk_index(self, name, block):
        """The index of the chunk of a variable where a block of the grid starts."""
        where = dict(zip(self.dims, zip(block, self.chunks)))
        return tuple(where[d][0].start // where[d][1] if d in where else 0
                     for d in self.variables[name].dims)


def auto_points_per_task(n_points, n_workers):
    """Points per task: about TASKS_PER_WORKER tasks per worker thread, within
    [MIN_POINTS_PER_TASK, MAX_POINTS_PER_TASK]."""
    wanted = math.ceil(n_points / (TASKS_PER_WORKER * max(1, n_workers)))
    return int(min(MAX_POINTS_PER_TASK, max(MIN_POINTS_PER_TASK, wanted)))


class Tasks:
    """The chunks still to hand out, cut into tasks when they are handed out: the grid of
    chunks is tiled into blocks of the task's extent (it may change from one task to the
    next, with the workers), taken longest first (by the plan's cost, else by size; ties in
    grid order: the last tasks to finish are short ones and no worker waits long for the
    others at the end, Graham's longest processing time first); a tile of which some chunks
    are taken already is split into the largest blocks of free chunks."""

    def __init__(self, plan, todo):
        self.plan = plan
        self.free = todo.copy()            #: chunks to compute not handed out yet
        self.extent = None
        self.order = []
        self.ready = []                    #: blocks of free chunks of the current tile

    def points_left(self):
        sizes = [np.diff(np.minimum(np.arange(g + 1) * c, n))
                 for g, c, n in zip(self.plan.chunk_grid, self.plan.chunks, self.plan.shape)]
        counts = sizes[0]
        for s in sizes[1:]:
            counts = np.multiply.outer(counts, s)
        return int(counts[self.free].sum())

    def _tile(self, extent):
        grid = self.plan.chunk_grid
        corners = [tuple(i * e for i, e in zip(index, extent))
                   for index in np.ndindex(*[math.ceil(g / e) for g, e in zip(grid, extent)])]
        tiles = [(lo, tuple(min(a + e, g) for a, e, g in zip(lo, extent, grid)))
                 for lo in corners]
        tiles = [t for t in tiles if self.free[tuple(slice(a, b) for a, b in zip(*t))].any()]
        key = self.plan.cost or self.plan.block_size
        self.order = sorted(tiles, key=lambda t: key(self.plan.block(*t)), reverse=True)
        self.order.reverse()               # popped from the end: the longest first
        self.extent = extent

    def _split(self, lower, upper):
        """The largest blocks of free chunks in lower..upper-1, halving the longest axis."""
        region = self.free[tuple(slice(a, b) for a, b in zip(lower, upper))]
        if region.all():
            return [(lower, upper)]
        if not region.any():
            return []
        axis = int(np.argmax([b - a for a, b in zip(lower, upper)]))
        middle = (lower[axis] + upper[axis]) // 2
        return (self._split(lower, upper[:axis] + (middle,) + upper[axis + 1:])
                + self._split(lower[:axis] + (middle,) + lower[axis + 1:], upper))

    def take(self, points):
        """The next task's block, about `points` points of whole chunks, or None when every
        chunk is handed out."""
        extent = self.plan.task_extent(points)
        if extent != self.extent:
            self._tile(extent)
            self.ready = []
        while not self.ready and self.order:
            self.ready = self._split(*self.order.pop())[::-1]
        if not self.ready:
            return None
        lower, upper = self.ready.pop()
        self.free[tuple(slice(a, b) for a, b in zip(lower, upper))] = False
        return self.plan.block(lower, upper)


def check_size(plan):
    """Refuse a study whose results would not fit in half the machine's memory (the result is
    returned whole), naming its axes, before anything runs."""
    n = int(np.prod(plan.shape))
    size = sum(np.dtype(v.dtype).itemsize * int(np.prod(plan.variable_shape(name)))
               for name, v in plan.variables.items())
    if size > _checks.MAX_OUTPUT_BYTES or n > _checks.C_INT_MAX:
        axes = " x ".join(f"{len(plan.coords[d][0])} {d}" for d in plan.dims)
        raise InputError(f"the study of {axes} values ({n} points) is too large: its results "
                         f"would take {size / 2**30:.3g} GiB (at most "
                         f"{_checks.MAX_OUTPUT_BYTES / 2**30:.3g} GiB, half this machine's "
                         "memory); split it into smaller studies")


@contextlib.contextmanager
def _remembered_interrupts():
    """A check() that raises again a Ctrl-C (SIGINT) or SIGTERM that came while the block runs:
    their handlers raise KeyboardInterrupt (sloshdyn-py's SIGTERM a kind of it) where Python
    runs next, and when that is a finalizer (a Dask Future's __del__) it is printed as
    "Exception ignored" and lost, and the study would run to its end; the caller checks after
    every finished task. In the main thread only, and only for signals with a Python handler
    (an ignored signal stays ignored)."""
    received = []
    previous = {sig: signal.getsignal(sig) for sig in (signal.SIGINT, signal.SIGTERM)}
    previous = {sig: handler for sig, handler in previous.items() if callable(handler)}

    def remember(signum, frame):
        received.append(signum)
        previous[signum](signum, frame)

    def check():
        if received:
            previous[received[0]](received[0], None)

    if threading.current_thread() is not threading.main_thread():
        previous = {}
    for sig in previous:
        signal.signal(sig, remember)
    try:
        yield check
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)


def _task_error(error, plan, block):
    """The error of a task that failed on its worker: a sloshdyn error as it is; a task
    that ended the workers that ran it (Dask's KilledWorker) names its points."""
    from distributed import KilledWorker
    if isinstance(error, KilledWorker):
        where = ", ".join(f"{d} {plan.coords[d][0][s][0]!s:.12}..{plan.coords[d][0][s][-1]!s:.12}"
                          for d, s in zip(plan.dims, block))
        return ClusterError(f"the task of {plan.block_size(block)} points ({where}) ended every "
                            f"worker that ran it ({error}): it is not retried")
    return error


def fetched(future):
    """A finished task's result, or None when it cannot be fetched within a tick: its result
    lived on a worker that left (Dask reschedules the task, and waiting on it would wait for
    ever when no worker is left to run it, past the grace time)."""
    try:
        return future.result(timeout=cluster.TICK)
    except TimeoutError:
        return None


def _run_tasks(c, plan, tasks, pool, writer, bar, check_interrupts):
    """Hand out the tasks in waves (TASKS_AHEAD_PER_THREAD per usable worker thread, each
    sized from the threads there at that moment, restricted to the usable workers), write
    each result as it comes, and watch the workers (a study without a usable worker fails
    after the grace time). Returns (points computed, seconds computed)."""
    from distributed import wait
    pending = {}                          #: future -> (block, the workers it may run on)
    computed, seconds = 0, 0.0
    todo_points = tasks.points_left()
    sequence = 0

    def submit(block):
        nonlocal sequence
        function, args = plan.task(block)
        allowed = list(pool.usable)
        sequence += 1
        future = c.submit(function, *args, pure=False, priority=-sequence, workers=allowed,
                          allow_other_workers=False)
        pending[future] = (block, set(allowed))

    try:
        while True:
            pool.check_alive()
            threads = pool.threads()
            if threads:
                per_task = plan.points_per_task or auto_points_per_task(todo_points, threads)
                while len(pending) < TASKS_AHEAD_PER_THREAD * threads:
                    block = tasks.take(per_task)
                    if block is None:
                        break
                    submit(block)
                for future, (block, allowed) in list(pending.items()):
                    if not allowed & set(pool.usable):    # its workers are gone: others now
                        del pending[future]
                        future.cancel()
                        submit(block)
            if not pending:
                if not tasks.free.any():
                    return computed, seconds
                time.sleep(cluster.TICK)         # no usable worker: check_alive waits
                continue
            try:
                finished = wait(list(pending), timeout=cluster.TICK,
                                return_when="FIRST_COMPLETED").done
            except TimeoutError:
                finished = ()
            for future in finished:
                block, allowed = pending.pop(future)
                status = future.status               # read once: a worker may leave meanwhile
                if status == "cancelled":            # by the cluster (not by us): again
                    submit(block)
                    continue
                if status == "error":
                    raise _task_error(future.exception(), plan, block)
                # lost or pending: its result left with its worker since wait (Dask computes it
                # again)
                result = fetched(future) if status == "finished" else None
                if result is None:                   # its data left with its worker: again
                    pending[future] = (block, allowed)
                    continue
                seconds += result.get(SECONDS, 0.0)
                writer.write(block, result)
                computed += plan.block_size(block)
                if bar:
                    bar.update(plan.block_size(block))
            check_interrupts()
    finally:
        for future in pending:
            future.cancel()
        pending.clear()


def run_plan(plan, store, *, client=None, scheduler=None, workers=None, worker_kind=None,
             min_workers=None, grace_time=None, progress=True, derive=None):
    """Run a study plan on Dask, storing each task's results in `store` as it finishes; return
    the whole study as an xarray Dataset (loaded). Already finished points are not recomputed;
    the returned dataset's attrs['points_computed'] counts the points this call computed,
    attrs['compute_seconds'] the time its tasks spent computing (summed over workers),
    attrs['points_repaired'] the finished points computed again because their stored data were
    missing, damaged or not theirs (attrs['repaired'] says which variables) and
    attrs['points_failed'] the points whose status is not 0. The study waits for
    `min_workers` usable workers at its start, and for a usable worker whenever none is alive,
    at most `grace_time` seconds each time (then ClusterError). derive(dataset), if given,
    adds the variables derived from all the points (basins' attractor list, the fragility
    fit): they join the store too, derived again by every rerun."""
    require("studies", "dask.distributed", "xarray", "zarr")
    path = stores.check_path(store)
    plan = _with_identity(plan)
    if worker_kind is None:
        worker_kind = cluster.WORKER_KIND
    embedded = None
    if client is None and scheduler:
        cluster.check_scheduler(scheduler)
    elif client is None:
        workers = cluster.check_workers(workers, worker_kind)
        embedded = cluster.embedded_size(workers, worker_kind)
    minimum, grace = cluster.check_waiting(min_workers, grace_time, embedded)
    check_size(plan)
    exists = os.path.exists(path)
    plan = dataclasses.replace(plan, chunks=stores.check_existing(plan, path) if exists else
                               stores.chunk_shape(plan))
    todo, repaired, damaged = None, 0, []
    if exists:
        todo, repaired, damaged = stores.Store(plan, path).verify()
    computed = compute_seconds = 0
    loading = None
    if todo is None or todo.any():
        bar = None
        try:
            with contextlib.ExitStack() as stack:
                stack.callback(_cancel.clear_cancel)      # once the cluster is closed
                c = stack.enter_context(cluster.connect(client, scheduler, workers, worker_kind))
                pool = cluster.Workers(c, grace, minimum if embedded is None else 1)
                pool.wait_for_minimum()
                if todo is None:
                    if not stores.create(plan, path):    # another study created it meanwhile
                        plan = dataclasses.replace(plan, chunks=stores.check_existing(plan, path))
                        todo, repaired, damaged = stores.Store(plan, path).verify()
                    else:
                        todo = np.ones(plan.chunk_grid, dtype=bool)
                tasks = Tasks(plan, todo)
                if progress:
                    from tqdm.auto import tqdm
                    total = math.prod(plan.shape)
                    bar = tqdm(total=total, initial=total - tasks.points_left(),
                               desc=plan.kind.replace("_", " "), unit="point", smoothing=0.1)
                try:
                    with _remembered_interrupts() as check_interrupts:
                        computed, compute_seconds = _run_tasks(
                            c, plan, tasks, pool, stores.Store(plan, path), bar,
                            check_interrupts)
                        check_interrupts()
                except BaseException:
                    # the tasks running in this process (worker threads) stop within one
                    # integrator step; the cluster's close waits for them
                    _cancel.request_cancel()
                    raise
                # every task is stored: the study is read while the cluster closes
                reader = concurrent.futures.ThreadPoolExecutor(1)
                loading = reader.submit(stores.load, path, plan)
                reader.shutdown(wait=False)
        except KeyboardInterrupt as exc:    # Ctrl-C, or SIGTERM as sloshdyn-py raises it
            raise type(exc)(f"study interrupted: {_stored(plan, path)} points stored in {path}"
                            "; rerun the same study on it to resume") from None
        except ClusterError as exc:
            raise ClusterError(f"{exc}; {_stored(plan, path)} of the study's "
                               f"{math.prod(plan.shape)} points are stored in {path}: rerun "
                               "the same study on it to resume") from None
        finally:
            if bar:
                bar.close()
    ds = loading.result() if loading else stores.load(path, plan)
    ds.attrs["points_computed"] = computed
    ds.attrs["compute_seconds"] = compute_seconds     #: inside the tasks, summed over workers
    ds.attrs["points_repaired"] = repaired
    ds.attrs["repaired"] = ", ".join(damaged)
    ds.attrs["store"] = path
    ds.attrs["points_failed"] = int((ds["status"] > 0).sum()) if "status" in ds else 0
    if derive is not None:
        points = set(ds.data_vars)
        ds = derive(ds)
        stores.store_derived(ds, [name for name in ds.data_vars if name not in points], RUN_ATTRS)
    return ds


def failed_points(ds, limit=5):
    """The failed points of a study's dataset named, at most `limit` of them (coordinates,
    status and message), and how many failed: ("", 0) when none did."""
    status = ds["status"]
    where = np.argwhere(status.values > 0)
    names = []
    for index in where[:limit]:
        point = status[tuple(index)]
        at = ", ".join(f"{d} = {point[d].values!s}" for d in status.dims)
        names.append(f"{at}: status {int(point)}, {ds['message'].values[tuple(index)]}")
    more = f"; and {len(where) - limit} more" if len(where) > limit else ""
    return "; ".join(names) + more, len(where)


def _with_identity(plan):
    """The plan with its `done` variable (each finished chunk's checksum, store.checksum) and
    the store format in its spec (a store of another format is another study)."""
    spec = {**plan.spec, "store_format": stores.STORE_FORMAT}
    variables = {**plan.variables, "done": Variable(plan.dims, "u8", 0, {
        "units": "1", "long_name": "the point's chunk is computed and stored: the checksum of "
                                   "its study, place and values (0: not computed)"})}
    attrs = {**plan.attrs, "study_spec": json.dumps(spec, sort_keys=True)}
    return dataclasses.replace(plan, spec=spec, variables=variables, attrs=attrs)


def _stored(plan, path):
    """The points marked done in the store (0 if it cannot be read)."""
    try:
        done = stores.open_group(path)["done"][...]
    except Exception:
        return 0
    return int((done != 0).sum())


def axis(name, values, lower, lower_open=True):
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


def positive_int(name, value, lower=1):
    return _checks.integer(name, value, lower)
