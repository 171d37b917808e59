"""The study engine: a study is a `Plan` (axes, variables, attributes, and the task that
computes one block of the grid); `run_plan` runs it on Dask and writes each task's results to a
Zarr store as it finishes, so that rerunning the same study on the same store resumes it.
The study kinds (response maps, basins, impact parameters, fragility) are plans built in their
own modules."""

from __future__ import annotations

import concurrent.futures
import contextlib
import dataclasses
import hashlib
import json
import math
import os
import shutil
import signal
import socket
import struct
import sys
import threading
import time
import uuid
import warnings
from dataclasses import dataclass

import numpy as np

from .. import _checks, _tables
from .._errors import FileError, InputError
from .._version import __version__
from .._extras import require

#: points per task unless told: about 8 tasks per worker for the load balance, within these
#: bounds (measured by benchmarks/studies.py: the engine's overhead is ~20 % of the work at 8
#: points per task, ~5 % at 32, ~2 % at 128; docs/studies.md)
MIN_POINTS_PER_TASK, MAX_POINTS_PER_TASK, TASKS_PER_WORKER = 8, 128, 8
#: the default worker kind of an embedded cluster, the core's (&study worker_kind): threads,
#: by measurement (docs/studies.md, "Worker kind and task size")
WORKER_KIND = _tables.codes("worker_kinds")[int(_tables.defaults("study")["worker_kind"])]
#: how long a scheduler address may take to answer
CONNECT_TIMEOUT = 5.0
#: a task's result entry (not stored) with the seconds the task computed
SECONDS = "_compute_seconds"
#: attributes of a returned dataset that describe the call, not the study (not stored)
RUN_ATTRS = ("points_computed", "compute_seconds", "points_repaired", "repaired", "store")
#: the memory a worker process takes, for the bound on their number (measured: ~150 MiB)
WORKER_PROCESS_BYTES = 512 * 2**20
#: Dask settings of an embedded cluster: its servers' periodic work (the event-loop tick, the
#: workers' sampling profiler, the system and memory monitors), made for dashboards, which
#: the embedded cluster does not start, took ~4 % of a core in the study's process and ~3 %
#: in each worker even while idle, CPU that two workers on two cores take from the tasks
#: (measured: docs/studies.md, "Worker kind and task size")
CLUSTER_CONFIG = {
    "distributed.admin.tick.interval": "1s",
    "distributed.worker.profile.enabled": False,
    "distributed.admin.system-monitor.interval": "2s",
    "distributed.worker.memory.monitor-interval": "500ms",
}


@dataclass
class Variable:
    dims: tuple
    dtype: str
    fill: object
    attrs: dict


@dataclass
class Plan:
    """A study in index space: its axes, variables, attributes, and tasks (blocks of the grid,
    aligned with the store's chunks). task(block) is (function, args) for Dask; the function
    returns {variable: array over the block}. chunking(points_per_task) gives the chunk shape;
    points_per_task None lets the engine choose (auto_points_per_task)."""

    kind: str
    dims: tuple
    coords: dict                 #: dim -> (values, attrs)
    variables: dict              #: name -> Variable (the 'done' mask is added)
    attrs: dict
    spec: dict                   #: what must match to resume (JSON-able)
    chunks: tuple
    task: object                 #: block (tuple of slices) -> (function, args)
    chunking: object = None      #: points per task -> chunk shape
    points_per_task: int = None
    cost: object = None          #: block -> its expected compute time, any unit (None: its size)

    def blocks(self):
        ranges = [range(0, len(self.coords[d][0]), c) for d, c in zip(self.dims, self.chunks)]
        for corner in np.ndindex(*[len(r) for r in ranges]):
            yield tuple(slice(r[i], min(r[i] + c, len(self.coords[d][0])))
                        for r, i, c, d in zip(ranges, corner, self.chunks, self.dims))

    @property
    def shape(self):
        return tuple(len(self.coords[d][0]) for d in self.dims)

    def block_size(self, block):
        return math.prod(s.stop - s.start for s in block)

    def longest_first(self, blocks):
        """The blocks in the order their tasks are dispatched: the longest expected first (by
        `cost`, else by size; ties in grid order), so that the last tasks to finish are short
        ones and no worker waits long for the others at the end (longest processing time
        first, Graham 1969)."""
        return sorted(blocks, key=self.cost or self.block_size, reverse=True)

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
        """The index of the chunk of a variable that a block of the grid is."""
        where = dict(zip(self.dims, zip(block, self.chunks)))
        return tuple(where[d][0].start // where[d][1] if d in where else 0
                     for d in self.variables[name].dims)


def auto_points_per_task(n_points, n_workers):
    """Points per task: about TASKS_PER_WORKER tasks per worker thread, within
    [MIN_POINTS_PER_TASK, MAX_POINTS_PER_TASK]."""
    wanted = math.ceil(n_points / (TASKS_PER_WORKER * max(1, n_workers)))
    return int(min(MAX_POINTS_PER_TASK, max(MIN_POINTS_PER_TASK, wanted)))


def version():
    return __version__


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
    """The empty study as a Dataset, and its encoding: the plan's chunks, and a CRC-32 in every
    chunk of a variable, so that a damaged chunk is found when the study is resumed."""
    import numcodecs
    import xarray as xr
    coords = {d: xr.Variable(d, np.asarray(v), attrs) for d, (v, attrs) in plan.coords.items()}
    data = {}
    encoding = {}
    for name, var in plan.variables.items():
        data[name] = xr.Variable(var.dims, np.full(plan.variable_shape(name), var.fill,
                                                   dtype=var.dtype), var.attrs)
        encoding[name] = {"chunks": plan.variable_chunks(name), "filters": [numcodecs.CRC32()],
                          "_FillValue": np.nan if np.dtype(var.dtype).kind == "f" else None}
    ds = xr.Dataset(data, coords=coords, attrs=plan.attrs)
    return ds, encoding


def _remove_tree(path):
    """Remove a directory that writes still under way may fill again (zarr writes a store's
    files concurrently: when one write fails, the others go on for a moment)."""
    for _ in range(100):
        shutil.rmtree(path, ignore_errors=True)
        time.sleep(0.05)
        if not os.path.exists(path):
            time.sleep(0.2)
            if not os.path.exists(path):
                return


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
        raise FileError(f"store = {path!r} cannot be written: {exc.strerror or exc}; nothing "
                        "of it is left") from exc
    finally:
        if os.path.exists(tmp):
            _remove_tree(tmp)


def _damaged(path, what):
    return InputError(f"store = {path!r} is damaged: {what}; it cannot be repaired by "
                      "recomputing points: give another store, or delete it to start again")


def _chunk_file(path, name, index):
    """The file of chunk `index` of array `name` (Zarr format 2, '.' separated keys)."""
    return os.path.join(path, name, ".".join(str(i) for i in index))


def _open_study(plan, path):
    """An existing store checked against the plan: the same study (else refused, naming what
    differs), every array of the plan there with its shape, coordinates equal to the plan's
    (else refused as damaged). Returns (chunks, todo, repaired): the store's chunk shape (its
    tasks), the blocks with points to compute, and the number of finished points whose stored
    data were missing or unreadable, and the arrays where (a deleted, truncated or garbled chunk: every chunk carries a CRC-32):
    those blocks' chunk files are removed, so that they are computed again."""
    import zarr
    if not os.path.isfile(os.path.join(path, ".zmetadata")):
        raise _damaged(path, "its consolidated metadata .zmetadata is missing")
    try:
        group = zarr.open_group(path, mode="r", zarr_format=2, use_consolidated=True)
        stored = json.loads(group.attrs["study_spec"])
    except Exception as exc:
        raise InputError(f"store = {path!r} exists but is not a sloshdyn study store "
                         f"({type(exc).__name__}: {exc}); give a new path") from None
    if _fingerprint(stored) != _fingerprint(plan.spec):
        differ = sorted(k for k in set(stored) | set(plan.spec) if stored.get(k) != plan.spec.get(k))
        raise InputError(f"store = {path!r} holds a different study (it differs in: "
                         f"{', '.join(differ)}); it is never mixed with this one: give another "
                         "store, or delete it to start again")
    arrays = {}
    for name in [*plan.coords, *plan.variables]:
        if not os.path.isfile(os.path.join(path, name, ".zarray")) or name not in group:
            raise _damaged(path, f"its array {name!r} is missing")
        arrays[name] = group[name]
    for name, (values, _) in plan.coords.items():
        try:
            same = np.array_equal(np.asarray(arrays[name][...]).astype(np.asarray(values).dtype),
                                  values)
        except Exception:
            same = False
        if not same:
            raise _damaged(path, f"its coordinate {name!r} is unreadable or not the study's")
    plan = dataclasses.replace(plan, chunks=tuple(arrays["done"].chunks))
    for name in plan.variables:
        if arrays[name].shape != plan.variable_shape(name) or \
                arrays[name].chunks != plan.variable_chunks(name):
            raise _damaged(path, f"its array {name!r} has shape {arrays[name].shape} in chunks "
                                 f"{arrays[name].chunks}, not the study's")
    todo, repaired, damaged_arrays = [], 0, set()
    for block in plan.blocks():
        damaged = []
        for name in ["done", *(v for v in plan.variables if v != "done")]:
            index = plan.chunk_index(name, block)
            try:
                ok = os.path.isfile(_chunk_file(path, name, index))
                values = arrays[name][plan.region(name, block)] if ok else None
            except Exception:        # a truncated or garbled chunk (CRC-32, decompression)
                ok = False
            if name == "done":
                if not ok or not values.all():
                    break            # not done (or its mark is lost): computed again
            elif not ok:
                damaged.append(name)
        else:
            if not damaged:
                continue             # done, every variable there
        todo.append(block)
        if damaged:                  # the block's chunks go: its points are no longer done
            for name in ["done", *damaged]:
                with contextlib.suppress(FileNotFoundError):
                    os.remove(_chunk_file(path, name, plan.chunk_index(name, block)))
            repaired += plan.block_size(block)
            damaged_arrays.update(damaged)
    return plan.chunks, todo, repaired, sorted(damaged_arrays)


def check_scheduler(scheduler):
    """The scheduler address: [scheme://]host:port, with a scheme Dask can connect by (tcp
    when none is given) and a port in 1..65535. Returns (address, scheme, host, port)."""
    from urllib.parse import urlsplit
    from distributed.comm import registry
    schemes = sorted(k for k in registry.backends if k != "inproc")
    if not isinstance(scheduler, str) or not scheduler.strip():
        raise InputError(f"scheduler = {scheduler!r:.80} is not valid: give the address of a "
                         "Dask scheduler, such as tcp://host:8786")
    address = scheduler.strip()
    scheme = address.split("://", 1)[0] if "://" in address else "tcp"
    if scheme not in schemes:
        raise InputError(f"scheduler = {scheduler!r:.80} is not valid: its scheme {scheme!r} "
                         f"is not one of {', '.join(schemes)}")
    try:
        parts = urlsplit(address if "://" in address else f"tcp://{address}")
        host, port = parts.hostname, parts.port
    except ValueError:
        host = port = None
    if not host or port is None or not 0 < port < 65536 or parts.path or parts.query:
        raise InputError(f"scheduler = {scheduler!r:.80} is not valid: give "
                         f"{scheme}://host:port with a port in 1..65535")
    return f"{scheme}://{parts.netloc}", scheme, host, port


#: the largest first message a Dask scheduler sends (its handshake is well under 1 kB)
_MAX_HANDSHAKE = 1 << 20


def _probe_scheduler(scheduler, host, port):
    """A scheduler at tcp://host:port answers at once with its handshake, a Dask message whose
    8-byte header is its length: wait for that header at most CONNECT_TIMEOUT, and check that
    it is a Dask message (an HTTP or other service answers other bytes, which Dask would take
    for a length of exabytes)."""
    deadline = time.monotonic() + CONNECT_TIMEOUT
    header = b""
    try:
        with socket.create_connection((host, port), timeout=CONNECT_TIMEOUT) as s:
            while len(header) < 8:
                s.settimeout(max(0.01, deadline - time.monotonic()))
                part = s.recv(8 - len(header))
                if not part:
                    raise ConnectionError("the connection was closed without a word")
                header += part
    except (OSError, TimeoutError) as exc:
        what = "no answer" if isinstance(exc, TimeoutError) else type(exc).__name__
        raise InputError(f"scheduler = {scheduler!r} did not answer within "
                         f"{CONNECT_TIMEOUT:g} s ({what}: {exc})") from None
    (length,) = struct.unpack("Q", header)
    if not 0 < length <= _MAX_HANDSHAKE:
        raise InputError(f"scheduler = {scheduler!r} is not a Dask scheduler: it answered "
                         f"{header!r} (a Dask scheduler answers with a message of at most "
                         f"{_MAX_HANDSHAKE} bytes)")


def max_workers(worker_kind):
    """The most workers an embedded cluster may have on this machine: 4 per core; worker
    processes also at most one per WORKER_PROCESS_BYTES of its memory."""
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    bound = 4 * (cores or 1)
    if worker_kind == "processes":
        bound = min(bound, max(1, 2 * _checks.MAX_OUTPUT_BYTES // WORKER_PROCESS_BYTES))
    return bound


def _check_workers(workers, worker_kind):
    _checks.choice("worker_kind", worker_kind, _tables.names("worker_kinds")[0])
    if workers is None:
        return None
    n = _checks.integer("workers", workers, 1)
    bound = max_workers(worker_kind)
    if n > bound:
        raise InputError(f"workers = {n} is out of range: this machine runs at most {bound} "
                         f"{'worker processes' if worker_kind == 'processes' else 'threads'} "
                         "(4 per core" + (", one per 512 MiB of memory" if worker_kind ==
                                          "processes" else "") + ")")
    return n


def _guarded(filename, lineno):
    """Line `lineno` of the file is inside a top-level `if __name__ == "__main__":` block."""
    import ast
    try:
        with open(filename, encoding="utf-8") as f:
            tree = ast.parse(f.read())
    except (OSError, SyntaxError, ValueError):
        return False

    def is_main(test):
        if not (isinstance(test, ast.Compare) and len(test.ops) == 1
                and isinstance(test.ops[0], ast.Eq)):
            return False
        sides = [test.left, test.comparators[0]]
        return (any(isinstance(x, ast.Name) and x.id == "__name__" for x in sides)
                and any(isinstance(x, ast.Constant) and x.value == "__main__" for x in sides))
    return any(isinstance(node, ast.If) and is_main(node.test)
               and node.body[0].lineno <= lineno <= node.body[-1].end_lineno
               for node in tree.body)


def _why_no_processes():
    """Why worker processes cannot start from this program, or None. Python starts them by
    spawning: each imports the program's main module again (as __mp_main__), so a main module
    read from standard input cannot be imported, and a study called outside the
    `if __name__ == "__main__":` block would start again in every worker."""
    main = sys.modules.get("__main__")
    path = getattr(main, "__file__", None)
    if getattr(getattr(main, "__spec__", None), "name", None) is None:
        if path is None:
            return None                 # python -c, interactive: nothing is imported again
        if not os.path.isfile(path):
            return f"its main program ({path}) is not a file that they can import"
    frame = sys._getframe(1)
    while frame is not None:
        if frame.f_code.co_name == "<module>" and frame.f_globals is vars(main) and \
                not _guarded(frame.f_code.co_filename, frame.f_lineno):
            return (f"the study is started at line {frame.f_lineno} of "
                    f"{frame.f_code.co_filename}, outside an `if __name__ == \"__main__\":` "
                    "block, so every worker process would start it again")
        frame = frame.f_back
    return None


@contextlib.contextmanager
def _client(client, scheduler, workers, worker_kind):
    """The Dask client of a study: the one given, one connected to `scheduler`, or an embedded
    local cluster sized to the machine (closed afterwards)."""
    import dask
    from dask.distributed import Client, LocalCluster
    if client is not None:
        yield client
        return
    if scheduler:
        address, scheme, host, port = check_scheduler(scheduler)
        if scheme == "tcp":
            _probe_scheduler(scheduler, host, port)
        try:
            c = Client(address, timeout=CONNECT_TIMEOUT)
        except (OSError, TimeoutError, ValueError) as exc:
            raise InputError(f"scheduler = {scheduler!r} did not answer within "
                             f"{CONNECT_TIMEOUT:g} s ({type(exc).__name__}: {exc})") from None
        try:
            yield c
        finally:
            c.close()
        return
    n = workers or min(os.cpu_count() or 1, max_workers(worker_kind))
    processes = worker_kind == "processes"
    why = _why_no_processes() if processes else None
    if why:
        warnings.warn(f"the study runs on {n} threads, not worker processes: {why}",
                      RuntimeWarning, stacklevel=4)
        processes = False
    options = {"preload": ["sloshdyn.studies.worker"]} if processes else {}
    with contextlib.ExitStack() as stack:
        with dask.config.set(CLUSTER_CONFIG):    # read as the servers start
            cluster = stack.enter_context(LocalCluster(
                n_workers=n if processes else 1, threads_per_worker=1 if processes else n,
                processes=processes, dashboard_address=None, silence_logs=50, **options))
        # results come straight from the workers (not through the scheduler: one copy and
        # one (de)serialisation less in the study's process per task)
        c = stack.enter_context(Client(cluster, direct_to_workers=True))
        yield c


def _put_chunk(path, data):
    """Write a chunk file under a temporary name, then rename it: a killed writer leaves no
    torn chunk (as Zarr's LocalStore writes). Not _files.atomic_path: inside a run_directory
    that defers every rename to the run's end, and a chunk must be in place before its task's
    'done' chunk."""
    tmp = f"{path}.{uuid.uuid4().hex}.partial"
    try:
        with open(tmp, "wb") as f:
            f.write(data)
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.remove(tmp)
        raise


class _Writer:
    """Writes a task's results into the store: each variable's chunk of the block, then the
    block's 'done' chunk, so a point is marked done only once its results are on disk. A
    chunk is encoded as Zarr format 2 encodes it, with the array's own codecs (the filters in
    order, then the compressor; an edge chunk padded with the fill value): the files are
    Zarr's, byte for byte, for a tenth of the CPU of zarr's asynchronous pipeline (which took
    ~8 ms of the study's process per task of 13 chunks, from the workers' cores)."""

    def __init__(self, path, plan):
        import zarr
        self.plan = plan
        self.path = path
        group = zarr.open_group(path, mode="r", zarr_format=2, use_consolidated=True)
        self.arrays = {}
        for name in plan.variables:
            array = group[name]       # its metadata as the study's reads see it (consolidated)
            fill = np.array(0 if array.fill_value is None else array.fill_value)
            self.arrays[name] = (array.dtype, array.chunks, fill.astype(array.dtype),
                                 [*array.filters, *array.compressors])

    def _put(self, name, block, values):
        dtype, chunks, fill, codecs = self.arrays[name]
        chunk = np.full(chunks, fill, dtype)
        chunk[tuple(slice(None) if s.stop is None else slice(0, s.stop - s.start)
                    for s in self.plan.region(name, block))] = values
        data = chunk
        for codec in codecs:
            data = codec.encode(data)
        _put_chunk(_chunk_file(self.path, name, self.plan.chunk_index(name, block)), data)

    def write(self, block, result):
        try:
            for name, values in result.items():
                if name != SECONDS:
                    self._put(name, block, values)
            self._put("done", block, True)
        except OSError as exc:
            raise FileError(f"store = {self.path!r}: the results of a task cannot be written "
                            f"({exc.strerror or exc}); the points stored before are kept: "
                            "rerun the same study on it to resume") from exc


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


def _load(path, plan):
    """The study's points from its store, loaded (derived variables are derived again)."""
    import xarray as xr
    ds = xr.open_zarr(path, consolidated=True, chunks=None)
    return ds[list(plan.variables)].load()


def run_plan(plan, store, *, client=None, scheduler=None, workers=None, worker_kind=None,
             progress=True, derive=None):
    """Run a study plan on Dask, storing each task's results in `store` as it finishes; return
    the whole study as an xarray Dataset (loaded). Already finished points are not recomputed;
    the returned dataset's attrs['points_computed'] counts the points this call computed,
    attrs['compute_seconds'] the time its tasks spent computing (summed over workers) and
    attrs['points_repaired'] the finished points computed again because their stored data were
    missing or damaged (attrs['repaired'] says which variables). derive(dataset), if given,
    adds the variables derived from all the points (basins' attractor list, the fragility
    fit): they join the store too, derived again by every rerun."""
    require("studies", "dask.distributed", "xarray", "zarr")
    path = _check_store(store)
    if worker_kind is None:
        worker_kind = WORKER_KIND
    if client is None and scheduler:
        check_scheduler(scheduler)
    elif client is None:
        workers = _check_workers(workers, worker_kind)
    check_size(plan)
    exists = os.path.exists(path)
    todo, repaired, damaged = None, 0, []
    if exists:    # the store's tasks win: its chunks are its tasks
        chunks, todo, repaired, damaged = _open_study(plan, path)
        plan = dataclasses.replace(plan, chunks=chunks)
    computed = 0
    compute_seconds = 0.0
    loading = None
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
                remaining = sum(plan.block_size(b) for b in todo)
                if progress:
                    from tqdm.auto import tqdm
                    total = int(np.prod(plan.shape))
                    bar = tqdm(total=total, initial=total - remaining,
                               desc=plan.kind.replace("_", " "), unit="point", smoothing=0.1)
                writer = _Writer(path, plan)
                futures = {}
                todo = plan.longest_first(todo)
                for k, block in enumerate(todo):
                    function, args = plan.task(block)
                    futures[c.submit(function, *args, pure=False,
                                     priority=len(todo) - k)] = block
                try:
                    with _remembered_interrupts() as check_interrupts:
                        for future in as_completed(futures):
                            block = futures.pop(future)
                            result = future.result()
                            compute_seconds += result.get(SECONDS, 0.0)
                            writer.write(block, result)
                            computed += plan.block_size(block)
                            if bar:
                                bar.update(plan.block_size(block))
                            check_interrupts()
                        check_interrupts()
                finally:
                    for future in futures:
                        future.cancel()
                # every task is stored: the study is read while the cluster closes
                reader = concurrent.futures.ThreadPoolExecutor(1)
                loading = reader.submit(_load, path, plan)
                reader.shutdown(wait=False)
        except KeyboardInterrupt as exc:    # Ctrl-C, or SIGTERM as sloshdyn-py raises it
            raise type(exc)(f"study interrupted: {computed} points stored in {path} this run; "
                            "rerun the same study on it to resume") from None
        finally:
            if bar:
                bar.close()
    ds = loading.result() if loading else _load(path, plan)
    ds.attrs["points_computed"] = computed
    ds.attrs["compute_seconds"] = compute_seconds     #: inside the tasks, summed over workers
    ds.attrs["points_repaired"] = repaired
    ds.attrs["repaired"] = ", ".join(damaged)
    ds.attrs["store"] = path
    if derive is not None:
        points = set(ds.data_vars)
        ds = derive(ds)
        _store_derived(ds, [name for name in ds.data_vars if name not in points])
    return ds


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



def _store_derived(ds, names):
    """Write the variables `names` of a study's dataset, derived from its points once they are
    all in (basins' attractor list, the fragility fit), into the study's store beside them."""
    import xarray as xr
    kept = {k: v for k, v in ds.attrs.items() if k not in RUN_ATTRS}   # the store's own
    try:
        xr.Dataset({name: ds[name] for name in names}, attrs=kept).to_zarr(
            ds.attrs["store"], mode="a", consolidated=True)
    except OSError as exc:
        raise FileError(f"store = {ds.attrs['store']!r}: {', '.join(names)} cannot be written "
                        f"({exc.strerror or exc}); its points are complete: rerun the same "
                        "study on it to write them") from exc
