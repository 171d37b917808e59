"""Multiple-scales analysis (sec 3.2-3.3): the cubic expansion of the equations of motion, its
modal form and the coefficients of the solvability conditions, computed by the Fortran core."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._cancel import cancellable
from . import _checks, _core, _tables
from ._errors import InputError, check_status, message_text, with_partial
from .options import Continuation, Integration
from .parameters import Parameters

_bridge = _core.sloshdyn_bridge_asymptotics

# eq (33): g_r = sum sign * name * monomial; exponents of (x1, x2, x1', x2')
HAT_TERMS = {
    1: [("gamma_hat11", +1, (0, 0, 0, 1)), ("alpha_hat11", +1, (3, 0, 0, 0)),
        ("alpha_hat12", +1, (2, 1, 0, 0)), ("gamma_hat12", -1, (2, 0, 0, 1)),
        ("gamma_hat13", -1, (1, 0, 2, 0)), ("alpha_hat13", +1, (1, 2, 0, 0)),
        ("gamma_hat14", -1, (1, 1, 0, 1)), ("gamma_hat15", +1, (1, 0, 0, 2)),
        ("gamma_hat16", -1, (0, 1, 2, 0)), ("alpha_hat14", +1, (0, 3, 0, 0)),
        ("gamma_hat17", -1, (0, 2, 0, 1)), ("gamma_hat18", +1, (0, 1, 0, 2))],
    2: [("gamma_hat21", -1, (0, 0, 0, 1)), ("alpha_hat21", -1, (3, 0, 0, 0)),
        ("alpha_hat22", +1, (2, 1, 0, 0)), ("gamma_hat22", +1, (2, 0, 0, 1)),
        ("gamma_hat23", +1, (1, 0, 2, 0)), ("alpha_hat23", +1, (1, 2, 0, 0)),
        ("gamma_hat24", +1, (1, 1, 0, 1)), ("gamma_hat25", -1, (1, 0, 0, 2)),
        ("gamma_hat26", +1, (0, 1, 2, 0)), ("alpha_hat24", +1, (0, 3, 0, 0)),
        ("gamma_hat27", +1, (0, 2, 0, 1)), ("gamma_hat28", -1, (0, 1, 0, 2))],
}
HAT_FORCING = {1: [("F_hat12", +1, (1, 1, 0, 0)), ("F_hat13", +1, (0, 2, 0, 0))],
               2: [("F_hat21", +1, (0, 0, 0, 0)), ("F_hat22", -1, (1, 1, 0, 0)),
                   ("F_hat23", -1, (0, 2, 0, 0))]}
# eq (36): h_r = -gamma_r1 u1' - ... ; exponents of (u1, u2, u1', u2')
_MODAL = [("gamma{r}1", (0, 0, 1, 0)), ("gamma{r}2", (0, 0, 0, 1)), ("alpha{r}1", (3, 0, 0, 0)),
          ("alpha{r}2", (0, 3, 0, 0)), ("alpha{r}3", (2, 1, 0, 0)), ("alpha{r}4", (1, 2, 0, 0)),
          ("gamma{r}3", (2, 0, 0, 1)), ("gamma{r}4", (0, 2, 0, 1)), ("gamma{r}5", (2, 0, 1, 0)),
          ("gamma{r}6", (0, 2, 1, 0)), ("gamma{r}7", (1, 0, 2, 0)), ("gamma{r}8", (1, 0, 1, 1)),
          ("gamma{r}9", (1, 0, 0, 2)), ("gamma{r}10", (0, 1, 1, 1)), ("gamma{r}11", (0, 1, 2, 0)),
          ("gamma{r}12", (1, 1, 1, 0)), ("gamma{r}13", (0, 1, 0, 2)), ("gamma{r}14", (1, 1, 0, 1))]
_MODAL_FORCING = {1: [("F11", -1, (0, 0, 0, 0)), ("F12", +1, (1, 1, 0, 0)),
                      ("F13", +1, (0, 2, 0, 0)), ("F14", +1, (2, 0, 0, 0))],
                  2: [("F22", +1, (1, 1, 0, 0)), ("F23", +1, (0, 2, 0, 0)),
                      ("F24", +1, (2, 0, 0, 0))]}


def _table(exponents, coefficients, forcing=False):
    """{exponent tuple: coefficient} for one row; forcing rows carry a constant term first."""
    table = {tuple(int(e) for e in exponents[:, k]): float(coefficients[k + forcing])
             for k in range(exponents.shape[1])}
    if forcing:
        table[(0, 0, 0, 0)] = float(coefficients[0])
    return table


@dataclass(frozen=True)
class ModalCoefficients:
    """The coefficients of the multiple-scales analysis, derived from the equations of motion
    (not typed in from Appendix A, which has misprints: see docs/errata.md)."""

    omega1: float              #: eq (28)
    omega2: float
    coefficients: dict         #: {name: value}: c11..c23 and F11 (eq 36, 44, 52), the modal
    #: damping gamma11, gamma22, every named coefficient of eq (33) ('alpha_hat11', ...,
    #: 'F_hat23') and of eq (36) ('alpha11', 'gamma17', ..., 'F24')
    g: list                    #: eq (32), per row: {exponents of (x1, x2, x1', x2'): coefficient}
    g_forcing: list            #: the forcing of eq (32), per row (constant term at (0, 0, 0, 0))
    h: list                    #: eq (35), per row: {exponents of (u1, u2, u1', u2'): coefficient}
    h_forcing: list            #: the forcing of eq (35), per row


def modal_coefficients(params: Parameters) -> ModalCoefficients:
    """The coefficients of the multiple-scales analysis at the given parameters (kappa > s1,
    n >= 2, p >= 1): omega1, omega2, the named coefficients and the polynomials of eq (32) and
    (35)."""
    _checks.instance("params", params, Parameters)
    (scalars, c, exponents, g, g_forcing, h, h_forcing, status,
     message) = _bridge.modal_expansion(*params.array())
    check_status(status, message)
    result = _tables.unpack("modal_scalars", scalars)
    for r in (1, 2):
        for j in (1, 2, 3):
            result[f"c{r}{j}"] = float(c[r - 1, j - 1])
    polys = {"g": [_table(exponents, g[r]) for r in range(2)],
             "g_forcing": [_table(exponents, g_forcing[r], True) for r in range(2)],
             "h": [_table(exponents, h[r]) for r in range(2)],
             "h_forcing": [_table(exponents, h_forcing[r], True) for r in range(2)]}
    for r in (1, 2):
        for name, sign, e in HAT_TERMS[r]:
            result[name] = sign * polys["g"][r - 1][e]
        for name, sign, e in HAT_FORCING[r]:
            result[name] = sign * polys["g_forcing"][r - 1][e]
        for name, e in _MODAL:
            result.setdefault(name.format(r=r), -polys["h"][r - 1][e])
        for name, sign, e in _MODAL_FORCING[r]:
            result.setdefault(name, sign * polys["h_forcing"][r - 1][e])
    omega1, omega2 = (float(result.pop(name)) for name in ("omega1", "omega2"))
    return ModalCoefficients(omega1, omega2, {k: float(v) for k, v in result.items()}, **polys)


_COLUMNS = _tables.columns("response")
SPECIAL_KINDS = _tables.codes("special")
_SPECIAL_COLUMNS = _tables.columns("special_points") + ["column"]
#: room for the points of all branches and their special points (both front doors)
MAX_TABLE_POINTS, MAX_SPECIAL_POINTS = 20000, 200


@dataclass(frozen=True)
class SpecialPoint:
    """A fold (saddle-node) or Hopf point located on a branch of the slow flow."""

    kind: str            #: 'fold' or 'hopf'
    branch: int
    rho: float
    A: float
    a1: float            #: |u1|
    a2: float            #: |u2|
    frequency: float     #: Hopf: sqrt(C3/C1), the frequency of the emerging oscillation of the
                         #: slow flow (the beat frequency); 0 for folds


@dataclass(frozen=True)
class FrequencyResponse:
    """Branches of steady states of the slow flow with their stability (sec 3.3, 4.1-4.2).

    ``table`` maps column names to arrays over all points, branch after branch, in the order
    of each branch: lambda (the swept parameter), rho, A, a1 = |u1|, a2 = |u2|, phi1, phi2
    (eq 54), stable, special (0, 1 fold, 2 hopf), re1..re4 and im1..im4 (eigenvalues of the
    slow-flow Jacobian), C1..C4, delta2, delta3 (eq 55), re_B1 ... im_B2 (the Cartesian unknowns).
    """

    parameter: str
    resonance: str
    table: dict
    special_points: list
    complete: bool
    message: str                 #: why an incomplete response stopped ('' if complete)

    @property
    def branches(self):
        """One table (dict of arrays) per branch."""
        ids = self.table["branch"]
        return [{k: v[ids == b] for k, v in self.table.items()} for b in np.unique(ids)]

    @property
    def eigenvalues(self):
        return (np.array([self.table[f"re{i}"] for i in range(1, 5)])
                + 1j * np.array([self.table[f"im{i}"] for i in range(1, 5)])).T


def frequency_response(params: Parameters, rho_range=None, *, resonance="3:1", A_range=None,
                       continuation: Continuation = Continuation()) -> FrequencyResponse:
    """Steady states of the slow flow (eq 46 without, eq 53 with the 3:1 internal resonance)
    for rho in rho_range (A from params), or for A in A_range (rho from params): every branch
    found, with stability and the folds and Hopf points located on it.

    Raises ConvergenceError (with ``partial``, the response computed so far, marked incomplete)
    if a branch could not be finished."""
    _checks.instance("params", params, Parameters)
    _checks.instance("continuation", continuation, Continuation)
    _checks.choice("resonance", resonance, _tables.names("resonances")[0])
    parameter, (lo, hi) = continuation_range(rho_range, A_range)
    (table, n_points, special, n_special, complete, status,
     message) = cancellable(_bridge.frequency_response, *params.array(), _tables.code("resonances", resonance),
                                           _tables.code("excitation_parameters", parameter), float(lo), float(hi),
                                           continuation.array(), MAX_TABLE_POINTS, MAX_SPECIAL_POINTS)
    columns = {name: table[i, :n_points].copy() for i, name in enumerate(_COLUMNS)}
    points = []
    for column in special[:, :n_special].T:
        row = dict(zip(_SPECIAL_COLUMNS, column))
        points.append(SpecialPoint(SPECIAL_KINDS[int(row["kind"])], int(row["branch"]),
                                   *(float(row[k]) for k in ("rho", "A", "a1", "a2", "frequency"))))
    result = FrequencyResponse(parameter, resonance, columns, points, bool(complete),
                               message_text(message))
    return with_partial(result, status, message, "frequency response")


def continuation_array(continuation: Continuation, direction):
    """The core's 'continuation' layout (periodic orbits, slow-flow cycles) from the fields of
    a Continuation of the same names and the first step's direction (+1 up, -1 down)."""
    return _tables.pack("continuation", {
        name: direction if name == "direction" else getattr(continuation, name)
        for name in _tables.layout("continuation")})


def continuation_range(rho_range, A_range):
    """(parameter, (low, high)) of a continuation given in rho or in A (exactly one)."""
    if (rho_range is None) == (A_range is None):
        raise InputError("give rho_range or A_range (the parameter to continue in), not both")
    if rho_range is not None:
        return "rho", _checks.interval("rho_range", rho_range)
    return "A", _checks.interval("A_range", A_range)


def nonresonant_amplitudes(params: Parameters, rho) -> list:
    """Every real solution |u1| of eq (49) (no internal resonance) at each rho (A from params):
    a list of ascending arrays, one per rho (1 or 3 values)."""
    _checks.instance("params", params, Parameters)
    rho = np.atleast_1d(_checks.reals("rho", rho))
    if rho.ndim != 1:
        raise InputError(f"rho has shape {rho.shape}: give a number or a 1-D array")
    _checks.output_size("rho", rho.size, 4)
    amplitudes, counts, status, message = _bridge.nonresonant_amplitudes(*params.array(), rho)
    check_status(status, message)
    return [amplitudes[:c, i].copy() for i, c in enumerate(counts)]


@dataclass(frozen=True)
class SlowFlowCycle:
    """The limit cycle of the 3:1 slow flow (eq 53 in Cartesian form) beyond a Hopf point: the
    slow amplitudes oscillate with `period`, so the full motion beats with it."""

    x: np.ndarray              #: (Re B1, Im B1, Re B2, Im B2) on the cycle
    period: float              #: in tau
    beat_periods: float        #: the period in forcing periods T = 2 pi/rho
    multipliers: np.ndarray    #: Floquet multipliers of the cycle (one is 1)
    iterations: int            #: Newton shots
    method: str                #: the integration method used ('auto' resolved)


def slow_flow_cycle(params: Parameters, *, settle_periods=5000, max_periods=2000,
                    n_samples=20000, integration: Integration = Integration()) -> SlowFlowCycle:
    """The limit cycle of the 3:1 slow flow at params' rho and A (sloshdyn_slowflow_cycle): the
    slow flow integrated from rest for settle_periods forcing periods, the period guessed by
    the first return to a section (searched up to max_periods on n_samples samples), then
    cycle and period by Newton shooting with the period unknown."""
    _checks.instance("params", params, Parameters)
    _checks.instance("integration", integration, Integration)
    if not params.rho > 0:
        raise InputError(f"rho = {params.rho} is not valid: the slow flow needs rho > 0")
    period = 2 * np.pi / params.rho
    x, tau, multipliers, iterations, status, message = _bridge.slow_flow_cycle(
        *params.array(), float(settle_periods) * period, float(max_periods) * period,
        int(n_samples), integration.array())
    check_status(status, message, "slow-flow limit cycle")
    return SlowFlowCycle(x.copy(), float(tau), float(tau) / period,
                         multipliers[0] + 1j * multipliers[1], int(iterations),
                         integration.method_used)
