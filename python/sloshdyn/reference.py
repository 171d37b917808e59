"""Regression against tabulated reference data (data/reference): the numbers the paper quotes,
with their place and a tolerance that reflects the printed digits, and tables the project
computed at tight tolerances and confirmed by an independent method."""

from __future__ import annotations

import csv
import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import figures
from ._errors import InputError
from ._files import file_error
from .asymptotics import frequency_response, modal_coefficients
from .model import equilibrium_angles, frequency_ratio, kappa_for_detuning, linear_modes
from .options import Lyapunov, Steady
from .parameters import Parameters
from .periodic import lyapunov_exponent, periodic_response
from .simulation import spectrum, simulate, steady_state

#: the reference tables shipped with the package (a copy of data/reference and docs/errata.md)
PACKAGE_REFERENCE = Path(__file__).parent / "reference"


@dataclass(frozen=True)
class Verdict:
    quantity: str
    place: str
    reference: float
    computed: float
    tolerance: str
    passed: bool
    note: str = ""
    reason: str = ""


_KINDS_NEEDING_TOLERANCE = ("abs", "rel", "factor")
_KINDS = _KINDS_NEEDING_TOLERANCE + ("at_least", "at_most")


def bad_file(path, line, what):
    """The error of a corrupted input file of `check` (exit 3, not 1 = out of tolerance)."""
    where = f"{path}, line {line}" if line else f"{path}"
    return InputError(f"bad file: {where}: {what}")


def load(directory=None):
    """Rows of paper_values.csv and computed_values.csv (method beside each), each checked: a
    finite reference, a known tolerance kind with a finite tolerance >= 0 where the kind needs
    one, no repeated quantity. A corrupted or empty table is an InputError naming the file and
    the line."""
    directory = Path(directory) if directory else PACKAGE_REFERENCE
    rows, seen = [], {}
    for name in ("paper_values.csv", "computed_values.csv"):
        path = directory / name
        if not path.is_file():
            raise bad_file(path, None, "the reference table is missing")
        with file_error(path, "read the reference table"):
            with open(path, newline="", encoding="utf-8") as f:
                try:
                    table = [(reader.line_num, row) for reader in [csv.DictReader(f)]
                             for row in reader]
                except (csv.Error, UnicodeDecodeError) as exc:
                    raise bad_file(path, None, f"not a CSV table ({exc})") from None
        if not table:
            raise bad_file(path, None, "the table has no rows: a reference table needs at least one")
        for line, row in table:
            _check_row(path, line, row)
            if row["quantity"] in seen:
                raise bad_file(path, line, f"quantity {row['quantity']!r} appears twice "
                                           f"(also {seen[row['quantity']]})")
            seen[row["quantity"]] = f"{path.name} line {line}"
            rows.append(row)
    return rows


def _check_row(path, line, row):
    if None in row or any(v is None for v in row.values()):
        raise bad_file(path, line, "the row has a different number of fields than the header")
    for column in ("quantity", "reference", "kind"):
        if not (row.get(column) or "").strip():
            raise bad_file(path, line, f"column {column!r} is missing or empty")
    if row["kind"] not in _KINDS:
        raise bad_file(path, line, f"kind = {row['kind']!r} is not one of {', '.join(_KINDS)}")
    _number(path, line, row, "reference")
    if row["kind"] in _KINDS_NEEDING_TOLERANCE or (row.get("tolerance") or "").strip():
        tol = _number(path, line, row, "tolerance")
        if tol < 0 or (row["kind"] == "factor" and tol < 1):
            raise bad_file(path, line, f"tolerance = {tol!r} is out of range: it must be >= "
                                       f"{1 if row['kind'] == 'factor' else 0}")


def _number(path, line, row, column):
    try:
        x = float(row.get(column) or "")
    except ValueError:
        x = math.nan
    if not math.isfinite(x):
        raise bad_file(path, line, f"{column} = {row.get(column)!r} is not a finite number")
    return x


def load_values(path):
    """The values.json of a `reproduce` run: {quantity: number}; a missing, corrupted or empty
    file is an InputError naming the file (and the line of a syntax error)."""
    path = Path(path)
    if not path.exists():
        raise InputError(f"{path} not found: run `reproduce --out {path.parent}` first")
    with file_error(path, "read"):
        text = path.read_bytes()
    try:
        values = json.loads(text.decode("utf-8"))
    except UnicodeDecodeError as exc:
        raise bad_file(path, None, f"not UTF-8 text ({exc.reason})") from None
    except json.JSONDecodeError as exc:
        raise bad_file(path, exc.lineno, f"not JSON ({exc.msg}, column {exc.colno})") from None
    if not isinstance(values, dict) or not values:
        raise bad_file(path, None, "it must be a non-empty JSON object {quantity: number}")
    for name, value in values.items():
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            line = next((k + 1 for k, text_line in enumerate(text.decode().splitlines())
                         if f'"{name}"' in text_line), None)
            raise bad_file(path, line, f"{name} = {value!r} is not a number")
    return values


def judge(row, computed):
    """Apply the row's tolerance kind to a computed value (the row as load checked it)."""
    reference = float(row["reference"])
    kind = row["kind"]
    tol = float(row["tolerance"]) if row.get("tolerance") else 0.0
    if computed is None or not math.isfinite(computed):
        return False, "not computed"
    if kind == "abs":
        return abs(computed - reference) <= tol, f"±{tol:g}"
    if kind == "rel":
        return abs(computed - reference) <= tol * abs(reference), f"±{tol:g} rel"
    if kind == "at_least":
        return computed >= reference, f">= {reference:g}"
    if kind == "at_most":
        return computed <= reference, f"<= {reference:g}"
    return reference / tol <= computed <= reference * tol, f"within a factor {tol:g}"


def compute(names, quick=True):
    """Compute the named quantities with the current core."""
    values = {}
    groups = {prefix: provider for prefix, provider in _PROVIDERS}
    for name in names:
        if name in values:
            continue
        for prefix, provider in groups.items():
            if name.startswith(prefix):
                values.update(provider(quick))
                break
    return values


def check(values=None, directory=None, quick=True):
    """Compare computed values (or compute them) with every reference row."""
    rows = load(directory)
    if values is None:
        values = compute([row["quantity"] for row in rows], quick)
    verdicts = []
    for row in rows:
        computed = values.get(row["quantity"])
        computed = float(computed) if computed is not None else float("nan")
        passed, tolerance = judge(row, computed)
        verdicts.append(Verdict(row["quantity"], row.get("place") or row.get("method", ""),
                                float(row["reference"]), computed, tolerance, passed,
                                row.get("note", ""), row.get("reason", "")))
    return verdicts


def format_table(verdicts):
    lines = ["| quantity | place / method | reference | computed | tolerance | why this "
             "tolerance | verdict |", "|---|---|---|---|---|---|---|"]
    for v in verdicts:
        lines.append(f"| {v.quantity} | {v.place} | {v.reference:.10g} | {v.computed:.10g} | "
                     f"{v.tolerance} | {v.reason} | {'pass' if v.passed else 'FAIL'} |")
    return "\n".join(lines)


# value providers: each computes a group of quantities whose names start with its prefix

def _linear(quick):
    modes = linear_modes(figures.FIG12)
    return {"omega1": modes.omega1, "omega2": modes.omega2,
            "kappa_31_sigma1_0": kappa_for_detuning(1.5, 0.5, 0.0)[0],
            "kappa_31_sigma1_0005": kappa_for_detuning(1.5, 0.5, 0.005)[0],
            "kappa_31_fig14": kappa_for_detuning(1.5, 0.5, 0.005)[0],
            "sec32_sigma_tilde_31": kappa_for_detuning(1.5, 0.5, 0.0)[0] - 1.5}


def _equilibria(quick):
    values = {"fig4_beta_hat_b": figures._beta_hat_bifurcation(),
              "fig6_pitchfork_kappa_hat": figures._pitchfork()}
    for b in (0.005, 0.08):
        values[f"fig4_equilibria_beta_hat_{b}"] = len(equilibrium_angles(figures._with_beta_hat(b), "theta").angles)
    for k in (1.3, 0.9):
        values[f"fig5_equilibria_kappa_hat_{k}"] = len(equilibrium_angles(figures._with_kappa_hat(k), "phi").angles)
    return values


def _c11(quick):
    return {f"fig9{letter}_c11": modal_coefficients(Parameters(kappa=k, **figures.FIG9)).coefficients["c11"]
            for letter, k in (("a", 4.7), ("b", 4.5))}


def _fig11(quick):
    p = figures.FIG12.replace(kappa=float(kappa_for_detuning(1.5, 0.5, 0.0)[0]), gamma=0.0025)
    return {f"fig11_folds_A_{A}": sum(s.kind == "fold" for s in
                                      frequency_response(p.replace(A=A), (0.48, 0.54)).special_points)
            for A in (0.00025, 0.001)}


def _hopf(quick):
    r = frequency_response(figures.FIG12, (0.49, 0.53))
    hopf = sorted(s.rho for s in r.special_points if s.kind == "hopf")
    return {f"fig13_hopf_rho_{i + 1}": h for i, h in enumerate(hopf)}


def _fig14(quick):
    _, _, beat, slow_beat = figures.fig14_beats(quick=True)
    return {"beat_fig14_simulation": beat, "beat_fig14_slow_flow": slow_beat,
            "beat_fig14_ratio": beat / slow_beat}


def _fig15(quick):
    p = figures.FIG12.replace(rho=0.513)
    st = steady_state(p)
    period = 2 * math.pi / p.rho
    tau = np.arange(256 * 32 + 1) * period / 32
    sim = simulate(p, tau[-1], st.y_end, tau_out=tau)
    line = spectrum(sim.x1[:-1], period / 32, window=None)
    omega, amp = line.omega, line.amplitude
    top = omega[np.argsort(amp)[::-1][:2]] / p.rho
    return {"fig15_max_x1": st.max_x1, "fig15_first_line_over_rho": min(top),
            "fig15_second_line_over_rho": max(top),
            "fig15_max_x1_over_slow_flow": st.max_x1 / _slow_flow_fig15_max_x1(p)}


def _slow_flow_fig15_max_x1(p):
    """max|x1| of the slow flow's stable steady state of least |B1| at p's rho (the one a
    start from rest reaches), from the stable branch points that bracket rho."""
    response = frequency_response(p, (0.49, 0.53))
    found = []
    for b in response.branches:
        x = b["rho"]
        for k in range(len(x) - 1):
            if (x[k] - p.rho) * (x[k + 1] - p.rho) <= 0 and x[k] != x[k + 1] and b["stable"][k]:
                w = (p.rho - x[k]) / (x[k + 1] - x[k])
                b1, b2 = ((1 - w) * (b[f"re_{n}"][k] + 1j * b[f"im_{n}"][k])
                          + w * (b[f"re_{n}"][k + 1] + 1j * b[f"im_{n}"][k + 1]) for n in ("B1", "B2"))
                found.append((abs(b1), b1, b2))
    _, b1, b2 = min(found, key=lambda item: item[0])
    return float(figures.slow_flow_max_x1(p, [b1], [b2])[0])


def _fig17(quick):
    p, states = figures._continuation(quick=True)
    y0, _ = states[2.0]
    q = p.replace(A=2.0)
    sim = simulate(q, 128 * 2 * math.pi / q.rho, y0, n_out=128 * 32 + 1)
    return {"fig17_max_x1": float(np.max(np.abs(sim.x1)))}


def _computed(quick):
    """The quantities of computed_values.csv."""
    p = figures.FIG12
    response = frequency_response(p, (0.49, 0.53))
    values = {}
    for rho in (0.505, 0.508, 0.5105, 0.511):
        values.update(_slow_flow_point(response, rho))
    # the row's source integrates 3015 + 200 periods: the integration-only path (shooting
    # jumps to the orbit itself, whose maxima lie ~1.5e-6 away, the transient's remainder)
    st = steady_state(p.replace(rho=0.513), steady=Steady(shooting=False))
    values["steady_fig15_max_x1"] = st.max_x1
    values["steady_fig15_max_u1"] = st.max_u1
    for sigma_t, mu_t in ((0.305, 0.5), (1.0, 0.5), (3.0, 0.1)):
        values[f"ratio_sigma_{sigma_t}_mu_{mu_t}"] = frequency_ratio(sigma_t, mu_t)
    return values


def _slow_flow_point(response, rho):
    """a1, a2 of the (single) branch point at rho, by interpolation of the Cartesian unknowns
    between the bracketing points (the points are dense enough for 1e-6)."""
    for b in response.branches:
        x = b["rho"]
        for k in range(len(x) - 1):
            if (x[k] - rho) * (x[k + 1] - rho) <= 0 and x[k] != x[k + 1] and b["stable"][k]:
                w = (rho - x[k]) / (x[k + 1] - x[k])
                b1 = (1 - w) * (b["re_B1"][k] + 1j * b["im_B1"][k]) + w * (b["re_B1"][k + 1] + 1j * b["im_B1"][k + 1])
                b2 = (1 - w) * (b["re_B2"][k] + 1j * b["im_B2"][k]) + w * (b["re_B2"][k + 1] + 1j * b["im_B2"][k + 1])
                return {f"slowflow_rho_{rho}_a1": abs(b1), f"slowflow_rho_{rho}_a2": abs(b2)}
    return {}


def _full_model(quick):
    branch = periodic_response(figures.FIG12.replace(rho=0.50), (0.50, 0.52))
    ns = sorted(s.rho for s in branch.special_points if s.kind == "neimark_sacker")
    return {f"full_ns_rho_{i + 1}": r for i, r in enumerate(ns)}


def _lyapunov(quick):
    values = {}
    for name, p, steady in (("lyapunov_fig14", figures.FIG12, Steady(settle_tol=0, transient_periods=5000)),
                            ("lyapunov_fig15", figures.FIG12.replace(rho=0.513), Steady()),
                            ("lyapunov_fig17", figures.FIG12.replace(rho=0.513, A=2.0),
                             Steady(max_transient_periods=2000))):
        st = steady_state(p, steady=steady)
        values[name] = lyapunov_exponent(p, st.y_end, lyapunov=Lyapunov(
            transient_periods=100, n_periods=2000)).exponent
    return values


_PROVIDERS = [("full_ns", _full_model), ("lyapunov", _lyapunov), ("omega", _linear), ("kappa_31", _linear), ("sec32", _linear),
              ("fig4", _equilibria), ("fig5", _equilibria), ("fig6", _equilibria),
              ("fig9", _c11), ("fig11", _fig11), ("fig13", _hopf), ("beat", _fig14),
              ("fig15", _fig15), ("fig17", _fig17), ("slowflow", _computed),
              ("steady", _computed), ("ratio", _computed)]
