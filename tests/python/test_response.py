"""Slow-flow frequency responses (sec 3.3, 4.1-4.2) against the paper's numbers, the paper's own
polar slow flow (eq 53) solved independently by scipy, eq (49)-(50), and direct simulation."""

import math

import numpy as np
import pytest
from scipy.optimize import root

import sloshdyn

FIG12 = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=math.pi / 4,
                            gamma=0.001, A=0.00075)
FIG9 = dict(s1=1.5, mu1=0.5, theta0=math.pi / 4, gamma=0.0025, A=0.0005)


@pytest.fixture(scope="module")
def fig12_response():
    return sloshdyn.frequency_response(FIG12, (0.49, 0.53))


def test_fig12_hopf_points_match_the_paper(fig12_response):
    hopf = sorted(s.rho for s in fig12_response.special_points if s.kind == "hopf")
    assert len(hopf) == 2
    assert abs(hopf[0] - 0.50925) < 1e-4 and abs(hopf[1] - 0.50998) < 1e-4   # sec 4.2, Fig 13


def test_hopf_frequency_is_sqrt_c3_over_c1(fig12_response):
    """docs/errata.md: after eq (55) the Hopf frequency is omega^2 = C3/C1 (printed C1/C3)."""
    t = fig12_response.table
    for s in fig12_response.special_points:
        if s.kind != "hopf":
            continue
        row = np.nonzero((t["special"] == 2) & np.isclose(t["rho"], s.rho, rtol=0, atol=1e-15))[0][0]
        critical = np.argmin(np.abs([t[f"re{i}"][row] for i in range(1, 5)]))
        imag = abs(t[f"im{critical + 1}"][row])
        assert s.frequency == pytest.approx(imag, rel=1e-6)
        assert math.sqrt(t["C1"][row] / t["C3"][row]) != pytest.approx(imag, rel=1e-2)


def test_stability_changes_exactly_at_special_points(fig12_response):
    t = fig12_response.table
    for k in range(len(t["rho"]) - 1):
        if t["branch"][k] != t["branch"][k + 1]:
            continue
        if t["stable"][k] != t["stable"][k + 1]:
            assert t["special"][k] or t["special"][k + 1], t["rho"][k]
    for k in np.nonzero(t["special"])[0]:
        neighbours = [j for j in (k - 1, k + 1) if 0 <= j < len(t["rho"]) and t["branch"][j] == t["branch"][k]]
        assert len({t["stable"][j] for j in neighbours}) == 2, t["rho"][k]   # stable on one side only


def polar_slow_flow(m, rho, A):
    """Eq (53) as printed, steady state in (a1, a2, phi1, phi2), eps = 1."""
    w1, w2 = m.omega1, m.omega2
    s1, s2 = w2 - 3 * w1, rho - w1
    f = m.coefficients["F11"] * rho**2 * A

    def equations(z):
        a1, a2, p1, p2 = z
        return [-0.5 * m.coefficients["gamma11"] * a1 + m.coefficients["c13"] / (8 * w1) * a1**2 * a2 * math.sin(p1)
                + f / (2 * w1) * math.cos(p2),
                s1 + (m.coefficients["c21"] / (8 * w2) - 3 * m.coefficients["c12"] / (4 * w1)) * a2**2
                + (m.coefficients["c22"] / (4 * w2) - 3 * m.coefficients["c11"] / (8 * w1)) * a1**2
                - m.coefficients["c23"] / (8 * w2) * a1**3 / a2 * math.cos(p1)
                + 3 * m.coefficients["c13"] / (8 * w1) * a1 * a2 * math.cos(p1) - 3 * f / (2 * w1 * a1) * math.sin(p2),
                -0.5 * m.coefficients["gamma22"] * a2 - m.coefficients["c23"] / (8 * w2) * a1**3 * math.sin(p1),
                s2 - m.coefficients["c11"] / (8 * w1) * a1**2 - m.coefficients["c12"] / (4 * w1) * a2**2
                + m.coefficients["c13"] / (8 * w1) * a1 * a2 * math.cos(p1) - f / (2 * w1 * a1) * math.sin(p2)]
    return equations


def branch_solutions(response, rho, polish=None):
    """(a1, a2) of every branch crossing rho: the Cartesian unknowns interpolated between the
    two points that bracket rho, then (with polish = the polar equations) solved exactly."""
    found = []
    for b in response.branches:
        x = b["rho"]
        for k in range(len(x) - 1):
            if (x[k] - rho) * (x[k + 1] - rho) <= 0 and x[k] != x[k + 1]:
                w = (rho - x[k]) / (x[k + 1] - x[k])
                b1, b2 = [(1 - w) * (b["re_" + n][k] + 1j * b["im_" + n][k])
                          + w * (b["re_" + n][k + 1] + 1j * b["im_" + n][k + 1]) for n in ("B1", "B2")]
                a1, a2 = abs(b1), abs(b2)
                if polish is not None:
                    phi2 = -np.angle(b1)
                    sol = root(polish, [a1, a2, np.angle(b2) + 3 * phi2, phi2], method="hybr",
                               options={"xtol": 1e-13})
                    assert sol.success and max(np.abs(polish(sol.x))) < 1e-10
                    a1, a2 = sol.x[:2]
                found.append((a1, a2))
    return found


@pytest.mark.parametrize("rho", [0.5092, 0.511, 0.5135])
def test_brute_force_polar_scan_finds_nothing_the_continuation_missed(fig12_response, rho):
    m = sloshdyn.modal_coefficients(FIG12)
    equations = polar_slow_flow(m, rho, FIG12.A)
    rng = np.random.default_rng(7)
    solutions = []
    for _ in range(1500):
        start = [10 ** rng.uniform(-3, -0.5), 10 ** rng.uniform(-4, -0.7),
                 rng.uniform(-math.pi, math.pi), rng.uniform(-math.pi, math.pi)]
        sol = root(equations, start, method="hybr", options={"xtol": 1e-13})
        a1, a2 = sol.x[:2]
        if not sol.success or a1 <= 1e-6 or a2 <= 1e-7 or max(np.abs(equations(sol.x))) > 1e-10:
            continue
        if all(abs(a1 - s[0]) > 1e-6 * a1 or abs(a2 - s[1]) > 1e-6 * a2 for s in solutions):
            solutions.append((a1, a2))
    continued = branch_solutions(fig12_response, rho, polish=equations)
    assert len(solutions) >= 1
    for a1, a2 in solutions:        # every brute-force solution lies on a continued branch
        assert min(abs(a1 - c[0]) / a1 + abs(a2 - c[1]) / a2 for c in continued) < 1e-6, (a1, a2)
    assert len(continued) == len(solutions)


@pytest.mark.parametrize("kappa,kind", [(4.7, "softening"), (4.5, "hardening")])
def test_fig9_nonresonant_response(kappa, kind):
    p = sloshdyn.Parameters(kappa=kappa, **FIG9)
    m = sloshdyn.modal_coefficients(p)
    w1 = m.omega1
    response = sloshdyn.frequency_response(p, (w1 - 0.04, w1 + 0.04), resonance="none")
    t = response.table
    # every point satisfies eq (50) with the square on eps a1 (docs/errata.md)
    lhs = t["rho"] ** 4 * p.A**2 * m.coefficients["F11"] ** 2 / (4 * w1**2)
    rhs = t["a1"] ** 2 * (m.coefficients["gamma11"] ** 2 / 4 + (t["rho"] - w1 - m.coefficients["c11"] / (8 * w1) * t["a1"] ** 2) ** 2)
    assert np.allclose(rhs, lhs, rtol=1e-8)
    # as printed (no square) it does not hold
    printed = t["a1"] * (m.coefficients["gamma11"] ** 2 / 4 + (t["rho"] - w1 - m.coefficients["c11"] / (8 * w1) * t["a1"] ** 2) ** 2)
    assert not np.allclose(printed, lhs, rtol=1e-2)
    folds = sorted(s.rho for s in response.special_points if s.kind == "fold")
    assert len(folds) == 2
    # softening bends the peak below omega1, hardening above (sign of c11, sec 4.1)
    assert (m.coefficients["c11"] < 0) == (kind == "softening")
    assert all(f < w1 for f in folds) if kind == "softening" else all(f > w1 for f in folds)
    # three solutions of eq (49) between the folds, one outside; the unstable one in the middle
    middle = sloshdyn.nonresonant_amplitudes(p, 0.5 * (folds[0] + folds[1]))[0]
    assert len(middle) == 3
    assert len(sloshdyn.nonresonant_amplitudes(p, w1 - 0.03)[0]) == 1
    continued = sorted(a1 for a1, _ in branch_solutions(response, 0.5 * (folds[0] + folds[1])))
    assert np.allclose(continued, middle, rtol=1e-2)      # linear interpolation between points


def harmonic_amplitudes(p, y0, periods=200, per=64):
    """Amplitudes of the rho component of u1 and the 3 rho component of u2 (eq 42, 45)."""
    period = 2 * math.pi / p.rho
    tau = np.arange(periods * per + 1) * period / per
    sim = sloshdyn.simulate(p, tau[-1], y0, tau_out=tau)
    t, u1, u2 = tau[:-1], sim.u[0][:-1], sim.u[1][:-1]
    return (2 * abs(np.mean(u1 * np.exp(-1j * p.rho * t))),
            2 * abs(np.mean(u2 * np.exp(-3j * p.rho * t))))


@pytest.mark.parametrize("rho", [0.505, 0.508, 0.5105, 0.511])
def test_slow_flow_agrees_with_direct_simulation(fig12_response, rho):
    p = FIG12.replace(rho=rho)
    st = sloshdyn.steady_state(p)
    assert st.motion == "periodic"
    (a1, a2), = branch_solutions(fig12_response, rho)      # one stable solution here
    h1, h2 = harmonic_amplitudes(p, st.y_end)
    assert a1 < 0.1
    assert h1 == pytest.approx(a1, rel=0.02)
    assert h2 == pytest.approx(a2, rel=0.10)
    assert st.max_u1 == pytest.approx(a1, rel=0.02)


def test_amplitude_continuation_and_isolated_branches():
    """In A at fixed rho: the 3:1 branch and its folds; every point solves the slow flow."""
    p = FIG12.replace(rho=0.5135)
    response = sloshdyn.frequency_response(p, A_range=(1e-5, 0.0015))
    assert response.complete and response.parameter == "A"
    m = sloshdyn.modal_coefficients(p)
    t = response.table
    for k in range(0, len(t["A"]), 7):
        eq = polar_slow_flow(m, 0.5135, t["A"][k])
        z = [t["a1"][k], t["a2"][k], t["phi1"][k], t["phi2"][k]]
        assert max(np.abs(eq(z))) < 1e-9 * max(1.0, 1 / t["a2"][k])
    assert any(s.kind == "fold" for s in response.special_points)


def test_bad_response_input():
    with pytest.raises(sloshdyn.InputError, match="resonance"):
        sloshdyn.frequency_response(FIG12, (0.49, 0.53), resonance="2:1")
    with pytest.raises(sloshdyn.InputError, match="rho_min = -0.1"):
        sloshdyn.frequency_response(FIG12, (-0.1, 0.53))
    with pytest.raises(sloshdyn.InputError, match="kappa"):
        sloshdyn.frequency_response(FIG12.replace(kappa=1.4), (0.49, 0.53))


def complex_slow_flow(m, rho, A):
    """Eq (53) in the Cartesian unknowns B1 = a1 exp(-i phi2), B2 = a2 exp(i (phi1 - 3 phi2))
    (eq 42, 45), typed here from the modal coefficients: x = (Re B1, Im B1, Re B2, Im B2)."""
    w1, w2 = m.omega1, m.omega2
    s2, s1 = rho - w1, w2 - 3 * w1

    def f(t, x):
        b1, b2 = x[0] + 1j * x[1], x[2] + 1j * x[3]
        f1 = (-(m.coefficients["gamma11"] / 2 + 1j * s2) * b1 + rho**2 * A * m.coefficients["F11"] / (2 * w1)
              + 1j / (8 * w1) * (m.coefficients["c11"] * abs(b1)**2 * b1 + 2 * m.coefficients["c12"] * abs(b2)**2 * b1
                                 - m.coefficients["c13"] * np.conj(b1)**2 * b2))
        f2 = (-(m.coefficients["gamma22"] / 2 + 1j * (3 * s2 - s1)) * b2
              + 1j / (8 * w2) * (m.coefficients["c21"] * abs(b2)**2 * b2 + 2 * m.coefficients["c22"] * abs(b1)**2 * b2
                                 - m.coefficients["c23"] * b1**3))
        return [f1.real, f1.imag, f2.real, f2.imag]
    return f


def scipy_return_time(p, cycle):
    """The first return of eq (53) (complex_slow_flow, scipy DOP853 at rtol 1e-11) from the
    cycle's point to the section through it normal to the flow, after half a period at least;
    and the run (dense output)."""
    from scipy.integrate import solve_ivp
    f = complex_slow_flow(sloshdyn.modal_coefficients(p), p.rho, p.A)
    normal = np.array(f(0, cycle.x))

    def section(t, x):
        return normal @ (x - cycle.x)
    section.direction = 1
    run = solve_ivp(f, (0, 1.5 * cycle.period), cycle.x, method="DOP853", rtol=1e-11,
                    atol=1e-14, events=section, dense_output=True)
    return run.t_events[0][run.t_events[0] > 0.5 * cycle.period][0], run


def test_slow_flow_limit_cycle_at_fig14_against_scipy(fig12_response):
    """The Fig 14 point lies between the Hopf points: the slow flow has a limit cycle. Its
    period by shooting (Fortran) against scipy's DOP853 on eq (53) typed in numpy: the
    trajectory from the cycle's point returns to its section after the same time, at the
    same point; the cycle is stable (the multipliers other than 1 inside the unit circle)."""
    p = FIG12.replace(rho=0.509615)
    hopf = sorted(s.rho for s in fig12_response.special_points if s.kind == "hopf")
    assert hopf[0] < p.rho < hopf[1]
    cycle = sloshdyn.slow_flow_cycle(p)
    returned, run = scipy_return_time(p, cycle)
    assert returned == pytest.approx(cycle.period, rel=1e-7)
    assert run.sol(cycle.period) == pytest.approx(cycle.x, abs=1e-7 * np.max(np.abs(cycle.x)))
    mu = np.sort(np.abs(cycle.multipliers))
    assert mu[-1] == pytest.approx(1, abs=1e-6) and mu[-2] < 1
    assert cycle.beat_periods == pytest.approx(cycle.period * p.rho / (2 * math.pi), rel=1e-15)
