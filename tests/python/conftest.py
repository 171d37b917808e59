import csv
import os
import pathlib
import subprocess
import sysconfig

import pytest

import sloshdyn

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "data" / "examples"


@pytest.fixture(scope="session")
def exe():
    """The installed `sloshdyn` executable (pip installs it beside the interpreter)."""
    path = pathlib.Path(sysconfig.get_path("scripts")) / "sloshdyn"
    assert path.exists(), f"sloshdyn executable not installed at {path}"
    return str(path)


@pytest.fixture
def fig12():
    """The paper's Fig 12 / Fig 14 parameters, as the figures use them (beta, delta defaults)."""
    from sloshdyn.figures import FIG12
    return FIG12


def run(exe, nml_path, cwd):
    return subprocess.run([exe, str(nml_path)], cwd=cwd, capture_output=True, text=True,
                          timeout=60)


def read_csv(path):
    """Rows of a result CSV as dicts of floats (strings kept where not numeric)."""
    rows = []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            parsed = {}
            for key, value in row.items():
                try:
                    parsed[key] = float(value)
                except ValueError:
                    parsed[key] = value.strip()
            rows.append(parsed)
    return rows


def write(tmp_path, text, name="input.nml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def directory_tree(path):
    return sorted(str(p.relative_to(path)) for p in pathlib.Path(path).rglob("*"))


os.environ.setdefault("MPLBACKEND", "Agg")
