"""A study's Zarr store (format 2): its chunking, fixed when it is created; each finished
chunk's identity, a checksum in its `done` chunk; its creation (whole or not at all), the
check of an existing store against the study (resume, repair or refusal), the writes of a
task's chunks and the reading of the finished study."""

from __future__ import annotations

import contextlib
import errno
import hashlib
import json
import math
import os
import shutil
import time
import uuid

import numpy as np

from .._errors import FileError, InputError

#: the store layout of this engine, part of every study's spec: the `done` chunks hold the
#: chunk's identity (stores of engines before it are another study, never mixed)
STORE_FORMAT = 2
#: the most chunks a study is cut into: a task is at least one chunk, each chunk a file per
#: variable, and the client keeps a mark per chunk
MAX_CHUNKS = 2**16
#: points per chunk unless a task of fewer is asked for: the engine's smallest task
CHUNK_POINTS = 8
#: the compressor of every array (Zarr format 2's default, written out so that the store is
#: the same whatever zarr's defaults become)
COMPRESSOR = {"id": "blosc", "cname": "lz4", "clevel": 5, "shuffle": 1, "blocksize": 0}


def fingerprint(spec):
    return hashlib.sha256(json.dumps(spec, sort_keys=True).encode()).hexdigest()


def check_path(store):
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
    existing = os.path.dirname(path)
    while not os.path.exists(existing):
        existing = os.path.dirname(existing)
    if not os.path.isdir(existing) or not os.access(existing, os.W_OK | os.X_OK):
        raise InputError(f"store = {os.fspath(store)!r} cannot be created: {existing!r} is not "
                         "a writable directory")
    return path


def chunk_shape(plan):
    """The chunks of a new store: CHUNK_POINTS points (fewer if the plan asks for smaller
    tasks), more where the grid would need more than MAX_CHUNKS; a points_per_task that would
    cut the study into more than MAX_CHUNKS tasks is refused, naming the smallest allowed."""
    n = math.prod(plan.shape)
    fewest = math.ceil(n / MAX_CHUNKS)
    if plan.points_per_task is not None and plan.points_per_task < fewest:
        raise InputError(f"points_per_task = {plan.points_per_task} is out of range: it would "
                         f"cut the study of {n} points into "
                         f"{math.ceil(n / plan.points_per_task)} tasks, more than the "
                         f"{MAX_CHUNKS} a study may have (each task is a file per variable "
                         f"in the store and a mark in the client): give points_per_task >= "
                         f"{fewest}, or leave it to the engine")
    chunks = tuple(plan.chunking(max(fewest, min(plan.points_per_task or CHUNK_POINTS,
                                                 CHUNK_POINTS))))
    count = math.prod(math.ceil(s / c) for s, c in zip(plan.shape, chunks))
    if count > MAX_CHUNKS:
        raise InputError(f"the study of {n} points cannot be cut into at most {MAX_CHUNKS} "
                         f"chunks of its tasks' shape ({count} chunks of {chunks}): split it "
                         "into smaller studies")
    return chunks


def chunk_file(path, name, index):
    """The file of chunk `index` of array `name` (Zarr format 2, '.' separated keys)."""
    return os.path.join(path, name, ".".join(str(i) for i in index))


class Codec:
    """Encodes and decodes the chunks of one array as Zarr format 2 does, with the array's own
    codecs (the filters in order, then the compressor; an edge chunk padded with the fill
    value): the engine's files are Zarr's, byte for byte, for a tenth of the CPU of zarr's
    asynchronous pipeline (~8 ms of the study's process per task of 13 chunks)."""

    def __init__(self, array):
        self.dtype = array.dtype
        self.text = self.dtype.kind in "OT"
        self.chunks = array.chunks
        fill = "" if self.text else (0 if array.fill_value is None else array.fill_value)
        self.fill = np.array(fill, dtype=object if self.text else None)
        if not self.text:
            self.fill = self.fill.astype(self.dtype)
        self.codecs = [*array.filters, *array.compressors]

    def empty(self):
        return np.full(self.chunks, self.fill, dtype=object if self.text else self.dtype)

    def encode(self, chunk):
        data = chunk
        for codec in self.codecs:
            data = codec.encode(data)
        return data

    def decode(self, data):
        for codec in reversed(self.codecs):
            data = codec.decode(data)
        if self.text:
            return np.asarray(data, dtype=object).reshape(self.chunks)
        return np.frombuffer(data, dtype=self.dtype).reshape(self.chunks)


def _bytes(values):
    """The bytes of a chunk's values that its checksum covers (text: UTF-8, NUL separated)."""
    values = np.asarray(values)
    if values.dtype.kind in "OT":
        return "\0".join(str(v) for v in values.ravel()).encode("utf-8", "surrogatepass")
    return np.ascontiguousarray(values).tobytes()


def checksum(study, plan, chunk, values):
    """A chunk's identity: the first 8 bytes of SHA-256 over the study's fingerprint, the
    chunk's place (its slices and the coordinates there) and every variable's values in it,
    as a nonzero uint64 (0 marks a chunk not done). A chunk copied to another block's place,
    or from another study, fails it."""
    h = hashlib.sha256(study.encode())
    for d, s in zip(plan.dims, chunk):
        h.update(f"{d}[{s.start}:{s.stop}]".encode())
        h.update(_bytes(plan.coords[d][0][s]))
    for name in sorted(values):
        h.update(name.encode())
        h.update(_bytes(values[name]))
    return int.from_bytes(h.digest()[:8], "little") or 1


def _remove_tree(path):
    """Remove a directory that writes still under way may fill again."""
    for _ in range(100):
        shutil.rmtree(path, ignore_errors=True)
        time.sleep(0.05)
        if not os.path.exists(path):
            time.sleep(0.2)
            if not os.path.exists(path):
                return


def _write_template(plan, path):
    """The empty study: the coordinates with their values, every variable's metadata (its
    chunks, a CRC-32 in every chunk so that a damaged chunk is found on resuming, NaN fill for
    reals, text in variable-length UTF-8) and no chunk of data, in xarray's layout; then the
    consolidated metadata."""
    import numcodecs
    import zarr
    compressor = numcodecs.get_codec(COMPRESSOR)
    group = zarr.open_group(path, mode="w-", zarr_format=2, attributes=plan.attrs)
    for d, (values, attrs) in plan.coords.items():
        values = np.asarray(values)
        group.create_array(d, shape=values.shape, chunks=values.shape, dtype=values.dtype,
                           filters=None, compressors=compressor,
                           attributes={**attrs, "_ARRAY_DIMENSIONS": [d]})[...] = values
    for name, var in plan.variables.items():
        text = var.dtype == "str"
        group.create_array(
            name, shape=plan.variable_shape(name), chunks=plan.variable_chunks(name),
            dtype=str if text else var.dtype,
            fill_value=np.nan if not text and np.dtype(var.dtype).kind == "f" else None,
            filters=[numcodecs.VLenUTF8(), numcodecs.CRC32()] if text else [numcodecs.CRC32()],
            compressors=compressor, attributes={**var.attrs, "_ARRAY_DIMENSIONS": list(var.dims)})
    zarr.consolidate_metadata(path, zarr_format=2)


def create(plan, path):
    """Write the empty study (every chunk not done) under a temporary name, then rename it: a
    store either exists whole or not at all. Returns False when another study created the
    same store meanwhile (the caller opens it as an existing store)."""
    tmp = f"{path}.creating-{uuid.uuid4().hex[:8]}"
    try:
        _write_template(plan, tmp)
        os.rename(tmp, path)
        return True
    except OSError as exc:
        if exc.errno in (errno.EEXIST, errno.ENOTEMPTY) and os.path.isdir(path):
            return False                  # created by another study started at the same time
        raise FileError(f"store = {path!r} cannot be written: {exc.strerror or exc}; nothing "
                        "of it is left") from exc
    finally:
        if os.path.exists(tmp):
            _remove_tree(tmp)


def _damaged(path, what):
    return InputError(f"store = {path!r} is damaged: {what}; it cannot be repaired by "
                      "recomputing points: give another store, or delete it to start again")


def open_group(path):
    import zarr
    return zarr.open_group(path, mode="r", zarr_format=2, use_consolidated=True)


def check_existing(plan, path):
    """An existing store checked against the plan: the same study (else refused, naming what
    differs), every array of the plan there with its shape, coordinates equal to the plan's
    (else refused as damaged). Returns the store's chunk shape."""
    if not os.path.isfile(os.path.join(path, ".zmetadata")):
        raise _damaged(path, "its consolidated metadata .zmetadata is missing")
    try:
        group = open_group(path)
        stored = json.loads(group.attrs["study_spec"])
    except Exception as exc:
        raise InputError(f"store = {path!r} exists but is not a sloshdyn study store "
                         f"({type(exc).__name__}: {exc}); give a new path") from None
    if fingerprint(stored) != fingerprint(plan.spec):
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
    chunks = tuple(arrays["done"].chunks)
    for name in plan.variables:
        along = dict(zip(plan.dims, chunks))
        expected = tuple(along.get(d, len(plan.coords[d][0])) for d in plan.variables[name].dims)
        if arrays[name].shape != plan.variable_shape(name) or arrays[name].chunks != expected:
            raise _damaged(path, f"its array {name!r} has shape {arrays[name].shape} in chunks "
                                 f"{arrays[name].chunks}, not the study's")
    return chunks


class Store:
    """The chunks of a study's store: written a task's block at a time (each variable's
    chunks, then each chunk's `done` checksum), and verified on resuming."""

    def __init__(self, plan, path):
        self.plan = plan
        self.path = path
        self.study = fingerprint(plan.spec)
        group = open_group(path)      # the metadata as the study's reads see it (consolidated)
        self.codecs = {name: Codec(group[name]) for name in plan.variables}

    def _chunk_values(self, name, chunk, block_values, block):
        """A variable's values over `chunk`, cut from its values over `block`."""
        region = self.plan.region(name, chunk)
        offset = dict(zip(self.plan.dims, block))
        where = dict(zip(self.plan.dims, region))
        cut = tuple(slice(where[d].start - offset[d].start, where[d].stop - offset[d].start)
                    if d in where else slice(None) for d in self.plan.variables[name].dims)
        return block_values[cut]

    def _put(self, name, chunk, values):
        """Write a variable's chunk; returns its values as stored (in the array's dtype)."""
        codec = self.codecs[name]
        data = codec.empty()
        inside = tuple(slice(0, n) for n in np.shape(values))
        data[inside] = values
        put_chunk(chunk_file(self.path, name, self.plan.chunk_index(name, chunk)),
                  codec.encode(data))
        return data[inside]

    def write(self, block, result):
        """A task's results over `block` (a whole number of chunks): every chunk's variables,
        then its `done` chunk, the checksum of what was written, so a point is marked done
        only once its results are on disk."""
        missing = set(self.codecs) - {"done"} - set(result)
        if missing:
            raise RuntimeError(f"a task of the study left out {sorted(missing)} (a defect)")
        try:
            for chunk in self.plan.chunks_of(block):
                written = {name: self._put(name, chunk, self._chunk_values(
                    name, chunk, np.asarray(values), block))
                    for name, values in result.items() if name in self.codecs}
                mark = checksum(self.study, self.plan, chunk, written)
                self._put("done", chunk, np.full([s.stop - s.start for s in chunk], mark,
                                                 np.uint64))
        except OSError as exc:
            raise FileError(f"store = {self.path!r}: the results of a task cannot be written "
                            f"({exc.strerror or exc}); the points stored before are kept: "
                            "rerun the same study on it to resume") from exc

    def _read(self, name, chunk):
        """A variable's stored values over `chunk`, or None if missing or damaged (a CRC-32
        or decompression failure)."""
        try:
            with open(chunk_file(self.path, name, self.plan.chunk_index(name, chunk)), "rb") as f:
                data = self.codecs[name].decode(f.read())
        except Exception:
            return None
        return data[tuple(slice(None) if s.stop is None else slice(0, s.stop - s.start)
                          for s in self.plan.region(name, chunk))]

    def verify(self):
        """The chunks to compute: a mask over the chunk grid, and the chunks whose done mark
        was there but whose data were missing, damaged or not theirs (a chunk of another
        block or study): those chunks' files are removed, so they are computed again.
        Returns (todo, repaired_points, damaged_variables)."""
        todo = np.ones(self.plan.chunk_grid, dtype=bool)
        repaired, damaged = 0, set()
        for index, chunk in self.plan.chunk_blocks():
            done = self._read("done", chunk)
            if done is None or not done.size or not np.all(done == done.flat[0]) or \
                    done.flat[0] == 0:
                continue                      # not done (or its mark is lost): computed again
            values = {name: self._read(name, chunk) for name in self.codecs if name != "done"}
            missing = sorted(name for name, v in values.items() if v is None)
            if not missing and checksum(self.study, self.plan, chunk, values) == done.flat[0]:
                todo[index] = False
                continue
            damaged.update(missing or ["a chunk not of its place or study"])
            for name in self.codecs:
                with contextlib.suppress(FileNotFoundError):
                    os.remove(chunk_file(self.path, name, self.plan.chunk_index(name, chunk)))
            repaired += self.plan.block_size(chunk)
        return todo, repaired, sorted(damaged)


def put_chunk(path, data):
    """Write a chunk file under a temporary name unique to the writer, created new (never an
    existing file, never through a symbolic link), then rename it: a killed writer leaves no
    torn chunk (as Zarr's LocalStore writes), and a chunk is in place before its 'done'
    chunk. A study's store is no run directory (a rerun resumes it): the rule of
    docs/failure.md's output directories does not apply, its files are created new all the
    same."""
    tmp = f"{path}.{uuid.uuid4().hex}.partial"
    try:
        with open(tmp, "xb") as f:
            f.write(data)
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.remove(tmp)
        raise


def load(path, plan):
    """The study's points from its store, loaded (derived variables are derived again)."""
    import xarray as xr
    ds = xr.open_zarr(path, consolidated=True, chunks=None)
    return ds[list(plan.variables)].load()


def store_derived(ds, names, run_attrs):
    """Write the variables `names` of a study's dataset, derived from its points once they are
    all in (basins' attractor list, the fragility fit), into the study's store beside them."""
    import xarray as xr
    kept = {k: v for k, v in ds.attrs.items() if k not in run_attrs}   # the store's own
    try:
        xr.Dataset({name: ds[name] for name in names}, attrs=kept).to_zarr(
            ds.attrs["store"], mode="a", consolidated=True)
    except OSError as exc:
        raise FileError(f"store = {ds.attrs['store']!r}: {', '.join(names)} cannot be written "
                        f"({exc.strerror or exc}); its points are complete: rerun the same "
                        "study on it to write them") from exc
