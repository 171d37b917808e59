"""Multiple-scales analysis (sec 3.2-3.3): the cubic expansion of the equations of motion, its
modal form and the coefficients of the solvability conditions, computed by the Fortran core."""

from __future__ import annotations

import numpy as np

from . import _core
from ._errors import check_status
from .parameters import Parameters

_bridge = _core.sloshdyn_bridge

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


def modal_coefficients(params: Parameters) -> dict:
    """The coefficients of the multiple-scales analysis at the given parameters (kappa > s1,
    n >= 2, p >= 1): omega1, omega2 (eq 28), c11..c23 and F11 (eq 36, 44, 52), the modal
    damping gamma11, gamma22, every named coefficient of eq (33) ('alpha_hat11', ...,
    'F_hat23') and of eq (36) ('alpha11', 'gamma17', ..., 'F24'), derived from the equations of
    motion (not typed in from Appendix A, which has misprints: see ERRATA.md). Also 'g', 'h',
    'g_forcing', 'h_forcing': {exponents: coefficient} polynomials of eq (32) and (35)."""
    (scalars, c, exponents, g, g_forcing, h, h_forcing, status,
     message) = _bridge.modal_expansion(*params.arrays())
    check_status(status, message)
    result = {"omega1": scalars[0], "omega2": scalars[1], "gamma11": scalars[2],
              "gamma22": scalars[3], "F11": scalars[4]}
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
    result.update(polys)
    return {k: (float(v) if isinstance(v, (float, np.floating)) else v) for k, v in result.items()}
