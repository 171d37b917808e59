"""Writing result files so that nothing is ever half-written: each file is written under a
temporary name beside its final one and renamed into place when complete."""

from __future__ import annotations

import contextlib
import csv
import os


@contextlib.contextmanager
def atomic_path(path):
    """Yield a temporary path beside `path`; rename it to `path` if the block succeeds,
    remove it if the block fails or is interrupted."""
    path = os.fspath(path)
    directory, name = os.path.split(os.path.abspath(path))
    os.makedirs(directory, exist_ok=True)
    base, ext = os.path.splitext(name)
    tmp = os.path.join(directory, f".{base}.partial{ext}")   # keeps the extension for matplotlib
    try:
        yield tmp
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def write_csv(path, columns: dict):
    """A CSV file: a header line, one column per quantity, full precision."""
    names = list(columns)
    length = len(columns[names[0]]) if names else 0
    with atomic_path(path) as tmp, open(tmp, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(names)
        for i in range(length):
            writer.writerow([_text(columns[n][i]) for n in names])


def _text(value):
    if isinstance(value, str):
        return value
    return repr(float(value))


def save_figure(fig, path):
    import matplotlib.pyplot as plt
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=110)
    plt.close(fig)
