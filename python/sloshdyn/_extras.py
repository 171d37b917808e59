"""The optional parts of sloshdyn: `pip install sloshdyn` is the core (the solver, its Python API
and the executable); figures need `sloshdyn[plot]` and parameter studies `sloshdyn[studies]`
(pyproject.toml's [project.optional-dependencies]). A missing one is a MissingExtraError that
names the extra to install."""

from __future__ import annotations

import importlib

from ._errors import SloshdynError


class MissingExtraError(SloshdynError, ImportError):
    """An optional dependency is not installed; the message names the extra that installs it."""


def require(extra, *modules):
    """Import `modules`, dependencies of sloshdyn[extra]; MissingExtraError if one is missing."""
    for module in modules:
        try:
            importlib.import_module(module)
        except ImportError as exc:
            package = module.split(".")[0]
            raise MissingExtraError(f"{package} is not installed; it comes with the '{extra}' "
                                    f"extra: pip install 'sloshdyn[{extra}]'") from exc
