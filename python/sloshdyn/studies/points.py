"""What the studies of steady states (response maps, basins) share: the bridge's summary and
orbit layouts, the variables of a steady state at each point of a grid and their unpacking from
the bridge's point arrays, and the settings and attributes common to these studies."""

from __future__ import annotations

import dataclasses
import json

import numpy as np

from .. import _tables
from .._errors import InputError, message_text
from ..options import Integration, Steady
from .engine import Variable, version

SUMMARY_COLUMNS = _tables.columns("summary")
MOTIONS = _tables.codes("motion")
MOTION_CODES = {name: code for code, name in MOTIONS.items()}
#: the orbit rows of sloshdyn_studies (bridge steady_path / attractor_points)
ORBIT_COLUMNS = _tables.columns("study_orbit")
MAX_PERIOD = 8

MOTION_ATTRS = {
    "flag_values": [-1, 0] + list(MOTIONS),
    "flag_meanings": " ".join(["not_computed", "failed"] + [MOTIONS[k].replace("-", "_")
                                                            for k in MOTIONS]),
    "units": "1",
}


def settings_arrays(steady, integration):
    if not isinstance(steady, Steady):
        raise InputError(f"steady = {steady!r} is not valid: give a sloshdyn.Steady")
    if not isinstance(integration, Integration):
        raise InputError(f"integration = {integration!r} is not valid: give a sloshdyn.Integration")
    return steady.array(), integration.array()


def orbit_rows(orbit):
    """{column: row} of the bridge's orbit array (the core's table 'study_orbit')."""
    return dict(zip(ORBIT_COLUMNS, orbit))


def common_attrs(kind, params, steady, integration, extra):
    return {
        "title": f"sloshdyn {kind.replace('_', ' ')}",
        "study": kind,
        "sloshdyn_version": version(),
        "parameters": json.dumps(dataclasses.asdict(params)),
        "steady": json.dumps(dataclasses.asdict(steady)),
        "integration": json.dumps(dataclasses.asdict(integration)),
        "method_used": integration.method_used,   # 'auto' resolved by rtol
        **extra,
    }


def summary_variables(dims, suffix="", what="steady state from rest"):
    v = {}
    desc = {"max_x1": "max |x1| = max |theta|/theta0 over the measuring window (pendulum)",
            "max_x2": "max |x2| = max |phi|/theta0 over the measuring window (tank)",
            "max_u1": "max |u1|, first modal coordinate (eq 34)",
            "max_u2": "max |u2|, second modal coordinate (eq 34)"}
    for name, text in desc.items():
        v[name + suffix] = Variable(dims, "f8", np.nan,
                                     {"units": "1", "long_name": f"{text}; {what}"})
    v["motion" + suffix] = Variable(dims, "i1", -1, {
        **MOTION_ATTRS, "long_name": f"kind of motion judged from the Poincare points; {what}"})
    v["period" + suffix] = Variable(dims, "i2", -1, {
        "units": "forcing periods", "long_name": f"period of periodic motion (0: not periodic); {what}"})
    v["roof_impact" + suffix] = Variable(dims, "i1", -1, {
        "units": "1", "flag_values": [-1, 0, 1], "flag_meanings": "not_computed no yes",
        "long_name": f"the liquid reaches the roof: max|x1| >= 1, the pendulum at theta0 "
                     f"(eq 3-4); {what}"})
    v["status" + suffix] = Variable(dims, "i2", -1, {
        "units": "1", "long_name": f"core status of the point (0 ok, -1 not computed; else "
                                   f"sloshdyn_status codes); {what}"})
    v["message" + suffix] = message_variable(dims, what)
    return v


def message_variable(dims, what="the point"):
    return Variable(dims, "str", "", {"long_name": f"the core's message of a failed point "
                                                   f"('' where status is 0); {what}"})


def unpack(summaries, orbit, impact, status, shape, suffix="", order="C"):
    """{variable: array of `shape`} from the bridge's point arrays."""
    def grid(x):
        return np.asarray(x).reshape(shape, order=order)
    col = {name: summaries[k] for k, name in enumerate(SUMMARY_COLUMNS)}
    ok = np.asarray(status) == 0
    out = {name + suffix: grid(col[name]) for name in ("max_x1", "max_x2", "max_u1", "max_u2")}
    out["motion" + suffix] = grid(np.where(ok, np.nan_to_num(col["motion"]), 0).astype(np.int8))
    out["period" + suffix] = grid(np.where(ok, np.nan_to_num(col["period"]), 0).astype(np.int16))
    out["roof_impact" + suffix] = grid(np.where(ok, impact, 0).astype(np.int8))
    out["status" + suffix] = grid(np.asarray(status).astype(np.int16))
    return out



def point_messages(status, messages, carried=False):
    """The message of each point of a task (an object array of text, '' where the status is
    0) from the bridge's point_message: what each failed point's run alone says (the core
    leaves out the point's number, so it is the same whatever the task it ran in).
    carried: a sweep that carries its state stops at its first failure; the points after it
    say so."""
    status = np.asarray(status).ravel()
    out = np.full(status.shape, "", dtype=object)
    failed = np.nonzero(status != 0)[0]
    for k, i in enumerate(failed):
        if carried and k > 0:
            out[i] = (f"not computed: the sweep carrying the state stopped at the failure of "
                      f"the point before ({out[failed[0]]})")
        else:
            out[i] = message_text(messages[i])
    return out
