"""The Lyapunov spectrum of the spatial model (issue 42, item 4) and the order of every
spectrum (issue 44, item 9): on a stable planar orbit the eight exponents are log|mu|/T of the
four in-plane Floquet multipliers (the planar shooting's monodromy matrix) and of the four
out-of-plane ones (sloshdyn.spatial.out_of_plane_multipliers), and their sum is the mean
divergence of the spatial equations along the orbit (Liouville; the divergence from central
differences of y', averaged over a period by the trapezoidal rule, exact for a periodic
integrand up to its Fourier tail)."""

import math

import numpy as np
import pytest

import sloshdyn
from sloshdyn import Lyapunov
from sloshdyn import spatial

FIG12 = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=math.pi / 4,
                            gamma=0.001, A=0.00075, rho=0.50)
#: damped, so that the frame settles fast; a stable planar orbit, stable to swirl
P = FIG12.replace(rho=0.513, gamma=0.05, A=0.05)


@pytest.fixture(scope="module")
def orbit():
    orbit = sloshdyn.periodic_orbit(P, sloshdyn.steady_state(P).y_end)
    assert orbit.stable
    return orbit


def mean_divergence(y0, n=256):
    """(1/T) int_0^T tr J dtau along the spatial orbit through y0, tr J = sum_i d(y'_i)/dy_i by
    central differences."""
    period = 2 * math.pi / P.rho
    tau = np.arange(n) * period / n
    run = spatial.simulate(P, period, y0, tau_out=tau,
                           integration=sloshdyn.Integration(rtol=1e-11, atol=1e-13))
    h, total = 1e-5, 0.0
    for k in range(n):
        y = run.y[:, k]
        total += sum((spatial.equations_of_motion(P, tau[k], y + h * e).dydt[i]
                      - spatial.equations_of_motion(P, tau[k], y - h * e).dydt[i]) / (2 * h)
                     for i, e in enumerate(np.eye(8)))
    return total / n


def test_spatial_spectrum_of_a_planar_orbit_is_its_in_and_out_of_plane_floquet(orbit):
    nu = spatial.out_of_plane_multipliers(P, orbit.y0)
    assert np.max(np.abs(nu)) < 1                         # stable to swirl too
    period = 2 * math.pi / P.rho
    floquet = np.sort(np.log(np.abs(np.concatenate([orbit.multipliers, nu]))) / period)[::-1]
    y0 = np.concatenate([orbit.y0, np.zeros(4)])
    spectrum = sloshdyn.lyapunov_spectrum(
        P, y0, spatial=True, lyapunov=Lyapunov(transient_periods=3000, n_periods=4000,
                                               renormalise_every=1),
        integration=sloshdyn.Integration(rtol=1e-11, atol=1e-13))
    assert spectrum.exponents.shape == (8,) and spectrum.history.shape == (8, 4000)
    assert np.all(np.diff(spectrum.exponents) <= 0)
    # the multipliers come in complex pairs (four moduli): the QR method splits a pair's common
    # exponent with an error bounded over the run, O(1/t) (1.6e-5 at t = 4000 T), while the
    # pair's sum (the growth of its invariant plane) converges at once (4.5e-11)
    error = np.abs(spectrum.exponents - floquet)
    pairs = spectrum.exponents.reshape(4, 2).sum(axis=1) - floquet.reshape(4, 2).sum(axis=1)
    assert np.max(error) < 3e-5
    assert np.max(np.abs(pairs)) < 1e-9
    # Liouville, twice: the exponents' sum and the multipliers' (measured 8e-13 and 4e-11)
    divergence = mean_divergence(y0)
    assert spectrum.sum == pytest.approx(divergence, rel=1e-9)
    assert np.sum(floquet) == pytest.approx(divergence, rel=1e-9)
    assert spectrum.kaplan_yorke == 0.0                   # all negative: a point


def test_weighted_average_reaches_the_floquet_exponents_to_1e_6(orbit):
    """The weighted Birkhoff average (Lyapunov(average='weighted'); Das, Saiki, Sander and
    Yorke 2017; Das and Yorke 2018): a complex pair's frame turns by arg(mu) each period, so the
    log growths are a smooth quasi-periodic signal and their weighted average converges faster
    than any power of 1/N, where the plain one (the history, the same run) converges as 1/N."""
    nu = spatial.out_of_plane_multipliers(P, orbit.y0)
    period = 2 * math.pi / P.rho
    floquet = np.sort(np.log(np.abs(np.concatenate([orbit.multipliers, nu]))) / period)[::-1]
    y0 = np.concatenate([orbit.y0, np.zeros(4)])
    spectrum = sloshdyn.lyapunov_spectrum(
        P, y0, spatial=True, lyapunov=Lyapunov(transient_periods=3000, n_periods=1000,
                                               renormalise_every=1, average="weighted"),
        integration=sloshdyn.Integration(rtol=1e-11, atol=1e-13))
    assert np.all(np.diff(spectrum.exponents) <= 0)
    # measured: 2.3e-11 over 1000 periods (the plain average 6.2e-5 over the same run)
    weighted = np.max(np.abs(spectrum.exponents - floquet))
    plain = np.max(np.abs(np.sort(spectrum.history[:, -1])[::-1] - floquet))
    assert weighted < 1e-6
    assert weighted < 1e-4 * plain
    assert spectrum.sum == pytest.approx(mean_divergence(y0), rel=1e-9)


def test_lyapunov_average_is_checked():
    with pytest.raises(sloshdyn.InputError, match="average.*'mean'.*'plain', 'weighted'"):
        Lyapunov(average="mean")
    assert Lyapunov().average == "plain"


def test_spatial_spectrum_input_is_checked():
    with pytest.raises(sloshdyn.InputError, match="y0"):
        sloshdyn.lyapunov_spectrum(P, np.zeros(4), spatial=True)
    with pytest.raises(sloshdyn.InputError, match="spatial"):
        sloshdyn.lyapunov_spectrum(P, spatial="yes")
