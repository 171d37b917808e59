"""The tank's structure for the design check's structural checks (issue 38; docs/namelist.md,
&tank_structure): `TankStructure`, a value type made from the core's layout 'tank_structure'
(its scalars with the core's kinds and defaults; the course variables as sequences, one field
per course in the core). It imports no analysis (docs/architecture.md, "Python layers"); the
core checks every rule, with the tank, when the design check runs."""

from __future__ import annotations

import dataclasses

from . import _checks, _tables
from ._errors import InputError
from ._settings import convert_fields, decode, decode_all, encode

#: the course variables of &tank_structure (sequences in Python, one field per course in the core)
COURSE_FIELDS = ("course_height", "course_thickness", "course_yield_strength",
                 "course_tensile_strength")
#: at most this many courses (the core's layout 'tank_structure')
MAX_COURSES = sum(1 for name in _tables.layout("tank_structure")
                  if name.startswith("course_height_"))


def _structure_fields():
    """The dataclass fields of TankStructure: the core layout's scalars with their kinds and
    defaults ('given' is the presence of the group, not a field), the courses as tuples."""
    kinds, defaults, docs = (_tables.kinds("tank_structure"), _tables.defaults("tank_structure"),
                             _tables.docs("tank_structure"))
    fields = []
    for name, kind in kinds.items():
        if name == "given" or name.startswith(tuple(f + "_" for f in COURSE_FIELDS)):
            continue
        default = decode(kind, defaults[name])
        fields.append((name, type(default), dataclasses.field(default=default,
                                                              metadata={"doc": docs[name]})))
    # the bottom course's height and thickness are required (&tank_structure's rule)
    return ([(name, tuple) for name in COURSE_FIELDS[:2]]
            + [(name, tuple, dataclasses.field(default=())) for name in COURSE_FIELDS[2:]]
            + fields)


def _structure_post_init(self):
    for name in COURSE_FIELDS:
        values = _checks.reals(name, getattr(self, name), ndim=1)
        if values.size > MAX_COURSES:
            raise InputError(f"{name} has {values.size} values: at most {MAX_COURSES} courses")
        object.__setattr__(self, name, tuple(float(x) for x in values))
    kinds = _tables.kinds("tank_structure")
    for name in ("material", "anchorage"):
        _checks.choice(name, getattr(self, name), _tables.names(kinds[name][len("code:"):])[0])
    convert_fields(self)


def _structure_array(self):
    """The flat array of the core's layout 'tank_structure' (given = 1)."""
    kinds = _tables.kinds("tank_structure")
    values = {"given": 1.0}
    for name in COURSE_FIELDS:
        given = getattr(self, name)
        for k in range(1, MAX_COURSES + 1):
            values[f"{name}_{k}"] = given[k - 1] if k <= len(given) else 0.0
    for name, kind in kinds.items():
        if name not in values:
            values[name] = encode(kind, getattr(self, name))
    return _tables.pack("tank_structure", values)


def _structure_from_array(cls, array):
    """The structure of a flat array in the core's layout, or None where it is not given."""
    values = decode_all("tank_structure", array)
    if not values.pop("given"):
        return None
    courses = {name: [values.pop(f"{name}_{k}") for k in range(1, MAX_COURSES + 1)]
               for name in COURSE_FIELDS}
    n = next((i for i, h in enumerate(courses["course_height"]) if h == 0), MAX_COURSES)
    return cls(**{name: tuple(v[:n]) for name, v in courses.items()}, **values)


TankStructure = dataclasses.make_dataclass(
    "TankStructure", _structure_fields(), frozen=True, kw_only=True,
    namespace={"__post_init__": _structure_post_init, "array": _structure_array,
               "from_array": classmethod(_structure_from_array), "layout": "tank_structure",
               "__module__": __name__})
TankStructure.__doc__ = """&tank_structure: the tank's structure for the design check's structural
    checks (docs/namelist.md, &tank_structure): the shell courses bottom first as sequences
    (course_height [m], course_thickness [mm] as built, course_yield_strength and
    course_tensile_strength [MPa], 0: as the course below), corrosion_allowance [mm],
    joint_efficiency, elastic_modulus [MPa] (0: 200 000 for steel), density [kg/m^3] (0: 7850
    steel, 2400 concrete), bottom_thickness, annular_thickness, bottom_corrosion_allowance [mm],
    annular_yield_strength [MPa], roof_mass [kg], roof_mass_height [m], anchorage ('self' or
    'mechanical'), anchor_count, anchor_capacity [N], friction; material 'steel' or 'concrete'.
    The core checks every rule (with the tank: sloshdyn.design_check)."""
