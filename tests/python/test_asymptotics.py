"""The multiple-scales coefficients against the paper's quoted numbers, against Taylor
coefficients of the right-hand side fitted numerically, and against Appendix A (confirming the
misprints of docs/errata.md)."""

import itertools
import math

import numpy as np
import pytest

import sloshdyn

FIG9 = dict(s1=1.5, mu1=0.5, theta0=math.pi / 4, gamma=0.0025, A=0.0005)


def test_c11_matches_fig9_caption():
    c11_47 = sloshdyn.modal_coefficients(sloshdyn.Parameters(kappa=4.7, **FIG9)).coefficients["c11"]
    c11_45 = sloshdyn.modal_coefficients(sloshdyn.Parameters(kappa=4.5, **FIG9)).coefficients["c11"]
    assert abs(c11_47 - (-0.03188)) < 1e-5      # Fig 9a: softening
    assert abs(c11_45 - 0.30585) < 1e-5         # Fig 9b: hardening


def odd_monomials(max_degree=5):
    return [e for d in range(1, max_degree + 1, 2)
            for e in itertools.product(range(d + 1), repeat=4) if sum(e) == d]


def fit(points, values, monomials):
    design = np.array([[np.prod(z ** np.array(e)) for e in monomials] for z in points])
    coefficients, *_ = np.linalg.lstsq(design, values, rcond=None)
    return dict(zip(monomials, coefficients))


def rhs_samples(p, points):
    """g = Q'' + K x from the equations of motion (eq 15) at z = (x1, x2, x1', x2')."""
    k = sloshdyn.linear_modes(p).stiffness
    g = np.empty((len(points), 2))
    for i, (x1, x2, v1, v2) in enumerate(points):
        dydt = sloshdyn.equations_of_motion(p, 0.0, [x1, v1, x2, v2]).dydt
        g[i] = [dydt[1], dydt[3]] + k @ [x1, x2]
    return g


@pytest.mark.parametrize("kappa,n,p_exp", [(1.804897259, 6, 2), (4.7, 2, 1), (2.6, 3, 2)])
def test_expansion_matches_numerical_taylor_coefficients(kappa, n, p_exp):
    p = sloshdyn.Parameters(kappa=kappa, beta=0.3, delta=0.2, n=n, p=p_exp, **{**FIG9, "A": 0.0})
    m = sloshdyn.modal_coefficients(p)
    rng = np.random.default_rng(1)
    points = rng.uniform(-0.01, 0.01, size=(500, 4))
    g = rhs_samples(p, points)
    monomials = odd_monomials()
    for r in range(2):
        fitted = fit(points, g[:, r], monomials)
        scale = max(abs(v) for v in m.g[r].values())
        for e, value in m.g[r].items():
            assert fitted.get(e, 0.0) == pytest.approx(value, abs=2e-6 * scale), (r, e)
    # the modal form: h(u, u') = P^-1 g(P u, P u')
    modes = sloshdyn.linear_modes(p)
    u_points = rng.uniform(-0.005, 0.005, size=(500, 4))
    points = np.array([np.concatenate([modes.modal @ u[:2], modes.modal @ u[2:]]) for u in u_points])
    h = rhs_samples(p, points) @ modes.modal_inverse.T
    for r in range(2):
        fitted = fit(u_points, h[:, r], monomials)
        scale = max(abs(v) for v in m.h[r].values())
        for e, value in m.h[r].items():
            assert fitted.get(e, 0.0) == pytest.approx(value, abs=2e-6 * scale), (r, e)


def test_forcing_terms_match_numerical_taylor_coefficients():
    p = sloshdyn.Parameters(kappa=1.8049, rho=0.5, **{**FIG9, "A": 1.0})   # F is linear in A
    m = sloshdyn.modal_coefficients(p)
    rng = np.random.default_rng(2)
    points = rng.uniform(-0.01, 0.01, size=(300, 2))
    tau = math.pi / (2 * p.rho)                       # sin(rho tau) = 1
    unforced = p.replace(A=0.0)
    g = []
    for x1, x2 in points:
        y = [x1, 0.0, x2, 0.0]
        forced = sloshdyn.equations_of_motion(p, tau, y).dydt
        free = sloshdyn.equations_of_motion(unforced, tau, y).dydt
        g.append((forced[[1, 3]] - free[[1, 3]]) / (p.rho**2 * p.A))
    g = np.array(g)
    monomials = [(0, 0), (2, 0), (1, 1), (0, 2), (4, 0), (3, 1), (2, 2), (1, 3), (0, 4)]
    for r in range(2):
        fitted = fit(points, g[:, r], monomials)
        assert fitted[(0, 0)] == pytest.approx(m.g_forcing[r][(0, 0, 0, 0)], abs=1e-9)
        for (i, j) in [(2, 0), (1, 1), (0, 2)]:
            assert fitted[(i, j)] == pytest.approx(m.g_forcing[r].get((i, j, 0, 0), 0.0), abs=1e-5)


def appendix_as_printed(s1, mu1, kappa, theta0, gamma):
    """Appendix A, typed in as printed (with the corrections of docs/errata.md marked)."""
    t2, q, d = theta0**2, 1 - mu1, kappa - s1
    return {
        "gamma_hat11": gamma / (s1 * q),
        "gamma_hat12_printed": gamma * (1 + mu1) / (2 * s1 * theta0 * q),
        "gamma_hat12_corrected": gamma * t2 * (1 + mu1) / (2 * s1 * q**2),
        "gamma_hat13": t2 * mu1 / q,
        "gamma_hat14_printed": gamma * t2 * (1 + mu1) / (2 * s1 * q**2),
        "gamma_hat15": t2 / (s1 * q),
        "gamma_hat21": gamma / q,
        "gamma_hat22": gamma * mu1 * t2 / q**2,
        "gamma_hat23": mu1 * s1 * t2 / q,
        "alpha_hat11": t2 / (6 * q**2) * (5 * mu1 + 1),
        "alpha_hat12": -t2 / (s1 * q**2) * (0.5 * (1 + mu1) * d - 2 * s1 * mu1),
        "alpha_hat13": -t2 / (s1 * q**2) * ((1 + mu1) * d - s1 * mu1),
        "alpha_hat14": -t2 / (6 * s1 * q**2) * (3 * (1 + mu1) * d - s1 * q),
        "alpha_hat21": t2 * s1 * mu1 / (3 * q**2) * (mu1 + 2),
        "alpha_hat22": -mu1 * t2 / q**2 * (s1 * q - d + 2 * mu1 * s1),
        "alpha_hat23_printed": -mu1 * t2 / q**2 * (0.5 * s1 * q - 2 * d + s1),
        "alpha_hat23_corrected": -mu1 * t2 / q**2 * (0.5 * s1 * q - 2 * d + mu1 * s1),
        "alpha_hat24": -t2 / (6 * q**2) * (s1 * q - 6 * mu1 * d),
        "F_hat12": theta0 / (s1 * q), "F_hat13": theta0 / (s1 * q), "F_hat21": 1 / theta0,
        "F_hat22": theta0 * mu1 / q, "F_hat23": theta0 * (1 + mu1) / (2 * q),
    }


@pytest.mark.parametrize("kappa", [1.8049, 4.5, 4.7])
def test_appendix_a_and_its_misprints(kappa):
    p = sloshdyn.Parameters(kappa=kappa, **FIG9)
    m = sloshdyn.modal_coefficients(p)
    paper = appendix_as_printed(p.s1, p.mu1, p.kappa, p.theta0, p.gamma)
    for name, value in paper.items():
        if name.endswith("_printed"):
            continue
        ours = m.coefficients[name.removesuffix("_corrected")]
        assert ours == pytest.approx(value, rel=1e-12, abs=1e-15), name
    # the misprints are real: as printed, these differ from the equations of motion
    assert m.coefficients["gamma_hat12"] != pytest.approx(paper["gamma_hat12_printed"], rel=1e-3)
    assert m.coefficients["gamma_hat14"] == pytest.approx(2 * paper["gamma_hat14_printed"], rel=1e-12)
    assert m.coefficients["alpha_hat23"] != pytest.approx(paper["alpha_hat23_printed"], rel=1e-3)
    # the pairs Appendix A states as equal
    assert m.coefficients["gamma_hat16"] == pytest.approx(m.coefficients["gamma_hat13"]) and m.coefficients["gamma_hat18"] == pytest.approx(m.coefficients["gamma_hat15"])
    assert m.coefficients["gamma_hat17"] == pytest.approx(m.coefficients["gamma_hat12"]) and m.coefficients["gamma_hat24"] == pytest.approx(2 * m.coefficients["gamma_hat22"])
    assert m.coefficients["gamma_hat25"] == pytest.approx(m.coefficients["gamma_hat13"]) and m.coefficients["gamma_hat26"] == pytest.approx(m.coefficients["gamma_hat23"])
    assert m.coefficients["gamma_hat27"] == pytest.approx(m.coefficients["gamma_hat22"]) and m.coefficients["gamma_hat28"] == pytest.approx(m.coefficients["gamma_hat25"])
    # modal forcing, eq (36): F11 = F_hat21/(omega2^2 - omega1^2), and +F11 in h2
    assert m.coefficients["F11"] == pytest.approx(m.coefficients["F_hat21"] / (m.omega2**2 - m.omega1**2), rel=1e-12)
    assert m.h_forcing[1][(0, 0, 0, 0)] == pytest.approx(m.coefficients["F11"], rel=1e-12)


def test_c11_with_appendix_as_printed_is_wrong():
    """docs/errata.md: with alpha_hat23 as printed every c_ij is wrong (c11 = 2.31 instead of -0.03188)."""
    p = sloshdyn.Parameters(kappa=4.7, **FIG9)
    m = sloshdyn.modal_coefficients(p)
    paper = appendix_as_printed(p.s1, p.mu1, p.kappa, p.theta0, p.gamma)
    w1, w2, k12 = m.omega1, m.omega2, (p.kappa - p.s1) / ((1 - p.mu1) * p.s1)
    a, b, k11 = w1**2 - 1 / (1 - p.mu1), w2**2 - 1 / (1 - p.mu1), 1 / (1 - p.mu1)

    def alpha11(hat23):
        r = (w2**2 - k11) / k12
        return (-(r * paper["alpha_hat11"] - paper["alpha_hat21"]) * k12**3
                + a * (r * paper["alpha_hat12"] + paper["alpha_hat22"]) * k12**2
                - (r * paper["alpha_hat13"] + hat23) * k12 * a**2
                + (r * paper["alpha_hat14"] + paper["alpha_hat24"]) * a**3) / (w2**2 - w1**2)

    # Appendix A's alpha11 with the corrected alpha_hat23 is ours; as printed it is not
    assert alpha11(paper["alpha_hat23_corrected"]) == pytest.approx(m.coefficients["alpha11"], rel=1e-10)
    gamma17 = m.coefficients["gamma17"]
    assert gamma17 * w1**2 + 3 * alpha11(paper["alpha_hat23_printed"]) == pytest.approx(2.31, abs=0.01)
