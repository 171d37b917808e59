"""Writing result files so that nothing is ever half-written, as the executable does, by the
run-directory rule of docs/failure.md ("An output directory belongs to a run"):

- every file is created new (O_EXCL, never through a symbolic link) under a temporary name
  unique to its writer (dir/.NAME.PID-RANDOM.partial.EXT) and renamed into place when
  complete (`atomic_path`);
- `run_directory(dir)` gives a run a new directory of its own beside dir
  (PARENT/.NAME.run-PID-RANDOM); when the run succeeds it gets its marker (.sloshdyn-run, the
  names of its files) and is swapped into dir's place whole, the previous run's directory
  removed; a failure or an interruption removes it. A dir that holds anything no run wrote (not
  listed by its marker, or not a regular file) is refused by name (FileError), so that an
  input can never be in it. The core does the same for the executable
  (fortran/app/sloshdyn_run_directory.c, with the same marker).

Every OSError becomes a FileError naming the file."""

from __future__ import annotations

import contextlib
import csv
import errno
import os
import signal
import tempfile
import threading
import uuid
from pathlib import Path

from ._errors import FileError

#: the marker of a run's directory and its first line (the core's, sloshdyn_files.f90): the
#: names of the run's files follow, one a line
MARKER = ".sloshdyn-run"
MARKER_HEADER = ("sloshdyn run directory: every file listed below was written by one run of "
                 "sloshdyn, and the next run into this directory replaces it as a whole\n")


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


def create_new(path):
    """Create `path` as a new empty file: never an existing file, never through a symbolic
    link."""
    os.close(os.open(path, os.O_CREAT | os.O_EXCL | os.O_WRONLY | os.O_NOFOLLOW | os.O_CLOEXEC,
                     0o644))


@contextlib.contextmanager
def atomic_path(path):
    """Yield a new temporary file beside `path` (created new, unique to this writer) for the
    block to write; on success rename it to `path`; on failure or interruption remove it."""
    path = os.path.abspath(os.fspath(path))
    _make_directory(os.path.dirname(path))
    tmp = temporary_name(path)
    try:
        with file_error(path):
            create_new(tmp)
            yield tmp
            if not os.path.exists(tmp):
                raise FileError(f"cannot write {path}: nothing was written")
            os.replace(tmp, path)
    except BaseException:
        _remove([tmp])
        raise


def _marker(directory):
    """The names a run's marker in `directory` lists, or None (no marker of sloshdyn's)."""
    try:
        fd = os.open(directory / MARKER, os.O_RDONLY | os.O_NOFOLLOW)
    except OSError:
        return None
    with open(fd, encoding="utf-8", errors="surrogateescape") as f:
        text = f.read(1 << 20)
    return set(text[len(MARKER_HEADER):].splitlines()) if text.startswith(MARKER_HEADER) \
        else None


def foreign_entry(directory):
    """The first entry of `directory` that no run of sloshdyn wrote (not the marker, and not a
    regular file that the marker lists: a symbolic link is none), or None: an empty or missing
    directory, or one a run wrote, may be replaced by a run."""
    directory = Path(directory)
    try:
        names = sorted(os.listdir(directory))
    except FileNotFoundError:
        return None
    listed = _marker(directory)
    for name in names:
        if listed is not None and name == MARKER:
            continue
        if listed is None or name not in listed or not (directory / name).is_file() \
                or (directory / name).is_symlink():
            return name
    return None


def check_output_directory(out):
    """Refuse (FileError) an output directory a run may not take: not a directory (a symbolic
    link included), or one holding an entry that no run wrote; the core's message."""
    shown, out = out, Path(out)
    if os.path.basename(os.fspath(shown).rstrip("/")) in ("", ".", ".."):
        raise FileError(f"cannot write into '{shown}': a run replaces its output directory "
                        "whole, so it must be named (e.g. 'out'), not . or .. or /")
    if out.is_symlink() or (out.exists() and not out.is_dir()):
        raise FileError(f"cannot write into '{out}': it is not a directory"
                        + (" but a symbolic link" if out.is_symlink() else ""))
    try:
        foreign = foreign_entry(out)
    except OSError as exc:
        raise FileError(f"cannot read the output directory '{out}': {exc.strerror or exc}") \
            from exc
    if foreign is not None:
        shown = os.fsencode(foreign).decode("utf-8", "backslashreplace")
        raise FileError(f"cannot write into '{out}': it holds '{shown}', which no sloshdyn run "
                        "wrote (an output directory belongs to a run and is replaced whole: "
                        f"give a new directory, or one a run wrote; its {MARKER} lists the "
                        "run's files)")


def remove_run_directory(directory, every=False):
    """Remove a run's directory: the regular files its marker lists (every file when `every`:
    the run's own new directory), the marker and the directory; anything else is left, and the
    directory with it (nothing that no run wrote is ever removed)."""
    directory = Path(directory)
    listed = _marker(directory) or set()
    with contextlib.suppress(OSError):
        for name in os.listdir(directory):
            path = directory / name
            ours = every or name == MARKER or (name in listed and path.is_file()
                                                and not path.is_symlink())
            if ours and (path.is_symlink() or not path.is_dir()):
                _remove([path])
        os.rmdir(directory)


def _beside(out, what):
    return tempfile.mkdtemp(prefix=f".{out.name}.{what}-{os.getpid()}-", dir=out.parent)


def swap_into_place(staging, out):
    """Put the run's directory `staging` (complete) in the place of `out` with its marker: a
    rename when out is missing or empty; otherwise out (checked again: a run's) moves to a new
    hidden directory beside it, staging takes its place and the previous run's directory is
    removed. A run that takes the place in between is replaced in turn: two runs at once
    leave one whole run. Ctrl-C and SIGTERM wait until it is done."""
    staging, out = Path(staging), Path(out)
    names = sorted(p.name for p in staging.iterdir() if p.is_file())
    write_text(staging / MARKER, MARKER_HEADER + "".join(f"{n}\n" for n in names))
    os.chmod(staging, 0o755)
    with _signals_held():
        for _ in range(1000):
            try:
                os.rename(staging, out)         # no directory there, or an empty one
                return
            except OSError as exc:
                if exc.errno not in (errno.EEXIST, errno.ENOTEMPTY):
                    raise
            check_output_directory(out)
            previous = _beside(out, "previous")
            try:
                os.rename(out, previous)        # onto the empty directory of that name
            except FileNotFoundError:           # another run moved it: again
                os.rmdir(previous)
                continue
            try:
                os.rename(staging, out)
                return
            except OSError as exc:
                if exc.errno not in (errno.EEXIST, errno.ENOTEMPTY):
                    raise
            finally:
                remove_run_directory(previous)
        raise FileError(f"cannot replace {out}: other runs kept taking its place")


@contextlib.contextmanager
def _signals_held():
    """Ctrl-C and SIGTERM held back while the directories are swapped, so that an
    interruption never leaves neither in place. One that came meanwhile is delivered after a
    failed swap; after a swap that succeeded the run is complete, and it is dropped (exit 0
    with every file in place, as the executable, whose signals only cancel what is not done)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    held = {signal.SIGINT, signal.SIGTERM}
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, held)
    try:
        yield
        while signal.sigtimedwait(held, 0) is not None:      # the run is complete
            pass
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


class RunDirectory:
    """The run's own new directory (`path`), swapped into the place of `out` when the run
    succeeds; keep_on_failure(): a failed run's files (the rows a sweep finished) are swapped
    in too, when there are any."""

    def __init__(self, out, path):
        self.out, self.path, self.keep = out, path, False

    def keep_on_failure(self):
        self.keep = True


@contextlib.contextmanager
def run_directory(out):
    """A run's files into `out`, all at once or none (the rule above): yields a RunDirectory
    whose `path` the block writes into; out is checked before the block runs."""
    shown = os.fspath(out).rstrip("/") or "/"          # named as given, as the core does
    check_output_directory(shown)
    out = Path(os.path.abspath(os.fspath(out)))
    try:
        out.parent.mkdir(parents=True, exist_ok=True)
        run = RunDirectory(out, Path(_beside(out, "run")))
    except OSError as exc:
        raise FileError(f"cannot write into '{shown}': cannot create its new directory in "
                        f"'{os.path.dirname(shown) or '.'}': {exc.strerror or exc}") from exc
    try:
        yield run
    except BaseException as exc:
        if run.keep and any(run.path.iterdir()):
            with file_error(out, "replace"):
                swap_into_place(run.path, out)
        else:
            remove_run_directory(run.path, every=True)
        if isinstance(exc, FileError) and str(run.path) in str(exc):   # name the files by out
            raise FileError(str(exc).replace(str(run.path), str(out)), exc.status) from exc
        raise
    try:
        with file_error(out, "replace"):
            swap_into_place(run.path, out)
    except BaseException:
        remove_run_directory(run.path, every=True)
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
