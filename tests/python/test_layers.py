"""The Fortran core is layered: a module uses only modules of its own layer and lower ones
(base < numerics < model < analysis < app, bridge). Numerics in particular never uses the model."""

import re

import pytest

from conftest import ROOT

LAYERS = ["base", "numerics", "model", "analysis", "app", "bridge"]


def modules():
    """{module name: layer index} of every sloshdyn module, and each file's used modules."""
    defined, uses = {}, {}
    for rank, layer in enumerate(LAYERS):
        for path in sorted((ROOT / "fortran" / layer).glob("*.f90")):
            text = path.read_text()
            for name in re.findall(r"^\s*module\s+(\w+)\s*$", text, re.M | re.I):
                defined[name.lower()] = rank
            uses[path] = (rank, {u.lower() for u in re.findall(r"^\s*use\s+(sloshdyn_\w+)", text,
                                                               re.M | re.I)})
    return defined, uses


def test_every_use_goes_to_the_same_or_a_lower_layer():
    defined, uses = modules()
    assert len(defined) > 20
    for path, (rank, used) in uses.items():
        for name in used:
            assert name in defined, f"{path.name} uses unknown module {name}"
            assert defined[name] <= rank, \
                f"{path.relative_to(ROOT)} ({LAYERS[rank]}) uses {name} ({LAYERS[defined[name]]})"


@pytest.mark.parametrize("text, expected", [
    ("module m\n  use sloshdyn_model, only: model_t\n", {"sloshdyn_model"}),
    ("  USE Sloshdyn_Ode\n", {"sloshdyn_ode"}),
])
def test_the_scan_sees_use_statements(text, expected):
    """The check above can fail: the pattern finds use statements in any case and indentation."""
    assert {u.lower() for u in re.findall(r"^\s*use\s+(sloshdyn_\w+)", text, re.M | re.I)} == expected


#: the longest a source file of the core may grow (DESIGN.md: one module per concern; a file
#: past this is split, as sloshdyn_namelist_groups.f90 was into a submodule)
MAX_LINES = 1100


def test_no_core_file_is_longer_than_the_limit():
    lengths = {path.relative_to(ROOT).as_posix(): len(path.read_text().splitlines())
               for path in sorted((ROOT / "fortran").rglob("*")) if path.suffix in (".f90", ".c")}
    assert len(lengths) > 20
    assert {name: n for name, n in lengths.items() if n > MAX_LINES} == {}


def test_every_bridge_message_has_the_cores_length():
    """A bridge message shorter than the core's message_len would cut what the core says (f2py
    needs a literal length, so the bridge cannot name message_len itself)."""
    kinds = (ROOT / "fortran" / "base" / "sloshdyn_kinds.f90").read_text()
    core_length = int(re.search(r"message_len\s*=\s*(\d+)", kinds).group(1))
    lengths = {}
    for path in sorted((ROOT / "fortran" / "bridge").glob("*.f90")):
        for n in re.findall(r"character\(len=(\d+)\),\s*intent\(out\)\s*::[^!\n]*\bmessage\b",
                            path.read_text(), re.I):
            lengths.setdefault(int(n), set()).add(path.name)
    assert core_length in lengths
    assert set(lengths) == {core_length}, lengths
