"""The raw arrays of a namelist input file as the executable's reader returns them through the
bridge (read and validated by the Fortran reader, so both front doors share its rules and
messages): `read_arrays` and a record's samples. sloshdyn.namelist decodes them into settings
objects; Parameters.from_namelist takes its own two. The bottom of the package: it imports no
value type and no analysis."""

from __future__ import annotations

import os
from typing import NamedTuple

import numpy as np

from . import _checks, _core
from ._cancel import app_call
from ._errors import check_status

_bridge = _core.sloshdyn_bridge_input


class InputArrays(NamedTuple):
    """What the bridge's read_input returns, by name, in its order (status and message
    checked)."""

    rpar: np.ndarray
    ipar: np.ndarray
    analysis: int
    values: np.ndarray
    directory: bytes
    has_tank: int
    tank: np.ndarray
    has_ground: int
    ground: np.ndarray
    n_samples: int
    seismic: np.ndarray
    integration: np.ndarray
    steady: np.ndarray
    response: np.ndarray
    lyapunov: np.ndarray
    simulation: np.ndarray
    sweep: np.ndarray
    response_range: np.ndarray
    chart: np.ndarray
    chart_range: np.ndarray
    study: np.ndarray
    store: bytes
    figure: bytes
    scheduler: bytes
    study_records: bytes
    planar: int
    spatial: np.ndarray
    has_ground_y: int
    ground_y: np.ndarray
    n_samples_y: int
    has_design: int
    design: np.ndarray
    tank_structure: np.ndarray


def read_arrays(path) -> InputArrays:
    """Read and validate a namelist input file with the executable's reader."""
    path = _checks.path("path", path)
    *arrays, status, message = app_call(_bridge.read_input, os.fsencode(path))
    check_status(status, message)
    return InputArrays(*arrays)


def record_samples(path, component, n):
    """The n samples [m/s^2] of the input file's record of a component (1: &ground_motion
    record, 2: record_y), scaled as the file says; none for n = 0 (harmonic motion)."""
    if n == 0:
        return np.zeros(0)
    samples, status, message = app_call(_bridge.input_record,
                                        os.fsencode(_checks.path("path", path)), component, n)
    check_status(status, message)
    return samples.copy()
