"""Swirl: the out-of-plane stability of planar periodic responses (sloshdyn.spatial.swirl_band,
docs/model.md "Spatial model and swirl").

Independent source: the forced spherical pendulum's averaged equations (Miles 1962, 1984),
derived here by sympy from the pendulum's Lagrangian expanded to fourth order in the horizontal
coordinates, x = p1 cos(rho tau) + q1 sin(rho tau) and y = p2 cos(...) + q2 sin(...) averaged
over a forcing period (first-order averaging, van der Pol). With the pivot amplitude epsilon,
amplitudes scale as epsilon^(1/3) and detuning and damping as epsilon^(2/3); the averaged
equations are exact to leading order, so the band's edges agree to O(epsilon^(4/3)) in rho.
The tank model reduces to this pendulum for rigid supports (large kappa, small mu1), no impacts
(beta = 0, theta0 far) and only linear sloshing damping zeta; its pivot amplitude is A/s1.
And independent of the Floquet machinery: scipy integrates the spatial equations from a planar
orbit slightly perturbed out of its plane, inside and outside the band.
"""

import functools

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, fsolve

import sloshdyn
from sloshdyn import spatial

EPSILON = 1e-3          # pivot amplitude / pendulum length
ZETA = 5e-4             # 0.05 epsilon^(2/3)
PARAMS = sloshdyn.Parameters(s1=1.0, mu1=0.01, kappa=1e3, theta0=1.4, beta=0.0, gamma=0.0,
                             delta=0.0, A=EPSILON, rho=1.02, zeta=ZETA, n=6, p=2)


@functools.lru_cache(maxsize=1)
def _averaged_field():
    """The averaged equations d(p1, q1, p2, q2)/dtau of the forced, damped spherical pendulum
    (unit length and frequency; pivot at epsilon sin(rho tau) along x; damping force -2 zeta v)
    and the Jacobian of the out-of-plane pair (p2, q2), as numerical functions."""
    tau = sp.Symbol("tau")
    eps, rho, zeta = sp.symbols("epsilon rho zeta", positive=True)
    x, y = sp.Function("x")(tau), sp.Function("y")(tau)
    r2 = x**2 + y**2
    height = 1 - r2 / 2 - r2**2 / 8                        # sqrt(1 - r^2) to fourth order
    vz2 = (x * x.diff(tau) + y * y.diff(tau))**2           # (dz/dtau)^2 to fourth order
    pivot_acceleration = -eps * rho**2 * sp.sin(rho * tau)
    lag = (x.diff(tau)**2 + y.diff(tau)**2 + vz2) / 2 + height - pivot_acceleration * x
    p1, q1, p2, q2, ph = sp.symbols("p1 q1 p2 q2 phi")
    X = p1 * sp.cos(ph) + q1 * sp.sin(ph)
    Y = p2 * sp.cos(ph) + q2 * sp.sin(ph)
    # second derivatives of the cubic terms at leading order: x'' = -rho^2 x
    subs = {x.diff(tau, 2): -rho**2 * X, y.diff(tau, 2): -rho**2 * Y,
            x.diff(tau): rho * X.diff(ph), y.diff(tau): rho * Y.diff(ph)}
    field = []
    for q in (x, y):
        residual = sp.expand(lag.diff(q.diff(tau)).diff(tau) - lag.diff(q)
                             + 2 * zeta * q.diff(tau))
        # x'' + rho^2 x = F, and the residual at the ansatz is -F
        F = -residual.subs(subs).subs({x: X, y: Y}).subs(tau, ph / rho)
        for weight in (-sp.sin(ph), sp.cos(ph)):
            field.append(sp.integrate(sp.expand(weight * F / rho), (ph, 0, 2 * sp.pi))
                         / (2 * sp.pi))
    state, groups = (p1, q1, p2, q2), (eps, rho, zeta)
    jac = sp.Matrix(field).jacobian(state)
    return (sp.lambdify((state, groups), field, "numpy"),
            sp.lambdify((state, groups), jac[2:, 2:], "numpy"))


def _theory_growth(rho, guess):
    """(largest out-of-plane growth rate, planar amplitude (p1, q1)) of the averaged equations at
    rho, on the planar fixed point nearest the guess."""
    field, out_of_plane = _averaged_field()
    groups = (EPSILON, rho, ZETA)
    s = fsolve(lambda u: field([u[0], u[1], 0, 0], groups)[:2], guess, xtol=1e-13)
    rate = np.linalg.eigvals(np.array(out_of_plane([s[0], s[1], 0, 0], groups), float)).real.max()
    return rate, s


@functools.lru_cache(maxsize=1)
def _band():
    return spatial.swirl_band(PARAMS, (0.995, 1.02), from_end="high")


def test_the_swirl_edge_is_the_forced_spherical_pendulums():
    band = _band()
    assert band.complete
    # from small planar sloshing above resonance into the resonant branch: one edge, refined
    assert len(band.edges["lambda"]) == 1 and band.edges["refined"][0] == 1
    edge = band.edges["rho"][0]
    guess = [0.0, 0.1]                          # the resonant branch near the edge (a ~ 0.11)

    def margin(rho):
        return _theory_growth(rho, guess)[0]

    theory = brentq(margin, 1.0 + 0.35 * EPSILON**(2 / 3), 1.0 + 0.45 * EPSILON**(2 / 3),
                    xtol=1e-12)
    assert abs(edge - theory) <= EPSILON**(4 / 3)     # measured 1.1e-6 with kappa = 1e4
    # planar above the edge, swirling below it on this branch
    table = band.table
    assert np.all(table["swirl"] == (table["rho"] < edge))


def test_growth_rates_inside_the_band_are_the_averaged_ones():
    """ln|nu|/T of the Floquet multipliers against the averaged equations' eigenvalues."""
    table = _band().table
    inside = np.flatnonzero(table["swirl"])
    assert inside.size >= 3
    for k in inside[::max(inside.size // 3, 1)]:
        rho = table["rho"][k]
        rate = np.log(table["max_abs_nu"][k]) * rho / (2 * np.pi)
        # follow the averaged equations' resonant branch down from the edge to rho
        guess = [0.0, 0.1]
        for r in np.linspace(1.0 + 0.4 * EPSILON**(2 / 3), rho, 50):
            theory, guess = _theory_growth(r, guess)
        amplitude = guess
        # the same planar orbit: amplitude max|theta| = |(p1, q1)| to O(epsilon^(2/3))
        assert np.hypot(*amplitude) == pytest.approx(table["max_x1"][k] * PARAMS.theta0,
                                                     rel=0.05)
        assert rate == pytest.approx(theory, rel=0.05, abs=2 * EPSILON**(4 / 3))


@pytest.mark.parametrize("rho, swirls", [(0.999, True), (1.008, False)])
def test_brute_force_integration_swirls_inside_the_band_only(rho, swirls):
    """scipy's DOP853 on the spatial equations from the planar orbit plus 1e-6 out of plane."""
    params = PARAMS.replace(rho=rho)
    table = _band().table
    k = int(np.argmin(np.abs(table["rho"] - rho)))
    guess = np.array([table[f"y{i}"][k] for i in range(1, 5)])
    orbit = sloshdyn.periodic_orbit(params, guess)
    y0 = np.concatenate([orbit.y0, [1e-6, 0.0, 0.0, 0.0]])
    period = 2 * np.pi / rho
    periods = 40

    def rhs(tau, y):
        return spatial.equations_of_motion(params, tau, y).dydt

    t_eval = np.linspace(0, periods * period, 64 * periods + 1)
    sol = solve_ivp(rhs, (0, periods * period), y0, method="DOP853", rtol=1e-8, atol=1e-12,
                    t_eval=t_eval)
    assert sol.success
    out = np.abs(sol.y[4])
    first, last = out[:64].max(), out[-64:].max()
    if swirls:
        assert last / first > 2.5     # growth rate 0.005 per tau: e^(0.005 * 250) = 3.5
        assert np.abs(sol.y[0][-64:]).max() < 1   # far from the wall: no impacts
    else:
        assert last / first < 1       # decays as zeta: e^(-0.0005 * 250) = 0.88


RHO_SWIRL = 1.003       # inside the band, just below its edge 1.0037539 (test above)


@functools.lru_cache(maxsize=1)
def _swirl():
    return spatial.swirl_orbit(PARAMS.replace(rho=RHO_SWIRL))


def _period_gap(params, y0):
    """max|y(T) - y0| by scipy's DOP853 on the spatial equations (independent of the shooting)."""
    period = 2 * np.pi / params.rho
    sol = solve_ivp(lambda tau, y: spatial.equations_of_motion(params, tau, y).dydt,
                    (0, period), y0, method="DOP853", rtol=1e-12, atol=1e-14)
    assert sol.success
    return np.abs(sol.y[:, -1] - y0).max()


def test_the_swirling_orbit_is_periodic_and_its_mirror_turns_the_other_way():
    params = PARAMS.replace(rho=RHO_SWIRL)
    orbit = _swirl()
    assert orbit.swirl_amplitude > 0.5 * orbit.max_x1           # it left the plane
    assert _period_gap(params, orbit.y0) < 1e-8
    # the mirror y -> -y of a solution is a solution (the forcing is along x)
    mirror = orbit.y0 * np.array([1, 1, 1, 1, -1, -1, -1, -1])
    image = spatial.swirl_orbit(params, mirror)
    assert _period_gap(params, image.y0) < 1e-8
    assert np.abs(image.y0 - mirror).max() < 1e-8
    assert image.angular_momentum == pytest.approx(-orbit.angular_momentum, rel=1e-6)
    assert {orbit.direction, image.direction} == {"clockwise", "counter-clockwise"}
    assert image.swirl_amplitude == pytest.approx(orbit.swirl_amplitude, rel=1e-6)


def test_the_swirling_orbit_is_the_averaged_equations_swirl():
    """The swirl fixed point (p2, q2) != 0 of the averaged equations (Miles 1962, 1984): in-plane
    and out-of-plane amplitudes, and the angular momentum m l^2 <x y' - y x'> =
    m rho (p1 q2 - q1 p2) in units of M L^2 omega (m/M = mu1, l = L for s1 = 1)."""
    orbit = _swirl()
    field, _ = _averaged_field()
    y1 = orbit.y0[4] * PARAMS.theta0                   # the swirl of the averaged equations
    s = fsolve(lambda u: field(u, (EPSILON, RHO_SWIRL, ZETA)), [0.0, 0.1, y1, 0.0], xtol=1e-13)
    assert np.hypot(s[2], s[3]) > 0.1                  # a swirl, not the planar fixed point
    # amplitudes to O(epsilon^(2/3)) relative (measured 0.3% and 0.1%)
    assert orbit.max_x1 * PARAMS.theta0 == pytest.approx(np.hypot(s[0], s[1]), rel=0.02)
    assert orbit.swirl_amplitude * PARAMS.theta0 == pytest.approx(np.hypot(s[2], s[3]), rel=0.02)
    theory = PARAMS.mu1 * RHO_SWIRL * (s[0] * s[3] - s[1] * s[2])
    assert orbit.angular_momentum == pytest.approx(theory, rel=0.05)    # measured 1%
    # the four slow Floquet multipliers (near 1) are exp(lambda T) of the averaged equations'
    # Jacobian at the swirl (central differences of the cubic field); the other four belong to
    # the stiff supports
    h, groups = 1e-7, (EPSILON, RHO_SWIRL, ZETA)
    jac = np.column_stack([(np.array(field(s + h * e, groups)) - field(s - h * e, groups))
                           / (2 * h) for e in np.eye(4)])
    theory = np.linalg.eigvals(jac)
    theory = theory[np.argsort(theory.imag)]
    slow = orbit.multipliers[np.abs(np.angle(orbit.multipliers)) < 0.5]
    rates = np.log(slow) * RHO_SWIRL / (2 * np.pi)
    rates = rates[np.argsort(rates.imag)]
    assert rates.size == 4
    assert np.allclose(rates.real, theory.real, atol=2 * EPSILON**(4 / 3))
    assert np.allclose(rates.imag, theory.imag, rtol=0.05)     # measured 1.2% and 0.9%
    assert orbit.stable == bool(theory.real.max() < 0)        # both: a stable swirl


def test_the_band_edge_widens_with_A_as_the_averaged_theory_says():
    """swirl_boundary: the band's upper edge at three amplitudes A, each where max|nu| = 1, each
    at the averaged equations' edge (rho - 1 scales as A^(2/3)) to O(A^(4/3))."""
    A_values = [5e-4, 1e-3, 2e-3]
    boundary = spatial.swirl_boundary(PARAMS, (0.995, 1.02), A_values, from_end="high")
    assert boundary.complete
    edges = boundary.edges
    assert np.array_equal(edges["A"], A_values) and np.all(edges["refined"] == 1)
    assert np.all(np.diff(edges["rho"]) > 0)           # wider with A
    field, out_of_plane = _averaged_field()
    for A, rho, y1, y2, y3, y4 in zip(*(edges[k] for k in ("A", "rho", "y1", "y2", "y3", "y4"))):
        params = PARAMS.replace(A=A, rho=rho)
        orbit = sloshdyn.periodic_orbit(params, [y1, y2, y3, y4])
        nu = spatial.out_of_plane_multipliers(params, orbit.y0)
        assert np.abs(nu).max() == pytest.approx(1, abs=1e-6)

        scale = A**(2 / 3)

        def margin(r, A=A, scale=scale):
            groups = (A, r, ZETA)
            s = fsolve(lambda u: field([u[0], u[1], 0, 0], groups)[:2], [0.0, 1.1 * scale**0.5],
                       xtol=1e-13)   # the resonant branch: amplitude ~ 1.1 A^(1/3)
            jac = np.array(out_of_plane([s[0], s[1], 0, 0], groups), float)
            return np.linalg.eigvals(jac).real.max()

        theory = brentq(margin, 1 + 0.3 * scale, 1 + 0.5 * scale, xtol=1e-12)
        assert abs(rho - theory) <= A**(4 / 3)    # measured 2.9e-6, 1.1e-6, 2.4e-6


@pytest.mark.parametrize("call, name", [
    (lambda: spatial.swirl_orbit(PARAMS, np.zeros(4)), "y0"),
    (lambda: spatial.swirl_orbit(PARAMS, np.zeros(8), transient=-1), "transient"),
    (lambda: spatial.swirl_orbit(PARAMS, np.zeros(8), periods=0), "periods"),
    (lambda: spatial.swirl_boundary(PARAMS, (0.995, 1.02), []), "A_values"),
    (lambda: spatial.swirl_boundary(PARAMS, (0.995, 1.02), [1e-3, np.nan]), "A_values")])
def test_swirl_orbit_and_boundary_name_a_bad_input(call, name):
    with pytest.raises(sloshdyn.InputError, match=name):
        call()
