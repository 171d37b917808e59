"""Fault injection at both front doors (the executable and sloshdyn-py): a full disk (a small
tmpfs), a read-only directory, kill -9 and SIGTERM while writing, two runs into one directory.
After each, the output directory holds the complete results of one run or nothing of it (no
file under a final name, no temporary left where the process could clean up), and the exit code
says which (docs/failure.md)."""

import contextlib
import os
import resource
import select
import signal
import subprocess
import sys
import time

import pytest

from conftest import read_csv
from sloshdyn import _core
from sloshdyn._errors import EXIT_TERMINATED

#: the exit code of a write failure, by the core's rule (status SD_IO_ERROR = 8)
EXIT_IO = int(_core.sloshdyn_bridge_input.exit_code(8, False))
SIMULATE = ("&model s1 = 1.5, mu1 = 0.5, kappa = 1.8049, theta0 = 0.785, gamma = 0.001 /\n"
            "&excitation A = 0.001, rho = 0.5 /\n&analysis kind = 'simulate' /\n"
            "&simulation t_end = {t_end}, n_out = {n_out} /\n&output directory = '{out}' /\n")
RUN_FILES = {"history.csv", "parameters.csv"}


def front_door(door, exe):
    if door == "executable":
        return [exe]
    if door == "slow start":      # the executable starting 3 s late, as on a loaded machine
        return ["sh", "-c", 'sleep 3; exec "$0" "$@"', exe]
    return [sys.executable, "-m", "sloshdyn", "run"]


@contextlib.contextmanager
def tmpfs(path, size="256k", read_only=False):
    """A small file system of its own at path (mount needs root; none here is a failure of the
    environment, reported as such)."""
    path.mkdir(exist_ok=True)
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs", str(path)],
                             capture_output=True)
    if mounted.returncode != 0:       # CI runs as root: a failure to mount is a failure
        pytest.fail(f"cannot mount a tmpfs here: {mounted.stderr.decode().strip()}")
    try:
        (path / "out").mkdir()
        if read_only:
            subprocess.run(["mount", "-o", "remount,ro", str(path)], check=True)
        yield path
    finally:
        subprocess.run(["umount", "-l", str(path)], check=True)


def final_files(directory):
    """Names in a run's output directory that are not temporaries (temporaries start with .)."""
    if not directory.exists():
        return set()
    return {p.name for p in directory.iterdir() if not p.name.startswith(".")}


def leftovers(directory):
    """Temporaries of a run: hidden names in its output directory (its marker .sloshdyn-run
    aside) and its new directories beside it (.NAME.run-..., .NAME.previous-...)."""
    inside = {p.name for p in directory.iterdir() if p.name.startswith(".")
              and p.name != ".sloshdyn-run"} if directory.exists() else set()
    beside = {p.name for p in directory.parent.iterdir()
              if p.name.startswith(f".{directory.name}.")} if directory.parent.exists() else set()
    return inside | beside


DOORS = ["executable", "sloshdyn-py"]


@pytest.mark.parametrize("door", DOORS)
def test_full_disk_leaves_nothing_and_says_so(exe, tmp_path, door):
    with tmpfs(tmp_path / "disk") as disk:
        (tmp_path / "input.nml").write_text(SIMULATE.format(t_end=2000, n_out=100000,
                                                            out=disk / "out"))
        result = subprocess.run(front_door(door, exe) + ["input.nml"], cwd=tmp_path,
                                capture_output=True, text=True, timeout=120)
        assert result.returncode == EXIT_IO, result.stderr
        assert "history.csv" in result.stderr and "Traceback" not in result.stderr
        assert final_files(disk / "out") == set()
        assert leftovers(disk / "out") == set()


@pytest.mark.parametrize("door", DOORS)
def test_read_only_directory_leaves_nothing_and_says_so(exe, tmp_path, door):
    with tmpfs(tmp_path / "disk", read_only=True) as disk:
        (tmp_path / "input.nml").write_text(SIMULATE.format(t_end=20, n_out=100,
                                                            out=disk / "out"))
        result = subprocess.run(front_door(door, exe) + ["input.nml"], cwd=tmp_path,
                                capture_output=True, text=True, timeout=120)
        assert result.returncode in (3, EXIT_IO), result.stderr
        assert str(disk / "out") in result.stderr and "Traceback" not in result.stderr
        assert final_files(disk / "out") == set()


#: seconds a test waits for a run to become ready, and for it to end after a signal: guards
#: against a run that never gets there or ignores the signal, generous at any load
READY_SECONDS = 300
GUARD_SECONDS = 120


def first_line(proc):
    """Ready: the run printed the first line of its summary (the analysis starts, the signal
    handlers of both doors installed; docs/failure.md, "Signals")."""
    if not select.select([proc.stdout], [], [], 0.1)[0]:
        return False
    return proc.stdout.readline() != ""       # the line comes whole (flushed after it)


def handlers_installed(signum):
    """Ready: the process catches signum (SigCgt of /proc/PID/status)."""
    def ready(proc):
        with open(f"/proc/{proc.pid}/status") as f:
            caught = next(int(line.split()[1], 16) for line in f if line.startswith("SigCgt:"))
        return bool(caught >> (signum - 1) & 1)
    return ready


def writing(out):
    """Ready: the run writes its files (a temporary waits in its output directory)."""
    return lambda proc: bool(leftovers(out))


def _cpu_seconds(pid):
    """User + system CPU time of a process so far, its threads included."""
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _start_and_signal(command, cwd, sig, ready=first_line, within=GUARD_SECONDS, stdin=None):
    """Start command, send sig once ready(proc) holds: (exit code, stderr, CPU seconds the run
    used after the signal, which load does not stretch as it does wall time). The test fails
    if the run ends before it is ready, or still runs `within` s after the signal."""
    proc = subprocess.Popen(command, cwd=cwd, stdin=stdin, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + READY_SECONDS
    try:
        while not ready(proc):
            if proc.poll() is not None or time.monotonic() > deadline:
                proc.kill()
                pytest.fail(f"the run ended or hung before it was ready: exit {proc.wait()}, "
                            f"{proc.stderr.read()}")
            time.sleep(0.005)
        before = _cpu_seconds(proc.pid)
        children = resource.getrusage(resource.RUSAGE_CHILDREN)
        proc.send_signal(sig)
        _, stderr = proc.communicate(timeout=within)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()
        pytest.fail(f"still running {within} s after signal {sig}")
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    total = after.ru_utime + after.ru_stime - children.ru_utime - children.ru_stime
    return proc.returncode, stderr, total - before


LONG_RUN = dict(t_end=20000, n_out=200000, out="out")   # about 2 s computing, 2 s writing


def _complete_or_nothing(out, code):
    """The directory after an interrupted run: the whole run (exit 0; after kill -9 possibly
    too, if it had finished writing) or none of it."""
    files = final_files(out)
    if code == 0 or (code == -signal.SIGKILL and files):
        assert RUN_FILES <= files
        assert len(read_csv(out / "history.csv")) == LONG_RUN["n_out"]
    else:
        assert files == set(), (code, files)


@pytest.mark.parametrize("door", DOORS)
def test_kill_9_while_writing_leaves_no_final_file(exe, tmp_path, door):
    (tmp_path / "input.nml").write_text(SIMULATE.format(**LONG_RUN))
    code, _, _ = _start_and_signal(front_door(door, exe) + ["input.nml"], tmp_path,
                                   signal.SIGKILL, writing(tmp_path / "out"))
    assert code in (0, -signal.SIGKILL)
    _complete_or_nothing(tmp_path / "out", code)


#: both front doors: sloshdyn-py runs the bridge's run_input cancellable (it releases the GIL);
#: and one that starts late, which a delay instead of a readiness marker would signal too early
SIGTERM_CASES = ["executable", "sloshdyn-py", "slow start"]


@pytest.mark.parametrize("door", SIGTERM_CASES)
def test_sigterm_while_writing_cleans_up_and_exits_143(exe, tmp_path, door):
    """SIGTERM once a temporary is in the output directory (a readiness marker, not a delay:
    at a load average of 12 a delay of 2 s once came before sloshdyn-py's handler)."""
    (tmp_path / "input.nml").write_text(SIMULATE.format(**LONG_RUN))
    code, stderr, _ = _start_and_signal(front_door(door, exe) + ["input.nml"], tmp_path,
                                        signal.SIGTERM, writing(tmp_path / "out"))
    assert code in (0, EXIT_TERMINATED), stderr
    _complete_or_nothing(tmp_path / "out", code)
    assert leftovers(tmp_path / "out") == set()


def test_sigterm_during_reproduce_leaves_none_of_its_files(tmp_path):
    """sloshdyn-py's own writers: a run of `reproduce` stopped by SIGTERM renames none of its
    files into place and removes its temporaries."""
    out = tmp_path / "out"
    proc = subprocess.Popen([sys.executable, "-m", "sloshdyn", "reproduce", "--out", str(out),
                             "--quick", "--only", "3", "4", "9a", "9b"], cwd=tmp_path,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120
    while not leftovers(out) and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.005)              # until its first file waits under a temporary name
    proc.send_signal(signal.SIGTERM)
    _, stderr = proc.communicate(timeout=120)
    code = proc.returncode
    assert code == EXIT_TERMINATED, stderr
    assert "Traceback" not in stderr and "terminated" in stderr
    assert final_files(tmp_path / "out") == set() and leftovers(tmp_path / "out") == set()


def test_reproduce_on_a_full_disk_writes_none_of_its_files(tmp_path):
    with tmpfs(tmp_path / "disk", size="64k") as disk:
        result = subprocess.run([sys.executable, "-m", "sloshdyn", "reproduce", "--out",
                                 str(disk / "out"), "--quick", "--only", "3", "4"],
                                capture_output=True, text=True, timeout=600)
        assert result.returncode == EXIT_IO, result.stderr
        assert str(disk / "out") in result.stderr and "Traceback" not in result.stderr
        assert final_files(disk / "out") == set() and leftovers(disk / "out") == set()


@pytest.mark.parametrize("door", DOORS)
def test_two_runs_into_one_directory_leave_one_whole_run(exe, tmp_path, door):
    """Two runs with different inputs into the same directory at once: both succeed, and the
    directory holds the files of one of them (its parameters with its own history)."""
    procs = []
    for k, t_end in enumerate((300, 400)):
        (tmp_path / f"input{k}.nml").write_text(SIMULATE.format(t_end=t_end, n_out=20000,
                                                                out="out"))
        procs.append(subprocess.Popen(front_door(door, exe) + [f"input{k}.nml"], cwd=tmp_path,
                                      stdout=subprocess.DEVNULL, stderr=subprocess.PIPE))
    codes = [p.wait(timeout=300) for p in procs]
    assert codes == [0, 0]
    history = read_csv(tmp_path / "out" / "history.csv")
    assert len(history) == 20000 and history[-1]["tau"] in (300.0, 400.0)
    assert leftovers(tmp_path / "out") == set()


LYAPUNOV = ("&model s1 = 1.5, mu1 = 0.5, kappa = 1.8049, theta0 = 0.785, gamma = 0.001 /\n"
            "&excitation A = 0.001, rho = 0.5 /\n&analysis kind = 'lyapunov' /\n"
            "&lyapunov n_periods = 1000000 /\n&output directory = 'out' /\n")
#: Ctrl-C must end a run within this many seconds of its CPU, whatever the core is doing (CPU
#: time, which a loaded machine does not stretch; the run would go on for minutes)
CTRL_C_SECONDS = 1.0


@pytest.mark.parametrize("door", SIGTERM_CASES)
def test_ctrl_c_during_a_long_computation_ends_it_within_a_second(exe, tmp_path, door):
    """Ctrl-C once the run has printed its first line (the analysis starts; a readiness
    marker, not a delay: at a load average of 12 a delay of 4 s once came before sloshdyn-py's
    handler): exit 130 within a second of CPU time."""
    (tmp_path / "input.nml").write_text(LYAPUNOV)
    code, stderr, cpu = _start_and_signal(front_door(door, exe) + ["input.nml"], tmp_path,
                                          signal.SIGINT)
    assert code == 130 and "Traceback" not in stderr
    assert cpu < CTRL_C_SECONDS, cpu
    # the message says what became of the files (it once ended in "interrupted; " and nothing)
    assert stderr.strip() and not stderr.rstrip().endswith(";"), stderr
    assert final_files(tmp_path / "out") == set() and leftovers(tmp_path / "out") == set()


def test_python_writers_commit_a_run_whole_or_not_at_all(tmp_path):
    """sloshdyn's Python writers: two writers of one file never share a temporary; the files of
    a run_directory appear together when it succeeds, and none (nor a temporary) when it fails;
    an OSError becomes a FileError naming the file."""
    from sloshdyn import FileError
    from sloshdyn._files import run_directory, temporary_name, write_csv, write_text
    assert temporary_name(tmp_path / "a.csv") != temporary_name(tmp_path / "a.csv")
    with pytest.raises(RuntimeError):
        with run_directory(tmp_path / "run") as run:
            write_csv(run.path / "a.csv", {"x": [1.0, 2.0]})
            assert final_files(tmp_path / "run") == set()     # waiting for the commit
            raise RuntimeError("the run fails after its first file")
    assert final_files(tmp_path / "run") == set() and leftovers(tmp_path / "run") == set()
    with run_directory(tmp_path / "run") as run:
        write_csv(run.path / "a.csv", {"x": [1.0, 2.0]})
        write_text(run.path / "b.txt", "done")
    assert final_files(tmp_path / "run") == {"a.csv", "b.txt"}
    assert read_csv(tmp_path / "run" / "a.csv") == [{"x": 1.0}, {"x": 2.0}]
    assert leftovers(tmp_path / "run") == set()
    (tmp_path / "c.txt").mkdir()                              # a directory where a file goes
    with pytest.raises(FileError, match="c.txt"):
        write_text(tmp_path / "c.txt", "x")
    assert leftovers(tmp_path / "c.txt") == set()
