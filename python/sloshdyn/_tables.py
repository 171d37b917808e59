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
def _names_text(list_name):
    text, first, status, message = _bridge.names(list_name)
    check_status(status, message)
    raw = text.decode() if isinstance(text, bytes) else str(text)
    return raw.rstrip(), int(first)


def names(list_name):
    """The names of a list and the code of the first one: the codes of an enumerated option
    (code_lists()), 'table:NAME' for a result table's columns, 'formats:NAME' for their format
    letters, 'layout:NAME' for the fields of a flat array (layouts()), 'kinds:NAME' for their
    kinds ('real', 'integer', 'flag', 'code:LIST')."""
    text, first = _names_text(list_name)
    return tuple(item.strip() for item in text.split(",")), first


def codes(list_name):
    """{code: name} of a kind list."""
    items, first = names(list_name)
    return {first + i: name for i, name in enumerate(items)}


def columns(table):
    """Column names of a result table, in the order of the core's arrays."""
    return list(names(f"table:{table}")[0])


def column_name(column):
    """A column's name without its unit: 't [s]' -> 't' (the attribute and key names)."""
    return column.split(" [")[0]


def code_lists():
    """The enumerated options whose codes the core names (the bridge's names routine)."""
    return names("code_lists")[0]


def layouts():
    """The flat arrays with a named layout (sloshdyn_layouts; 'model' and 'model_integers' are
    the model's rpar and ipar)."""
    return names("layouts")[0]


def layout(name):
    """The field names of a flat array, in the order of the core's array."""
    return names(f"layout:{name}")[0]


def kinds(name):
    """{field: kind} of a layout: 'real', 'integer', 'flag' (1/0) or 'code:LIST' (a code of the
    enumerated option LIST)."""
    return dict(zip(layout(name), names(f"kinds:{name}")[0]))


def docs(name):
    """{field: what it is} of a layout, as the core documents it ('' where it does not)."""
    lines = _names_text(f"docs:{name}")[0].split("\n")
    return dict(zip(layout(name), [line.strip() for line in lines] + [""] * len(layout(name))))


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


def check_settings(name, values):
    """The core's range rules for the values of a settings layout (sloshdyn_layouts'
    check_layout): InputError naming the variable, its value and the allowed range."""
    status, message = _bridge.check_settings(name, np.asarray(values, dtype=float))
    check_status(status, message)


@lru_cache(maxsize=None)
def defaults(name):
    """The core's defaults {field: value} of a settings layout (the option types' defaults, as
    the namelist reader starts from them; 'model' and 'model_integers': model_t's)."""
    values, status, message = _bridge.layout_defaults(name, len(layout(name)))
    check_status(status, message)
    return unpack(name, values.copy())
