"""The design check (issue 25 items 1-3 and 6; docs/design.md): the codes' design spectra, their
loads in each code's format and their freeboard checks, against hand calculations typed here
from the codes' equations (numpy and scipy.special, independent of the Fortran core), and
&design / design_loads.csv / freeboard_check.csv of the executable."""

from __future__ import annotations

import math
import re
import shutil

import numpy as np
import pytest
from scipy.special import jnp_zeros

import sloshdyn
from sloshdyn import DesignSpectrum, design_check
from sloshdyn.design import Design
from conftest import EXAMPLES, ec8_impulsive, read_csv, run, write
from test_design_check_hand import EC8, asce7, ec8_sd, ec8_se, restricted_sloshing
from test_seismic import spectral_acceleration, tapered_sines

BROAD = dict(radius=5.0, liquid_depth=6.0, freeboard=1.0, tank_mass=5.0e4)     # D/H = 1.67
SLENDER = dict(radius=3.0, liquid_depth=12.0, freeboard=1.5, tank_mass=3.0e4)  # D/H = 0.5
TANKS = {"broad": BROAD, "slender": SLENDER}


def make_tank(**geometry):
    return sloshdyn.Tank(**geometry, liquid_density=1000.0, support_frequency=2.0,
                         support_damping=0.02)


# --- the spectra, typed from the codes --------------------------------------------------------

def aci_ci(T, s_ds, s_d1):
    """ACI 350.3-06 eq 9-32 (T <= T_S) and 9-33."""
    return s_ds if T <= s_d1 / s_ds else min(s_d1 / T, s_ds)


def aci_cc(T, s_ds, s_d1):
    """ACI 350.3-06 eq 9-34 (T <= 1.6/T_S) and 9-35."""
    if T <= 1.6 / (s_d1 / s_ds):
        return min(1.5 * s_d1 / T, 1.5 * s_ds)
    return 2.4 * s_ds / T**2


S_DS, S_D1, T_L = 1.0, 0.6, 4.0
T_S = S_D1 / S_DS


@pytest.mark.parametrize("period", [0.1, 0.5, T_S, 2.0, T_L, 6.0])
def test_api650_and_aci350_spectrum_ordinates(period):
    """ASCE 7-16 11.4.6 at 5 % and API 650's K = 1.5 times it at 0.5 % (E.4.6.1); ACI 350.3's
    C_i (5 %) and C_c (0.5 %): the ordinates at T in {0.1, 0.5, T_S, 2, T_L, 6} s."""
    asce = DesignSpectrum.asce7(s_ds=S_DS, s_d1=S_D1, t_l=T_L)
    aci = DesignSpectrum.aci350(s_ds=S_DS, s_d1=S_D1)
    assert asce.sa(period) == pytest.approx(asce7(period, S_DS, S_D1, T_L), rel=1e-14)
    assert asce.sa(period, damping_ratio=0.005) == pytest.approx(
        1.5 * asce7(period, S_DS, S_D1, T_L), rel=1e-14)
    assert aci.sa(period, damping_ratio=0.05) == pytest.approx(aci_ci(period, S_DS, S_D1),
                                                               rel=1e-14)
    assert aci.sa(period, damping_ratio=0.005) == pytest.approx(aci_cc(period, S_DS, S_D1),
                                                                rel=1e-14)
    # vectorised: the same numbers in an array
    assert np.array_equal(asce.sa(np.array([period, period])), [asce.sa(period)] * 2)


@pytest.mark.parametrize("kind", [1, 2])
@pytest.mark.parametrize("ground", ["A", "B", "C", "D", "E"])
def test_ec8_spectrum_ordinates_at_and_between_the_corner_periods(kind, ground):
    """EN 1998-1 3.2.2.2: Se at 0, T_B, T_C, T_D, 4 s and between them, at 5 %, 0.5 % and 30 %
    (eta floored at 0.55), a_g = gamma_I a_gR."""
    spectrum = DesignSpectrum.ec8(a_gr=0.25, ground_type=ground, spectrum_type=kind,
                                  gamma_i=1.2)
    S, TB, TC, TD = EC8[kind][ground]
    periods = [0.0, TB / 2, TB, (TB + TC) / 2, TC, (TC + TD) / 2, TD, (TD + 4) / 2, 4.0]
    for ratio in (0.05, 0.005, 0.3):
        got = spectrum.sa(np.array(periods), damping_ratio=ratio)
        assert got == pytest.approx([ec8_se(T, 0.3, ground, kind, 100 * ratio)
                                     for T in periods], rel=1e-14)
    assert spectrum.sa(TC) == pytest.approx(0.3 * S * 2.5, rel=1e-14)   # eta(5 %) = 1


def test_ec8_impulsive_mass_289_t():
    """EN 1998-4 Annex A.2.1: the impulsive mass of the trial tank (R = 5 m, H = 6 m of water)
    is 289 t (issue 25) to 0.1 %, and the series by scipy.special to 1e-9; design_codes'
    EC8-4 impulsive mass and height (no longer NaN) are the series'."""
    tank = make_tank(**BROAD)
    codes = tank.design_codes()
    ratio, h_i, _ = ec8_impulsive(5.0, 6.0)
    liquid = math.pi * 25 * 6 * 1000
    assert codes.value("EC8-4", "impulsive_mass") == pytest.approx(289e3, rel=1e-3)
    assert codes.value("EC8-4", "impulsive_mass") == pytest.approx(ratio * liquid, rel=1e-9)
    assert codes.value("EC8-4", "impulsive_height") == pytest.approx(h_i, rel=1e-9)

    # potential flow: the impulsive mass and every convective mode's,
    # 2 tanh(l_n gamma)/(gamma l_n (l_n^2 - 1)) over the roots l_n of J1', add to the liquid
    roots = jnp_zeros(1, 4000)
    for R, H in ((5.0, 6.0), (3.0, 12.0), (20.0, 4.0)):
        gamma = H / R
        convective = np.sum(2 * np.tanh(roots * gamma) / (gamma * roots * (roots**2 - 1)))
        assert ec8_impulsive(R, H)[0] + convective == pytest.approx(1.0, abs=1e-6), (R, H)


# --- the codes' masses, heights and loads, typed from the codes -------------------------------

def api650_parameters(R, H):
    """API 650 E.4.5.2 (T_c), E.6.1.1 (W_i, W_c), E.6.1.2.1 (X_i, X_c), E.6.1.2.2 (X_is, X_cs)."""
    D = 2 * R
    r = D / H
    x = 3.67 * H / D
    T_c = 1.8 * 0.578 / math.sqrt(math.tanh(3.68 * H / D)) * math.sqrt(D)
    if r >= 1.333:
        w_i = math.tanh(0.866 * r) / (0.866 * r)
        X_i, X_is = 0.375 * H, 0.375 * (1 + 1.333 * (0.866 * r / math.tanh(0.866 * r) - 1)) * H
    else:
        w_i, X_i, X_is = 1 - 0.218 * r, (0.5 - 0.094 * r) * H, (0.5 + 0.06 * r) * H
    w_c = 0.230 * r * math.tanh(x)
    X_c = (1 - (math.cosh(x) - 1) / (x * math.sinh(x))) * H
    X_cs = (1 - (math.cosh(x) - 1.937) / (x * math.sinh(x))) * H
    return T_c, w_i, w_c, (X_i, X_c, X_is, X_cs)


def aci350_parameters(R, H, g):
    """ACI 350.3-06 eq 9-15 to 9-22, 9-29 to 9-31."""
    D = 2 * R
    r = D / H
    x = 3.68 * H / D
    T_c = 2 * math.pi * math.sqrt(D) / math.sqrt(3.68 * g * math.tanh(x))
    w_i = math.tanh(0.866 * r) / (0.866 * r)
    w_c = 0.230 * r * math.tanh(x)
    h_i = 0.375 * H if r >= 1.333 else (0.5 - 0.09375 * r) * H
    h_c = (1 - (math.cosh(x) - 1) / (x * math.sinh(x))) * H
    h_ip = 0.45 * H if r < 0.75 else (0.866 * r / (2 * math.tanh(0.866 * r)) - 0.125) * H
    h_cp = (1 - (math.cosh(x) - 2.01) / (x * math.sinh(x))) * H
    return T_c, w_i, w_c, (h_i, h_c, h_ip, h_cp)


def ec8_parameters(R, H, g):
    """EN 1998-4 A.2.1: first sloshing mode (lambda_1 = 1.841) and the impulsive series."""
    gamma, lam = H / R, 1.841
    x = lam * gamma
    T_c = 2 * math.pi / math.sqrt(g * lam / R * math.tanh(x))
    w_c = 2 * math.tanh(x) / (gamma * lam * (lam**2 - 1))
    h_c = H * (1 - (math.cosh(x) - 1) / (x * math.sinh(x)))
    h_cp = H * (1 - (math.cosh(x) - 2) / (x * math.sinh(x)))
    w_i, h_i, h_ip = ec8_impulsive(R, H)
    return T_c, w_i, w_c, (h_i, h_c, h_ip, h_cp)


def loads(a_i, a_c, m_i, m_c, m_t, heights, h_t, g, srss, m_conf=0.0):
    """V_i = a_i g (m_i + m_conf + m_t), V_c = a_c g (m_c - m_conf), combined; moments EBP and
    IBP (API 650 E.6.1, E.6.1.5; ACI 350.3 eq 4-1 to 4-15 with the wall and roof as m_t at h_t;
    EN 1998-4 A.3.2); m_conf: the confined convective mass of the restricted-sloshing method
    (ASCE 7-16 15.7.6.1.2 as read here), impulsive at the convective heights."""
    h_i, h_c, h_ip, h_cp = heights
    combine = (lambda a, b: math.hypot(a, b)) if srss else (lambda a, b: abs(a) + abs(b))
    V_i, V_c = a_i * g * (m_i + m_conf + m_t), a_c * g * (m_c - m_conf)
    return {"impulsive_shear": V_i, "convective_shear": V_c, "base_shear": combine(V_i, V_c),
            "moment_ebp": combine(a_i * g * (m_i * h_i + m_conf * h_c + m_t * h_t),
                                  a_c * g * (m_c - m_conf) * h_c),
            "moment_ibp": combine(a_i * g * (m_i * h_ip + m_conf * h_cp + m_t * h_t),
                                  a_c * g * (m_c - m_conf) * h_cp)}


def confined(R, f, wave, m_c):
    """The confined convective mass where the wave exceeds the freeboard (a flat roof; the
    integrals by scipy in test_design_check_hand), else 0."""
    return restricted_sloshing(R, f, wave, 1000.0, m_c)["m_conf"] if wave > f else 0.0


def check_row(row, expected):
    for name, value in expected.items():
        assert row[name] == pytest.approx(value, rel=1e-6), name   # 4 digits asked; 6 shown


FACTORS = dict(importance=1.25, use_group=2, r_wi=3.5, r_wc=2.0, r_i=2.0, r_c=1.0)


@pytest.mark.parametrize("name", TANKS)
@pytest.mark.parametrize("t_i", [0.0, 0.9])
def test_api650_and_aci350_loads_from_the_asce7_spectrum(name, t_i):
    """API 650 E.4.6.1 (A_i = S_DS I/R_wi on the plateau, or Sa(T_i) I/R_wi; A_c = K S_D1/T_c
    I/R_wc <= A_i) and E.6.1 (SRSS); ACI 350.3 sec 4 with C_i, C_c of sec 9.4: shears and
    moments (EBP: ringwall M_rw, M_b; IBP: slab M_s, M_o) of a broad and a slender tank."""
    geometry = TANKS[name]
    tank = make_tank(**geometry)
    R, H, m_t = geometry["radius"], geometry["liquid_depth"], geometry["tank_mass"]
    g, m_L = tank.gravity, math.pi * R**2 * H * 1000
    h_t = (H + geometry["freeboard"]) / 2
    t_l = 8.0
    check = sloshdyn.design_check(tank, DesignSpectrum.asce7(s_ds=S_DS, s_d1=S_D1, t_l=t_l),
                                  design=Design(impulsive_period=t_i, **FACTORS))
    assert set(check.loads) == {"API 650", "ACI 350.3", "sloshdyn linear"}
    # API 650
    T_c, w_i, w_c, heights = api650_parameters(R, H)
    sa_i = S_DS if t_i == 0 else asce7(t_i, S_DS, S_D1, t_l)
    A_i = sa_i * 1.25 / 3.5
    A_c = min(1.5 * S_D1 / T_c * 1.25 / 2.0, A_i)
    delta_s = 0.42 * 2 * R * 1.5 * S_D1 * 1.25 * (1 / T_c if T_c <= 4 else 4 / T_c**2)  # E.7.2
    m_conf = confined(R, geometry["freeboard"], delta_s, w_c * m_L)
    check_row(check.loads["API 650"], {"convective_period": T_c, "impulsive_acceleration": A_i,
                                      "convective_acceleration": A_c,
                                      "impulsive_mass": w_i * m_L + m_conf,
                                      "convective_mass": w_c * m_L - m_conf,
                                      **loads(A_i, A_c, w_i * m_L, w_c * m_L, m_t, heights, h_t,
                                              g, True, m_conf)})
    # ACI 350.3
    T_c, w_i, w_c, heights = aci350_parameters(R, H, g)
    C_i = aci_ci(t_i, S_DS, S_D1) if t_i > 0 else S_DS
    C_c = aci_cc(T_c, S_DS, S_D1)
    m_conf = confined(R, geometry["freeboard"], R * C_c * 1.25, w_c * m_L)     # d_max, eq 7-2
    check_row(check.loads["ACI 350.3"], {
        "convective_period": T_c, "impulsive_acceleration": C_i * 1.25 / 2.0,
        "convective_acceleration": C_c * 1.25 / 1.0,
        **loads(C_i * 1.25 / 2.0, C_c * 1.25, w_i * m_L, w_c * m_L, m_t, heights, h_t, g, True,
                m_conf)})


@pytest.mark.parametrize("name", TANKS)
@pytest.mark.parametrize("t_i", [0.0, 0.3])
def test_ec8_loads_from_the_ec8_spectrum(name, t_i):
    """EN 1998-4 Annex A: impulsive from the design spectrum with q (EN 1998-1 3.2.2.5),
    convective elastic at 0.5 % (eq 3.2-3.6), absolute sum (A.3.2.2); the impulsive mass and
    heights from A.2.1's series; a broad and a slender tank."""
    geometry = TANKS[name]
    tank = make_tank(**geometry)
    R, H, m_t = geometry["radius"], geometry["liquid_depth"], geometry["tank_mass"]
    g, m_L = tank.gravity, math.pi * R**2 * H * 1000
    h_t = (H + geometry["freeboard"]) / 2
    check = sloshdyn.design_check(tank, DesignSpectrum.ec8(a_gr=0.25, ground_type="C",
                                                           gamma_i=1.2, q=1.5),
                                  design=Design(impulsive_period=t_i))
    assert set(check.loads) == {"EC8-4", "sloshdyn linear"}
    T_c, w_i, w_c, heights = ec8_parameters(R, H, g)
    a_g = 1.2 * 0.25
    a_i = ec8_sd(t_i if t_i > 0 else 0.6, a_g, "C", 1, 1.5)
    a_c = ec8_se(T_c, a_g, "C", 1, 0.5)
    m_conf = confined(R, geometry["freeboard"], 0.84 * R * a_c, w_c * m_L)      # d_max, A.2.1
    assert m_conf == 0                        # the waves stay below the roof here
    check_row(check.loads["EC8-4"], {
        "convective_period": T_c, "impulsive_acceleration": a_i, "convective_acceleration": a_c,
        "impulsive_mass": w_i * m_L, "impulsive_height": heights[0],
        "impulsive_height_ibp": heights[2],
        **loads(a_i, a_c, w_i * m_L, w_c * m_L, m_t, heights, h_t, g, False)})
    # freeboard: d_max = 0.84 R Se(T_c1)/g
    check_row(check.freeboard["EC8-4"], {"wave_height": 0.84 * R * a_c,
                                         "required_freeboard": 0.84 * R * a_c})


@pytest.mark.parametrize("geometry, use_group, s_ds, t_l, branch", [
    (BROAD, 2, 1.0, 8.0, "E.7.2-2"),          # T_c = 3.33 s <= 4 s, SUG II, S_DS >= 0.33 g
    (BROAD, 2, 0.3, 8.0, "E.7.2-2"),          # S_DS < 0.33 g: no freeboard required
    (BROAD, 3, 1.0, 2.0, "E.7.2-5"),          # SUG III, T_c > T_L
    (SLENDER, 1, 1.0, 8.0, "E.7.2-2"),        # SUG I: none required
    (SLENDER, 3, 1.0, 8.0, "E.7.2-4"),        # SUG III, T_c <= T_L
    (dict(radius=20.0, liquid_depth=10.0, freeboard=2.0, tank_mass=2e5), 2, 1.0, 12.0,
     "E.7.2-3"),                              # T_c = 7.7 s > 4 s: 4 s in place of T_L
])
def test_freeboard_api650_by_use_group_and_aci350(geometry, use_group, s_ds, t_l, branch):
    """API 650 E.7.2: delta_s = 0.42 D A_f with A_f by SUG (I, II: 4 s in place of T_L) and
    Table E-7's required freeboard (SUG I none, II 0.7 delta_s where S_DS >= 0.33 g, III
    delta_s); ACI 350.3 eq 7-2: d_max = R C_c I, required d_max; the verdict against the
    tank's freeboard."""
    tank = make_tank(**geometry)
    R, f = geometry["radius"], geometry["freeboard"]
    importance = {1: 1.0, 2: 1.25, 3: 1.5}[use_group]
    check = sloshdyn.design_check(tank, DesignSpectrum.asce7(s_ds=s_ds, s_d1=0.6, t_l=t_l),
                                  design=Design(importance=importance, use_group=use_group))
    T_c = api650_parameters(R, geometry["liquid_depth"])[0]
    limit = t_l if use_group == 3 else 4.0
    A_f = 1.5 * 0.6 * importance * (1 / T_c if T_c <= limit else limit / T_c**2)
    assert (T_c <= limit) == (branch in ("E.7.2-2", "E.7.2-4"))
    delta_s = 0.42 * 2 * R * A_f
    required = {1: 0.0, 2: 0.7 * delta_s if s_ds >= 0.33 else 0.0, 3: delta_s}[use_group]
    check_row(check.freeboard["API 650"], {"convective_acceleration": A_f,
                                           "wave_height": delta_s,
                                           "required_freeboard": required,
                                           "margin": f - required})
    assert check.sufficient["API 650"] == (f >= required)
    T_c = aci350_parameters(R, geometry["liquid_depth"], tank.gravity)[0]
    d_max = R * aci_cc(T_c, s_ds, 0.6) * importance
    check_row(check.freeboard["ACI 350.3"], {"wave_height": d_max, "required_freeboard": d_max})
    assert check.sufficient["ACI 350.3"] == (f >= d_max)


@pytest.mark.parametrize("factor, sufficient", [(1.0, True), (1 - 1e-13, True),
                                                (1 - 1e-6, False)])
def test_a_freeboard_equal_to_the_required_one_is_sufficient(factor, sufficient):
    """ACI 350.3 eq 7-2 with the tank's freeboard set to d_max = R C_c I (numpy) times factor:
    equal within round-off is sufficient (the core's d_max may differ from numpy's in the last
    bits), a freeboard 1e-6 short is not."""
    T_c = aci350_parameters(5.0, 6.0, 9.80665)[0]
    d_max = 5.0 * aci_cc(T_c, 1.0, 0.6)
    tank = make_tank(**dict(BROAD, freeboard=d_max * factor))
    check = sloshdyn.design_check(tank, DesignSpectrum.aci350(s_ds=1.0, s_d1=0.6))
    assert check.freeboard["ACI 350.3"]["required_freeboard"] == pytest.approx(d_max, rel=1e-12)
    assert check.sufficient["ACI 350.3"] is sufficient


def test_loads_from_a_record_and_the_nonlinear_row():
    """From a ground motion: each code's accelerations are its pseudo-spectral accelerations
    (expm here, independent of the core's recurrence) at the code's periods, 0.5 % convective,
    the rigid tank's PGA impulsive (EC8: divided by q); the nonlinear row is the time history's
    peaks and its roof verdict; S_DS for Table E-7 is 0.9 max Sa(5 %) over 0.2-5 s (ASCE 7-16
    21.4)."""
    tank = make_tank(**BROAD)
    ground = tapered_sines(pga=2.0)
    g = tank.gravity
    response = sloshdyn.seismic_response(tank, ground)
    check = design_check(tank, ground, design=Design(q=1.5, use_group=2, importance=1.25),
                         response=response)
    assert list(check.loads) == ["API 650", "EC8-4", "ACI 350.3", "sloshdyn linear",
                                 "sloshdyn nonlinear"]
    pga = 2.0 / g
    T_api = api650_parameters(5.0, 6.0)[0]
    sa_api = spectral_acceleration(ground, T_api, 0.005, 5 * T_api) / g
    api = check.loads["API 650"]
    assert api["impulsive_acceleration"] == pytest.approx(pga * 1.25 / 3.5, rel=1e-12)
    assert api["convective_acceleration"] == pytest.approx(min(sa_api * 1.25 / 2, pga * 1.25 / 3.5),
                                                           rel=1e-7)
    T_ec8 = ec8_parameters(5.0, 6.0, g)[0]
    ec8 = check.loads["EC8-4"]
    assert ec8["impulsive_acceleration"] == pytest.approx(pga / 1.5, rel=1e-12)
    assert ec8["convective_acceleration"] == pytest.approx(
        spectral_acceleration(ground, T_ec8, 0.005, 5 * T_ec8) / g, rel=1e-7)
    nonlinear = check.loads["sloshdyn nonlinear"]
    assert nonlinear["base_shear"] == response.peaks["base_shear"][0]
    assert nonlinear["moment_ebp"] == response.peaks["overturning_moment"][0]
    assert check.freeboard["sloshdyn nonlinear"]["wave_height"] == \
        response.peak_table["free_wave_height"]
    assert check.sufficient["sloshdyn nonlinear"] == (not response.roof_reached)
    # API 650 Table E-7 with the record's S_DS
    periods = 0.2 * 25.0**(np.arange(100) / 99)
    s_ds = 0.9 * max(spectral_acceleration(ground, T, 0.05, 25.0) for T in periods) / g
    delta_s = check.freeboard["API 650"]["wave_height"]
    assert delta_s == pytest.approx(0.42 * 10 * sa_api * 1.25, rel=1e-7)
    assert check.freeboard["API 650"]["required_freeboard"] == pytest.approx(
        0.7 * delta_s if s_ds >= 0.33 else 0.0, rel=1e-12)


def test_design_codes_wave_heights_from_a_design_spectrum():
    """Tank.design_codes(spectrum): each source's wave height from the spectrum's Sa at its
    period and the tank's sloshing damping (0.5 %: K S_D1/T for ASCE 7)."""
    tank = make_tank(**BROAD)
    spectrum = DesignSpectrum.asce7(s_ds=S_DS, s_d1=S_D1, t_l=8.0)
    codes = tank.design_codes(spectrum)
    T_api = codes.value("API 650", "convective_period")
    assert codes.value("API 650", "wave_height") == pytest.approx(
        0.42 * 10 * 1.5 * S_D1 / T_api, rel=1e-12)                       # E.7.2-1, I = 1


def test_design_spectrum_figure():
    """plotting.design_spectrum: one curve per spectrum and damping, each the spectrum's Sa
    (checked above against the codes), on axes in s and g; EN 1998-1's curves end at 4 s."""
    from sloshdyn import plotting
    spectra = [DesignSpectrum.asce7(s_ds=S_DS, s_d1=S_D1, t_l=8.0),
               DesignSpectrum.ec8(a_gr=0.25, ground_type="C")]
    fig = plotting.design_spectrum(spectra)
    ax = fig.axes[0]
    assert ax.get_xlabel() == "period T [s]" and ax.get_ylabel().endswith("[g]")
    lines = ax.get_lines()
    assert len(lines) == 4
    for line, (spectrum, ratio) in zip(lines, [(s, r) for s in spectra for r in (0.05, 0.005)]):
        t, sa = line.get_data()
        assert np.array_equal(sa, spectrum.sa(t, damping_ratio=ratio))
    # EN 1998-1's curves continue beyond 4 s (its informative Annex A)
    assert lines[2].get_data()[0][-1] == 10.0 and lines[0].get_data()[0][-1] == 10.0


# --- bad input --------------------------------------------------------------------------------


def asce7_site():
    """The ASCE 7 site of the broad tank's checks (S_DS 1.0 g, S_D1 0.6 g, T_L 8 s)."""
    return DesignSpectrum.asce7(s_ds=1.0, s_d1=0.6, t_l=8)

@pytest.mark.parametrize("make, words", [
    (lambda: DesignSpectrum.asce7(s_ds=-1.0, s_d1=0.6, t_l=8), ["s_ds = -1", "(0, 10]",
                                                               "11.4.5"]),
    (lambda: DesignSpectrum.asce7(s_ds=1.0, s_d1=2.0, t_l=1.0), ["t_l = 1", "T_S = S_D1/S_DS"]),
    (lambda: DesignSpectrum.asce7(s_ds=1.0, s_d1=0.6, t_l=8).sa(1.0, damping_ratio=0.02),
     ["damping_ratio = 0.02", "0.05 or 0.005", "ASCE 7-16 11.4.6"]),
    (lambda: DesignSpectrum.aci350(s_ds=1.0, s_d1=0.6).sa(1.0, damping_ratio=0.01),
     ["damping_ratio = 0.01", "9.4.2"]),
    (lambda: DesignSpectrum.ec8(a_gr=0.25).sa(5.0, damping_ratio=5.0),
     ["damping_ratio = 5", "(0, 1)", "0.05 for 5 %"]),
    (lambda: DesignSpectrum.ec8(a_gr=3.0), ["a_gr = 3", "(0, 2]"]),
    (lambda: DesignSpectrum.ec8(a_gr=0.2, q=0.5), ["q = 0.5", "[1, 8]"]),
    (lambda: DesignSpectrum.ec8(a_gr=0.2, ground_type="F"), ["ground_type", "'F'"]),
    (lambda: DesignSpectrum.ec8(a_gr=0.2, spectrum_type=3), ["spectrum_type = 3", "1 or 2"]),
    (lambda: sloshdyn.design_check(make_tank(**BROAD), asce7_site(), design=Design(use_group=4)),
     ["use_group = 4", "1, 2 or 3", "E.3.1"]),
    (lambda: sloshdyn.design_check(make_tank(**BROAD), asce7_site(), design=Design(r_wi=0.5)),
     ["r_wi = 0.5", "[1, 10]", "Table E-4"]),
    (lambda: sloshdyn.design_check(make_tank(**BROAD), asce7_site(),
                                   design=Design(impulsive_damping_ratio=0.02)),
     ["impulsive_damping_ratio = 0.02", "0.05 (5 %) only"]),
    (lambda: sloshdyn.design_check(make_tank(**BROAD), design=Design(spectrum="ground_motion")),
     ["needs the ground motion"]),
    (lambda: sloshdyn.design_check(make_tank(**BROAD), design=Design()), ["s_ds = 0", "(0, 10]"]),
])
def test_bad_design_input_names_the_variable_value_and_clause(make, words):
    with pytest.raises(sloshdyn.InputError) as info:
        make()
    for word in words:
        assert word in str(info.value), (word, str(info.value))


# --- the executable ---------------------------------------------------------------------------

@pytest.mark.parametrize("example, sources", [
    ("tank_design", ["API 650", "ACI 350.3", "sloshdyn linear"]),
    ("tank_slender_design", ["EC8-4", "sloshdyn linear"])])
def test_executable_writes_design_loads_and_freeboard_check(exe, tmp_path, example, sources):
    """data/examples/tank_design.nml (ASCE 7) and tank_slender_design.nml (EN 1998-1): a
    spectrum, no record; design_loads.csv and freeboard_check.csv hold the rows the spectrum
    feeds, the numbers Python's design_check gives for the namelist's tank and &design (one
    core)."""
    result = run(exe, _copied(f"{example}.nml", tmp_path), tmp_path)
    assert result.returncode == 0, result.stderr
    assert "Design check" in result.stdout
    out = tmp_path / "sloshdyn_output" / example
    inp = sloshdyn.read_namelist(EXAMPLES / f"{example}.nml")
    check = sloshdyn.design_check(inp.tank, design=inp.design, tank_structure=inp.tank_structure)
    for name, rows in (("design_loads.csv", check.loads),
                       ("freeboard_check.csv", check.freeboard)):
        lines = read_csv(out / name)
        assert [line["source"] for line in lines] == list(rows) == sources
        for line in lines:
            values = [v for k, v in line.items() if k != "source"]
            assert values == pytest.approx(list(rows[line["source"]].values()), rel=1e-15,
                                           nan_ok=True)
    # the summary's loads are design_loads.csv's in MN and MN m, to 5 significant digits ('-':
    # a code that gives no moment including the base pressure)
    printed = {m[1]: m.groups()[1:] for m in re.finditer(
        r"^  (\S.*?) +V (\S+) +M (\S+) +M' (\S+)$", result.stdout, flags=re.M)}
    loads = {line["source"]: line for line in read_csv(out / "design_loads.csv")}
    assert list(printed) == list(loads)
    for source, texts in printed.items():
        for text, column in zip(texts, ("base_shear [N]", "moment_ebp [N m]", "moment_ibp [N m]")):
            value = float(loads[source][column])/1e6
            if math.isnan(value):
                assert text == "-"
            else:
                assert len(text.lstrip("-").replace(".", "").lstrip("0")) <= 5, (source, text)
                assert float(text) == float(f"{value:.5g}"), (source, column, text)


def test_seismic_run_with_design_from_its_ground_motion(exe, tmp_path):
    """kind = 'seismic' with &design spectrum = 'ground_motion': the nonlinear row of
    design_loads.csv is seismic_peaks.csv's peak base shear and overturning moment."""
    (tmp_path / "records").mkdir()
    (tmp_path / "records" / "synthetic_kt.AT2").write_bytes(
        (EXAMPLES / "records" / "synthetic_kt.AT2").read_bytes())
    text = (EXAMPLES / "tank_seismic.nml").read_text()
    path = write(tmp_path, text + "&design\n  spectrum = 'ground_motion'\n  q = 1.5\n/\n")
    result = run(exe, path, tmp_path)
    assert result.returncode == 0, result.stderr
    out = tmp_path / "sloshdyn_output" / "tank_seismic"
    rows = {line["source"]: line for line in read_csv(out / "design_loads.csv")}
    assert list(rows) == ["API 650", "EC8-4", "ACI 350.3", "sloshdyn linear",
                          "sloshdyn nonlinear"]
    peaks = read_csv(out / "seismic_peaks.csv")[0]
    assert rows["sloshdyn nonlinear"]["base_shear [N]"] == peaks["peak_base_shear [N]"]
    assert rows["sloshdyn nonlinear"]["moment_ebp [N m]"] == \
        peaks["peak_overturning_moment [N m]"]


@pytest.mark.parametrize("text, words", [
    ("&design\n  spectrum = 'asce7'\n  s_ds = 1.0\n  t_l = 8\n/\n",
     ["&design", "s_d1", "missing"]),
    ("&design\n  spectrum = 'ground_motion'\n/\n", ["&design", "ground_motion", "needs"]),
    ("&design\n  spectrum = 'ec9'\n/\n", ["&design", "spectrum = 'ec9'", "asce7, aci350, ec8"]),
    ("&design\n  spectrum = 'ec8'\n  a_gr = 0.2\n  ground_type = 'F'\n/\n",
     ["ground_type = 'F'", "A, B, C, D, E"]),
    ("&design\n  spectrum = 'asce7'\n  s_ds = 1.0\n  s_d1 = 0.6\n  t_l = 8\n  use_group = 0\n/\n",
     ["&design", "use_group = 0", "1, 2 or 3"]),
    ("&design\n  spectrum = 'ec8'\n  a_gr = 0.2\n  spectrum_type = 5\n/\n",
     ["&design", "spectrum_type = 5", "1 or 2"]),
])
def test_design_group_errors(exe, tmp_path, text, words):
    """&design's rules: required variables by spectrum, known names, ranges with the clause."""
    tank = (EXAMPLES / "tank_linear.nml").read_text()
    path = write(tmp_path, tank + text)
    result = run(exe, path, tmp_path)
    assert result.returncode != 0
    for word in words:
        assert word in result.stderr + result.stdout, (word, result.stderr)
    with pytest.raises(sloshdyn.InputError) as info:
        sloshdyn.read_namelist(path)
    for word in words:
        assert word in str(info.value)


@pytest.mark.parametrize("example, source, srss", [("tank_slender_design", "EC8-4", False),
                                                   ("tank_design", "API 650", True)])
def test_executable_writes_the_wall_pressure_of_the_design_check(exe, tmp_path, example, source,
                                                                 srss):
    """wall_pressure.csv, base_pressure.csv, pressure_resultants.csv of the design check: from
    EN 1998-4's design accelerations (absolute sum) where it has a row, else from API 650's
    (SRSS); the impulsive resultant is a_i g m_i with Annex A.2.1's m_i (typed here
    with scipy, independent of both core series), the convective one a_c g m_c with the row's
    m_c (to the codes' rounding of lambda_1 = 1.841); profile at 21 heights, hoop force p R."""
    result = run(exe, _copied(f"{example}.nml", tmp_path), tmp_path)
    assert result.returncode == 0, result.stderr
    out = tmp_path / "sloshdyn_output" / example
    inp = sloshdyn.read_namelist(EXAMPLES / f"{example}.nml")
    R, H, g = inp.tank.radius, inp.tank.liquid_depth, inp.tank.gravity
    row = {line["source"]: line for line in read_csv(out / "design_loads.csv")}[source]
    a_i, a_c = row["impulsive_acceleration [g]"] * g, row["convective_acceleration [g]"] * g
    m_i = ec8_impulsive(R, H)[0] * inp.tank.liquid_density * math.pi * R**2 * H
    impulsive, convective = read_csv(out / "pressure_resultants.csv")
    assert impulsive["mass [kg]"] == pytest.approx(m_i, rel=1e-9)
    assert impulsive["base_shear [N]"] == pytest.approx(a_i * m_i, rel=1e-9)
    # the first mode's convective mass of potential flow (the pressure's; the row's mass may be
    # less by the confined mass of the restricted-sloshing method)
    gamma, xi = H / R, float(jnp_zeros(1, 1)[0])
    m_c1 = (2 * math.tanh(xi * gamma) / (gamma * xi * (xi**2 - 1))
            * inp.tank.liquid_density * math.pi * R**2 * H)
    assert convective["base_shear [N]"] == pytest.approx(a_c * m_c1, rel=1e-6)
    wall = read_csv(out / "wall_pressure.csv")
    assert [w["z [m]"] for w in wall] == pytest.approx(np.linspace(0.0, H, 21), abs=1e-12)
    for w in wall:
        p_i, p_c = w["impulsive_pressure [Pa]"], w["convective_pressure [Pa]"]
        total = math.hypot(p_i, p_c) if srss else abs(p_i) + abs(p_c)
        assert w["total_pressure [Pa]"] == pytest.approx(total, rel=1e-12)
        assert w["hoop_force [N/m]"] == pytest.approx(w["total_pressure [Pa]"] * R, rel=1e-12)
    assert len(read_csv(out / "base_pressure.csv")) == 11


def test_executable_writes_the_design_spectrum(exe, tmp_path):
    """design_spectrum.csv of tank_design.nml (ASCE 7: S_DS 1.0 g, S_D1 0.6 g, T_L 8 s): 100
    log-spaced periods 0.02-10 s; Sa at 5 % is ASCE 7-16 11.4.6 typed here, at 0.5 % API 650's
    K = 1.5 times it (E.4.6.1)."""
    result = run(exe, _copied("tank_design.nml", tmp_path), tmp_path)
    assert result.returncode == 0, result.stderr
    rows = read_csv(tmp_path / "sloshdyn_output" / "tank_design" / "design_spectrum.csv")
    periods = [row["period [s]"] for row in rows]
    assert periods == pytest.approx(np.geomspace(0.02, 10.0, 100), rel=1e-12)
    for row, T in zip(rows, periods):
        assert row["sa_5_percent [g]"] == pytest.approx(asce7(T, 1.0, 0.6, 8.0), rel=1e-12)
        assert row["sa_0.5_percent [g]"] == pytest.approx(1.5 * asce7(T, 1.0, 0.6, 8.0),
                                                          rel=1e-12)


def _copied(example, folder):
    """The example input copied into `folder`: its output directory is relative to the file's
    folder (docs/namelist.md, &output)."""
    shutil.copy(EXAMPLES / example, folder / example)
    return folder / example
