"""Reliability of the core and the executable under faults (issue 11, Fortran half): a full disk,
a failed rename, two runs into one directory, SIGINT/SIGTERM and Ctrl-C in Python, LAPACK's
XERBLA, and counts whose products overflow the integers. Each case runs in a subprocess, so a
process death shows as a failure and not as a dead test run.

Independent sources: the file-size limit set here (RLIMIT_FSIZE) decides which files can be
written; the files' row counts come from n_out; the exit codes are the table of
fortran/base/sloshdyn_status.f90 (docs/failure.md); the dynamic linker's own report
(LD_DEBUG=bindings) says which XERBLA LAPACK calls.
"""

import ctypes.util
import os
import resource
import signal
import subprocess
import sys
import textwrap
import time

import pytest

from conftest import read_csv, run, write

MODEL = ("&model s1 = 1.5, mu1 = 0.5, kappa = 1.804897259, theta0 = 0.7853981633974483, "
         "gamma = 0.001, beta = 10.0, delta = 0.1 /\n")
SIMULATE = MODEL + textwrap.dedent("""\
    &excitation A = 1.0475, rho = 0.513 /
    &analysis kind = 'simulate' /
    &simulation t_end = {t_end}, n_out = {n_out} /
    &output directory = 'out' /
    """)
# exit codes of fortran/base/sloshdyn_status.f90
EXIT_INPUT, EXIT_IO, EXIT_INTERRUPTED, EXIT_TERMINATED = 3, 5, 130, 143


def _leftovers(directory):
    """Hidden files (temporaries) left in the output directory (its run marker aside) or
    beside it (a run's new or previous directory, docs/failure.md)."""
    inside = [p.name for p in directory.iterdir() if p.name.startswith(".")
              and p.name != ".sloshdyn-run"]
    beside = [p.name for p in directory.parent.iterdir()
              if p.name.startswith(f".{directory.name}.")]
    return sorted(inside + beside)


def _limit_file_size(limit):
    """Before exec: files may not grow past `limit` bytes (ulimit -f). The executable ignores
    SIGXFSZ, so writing past it fails with EFBIG as writing to a full disk fails with ENOSPC."""
    def preexec():
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
    return preexec


def test_a_full_disk_leaves_nothing_and_exits_5(exe, tmp_path):
    # history.csv of 1001 rows is about 245 kB, parameters.csv under 1 kB: a 20 kB limit lets the
    # small files through and cuts history.csv (gfortran reports no error on write or close)
    write(tmp_path, SIMULATE.format(t_end=100.0, n_out=1001))
    result = subprocess.run([exe, "input.nml"], cwd=tmp_path, capture_output=True, text=True,
                            timeout=60, preexec_fn=_limit_file_size(20000))
    assert result.returncode == EXIT_IO, result.stderr
    assert "history.csv" in result.stderr and "bytes reached the disk" in result.stderr
    assert "Results written" not in result.stdout
    out = tmp_path / "out"
    assert not out.exists() or list(out.iterdir()) == []


def test_a_result_name_taken_by_a_directory_is_refused_and_kept(exe, tmp_path):
    # simulation.csv is a non-empty directory no run wrote: once the table's rename onto it
    # failed after parameters.csv and history.csv were in place; now the output directory is
    # refused before the run (it holds what no run wrote) and nothing in it is touched
    write(tmp_path, SIMULATE.format(t_end=10.0, n_out=11))
    blocker = tmp_path / "out" / "simulation.csv"
    blocker.mkdir(parents=True)
    (blocker / "keep").write_text("not ours\n")
    result = run(exe, "input.nml", tmp_path)
    assert result.returncode == EXIT_IO, result.stderr
    assert "simulation.csv" in result.stderr and "no sloshdyn run wrote" in result.stderr
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["simulation.csv"]
    assert (blocker / "keep").read_text() == "not ours\n"
    assert _leftovers(tmp_path / "out") == []


def test_two_runs_into_one_directory_each_write_whole_files(exe, tmp_path):
    # different n_out, so a file holding the other run's rows (or a mixture) is seen
    for name, n_out in (("a.nml", 4001), ("b.nml", 3001)):
        write(tmp_path, SIMULATE.format(t_end=200.0, n_out=n_out), name)
    children = [subprocess.Popen([exe, name], cwd=tmp_path, stdout=subprocess.DEVNULL,
                                 stderr=subprocess.PIPE, text=True) for name in ("a.nml", "b.nml")]
    for child in children:
        _, err = child.communicate(timeout=120)
        assert child.returncode == 0, err
    out = tmp_path / "out"
    assert _leftovers(out) == []
    rows = read_csv(out / "history.csv")
    assert len(rows) in (4001, 3001)
    assert rows[-1]["tau"] == 200.0 and all(len(r) == len(rows[0]) for r in rows)


def _start_long_run(exe, tmp_path):
    """A simulation to tau = 1e7 (the longest span allowed: many minutes), started and seen to
    be integrating."""
    write(tmp_path, SIMULATE.format(t_end=1e7, n_out=1001).replace(
        "&output", "&integration max_steps = 2000000000 /\n&output"))
    child = subprocess.Popen([exe, "input.nml"], cwd=tmp_path, stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
    assert child.stdout.readline().startswith("sloshdyn: simulate")
    time.sleep(1.0)          # past reading and into the integration
    assert child.poll() is None
    return child


def _signal_and_wait(child, sig):
    """Send sig, wait for the end (30 s: a bound for a hang, not a speed test; a child still
    running then is killed, so no test leaves a process behind)."""
    child.send_signal(sig)
    try:
        return child.communicate(timeout=30)
    finally:
        child.kill()
        child.wait()


@pytest.mark.parametrize("sig, code", [(signal.SIGINT, EXIT_INTERRUPTED),
                                       (signal.SIGTERM, EXIT_TERMINATED)])
def test_a_signal_stops_the_executable_and_removes_its_temporaries(exe, tmp_path, sig, code):
    child = _start_long_run(exe, tmp_path)
    _, err = _signal_and_wait(child, sig)
    assert child.returncode == code, err
    assert f"signal {int(sig)}" in err and "stopped on request" in err
    out = tmp_path / "out"
    assert not out.exists() or list(out.iterdir()) == []


CTRL_C = textwrap.dedent("""\
    import sys
    import sloshdyn
    p = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=0.7853981633974483,
                            A=1.0475, rho=0.513)
    call = {call}
    try:
        print("ready", flush=True)     # inside the try: a signal right after it is caught too
        call(p)
    except KeyboardInterrupt:
        # the flag is cleared: the next call runs to its end (tau = 10: 101 finite points)
        y = sloshdyn.simulate(p, 10.0, n_out=101).y
        print("interrupted", y.shape, bool((abs(y) < 10).all()), flush=True)
        sys.exit(130)
    """)


@pytest.mark.parametrize("call", [
    "lambda p: sloshdyn.simulate(p, 1e7, n_out=11, integration=sloshdyn.Integration(max_steps=2000000000))",
    "lambda p: sloshdyn.lyapunov_exponent(p, lyapunov=sloshdyn.Lyapunov(n_periods=10000000, transient_periods=0))",
])
def test_ctrl_c_stops_a_long_call_in_python(tmp_path, call):
    script = write(tmp_path, CTRL_C.format(call=call), "ctrl_c.py")
    child = subprocess.Popen([sys.executable, str(script)], cwd=tmp_path, stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
    assert child.stdout.readline().strip() == "ready"
    time.sleep(1.5)
    assert child.poll() is None
    out, err = _signal_and_wait(child, signal.SIGINT)
    assert child.returncode == 130, err
    assert out.strip() == "interrupted (4, 101) True"


def _xerbla_binding(command):
    """Which object LAPACK's reference to xerbla_ binds to, in the dynamic linker's words."""
    env = dict(os.environ, LD_BIND_NOW="1", LD_DEBUG="bindings")
    result = subprocess.run(command, capture_output=True, text=True, env=env, timeout=60)
    return [line for line in result.stderr.splitlines()
            if "liblapack" in line.split("to")[0] and "`xerbla_'" in line]


def test_lapack_calls_our_xerbla_in_the_executable_and_the_extension(exe):
    lines = _xerbla_binding([exe, "--help"])
    assert lines and all(line.split(" to ")[1].split()[0].endswith("/sloshdyn") for line in lines)
    lines = _xerbla_binding([sys.executable, "-c", "import sloshdyn"])
    assert lines and all("_core." in line.split(" to ")[1] for line in lines)


def test_an_illegal_lapack_argument_returns_info_in_python():
    # dgeev with lda = 1 < n = 2: LAPACK's own XERBLA would print and stop the interpreter
    code = textwrap.dedent(f"""\
        import ctypes
        import sloshdyn
        lapack = ctypes.CDLL({ctypes.util.find_library("lapack")!r})
        n, lda, one, lwork, info = (ctypes.c_int(v) for v in (2, 1, 1, 16, 0))
        a, w = (ctypes.c_double * 4)(), (ctypes.c_double * 16)()
        wr, wi, no = (ctypes.c_double * 2)(), (ctypes.c_double * 2)(), (ctypes.c_double * 1)()
        lapack.dgeev_(b"N", b"N", ctypes.byref(n), a, ctypes.byref(lda), wr, wi, no,
                      ctypes.byref(one), no, ctypes.byref(one), w, ctypes.byref(lwork),
                      ctypes.byref(info), 1, 1)
        print("info", info.value)
        """)
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            timeout=60)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "info -5"      # the 5th argument, lda, is illegal


BOUNDS = MODEL + "&excitation A = 0.00075, rho = 0.509615 /\n&output directory = 'out' /\n"


@pytest.mark.parametrize("groups, named", [
    # (10**5)**2 Newton starts per parameter value wrapped around the integers: a hang
    ("&analysis kind = 'frequency_response' /\n"
     "&response start = 0.45, stop = 0.55, n_amplitudes = 100000, n_phases = 100000 /",
     "n_amplitudes = 100000"),
    # 2e9 starts would allocate 85 GB and end the process
    ("&analysis kind = 'frequency_response' /\n&response start = 0.45, stop = 0.55, "
     "n_scan = 2000000000 /", "n_scan = 2000000000"),
    # 200 x 2e9 samples wrapped around the integers: maxima 0, motion 'periodic', exit 0
    ("&analysis kind = 'steady_state' /\n&steady samples_per_period = 2000000000 /",
     "samples_per_period = 2000000000"),
    ("&analysis kind = 'lyapunov' /\n&lyapunov n_periods = 2000000000 /",
     "n_periods = 2000000000"),
    ("&analysis kind = 'frequency_response' /\n"
     "&response start = 0.45, stop = 0.55, max_points = 2000000000 /",
     "max_points = 2000000000"),
])
def test_counts_beyond_their_bounds_are_refused_before_allocating(exe, tmp_path, groups, named):
    write(tmp_path, BOUNDS + groups + "\n")
    result = run(exe, "input.nml", tmp_path)
    assert result.returncode == EXIT_INPUT, result.stderr
    assert named in result.stderr and "out of range" in result.stderr
    assert not (tmp_path / "out").exists()


def test_python_gets_the_same_bound_as_the_executable(tmp_path):
    # in a subprocess: before the bound, this call hung (the product wrapped around)
    code = textwrap.dedent("""\
        import sloshdyn
        from sloshdyn.figures import FIG12
        try:
            sloshdyn.frequency_response(FIG12, (0.45, 0.55), continuation=sloshdyn.Continuation(
                n_amplitudes=100000, n_phases=100000))
        except sloshdyn.InputError as exc:
            print(exc)
        """)
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            timeout=60, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "n_amplitudes = 100000" in result.stdout and "out of range" in result.stdout


@pytest.mark.parametrize("excitation, named", [
    ("A = nan, rho = 0.5", "&excitation: A = NaN is out of range"),
    ("A = 0.001, rho = -1", "&excitation: rho = -1 is out of range"),
])
def test_an_excitation_value_blames_its_group(exe, tmp_path, excitation, named):
    write(tmp_path, MODEL + f"&excitation {excitation} /\n&analysis kind = 'linear' /\n"
          "&output directory = 'out' /\n")
    result = run(exe, "input.nml", tmp_path)
    assert result.returncode == EXIT_INPUT and named in result.stderr, result.stderr


def test_a_directory_nothing_can_be_written_to_exits_5(exe, tmp_path):
    # /proc refuses new entries to every user, root included (where chmod 555 would not stop
    # root): the run's new directory beside /proc/sloshdyn_out cannot be made
    write(tmp_path, SIMULATE.format(t_end=10.0, n_out=11).replace("'out'",
                                                                 "'/proc/sloshdyn_out'"))
    errors = []
    for command in ([exe], [sys.executable, "-m", "sloshdyn", "run"]):
        result = subprocess.run(command + ["input.nml"], cwd=tmp_path, capture_output=True,
                                text=True)
        assert result.returncode == EXIT_IO, result.stderr
        assert "Results written" not in result.stdout
        errors.append([line.split(": ", 1)[1] for line in result.stderr.splitlines()
                       if "cannot" in line])                # without the program's name
    assert errors[0] == errors[1]                       # both doors say it in the same words
    assert errors[0] and errors[0][0].endswith(
        "cannot write into '/proc/sloshdyn_out': cannot create its new directory in '/proc': "
        + os.strerror(2)), errors
