"""Records and input (issue 22, items 6, 7, 10, 11 and 15): only regular record files are read
and a FIFO or a device is refused at once by both front doors; a record's step and duration
are checked and named; a header line of column names, a tab in an AT2 header and a Unicode
path are read, a name ending in a blank and the bytes of a bad file are reported clearly; one
default damping (the convective 0.5 %) and unit (g) for a spectral acceleration; and the slow
flow's limit cycle outside the Hopf interval is reported as absent."""

import math
import os
import subprocess
import sys

import numpy as np
import pytest
from scipy import signal

import sloshdyn
from conftest import EXAMPLES

G = 9.80665                                             # standard gravity (CGPM 1901)
TANK = dict(radius=5.0, liquid_depth=6.0, freeboard=1.0, liquid_density=1000.0, tank_mass=5e4,
            support_frequency=2.0, support_damping=0.02)
TANK_NML = ("&tank radius = 5.0, liquid_depth = 6.0, freeboard = 1.0, liquid_density = 1000, "
            "tank_mass = 5.0e4, support_frequency = 2.0, support_damping = 0.02 /\n")
RECORD = EXAMPLES / "records" / "synthetic_kt.AT2"
HANG = 60          # a guard only: a run that waits for a FIFO's writer would never end


def seismic_nml(ground):
    return (TANK_NML + f"&ground_motion {ground} /\n&analysis kind = 'seismic' /\n"
            "&output directory = 'out' /\n")


def both_doors(exe, tmp_path, text):
    """(executable, sloshdyn-py run) on input.nml = text, each as a CompletedProcess."""
    (tmp_path / "input.nml").write_text(text, encoding="utf-8")
    runs = [subprocess.run(cmd + ["input.nml"], cwd=tmp_path, capture_output=True, text=True,
                           timeout=HANG)
            for cmd in ([exe], [sys.executable, "-m", "sloshdyn", "run"])]
    return runs


def in_child(code, tmp_path):
    """Run Python code in a child with 1 GiB of address space at most (a read of /dev/zero
    fails there instead of filling the machine), the guard timeout against a hang."""
    def limit():
        import resource
        resource.setrlimit(resource.RLIMIT_AS, (2 << 30, 2 << 30))
    return subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True,
                          text=True, timeout=HANG, preexec_fn=limit)


# ---- 6. FIFOs and devices -------------------------------------------------------------------

def test_a_fifo_as_a_record_is_refused_at_once_by_both_doors(exe, tmp_path):
    """Opening a FIFO waits for a writer: the reader must refuse it before it opens it."""
    os.mkfifo(tmp_path / "quake.AT2")
    for run in both_doors(exe, tmp_path, seismic_nml("record = 'quake.AT2'")):
        assert run.returncode == 3, run.stderr
        assert "quake.AT2" in run.stderr and "not a regular file" in run.stderr
        assert "Traceback" not in run.stderr
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("what", ["fifo", "/dev/zero", "/dev/null"])
def test_from_file_refuses_a_fifo_or_a_device_without_reading_it(tmp_path, what):
    if what == "fifo":
        os.mkfifo(tmp_path / "fifo")
    child = in_child(
        "import sloshdyn\n"
        "try:\n"
        f"    sloshdyn.GroundMotion.from_file({what!r})\n"
        "except sloshdyn.FileError as exc:\n"
        "    print(exc)\n", tmp_path)
    assert child.returncode == 0, child.stderr[-2000:]
    assert what in child.stdout and "not a regular file" in child.stdout


# ---- 7. the record's step and duration ------------------------------------------------------

@pytest.mark.parametrize("dt,named", [(1e-12, "dt = 1e-12"), (1e-300, "dt = 1e-300"),
                                      (1e300, "duration")])
def test_a_record_step_out_of_range_is_named(dt, named):
    """dt = 1e-12 s made t_end/dt overflow an integer (f2py's 'negative dimension' or a t_end
    the user never set); the rules: dt >= 1e-6 s and (n - 1) dt <= 1e6 s."""
    with pytest.raises(sloshdyn.InputError, match=named.replace("+", r"\+")):
        sloshdyn.GroundMotion(dt=dt, acceleration=[0.0, 1.0, 0.0])


def test_a_record_shorter_than_the_target_period_is_not_scaled_to_sa(exe, tmp_path):
    """Sa(T) of a record shorter than T would come from the free-vibration tail alone (an
    extrapolation): both doors refuse target_sa at the tank's sloshing period (3.35 s, the
    default target_period) for a 2 s record, naming target_period and the record's length;
    the same record scaled by its PGA runs; Python's scaled() names the same rule."""
    (tmp_path / "short.csv").write_text("".join(f"{0.01 * k!r}, {0.1 * np.sin(3.0 * k / 100)}\n"
                                                for k in range(201)))
    for run in both_doors(exe, tmp_path, seismic_nml("record = 'short.csv', target_sa = 0.1")):
        assert run.returncode == 3, run.stderr
        assert "target_period = 3.3" in run.stderr and "longer than the record (2 s)" in \
            run.stderr, run.stderr
    for run in both_doors(exe, tmp_path, seismic_nml("record = 'short.csv', target_pga = 0.1")):
        assert run.returncode == 0, run.stderr
    ground = sloshdyn.GroundMotion(dt=0.01, acceleration=np.sin(np.arange(201) * 0.03))
    with pytest.raises(sloshdyn.InputError, match="longer than the record"):
        ground.scaled(sa=0.1, period=2.5)
    assert ground.scaled(sa=0.1, period=1.5).scale_factor > 0


def test_a_record_file_with_a_too_fine_step_is_named_by_both_doors(exe, tmp_path):
    (tmp_path / "fine.csv").write_text("".join(f"{k * 1e-12!r}, {0.1 * (k % 2)}\n"
                                               for k in range(5)))
    for run in both_doors(exe, tmp_path, seismic_nml("record = 'fine.csv'")):
        assert run.returncode == 3, run.stderr
        assert "dt = 1e-12" in run.stderr and "t_end" not in run.stderr


# ---- 10. headers, tabs, names and bytes -----------------------------------------------------

def test_a_two_column_record_may_start_with_one_line_of_column_names(tmp_path):
    path = tmp_path / "quake.csv"
    path.write_text("time_s,accel_g\n0.00,0.0\n0.01,0.1\n0.02,-0.2\n0.03,0.0\n")
    g = sloshdyn.GroundMotion.from_file(path)
    assert g.dt == pytest.approx(0.01, rel=1e-12)
    assert g.acceleration == pytest.approx(G * np.array([0.0, 0.1, -0.2, 0.0]), rel=1e-15)
    # only one: a second line of words is an error naming its line
    path.write_text("time_s,accel_g\nseconds,g\n0.00,0.0\n0.01,0.1\n")
    with pytest.raises(sloshdyn.InputError, match="line 2"):
        sloshdyn.GroundMotion.from_file(path)
    # and a NaN in the first line is an error, not a header
    path.write_text("nan,0.0\n0.01,0.1\n0.02,0.0\n")
    with pytest.raises(sloshdyn.InputError, match="not finite"):
        sloshdyn.GroundMotion.from_file(path)


@pytest.mark.parametrize("fourth", ["NPTS=\t3,\tDT=\t0.01 SEC", "NPTS =\t3, DT\t= .01"])
def test_an_at2_header_may_have_tabs_around_its_equals_signs(tmp_path, fourth):
    path = tmp_path / "quake.AT2"
    path.write_text(f"PEER\nquake\nIN UNITS OF G\n{fourth}\n 0.1 -0.2 0.0\n")
    g = sloshdyn.GroundMotion.from_file(path)
    assert g.dt == pytest.approx(0.01, rel=1e-12)
    assert g.acceleration == pytest.approx(G * np.array([0.1, -0.2, 0.0]), rel=1e-15)


def test_a_record_name_ending_in_a_blank_is_refused_by_that_name(tmp_path):
    """Fortran drops trailing blanks: 'quake.AT2 ' would read quake.AT2, another file."""
    (tmp_path / "quake.AT2").write_bytes(RECORD.read_bytes())
    with pytest.raises(sloshdyn.InputError, match="ends in a blank"):
        sloshdyn.GroundMotion.from_file(tmp_path / "quake.AT2 ")


def test_the_bytes_of_a_bad_file_are_quoted_short_and_escaped(exe, tmp_path):
    junk = b"\x1b[2J\x1b[31m\x00\x07\xff\xfe" + bytes(range(128, 256)) * 40
    (tmp_path / "junk.csv").write_bytes(junk)
    with pytest.raises(sloshdyn.InputError) as raised:
        sloshdyn.GroundMotion.from_file(tmp_path / "junk.csv")
    message = str(raised.value)
    assert "\\x1b[2J\\x1b[31m\\x00\\x07\\xff\\xfe" in message and "..." in message
    assert all(32 <= ord(c) < 127 for c in message) and len(message) < 256
    for run in both_doors(exe, tmp_path, seismic_nml("record = 'junk.csv'")):
        assert run.returncode == 3
        assert "\x1b" not in run.stderr and "\\x1b" in run.stderr


def test_a_message_longer_than_256_characters_arrives_whole(tmp_path):
    """The core's messages were cut at 256 characters: a deep record path left no room for the
    line and the reason. The message names the whole path, the line and what was wrong."""
    folder = tmp_path / ("d" * 200)
    folder.mkdir()
    path = folder / ("r" * 40 + ".txt")
    path.write_text("0 0\n0.01 0.1\n0.02 0.3 9\n")
    with pytest.raises(sloshdyn.InputError) as raised:
        sloshdyn.GroundMotion.from_file(path)
    message = str(raised.value)
    assert len(message) > 256
    assert message == (f"record file '{path}', line 3: expected 2 values (time, acceleration), "
                       "found 3")


def test_a_unicode_record_path_works_in_both_doors(exe, tmp_path):
    folder = tmp_path / "séismes"
    folder.mkdir()
    (folder / "Kobé.AT2").write_bytes(RECORD.read_bytes())
    direct = sloshdyn.GroundMotion.from_file(folder / "Kobé.AT2")
    assert np.array_equal(direct.acceleration, sloshdyn.GroundMotion.from_file(RECORD)
                          .acceleration)
    (folder / "entrée.nml").write_text(seismic_nml("record = 'Kobé.AT2'"), encoding="utf-8")
    read = sloshdyn.read_namelist(folder / "entrée.nml")
    assert np.array_equal(read.ground_motion.acceleration, direct.acceleration)


# ---- 11. one default damping and unit for a spectral acceleration ----------------------------

def psa_by_scipy(ground, period, damping, tail_periods=5):
    """The pseudo-spectral acceleration of the piecewise linear record by scipy's lsim (a
    first-order hold is exact for it), with a free-vibration tail: independent of the core."""
    omega = 2 * np.pi / period
    a = np.concatenate([ground.acceleration,
                        np.zeros(int(math.ceil(tail_periods * period / ground.dt)))])
    system = signal.lti([[0, 1], [-omega ** 2, -2 * damping * omega]], [[0], [-1]],
                        [[1, 0]], [[0]])
    _, u, _ = signal.lsim(system, a, ground.dt * np.arange(a.size), interp=True)
    return omega ** 2 * np.max(np.abs(u))


def test_scaled_to_sa_at_the_sloshing_period_is_at_the_convective_damping_in_g():
    """scaled(sa=0.3, period=Tc) meant 0.3 g at 5 % and gave Sa(Tc, 0.5 %) = 0.036 g: now the
    default damping is the tank's convective 0.5 % and the unit g, as in &ground_motion."""
    tank = sloshdyn.Tank(**TANK)
    tc = tank.sloshing_period
    scaled = sloshdyn.GroundMotion.from_file(RECORD).scaled(sa=0.3, period=tc)
    assert psa_by_scipy(scaled, tc, 0.005) == pytest.approx(0.3 * G, rel=1e-6)
    assert tank.sloshing_damping == 0.005
    assert scaled.scaling == f"Sa({tc:g} s, 0.5 % damping) = 0.3 g"
    assert scaled.scale_factor == pytest.approx(scaled.pga / sloshdyn.GroundMotion.from_file(
        RECORD).pga, rel=1e-15)
    assert "0.5 % damping" in repr(scaled) and "0.3 g" in repr(scaled)
    spectrum = scaled.response_spectrum([tc])           # the same default damping
    assert spectrum.damping == 0.005 and spectrum.psa[0] == pytest.approx(0.3 * G, rel=1e-6)


def test_the_namelist_scales_with_the_same_defaults_and_prints_them(exe, tmp_path):
    (tmp_path / "quake.AT2").write_bytes(RECORD.read_bytes())
    text = seismic_nml("record = 'quake.AT2', target_sa = 0.3")
    (tmp_path / "input.nml").write_text(text)
    read = sloshdyn.read_namelist(tmp_path / "input.nml")
    tc = sloshdyn.Tank(**TANK).sloshing_period
    python = sloshdyn.GroundMotion.from_file(RECORD).scaled(sa=0.3, period=tc)
    assert np.array_equal(read.ground_motion.acceleration, python.acceleration)
    run = subprocess.run([exe, "input.nml"], cwd=tmp_path, capture_output=True, text=True,
                         timeout=120)
    assert run.returncode == 0, run.stderr
    line = next(x for x in run.stdout.splitlines() if x.strip().startswith("scaled"))
    assert "0.5 % damping" in line and f"{0.3 * G:g}" in line and "m/s^2" in line
    factor = line.rsplit("factor", 1)[1].strip()        # the tank summary: 5 significant digits
    assert factor == f"{python.scale_factor:.5g}"


# ---- 15. no limit cycle outside the Hopf interval --------------------------------------------

def test_slow_flow_cycle_outside_the_hopf_interval_says_there_is_none(fig12):
    """At rho = 0.515 (beyond the upper Hopf point of Fig 12's response) the slow flow settles
    to a stable steady state: a ConvergenceError that says so, not an internal t_out."""
    response = sloshdyn.frequency_response(fig12, rho_range=(0.49, 0.53))
    hopf = sorted(s.rho for s in response.special_points if s.kind == "hopf")
    p = fig12.replace(rho=0.515)
    assert len(hopf) == 2 and not hopf[0] < p.rho < hopf[1]
    with pytest.raises(sloshdyn.ConvergenceError, match="no limit cycle at rho = 0.515") as e:
        sloshdyn.slow_flow_cycle(p)
    assert "settles to an equilibrium" in str(e.value) and "t_out" not in str(e.value)
