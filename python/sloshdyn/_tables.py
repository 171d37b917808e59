"""Names and defaults that the Fortran core defines once (sloshdyn_tables, sloshdyn_layouts, the
option types): column names of result tables, the field names of every flat array that crosses
the bridge (its layout), the codes of every enumerated option, and the defaults of every
settings type. Python takes them from the bridge instead of keeping copies, and builds and
decodes the arrays by name (pack, unpack)."""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from . import _core
from ._errors import check_status

_bridge = _core.sloshdyn_bridge_tables


def _text(raw):
    return (raw.decode() if isinstance(raw, bytes) else str(raw)).strip()


@lru_cache(maxsize=None)
def names(list_name):
    """The names of a list and the code of the first one: the codes of an enumerated option
    (CODE_LISTS), 'table:NAME' for a result table's columns, 'formats:NAME' for their format
    letters, 'layout:NAME' for the fields of a flat array (LAYOUTS)."""
    text, first, status, message = _bridge.names(list_name)
    check_status(status, message)
    return tuple(_text(text).split(",")), int(first)


def codes(list_name):
    """{code: name} of a kind list."""
    items, first = names(list_name)
    return {first + i: name for i, name in enumerate(items)}


def columns(table):
    """Column names of a result table, in the order of the core's arrays."""
    return list(names(f"table:{table}")[0])


#: The enumerated options whose codes the core names (the bridge's names routine).
CODE_LISTS = ("analyses", "methods", "chart_models", "chart_axes", "excitation_parameters",
              "directions", "study_kinds", "worker_kinds", "continuations", "ground_kinds",
              "resonances", "tank_shapes", "special", "motion", "verdict", "source", "curve", "codim2",
              "curve_end")
#: The flat arrays with a named layout (sloshdyn_layouts; 'model' and 'model_integers' are the
#: model's rpar and ipar).
LAYOUTS = ("model", "model_integers", "integration", "steady", "response", "response_range",
           "lyapunov", "tank", "ground", "chart", "study", "sweep", "simulation", "seismic",
           "analysis", "continuation", "cycle_continuation", "shooting", "pendulum", "physical",
           "groups", "routh", "orbit_info")


def layout(name):
    """The field names of a flat array, in the order of the core's array."""
    return names(f"layout:{name}")[0]


def pack(name, values, dtype=np.float64):
    """The flat array of layout `name` from {field: value}; every field must be given, no other."""
    fields = layout(name)
    if set(values) != set(fields):
        raise KeyError(f"layout {name!r} has the fields {fields}, given {tuple(values)}")
    return np.array([values[f] for f in fields], dtype=dtype)


def unpack(name, array):
    """{field: value} of a flat array of layout `name` (numpy scalars as given)."""
    fields = layout(name)
    if len(array) != len(fields):
        raise ValueError(f"layout {name!r} has {len(fields)} fields, the array {len(array)}")
    return dict(zip(fields, array))


def code(list_name, name):
    """The code of a name in an enumerated option's list."""
    return {v: k for k, v in codes(list_name).items()}[name]


@lru_cache(maxsize=None)
def defaults():
    """The core's defaults {layout: {field: value}}: the model ('model' and 'model_integers'
    merged), integration, steady, response, lyapunov and shooting."""
    model, model_integers, *arrays = _bridge.defaults()
    result = {"model": {**unpack("model", model.copy()),
                        **unpack("model_integers", model_integers.copy())}}
    for key, array in zip(("integration", "steady", "response", "lyapunov", "shooting"), arrays):
        result[key] = unpack(key, array.copy())
    return result
