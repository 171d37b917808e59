"""The spatial model (issue 26): the tank on rods that tilt in x and y, the sloshing mass as a
spherical pendulum, ground motion in two horizontal components, and swirl. Computed by the
Fortran core (sloshdyn_spatial); docs/model.md, "Spatial model and swirl", derives it.

The state is y = (x1, x1', x2, x2', y1, y1', y2, y2'): x1 = theta_x/theta0 and x2 = phi_x/theta0
in the xz plane as in the planar model, y1 = theta_y/theta0 and y2 = phi_y/theta0 out of it.
The second component of harmonic ground motion is set by keywords: ``azimuth`` (rad, the
direction of the motion A sin(rho tau) from the x axis) and ``ellipticity`` (the ellipse's
minor over major axis; the minor axis moves as ellipticity A cos(rho tau)).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import _checks, _core, _tables
from ._errors import check_status
from .parameters import Parameters

_bridge = _core.sloshdyn_bridge_spatial


def _spatial_array(azimuth, ellipticity):
    return _tables.pack("spatial", {"azimuth": _checks.real("azimuth", azimuth),
                                    "ellipticity": _checks.real("ellipticity", ellipticity)})


@dataclass(frozen=True)
class SpatialMotion:
    """The spatial equations at one state (docs/model.md, eq S7)."""

    mass: np.ndarray              #: inertia matrix M (4x4; unknowns x1'', x2'', y1'', y2'')
    dydt: np.ndarray              #: (x1', x1'', x2', x2'', y1', y1'', y2', y2'')
    jacobian: np.ndarray          #: analytic d(dydt)/dy, 8x8
    energy: float                 #: T + V relative to the ground [M L^2 omega^2]
    angular_momentum: float       #: about the vertical, relative to the ground [M L^2 omega]


def equations_of_motion(params: Parameters, tau, y, *, azimuth=0.0,
                        ellipticity=0.0) -> SpatialMotion:
    """Evaluate the spatial equations (eq S7) with the ground motion of params (A, rho) along
    ``azimuth`` and ``ellipticity`` times it across, at state y (8 entries)."""
    _checks.instance("params", params, Parameters)
    y, tau = _checks.reals("y", y, (8,)), _checks.real("tau", tau)
    mass, dydt, jac, invariants, status, message = _bridge.spatial_equations(
        *params.array(), _spatial_array(azimuth, ellipticity), tau, y)
    check_status(status, message)
    return SpatialMotion(mass, dydt, jac, float(invariants[0]), float(invariants[1]))
