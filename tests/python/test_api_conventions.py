"""The conventions of the public Python API (issue 21, item 3; docs/architecture.md, "Python
layer"), checked over everything sloshdyn exports -- sloshdyn.__all__, the public methods of
its classes and the functions of sloshdyn.plotting -- so that a new function follows them or
this test names it:

- every result is a frozen dataclass built complete: a function's return annotation names it,
  and a result of an integration carries the method that ran (`method`, a field without a
  default, so it is given at construction, never attached afterwards);
- settings are objects passed by keyword: a parameter that takes a settings class (a public
  dataclass whose every field has a default: Integration, Steady, Continuation, ...) is
  keyword-only and named after its class; no function takes a field of a settings class as a
  loose keyword, nor **keywords;
- the same name and unit for the same quantity: a bridge array is `array()`, the tank's
  quantities have the names of sloshdyn.Tank and of the core's tank table, and every `units`
  defaults to the unit in which the namelist reads accelerations (asked of the core's reader).
"""

from __future__ import annotations

import dataclasses
import inspect
import re
import typing

import numpy as np
import pytest

import sloshdyn
from sloshdyn import _tables, plotting

PUBLIC = {name: getattr(sloshdyn, name) for name in sloshdyn.__all__}
CLASSES = {name: c for name, c in PUBLIC.items()
           if inspect.isclass(c) and not issubclass(c, BaseException)}
#: the settings classes: public dataclasses that can be built from their defaults alone
SETTINGS = {name: c for name, c in CLASSES.items() if dataclasses.is_dataclass(c)
            and all(f.default is not dataclasses.MISSING
                    or f.default_factory is not dataclasses.MISSING
                    for f in dataclasses.fields(c) if f.init)}
#: functions whose result is one number or array of numbers of one quantity (a formula
#: vectorised like numpy, or values to sweep over), not a result object
VALUE_FUNCTIONS = {"frequency_ratio", "kappa_for_detuning", "sweep_values", "beat_period",
                   "acceleration_factor", "nonresonant_amplitudes"}


def _public_callables():
    """(label, callable) of every public function and public method of the API."""
    found = {name: f for name, f in PUBLIC.items() if inspect.isfunction(f)}
    for name, cls in CLASSES.items():
        for attr, member in vars(cls).items():
            if attr.startswith("_"):
                continue
            function = member.__func__ if isinstance(member, (classmethod, staticmethod)) else member
            if inspect.isfunction(function):
                found[f"{name}.{attr}"] = function
    for name, f in vars(plotting).items():
        if inspect.isfunction(f) and not name.startswith("_") and f.__module__ == plotting.__name__:
            found[f"plotting.{name}"] = f
    return found


CALLABLES = _public_callables()


def _snake(name):
    return re.sub(r"(?<!^)(?=[A-Z])", "_", name).lower()


def _studies(function):
    """The study functions return xarray Datasets (docs/architecture.md, "Studies on Dask")."""
    return function.__module__.startswith("sloshdyn.studies")




def test_the_api_has_the_expected_kinds_of_things():
    # the lists this test walks are not empty by accident
    assert {"Integration", "Steady", "Continuation", "Lyapunov", "Shooting", "Chart"} <= set(SETTINGS)
    assert "Parameters" not in SETTINGS and "Tank" not in SETTINGS
    assert {"simulate", "lyapunov_exponent", "Tank.design_codes", "plotting.fragility"} <= set(CALLABLES)


@pytest.mark.parametrize("name", sorted(n for n, f in CALLABLES.items() if "." not in n))
def test_every_result_is_a_frozen_dataclass(name):
    function = CALLABLES[name]
    if _studies(function) and name != "fit_fragility":
        return
    hints = typing.get_type_hints(function)
    assert "return" in hints, f"{name} does not say what it returns (a return annotation)"
    result = hints["return"]
    if name in VALUE_FUNCTIONS:
        assert result in (float, np.ndarray, list), (name, result)
        return
    assert inspect.isclass(result) and dataclasses.is_dataclass(result), \
        f"{name} returns {result}: results are dataclasses (not tuples, dicts or bare arrays)"
    assert result.__dataclass_params__.frozen, f"{name} returns a {result.__name__}, not frozen"
    if "integration" in inspect.signature(function).parameters:
        method = {f.name: f for f in dataclasses.fields(result)}.get("method")
        assert method is not None, f"{result.__name__} does not say which method integrated it"
        assert method.default is dataclasses.MISSING, \
            f"{result.__name__}.method has a default: it must be given at construction"


def test_every_public_dataclass_of_the_package_is_frozen():
    from sloshdyn import figures, reference, studies  # noqa: F401 (their dataclasses too)
    import sys
    # (the study engine's work plan is its own business, never returned)
    modules = [m for name, m in sys.modules.items()
               if name.startswith("sloshdyn.") and name != "sloshdyn.studies.engine"]
    found = {}
    for module in modules:
        for name, value in vars(module).items():
            if (inspect.isclass(value) and dataclasses.is_dataclass(value)
                    and not name.startswith("_") and value.__module__ == module.__name__):
                found[f"{module.__name__}.{name}"] = value
    assert {"sloshdyn.figures.Figure", "sloshdyn.reference.Verdict",
            "sloshdyn.seismic.SeismicResponse"} <= set(found)
    assert [name for name, c in found.items() if not c.__dataclass_params__.frozen] == []


@pytest.mark.parametrize("name", sorted(CALLABLES))
def test_settings_are_keyword_only_objects(name):
    function = CALLABLES[name]
    loose = {f.name: settings for settings in SETTINGS.values()
             for f in dataclasses.fields(settings)}
    hints = typing.get_type_hints(function)
    for p in inspect.signature(function).parameters.values():
        if p.kind is p.VAR_KEYWORD and p.name == "changes":
            continue        # as dataclasses.replace: the object's own fields (replace, from_array)
        assert p.kind is not p.VAR_KEYWORD, f"{name}(**{p.name}): settings go in settings objects"
        hint = hints.get(p.name)
        kind = next((c for c in SETTINGS.values() if isinstance(p.default, c) or hint is c), None)
        if kind is not None:
            assert p.kind is p.KEYWORD_ONLY, f"{name}: {p.name} must be keyword-only"
            assert p.name == _snake(kind.__name__), \
                f"{name}: a {kind.__name__} is passed as {_snake(kind.__name__)}=, not {p.name}="
        elif name.split(".")[0] not in SETTINGS and not name.startswith("plotting."):
            # (plots take results: plotting's ds is a Dataset, not Continuation's step)
            assert p.name not in loose, (f"{name}({p.name}=...) is a loose setting: it belongs "
                                         f"in a sloshdyn.{loose[p.name].__name__}")


def test_bridge_arrays_are_array_everywhere():
    import sys
    for name, module in sys.modules.items():
        if name.startswith("sloshdyn"):
            for cls in (v for v in vars(module).values() if inspect.isclass(v)):
                assert not hasattr(cls, "arrays"), f"{cls.__name__}.arrays(): the name is array()"
    for cls in (sloshdyn.Parameters, sloshdyn.Tank, sloshdyn.Integration, sloshdyn.Steady,
                sloshdyn.Continuation, sloshdyn.Lyapunov):
        assert callable(getattr(cls, "array", None)), cls


def test_tank_quantities_have_one_name():
    """A tank's radius, liquid depth, density and mass are named as sloshdyn.Tank and the
    &tank group name them, everywhere; the pendulum's fields are columns of the core's tank
    table (tank.csv)."""
    paper_symbols = {"R": "radius", "h": "liquid_depth", "rho_liquid": "liquid_density",
                     "m_liquid": "liquid_mass", "m_F": "liquid_mass"}
    tank_fields = {f.name for f in dataclasses.fields(sloshdyn.Tank)}
    assert set(paper_symbols.values()) <= tank_fields
    # what names a tank's liquid (h alone is also eq 35's polynomial) holds no paper symbol
    liquid = set(paper_symbols) - {"h"} | {"radius", "liquid_density", "liquid_mass"}
    names = {name: list(inspect.signature(f).parameters) for name, f in CALLABLES.items()}
    names.update({name: [f.name for f in dataclasses.fields(c)] for name, c in CLASSES.items()
                  if dataclasses.is_dataclass(c)})
    for name, found in names.items():
        if liquid & set(found):
            wrong = [p for p in found if p in paper_symbols]
            assert wrong == [], f"{name}: call {wrong} {[paper_symbols[p] for p in wrong]}"
    columns = {c.split(" [")[0] for c in _tables.columns("tank_si")}
    assert {f.name for f in dataclasses.fields(sloshdyn.TankPendulum)} <= columns
    pendulum = sloshdyn.tank_pendulum(radius=5.0, liquid_depth=6.0, liquid_density=1000.0)
    tank = sloshdyn.Tank(radius=5.0, liquid_depth=6.0, freeboard=1.0, liquid_density=1000.0,
                         tank_mass=5e4, support_frequency=2.0)
    for f in dataclasses.fields(pendulum):     # the same quantity has the same value
        assert getattr(pendulum, f.name) == pytest.approx(tank.properties[f.name], rel=1e-12)
    with pytest.raises(sloshdyn.InputError, match="^radius = -1"):
        sloshdyn.tank_pendulum(-1.0, 6.0, liquid_density=1000.0)


def test_accelerations_default_to_the_namelists_unit(tmp_path):
    """The namelist reads &ground_motion's accelerations in `units`, 'g' unless told: every
    `units` of the API defaults to the same, so a number means the same in both front doors."""
    (tmp_path / "in.nml").write_text(
        "&tank radius = 5, liquid_depth = 6, freeboard = 1, liquid_density = 1000, "
        "tank_mass = 5e4, support_frequency = 2 /\n"
        "&ground_motion peak_acceleration = 0.3, frequency = 0.5 /\n"
        "&analysis kind = 'seismic' /\n")
    read = sloshdyn.read_namelist(tmp_path / "in.nml").ground_motion.peak_acceleration
    factors = {u: sloshdyn.acceleration_factor(u) for u in ("g", "m/s^2", "cm/s^2")}
    namelist_unit = [u for u, f in factors.items() if read == pytest.approx(0.3 * f, rel=1e-15)]
    assert namelist_unit == ["g"]
    defaults = {name: inspect.signature(f).parameters["units"].default
                for name, f in CALLABLES.items() if "units" in inspect.signature(f).parameters
                and name != "acceleration_factor"}      # the conversion itself: no default
    assert {"GroundMotion.harmonic", "GroundMotion.from_file", "GroundMotion.scaled",
            "harmonic_sweep", "StabilityChart.frequency_and_acceleration",
            "plotting.fragility"} <= set(defaults)
    assert {name: u for name, u in defaults.items() if u != namelist_unit[0]} == {}
    units = inspect.signature(sloshdyn.GroundMotion).parameters["units"].default
    assert units == namelist_unit[0]
    for name, function in CALLABLES.items():
        assert "unit" not in inspect.signature(function).parameters, f"{name}(unit=): units="
    # the same numbers make the same ground motion in both front doors
    python = sloshdyn.GroundMotion(peak_acceleration=0.3, frequency=0.5)
    assert python.peak_acceleration == read
    assert sloshdyn.GroundMotion.harmonic(0.3, 0.5).peak_acceleration == read
