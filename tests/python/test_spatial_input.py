"""The spatial model's front doors (issue 26, step 4): &model/&tank planar = .false., the second
ground-motion component of &ground_motion (record_y, azimuth, ellipticity), kind = 'swirl' and
the two-component seismic response, read by the one reader and run by the one driver.

Independent sources: the record files themselves (numpy reads the .AT2 values: both components
carry one scale factor, the first's, as FEMA P695 scales a pair); the Python API called on the
inputs the reader returns (sloshdyn.spatial: the executable's CSV files hold the same numbers,
bit for bit); the planar model's own seismic files (the planar default is unchanged)."""

import math
import shutil

import numpy as np
import pytest

import sloshdyn
from sloshdyn import spatial
from conftest import EXAMPLES, read_csv, run

G = 9.80665        # m/s^2 per g: the unit of the .AT2 values


def _at2(path):
    """The samples of a PEER .AT2 file [g], read independently of the core."""
    lines = path.read_text().splitlines()
    return np.array([float(v) for line in lines[4:] for v in line.split()])


def _copy_example(tmp_path, name):
    shutil.copy(EXAMPLES / name, tmp_path)
    shutil.copytree(EXAMPLES / "records", tmp_path / "records")
    return tmp_path / name


def test_two_components_example_reads_one_factor_for_both(tmp_path):
    inp = sloshdyn.read_namelist(_copy_example(tmp_path, "tank_two_components.nml"))
    assert not inp.planar and inp.analysis == "seismic"
    assert inp.spatial == {"azimuth": pytest.approx(math.pi / 6, abs=1e-15), "ellipticity": 0.0}
    x = _at2(EXAMPLES / "records" / "synthetic_kt.AT2")
    y = _at2(EXAMPLES / "records" / "synthetic_kt_y.AT2")
    first, second = inp.ground_motion, inp.ground_motion_y
    assert second.dt == first.dt == 0.01
    factor_x = first.acceleration[np.abs(x) > 0] / (G * x[np.abs(x) > 0])
    factor_y = second.acceleration[np.abs(y) > 0] / (G * y[np.abs(y) > 0])
    # one factor (not 1: the first record is scaled to Sa = 0.2 g), the same for both
    assert np.ptp(factor_x) < 1e-12 * factor_x[0] and abs(factor_x[0] - 1) > 1e-3
    assert np.allclose(factor_y, factor_x[0], rtol=1e-12, atol=0)


def test_two_components_executable_equals_the_python_api(exe, tmp_path):
    path = _copy_example(tmp_path, "tank_two_components.nml")
    result = run(exe, path.name, tmp_path)
    assert result.returncode == 0, result.stderr
    inp = sloshdyn.read_namelist(path)
    out = tmp_path / inp.directory
    r = spatial.seismic_response_2d(inp.tank, inp.ground_motion, inp.ground_motion_y,
                                    azimuth=inp.spatial["azimuth"], integration=inp.integration)
    rows = read_csv(out / "seismic_spatial.csv")
    for column, values in r.table.items():
        key = next(k for k in rows[0] if k.split(" [")[0] == column)
        assert [row[key] for row in rows] == list(values), column
    peaks = read_csv(out / "seismic_spatial_peaks.csv")[0]
    assert {k.split(" [")[0]: v for k, v in peaks.items()} == r.peaks
    # the codes' combinations of the two planar runs, from their peaks (ASCE 7-16 12.5.3.1(a))
    p1, p2 = r.peaks["base_shear_run_1"], r.peaks["base_shear_run_2"]
    assert r.peaks["base_shear_srss"] == pytest.approx(math.hypot(p1, p2), rel=1e-15)
    assert r.peaks["base_shear_100_30"] == pytest.approx(max(p1 + 0.3 * p2, 0.3 * p1 + p2),
                                                         rel=1e-15)
    assert not (out / "seismic.csv").exists()


def test_a_record_y_at_another_dt_is_read_onto_the_records_grid(tmp_path):
    """record_y at dt = 0.02 s beside a record at 0.01 s: read as its samples linear in between
    (numpy.interp) at the record's times over its own duration, scaled by the one factor."""
    shutil.copytree(EXAMPLES / "records", tmp_path / "records")
    y = _at2(EXAMPLES / "records" / "synthetic_kt_y.AT2")[::2]
    (tmp_path / "other_dt.AT2").write_text(
        "other dt\n\nACCELERATION TIME SERIES IN UNITS OF G\n"
        f"NPTS= {len(y):7d}, DT= 0.0200 SEC\n" + "\n".join(f"{v:15.7E}" for v in y) + "\n")
    path = _case(tmp_path, TANK.format(tank=", planar = .false.") + "&ground_motion record = "
                 "'records/synthetic_kt.AT2', record_y = 'other_dt.AT2', scale_factor = 1.5 /\n"
                 "&analysis kind = 'seismic' /\n")
    inp = sloshdyn.read_namelist(path)
    first, second = inp.ground_motion, inp.ground_motion_y
    assert second.dt == first.dt == 0.01 and len(second.acceleration) == 2 * len(y) - 1
    t = 0.01 * np.arange(len(second.acceleration))
    want = 1.5 * G * np.interp(t, 0.02 * np.arange(len(y)), y)
    np.testing.assert_allclose(second.acceleration, want, rtol=1e-14, atol=1e-15 * G)


def test_planar_default_is_unchanged(exe, tmp_path):
    """planar = .true. written out gives the files of the example without it, bit for bit."""
    for sub, extra in (("default", ""), ("explicit", "  planar = .true.\n")):
        (tmp_path / sub).mkdir()
        path = _copy_example(tmp_path / sub, "tank_seismic.nml")
        path.write_text(path.read_text().replace("  support_damping = 0.02\n",
                                                 "  support_damping = 0.02\n" + extra))
        assert run(exe, path.name, tmp_path / sub).returncode == 0
    out = sloshdyn.read_namelist(tmp_path / "default" / "tank_seismic.nml").directory
    for name in ("seismic.csv", "seismic_peaks.csv", "parameters.csv"):
        assert (tmp_path / "default" / out / name).read_bytes() == \
               (tmp_path / "explicit" / out / name).read_bytes(), name


def test_swirl_example_executable_equals_the_python_api(exe, tmp_path):
    path = _copy_example(tmp_path, "swirl_sweep.nml")
    result = run(exe, path.name, tmp_path)
    assert result.returncode == 0, result.stderr
    inp = sloshdyn.read_namelist(path)
    assert not inp.planar and inp.analysis == "swirl"
    r = inp.response_range
    band = spatial.swirl_band(inp.params, (r["start"], r["stop"]), continuation=inp.response,
                              integration=inp.integration)
    rows = read_csv(tmp_path / inp.directory / "swirl_branch.csv")
    assert [row["lambda"] for row in rows] == list(band.table["lambda"])
    assert [row["max_abs_nu"] for row in rows] == list(band.table["max_abs_nu"])
    edges = read_csv(tmp_path / inp.directory / "swirl_edges.csv")
    assert [e["lambda"] for e in edges] == list(band.edges["lambda"])
    # an edge lies between branch points on either side of |nu| = 1 (the band's definition)
    lam, nu = band.table["lambda"], band.table["max_abs_nu"]
    for e in edges:
        j = np.flatnonzero((lam[:-1] - e["lambda"]) * (lam[1:] - e["lambda"]) <= 0)
        assert any((nu[k] - 1) * (nu[k + 1] - 1) <= 0 for k in j)
    assert len(edges) >= 1


def _case(tmp_path, text, name="case.nml"):
    (tmp_path / name).write_text(text)
    return tmp_path / name


TANK = ("&tank radius = 5, liquid_depth = 6, freeboard = 1, liquid_density = 1000, tank_mass = 5e4, "
        "support_frequency = 2, support_damping = 0.02{tank} /\n")
SWIRL = ("&model s1 = 1.0, mu1 = 0.01, kappa = 1000, theta0 = 1.4, beta = 0, zeta = 5e-4, "
         "p = {p}, planar = .false. /\n&excitation A = 0.001, rho = 1.0 /\n"
         "&analysis kind = '{kind}' /\n&response start = 1.0, stop = 1.02 /\n")


@pytest.mark.parametrize("text,words", [
    (SWIRL.format(p=0, kind="swirl"), ["&model", "planar = .false.", "p >= 1", "p = 0"]),
    (SWIRL.format(p=2, kind="periodic_response"), ["&model", "planar = .false.",
                                                    "periodic_response"]),
    (SWIRL.format(p=2, kind="swirl").replace(", planar = .false.", ""),
     ["'swirl'", "planar = .false."]),
    (TANK.format(tank="") + "&ground_motion peak_acceleration = 0.1, frequency = 0.3, "
     "azimuth = 0.5 /\n&analysis kind = 'seismic' /\n", ["&ground_motion", "azimuth",
                                                        "planar = .false."]),
    (TANK.format(tank=", planar = .false.") + "&ground_motion peak_acceleration = 0.1, "
     "frequency = 0.3, azimuth = 7 /\n&analysis kind = 'seismic' /\n",
     ["&ground_motion", "azimuth = 7", "[-2 pi, 2 pi]"]),
    (TANK.format(tank=", planar = .false.") + "&ground_motion peak_acceleration = 0.1, "
     "frequency = 0.3, azimuth = NaN /\n&analysis kind = 'seismic' /\n",
     ["&ground_motion", "azimuth", "NaN"]),
    (TANK.format(tank=", planar = .false.") + "&ground_motion peak_acceleration = 0.1, "
     "frequency = 0.3, ellipticity = 1.5 /\n&analysis kind = 'seismic' /\n",
     ["&ground_motion", "ellipticity = 1.5", "[0, 1]"]),
    (TANK.format(tank=", planar = .false.") + "&ground_motion record = 'records/"
     "synthetic_kt.AT2', record_y = 'records/missing.AT2' /\n&analysis kind = 'seismic' /\n",
     ["&ground_motion", "record_y = 'records/missing.AT2'"]),
    (TANK.format(tank=", planar = .false.") + "&ground_motion peak_acceleration = 0.1, "
     "frequency = 0.3, record_y = 'records/synthetic_kt.AT2' /\n&analysis kind = 'seismic' /\n",
     ["&ground_motion", "record_y", "record"]),
])
def test_bad_spatial_input_names_the_variable_at_both_doors(exe, tmp_path, text, words):
    shutil.copytree(EXAMPLES / "records", tmp_path / "records")
    x = _at2(EXAMPLES / "records" / "synthetic_kt.AT2")[::2]
    (tmp_path / "other_dt.AT2").write_text(
        "other dt\n\nACCELERATION TIME SERIES IN UNITS OF G\n"
        f"NPTS= {len(x):7d}, DT= 0.0200 SEC\n" + "\n".join(f"{v:15.7E}" for v in x) + "\n")
    path = _case(tmp_path, text)
    result = run(exe, path.name, tmp_path)
    missing = "missing.AT2" in text      # FileError in Python, as for a missing record
    assert result.returncode == 3, result.stderr     # bad input (sloshdyn_main)
    with pytest.raises(sloshdyn.FileError if missing else sloshdyn.InputError) as info:
        sloshdyn.read_namelist(path)
    for word in words:
        assert word in result.stderr, (word, result.stderr)
        assert word in str(info.value), (word, str(info.value))
    assert not (tmp_path / "sloshdyn_output").exists()
