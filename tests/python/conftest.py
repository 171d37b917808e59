import csv
import os
import pathlib
import signal
import subprocess
import sysconfig

import numpy as np
import pytest

import sloshdyn

ROOT = pathlib.Path(__file__).resolve().parents[2]

# A shell without job control starts a background command (`cmd &`) with SIGINT ignored, and an
# ignored signal stays ignored in every child: the Ctrl-C tests (test_faults, test_studies,
# test_reliability_core) would then test nothing but that. They need the terminal's default,
# which a Python handler gives every child (a handled signal is reset to the default on exec).
if signal.getsignal(signal.SIGINT) == signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)
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


def ec8_impulsive(radius, depth, terms=20000):
    """EN 1998-4 Annex A.2.1's impulsive series (rigid circular tank), by scipy.special: with
    nu_n = (2n + 1) pi/2, gamma = H/R and a_n = I1(nu_n/gamma)/(nu_n^3 I1'(nu_n/gamma)),
    m_i/m = 2 gamma sum a_n; the heights of the resultant of its wall pressure
    p ~ cos(nu_n z/H) I1(nu_n r/(R gamma)), excluding the base pressure
    h_i/H = sum a_n (1 - (-1)^n/nu_n)/sum a_n, and including it
    h_i' = h_i + R sum (-1)^n I2(nu_n/gamma)/(nu_n^3 I1'(nu_n/gamma))/sum a_n.
    Returns (m_i/m, h_i, h_i')."""
    from scipy.special import ive, ivp
    gamma = depth / radius
    n = np.arange(terms)
    nu = (2 * n + 1) * np.pi / 2
    x = nu / gamma
    # I1' by scipy (ivp), scaled by e^-x like ive: ivp(1, x) e^-x without overflow
    d1 = ive(0, x) - ive(1, x) / x
    assert np.allclose(d1[x < 50] * np.exp(x[x < 50]), ivp(1, x[x < 50]), rtol=1e-12)
    a = ive(1, x) / (nu**3 * d1)
    h_i = depth * np.sum(a * (1 - (-1.0)**n / nu)) / np.sum(a)
    h_ip = h_i + radius * np.sum((-1.0)**n * ive(2, x) / (nu**3 * d1)) / np.sum(a)
    return 2 * gamma * np.sum(a), h_i, h_ip
