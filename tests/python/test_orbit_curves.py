"""Two-parameter curves of the full model started from a special point of a PeriodicBranch
(issue 42, item 1): the period-doubling curve in (rho, A) through the period doubling of Fig 12's
tank at rho = 1 (test_branch_switching's cascade: symmetric branch, branch point, asymmetric
branch, period doubling at A = 0.96828) passes through the period doublings that independent
one-parameter branches (continuation in A at three other values of rho, each switched at its own
branch point) locate, to 1e-8 in A."""

import numpy as np
import pytest

import sloshdyn
from test_branch_switching import P, Y_SYMMETRIC


def doubling_at(rho):
    """The period doubling on the asymmetric branch at rho (continuation in A)."""
    p = P.replace(rho=rho)
    symmetric = sloshdyn.periodic_response(p, A_range=(0.9, p.A), y0=Y_SYMMETRIC,
                                           from_end="high")
    asymmetric = symmetric.switch([s for s in symmetric.special_points
                                   if s.kind == "branch_point"][0])
    doublings = [s for s in asymmetric.special_points if s.kind == "period_doubling"]
    assert len(doublings) == 1
    return asymmetric, doublings[0]


@pytest.fixture(scope="module")
def curve():
    asymmetric, doubling = doubling_at(P.rho)
    return asymmetric.curve(doubling, (0.997, 1.003), (0.9, 1.05),
                            chart=sloshdyn.Chart(max_points=200))


def test_period_doubling_curve_passes_through_independent_doublings(curve):
    assert curve.kind == "period_doubling" and curve.complete
    assert curve.ends == ("box", "box")
    assert curve.rho.min() == pytest.approx(0.997) and curve.rho.max() == pytest.approx(1.003)
    for target in (0.998, 1.0015, 1.0025):             # three points of the curve
        j = int(np.argmin(np.abs(curve.rho - target)))
        rho, A = float(curve.rho[j]), float(curve.A[j])
        assert abs(rho - P.rho) > 5e-4                  # other parameter values than the start
        _, doubling = doubling_at(rho)
        assert abs(doubling.A - A) < 1e-8, (rho, doubling.A, A)   # measured 9e-12 .. 1.3e-11


def test_curves_start_only_at_their_kinds():
    asymmetric, _ = doubling_at(P.rho)
    symmetric_point = sloshdyn.PeriodicSpecialPoint("branch_point", 1.0, 1.0, 0.8, np.zeros(4))
    with pytest.raises(sloshdyn.InputError, match="a curve starts at"):
        asymmetric.curve(symmetric_point, (0.99, 1.01), (0.9, 1.05))
