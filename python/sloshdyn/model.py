"""Equations of motion, linear analysis and equilibria, computed by the Fortran core."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import _checks, _core, _tables
from ._errors import InputError, check_status
from .parameters import Parameters

_bridge = _core.sloshdyn_bridge_model
MAX_EQUILIBRIA = 4096
MAX_ROOTS = 256
VERDICTS = _tables.codes("verdict")


@dataclass(frozen=True)
class Motion:
    """Equations of motion at one state: M Q'' = F (eq 12-14), y' (eq 15) and dy'/dy."""

    mass: np.ndarray      #: inertia matrix M, eq (13)
    force: np.ndarray     #: forcing vector F, eq (14)/(31)
    dydt: np.ndarray      #: (x1', x1'', x2', x2'')
    jacobian: np.ndarray  #: analytic d(dydt)/dy, 4x4


def equations_of_motion(params: Parameters, tau, y) -> Motion:
    """Evaluate eq (13)-(15) with X = A sin(rho tau) at state y = (x1, x1', x2, x2')."""
    _checks.instance("params", params, Parameters)
    y, tau = _checks.reals("y", y, (4,)), _checks.real("tau", tau)
    mass, force, dydt, jac, status, message = _bridge.equations_of_motion(*params.array(), tau, y)
    check_status(status, message)
    return Motion(mass, force, dydt, jac)


@dataclass(frozen=True)
class LinearModes:
    """Linear analysis about the trivial equilibrium (sec 3.2)."""

    omega1: float               #: eq (28)
    omega2: float               #: eq (28)
    omega1_dgeev: float         #: from the eigenvalues of the undamped linearised equations
    omega2_dgeev: float         #: (these four: the core's 'natural_frequencies' layout)
    stiffness: np.ndarray       #: K of eq (26)
    modal: np.ndarray           #: P of eq (34), x = P u
    modal_inverse: np.ndarray   #: P^-1

    @property
    def ratio(self):
        return self.omega2 / self.omega1


def linear_modes(params: Parameters) -> LinearModes:
    """Natural frequencies by eq (28) and by dgeev, K, P and P^-1 (needs kappa > s1)."""
    _checks.instance("params", params, Parameters)
    omegas, k, p, p_inv, status, message = _bridge.natural_frequencies(*params.array())
    check_status(status, message)
    omega = {name: float(w) for name, w in _tables.unpack("natural_frequencies", omegas).items()}
    return LinearModes(**omega, stiffness=k, modal=p, modal_inverse=p_inv)


def frequency_ratio(sigma_tilde, mu_tilde) -> np.ndarray:
    """omega2/omega1 as a function of sigma~ = kappa - s1 and mu~ = 1 - mu1 (Fig 7, 8);
    broadcasts like numpy."""
    sigma_tilde, mu_tilde = _checks.reals("sigma_tilde", sigma_tilde), _checks.reals("mu_tilde",
                                                                                      mu_tilde)
    try:
        sigma_tilde, mu_tilde = np.broadcast_arrays(sigma_tilde, mu_tilde)
    except ValueError:
        raise InputError(f"sigma_tilde has shape {sigma_tilde.shape} and mu_tilde "
                         f"{mu_tilde.shape}: they must broadcast together") from None
    _checks.output_size("sigma_tilde", sigma_tilde.size)
    if sigma_tilde.size == 0:
        return np.zeros(sigma_tilde.shape)
    ratio, status, message = _bridge.frequency_ratios(sigma_tilde.ravel(), mu_tilde.ravel())
    check_status(status, message)
    return ratio.reshape(sigma_tilde.shape) if sigma_tilde.ndim else float(ratio[0])


def kappa_for_detuning(s1, mu1, sigma1, kappa_min=None, kappa_max=None) -> np.ndarray:
    """All kappa in (max(kappa_min, s1), kappa_max] with omega2 - 3 omega1 = sigma1 (eq 51),
    ascending; kappa_max defaults to s1 + 1000."""
    s1, mu1, sigma1 = (_checks.real(n, v) for n, v in (("s1", s1), ("mu1", mu1),
                                                        ("sigma1", sigma1)))
    kappa_min = _checks.optional_real("kappa_min", kappa_min, 0.0)
    kappa_max = _checks.optional_real("kappa_max", kappa_max, s1 + 1000.0)
    roots, n, status, message = _bridge.kappa_for_detuning(s1, mu1, sigma1, kappa_min, kappa_max,
                                                           MAX_ROOTS)
    check_status(status, message)
    return roots[:n].copy()


@dataclass(frozen=True)
class EquilibriumAngles:
    """The real roots of eq (17) or eq (18)."""

    which: str                 #: 'theta' (eq 17) or 'phi' (eq 18)
    angles: np.ndarray         #: the roots [rad], ascending
    truncated: bool            #: the search stopped at |angle| = 32 pi


def equilibrium_angles(params: Parameters, which: str) -> EquilibriumAngles:
    """Real roots of eq (17) (which='theta') or eq (18) (which='phi') in radians, ascending,
    and whether the search stopped at |angle| = 32 pi."""
    _checks.instance("params", params, Parameters)
    code = {"theta": 1, "phi": 2}[_checks.choice("which", which, ("theta", "phi"))]
    roots, n, truncated, status, message = _bridge.equilibrium_angles(*params.array(), code,
                                                                      MAX_ROOTS)
    check_status(status, message)
    return EquilibriumAngles(which, roots[:n].copy(), bool(truncated))


@dataclass(frozen=True)
class Equilibrium:
    """One equilibrium of the unforced system (sec 3.1)."""

    theta: float               #: pendulum angle [rad], a root of eq (17)
    phi: float                 #: rod angle [rad], a root of eq (18)
    physical: bool             #: both angles inside (-pi/2, pi/2)
    eigenvalues: np.ndarray    #: of the 4x4 Jacobian (LAPACK dgeev), complex
    verdict: str               #: 'stable', 'marginal' or 'unstable'

    @property
    def stable(self):
        return self.verdict == "stable"


@dataclass(frozen=True)
class Equilibria:
    """All equilibria with their stability, and Routh-Hurwitz of eq (20) at the trivial one."""

    points: list
    truncated: bool                    #: roots beyond |angle| = 32 pi were not searched
    routh_coefficients: np.ndarray     #: c1..c4 of eq (20)
    routh_delta2: float
    routh_delta3: float
    routh_stable: bool

    def __iter__(self):
        return iter(self.points)

    def __len__(self):
        return len(self.points)

    @property
    def trivial(self) -> Equilibrium:
        return next(e for e in self.points if e.theta == 0 and e.phi == 0)


def equilibria(params: Parameters) -> Equilibria:
    """Every equilibrium (theta, phi) of eq (16)-(18) with eigenvalues and verdict."""
    _checks.instance("params", params, Parameters)
    (theta, phi, physical, re, im, verdict, n, truncated, routh, status,
     message) = _bridge.equilibria(*params.array(), MAX_EQUILIBRIA)
    check_status(status, message)
    points = [Equilibrium(float(theta[i]), float(phi[i]), bool(physical[i]),
                          re[:, i] + 1j * im[:, i], VERDICTS[int(verdict[i])]) for i in range(n)]
    routh = _tables.unpack("routh", routh)
    return Equilibria(points, bool(truncated), np.array([routh[f"c{i}"] for i in range(1, 5)]),
                      float(routh["delta2"]), float(routh["delta3"]), bool(routh["routh_stable"]))
