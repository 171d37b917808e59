"""Parameter studies (sloshdyn.studies): each result against an independent source -- a serial
loop of steady_state, the sweeps that carry the state, the shooting code's orbits, synthetic
data with known parameters -- and the engine's promises: resumable after SIGKILL, a killed
worker changes nothing, other studies' stores refused, bad input named before anything is
written. Grids are tiny and transients short: the long measurements are in
benchmarks/studies.py."""

import json
import math
import os
import signal
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import sloshdyn
from sloshdyn import studies
from conftest import ROOT

pytest.importorskip("dask.distributed")
xr = pytest.importorskip("xarray")
zarr = pytest.importorskip("zarr")

FIG12 = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=math.pi / 4,
                            gamma=0.001, A=0.00075, rho=0.50)
QUICK = sloshdyn.Steady(max_transient_periods=600, window_periods=32)
FREQUENCIES = [0.505, 0.513, 0.52]
AMPLITUDES = [0.0005, 0.00075]


@pytest.fixture(scope="module")
def client():
    from dask.distributed import Client, LocalCluster
    with LocalCluster(n_workers=1, threads_per_worker=2, processes=False,
                      dashboard_address=None) as cluster, Client(cluster) as c:
        yield c


def serial(frequencies, amplitudes, steady=QUICK):
    """The independent source: a plain loop of steady_state over the grid."""
    return [[sloshdyn.steady_state(FIG12.replace(rho=f, A=a), steady=steady)
             for a in amplitudes] for f in frequencies]


def assert_equals_serial(ds, expected):
    for i, row in enumerate(expected):
        for j, st in enumerate(row):
            point = ds.isel(frequency=i, amplitude=j)
            for name in ("max_x1", "max_x2", "max_u1", "max_u2", "transient_periods"):
                assert float(point[name]) == getattr(st, name), (name, i, j)   # bit for bit
            assert sloshdyn.simulation.MOTIONS[int(point["motion"])] == st.motion
            assert int(point["period"]) == st.period
            assert bool(point["roof_impact"]) == (st.max_x1 >= 1)


def test_response_map_equals_a_serial_loop_bit_for_bit(client, tmp_path):
    ds = sloshdyn.response_map(FIG12, FREQUENCIES, AMPLITUDES, tmp_path / "map.zarr",
                               client=client, steady=QUICK, points_per_task=2, progress=False)
    assert ds["max_x1"].dims == ("frequency", "amplitude")
    assert list(ds.frequency.values) == FREQUENCIES and list(ds.amplitude.values) == AMPLITUDES
    assert_equals_serial(ds, serial(FREQUENCIES, AMPLITUDES))
    assert bool(ds["done"].all()) and ds.attrs["points_computed"] == 6
    for name, var in ds.data_vars.items():              # every variable described
        assert "long_name" in var.attrs, name
        assert name.startswith("message") or "units" in var.attrs, name    # text: none
    assert ds.frequency.attrs["units"] == "1" and "rho" in ds.frequency.attrs["long_name"]
    assert json.loads(ds.attrs["parameters"])["kappa"] == FIG12.kappa
    assert json.loads(ds.attrs["steady"])["max_transient_periods"] == 600
    assert ds.attrs["sloshdyn_version"] == sloshdyn.__version__
    # the store holds the same, and a rerun returns at once without computing anything
    stored = xr.open_zarr(tmp_path / "map.zarr").load()
    assert stored["max_x1"].equals(ds["max_x1"])
    again = sloshdyn.response_map(FIG12, FREQUENCIES, AMPLITUDES, tmp_path / "map.zarr",
                                  client=client, steady=QUICK, progress=False)
    assert again.attrs["points_computed"] == 0 and again["max_x1"].equals(ds["max_x1"])


def test_continuation_equals_the_sweeps_that_carry_the_state(client, tmp_path):
    f = [0.5107, 0.514, 0.517, 0.52]
    ds = sloshdyn.response_map(FIG12, f, [0.00075], tmp_path / "c.zarr", client=client,
                               continuation="both", progress=False)
    up = sloshdyn.frequency_sweep(FIG12, f)
    down = sloshdyn.frequency_sweep(FIG12, f[::-1])
    assert list(ds["max_x1_up"].values[:, 0]) == list(up.column("max_x1"))
    assert list(ds["max_x1_down"].values[::-1, 0]) == list(down.column("max_x1"))
    # 0.52 is between the folds: from rest the low branch, carried up the large one
    assert ds["max_x1_up"].values[-1, 0] > 10 * ds["max_x1"].values[-1, 0]


def test_impact_parameter_study_equals_a_serial_loop_of_the_same_points(client, tmp_path):
    """A 2 x 2 (beta, delta) study against the loop it stands for: at each point the
    carried continuation along A (amplitude_sweep) and the Lyapunov exponent at the last A."""
    p = FIG12.replace(rho=0.513)
    betas, deltas, a = [1.0, 100.0], [0.01, 1.0], [0.00075, 0.3, 1.0475, 2.0]
    steady, lyapunov = sloshdyn.Steady(max_transient_periods=300, window_periods=32), (10, 60)
    ds = sloshdyn.impact_parameters(p, betas, deltas, a, tmp_path / "impact.zarr", client=client,
                                    steady=steady, lyapunov_periods=lyapunov,
                                    points_per_task=1, progress=False)
    assert ds["max_x1"].dims == ("beta", "delta", "A") and bool(ds["done"].all())
    for i, beta in enumerate(betas):
        for j, delta in enumerate(deltas):
            q = p.replace(beta=beta, delta=delta)
            sweep = sloshdyn.amplitude_sweep(q, a, steady=steady)
            exponent = sloshdyn.lyapunov_exponent(q.replace(A=2.0), sweep.y_final,
                                                  lyapunov=sloshdyn.Lyapunov(
                                                      transient_periods=10, n_periods=60)).exponent
            assert list(ds["max_x1"].values[i, j]) == list(sweep.column("max_x1"))
            assert [studies.MOTIONS[int(m)] for m in ds["motion"].values[i, j]] == \
                [pt.motion for pt in sweep.points]
            assert ds["lyapunov"].values[i, j] == exponent
            x = dict(zip(a, sweep.column("max_x1")))
            fig17 = x[2.0] >= 1 and exponent > 0
            assert bool(ds["fig17_holds"].values[i, j]) == fig17
            assert bool(ds["all_hold"].values[i, j]) == (
                bool(ds["fig15_holds"].values[i, j]) and bool(ds["fig16_holds"].values[i, j])
                and fig17)
    with pytest.raises(sloshdyn.InputError, match="A_values lacks A = 1.0475"):
        sloshdyn.impact_parameters(p, betas, deltas, [0.00075, 2.0], tmp_path / "bad.zarr",
                                   client=client, progress=False)


def test_a_store_of_another_study_is_refused_and_left_alone(client, tmp_path):
    store = tmp_path / "s.zarr"
    sloshdyn.response_map(FIG12, [0.505], [0.0005], store, client=client, steady=QUICK,
                          progress=False)
    before = sorted(p.name for p in store.rglob("*"))
    other = sloshdyn.Steady(max_transient_periods=700, window_periods=32)
    with pytest.raises(sloshdyn.InputError, match=r"s\.zarr.*different study.*steady"):
        sloshdyn.response_map(FIG12, [0.505], [0.0005], store, client=client, steady=other,
                              progress=False)
    with pytest.raises(sloshdyn.InputError, match="frequencies"):
        sloshdyn.response_map(FIG12, [0.505, 0.51], [0.0005], store, client=client,
                              steady=QUICK, progress=False)
    assert sorted(p.name for p in store.rglob("*")) == before


@pytest.mark.parametrize("frequencies, amplitudes, match", [
    ([], [0.001], "frequencies is empty"),
    ([0.5], [], "amplitudes is empty"),
    ([0.5, float("nan")], [0.001], r"frequencies\[1\] = nan"),
    ([0.5], [-0.001], r"amplitudes\[0\] = -0.001"),
    ([0.0], [0.001], r"frequencies\[0\] = 0.0"),
    ([0.5, 0.5], [0.001], "repeated"),
    ([0.5], [2000.0], "A = 2000"),
])
def test_bad_axes_are_named_and_nothing_is_written(tmp_path, frequencies, amplitudes, match):
    with pytest.raises(sloshdyn.InputError, match=match):
        sloshdyn.response_map(FIG12, frequencies, amplitudes, tmp_path / "x.zarr",
                              progress=False)
    assert not list(tmp_path.iterdir())


def test_unwritable_store_and_bad_settings_are_refused_before_anything_runs(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("")
    with pytest.raises(sloshdyn.InputError, match="cannot be created"):
        sloshdyn.response_map(FIG12, [0.5], [0.001], blocker / "x.zarr", progress=False)
    with pytest.raises(sloshdyn.InputError, match="is a file"):
        sloshdyn.response_map(FIG12, [0.5], [0.001], blocker, progress=False)
    with pytest.raises(sloshdyn.InputError, match="continuation"):
        sloshdyn.response_map(FIG12, [0.5], [0.001], tmp_path / "y.zarr", continuation="sideways")
    with pytest.raises(sloshdyn.InputError, match="points_per_task"):
        sloshdyn.response_map(FIG12, [0.5], [0.001], tmp_path / "y.zarr", points_per_task=0)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file"]


def test_a_scheduler_address_where_nothing_listens_is_refused_at_once_and_said_so(tmp_path):
    """Issue 44 item 12: a refused connection is said as such, not as a silence of 5 s."""
    with socket.socket() as s:          # a port nobody listens on
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    start = time.monotonic()
    with pytest.raises(sloshdyn.InputError, match=f"scheduler = 'tcp://127.0.0.1:{port}' "
                                                  "refused the connection: nothing listens at "
                                                  f"127.0.0.1:{port}"):
        sloshdyn.response_map(FIG12, [0.5], [0.001], tmp_path / "x.zarr",
                              scheduler=f"tcp://127.0.0.1:{port}", progress=False)
    assert time.monotonic() - start < 20


def test_progress_bar_shows_rate_and_eta(client, tmp_path, capsys):
    sloshdyn.response_map(FIG12, [0.505, 0.51], [0.0005], tmp_path / "p.zarr", client=client,
                          steady=QUICK, points_per_task=1, progress=True)
    err = capsys.readouterr().err
    assert "response map" in err and "point/s" in err and "<" in err    # rate and ETA


def test_the_bridge_releases_the_gil_during_fortran_work():
    """While a long Fortran call runs, another Python thread keeps counting (with the GIL held
    it could not count at all between the two reads around the call)."""
    count = [0]
    running = [True]

    def counter():
        while running[0]:
            count[0] += 1

    thread = threading.Thread(target=counter)
    thread.start()
    try:
        time.sleep(0.01)
        before = count[0]
        sloshdyn.steady_state(FIG12.replace(rho=0.513), steady=sloshdyn.Steady(
            settle_tol=0, transient_periods=1500))
        during = count[0] - before
    finally:
        running[0] = False
        thread.join()
    assert during > 1000


def test_eight_thread_workers_give_the_serial_answer(tmp_path):
    ds = sloshdyn.response_map(FIG12, FREQUENCIES, AMPLITUDES, tmp_path / "w8.zarr",
                               workers=8, worker_kind="threads", steady=QUICK,
                               points_per_task=1, progress=False)
    assert_equals_serial(ds, serial(FREQUENCIES, AMPLITUDES))


SLOW = sloshdyn.Steady(settle_tol=0, transient_periods=800, window_periods=16, shooting=False)
SLOW_F = list(np.linspace(0.50, 0.52, 12))

_CHILD = """
import sys, numpy as np, sloshdyn
from test_studies import FIG12, SLOW, SLOW_F
if __name__ == "__main__":
    sloshdyn.response_map(FIG12, SLOW_F, [0.00075], sys.argv[1], workers=1,
                          worker_kind="threads", steady=SLOW, points_per_task=1, progress=False)
"""


def done_count(store):
    try:
        return int((zarr.open_group(str(store), mode="r")["done"][...] != 0).sum())
    except Exception:
        return 0


def test_a_study_killed_mid_way_resumes_and_recomputes_only_what_was_missing(tmp_path):
    store = tmp_path / "k.zarr"
    script = tmp_path / "child.py"
    script.write_text(_CHILD)
    env = {**os.environ, "PYTHONPATH": str(ROOT / "tests" / "python")}
    child = subprocess.Popen([sys.executable, str(script), str(store)], env=env,
                             start_new_session=True, stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE)
    try:
        deadline = time.monotonic() + 120
        while done_count(store) < 3 and time.monotonic() < deadline and child.poll() is None:
            time.sleep(0.02)
        os.kill(child.pid, signal.SIGKILL)          # the process running the study
    finally:
        child.wait()
    finished = done_count(store)
    assert 3 <= finished < len(SLOW_F), child.stderr.read().decode()[-2000:]
    ds = sloshdyn.response_map(FIG12, SLOW_F, [0.00075], store, workers=1,
                               worker_kind="threads", steady=SLOW, points_per_task=1,
                               progress=False)
    assert ds.attrs["points_computed"] == len(SLOW_F) - finished
    assert_equals_serial(ds, serial(SLOW_F, [0.00075], SLOW))


def test_a_worker_killed_mid_study_changes_nothing(tmp_path):
    from dask.distributed import Client, LocalCluster
    store = tmp_path / "w.zarr"
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None, silence_logs=50) as cluster, Client(cluster) as c:
        pids = list(c.run(os.getpid).values())
        killed = []

        def killer():
            deadline = time.monotonic() + 60
            while done_count(store) < 2 and time.monotonic() < deadline:
                time.sleep(0.02)
            os.kill(pids[0], signal.SIGKILL)
            killed.append(done_count(store))

        thread = threading.Thread(target=killer)
        thread.start()
        ds = sloshdyn.response_map(FIG12, SLOW_F, [0.00075], store, client=c, steady=SLOW,
                                   points_per_task=1, progress=False)
        thread.join()
    assert killed and killed[0] < len(SLOW_F)       # killed mid-study
    assert_equals_serial(ds, serial(SLOW_F, [0.00075], SLOW))



def test_a_result_lost_between_wait_and_fetch_is_waited_for_again(monkeypatch):
    """A task's future that wait reported done and that is no longer finished when the loop
    looks (its result left with a killed worker in between: Dask computes it again, status
    'lost' or 'pending') is waited for again, not raised as the task's error (it has none:
    the loop raised None, a TypeError, in the killed-worker test above). Stand-ins for the
    client, the plan, the tasks and the workers; the future is lost on the first wait only."""
    import distributed
    from sloshdyn.studies import engine

    class Future:
        status, waits = "pending", 0

        def result(self, timeout=None):
            return {"x": 1.0}

        def exception(self):
            return None

        def cancel(self):
            pass

    future = Future()

    def fake_wait(futures, timeout, return_when):
        future.waits += 1
        future.status = "lost" if future.waits == 1 else "finished"
        return type("Done", (), {"done": set(futures)})()

    class Plan:
        points_per_task = 1

        def task(self, block):
            return sum, ([1],)

        def block_size(self, block):
            return 1

    class Tasks:
        free = np.array([True])

        def points_left(self):
            return int(self.free.sum())

        def take(self, points):
            if not self.free.any():
                return None
            self.free[:] = False
            return (slice(0, 1),)

    class Pool:
        usable = ["worker"]

        def check_alive(self):
            pass

        def threads(self):
            return 1

    written = []
    client = type("Client", (), {"submit": lambda self, *a, **k: future})()
    writer = type("Writer", (), {"write": lambda self, block, result: written.append(result)})()
    monkeypatch.setattr(distributed, "wait", fake_wait)
    computed, _ = engine._run_tasks(client, Plan(), Tasks(), Pool(), writer, None, lambda: None)
    assert (computed, written, future.waits) == (1, [{"x": 1.0}], 2)

# ---- basins ----------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def two_orbits():
    """rho = 0.52 lies between the folds of Fig 12's large branch: the small orbit from rest,
    the large one carried up from rho = 0.5107 (both by the shooting code)."""
    p = FIG12.replace(rho=0.52)
    low = sloshdyn.periodic_orbit(p, sloshdyn.steady_state(p).y_end)
    sweep = sloshdyn.frequency_sweep(FIG12, np.linspace(0.5107, 0.52, 10))
    high = sloshdyn.periodic_orbit(p, sweep.y_final)
    assert low.stable and high.stable and high.max_x1 > 10 * low.max_x1
    return p, low, high


def test_basins_find_both_coexisting_orbits_and_start_on_each_stays_there(client, tmp_path,
                                                                       two_orbits):
    p, low, high = two_orbits
    for name, orbit in (("high", high), ("low", low)):
        c = orbit.y0
        ds = sloshdyn.basins(p, (c[0] - 0.1, c[0] + 0.1), (c[1] - 0.1, c[1] + 0.1), n=3,
                             store=tmp_path / f"{name}.zarr", x2=float(c[2]), dx2=float(c[3]),
                             client=client, progress=False)
        centre = ds.isel(x1=1, dx1=1)          # started on the orbit
        label = int(centre["attractor"])
        state = ds["attractor_state"].sel(attractor_id=label).values
        assert np.allclose(state, orbit.y0, rtol=0, atol=1e-8 * np.abs(orbit.y0).max())
        assert ds["attractor_stability"].sel(attractor_id=label) == "stable"
        assert float(centre["transient_periods"]) <= 16
        assert ds["attractor_share"].sum() == pytest.approx(1.0)
        stored = xr.open_zarr(tmp_path / f"{name}.zarr").load()
        assert stored["attractor"].equals(ds["attractor"])
        assert stored.attrs["study_spec"] == ds.attrs["study_spec"]
        assert "points_computed" not in stored.attrs
        assert list(stored["attractor_stability"].values) == list(ds["attractor_stability"].values)
        rerun = sloshdyn.basins(p, (c[0] - 0.1, c[0] + 0.1), (c[1] - 0.1, c[1] + 0.1), n=3,
                                store=tmp_path / f"{name}.zarr", x2=float(c[2]),
                                dx2=float(c[3]), client=client, progress=False)
        assert rerun.attrs["points_computed"] == 0 and rerun["attractor"].equals(ds["attractor"])
        if name == "high":                     # this grid reaches both attractors
            assert ds.sizes["attractor_id"] == 2
            for j in ds.attractor_id.values:
                s = ds["attractor_state"].sel(attractor_id=j).values
                shot = sloshdyn.periodic_orbit(p, s)       # the shooting code's orbit
                assert np.allclose(shot.y0, s, rtol=0, atol=1e-8 * np.abs(s).max())
                assert max(abs(shot.multipliers)) == pytest.approx(
                    float(ds["attractor_max_multiplier"].sel(attractor_id=j)), rel=1e-6)
            states = ds["attractor_state"].values
            assert any(np.allclose(s, low.y0, atol=1e-8) for s in states)
            # shooting jumps only to the attractor the integration approaches: every start
            # ends on the same orbit as by integration alone
            plain = sloshdyn.basins(p, (c[0] - 0.1, c[0] + 0.1), (c[1] - 0.1, c[1] + 0.1),
                                    n=3, store=tmp_path / "plain.zarr", x2=float(c[2]),
                                    dx2=float(c[3]), client=client, progress=False,
                                    steady=sloshdyn.Steady(shooting=False))
            assert np.allclose(plain["max_x1"], ds["max_x1"], rtol=1e-5)
            same = {int(a): int(b) for a, b in zip(ds.attractor.values.ravel(),
                                                   plain.attractor.values.ravel())}
            assert len(same) == 2 and len(set(same.values())) == 2


def test_basins_bad_input(tmp_path):
    with pytest.raises(sloshdyn.InputError, match="x1_range"):
        sloshdyn.basins(FIG12, (0.1, 0.1), (0, 1), n=3, store=tmp_path / "b.zarr")
    with pytest.raises(sloshdyn.InputError, match="n = 1"):
        sloshdyn.basins(FIG12, (0, 1), (0, 1), n=1, store=tmp_path / "b.zarr")
    with pytest.raises(sloshdyn.InputError, match="store is missing"):
        sloshdyn.basins(FIG12, (0, 1), (0, 1), n=3)
    assert not list(tmp_path.iterdir())


# ---- fragility fit ---------------------------------------------------------------------------

def synthetic(rng, median, beta, n_levels=10, runs=40):
    x = np.repeat(np.geomspace(median / 4, median * 4, n_levels), runs)
    failed = rng.random(x.size) < sloshdyn.FragilityFit(median, beta, 0, 0, 0, 0).probability(x)
    return x, failed.astype(float)


def test_fragility_fit_recovers_median_and_dispersion_within_their_standard_errors():
    """Synthetic lognormal data with known median and beta: over 200 data sets the estimates
    fall within one standard error about 68 % of the time and within two about 95 %, as
    standard errors must (binomial bounds at about 3 sigma)."""
    rng = np.random.default_rng(13)
    median, beta = 0.45, 0.4
    within1, within2 = np.zeros(2), np.zeros(2)
    trials = 200
    for _ in range(trials):
        fit = sloshdyn.fit_fragility(*synthetic(rng, median, beta))
        err = np.abs([fit.median - median, fit.beta - beta]) / [fit.median_se, fit.beta_se]
        within1 += err < 1
        within2 += err < 2
    assert np.all(np.abs(within1 / trials - 0.683) < 0.1), within1
    assert np.all(np.abs(within2 / trials - 0.954) < 0.05), within2


def test_fragility_fit_counts_form_and_bad_input():
    x = np.geomspace(0.1, 2, 8)
    counts = np.full(8, 50)
    failures = np.round(counts * sloshdyn.FragilityFit(0.5, 0.3, 0, 0, 0, 0).probability(x))
    fit = sloshdyn.fit_fragility(x, failures, counts)
    assert fit.median == pytest.approx(0.5, rel=0.05) and fit.beta == pytest.approx(0.3, rel=0.1)
    with pytest.raises(sloshdyn.InputError, match="all 0 or all 1"):
        sloshdyn.fit_fragility([0.1, 0.2], [0, 0])
    with pytest.raises(sloshdyn.InputError, match=r"intensities\[1\] = -0.2"):
        sloshdyn.fit_fragility([0.1, -0.2], [0, 1])


# ---- steady states by shooting (item 6) -----------------------------------------------------

@pytest.mark.parametrize("rho", [0.49, 0.505, 0.513, 0.52])
def test_shooting_gives_the_integration_only_steady_state_of_periodic_cases(rho):
    p = FIG12.replace(rho=rho)
    jump = sloshdyn.steady_state(p)
    plain = sloshdyn.steady_state(p, steady=sloshdyn.Steady(shooting=False))
    assert jump.motion == plain.motion == "periodic" and jump.period == plain.period
    for name in ("max_x1", "max_x2", "max_u1", "max_u2"):
        # the integration only approaches the orbit: settle_tol/(1 - |mu|) ~ 2e-5 relative
        assert getattr(jump, name) == pytest.approx(getattr(plain, name), rel=1e-5), name
    assert jump.transient_periods < plain.transient_periods / 20
    orbit = sloshdyn.periodic_orbit(p, jump.y_end)       # it ends on the shooting code's orbit
    assert np.allclose(orbit.y0, jump.y_end, atol=1e-9) and orbit.stable


def test_non_periodic_steady_states_are_those_of_the_integration():
    p = FIG12.replace(rho=0.51)                          # quasi-periodic (Fig 12, between Hopfs)
    settings = dict(max_transient_periods=1500, window_periods=64)
    jump = sloshdyn.steady_state(p, steady=sloshdyn.Steady(**settings))
    plain = sloshdyn.steady_state(p, steady=sloshdyn.Steady(shooting=False, **settings))
    assert jump.motion in ("quasi-periodic", "settling") and jump.transient_periods == 1500
    for name in sloshdyn.simulation.SUMMARY_COLUMNS:
        assert getattr(jump, name) == getattr(plain, name), name
    assert np.array_equal(jump.poincare, plain.poincare)


# ---- sweeps of the executable keep what they finished (item 5) -------------------------------

SWEEP_NML = """
&model s1 = 1.5, mu1 = 0.5, kappa = 1.804897259, theta0 = 0.7853981633974483, gamma = 0.001 /
&excitation A = 0.00075, rho = 0.5 /
&analysis kind = 'sweep' /
&sweep parameter = 'A', start = 0.00075, stop = 3.0, n_points = 6 /
&integration max_steps = {max_steps} /
&steady {steady} /
&output directory = 'out' /
"""


def sweep_rows(path):
    from conftest import read_csv
    return read_csv(path)


def test_a_failing_sweep_keeps_the_points_it_finished(exe, tmp_path):
    from conftest import run, write
    write(tmp_path, SWEEP_NML.format(max_steps=300000, steady=""))
    result = run(exe, "input.nml", tmp_path)       # out: beside it (relative in the message)
    assert result.returncode == 4                       # the last points need more steps
    partial = tmp_path / "out" / "sweep.partial.csv"
    rows = sweep_rows(partial)
    assert f"the {len(rows)} of 6 points completed are kept in out/sweep.partial.csv" in result.stderr
    assert 1 <= len(rows) < 6
    # the failed run's directory, swapped into place, holds them and its marker only
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == [".sloshdyn-run",
                                                                     "sweep.partial.csv"]
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".out.")]
    # the same points in a sweep that completes: identical rows (the independent source)
    done = write(tmp_path, SWEEP_NML.format(max_steps=300000, steady="").replace(
        "stop = 3.0, n_points = 6", f"stop = {rows[-1]['A']!r}, n_points = {len(rows)}")
        .replace("'out'", "'full'"), "full.nml")
    assert run(exe, done, tmp_path).returncode == 0
    assert sweep_rows(tmp_path / "full" / "sweep.csv") == rows
    assert not (tmp_path / "full" / "sweep.partial.csv").exists()


def test_a_killed_sweep_keeps_the_points_it_finished(exe, tmp_path):
    from conftest import write
    slow = "settle_tol = 0, transient_periods = 3000, window_periods = 16, shooting = .false."
    nml = write(tmp_path, SWEEP_NML.format(max_steps=100000000, steady=slow)
                .replace("stop = 3.0", "stop = 0.00125"))
    child = subprocess.Popen([exe, str(nml)], cwd=tmp_path, stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
    try:
        said = ""        # the line saying where the points go (in the run's own directory)
        for line in child.stdout:
            if "points are written to" in line:
                said = line
                break
        partial = Path(said.split("points are written to ")[1].split(" as they")[0])
        assert partial.parent.name.startswith(".out.run-") and partial.name == "sweep.partial.csv"
        for line in child.stdout:           # a line per point: two points are on disk
            if line.strip().startswith("0.00") and len(partial.read_text().splitlines()) >= 3:
                break
        child.kill()
    finally:
        child.wait()
    rows = sweep_rows(partial)
    assert 2 <= len(rows) < 6 and all(len(r) == 11 for r in rows)
    # the first point as steady_state computes it from rest (CSV keeps 17 digits: exact)
    first = sloshdyn.steady_state(FIG12.replace(A=rows[0]["A"]), steady=sloshdyn.Steady(
        settle_tol=0, transient_periods=3000, window_periods=16, shooting=False))
    assert rows[0]["max_x1"] == first.max_x1 and rows[0]["max_u2"] == first.max_u2


# ---- the command line and &study ---------------------------------------------------------------

STUDY_NML = """
&model s1 = 1.5, mu1 = 0.5, kappa = 1.804897259, theta0 = 0.7853981633974483, gamma = 0.001 /
&excitation A = 0.00075, rho = 0.52 /
&steady max_transient_periods = 600, window_periods = 32 /
&study kind = 'response_map', store = 'map.zarr', frequency_start = 0.505,
  frequency_stop = 0.52, n_frequencies = 3, amplitude_start = 0.0005, amplitude_stop = 0.00075,
  n_amplitudes = 2, workers = 1, worker_kind = 'threads' {extra} /
"""


def test_study_command_runs_the_namelist_study_and_draws_it(tmp_path):
    from conftest import write
    nml = write(tmp_path, STUDY_NML.format(extra=""))
    result = subprocess.run([sys.executable, "-m", "sloshdyn", "study", str(nml), "--no-progress"],
                            cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr[-2000:]
    assert "6 points computed now" in result.stdout
    assert (tmp_path / "map.png").stat().st_size > 10000
    ds = xr.open_zarr(tmp_path / "map.zarr").load()
    assert_equals_serial(ds, serial(np.linspace(0.505, 0.52, 3), AMPLITUDES))
    # the executable refuses a study file, naming the front door that runs it
    from conftest import run
    import sysconfig
    exe = os.path.join(sysconfig.get_path("scripts"), "sloshdyn")
    refused = run(exe, nml, tmp_path)
    assert refused.returncode == 3 and "sloshdyn-py study" in refused.stderr


@pytest.mark.parametrize("extra, match", [
    (", kind = 'fragile'", "kind = 'fragile' is not known"),
    (", continuation = 'left'", "continuation = 'left' is not known"),
    (", worker_kind = 'gpus'", "worker_kind = 'gpus' is not known"),
    (", n_frequencies = 0", r"n_frequencies = 0 is out of range"),
    (", workers = -1", r"workers = -1 is out of range"),
    (", frequency_start = -0.1", "frequency_start = -0.1"),
    (", store = ''", "store = '' is empty"),
])
def test_study_group_rules_name_the_variable(tmp_path, extra, match):
    from conftest import write
    nml = write(tmp_path, STUDY_NML.format(extra=extra))
    with pytest.raises(sloshdyn.InputError, match="&study: " + match):
        sloshdyn.read_namelist(nml)
    result = subprocess.run([sys.executable, "-m", "sloshdyn", "study", str(nml)], cwd=tmp_path,
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 3 and match.replace("\\", "") in result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["input.nml"]


# ---- a tank in SI units: response map in Hz x g, fragility study -----------------------------

def example_tank():
    """The tank of data/examples/tank_seismic.nml."""
    return sloshdyn.Tank(radius=5.0, liquid_depth=6.0, freeboard=1.0, liquid_density=1000,
                         tank_mass=5.0e4, support_frequency=2.0, support_damping=0.02)


def test_tank_response_map_in_hz_and_g_at_constant_acceleration(client, tmp_path):
    tank = example_tank()
    f = [0.9 / tank.sloshing_period, 1.1 / tank.sloshing_period]       # [Hz]
    a = [0.02, 0.05]                                                    # [g]
    ds = sloshdyn.response_map(tank, f, a, tmp_path / "t.zarr", client=client, steady=QUICK,
                               progress=False)
    assert ds.frequency.attrs["units"] == "Hz" and ds.amplitude.attrs["units"] == "g"
    for i, fi in enumerate(f):
        for j, aj in enumerate(a):
            p = tank.parameters(sloshdyn.GroundMotion.harmonic(aj, fi, units="g"))
            st = sloshdyn.steady_state(p, steady=QUICK)
            point = ds.isel(frequency=i, amplitude=j)
            assert float(point.max_x1) == st.max_x1 and float(point.rho) == p.rho
            assert float(point.A) == p.A
    # constant acceleration: A = a/(L Omega^2) falls as 1/f^2
    ratio = ds.A.values[0, :] / ds.A.values[1, :]
    assert ratio == pytest.approx([(f[1] / f[0]) ** 2] * 2, rel=1e-12)


def records():
    """Four records made from the example (synthetic) one -- as written, reversed in time and
    played faster, played 1.5 and 2 times slower. Scaled to Sa(T_sloshing, 0.5 %), their free
    waves (which decide the roof contact, issue 23) are nearly the linear 0.84 R Sa/g
    (measured at 0.24 g: 0.997, 0.993, 0.990, 1.015 m against the 1 m freeboard)."""
    base = sloshdyn.GroundMotion.from_file(ROOT / "data/examples/records/synthetic_kt.AT2")
    a = base.acceleration
    return [base, sloshdyn.GroundMotion(dt=0.7 * base.dt, acceleration=a[::-1], units="m/s^2"),
            sloshdyn.GroundMotion(dt=1.5 * base.dt, acceleration=a, units="m/s^2"),
            sloshdyn.GroundMotion(dt=2.0 * base.dt, acceleration=a, units="m/s^2")]


NAMES = ["kt", "kt_reversed_fast", "kt_slow", "kt_slower"]


def test_fragility_study_of_a_tank(client, tmp_path):
    tank = example_tank()
    # Sa(T_sloshing, 0.5 %) [g]: the free wave reaches the 1 m freeboard near 0.24 g, where
    # the linear wave 0.84 R Sa/g = 1.0 m (EC8-4 A.2.1.4)
    intensities = [0.15, 0.2, 0.24, 0.26, 0.3]
    ds = sloshdyn.fragility_study(tank, records(), intensities, tmp_path / "f.zarr",
                                  client=client, names=NAMES, progress=False)
    assert ds.peak_wave_height.dims == ("record", "intensity")
    assert ds.peak_base_shear.attrs["units"] == "N"
    assert ds.peak_overturning_moment.attrs["units"] == "N m"
    fraction = (ds.roof_impact == 1).mean("record").values
    assert np.all(np.diff(fraction) >= 0) and fraction[0] == 0 and fraction[-1] == 1
    assert 0 < fraction[2] < 1                                     # the runs overlap
    assert np.all(np.diff(ds.free_wave_height.values, axis=1) > 0)   # more shaking, higher wave
    # each run is sloshdyn.seismic_response of the record scaled to the intensity
    g = records()[1].scaled(sa=0.24, period=tank.sloshing_period, damping=0.005, units="g")
    run = sloshdyn.seismic_response(tank, g)
    point = ds.sel(record="kt_reversed_fast", intensity=0.24)
    assert float(point.peak_wave_height) == run.peaks["wave_height"][0]
    assert float(point.peak_base_shear) == run.peaks["base_shear"][0]
    assert int(point.roof_impact) == run.roof_reached
    # the fit of the study is fit_fragility of its runs
    fit = sloshdyn.fit_fragility(np.tile(intensities, 4), ds.roof_impact.values.ravel())
    assert float(ds.fragility_median) == pytest.approx(fit.median, rel=1e-12)
    assert float(ds.fragility_dispersion) == pytest.approx(fit.beta, rel=1e-12)
    assert intensities[0] < float(ds.fragility_median) < intensities[-1]
    assert ds.fragility_median.attrs["units"] == "g"
    # and the store holds it (issue 22 item 5)
    stored = xr.open_zarr(tmp_path / "f.zarr").load()
    for name in ("fragility_median", "fragility_dispersion", "fragility_median_se",
                 "fragility_dispersion_se"):
        assert float(stored[name]) == float(ds[name]), name
        assert stored[name].attrs == ds[name].attrs


def test_fragility_tasks_are_dispatched_longest_first_and_give_the_same_runs(tmp_path,
                                                                              monkeypatch):
    """Issue 28: the tasks go to the workers longest first -- by the records' numbers of
    samples, which a run's time follows -- so that no worker idles long at the end; only the
    order changes: every run equals that of one task over the records in their given order."""
    from dask.distributed import Client, LocalCluster
    from sloshdyn.studies import store
    base = records()[0]
    lengths = [600, 1500, 300, 1200]        # samples: the longest-first order is 1, 3, 0, 2
    suite = [sloshdyn.GroundMotion(dt=base.dt, acceleration=base.acceleration[:n],
                                   units="m/s^2") for n in lengths]
    intensities = [0.2, 0.3]
    finished = []                           # one worker thread: the order the tasks ran
    write = store.Store.write

    def recording(writer, block, result):
        finished.append(lengths[block[0].start])
        return write(writer, block, result)
    monkeypatch.setattr(store.Store, "write", recording)
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                      dashboard_address=None) as cluster, Client(cluster) as one_thread:
        ds = sloshdyn.fragility_study(example_tank(), suite, intensities, tmp_path / "a.zarr",
                                      client=one_thread, points_per_task=len(intensities),
                                      progress=False)
    assert finished == sorted(lengths, reverse=True)
    finished.clear()
    whole = sloshdyn.fragility_study(example_tank(), suite, intensities, tmp_path / "b.zarr",
                                     workers=1, worker_kind="threads", progress=False,
                                     points_per_task=len(lengths) * len(intensities))
    assert finished == [lengths[0]]         # one task, the records in their given order
    for name in whole.data_vars:
        if name == "done":                  # the checksum of each chunk, of their chunking
            continue
        assert np.array_equal(ds[name].values, whole[name].values, equal_nan=True), name


def assert_chunks_are_zarrs(store, names):
    """Every chunk file of the arrays `names` that the engine wrote is the file zarr writes
    for the same values: the array is written again by zarr (write_empty_chunks, so every
    chunk is written) into a copy of the store stripped of its chunk files, and compared
    byte for byte, the edge chunks (padded) included."""
    import shutil
    copy = store.parent / (store.name + ".zarr-written")
    shutil.copytree(store, copy)
    for name in names:
        for chunk in (copy / name).iterdir():
            if not chunk.name.startswith("."):
                chunk.unlink()
        values = zarr.open_array(store / name, mode="r", zarr_format=2)[...]
        again = zarr.open_array(copy / name, mode="r+", zarr_format=2).with_config(
            {"write_empty_chunks": True})
        again[...] = values
        files = sorted(f.name for f in (store / name).iterdir() if not f.name.startswith("."))
        assert files == sorted(f.name for f in (copy / name).iterdir()
                               if not f.name.startswith(".")), name
        assert len(files) > 1, name
        for f in files:
            assert (store / name / f).read_bytes() == (copy / name / f).read_bytes(), (name, f)


def test_the_engine_writes_the_chunk_files_zarr_writes(client, tmp_path):
    """Issue 28: the engine encodes a task's chunks itself (the array's codecs, as Zarr
    format 2 does) instead of through zarr's pipeline: the files are zarr's own, for floats
    with NaN fill, integers and booleans, edge chunks (3 frequencies in chunks of 2, 4 records
    in chunks of 3) and variables with dimensions of their own (basins' states)."""
    ds = sloshdyn.response_map(FIG12, FREQUENCIES, AMPLITUDES, tmp_path / "map.zarr",
                               client=client, steady=QUICK, points_per_task=2, progress=False)
    assert_chunks_are_zarrs(tmp_path / "map.zarr", list(ds.data_vars))
    frag = sloshdyn.fragility_study(example_tank(), records(), [0.2], tmp_path / "f.zarr",
                                    client=client, points_per_task=3, progress=False)
    assert_chunks_are_zarrs(tmp_path / "f.zarr", [n for n in frag.data_vars
                                                  if frag[n].ndim == 2])
    basins = sloshdyn.basins(FIG12, (0.0, 0.2), (0.0, 0.2), n=3, store=tmp_path / "b.zarr",
                             client=client, steady=QUICK, points_per_task=2, progress=False)
    assert_chunks_are_zarrs(tmp_path / "b.zarr", [   # 'attractor' is derived, written whole
        n for n in basins.data_vars if set(basins[n].dims) >= {"x1", "dx1"} and n != "attractor"])


def test_an_embedded_cluster_runs_without_the_dashboards_periodic_work():
    """Issue 28: the embedded cluster's servers start with cluster.CLUSTER_CONFIG (their
    periodic work for dashboards slowed or off: the worker processes too, which receive the
    configuration at their start), the client takes results straight from the workers, and
    the caller's Dask configuration is left as it was."""
    import dask
    from sloshdyn.studies import cluster
    before = dask.config.get("distributed.admin.tick.interval")
    with cluster.connect(None, None, 1, "processes") as c:
        assert c.direct_to_workers is True
        assert c.cluster.scheduler._tick_interval == 1.0
        assert c.run(lambda: dask.config.get("distributed.worker.profile.enabled")) == \
            {w: False for w in c.scheduler_info()["workers"]}
        assert c.run(lambda dask_worker: "profile" in dask_worker.periodic_callbacks) == \
            {w: False for w in c.scheduler_info()["workers"]}
    assert dask.config.get("distributed.admin.tick.interval") == before
    assert cluster.CLUSTER_CONFIG["distributed.worker.profile.enabled"] is False


def test_fragility_study_bad_input(tmp_path):
    tank = example_tank()
    with pytest.raises(sloshdyn.InputError, match="records is empty"):
        sloshdyn.fragility_study(tank, [], [1.0], tmp_path / "f.zarr")
    with pytest.raises(sloshdyn.InputError, match=r"records\[0\]"):
        sloshdyn.fragility_study(tank, [sloshdyn.GroundMotion.harmonic(0.1, 1.0)], [1.0],
                                 tmp_path / "f.zarr")
    with pytest.raises(sloshdyn.InputError, match="separate perfectly"):
        sloshdyn.fit_fragility([1, 2, 3, 4], [0, 0, 1, 1])
    with pytest.raises(sloshdyn.InputError, match=r"intensities\[1\] = nan"):
        sloshdyn.fragility_study(tank, records()[:1], [1.0, float("nan")], tmp_path / "f.zarr")
    with pytest.raises(sloshdyn.InputError, match="tank"):
        sloshdyn.fragility_study(FIG12, records()[:1], [1.0], tmp_path / "f.zarr")
    assert not list(tmp_path.iterdir())


FRAGILITY_NML = """
&tank radius = 5.0, liquid_depth = 6.0, freeboard = 1.0, liquid_density = 1000,
  tank_mass = 5.0e4, support_frequency = 2.0, support_damping = 0.02 /
&study kind = 'fragility', store = 'frag.zarr', records = 'rec/*.csv', intensity_start = 1.0,
  intensity_stop = 4.0, n_intensities = 4, workers = 1, worker_kind = 'threads' /
"""


def test_study_command_runs_a_fragility_study(tmp_path):
    from conftest import write
    (tmp_path / "rec").mkdir()
    for name, r in zip(NAMES, records()):       # two columns: time [s], acceleration [g]
        np.savetxt(tmp_path / "rec" / f"{name}.csv",
                   np.column_stack([r.time, r.acceleration / 9.80665]), delimiter=",")
    nml = write(tmp_path, FRAGILITY_NML)
    result = subprocess.run([sys.executable, "-m", "sloshdyn", "study", str(nml), "--no-progress"],
                            cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr[-2000:]
    assert "fragility: 4 records x 4 intensities, 16 runs computed now" in result.stdout
    ds = xr.open_zarr(tmp_path / "frag.zarr").load()
    assert sorted(ds.record.values) == sorted(f"{n}.csv" for n in NAMES)
    assert (tmp_path / "frag.png").stat().st_size > 10000
    bad = write(tmp_path, "&model s1 = 1.5, mu1 = 0.5, kappa = 2, theta0 = 0.7 /\n" +
                FRAGILITY_NML.split("/", 1)[1], "bad.nml")       # no &tank
    result = subprocess.run([sys.executable, "-m", "sloshdyn", "study", str(bad)], cwd=tmp_path,
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 3 and "needs the tank: group &tank is missing" in result.stderr


@pytest.mark.parametrize("change, match", [
    ("intensity_start = 1.0", "required variable intensity_start is missing"),
    ("records = 'rec/*.csv'", "required variable records is missing"),
    ("n_intensities = 4", "n_intensities = 4, spectral_damping = 1.5"),
])
def test_fragility_group_rules(tmp_path, change, match):
    from conftest import write
    text = FRAGILITY_NML.replace(change + ",", "") if "n_intensities" not in change else \
        FRAGILITY_NML.replace(change, change + ", spectral_damping = 1.5")
    nml = write(tmp_path, text)
    expected = match if "missing" in match else "spectral_damping = 1.5"
    with pytest.raises(sloshdyn.InputError, match=expected):
        sloshdyn.read_namelist(nml)


def test_ctrl_c_keeps_what_was_computed_and_the_rerun_finishes_it(tmp_path):
    from conftest import write
    slow = ("&steady settle_tol = 0, transient_periods = 800, window_periods = 16, "
            "shooting = .false. /")
    text = STUDY_NML.format(extra=", points_per_task = 1").replace(
        "&steady max_transient_periods = 600, window_periods = 32 /", slow).replace(
        "n_frequencies = 3", "n_frequencies = 6")
    nml = write(tmp_path, text)
    store = tmp_path / "map.zarr"
    child = subprocess.Popen([sys.executable, "-m", "sloshdyn", "study", str(nml),
                              "--no-progress"], cwd=tmp_path, stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120
    while done_count(store) < 2 and time.monotonic() < deadline and child.poll() is None:
        time.sleep(0.02)
    child.send_signal(signal.SIGINT)                 # Ctrl-C
    out, err = child.communicate(timeout=120)
    kept = done_count(store)
    assert child.returncode == 130, err[-2000:]
    assert "study interrupted" in err and "rerun the same study" in err
    assert 2 <= kept < 12
    again = subprocess.run([sys.executable, "-m", "sloshdyn", "study", str(nml), "--no-progress"],
                           cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert again.returncode == 0 and f"{12 - kept} points computed now" in again.stdout
    ds = xr.open_zarr(store).load()
    steady = sloshdyn.Steady(settle_tol=0, transient_periods=800, window_periods=16,
                             shooting=False)
    assert_equals_serial(ds, serial(np.linspace(0.505, 0.52, 6), AMPLITUDES, steady))


def test_the_engine_chooses_the_task_size_from_the_workers():
    choose = studies.auto_points_per_task
    assert choose(10000, 2) == 128        # 2 workers: big tasks, the overhead ~2 %
    assert choose(10000, 64) == 20        # 64 workers: ~8 tasks each for the load balance
    assert choose(6, 2) == 8              # never below 8 points (overhead ~20 % at 8)


# ---- damaged stores, scheduler addresses, bounds, signals (issue 22, items 1-5) -------------

DAMAGE_F, DAMAGE_A = [0.505, 0.52], [0.0005, 0.00075]


@pytest.fixture(scope="module")
def damage_reference():
    """The points of the damaged-store tests from the independent source, a serial loop."""
    return serial(DAMAGE_F, DAMAGE_A)


def small_study(client, store):
    return sloshdyn.response_map(FIG12, DAMAGE_F, DAMAGE_A, store, client=client, steady=QUICK,
                                 points_per_task=2, progress=False)


def truncate(path):
    path.write_bytes(path.read_bytes()[:len(path.read_bytes()) // 2])


def garble(path):
    data = bytearray(path.read_bytes())
    data[-3] ^= 0x5A
    path.write_bytes(bytes(data))


@pytest.mark.parametrize("damage", [
    lambda s: (s / "max_x1" / "0.1").unlink(),           # a deleted chunk
    lambda s: truncate(s / "max_x2" / "0.0"),            # a truncated chunk
    lambda s: garble(s / "motion" / "0.1"),              # a garbled chunk
    lambda s: garble(s / "done" / "0.0"),                # a garbled done mask
    lambda s: (s / "done" / "0.1").unlink(),             # a lost done mark
], ids=["deleted", "truncated", "garbled", "garbled-done", "deleted-done"])
def test_a_damaged_chunk_is_computed_again_and_counted(client, tmp_path, damage,
                                                       damage_reference):
    store = tmp_path / "d.zarr"
    small_study(client, store)                    # 2 chunks of 2 points, one per amplitude
    damage(store)
    ds = small_study(client, store)
    assert ds.attrs["points_computed"] == 2       # the damaged chunk's points, no other
    assert_equals_serial(ds, damage_reference)    # never NaN, never garbled values
    assert bool(ds["done"].all())
    assert small_study(client, store).attrs["points_computed"] == 0     # repaired on disk


def test_a_damaged_chunk_is_reported_by_the_study_command(tmp_path):
    from conftest import write
    nml = write(tmp_path, STUDY_NML.format(extra=", points_per_task = 2"))
    command = [sys.executable, "-m", "sloshdyn", "study", str(nml), "--no-progress"]
    assert subprocess.run(command, cwd=tmp_path, capture_output=True, timeout=300).returncode == 0
    (tmp_path / "map.zarr" / "max_x1" / "0.0").unlink()
    again = subprocess.run(command, cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert again.returncode == 0, again.stderr[-2000:]
    assert "2 points computed now" in again.stdout
    assert "repaired: 2 finished points" in again.stdout and "max_x1" in again.stdout
    ds = xr.open_zarr(tmp_path / "map.zarr").load()
    assert_equals_serial(ds, serial(np.linspace(0.505, 0.52, 3), AMPLITUDES))


@pytest.mark.parametrize("damage, what", [
    (lambda s: __import__("shutil").rmtree(s / "max_x1"), "array 'max_x1' is missing"),
    (lambda s: (s / ".zmetadata").unlink(), ".zmetadata is missing"),
    (lambda s: (s / "frequency" / "0").write_bytes(b"junk"), "coordinate 'frequency'"),
    (lambda s: (s / ".zattrs").write_text("{"), "not a sloshdyn study store"),
])
def test_a_store_that_cannot_be_repaired_is_refused_naming_the_damage(client, tmp_path, damage,
                                                                      what):
    from sloshdyn._errors import exit_code
    store = tmp_path / "d.zarr"
    small_study(client, store)
    damage(store)
    before = sorted(p.name for p in store.rglob("*"))
    with pytest.raises(sloshdyn.InputError, match=f"d.zarr.*{what}") as refused:
        small_study(client, store)
    assert exit_code(refused.value) == 3            # a bad file
    assert sorted(p.name for p in store.rglob("*")) == before


NO_GUARD = """
import sys, math, sloshdyn
p = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=math.pi / 4, gamma=0.001,
                        A=0.00075, rho=0.50)
ds = sloshdyn.response_map(p, [0.505, 0.52], [0.0005], {store!r}, workers=1,
                           worker_kind="processes", steady=sloshdyn.Steady(max_transient_periods=600, window_periods=32),
                           progress=False)
print("computed", ds.attrs["points_computed"], float(ds.max_x1.max()))
"""


@pytest.mark.parametrize("how", ["script", "stdin"])
def test_a_study_started_without_the_main_guard_runs_on_threads(tmp_path, how):
    """Worker processes import the main module again: a script without the main guard (or
    standard input) that asks for them runs the study on threads instead, with the same
    numbers, and says why."""
    store = tmp_path / "g.zarr"
    script = tmp_path / "noguard.py"
    script.write_text(NO_GUARD.format(store=str(store)))
    command = [sys.executable, str(script)] if how == "script" else [sys.executable, "-"]
    result = subprocess.run(command, input=script.read_text() if how == "stdin" else None,
                            cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr[-2000:]
    assert "Traceback" not in result.stderr
    assert "runs on 1 threads, not worker processes" in result.stderr
    expected = max(st.max_x1 for row in serial([0.505, 0.52], [0.0005]) for st in row)
    assert result.stdout.split() == ["computed", "2", repr(expected)]


def test_the_main_guard_is_read_from_the_source():
    from sloshdyn.studies.cluster import _guarded
    source = ("import x\n"                                    # 1
              "run()\n"                                       # 2
              "if __name__ == '__main__':\n"                  # 3
              "    run()\n"                                   # 4
              "    run()\n"                                   # 5
              "if '__main__' == __name__:\n"                  # 6
              "    run()\n"                                   # 7
              "if __name__ != '__main__':\n"                  # 8
              "    run()\n")                                  # 9
    import tempfile
    with tempfile.NamedTemporaryFile("w", suffix=".py", delete=False) as f:
        f.write(source)
    try:
        assert [_guarded(f.name, line) for line in range(1, 10)] == [
            False, False, False, True, True, False, True, False, False]
    finally:
        os.remove(f.name)


def silent_server(kind):
    """A loopback server for the scheduler tests, in a thread that stops by itself: 'http'
    (Python's HTTP server), 'greeting' (answers HTTP bytes at once), 'mute' (accepts, never
    answers), or bytes (answers them and closes). Returns (address, stop)."""
    import http.server
    stop = threading.Event()
    if kind == "http":
        server = http.server.ThreadingHTTPServer(("127.0.0.1", 0),
                                                 http.server.BaseHTTPRequestHandler)
        server.timeout = 0.2
        port = server.server_address[1]

        def serve():
            deadline = time.monotonic() + 60
            while not stop.is_set() and time.monotonic() < deadline:
                server.handle_request()
            server.server_close()
    else:
        listener = socket.socket()
        listener.bind(("127.0.0.1", 0))
        listener.listen(8)
        listener.settimeout(0.2)
        port = listener.getsockname()[1]

        def serve():
            deadline = time.monotonic() + 60
            held = []
            while not stop.is_set() and time.monotonic() < deadline:
                try:
                    conn, _ = listener.accept()
                except OSError:
                    continue
                held.append(conn)
                if kind == "greeting":
                    conn.sendall(b"HTTP/1.1 400 Bad Request\r\nContent-Length: 0\r\n\r\n")
                elif isinstance(kind, bytes):
                    conn.sendall(kind)
                    conn.close()
            for conn in held:
                conn.close()
            listener.close()
    thread = threading.Thread(target=serve, daemon=True)
    thread.start()

    def close():
        stop.set()
        thread.join()
    return f"tcp://127.0.0.1:{port}", close


@pytest.mark.parametrize("kind, match", [
    ("http", "did not answer within 5 s"),       # HTTP waits for a request: Dask's was 3 EiB
    ("greeting", "is not a Dask scheduler: it answered b'HTTP/1.1"),
    ("mute", "did not answer within 5 s"),
])
def test_a_scheduler_address_of_another_service_is_refused_within_the_timeout(tmp_path, kind,
                                                                              match):
    address, close = silent_server(kind)
    try:
        start = time.monotonic()
        with pytest.raises(sloshdyn.InputError, match=f"scheduler = '{address}' {match}"):
            sloshdyn.response_map(FIG12, [0.5], [0.001], tmp_path / "x.zarr", scheduler=address,
                                  progress=False)
        assert time.monotonic() - start < 5 + 10    # the stated 5 s (the old client: ~50 s)
    finally:
        close()
    assert not list(tmp_path.iterdir())


@pytest.mark.parametrize("address, match", [
    ("notanaddress", "give tcp://host:port"),
    ("tcp://host:notaport", "give tcp://host:port"),
    ("tcp://host:0", "port in 1..65535"),
    ("tcp://host:70000", "port in 1..65535"),
    ("ftp://x:1", "its scheme 'ftp' is not one of"),
    ("", "give the address of a Dask scheduler"),
])
def test_a_malformed_scheduler_address_is_named(tmp_path, address, match):
    with pytest.raises(sloshdyn.InputError, match=match):
        sloshdyn.response_map(FIG12, [0.5], [0.001], tmp_path / "x.zarr", scheduler=address or 1,
                              progress=False)
    assert not list(tmp_path.iterdir())


def test_a_study_too_large_for_the_machine_is_refused_before_anything_runs(tmp_path):
    f = np.linspace(0.5, 0.52, 100000)
    a = np.linspace(0.0, 0.001, 100000)
    with pytest.raises(sloshdyn.InputError, match=r"100000 frequency x 100000 amplitude values "
                                                  r"\(10000000000 points\) is too large"):
        sloshdyn.response_map(FIG12, f, a, tmp_path / "x.zarr", progress=False)
    assert not list(tmp_path.iterdir())


def test_more_workers_than_the_machine_runs_are_refused_before_anything_runs(tmp_path):
    bound = studies.cluster.max_workers("processes")
    assert bound <= 4 * os.cpu_count()
    for kind in ("threads", "processes"):
        n = studies.cluster.max_workers(kind) + 1
        with pytest.raises(sloshdyn.InputError, match=f"workers = {n} is out of range"):
            sloshdyn.response_map(FIG12, [0.5], [0.001], tmp_path / "x.zarr", workers=n,
                                  worker_kind=kind, progress=False)
    assert not list(tmp_path.iterdir())


def test_the_study_command_refuses_a_huge_grid_and_too_many_workers(tmp_path):
    from conftest import write
    base = STUDY_NML.format(extra="").replace(", workers = 1, worker_kind = 'threads'", "")
    for change, match in [
            ("n_frequencies = 100000, n_amplitudes = 100000", "too large"),
            ("n_frequencies = 3, n_amplitudes = 2, workers = 1024",
             "workers = 1024 is out of range")]:
        text = base.replace("n_frequencies = 3", "").replace("n_amplitudes = 2", change)
        nml = write(tmp_path, text)
        result = subprocess.run([sys.executable, "-m", "sloshdyn", "study", str(nml)],
                                cwd=tmp_path, capture_output=True, text=True, timeout=120)
        assert result.returncode == 3, result.stderr[-2000:]
        assert match in result.stderr and "Traceback" not in result.stderr
        assert sorted(p.name for p in tmp_path.iterdir()) == ["input.nml"]


def full_disk(monkeypatch, where):
    """The store's file writes (zarr's, and the engine's writes of the tasks' chunks) fail
    with ENOSPC (no space left on device) in paths containing `where`, as on a full disk."""
    import errno
    from zarr.storage import _local
    from sloshdyn.studies import store
    put, put_chunk = _local._put, store.put_chunk

    def full(path):
        if where in str(path):
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(path))

    def failing(path, value, exclusive=False):
        full(path)
        return put(path, value, exclusive)

    def failing_chunk(path, data):
        full(path)
        return put_chunk(path, data)
    monkeypatch.setattr(_local, "_put", failing)
    monkeypatch.setattr(store, "put_chunk", failing_chunk)


def test_a_full_disk_while_the_store_is_created_leaves_nothing(client, tmp_path, monkeypatch):
    from sloshdyn._errors import exit_code
    full_disk(monkeypatch, ".creating-")
    with pytest.raises(sloshdyn.FileError, match=r"f\.zarr' cannot be written: No space left")\
            as failed:
        sloshdyn.response_map(FIG12, [0.505 + 0.001 * k for k in range(20)], [0.0005, 0.00075],
                              tmp_path / "f.zarr", client=client, progress=False)
    assert exit_code(failed.value) == 5
    time.sleep(0.5)                  # writes that were under way would show up by now
    assert not list(tmp_path.iterdir())


def test_a_full_disk_while_results_are_written_is_a_file_error(client, tmp_path, monkeypatch,
                                                               damage_reference):
    from sloshdyn._errors import exit_code
    store = tmp_path / "f.zarr"
    small_study(client, store)
    (store / "max_x1" / "0.1").unlink()          # one chunk to write again
    full_disk(monkeypatch, "f.zarr/")
    with pytest.raises(sloshdyn.FileError, match=r"f\.zarr'.*cannot be written.*No space left.*"
                                                 "rerun the same study") as failed:
        small_study(client, store)
    assert exit_code(failed.value) == 5
    monkeypatch.undo()
    ds = small_study(client, store)              # nothing lost: resumed once there is space
    assert ds.attrs["points_computed"] == 2
    assert_equals_serial(ds, damage_reference)


SLOW_STUDY = ("&steady settle_tol = 0, transient_periods = 800, window_periods = 16, "
              "shooting = .false. /")


def slow_study_file(tmp_path, kind):
    from conftest import write
    text = STUDY_NML.format(extra=", points_per_task = 1").replace(
        "&steady max_transient_periods = 600, window_periods = 32 /", SLOW_STUDY).replace(
        "n_frequencies = 3", "n_frequencies = 6").replace("worker_kind = 'threads'",
                                                          f"worker_kind = '{kind}'")
    return write(tmp_path, text)


def interrupt_study(tmp_path, kind, signum, group):
    nml = slow_study_file(tmp_path, kind)
    child = subprocess.Popen([sys.executable, "-m", "sloshdyn", "study", str(nml),
                              "--no-progress"], cwd=tmp_path, stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True, start_new_session=True)
    try:
        deadline = time.monotonic() + 120
        while done_count(tmp_path / "map.zarr") < 1 and time.monotonic() < deadline \
                and child.poll() is None:
            time.sleep(0.02)
        (os.killpg if group else os.kill)(child.pid, signum)
        out, err = child.communicate(timeout=120)
    finally:
        if child.poll() is None:
            os.killpg(child.pid, signal.SIGKILL)
            child.wait()
    return child.returncode, err


def test_ctrl_c_to_the_process_group_prints_no_worker_tracebacks(tmp_path):
    """Ctrl-C in a terminal reaches every process of its group: the worker processes too."""
    code, err = interrupt_study(tmp_path, "processes", signal.SIGINT, group=True)
    assert code == 130, err[-2000:]
    assert "study interrupted" in err
    assert "Traceback" not in err and "KeyboardInterrupt" not in err, err[-2000:]


def test_sigterm_during_a_study_exits_143(tmp_path):
    code, err = interrupt_study(tmp_path, "threads", signal.SIGTERM, group=False)
    assert code == 143, err[-2000:]
    assert "terminated; study interrupted" in err and "rerun the same study" in err


@pytest.mark.filterwarnings("ignore::pytest.PytestUnraisableExceptionWarning")
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_an_interrupt_lost_in_a_finalizer_is_raised_again(sig):
    """Ctrl-C (and sloshdyn-py's SIGTERM) raise KeyboardInterrupt where Python runs next;
    inside a finalizer (__del__, as a Dask Future's) it is only printed ("Exception ignored")
    and the study would run to its end. The engine's check raises it again (the handler's own
    exception); the handlers before it are back afterwards."""
    from sloshdyn.cli import _on_sigterm, _terminate, _Terminated
    from sloshdyn.studies import engine

    class Finalized:
        def __del__(self):
            os.kill(os.getpid(), sig)
            time.sleep(0.01)                     # the handler runs here, inside __del__

    before_term = _on_sigterm(_terminate)
    try:
        before = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM)}
        with engine._remembered_interrupts() as check:
            finalized = Finalized()
            del finalized                        # no KeyboardInterrupt reaches this frame
            with pytest.raises(_Terminated if sig == signal.SIGTERM else KeyboardInterrupt):
                check()
        assert {s: signal.getsignal(s) for s in before} == before
    finally:
        signal.signal(signal.SIGTERM, before_term)
