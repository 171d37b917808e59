"""The study engine's store and tasks (issue 40, items 2-5): chunks fixed when the store is
created, tasks of whole chunks sized when they are handed out and handed out in waves, a
resume not bound to the first run's task size, results identical whatever the task size; each
chunk's identity checked (a chunk copied to another block's place, or from another study, is
computed again); failed points stored with their status and message, counted and named; what a
study needs checked before its first point. Every expected value comes from an independent
source: a serial loop of steady_state, sloshdyn.seismic_response of the scaled record."""

import math
import shutil
import subprocess
import sys

import numpy as np
import pytest

import sloshdyn
from sloshdyn.studies import engine, store as stores
from conftest import ROOT, write
from test_studies import (AMPLITUDES, FIG12, FREQUENCIES, QUICK, STUDY_NML, assert_equals_serial,
                          example_tank, records, serial)

pytest.importorskip("dask.distributed")
xr = pytest.importorskip("xarray")


@pytest.fixture(scope="module")
def client():
    from dask.distributed import Client, LocalCluster
    with LocalCluster(n_workers=1, threads_per_worker=2, processes=False,
                      dashboard_address=None) as cluster, Client(cluster) as c:
        yield c


@pytest.fixture(scope="module")
def reference():
    return serial(FREQUENCIES, AMPLITUDES)


def study(client, store, ppt=1, **kw):
    return sloshdyn.response_map(FIG12, FREQUENCIES, AMPLITUDES, store, client=client,
                                 steady=QUICK, points_per_task=ppt, progress=False, **kw)


def recorded_blocks(monkeypatch):
    """The blocks of the tasks whose results the engine writes, in order."""
    blocks = []
    write = stores.Store.write

    def recording(self, block, result):
        blocks.append(tuple((s.start, s.stop) for s in block))
        return write(self, block, result)
    monkeypatch.setattr(stores.Store, "write", recording)
    return blocks


# ---- item 2: chunks fixed at creation, tasks of whole chunks sized when handed out ----------

def test_a_resume_is_not_bound_to_the_first_runs_task_size(client, tmp_path, monkeypatch,
                                                           reference):
    """The store is cut into chunks of 1 point (points_per_task = 1 at its creation); a rerun
    asking 6 points per task computes what is left in tasks of several chunks, and the study
    equals, variable for variable and bit for bit, one run in one task, and the serial loop."""
    s = tmp_path / "r.zarr"
    study(client, s, ppt=1)
    for chunk in ("0.0", "0.1", "1.0", "1.1", "2.0"):   # five of six points to compute again
        (s / "done" / chunk).unlink()
    blocks = recorded_blocks(monkeypatch)
    ds = study(client, s, ppt=6)
    assert ds.attrs["points_computed"] == 5
    assert max((b[0][1] - b[0][0]) * (b[1][1] - b[1][0]) for b in blocks) > 1   # not 1 point
    assert ds["done"].attrs and xr.open_zarr(s)["max_x1"].encoding["chunks"] == (1, 1)
    assert_equals_serial(ds, reference)
    monkeypatch.undo()
    whole = study(client, tmp_path / "w.zarr", ppt=6)
    single = study(client, tmp_path / "one.zarr", ppt=1)
    for name in whole.data_vars:
        assert np.array_equal(single[name].values, ds[name].values), name   # same chunks
        if name != "done":                   # the checksums follow the chunking
            assert np.array_equal(whole[name].values, ds[name].values), name


def test_tasks_are_whole_chunks_each_handed_out_once_whatever_the_task_size():
    """Tasks.take over a 7 x 5 grid of chunks of 2 x 3 points, with the task size changing at
    every call (as the workers come and go): every point is in exactly one task, every task a
    block of whole chunks (the last ones of an axis cut at its end)."""
    f, a = np.linspace(0.5, 0.52, 13), np.linspace(0.001, 0.002, 14)
    plan = engine.Plan("response_map", ("frequency", "amplitude"),
                       {"frequency": (f, {}), "amplitude": (a, {})}, {}, {}, {}, (2, 3), None,
                       lambda p: (min(13, p), max(1, min(14, p // min(13, p)))))
    tasks = engine.Tasks(plan, np.ones(plan.chunk_grid, dtype=bool))
    covered = np.zeros((13, 14), dtype=int)
    sizes = [1, 40, 7, 100, 12, 3, 64]
    k = 0
    while (block := tasks.take(sizes[k % len(sizes)])) is not None:
        k += 1
        covered[block] += 1
        for s, c, n in zip(block, plan.chunks, plan.shape):
            assert s.start % c == 0 and (s.stop % c == 0 or s.stop == n)
    assert k > 5 and np.all(covered == 1)


def test_tasks_are_handed_out_in_waves_a_few_per_worker_thread(client, tmp_path, monkeypatch,
                                                               reference):
    """Issue 40 item 5: the client holds at most TASKS_AHEAD_PER_THREAD tasks per worker
    thread (2 threads here), not one future per task (a 4000 x 4000 map of 1 point per task
    took 1.1 GB before its first point), and the study is the serial loop's."""
    from dask.distributed import Client
    outstanding = []
    submit = Client.submit

    def counting(self, *args, **kw):
        future = submit(self, *args, **kw)
        outstanding.append(future)
        waiting = [f for f in outstanding if not f.done()]
        counting.most = max(counting.most, len(waiting))
        return future
    counting.most = 0
    monkeypatch.setattr(Client, "submit", counting)
    ds = study(client, tmp_path / "waves.zarr", ppt=1)
    assert len(outstanding) == 6
    assert counting.most <= engine.TASKS_AHEAD_PER_THREAD * 2
    assert_equals_serial(ds, reference)


def test_a_4000_by_4000_map_of_one_point_per_task_is_refused_before_it_starts(tmp_path):
    """Issue 40 item 5: 16 million tasks of one point (a file per variable each, a mark in the
    client) are refused naming points_per_task and the smallest allowed, before anything is
    allocated or written; the refusing process stays far below 1 GB."""
    code = (
        "import resource, sys, numpy as np, sloshdyn\n"
        "from test_studies import FIG12\n"
        "try:\n"
        "    sloshdyn.response_map(FIG12, np.linspace(0.5, 0.52, 4000), "
        "np.linspace(0, 0.001, 4000), sys.argv[1], points_per_task=1, progress=False)\n"
        "except sloshdyn.InputError as exc:\n"
        "    print(exc)\n"
        "print('maxrss', resource.getrusage(resource.RUSAGE_SELF).ru_maxrss)\n")
    result = subprocess.run([sys.executable, "-c", code, str(tmp_path / "big.zarr")],
                            capture_output=True, text=True, timeout=300,
                            env={**__import__("os").environ,
                                 "PYTHONPATH": str(ROOT / "tests" / "python")})
    assert result.returncode == 0, result.stderr[-2000:]
    assert ("points_per_task = 1 is out of range: it would cut the study of 16000000 points "
            "into 16000000 tasks") in result.stdout
    fewest = math.ceil(16000000 / stores.MAX_CHUNKS)
    assert f"give points_per_task >= {fewest}" in result.stdout
    maxrss_kib = int(result.stdout.split("maxrss")[1])
    assert maxrss_kib < 1024**2                      # under 1 GiB (ru_maxrss is in KiB)
    assert not list(tmp_path.iterdir())


# ---- item 3: every chunk carries its identity ---------------------------------------------

def copy_chunk(store, source, target, names):
    for name in names:
        shutil.copyfile(store / name / source, store / name / target)


def test_a_valid_chunk_copied_to_another_blocks_place_is_computed_again(client, tmp_path,
                                                                        reference):
    """The attack of issue 40: every file of one finished chunk (its done mark included)
    copied over another's place; the rerun finds that the chunk is not of its place (its
    checksum covers the coordinates), computes it again and counts it, and every value is the
    serial loop's."""
    s = tmp_path / "c.zarr"
    first = study(client, s, ppt=1)
    names = [n for n in first.data_vars]
    copy_chunk(s, "0.0", "2.1", names)
    ds = study(client, s, ppt=1)
    assert ds.attrs["points_computed"] == 1 and ds.attrs["points_repaired"] == 1
    assert "not of its place" in ds.attrs["repaired"]
    assert_equals_serial(ds, reference)


def test_a_chunk_of_another_study_is_not_read_as_data(client, tmp_path, reference):
    """A chunk of another study of the same grid (another gamma) put into the store: its
    checksum names its study, so it is computed again, never read."""
    s, other = tmp_path / "s.zarr", tmp_path / "o.zarr"
    study(client, s, ppt=1)
    sloshdyn.response_map(FIG12.replace(gamma=0.002), FREQUENCIES, AMPLITUDES, other,
                          client=client, steady=QUICK, points_per_task=1, progress=False)
    for name in xr.open_zarr(s).data_vars:
        shutil.copyfile(other / name / "1.1", s / name / "1.1")
    ds = study(client, s, ppt=1)
    assert ds.attrs["points_repaired"] == 1
    assert_equals_serial(ds, reference)


# ---- item 4: a failed point is a result -----------------------------------------------------

def test_a_zero_record_is_a_failed_run_counted_named_and_left_out_of_the_fit(client, tmp_path):
    """Issue 40: a record of all zeros cannot be scaled to any Sa; its runs fail, each stored
    with its status and the core's message, and the fit says it rests on the other runs only
    (their count, and the failed ones named); the runs that succeed are seismic_response's."""
    tank = example_tank()
    base = records()[0]
    zero = sloshdyn.GroundMotion(dt=base.dt, acceleration=np.zeros(200), units="m/s^2")
    intensities = [0.15, 0.24, 0.3]
    ds = sloshdyn.fragility_study(tank, [base, zero], intensities, tmp_path / "z.zarr",
                                  client=client, names=["kt", "zeros"], progress=False)
    failed = ds.sel(record="zeros")
    assert np.all(failed.status.values > 0)
    assert all(m for m in failed.message.values)            # the core's reason, per run
    assert np.all(failed.roof_impact.values == -1) and np.all(np.isnan(failed.peak_base_shear))
    good = ds.sel(record="kt")
    assert np.all(good.status.values == 0) and not any(good.message.values)
    run = sloshdyn.seismic_response(tank, base.scaled(sa=0.24, period=tank.sloshing_period,
                                                      damping=0.005, units="g"))
    assert float(good.sel(intensity=0.24).peak_base_shear) == run.peaks["base_shear"][0]
    assert int(ds.fragility_runs) == 3 and ds.attrs["points_failed"] == 3
    assert "over 3 of 6 runs (3 failed and left out: record = zeros" in ds.attrs["fragility_fit"]


def test_the_study_command_names_failed_runs_and_exits_6(tmp_path):
    """sloshdyn-py study: the summary counts and names the failed runs and the exit status
    says that some failed (6, docs/failure.md); the fit's runs are counted."""
    from test_studies import FRAGILITY_NML, NAMES
    from sloshdyn._errors import EXIT_MEANINGS, EXIT_POINTS_FAILED
    (tmp_path / "rec").mkdir()
    for name, r in zip(NAMES[:2], records()[:2]):
        np.savetxt(tmp_path / "rec" / f"{name}.csv",
                   np.column_stack([r.time, r.acceleration / 9.80665]), delimiter=",")
    np.savetxt(tmp_path / "rec" / "zeros.csv", np.column_stack([np.arange(200) * 0.01,
                                                                 np.zeros(200)]), delimiter=",")
    nml = write(tmp_path, FRAGILITY_NML.replace("n_intensities = 4", "n_intensities = 2"))
    result = subprocess.run([sys.executable, "-m", "sloshdyn", "study", str(nml),
                             "--no-progress"], cwd=tmp_path, capture_output=True, text=True,
                            timeout=300)
    assert result.returncode == EXIT_POINTS_FAILED == 6, result.stderr[-2000:]
    assert "some points failed" in EXIT_MEANINGS[6]
    assert "failed: 2 of 6 points" in result.stdout and "record = zeros.csv" in result.stdout
    assert "of the 4 runs that succeeded (of 6)" in result.stdout
    assert "over 4 of 6 runs (2 failed and left out" in result.stdout


def test_a_failed_points_message_is_the_same_whatever_its_task(client, tmp_path):
    """Points that fail (here: too few steps allowed) carry the core's reason, without the
    number the core gives a point within its task: the same in tasks of 1 and of 6 points."""
    tight = sloshdyn.Integration(max_steps=50)
    one = study(client, tmp_path / "a.zarr", ppt=1, integration=tight)
    six = study(client, tmp_path / "b.zarr", ppt=6, integration=tight)
    assert np.all(one.status.values > 0) and one.attrs["points_failed"] == 6
    assert all(m and not m.startswith("point") for m in one.message.values.ravel())
    assert np.array_equal(one.message.values, six.message.values)
    single = sloshdyn.SloshdynError
    with pytest.raises(single) as alone:
        sloshdyn.steady_state(FIG12.replace(rho=FREQUENCIES[1], A=AMPLITUDES[0]), steady=QUICK,
                              integration=tight)
    assert str(one.message.values[1, 0]).split(": ")[-1] in str(alone.value)


# ---- item 5: checked before the first point -------------------------------------------------

def test_a_figure_format_that_cannot_be_drawn_is_refused_before_the_first_point(tmp_path):
    """&study figure = 'map.xyz': refused (exit 3, naming figure and the formats) before the
    study starts: no store is created (it used to fail after the whole study, traceback)."""
    nml = write(tmp_path, STUDY_NML.format(extra=", figure = 'map.xyz'"))
    result = subprocess.run([sys.executable, "-m", "sloshdyn", "study", str(nml),
                             "--no-progress"], cwd=tmp_path, capture_output=True, text=True,
                            timeout=300)
    assert result.returncode == 3, result.stderr[-2000:]
    assert "&study: figure = 'map.xyz' cannot be drawn" in result.stderr and ".png" in \
        result.stderr and "Traceback" not in result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["input.nml"]


@pytest.mark.parametrize("extra, match", [
    (", min_workers = 0", "min_workers = 0 is out of range"),
    (", min_workers = 2", "min_workers = 2 is out of range: the embedded cluster has workers = 1"),
    (", grace_time = 0", "grace_time = 0"),
    (", grace_time = 1e9", "grace_time = 1"),
])
def test_worker_bounds_are_checked_before_anything_runs(tmp_path, extra, match):
    nml = write(tmp_path, STUDY_NML.format(extra=extra))
    with pytest.raises(sloshdyn.InputError, match="&study: " + match):
        sloshdyn.read_namelist(nml)
    with pytest.raises(sloshdyn.InputError, match="min_workers = 3 is out of range"):
        sloshdyn.response_map(FIG12, [0.5], [0.001], tmp_path / "x.zarr", workers=2,
                              worker_kind="threads", min_workers=3, progress=False)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["input.nml"]


def test_a_study_of_the_spatial_model_is_refused_naming_the_study_and_the_model(tmp_path):
    """Issue 37 item 6: planar = .false. is refused by &study before the study starts (it used
    to run the planar model silently)."""
    text = STUDY_NML.format(extra="").replace("&model", "&model planar = .false., p = 1,", 1)
    nml = write(tmp_path, text)
    with pytest.raises(sloshdyn.InputError, match="&study: a response_map study runs the planar "
                                                  r"model only: planar = \.false\. \(the spatial "
                                                  r"model\) in &model"):
        sloshdyn.read_namelist(nml)


def test_a_study_started_before_its_workers_sizes_its_tasks_from_those_that_came(tmp_path,
                                                                                monkeypatch):
    """The docs' SLURM recipe starts the study right after cluster.scale, before any worker
    has joined: the study waits for min_workers, and its tasks are sized from the 4 workers
    then there -- 8 points each (auto_points_per_task(256, 4)) -- not as for one worker (32)."""
    import threading
    from dask.distributed import Client, LocalCluster
    f, a = np.linspace(0.5, 0.52, 32), np.linspace(0.0005, 0.001, 8)
    blocks = recorded_blocks(monkeypatch)
    with LocalCluster(n_workers=0, threads_per_worker=1, processes=False,
                      dashboard_address=None) as cluster, Client(cluster) as c:
        later = threading.Thread(target=cluster.scale, args=(4,))
        later.start()                             # the workers join while the study waits
        try:
            ds = sloshdyn.response_map(FIG12, f, a, tmp_path / "late.zarr", client=c,
                                       steady=QUICK, min_workers=4, progress=False)
        finally:
            later.join()
    assert engine.auto_points_per_task(256, 4) == 8 and engine.auto_points_per_task(256, 1) == 32
    sizes = {(b[0][1] - b[0][0]) * (b[1][1] - b[1][0]) for b in blocks}
    assert sizes == {8}, sizes
    assert ds.attrs["points_computed"] == 256 and ds.attrs["points_failed"] == 0
    expected = sloshdyn.steady_state(FIG12.replace(rho=float(f[5]), A=float(a[3])), steady=QUICK)
    assert float(ds.max_x1[5, 3]) == expected.max_x1


@pytest.mark.parametrize("build, group, text", [
    (lambda: sloshdyn.Steady(window_periods=10), "steady", "window_periods = 10"),
    (lambda: sloshdyn.Integration(rtol=1e-20), "integration", "rtol = 1e-20"),
    (lambda: sloshdyn.Lyapunov(n_periods=0), "lyapunov", "n_periods = 0"),
])
def test_settings_validate_their_ranges_when_built_by_the_cores_rules(tmp_path, build, group,
                                                                      text):
    """Issue 40 item 5: Steady(window_periods=10) (allowed 16...10^6) used to be accepted, and a
    map of it "completed" with status 1 and NaN at every point, exit 0. Now the settings
    object refuses it when built, by the core's rule (its message, as the namelist door
    gives it for the same value)."""
    with pytest.raises(sloshdyn.InputError) as built:
        build()
    assert text in str(built.value) and "out of range" in str(built.value)
    nml = write(tmp_path, STUDY_NML.format(extra="").replace(
        "&study", f"&{group} {text} /\n&study"), f"{group}.nml")
    if group == "steady":                 # the file's own &steady group gets the value
        nml = write(tmp_path, STUDY_NML.format(extra="").replace(
            "window_periods = 32", "window_periods = 10"), f"{group}.nml")
    with pytest.raises(sloshdyn.InputError) as read:
        sloshdyn.read_namelist(nml)
    assert str(read.value).endswith(str(built.value)), (read.value, built.value)


def test_the_second_of_two_studies_creating_one_store_opens_the_first_ones(client, tmp_path,
                                                                           monkeypatch,
                                                                           reference):
    """Two studies started at once on a new store: the second's rename finds the first's
    store in place. It opens that store (the same study: it resumes it) instead of saying
    "nothing of it is left" while the first one's store is there."""
    s = tmp_path / "race.zarr"
    create = stores.create

    def first_one_wins(plan, path):
        create(plan, path)                 # the other study's store, created just before
        return create(plan, path)          # this one's: the rename finds it there
    monkeypatch.setattr(stores, "create", first_one_wins)
    ds = study(client, s, ppt=2)
    assert_equals_serial(ds, reference)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["race.zarr"]   # no temporary left


def test_a_settings_group_out_of_range_is_refused_by_both_doors_whatever_the_analysis(exe,
                                                                                     tmp_path):
    """One rule: the executable refuses a &lyapunov or &steady the core's rules reject even
    when its analysis does not use it (exit 3, the same message as Python's settings object),
    as sloshdyn.Lyapunov(...) and sloshdyn.Steady(...) refuse it when built."""
    from conftest import run
    model = STUDY_NML.split("&steady")[0]
    for group, values, built in [
            ("lyapunov", "n_periods = 301, renormalise_every = 3",
             lambda: sloshdyn.Lyapunov(n_periods=301, renormalise_every=3)),
            ("steady", "window_periods = 10", lambda: sloshdyn.Steady(window_periods=10))]:
        nml = write(tmp_path, model + f"&{group} {values} /\n&analysis kind = 'linear' /\n"
                    "&output directory = 'out' /\n", f"{group}.nml")
        with pytest.raises(sloshdyn.InputError) as python:
            built()
        result = run(exe, nml, tmp_path)
        assert result.returncode == 3, result.stderr
        assert f"&{group}: {python.value}" in result.stderr
        assert not (tmp_path / "out").exists()
