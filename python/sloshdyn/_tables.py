"""Names and defaults that the Fortran core defines once (sloshdyn_tables, the option types):
column names of result tables, kind codes, analyses, integration methods, and the defaults of
every settings type. Python takes them from the bridge instead of keeping copies."""

from __future__ import annotations

from functools import lru_cache

from . import _core
from ._errors import check_status

_bridge = _core.sloshdyn_bridge


def _text(raw):
    return (raw.decode() if isinstance(raw, bytes) else str(raw)).strip()


@lru_cache(maxsize=None)
def names(list_name):
    """The names of a list ('analyses', 'methods', 'special', 'motion', 'verdict', 'source',
    'curve', 'codim2', 'curve_end', 'chart_models', 'table:NAME' for a result table's columns,
    'formats:NAME' for their format letters) and the code of the first one."""
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


@lru_cache(maxsize=None)
def defaults():
    """The core's defaults: model [beta, gamma, delta, n, p, zeta], the integration, steady, response
    and lyapunov settings in their bridge layouts, and shooting [newton_tol, max_iter]."""
    arrays = _bridge.defaults()
    keys = ("model", "integration", "steady", "response", "lyapunov", "shooting")
    return {key: array.copy() for key, array in zip(keys, arrays)}
