"""Settings classes made from the core's layouts: a class decorated with ``@settings(LAYOUT)``
gets the layout's fields, in order, with the kinds, defaults and descriptions the core gives
(sloshdyn_layouts), and becomes a frozen, keyword-only dataclass with ``array()`` (the flat array
of the layout) and ``from_array()``. So a new variable of a settings group is written in the
Fortran core only (docs/architecture.md, "Layouts: one source for every flat array")."""

from __future__ import annotations

import dataclasses

from . import _checks, _tables

#: the Python type of each kind of field; 'code:LIST' fields are the names of LIST's codes
_TYPES = {"real": float, "integer": int, "flag": bool}
_CHECKS = {"float": _checks.real, "int": _checks.integer, "bool": _checks.flag,
           "str": _checks.text}


def convert_fields(settings):
    """Check and convert every field of a settings dataclass by its annotation (int: a C int,
    float: a finite real, bool: True or False, str: text), in place (frozen or not)."""
    for f in dataclasses.fields(settings):
        check = _CHECKS.get(f.type)
        if check is not None:
            object.__setattr__(settings, f.name, check(f.name, getattr(settings, f.name)))


def _code_list(kind):
    return kind[len("code:"):] if kind.startswith("code:") else None


def decode(kind, value):
    """A value of a flat array as the Python value of a field of this kind."""
    codes = _code_list(kind)
    if codes is not None:
        return _tables.codes(codes)[int(value)]
    return _TYPES[kind](value) if kind != "flag" else bool(value != 0)


def decode_all(layout, array):
    """{field: Python value} of a flat array of a layout (codes by name)."""
    kinds = _tables.kinds(layout)
    return {name: decode(kinds[name], x) for name, x in _tables.unpack(layout, array).items()}


def encode(kind, value):
    """The number a field of this kind has in a flat array."""
    codes = _code_list(kind)
    if codes is not None:
        return _tables.code(codes, value)
    return float(value)


def settings(layout):
    """Class decorator: the fields of the core's layout `layout` (names, order, kinds, defaults
    and descriptions from the core), a frozen keyword-only dataclass, checked when created, with
    ``array()`` and ``from_array(array)``. The class body holds only its docstring and what is
    its own (properties, methods, an optional ``_check(self)`` run after the fields' checks)."""
    def make(cls):
        kinds, docs, defaults = (_tables.kinds(layout), _tables.docs(layout),
                                 _tables.defaults(layout))
        annotations, lines = {}, []
        for name, kind in kinds.items():
            default = decode(kind, defaults[name])
            annotations[name] = type(default).__name__
            setattr(cls, name, default)
            choices = _code_list(kind)
            what = (f"one of {', '.join(repr(c) for c in _tables.names(choices)[0])}"
                    if choices else annotations[name])
            lines.append(f"    {name} ({what}; default {default!r})"
                         + (f": {docs[name]}" if docs[name] else ""))
        cls.__annotations__ = annotations
        cls.__doc__ = ((cls.__doc__ or "").rstrip() + f"\n\n    Fields (the core's layout "
                       f"{layout!r}, in order, with the core's defaults):\n" + "\n".join(lines))
        cls.layout = layout
        cls.__post_init__ = _post_init
        cls.array = _array
        cls.from_array = classmethod(_from_array)
        return dataclasses.dataclass(frozen=True, kw_only=True)(cls)
    return make


def _post_init(self):
    for name, kind in _tables.kinds(self.layout).items():
        choices = _code_list(kind)
        if choices is not None:
            _checks.choice(name, getattr(self, name), _tables.names(choices)[0])
    convert_fields(self)
    _tables.check_settings(self.layout, _array(self))   # the core's range rules
    check = getattr(self, "_check", None)
    if check is not None:
        check()


def _array(self):
    """The flat array of the core's layout (codes by number, flags 1/0)."""
    kinds = _tables.kinds(self.layout)
    return _tables.pack(self.layout, {name: encode(kind, getattr(self, name))
                                      for name, kind in kinds.items()})


def _from_array(cls, array):
    """The settings of a flat array in the core's layout."""
    return cls(**decode_all(cls.layout, array))
