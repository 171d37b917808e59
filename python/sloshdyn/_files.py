"""Writing result files so that nothing is ever half-written, as the executable does: each file
is written under a temporary name unique to the writer (dir/.NAME.PID-RANDOM.partial.EXT, so
two runs sharing a directory never write into each other's files) and renamed into place when
complete. Inside `run_directory(dir)` every file of the run waits under its temporary name and
all are renamed together when the run succeeds (a run's files are all there or none is); a
failure or an interruption removes the temporaries. Every OSError becomes a FileError naming the
file."""

from __future__ import annotations

import contextlib
import contextvars
import csv
import os
import uuid

from ._errors import FileError

#: the run whose files wait for its commit (None: each file is renamed when complete)
_RUN = contextvars.ContextVar("sloshdyn_run", default=None)


def temporary_name(path):
    """A name beside `path` that no other writer uses; it keeps the extension (matplotlib
    chooses the format by it)."""
    directory, name = os.path.split(os.path.abspath(path))
    base, ext = os.path.splitext(name)
    return os.path.join(directory, f".{base}.{os.getpid()}-{uuid.uuid4().hex[:12]}.partial{ext}")


@contextlib.contextmanager
def file_error(path, action="write"):
    """OSError inside the block -> FileError naming the file and the cause."""
    try:
        yield
    except FileError:
        raise
    except OSError as exc:
        raise FileError(f"cannot {action} {os.fspath(path)}: {exc.strerror or exc}") from exc


def _remove(paths):
    for tmp in paths:
        with contextlib.suppress(OSError):
            os.remove(tmp)


def _make_directory(directory):
    with file_error(directory, "create the directory"):
        os.makedirs(directory, exist_ok=True)


@contextlib.contextmanager
def atomic_path(path):
    """Yield a temporary path beside `path` for the block to write; on success rename it to
    `path` (or, inside run_directory, leave it to the run's commit); on failure or interruption
    remove it."""
    path = os.path.abspath(os.fspath(path))
    _make_directory(os.path.dirname(path))
    tmp = temporary_name(path)
    run = _RUN.get()
    try:
        with file_error(path):
            yield tmp
            if not os.path.exists(tmp):
                raise FileError(f"cannot write {path}: nothing was written")
            if run is None:
                os.replace(tmp, path)
            else:
                run.append((tmp, path))
    except BaseException:
        _remove([tmp])
        raise


@contextlib.contextmanager
def run_directory(directory):
    """The files written inside the block (atomic_path, write_csv, save_figure) are renamed
    into place together when the block succeeds; on failure or interruption none is."""
    _make_directory(os.fspath(directory))
    pending = []
    token = _RUN.set(pending)
    try:
        yield
    except BaseException:
        _remove(tmp for tmp, _ in pending)
        raise
    finally:
        _RUN.reset(token)
    for k, (tmp, path) in enumerate(pending):
        try:
            with file_error(path, "rename into place"):
                os.replace(tmp, path)
        except BaseException:
            _remove(tmp for tmp, _ in pending[k:])
            raise


def write_csv(path, columns: dict):
    """A CSV file: a header line, one column per quantity, full precision."""
    names = list(columns)
    length = len(columns[names[0]]) if names else 0
    with atomic_path(path) as tmp, open(tmp, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(names)
        for i in range(length):
            writer.writerow([_text(columns[n][i]) for n in names])


def write_text(path, text):
    """A text file, written whole."""
    with atomic_path(path) as tmp, open(tmp, "w") as f:
        f.write(text)


def _text(value):
    if isinstance(value, str):
        return value
    return repr(float(value))


def save_figure(fig, path):
    import matplotlib.pyplot as plt    # the plot extra: only a caller with a figure gets here
    try:
        with atomic_path(path) as tmp:
            fig.savefig(tmp, dpi=110)
    finally:
        plt.close(fig)
