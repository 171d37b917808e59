"""The criticality of a Neimark-Sacker point (issue 42, item 2): PeriodicBranch.criticality's
first Lyapunov coefficient d of the map's normal form z -> e^{i theta} z (1 + beta + d |z|^2)
against the same formula (Kuznetsov 2004, secs 4.7 and 5.4) evaluated independently on scipy's
stroboscopic map of eq (10) (DOP853 on test_model's numpy equations; the complex multilinear
forms by real finite differences of the map itself, polarised, at two steps and Richardson-
extrapolated; the core takes them from the monodromy matrices of the variational equations);
and against direct simulation: past the first point (supercritical, d < 0) the orbit's
Poincare points settle on a stable invariant closed curve of mean |z|^2 = beta/(-d) to leading
order in beta = |mu| - 1 (z = <p, y - y*>, the centre-manifold coordinate).

The case: the Neimark-Sacker points of Fig 12's tank at A = 0.00075 on the branch in rho
(test_charts, test_orbit_curve_input)."""

import math

import numpy as np
import pytest

import sloshdyn
from test_branch_switching import flow
from test_orbit_curve_input import CONTINUATION, FIG12, RHO


@pytest.fixture(scope="module")
def branch():
    return sloshdyn.periodic_response(FIG12, RHO, continuation=CONTINUATION)


def scipy_ns_coefficient(p, y, h):
    """d = Re{e^{-i theta} [<p, C(q,q,qb)> + 2 <p, B(q, (I - M)^-1 B(q,qb))>
    + <p, B(qb, (e^{2 i theta} I - M)^-1 B(q,q))>]}/2 on scipy's map, step h."""
    period = 2 * math.pi / p.rho
    f = lambda z: flow(p, z, period)                                         # noqa: E731
    m = np.column_stack([(f(y + 1e-5 * e) - f(y - 1e-5 * e)) / 2e-5 for e in np.eye(4)])
    w, right = np.linalg.eig(m)
    j = min((i for i in range(4) if w[i].imag > 0), key=lambda i: abs(abs(w[i]) - 1))
    mu = w[j]
    q = right[:, j] / np.linalg.norm(right[:, j])
    w_left, left = np.linalg.eig(m.T)
    pv = left[:, np.argmin(abs(w_left - mu.conjugate()))]
    pv = pv / np.conj(np.vdot(pv, q))                 # conj(p)^T q = 1
    e = mu / abs(mu)
    r, s = q.real, q.imag

    def b_real(u, v):                                 # B(u, v), u and v real
        nu, nv = np.linalg.norm(u), np.linalg.norm(v)
        if nu == 0 or nv == 0:
            return np.zeros(4)
        u, v = u / nu, v / nv
        return nu * nv * (f(y + h * u + h * v) - f(y + h * u - h * v) - f(y - h * u + h * v)
                          + f(y - h * u - h * v)) / (4 * h * h)

    def b(a, c):                                      # complex bilinear extension
        return (b_real(a.real, c.real) - b_real(a.imag, c.imag)
                + 1j * (b_real(a.real, c.imag) + b_real(a.imag, c.real)))

    def c_cube(u):                                    # C(u, u, u), u real
        return (f(y + 2 * h * u) - 2 * f(y + h * u) + 2 * f(y - h * u) - f(y - 2 * h * u)) / (
            2 * h**3)

    crrr, csss, cp, cm = c_cube(r), c_cube(s), c_cube(r + s), c_cube(r - s)
    crrs = (cp - cm - 2 * csss) / 6
    crss = (cp + cm - 2 * crrr) / 6
    cqqqb = crrr + crss + 1j * (crrs + csss)          # (r + is)^2 (r - is), symmetrised
    w1 = np.linalg.solve(np.eye(4) - m, b(q, q.conj()).real)
    w2 = np.linalg.solve(e**2 * np.eye(4) - m, b(q, q))
    term = (np.vdot(pv, cqqqb) + 2 * np.vdot(pv, b(q, w1.astype(complex)))
            + np.vdot(pv, b(q.conj(), w2)))
    return (np.conj(e) * term).real / 2, mu


def test_neimark_sacker_coefficient_agrees_with_scipys_normal_form(branch):
    points = [s for s in branch.special_points if s.kind == "neimark_sacker"]
    assert len(points) == 2
    for point in points:
        critical = branch.criticality(point)
        assert critical.kind == "neimark_sacker"
        assert abs(abs(critical.multiplier) - 1) < 1e-6 and critical.multiplier.imag > 0
        assert critical.supercritical == (critical.coefficient < 0)
        p = FIG12.replace(rho=point.rho)
        (d1, mu), (d2, _) = (scipy_ns_coefficient(p, point.y0, h) for h in (2e-3, 1e-3))
        assert abs(mu - critical.multiplier) < 1e-6
        richardson = d2 + (d2 - d1) / 3                # the differences' error is O(h^2)
        # measured: -41.08721 against -41.08721 (1.1e-7), -2.856700 against -2.856700 (1.2e-7)
        assert critical.coefficient == pytest.approx(richardson, rel=1e-5)


def test_simulation_settles_on_the_invariant_curve_the_coefficient_predicts(branch):
    point = [s for s in branch.special_points if s.kind == "neimark_sacker"][0]
    d = branch.criticality(point).coefficient
    assert d < 0                                       # supercritical
    ratios = []
    for step in (1.5e-5, 3e-5):                        # rho past the point: the orbit unstable
        p = FIG12.replace(rho=point.rho + step)
        orbit = sloshdyn.periodic_orbit(p, point.y0)
        w, right = np.linalg.eig(orbit.monodromy)
        j = int(np.argmax(abs(w) * (w.imag > 0)))
        q = right[:, j] / np.linalg.norm(right[:, j])
        w_left, left = np.linalg.eig(orbit.monodromy.T)
        pv = left[:, np.argmin(abs(w_left - w[j].conjugate()))]
        pv = pv / np.conj(np.vdot(pv, q))
        beta = abs(w[j]) - 1
        assert beta > 0
        period, n = 2 * math.pi / p.rho, int(12 / beta)     # e^-24 of the transient left
        sim = sloshdyn.simulate(p, n * period, orbit.y0 + 1e-3 * q.real,
                                tau_out=np.arange(n + 1) * period,
                                integration=sloshdyn.Integration(rtol=1e-11, atol=1e-13))
        z = np.array([np.vdot(pv, y - orbit.y0) for y in sim.y[:, -600:].T])   # two loops
        ratios.append(np.mean(abs(z) ** 2) / (beta / -d))
    # measured 1.015 and 1.052 (1 + O(beta)); at rho + 6e-5 1.14
    assert abs(ratios[0] - 1) < 0.05 and abs(ratios[0] - 1) < abs(ratios[1] - 1) < 0.1


def test_other_kinds_are_refused(branch):
    fold = [s for s in branch.special_points if s.kind == "fold"][0]
    with pytest.raises(sloshdyn.InputError, match="'period_doubling' or a 'neimark_sacker'"):
        branch.criticality(fold)
