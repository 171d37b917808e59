"""Research toolkit (issue 27): the Lyapunov spectrum of the full equations of motion (QR method
on the variational equations, Kaplan-Yorke dimension). Computed by the Fortran core
(sloshdyn_lyapunov, sloshdyn_tank_lyapunov)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import _checks, _core, _tables
from ._cancel import cancellable
from ._errors import check_status
from .parameters import Parameters, convert_fields
from .simulation import Integration

_bridge = _core.sloshdyn_bridge
_LYAPUNOV = _tables.defaults()["lyapunov"]


@dataclass(frozen=True)
class Lyapunov:
    """How Lyapunov exponents are measured (&lyapunov); times in forcing periods T = 2 pi/rho.
    Fields in the core's layout, with its defaults."""

    transient_periods: int = int(_LYAPUNOV[0])   #: integrated before measuring
    n_periods: int = int(_LYAPUNOV[1])           #: measured; a multiple of renormalise_every
    renormalise_every: int = int(_LYAPUNOV[2])   #: periods between QR renormalisations

    def __post_init__(self):
        convert_fields(self)

    def array(self):
        return np.array([self.transient_periods, self.n_periods, self.renormalise_every],
                        dtype=np.float64)


@dataclass(frozen=True)
class LyapunovSpectrum:
    """The four Lyapunov exponents of the full equations (per unit tau) from one start."""

    exponents: np.ndarray        #: l1 >= l2 >= l3 >= l4 once converged (the QR order)
    history: np.ndarray          #: (4, blocks): running estimates after each renormalisation
    periods: np.ndarray          #: forcing periods measured at the end of each block
    kaplan_yorke: float          #: Kaplan-Yorke dimension of the sorted exponents
    method: str = ""             #: the integration method used ('auto' resolved)

    @property
    def sum(self):
        """l1 + .. + l4: the mean phase-space contraction rate (mean trace of the Jacobian)."""
        return float(np.sum(self.exponents))


def lyapunov_spectrum(params: Parameters, y0=None, *, lyapunov: Lyapunov = Lyapunov(),
                      integration: Integration = Integration()) -> LyapunovSpectrum:
    """All four Lyapunov exponents per unit tau from y0 (default rest) by the QR method: the
    orbit and four tangent vectors of the variational equations, orthonormalised by modified
    Gram-Schmidt every renormalise_every forcing periods. The first exponent is that of
    lyapunov_exponent (Benettin's method: the same start direction), up to the step sequence."""
    _checks.instance("params", params, Parameters)
    _checks.instance("lyapunov", lyapunov, Lyapunov)
    _checks.instance("integration", integration, Integration)
    y0 = np.zeros(4) if y0 is None else _checks.reals("y0", y0, (4,))
    blocks = max(lyapunov.n_periods // max(lyapunov.renormalise_every, 1), 1)
    exponents, history, dimension, status, message = cancellable(
        _bridge.lyapunov_spectrum, *params.arrays(), y0, lyapunov.array(), integration.array(),
        blocks)
    check_status(status, message, "Lyapunov spectrum")
    periods = lyapunov.renormalise_every * np.arange(1, blocks + 1, dtype=float)
    return LyapunovSpectrum(exponents, history, periods, float(dimension),
                            integration.method_used)
