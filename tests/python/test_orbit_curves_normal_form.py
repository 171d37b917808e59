"""Codimension-2 points of the normal forms on the full model's two-parameter curves (issue 42,
item 1): the generalised flip (the flip coefficient c = 0) on a period-doubling curve and the
Chenciner point (the Neimark-Sacker coefficient d = 0) on a Neimark-Sacker curve, detected in
the core while PeriodicBranch.curve continues the curve (the coefficients of
PeriodicBranch.criticality as test functions, sloshdyn_map_bifurcation), against an
independent location: scipy's brentq on the coefficient's sign in rho, each value from an
independent one-parameter branch in A at that rho (its special point located by the branch,
its coefficient by criticality); the namelist's periodic_curve_codim2.csv names the point as
Python does.

The cases (docs/model.md, "Curves from a special point"): Fig 12's tank (test_branch_switching's
P) at gamma = 0.02, the period-doubling curve of the asymmetric orbits through the subcritical
period doubling of test_criticality_simulation (rho = 0.75, A = 1.10775), followed here near
rho = 0.727 where c changes sign; at gamma = 0.05, the Neimark-Sacker curve of the symmetric
orbits through the subcritical point of test_criticality_simulation (rho = 0.7, A = 1.48815),
near rho = 0.7357 where d changes sign. The orbits below continue those (periodic_orbit
stepped in rho by 0.001)."""

import functools

import numpy as np
import pytest
from scipy.optimize import brentq

import sloshdyn
from conftest import read_csv, run, write
from test_branch_switching import P
from test_one_reader import sys_exe

GENERALISED_FLIP = ("period_doubling", "generalised_flip", P.replace(gamma=0.02, rho=0.727),
                    (1.005, 1.03), (0.7265, 0.7275), (0.99, 1.05),
                    [0.008149924157067823, 0.2827596261672893, -0.08240825742523673,
                     1.0205838092358839])
CHENCINER = ("neimark_sacker", "chenciner", P.replace(gamma=0.05, rho=0.7357), (1.54, 1.58),
             (0.735, 0.7365), (1.5, 1.6),
             [0.06591991159603433, -0.18224594465616673, -0.1701221418602872,
              1.2142645395851765])


def one_parameter(case, rho):
    """The branch in A at rho from the case's orbit, and its one special point of the kind."""
    kind, _, params, (a0, a1), _, _, y0 = case
    start = params.replace(rho=rho, A=a0)
    branch = sloshdyn.periodic_response(start, A_range=(a0, a1),
                                        y0=sloshdyn.periodic_orbit(start, y0).y0)
    points = [s for s in branch.special_points if s.kind == kind]
    assert len(points) == 1
    return branch, points[0]


POINTS = 300
CASES = {case[1]: case for case in (GENERALISED_FLIP, CHENCINER)}


@functools.cache
def curve_of(codim2):
    """The case's curve from the special point of its branch at the case's rho."""
    case = CASES[codim2]
    _, _, params, _, rho_box, A_box, _ = case
    branch, point = one_parameter(case, params.rho)
    return branch.curve(point, rho_box, A_box, chart=sloshdyn.Chart(max_points=POINTS))


@pytest.mark.parametrize("codim2", CASES)
def test_codim2_point_of_the_normal_form_where_brentq_finds_it(codim2):
    case = CASES[codim2]
    kind, _, _, _, rho_box, _, _ = case
    curve = curve_of(codim2)
    assert curve.kind == kind and curve.complete and curve.ends == ("box", "box")
    found = [i for i, k in enumerate(curve.codim2) if k == codim2]
    assert len(found) == 1, curve.codim2
    rho, A = float(curve.rho[found[0]]), float(curve.A[found[0]])

    def coefficient(r):
        b, s = one_parameter(case, r)
        coefficient.point = s
        return b.criticality(s).coefficient

    # the coefficient changes sign across the box (brentq needs the bracket)
    rho_star = brentq(coefficient, *rho_box, xtol=1e-10)
    coefficient(rho_star)
    # measured: generalised flip (0.727077737, 1.016768255) against (0.727077767, 1.016768361),
    # Chenciner (0.735639303, 1.560266241) against (0.735639268, 1.560266167): 3e-8 in rho,
    # 1.1e-7 and 7e-8 in A, the coefficients' noise (~1e-7, differences of monodromy
    # matrices) over their slope along the curve
    assert abs(rho - rho_star) < 1e-6 and abs(A - coefficient.point.A) < 1e-6, (
        rho, A, rho_star, coefficient.point.A)


def test_the_namelist_names_the_point_where_python_finds_it(tmp_path):
    # the branch from the orbit's start y0 (stable there: the steady state of &steady is it)
    kind, codim2, params, (a0, a1), (r0, r1), _, y0 = CHENCINER
    curve = curve_of(codim2)
    write(tmp_path, f"&model s1 = 1.5, mu1 = 0.5, kappa = 1.804897259, "
          f"theta0 = 0.7853981633974483, gamma = {params.gamma} /\n"
          f"&excitation A = {a0}, rho = {params.rho} /\n"
          f"&simulation y0 = {', '.join(map(repr, y0))} /\n"
          "&analysis kind = 'periodic_response' /\n"
          f"&response parameter = 'A', start = {a0}, stop = {a1}, max_points = {POINTS}, "
          f"curve_at = 1, curve_start = {r0}, curve_stop = {r1} /\n"
          "&output directory = 'out' /\n")
    exe = run(sys_exe(), "input.nml", tmp_path)
    assert exe.returncode == 0, exe.stdout + exe.stderr
    assert [r["kind"] for r in read_csv(tmp_path / "out" / "periodic_special_points.csv")] == [
        kind]
    rows = read_csv(tmp_path / "out" / "periodic_curve_codim2.csv")
    found = [i for i, k in enumerate(curve.codim2) if k == codim2]
    assert [r["kind"] for r in rows] == [codim2] and len(found) == 1
    # the executable's orbit comes from a simulation, then shooting: not bit for bit Python's,
    # and the located zero moves with the coefficient's noise (measured 1.7e-9 in rho, 3.7e-9
    # in A)
    assert abs(rows[0]["rho"] - curve.rho[found[0]]) < 1e-7
    assert abs(rows[0]["A"] - curve.A[found[0]]) < 1e-7
    assert rows[0]["omega"] == pytest.approx(curve.omega[found[0]], abs=1e-6)   # theta


def test_the_chenciner_point_next_to_the_1_1_resonance_is_one():
    """Fig 12's Neimark-Sacker curve (gamma = 0.001, through the point of the branch in rho at
    A = 0.00075) has a Chenciner point at theta = 0.0166, close to the 1:1 resonance where the
    normal form's (I - A)^-1 grows like 1/theta: d changes sign through a zero, not a pole
    (measured -5.95 and +5.40 at the curve's neighbouring points, each from its own branch in
    A), where brentq on d from independent branches in A finds it."""
    from test_orbit_curve_input import FIG12, RHO, branch_at
    branch = branch_at(FIG12.A)
    start = [s for s in branch.special_points if s.kind == "neimark_sacker"][0]
    curve = branch.curve(start, RHO, (1e-4, 1.5e-3), chart=sloshdyn.Chart(max_points=POINTS))
    found = [i for i, k in enumerate(curve.codim2) if k == "chenciner"]
    assert curve.complete and len(found) == 1, curve.codim2
    i = found[0]
    assert 0.01 < curve.omega[i] < 0.03                    # theta, next to the 1:1 resonance

    def coefficient(rho):
        """d at the Neimark-Sacker point of the branch in A at rho, grown from the curve's
        orbit nearest in rho (within 3e-5 of its A: one crossing there)."""
        k = int(np.argmin(np.abs(curve.rho[i - 2:i + 3] - rho))) + i - 2
        lo = curve.A[k] - 3e-5
        params = FIG12.replace(rho=rho, A=lo)
        branch = sloshdyn.periodic_response(
            params, A_range=(lo, lo + 6e-5),
            y0=sloshdyn.periodic_orbit(params, curve.state[:, k]).y0)
        points = [s for s in branch.special_points if s.kind == "neimark_sacker"]
        assert len(points) == 1
        coefficient.point = points[0]
        return branch.criticality(points[0]).coefficient

    before, after = coefficient(curve.rho[i - 1]), coefficient(curve.rho[i + 2])
    assert before * after < 0 and min(abs(before), abs(after)) > 1     # a zero, not a pole
    rho_star = brentq(coefficient, curve.rho[i + 2], curve.rho[i - 1], xtol=1e-12)
    coefficient(rho_star)
    assert abs(curve.rho[i] - rho_star) < 1e-8 and abs(curve.A[i] - coefficient.point.A) < 1e-8, (
        curve.rho[i], curve.A[i], rho_star, coefficient.point.A)
