"""Nothing refused that a code checks, nothing silently off (issue 38; docs/design.md): each
case the issue lists, through both front doors where it is an input file. Each of these tests
fails on the main branch before issue 38 (the refusal, the silent value or the Infinity it
describes)."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest

import sloshdyn
from sloshdyn import InputError
from sloshdyn.design import Design, DesignSpectrum, TankStructure
from conftest import run, write
from test_design_check_hand import BROAD, BROAD_STRUCTURE, SUG_II, ec8_se

TANK = "&tank\n  radius = {R}\n  liquid_depth = {H}\n  freeboard = {f}\n  liquid_density = " \
       "1000\n  tank_mass = 3e5\n  support_frequency = 3\n  support_damping = 0.02\n/\n"
LINEAR = "&analysis\n  kind = 'linear'\n/\n&output\n  directory = 'out'\n/\n"
ASCE_GROUP = "&design\n  spectrum = 'asce7'\n  s_ds = 1.0\n  s_d1 = 0.6\n  t_l = 8\n{extra}/\n"


def both_doors(exe, tmp_path, text):
    """The executable's and sloshdyn-py run's results of one input text, each door on its own
    copy (exe/input.nml, py/input.nml: &output directory is relative to the input's folder):
    (returncode, output) of each."""
    (tmp_path / "exe").mkdir(exist_ok=True)
    (tmp_path / "py").mkdir(exist_ok=True)
    a = run(exe, write(tmp_path / "exe", text), tmp_path / "exe")
    b = subprocess.run([sys.executable, "-m", "sloshdyn", "run",
                        str(write(tmp_path / "py", text))],
                       cwd=tmp_path / "py", capture_output=True, text=True, timeout=120)
    return (a.returncode, a.stdout + a.stderr), (b.returncode, b.stdout + b.stderr)


def assert_refused_alike(exe, tmp_path, text, words):
    (code_a, out_a), (code_b, out_b) = both_doors(exe, tmp_path, text)
    assert code_a != 0 and code_a == code_b, (code_a, code_b, out_a, out_b)
    for word in words:
        assert word in out_a and word in out_b, (word, out_a, out_b)
    assert not (tmp_path / "exe" / "out").exists() and not (tmp_path / "py" / "out").exists()


def test_ec8_convective_period_beyond_4_s_by_annex_a(exe, tmp_path):
    """EN 1998-4 for the D 30 m tank (T_c1 = 6.24 s): the check runs (impulsive loads
    included), its convective Se by EN 1998-1's informative Annex A (eq A.1-A.3, Table A.1)
    typed here, d_max = 0.84 R Se/g; both doors exit 0 (main: exit 3)."""
    tank = sloshdyn.Tank(**BROAD)
    check = sloshdyn.design_check(tank, DesignSpectrum.ec8(a_gr=0.25, ground_type="C", q=1.5))
    row = check.loads["EC8-4"]
    T = row["convective_period"]
    assert T > 6.0                                            # beyond T_E = 6 s of ground C
    assert row["convective_acceleration"] == pytest.approx(ec8_se(T, 0.25, "C", 1, 0.5), rel=1e-12)
    assert check.freeboard["EC8-4"]["wave_height"] == pytest.approx(
        0.84 * 15 * ec8_se(T, 0.25, "C", 1, 0.5), rel=1e-12)
    assert row["impulsive_shear"] > 0
    spectrum = DesignSpectrum.ec8(a_gr=0.25, ground_type="C")
    for period in (4.5, 6.0, 8.0, 12.0):                      # eq 3.5 / A.1, A.2, A.3
        assert spectrum.sa(period, damping_ratio=0.005) == pytest.approx(
            ec8_se(period, 0.25, "C", 1, 0.5), rel=1e-13)
    text = TANK.format(R=15, H=10, f=1) + "&design\n  spectrum = 'ec8'\n  a_gr = 0.25\n" \
        "  ground_type = 'C'\n  q = 1.5\n/\n" + LINEAR
    (code_a, out_a), (code_b, _) = both_doors(exe, tmp_path, text)
    assert code_a == code_b == 0, out_a
    assert "Annex A" in (tmp_path / "exe" / "out" / "design_calc.csv").read_text()


def test_a_freeboard_beyond_the_linear_wave_runs_the_code_check(exe, tmp_path):
    """A slender tank run at reduced level, freeboard 8 m > 2R/(xi^2 - 1) = 2.51 m: the tank and
    its code check run (main: 'the roof impact model needs a smaller freeboard', exit 3), theta0
    capped below pi/2, and the calc sheet says the linear wave cannot reach the roof."""
    tank = sloshdyn.Tank(radius=3.0, liquid_depth=4.0, freeboard=8.0, liquid_density=1000.0,
                         tank_mass=3e4, support_frequency=3.0, support_damping=0.02)
    assert tank.properties["theta0"] == pytest.approx(0.4999 * math.pi, rel=1e-12)
    check = sloshdyn.design_check(tank, DesignSpectrum.asce7(s_ds=1.0, s_d1=0.6, t_l=8.0))
    assert all(check.sufficient.values())
    notes = [row for row in check.calc if row["code"] == "tank"]
    assert notes and "cannot reach the roof" in notes[0]["quantity"]
    text = TANK.format(R=3, H=4, f=8) + ASCE_GROUP.format(extra="") + LINEAR
    (code_a, out_a), (code_b, out_b) = both_doors(exe, tmp_path, text)
    assert code_a == code_b == 0, out_a
    assert "cannot reach the roof" in out_a and "cannot reach the roof" in out_b
    # a freeboard the wave reaches keeps its exact theta0 (the research model unchanged)
    normal = sloshdyn.Tank(radius=3.0, liquid_depth=4.0, freeboard=1.0, liquid_density=1000.0,
                           tank_mass=3e4, support_frequency=3.0, support_damping=0.02)
    assert normal.properties["theta0"] == math.asin(1.0 * (1.84**2 - 1) / 6.0)


def test_api650_minimum_impulsive_acceleration():
    """API 650 E.4.6.1-2: A_i >= 0.007 (S_DS = 0.01 g gives S_DS I/R_wi = 0.0029; main reports
    it)."""
    check = sloshdyn.design_check(sloshdyn.Tank(**BROAD),
                                  DesignSpectrum.asce7(s_ds=0.01, s_d1=0.005, t_l=8.0))
    assert check.loads["API 650"]["impulsive_acceleration"] == 0.007
    steps = [row for row in check.calc if row["symbol"] == "A_i" and row["code"] == "API 650"]
    assert steps[0]["value"] == pytest.approx(0.01 / 3.5, rel=1e-14)
    assert steps[-1]["clause"] == "API 650 13th ed. E.4.6.1-2"


def test_the_weights_at_their_own_heights_and_the_bottom():
    """W_f in V_i and W_s, W_r at X_s, X_r (E.6.1-2, E.6.1.5-1): with the structure the API 650
    row differs from the lumped mass's (main has no structure: W_f omitted, shell and roof at
    mid-shell)."""
    tank = sloshdyn.Tank(**BROAD)
    structure = TankStructure(**BROAD_STRUCTURE)
    spectrum = DesignSpectrum.asce7(s_ds=1.0, s_d1=0.6, t_l=8.0)
    with_structure = sloshdyn.design_check(tank, spectrum, design=Design(**SUG_II),
                                           tank_structure=structure)
    api = with_structure.loads["API 650"]
    steps = {row["symbol"]: row["value"] for row in with_structure.calc
             if row["code"] == "API 650"}
    assert api["tank_mass"] == pytest.approx((steps["W_s"] + steps["W_r"] + steps["W_f"])
                                             / 9.80665, rel=1e-14)
    assert api["tank_mass_height"] == pytest.approx(
        (steps["W_s"] * steps["X_s"] + steps["W_r"] * steps["X_r"])
        / (steps["W_s"] + steps["W_r"] + steps["W_f"]), rel=1e-14)
    assert steps["W_f"] == pytest.approx(7850 * math.pi * 30**2 / 4 * 0.008 * 9.80665, rel=1e-14)


@pytest.mark.parametrize("use_group, importance, ok", [(3, 1.25, False), (2, 1.0, False),
                                                       (3, 1.5, True), (1, 1.25, True)])
def test_importance_below_table_e5_is_refused(exe, tmp_path, use_group, importance, ok):
    """API 650 Table E-5: I >= 1.0, 1.25, 1.5 for SUG I, II, III (a higher I is the purchaser's
    choice); main accepted use_group = 3 with importance = 1.25."""
    design = Design(use_group=use_group, importance=importance)
    spectrum = DesignSpectrum.asce7(s_ds=1.0, s_d1=0.6, t_l=8.0)
    if ok:
        sloshdyn.design_check(sloshdyn.Tank(**BROAD), spectrum, design=design)
        return
    with pytest.raises(InputError, match=f"importance = {importance:g} .*Table E-5"):
        sloshdyn.design_check(sloshdyn.Tank(**BROAD), spectrum, design=design)
    text = TANK.format(R=15, H=10, f=1) + ASCE_GROUP.format(
        extra=f"  use_group = {use_group}\n  importance = {importance}\n") + LINEAR
    assert_refused_alike(exe, tmp_path, text, ["importance", "Table E-5"])


def test_damping_is_a_ratio_and_an_old_call_in_percent_fails():
    """One convention: DesignSpectrum.sa(period, damping_ratio=...) (keyword only); main's
    sa(T, 0.005), meant as 0.5 % and read as 0.005 %, returned 0.2232 g for 0.2130 g."""
    spectrum = DesignSpectrum.ec8(a_gr=0.25, ground_type="C")
    expected = ec8_se(2.0, 0.25, "C", 1, 0.5)
    assert spectrum.sa(2.0, damping_ratio=0.005) == pytest.approx(expected, rel=1e-14)
    with pytest.raises(TypeError):
        spectrum.sa(2.0, 0.005)                      # positional: the old percent call
    with pytest.raises(TypeError):
        spectrum.sa(2.0, damping=0.5)                # the old keyword
    with pytest.raises(InputError, match="damping_ratio = 5 .*0.05 for 5 %"):
        spectrum.sa(2.0, damping_ratio=5.0)


@pytest.mark.parametrize("extra, words", [
    ("  impulsive_damping = 0.5\n", ["impulsive_damping"]),
    ("  impulsive_damping_ratio = 0.005\n", ["impulsive_damping_ratio = 0.005", "0.05"]),
    ("  tank_mass_height = 1e300\n", ["tank_mass_height = ", "[0, 1e4]"]),
    ("  r_wi = 5e-324\n", ["r_wi = ", "[1, 10]"]),
])
def test_damping_and_factors_refused_alike(exe, tmp_path, extra, words):
    """&design's old impulsive_damping in percent is not read (main: 0.5 accepted as 0.5 % for
    ASCE 7 and the impulsive loads 1.5 times larger); a damping ratio other than 5 % for
    ASCE 7; a height of the tank's mass of 1e300 m and R_wi = 5e-324 (main: Infinity in
    design_loads.csv, exit 0): refused in both doors with one exit code, nothing written."""
    text = TANK.format(R=15, H=10, f=1) + ASCE_GROUP.format(extra=extra) + LINEAR
    assert_refused_alike(exe, tmp_path, text, words)


def test_tank_mass_height_within_the_tank(exe, tmp_path):
    """The tank's mass lies within the tank: a height above its top (11 m, flat roof) is
    refused."""
    text = TANK.format(R=15, H=10, f=1) + ASCE_GROUP.format(extra="  tank_mass_height = 12\n") \
        + LINEAR
    assert_refused_alike(exe, tmp_path, text, ["tank_mass_height = 12", "[0, 11]"])


@pytest.mark.parametrize("design, words", [
    ("&design\n  spectrum = 'aci350'\n  s_ds = 1.0\n  s_d1 = 0.6\n  t_l = NaN\n/\n",
     ["t_l = NaN"]),
    ("&design\n  spectrum = 'ground_motion'\n  s_ds = NaN\n/\n", ["s_ds = NaN", "finite"]),
])
def test_nan_in_design_refused_alike(exe, tmp_path, design, words):
    """A NaN t_l of an ACI 350.3 spectrum, or a NaN s_ds beside a ground motion's spectrum:
    main exited 0 in the executable and 3 in sloshdyn-py run; now one rule in the core."""
    ground = "&ground_motion\n  peak_acceleration = 0.2\n  frequency = 0.5\n/\n"
    text = TANK.format(R=15, H=10, f=1) + ground + design + LINEAR
    assert_refused_alike(exe, tmp_path, text, words)


def test_a_record_scaled_by_1e250_ends_in_an_error_not_infinity(exe, tmp_path):
    """The design check of a ground motion scaled by 1e250 overflows: an error naming the
    quantity in both doors (main: Infinity in design_loads.csv and exit 0)."""
    t = np.arange(400) * 0.02
    for door in ("exe", "py"):                  # beside each door's copy of the input
        (tmp_path / door).mkdir()
        (tmp_path / door / "record.csv").write_text(
            "".join(f"{x:.4f} {0.2 * math.sin(2 * x):.6f}\n" for x in t))
    ground = "&ground_motion\n  record = 'record.csv'\n  scale_factor = 1e250\n/\n"
    text = TANK.format(R=15, H=10, f=1) + ground + \
        "&design\n  spectrum = 'ground_motion'\n/\n" + LINEAR
    (code_a, out_a), (code_b, out_b) = both_doors(exe, tmp_path, text)
    assert code_a != 0 and code_a == code_b, (out_a, out_b)
    assert "the design check gives" in out_a and "the design check gives" in out_b
    for door in ("exe", "py"):
        for path in (tmp_path / door).rglob("*.csv"):
            assert "Infinity" not in path.read_text() and "NaN" not in path.read_text()


def test_complex_period_is_an_input_error():
    """DesignSpectrum.sa(1+1j): an InputError naming the period (main: a plain TypeError)."""
    with pytest.raises(InputError, match="period"):
        DesignSpectrum.asce7(s_ds=1.0, s_d1=0.6, t_l=8).sa(1 + 1j)


@pytest.mark.parametrize("factor", [0.8, 1.2])
def test_a_dome_radius_of_exactly_0_8_or_1_2_d_is_allowed(factor):
    """API 650 5.10.6's bounds are allowed (main refused 2.4 m for a 3 m tank, 0.8 x 3 =
    2.4000000000000004, quoting [2.4, 3.6] as allowed)."""
    roof_radius = float(f"{factor * 3.0:.10g}")
    tank = sloshdyn.Tank(radius=1.5, liquid_depth=2.0, freeboard=0.5, liquid_density=1000.0,
                         tank_mass=1e3, support_frequency=3.0, support_damping=0.02,
                         roof_radius=roof_radius)
    assert tank.properties["theta0"] > 0
    with pytest.raises(InputError, match=r"roof_radius = .*\[2.4, 3.6\]"):
        sloshdyn.Tank(radius=1.5, liquid_depth=2.0, freeboard=0.5, liquid_density=1000.0,
                      tank_mass=1e3, support_frequency=3.0, support_damping=0.02,
                      roof_radius=roof_radius * (0.99 if factor < 1 else 1.01))


@pytest.mark.parametrize("choice, label", [("code", "design accelerations"),
                                           ("elastic", "ELASTIC accelerations")])
def test_wall_pressure_at_the_codes_design_accelerations_labelled(exe, tmp_path, choice, label):
    """wall_pressure.csv at a code's design accelerations (API 650's A_i, A_c with I and R, SRSS)
    by default, the elastic ones only where asked, labelled so in the summary and the calc
    sheet (main: elastic, S_DS = 1.0 g, unlabelled)."""
    text = TANK.format(R=15, H=10, f=1) + ASCE_GROUP.format(
        extra=f"  importance = 1.25\n  use_group = 2\n  wall_pressure = '{choice}'\n") + LINEAR
    path = write(tmp_path, text)
    result = run(exe, path, tmp_path)
    assert result.returncode == 0, result.stderr
    assert label in result.stdout
    calc = (tmp_path / "out" / "design_calc.csv").read_text()
    assert ("ELASTIC" in calc.split("wall_pressure.csv")[1]) == (choice == "elastic")
    rows = {line.split(",")[0]: line for line in
            (tmp_path / "out" / "design_loads.csv").read_text().splitlines()[1:]}
    a_i = float(rows["API 650" if choice == "code" else "sloshdyn linear"].split(",")[3])
    assert f"a_i = {a_i:.5g} g" in result.stdout


def test_structure_rules_refused_alike(exe, tmp_path):
    """&tank_structure's rules with the tank: the courses' heights sum to liquid_depth +
    freeboard."""
    structure = "&tank_structure\n  course_height = 2, 2, 2\n  course_thickness = 10, 8, 6\n" \
                "  course_yield_strength = 250\n  course_tensile_strength = 400\n/\n"
    text = TANK.format(R=15, H=10, f=1) + structure + ASCE_GROUP.format(extra="") + LINEAR
    assert_refused_alike(exe, tmp_path, text, ["&tank_structure", "course_height", "11"])
    with pytest.raises(InputError, match="course_height"):
        sloshdyn.design_check(
            sloshdyn.Tank(**BROAD), DesignSpectrum.asce7(s_ds=1.0, s_d1=0.6, t_l=8.0),
            tank_structure=TankStructure(course_height=(2, 2, 2), course_thickness=(10, 8, 6),
                                         course_yield_strength=(250,),
                                         course_tensile_strength=(400,)))
