"""Branch switching of the full model's periodic orbits (PeriodicBranch.switch): the
symmetry-breaking branch point of a Z2-symmetric orbit, a period doubling on the asymmetric
branch and the doubled orbits, checked by an independent shooting (scipy's DOP853 on eq 10 and
scipy.optimize.root) and by the Floquet multipliers of scipy's monodromy matrix.

The case (docs/model.md, "Branch switching"): Fig 12's tank at rho = 1 and gamma = 0.001, in the
impact regime (max|x1| ~ 0.85). The symmetric orbit below is the one of the branch continued in A
from A = 0.01 (it passes folds and Neimark-Sacker points first), at A = 1.04518."""

import dataclasses
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import root

import sloshdyn
from sloshdyn import InputError
from test_model import eq10_numpy

P = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=math.pi / 4, gamma=0.001,
                        rho=1.0, A=1.0451820685183326)
Y_SYMMETRIC = [-0.7309371728027403, 0.7465831246171408, 0.730688906743233, -2.7171951275930177]


def flow(p, y0, t_end):
    """y(t_end) from y0 at tau = 0 by scipy's DOP853 on eq (10)."""
    sol = solve_ivp(lambda t, y: eq10_numpy(p, t, y), (0, t_end), y0, method="DOP853",
                    rtol=1e-12, atol=1e-13)
    return sol.y[:, -1]


def monodromy(p, y0, t_end, h=1e-6):
    """The monodromy matrix by central differences of scipy's flow."""
    return np.column_stack([(flow(p, y0 + h * e, t_end) - flow(p, y0 - h * e, t_end)) / (2 * h)
                            for e in np.eye(4)])


def at(branch, i):
    """The parameters and the orbit's start of point i of a branch in A."""
    y0 = np.array([branch.table[f"y{k}"][i] for k in range(1, 5)])
    return P.replace(A=float(branch.table["A"][i])), y0


@pytest.fixture(scope="module")
def branches():
    symmetric = sloshdyn.periodic_response(P, A_range=(0.9, P.A), y0=Y_SYMMETRIC,
                                           from_end="high")
    branch_point = [s for s in symmetric.special_points if s.kind == "branch_point"]
    asymmetric = symmetric.switch(branch_point[0])
    doubling = [s for s in asymmetric.special_points if s.kind == "period_doubling"]
    doubled = asymmetric.switch(doubling[0])
    return symmetric, branch_point, asymmetric, doubling, doubled


def test_symmetric_orbit_breaks_its_symmetry_at_the_branch_point(branches):
    symmetric, branch_point, asymmetric, _, _ = branches
    assert len(branch_point) == 1 and branch_point[0].A == pytest.approx(1.00695, abs=1e-4)
    assert asymmetric.complete and asymmetric.periods == 1
    half = math.pi / P.rho
    # Z2: y -> -y with tau -> tau + T/2 (X'' changes sign): y(T/2) = -y(0) on the symmetric
    # branch (scipy), not on the switched one, whose orbits are T-periodic (scipy)
    p, y0 = at(symmetric, 0)
    assert np.max(np.abs(flow(p, y0, half) + y0)) < 1e-8
    p, y0 = at(asymmetric, -1)
    assert np.max(np.abs(flow(p, y0, 2 * half) - y0)) < 1e-8
    assert np.max(np.abs(flow(p, y0, half) + y0)) > 1e-2
    # the new branch starts at the branch point
    assert abs(asymmetric.table["A"][0] - branch_point[0].A) < 1e-3
    # at the branch point a multiplier of scipy's monodromy matrix is +1 (a branch point is
    # located where the corrector's matrix turns singular: to |mu - 1| ~ 4e-4 here)
    p, y0 = P.replace(A=branch_point[0].A), branch_point[0].y0
    mu = np.linalg.eigvals(monodromy(p, y0, 2 * half))
    assert np.min(np.abs(mu - 1)) < 1e-3


def test_period_doubling_on_the_asymmetric_branch(branches):
    _, _, asymmetric, doubling, _ = branches
    assert len(doubling) == 1 and doubling[0].A == pytest.approx(0.96828, abs=1e-4)
    p, y0 = P.replace(A=doubling[0].A), doubling[0].y0
    mu = np.linalg.eigvals(monodromy(p, y0, 2 * math.pi / P.rho))    # scipy: a multiplier -1
    assert np.min(np.abs(mu + 1)) < 1e-4


def test_doubled_orbit_by_independent_shooting(branches):
    _, _, _, doubling, doubled = branches
    assert doubled.complete and doubled.periods == 2
    assert abs(doubled.table["A"][0] - doubling[0].A) < 1e-3
    t2 = 4 * math.pi / P.rho
    p, y0 = at(doubled, len(doubled.table["A"]) // 2)
    # scipy's shooting on y(2T) - y0 = 0 from a start 1e-3 off the core's orbit
    sol = root(lambda y: flow(p, y, t2) - y, y0 + 1e-3, method="hybr", tol=1e-13)
    assert sol.success
    assert np.max(np.abs(sol.x - y0)) < 1e-8
    # of period 2T, not T
    assert np.max(np.abs(flow(p, y0, t2 / 2) - y0)) > 1e-2


def test_doubled_branch_has_its_own_period_doubling(branches):
    """The cascade goes on: the doubled orbits double again (period 4T) at A = 0.963757."""
    _, _, _, _, doubled = branches
    again = [s for s in doubled.special_points if s.kind == "period_doubling"]
    assert len(again) == 1 and again[0].A == pytest.approx(0.96376, abs=1e-4)
    mu = np.linalg.eigvals(monodromy(P.replace(A=again[0].A), again[0].y0, 4 * math.pi / P.rho))
    assert np.min(np.abs(mu + 1)) < 1e-4


def test_switch_needs_a_branch_point_or_a_period_doubling(branches):
    symmetric, branch_point, asymmetric, _, _ = branches
    fold = dataclasses.replace(branch_point[0], kind="fold")
    with pytest.raises(InputError, match="special_point.kind"):
        symmetric.switch(fold)
    with pytest.raises(InputError, match="special_point"):
        asymmetric.switch("period_doubling")


def test_namelist_switch_at_writes_the_switched_branch(tmp_path):
    """&response switch_at = 1: the executable follows the branch born at the first special
    point (here the symmetry-breaking branch point of rho = 0.3, A = 1.5871), as
    PeriodicBranch.switch does (one core: the same orbits to the start's round-off; the
    start states come from simulations with different &steady settings)."""
    from conftest import run, write
    from test_one_reader import MODEL, sys_exe
    p = P.replace(rho=0.3, A=1.55)
    text = (MODEL + "&excitation A = 1.55, rho = 0.3 /\n&analysis kind = 'periodic_response' /\n"
            "&response parameter = 'A', start = 1.55, stop = 1.62, switch_at = 1 /\n"
            "&output directory = 'out' /\n")
    write(tmp_path, text)
    exe = run(sys_exe(), "input.nml", tmp_path)
    assert exe.returncode == 0, exe.stderr
    assert "The branch born at the branch_point 1 (orbits of period 1 T)" in exe.stdout
    table = np.loadtxt(tmp_path / "out" / "periodic_switched_branch.csv", delimiter=",",
                       skiprows=1, ndmin=2)
    branch = sloshdyn.periodic_response(p, A_range=(1.55, 1.62))
    assert [s.kind for s in branch.special_points] == ["branch_point"]
    switched = branch.switch(branch.special_points[0])
    assert table.shape[0] == len(switched.table["A"])
    assert np.allclose(table[:, 0], switched.table["A"], rtol=0, atol=1e-7)
    assert np.allclose(table[:, 1:5].T, [switched.table[f"y{i}"] for i in range(1, 5)],
                       rtol=0, atol=1e-6)
    # the switched orbits are T-periodic but not Z2-symmetric (scipy)
    y0 = table[-1, 1:5]
    q = p.replace(A=float(table[-1, 0]))
    assert np.max(np.abs(flow(q, y0, 2 * math.pi / 0.3) - y0)) < 1e-8
    assert np.max(np.abs(flow(q, y0, math.pi / 0.3) + y0)) > 1e-2


def test_namelist_switch_at_must_name_a_branch_point_or_a_period_doubling(tmp_path):
    from conftest import run, write
    from test_one_reader import MODEL, sys_exe
    for switch_at, words in ((2, "switch_at = 2 is out of range: the branch has 1 special"),
                             (-1, "switch_at = -1 is out of range: it must be >= 0")):
        text = (MODEL + "&excitation A = 1.55, rho = 0.3 /\n"
                "&analysis kind = 'periodic_response' /\n"
                f"&response parameter = 'A', start = 1.55, stop = 1.62, switch_at = {switch_at} /\n"
                "&output directory = 'out' /\n")
        write(tmp_path, text)
        exe = run(sys_exe(), "input.nml", tmp_path)
        assert exe.returncode != 0
        assert words in exe.stdout + exe.stderr
