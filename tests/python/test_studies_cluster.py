"""A study on a cluster of separate processes started by the `dask` command line (issue 40's
"Done when"): a scheduler and two workers; both workers killed mid-study -- the study fails
after its grace time, exit 7, naming the cause; with workers back the rerun finishes, equal
bit for bit to a single-process run. Workers that cannot import sloshdyn, or import another
version, are refused by name. Readiness is waited for (the scheduler's file, the workers
registered, points in the store), never slept for; the limits are generous, the grace time
short (set by the test)."""

import os
import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest

from conftest import write

pytest.importorskip("dask.distributed")
xr = pytest.importorskip("xarray")
zarr = pytest.importorskip("zarr")

GRACE = 3        #: seconds, &study grace_time of these tests
PATIENCE = 180   #: seconds any readiness may take on a loaded machine

#: 8 points of ~0.5 s each (transient_periods): the study cannot finish in the moment between
#: the store's marker of 2 points done and the kill of the workers
SPEC = """
&model s1 = 1.5, mu1 = 0.5, kappa = 1.804897259, theta0 = 0.7853981633974483, gamma = 0.001 /
&excitation A = 0.00075, rho = 0.52 /
&steady settle_tol = 0, transient_periods = 3000, window_periods = 16, shooting = .false. /
&study kind = 'response_map', store = 'map.zarr', frequency_start = 0.5, frequency_stop = 0.52,
  n_frequencies = 8, amplitude_start = 0.00075, amplitude_stop = 0.00075, n_amplitudes = 1,
  points_per_task = 1, grace_time = {grace}, workers = 1, worker_kind = 'threads' /
"""

#: a worker preload: sloshdyn is not importable in it, as on a node where it is not installed
NO_SLOSHDYN = """
import sys
import textwrap


class NotInstalled:
    def find_spec(self, name, path=None, target=None):
        if name == "sloshdyn" or name.startswith("sloshdyn."):
            raise ModuleNotFoundError(f"No module named {name!r}", name=name)
        return None


for name in [m for m in sys.modules if m == "sloshdyn" or m.startswith("sloshdyn.")]:
    del sys.modules[name]
sys.meta_path.insert(0, NotInstalled())
"""

#: a worker preload: the sloshdyn it imports says another version, as another install would
OTHER_VERSION = """
import sloshdyn
sloshdyn.__version__ = "0.0.1"
"""


class DaskCluster:
    """A scheduler and workers, each a process group of its own started by `python -m dask`,
    their output in log files; stop() ends every group it started."""

    def __init__(self, where):
        self.where = where
        self.file = where / "scheduler.json"
        self.groups = []
        self.scheduler = self._start(["scheduler", "--host", "127.0.0.1", "--port", "0",
                                      "--no-dashboard", "--scheduler-file", str(self.file)],
                                     "scheduler")
        deadline = time.monotonic() + PATIENCE
        while not self.file.exists() and time.monotonic() < deadline:
            assert self.scheduler.poll() is None, self.log("scheduler")
            time.sleep(0.05)
        assert self.file.exists(), self.log("scheduler")
        from dask.distributed import Client
        self.client = Client(scheduler_file=str(self.file), timeout=PATIENCE)
        self.address = self.client.scheduler.address

    def _start(self, args, name):
        log = open(self.where / f"{name}.log", "w")
        process = subprocess.Popen([sys.executable, "-m", "dask", *args], cwd=self.where,
                                   stdout=log, stderr=subprocess.STDOUT,
                                   start_new_session=True)
        self.groups.append(process)
        return process

    def log(self, name):
        return (self.where / f"{name}.log").read_text()[-3000:]

    def worker(self, name, preload=None):
        """A worker (one thread, no nanny: killing it kills it), started and registered."""
        args = ["worker", "--scheduler-file", str(self.file), "--nthreads", "1", "--no-nanny",
                "--no-dashboard", "--name", name, "--local-directory", str(self.where)]
        if preload:
            args += ["--preload", str(write(self.where, preload, f"{name}_preload.py"))]
        process = self._start(args, name)
        deadline = time.monotonic() + PATIENCE
        while time.monotonic() < deadline:
            workers = self.client.scheduler_info(n_workers=-1)["workers"]
            named = [a for a, w in workers.items() if w.get("name") == name]
            if named:
                return process, named[0]
            assert process.poll() is None, self.log(name)
            time.sleep(0.05)
        raise AssertionError(f"worker {name} did not register: {self.log(name)}")

    def kill(self, process):
        os.killpg(process.pid, signal.SIGKILL)
        process.wait()

    def stop(self):
        self.client.close()
        for process in self.groups:
            if process.poll() is None:
                os.killpg(process.pid, signal.SIGKILL)
                process.wait()


@pytest.fixture
def dask_cluster(tmp_path):
    cluster = DaskCluster(tmp_path)
    try:
        yield cluster
    finally:
        cluster.stop()


def done_count(store):
    try:
        return int((zarr.open_group(str(store), mode="r")["done"][...] != 0).sum())
    except Exception:
        return 0


def study(spec, scheduler=None):
    command = [sys.executable, "-m", "sloshdyn", "study", str(spec), "--no-progress"]
    if scheduler:
        command += ["--scheduler", scheduler]
    return subprocess.Popen(command, cwd=spec.parent, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)


def test_killed_workers_fail_the_study_after_the_grace_time_and_the_rerun_is_exact(dask_cluster,
                                                                                   tmp_path):
    spec = write(tmp_path, SPEC.format(grace=GRACE), "spec.nml")
    store = tmp_path / "map.zarr"
    workers = [dask_cluster.worker(f"w{k}")[0] for k in (1, 2)]
    child = study(spec, dask_cluster.address)
    try:
        deadline = time.monotonic() + PATIENCE
        while done_count(store) < 2 and time.monotonic() < deadline and child.poll() is None:
            time.sleep(0.02)
        for worker in workers:
            dask_cluster.kill(worker)              # every worker gone mid-study
        killed = time.monotonic()
        stored_at_kill = done_count(store)
        out, err = child.communicate(timeout=PATIENCE)
        waited = time.monotonic() - killed
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()
    assert 2 <= stored_at_kill < 8, err[-3000:]
    assert child.returncode == 7, err[-3000:]
    assert waited >= GRACE                         # it waited the grace time, then failed
    assert f"no worker able to run the study has been alive for {GRACE} s (grace_time)" in err
    assert "left the cluster (killed, or lost)" in err and "rerun the same study" in err
    assert "Traceback" not in err
    kept = done_count(store)
    # with workers back, the rerun computes the rest
    for k in (3, 4):
        dask_cluster.worker(f"w{k}")
    again = study(spec, dask_cluster.address)
    out, err = again.communicate(timeout=PATIENCE)
    assert again.returncode == 0, err[-3000:]
    assert f"{8 - kept} points computed now" in out
    # ... equal, bit for bit, to the same study run in one process (embedded, one thread)
    alone = tmp_path / "alone"
    alone.mkdir()
    single = study(write(alone, SPEC.format(grace=GRACE), "spec.nml"))
    out, err = single.communicate(timeout=PATIENCE)
    assert single.returncode == 0, err[-3000:]
    cluster_run = xr.open_zarr(store).load()
    one_process = xr.open_zarr(alone / "map.zarr").load()
    assert set(cluster_run.data_vars) == set(one_process.data_vars)
    for name in one_process.data_vars:
        assert cluster_run[name].dtype == one_process[name].dtype, name
        assert np.array_equal(cluster_run[name].values, one_process[name].values,
                              equal_nan=cluster_run[name].dtype.kind == "f"), name


def test_workers_without_sloshdyn_or_with_another_version_are_refused_by_name(dask_cluster,
                                                                             tmp_path):
    spec = write(tmp_path, SPEC.format(grace=GRACE), "spec.nml")
    without, missing = dask_cluster.worker("without", NO_SLOSHDYN)
    another, other = dask_cluster.worker("other", OTHER_VERSION)
    child = study(spec, dask_cluster.address)
    out, err = child.communicate(timeout=PATIENCE)
    assert child.returncode == 7, err[-3000:]
    assert (f"{missing} is refused: it cannot import sloshdyn (ModuleNotFoundError: No module "
            f"named 'sloshdyn') with {sys.executable}") in err
    assert f"{other} is refused: it imports sloshdyn 0.0.1 with {sys.executable}, this client" \
        in err
    assert "Traceback" not in err
    assert done_count(tmp_path / "map.zarr") == 0
    # the workers refused were given no task (one it cannot unpickle ends a worker): alive
    assert without.poll() is None and another.poll() is None


def test_a_study_waits_for_min_workers_then_fails_naming_how_many_joined(dask_cluster,
                                                                         tmp_path):
    """&study min_workers: the study waits for them (at most grace_time), then exit 7."""
    spec = write(tmp_path, SPEC.format(grace=GRACE).replace("workers = 1,", "min_workers = 2,"),
                 "spec.nml")
    dask_cluster.worker("only")
    start = time.monotonic()
    child = study(spec, dask_cluster.address)
    out, err = child.communicate(timeout=PATIENCE)
    assert child.returncode == 7, err[-3000:]
    assert time.monotonic() - start >= GRACE
    assert (f"only 1 of the 2 workers asked for (min_workers) can run the study after {GRACE} "
            "s (grace_time): 1 joined the scheduler") in err
    assert not (tmp_path / "map.zarr").exists()         # nothing written before it starts



def test_ctrl_c_stops_the_point_a_worker_thread_is_computing(tmp_path):
    """A study of one point of 10 million forcing periods (about half an hour of one core) on a
    worker thread of this process: once the thread runs the task, Ctrl-C (SIGINT) sets the
    core's cancellation flag, which the running integration polls at every step, so the task
    ends and the cluster closes with no thread left computing (without the flag the close gave
    up after ~30 s and left the thread computing the point)."""
    import threading
    import sloshdyn
    point = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=0.7853981633974483,
                                gamma=0.001, A=0.00075, rho=0.5)
    long = sloshdyn.Steady(settle_tol=0, transient_periods=1e7, shooting=False)

    def computing():
        return [t for t in threading.enumerate() if "Dask-Default-Threads" in t.name]

    def interrupt():                          # once a worker thread runs the task
        deadline = time.monotonic() + PATIENCE
        while not computing() and time.monotonic() < deadline:
            time.sleep(0.05)
        os.kill(os.getpid(), signal.SIGINT)
    sender = threading.Thread(target=interrupt)
    sender.start()
    try:
        with pytest.raises(KeyboardInterrupt, match="study interrupted: 0 points stored"):
            sloshdyn.response_map(point, [0.5], [0.00075], tmp_path / "long.zarr", workers=1,
                                  worker_kind="threads", steady=long, progress=False)
    finally:
        sender.join()
    assert computing() == []
    # the flag is cleared: the next computation runs
    assert sloshdyn.steady_state(point.replace(rho=0.52)).motion


def test_a_result_lost_with_its_worker_is_not_waited_for(dask_cluster):
    """A task finished on a worker killed before its result was fetched: Dask reschedules it,
    and fetching it would wait for ever with no worker left (a study hung so, past its grace
    time, in CI). The engine's fetch gives up after a tick; the study's loop then resubmits
    the block or fails after the grace time. (In a child: a lost fetch leaves CPython 3.11.7's
    recursion count off, and the test process's later ast.parse would fail.)"""
    process, address = dask_cluster.worker("w1")
    child = subprocess.Popen([sys.executable, "-c", textwrap.dedent(f"""\
        import sys, time
        from distributed import Client
        from sloshdyn.studies.engine import fetched
        client = Client({dask_cluster.address!r}, timeout={PATIENCE})
        future = client.submit(sum, [3, 4], pure=False, workers=[{address!r}],
                               allow_other_workers=False)
        deadline = time.monotonic() + {PATIENCE}
        while future.status != "finished" and time.monotonic() < deadline:
            time.sleep(0.02)
        print(future.status, flush=True)
        sys.stdin.readline()                    # the parent has killed the worker
        print(repr(fetched(future)), flush=True)
        """)], stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert child.stdout.readline() == "finished\n", child.stderr.read()
        dask_cluster.kill(process)              # the result's only copy is gone
        out, err = child.communicate("go\n", timeout=PATIENCE)
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()
    assert out.splitlines()[0] == "None", err[-3000:]
