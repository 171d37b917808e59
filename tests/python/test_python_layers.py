"""The Python package is layered like the Fortran core (docs/architecture.md, "Python layers"):
a module imports only modules of its own layer and of lower ones, and the import graph has no
circle. The graph is read from the source, imports inside functions included, so a circle
cannot hide behind a function-level import."""

import ast
import shutil

import pytest

from conftest import ROOT

PACKAGE = ROOT / "python" / "sloshdyn"
#: modules of the package that are not Python source: the f2py extension the build makes
EXTENSIONS = {"_core"}

#: the layers, lowest first; a module imports only modules of its own layer and lower ones
LAYERS = [
    ("infrastructure", {"_core", "_errors", "_checks", "_tables", "_settings", "_files",
                        "_cancel", "_extras", "_version", "_input", "_shipped"}),
    ("value types", {"parameters", "options", "ground", "tank", "structure"}),
    ("analyses", {"model", "simulation", "asymptotics", "periodic", "research", "charts",
                  "seismic", "pressure", "design", "spatial", "plotting", "studies",
                  "export"}),
    ("input", {"namelist"}),
    ("runs", {"runner"}),
    ("front doors", {"report", "report_layout", "report_tables", "report_figures", "report_pdf",
                     "figures", "reference", "cli", "__main__", "__init__"}),
]


def layer_of(module):
    """The layer index of a module name relative to the package ('studies.engine' -> the
    layer of 'studies')."""
    top = module.split(".")[0]
    for rank, (_, names) in enumerate(LAYERS):
        if top in names:
            return rank
    raise AssertionError(f"sloshdyn.{module} is in no layer of {__name__}.LAYERS")


def module_name(path, package):
    """'studies.engine' for package/studies/engine.py, '__init__' for package/__init__.py,
    'studies' for package/studies/__init__.py."""
    parts = list(path.relative_to(package).with_suffix("").parts)
    if parts[-1] == "__init__" and len(parts) > 1:
        parts.pop()
    return ".".join(parts)


def imported_modules(path, package):
    """The package's modules that a file imports anywhere (top level or inside a function):
    'from . import x' names x; 'from .x import y' names x (or x.y when that is a module);
    'import sloshdyn' names the package itself ('__init__')."""
    name = module_name(path, package)
    # the package a relative import starts from: the file's own for a package's __init__
    here = name.split(".") if path.name == "__init__.py" and name != "__init__" else \
        name.split(".")[:-1]
    modules = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.ImportFrom):
            if node.level == 0:
                if node.module and node.module.split(".")[0] == "sloshdyn":
                    base = node.module.split(".")[1:]
                else:
                    continue
            else:
                base = (here[:len(here) - node.level + 1] if node.level > 1 else here) + (
                    node.module.split(".") if node.module else [])
            for alias in node.names:
                candidate = base + [alias.name]
                if (".".join(candidate) in EXTENSIONS
                        or package.joinpath(*candidate).with_suffix(".py").exists()
                        or (package.joinpath(*candidate) / "__init__.py").exists()):
                    modules.add(".".join(candidate))
                elif base:
                    modules.add(".".join(base))
                else:
                    modules.add("__init__")
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] == "sloshdyn":
                    modules.add(".".join(alias.name.split(".")[1:]) or "__init__")
    modules.discard(name)
    return modules


def import_graph(package=PACKAGE):
    """{module: set of imported modules} over every .py file of the package."""
    return {module_name(path, package) or "__init__": imported_modules(path, package)
            for path in sorted(package.rglob("*.py"))}


def circles(graph):
    """The strongly connected components with more than one module (Tarjan), each sorted."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def test_the_package_imports_in_one_direction():
    graph = import_graph()
    assert len(graph) > 30 and "seismic" in graph["design"]   # the scan sees the package
    assert circles(graph) == []


def test_every_import_goes_to_the_same_or_a_lower_layer():
    for module, imported in import_graph().items():
        for other in imported:
            assert layer_of(other) <= layer_of(module), (
                f"sloshdyn.{module} ({LAYERS[layer_of(module)][0]}) imports sloshdyn.{other} "
                f"({LAYERS[layer_of(other)][0]})")


def test_a_circle_added_inside_a_function_is_found(tmp_path):
    """The checks above can fail: a copy of the package with one import inside a function that
    closes a circle (the value type Tank importing the design check, as Tank.design_check did)
    has a circle and an import from a lower layer to a higher one."""
    copy = tmp_path / "sloshdyn"
    shutil.copytree(PACKAGE, copy)
    tank = copy / "tank.py"
    tank.write_text(tank.read_text() + "\n\ndef _check(self):\n    from .design import design_check\n"
                    "    return design_check(self)\n")
    graph = import_graph(copy)
    assert "design" in graph["tank"]
    assert any({"tank", "design"} <= set(c) for c in circles(graph))
    assert layer_of("design") > layer_of("tank")


@pytest.mark.parametrize("source, expected", [
    ("from . import _core, _tables\n", {"_core", "_tables"}),
    ("def f():\n    from .seismic import Tank\n", {"seismic"}),
    ("import sloshdyn\n", {"__init__"}),
    ("from sloshdyn.studies import engine\n", {"studies.engine"}),
    ("import numpy\nfrom dataclasses import field\n", set()),
])
def test_the_scan_sees_every_kind_of_import(tmp_path, source, expected):
    copy = tmp_path / "sloshdyn"
    shutil.copytree(PACKAGE, copy)
    (copy / "probe.py").write_text(source)
    assert imported_modules(copy / "probe.py", copy) == expected
