"""Export of results with their parameters, units and method (issue 42): a periodic branch
(sloshdyn.PeriodicBranch), a bifurcation curve (sloshdyn.charts.Curve, with the chart's
parameters) and a study (the xarray Dataset of sloshdyn.studies) become an xarray Dataset
(`to_dataset`) or one CSV file (`write_csv`), read back by `read_csv` into the same Dataset;
`branch_from_dataset` rebuilds the PeriodicBranch. docs/python.md, "Export", describes the file.

The CSV file is text a spreadsheet or pandas reads (``comment='#'`` skips the header): lines
starting with '#' hold JSON, the Dataset's attributes (kind, method, parameters) and one line
per variable (name, dimensions, dtype, attributes with its ``units``); then one table per group
of variables sharing dimensions, introduced by '# table {"dims": [...], "shape": [...]}', a
header row of names and one row per element (C order over the dimensions; a grid's rows start
with their coordinates, e.g. frequency and amplitude of a response map). Numbers are written
with repr (they read back bit for bit), complex ones as Python writes them ('(1+2j)'). xarray
is imported on first use."""

from __future__ import annotations

import csv
import dataclasses
import json

import numpy as np

from . import _files
from ._errors import InputError
from ._version import __version__
from .charts import Curve
from .options import Continuation, Integration
from .parameters import Parameters
from .periodic import PeriodicBranch, PeriodicSpecialPoint

#: what each periodic branch was computed by (sloshdyn_shooting, sloshdyn_continuation)
BRANCH_METHOD = ("pseudo-arclength continuation of periodic orbits by single shooting; Floquet "
                 "multipliers the eigenvalues of the monodromy matrix (variational equations)")
#: the same for the slow-flow curves of a stability chart (sloshdyn_bifurcation_tracer)
CURVE_METHOD = ("pseudo-arclength continuation of the slow flow's fold or Hopf condition in two "
                "parameters, with its codimension-2 points")
#: units of the dimensionless model's quantities (docs/model.md, eq 9-11 and 29)
_STATE_UNITS = {"y1": "theta0", "y2": "theta0 omega", "y3": "theta0", "y4": "theta0 omega"}
_UNITS = {"lambda": "1", "rho": "1 (forcing frequency over omega)",
          "A": "1 (ground amplitude over the support height L)", "gamma": "1", "kappa": "1",
          "max_x1": "theta0", "stable": "1", "omega": "omega (slow time)", "l1": "1",
          **_STATE_UNITS}
_LONG = {"lambda": "the continued parameter", "y1": "x1 at phase 0", "y2": "x1' at phase 0",
         "y3": "x2 at phase 0", "y4": "x2' at phase 0", "max_x1": "max |x1| over the orbit",
         "stable": "all Floquet multipliers inside the unit circle (1) or not (0)"}


def _params_attrs(params):
    """The parameters as the studies record them: a JSON text (netCDF and Zarr keep it)."""
    return {} if params is None else {"parameters": json.dumps(dataclasses.asdict(params))}


def _variable(xr, dims, values, name, long_name=None):
    attrs = {"units": _UNITS.get(name, "1")}
    if long_name or name in _LONG:
        attrs["long_name"] = long_name or _LONG[name]
    return xr.Variable(dims, values, attrs)


def _branch_dataset(xr, branch: PeriodicBranch):
    t = branch.table
    data = {name: _variable(xr, ("point",), np.asarray(t[name], float), name)
            for name in ("lambda", "rho", "A", "y1", "y2", "y3", "y4", "max_x1")}
    data["stable"] = _variable(xr, ("point",), np.asarray(t["stable"]) != 0, "stable")
    for i in range(1, 5):
        data[f"mu{i}"] = _variable(xr, ("point",), np.asarray(t[f"mu{i}"], complex), f"mu{i}",
                                   f"Floquet multiplier {i}")
    s = branch.special_points
    data["special_kind"] = xr.Variable(("special",), np.array([p.kind for p in s], dtype=str),
                                       {"units": "1", "long_name": "the special point's kind"})
    for name in ("rho", "A", "max_x1"):
        data[f"special_{name}"] = _variable(xr, ("special",),
                                            np.array([getattr(p, name) for p in s], float), name)
    for i in range(4):
        data[f"special_y{i + 1}"] = _variable(xr, ("special",),
                                              np.array([p.y0[i] for p in s], float), f"y{i + 1}")
    attrs = {"kind": "periodic_branch", "method": BRANCH_METHOD,
             "integration_method": branch.method, "parameter": branch.parameter,
             "periods": branch.periods, "complete": int(branch.complete), "message": branch.message,
             "lambda_range": list(branch.lambda_range), **_params_attrs(branch.params)}
    for name in ("continuation", "integration"):
        value = getattr(branch, name)
        if value is not None:
            attrs[name] = json.dumps(dataclasses.asdict(value))
    return xr.Dataset(data, attrs=attrs)


def _curve_dataset(xr, curve: Curve, params):
    data = {name: _variable(xr, ("point",), np.asarray(getattr(curve, name), float), name)
            for name in ("rho", "A", "gamma", "kappa", "omega", "l1")}
    data["state"] = xr.Variable(("component", "point"), np.asarray(curve.state, float),
                                {"units": "1", "long_name": "slow-flow state (Re B1, Im B1, "
                                 "Re B2, Im B2)"})
    data["codim2"] = xr.Variable(("point",), np.array(curve.codim2, dtype=str),
                                 {"units": "1", "long_name": "codimension-2 kind ('none')"})
    attrs = {"kind": f"{curve.kind}_curve", "method": CURVE_METHOD, "complete": int(curve.complete),
             "ends": json.dumps(list(curve.ends)), "note": curve.note, **_params_attrs(params)}
    return xr.Dataset(data, attrs=attrs)


def to_dataset(result, *, params: Parameters = None):
    """The xarray Dataset of a PeriodicBranch (dimensions point and special), a charts.Curve
    (point; give the chart's params to record them) or a study's Dataset (returned as it is:
    the studies name their units and settings already). Every variable has a ``units``
    attribute; the Dataset's attributes hold kind, method and the parameters."""
    import xarray as xr
    if isinstance(result, PeriodicBranch):
        ds = _branch_dataset(xr, result)
    elif isinstance(result, Curve):
        ds = _curve_dataset(xr, result, params)
    elif isinstance(result, xr.Dataset):
        ds = result.copy()
    else:
        raise InputError(f"result is a {type(result).__name__}: give a PeriodicBranch, a "
                         "charts.Curve or a study's xarray Dataset")
    ds.attrs.setdefault("sloshdyn_version", __version__)
    return ds


def _json(value):
    """value in JSON's types (numpy scalars and arrays as numbers and lists)."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    raise TypeError(f"{type(value).__name__} cannot be written to an export file")


def _cell(value):
    if isinstance(value, (bool, np.bool_)):
        return "1" if value else "0"
    if isinstance(value, (complex, np.complexfloating)):
        return repr(complex(value))
    if isinstance(value, str):
        return value
    if isinstance(value, (np.integer, int)):
        return str(int(value))
    return repr(float(value))


def write_csv(result, path, *, params: Parameters = None):
    """Write to_dataset(result, params=params) to the CSV file `path` (written under a
    temporary name and renamed into place); returns the path."""
    ds = to_dataset(result, params=params)
    groups = {}
    for name, var in ds.variables.items():
        groups.setdefault(var.dims, []).append(name)
    with _files.atomic_path(path) as tmp, open(tmp, "w", newline="") as f:
        f.write(f"# sloshdyn export: {ds.attrs.get('kind', 'dataset')}\n")
        f.write("# dataset " + json.dumps({"attrs": ds.attrs, "coords": list(ds.coords)},
                                          default=_json) + "\n")
        for name, var in ds.variables.items():
            f.write("# variable " + json.dumps({"name": name, "dims": list(var.dims),
                                                "dtype": _dtype_name(var.dtype),
                                                "attrs": var.attrs},
                                               default=_json) + "\n")
        writer = csv.writer(f, lineterminator="\n")
        for dims, names in groups.items():
            shape = ds.variables[names[0]].shape
            f.write("# table " + json.dumps({"dims": list(dims), "shape": list(shape)}) + "\n")
            # a grid's rows start with their coordinates (read back from their own table)
            index = [d for d in dims if len(dims) > 1 and d in ds.coords
                     and ds.coords[d].dims == (d,)]
            grid = np.meshgrid(*[ds.coords[d].values for d in index], indexing="ij")
            grid = [np.broadcast_to(g.reshape([ds.sizes[d] if d in index else 1 for d in dims]),
                                    shape).reshape(-1) for g in grid]
            writer.writerow(index + names)
            columns = grid + [np.asarray(ds.variables[n].values).reshape(-1) for n in names]
            for row in zip(*columns):
                writer.writerow([_cell(v) for v in row])
    return path


def _dtype_name(dtype):
    """numpy's name of a dtype; 'T' for numpy's variable-width strings (StringDType)."""
    return "T" if dtype.kind == "T" else dtype.str


def _parse(texts, dtype):
    if dtype == "T":
        return np.array(texts, dtype=np.dtypes.StringDType())
    dtype = np.dtype(dtype)
    if dtype.kind == "b":
        return np.array([t == "1" for t in texts], dtype=bool)
    if dtype.kind == "c":
        return np.array([complex(t) for t in texts], dtype=dtype)
    if dtype.kind in "US":
        return np.array(texts, dtype=str)
    if dtype.kind in "iu":
        return np.array([int(t) for t in texts], dtype=dtype)
    return np.array([float(t) for t in texts], dtype=dtype)


def read_csv(path):
    """The Dataset of a file written by write_csv (equal to the one written: values bit for
    bit, dtypes, dimensions, coordinates and attributes)."""
    import xarray as xr
    header, variables, tables = None, {}, []
    with _files.file_error(path, "read"), open(path, newline="") as f:
        lines = f.read().splitlines()
    k = 0
    while k < len(lines):
        line = lines[k]
        if line.startswith("# dataset "):
            header = json.loads(line[len("# dataset "):])
        elif line.startswith("# variable "):
            v = json.loads(line[len("# variable "):])
            variables[v["name"]] = v
        elif line.startswith("# table "):
            table = json.loads(line[len("# table "):])
            rows = int(np.prod(table["shape"]))
            body = list(csv.reader(lines[k + 1:k + 2 + rows]))
            tables.append((table, body[0], body[1:]))
            k += 1 + rows
        k += 1
    if header is None:
        raise InputError(f"{path} is not a sloshdyn export file: it has no '# dataset' line")
    data = {}
    for table, names, rows in tables:
        for j, name in enumerate(names):
            v = variables[name]
            if v["dims"] != table["dims"]:
                continue                    # a grid's coordinate column
            values = _parse([r[j] for r in rows], v["dtype"]).reshape(table["shape"])
            data[name] = xr.Variable(tuple(v["dims"]), values, v["attrs"])
    coords = {n: data.pop(n) for n in header["coords"]}
    return xr.Dataset(data, coords=coords, attrs=header["attrs"])


def branch_from_dataset(ds) -> PeriodicBranch:
    """The PeriodicBranch of a Dataset made by to_dataset (or read_csv) from one."""
    if ds.attrs.get("kind") != "periodic_branch":
        raise InputError(f"the Dataset's kind is {ds.attrs.get('kind')!r}: it must be "
                         "'periodic_branch'")
    a = ds.attrs
    table = {name: ds[name].values for name in ("lambda", "rho", "A", "y1", "y2", "y3", "y4")}
    for i in range(1, 5):
        table[f"mu{i}"] = ds[f"mu{i}"].values
    table["max_x1"] = ds["max_x1"].values
    table["stable"] = ds["stable"].values.astype(float)
    specials = [PeriodicSpecialPoint(str(ds["special_kind"].values[j]),
                                     float(ds["special_rho"].values[j]),
                                     float(ds["special_A"].values[j]),
                                     float(ds["special_max_x1"].values[j]),
                                     np.array([ds[f"special_y{i}"].values[j]
                                               for i in range(1, 5)]))
                for j in range(ds.sizes.get("special", 0))]
    params = Parameters(**json.loads(a["parameters"])) if "parameters" in a else None
    continuation = (Continuation(**json.loads(a["continuation"])) if "continuation" in a
                    else None)
    integration = (Integration(**json.loads(a["integration"])) if "integration" in a
                   else None)
    return PeriodicBranch(a["parameter"], table, specials, bool(a["complete"]), a["message"],
                          a["integration_method"], int(a["periods"]), params,
                          tuple(a["lambda_range"]), continuation, integration)
