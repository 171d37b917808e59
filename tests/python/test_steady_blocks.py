"""Steady states in blocks: the studies hand their points to the core's ensemble integrator
(steady_state_block, through advance_members) a block at a time, and every point must be the
steady state computed alone (steady_state, the single integrator) bit for bit -- compared with
==, never approx -- for any block size; points that settle at different times, that jump to
their orbit by shooting or not, of different forcing periods, and points that fail inside a
block. Then the studies (basin task, sweep, response task) against their block = 1 path."""

import importlib
import math

import numpy as np
import pytest

import sloshdyn
from sloshdyn import _core
from sloshdyn.studies.engine import SECONDS
from sloshdyn import simulation

STUDIES = _core.sloshdyn_bridge_studies
SINGLE = _core.sloshdyn_bridge_simulation
# the modules (sloshdyn.studies re-exports functions of the same names)
basins = importlib.import_module("sloshdyn.studies.basins")
response = importlib.import_module("sloshdyn.studies.response")

FIG12 = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=math.pi / 4,
                            gamma=0.001, A=0.00075, rho=0.52)
QUICK = sloshdyn.Steady(max_transient_periods=600, window_periods=32)
#: without shooting, and damped ten times more so that the points settle (settle_tol) at
#: different times within max_transient_periods
PLAIN = sloshdyn.Steady(transient_periods=50, settle_tol=1e-4, max_transient_periods=600,
                        window_periods=32, shooting=False)
DAMPED = FIG12.replace(gamma=0.01)
WINDOW = 32
BLOCKS = (1, 2, 3, 16)


def initial_states():
    """Ten initial states about rest (two attractors coexist at rho = 0.52: the small and the
    large orbit of Fig 12), one out of range (|x1| > 1e3: refused by the checks) and one NaN
    (refused by the integrator's set-up), inside the block."""
    y0 = np.asfortranarray(np.random.default_rng(1).uniform(-0.5, 0.5, (4, 12)))
    y0[:, 3] = [2e3, 0, 0, 0]
    y0[:, 5] = np.nan
    return y0


def alone(params, y0, steady, integration):
    """steady_state of one point: summary, y_end, counts, status, message."""
    summary, _, y_end, counts, status, message = SINGLE.steady_state(
        *params.array(), np.array(y0, dtype=float), integration.array(), steady.array(), WINDOW)
    return summary, y_end, counts, int(status), message


def same_bits(a, b):
    """Equal bit for bit (NaN where NaN); == on the values, not a tolerance."""
    a, b = np.asarray(a), np.asarray(b)
    if a.dtype.kind != "f":
        return bool(np.array_equal(a, b))
    return a.shape == b.shape and bool(np.all((a == b) | (np.isnan(a) & np.isnan(b))))


@pytest.fixture(scope="module", params=[(FIG12, QUICK), (DAMPED, PLAIN)],
                ids=["shooting", "no-shooting"])
def singles(request):
    params, steady = request.param
    y0 = initial_states()
    runs = [alone(params, y0[:, i], steady, sloshdyn.Integration()) for i in range(y0.shape[1])]
    return params, steady, y0, runs


@pytest.mark.parametrize("block", BLOCKS)
def test_basin_points_in_blocks_are_their_steady_states_alone_bit_for_bit(singles, block):
    params, steady, y0, runs = singles
    summaries, y_end, orbit, _, point_status, _, _, _ = STUDIES.attractor_points(
        *params.array(), y0, sloshdyn.Integration().array(), steady.array(), block)
    for i, (summary, end, _, status, _) in enumerate(runs):
        assert point_status[i] == status
        if status == 0:
            assert same_bits(summaries[:, i], summary) and same_bits(y_end[:, i], end), i
        else:           # a failed point: NaN results (attractor_points), the others go on
            assert np.all(np.isnan(summaries[:, i])), i
    # the points exercise what the test claims: two refused, the others settle at different
    # times; with shooting, some jump to their orbit after different numbers of attempts
    ok = [i for i, r in enumerate(runs) if r[3] == 0]
    assert [i for i in range(12) if i not in ok] == [3, 5]
    transients = summaries[simulation.SUMMARY_COLUMNS.index("transient_periods"), ok]
    assert len(set(transients)) >= len(ok) - 2
    found, attempts = orbit[0, ok], orbit[2, ok]
    if steady.shooting:
        assert np.any(found == 1) and len(set(attempts)) > 2
    else:
        assert np.all(found != 1) and np.all(attempts == 0)


def test_points_failing_mid_run_and_of_different_periods_inside_a_block():
    """A step budget that half the points exhaust (SD_TOO_MANY_STEPS half-way through their
    transient), at forcing frequencies of different periods, one of them irregular (Fig 17's
    rho = 0.513, A = 2): each point equals its steady state alone, failures included (status
    and message)."""
    rho = np.array([0.50, 0.513, 0.52, 0.53, 0.513, 0.505, 0.0, 0.54])
    A = np.array([0.00075, 0.00075, 0.00075, 0.0005, 2.0, 0.00075, 0.00075, 0.001])
    steady = sloshdyn.Steady(max_transient_periods=300, window_periods=32)
    free = [alone(FIG12.replace(rho=r, A=a), np.zeros(4), steady, sloshdyn.Integration())
            for r, a in zip(rho, A)]
    steps = sorted(c[1] + c[2] for _, _, c, st, _ in free if st == 0)
    budget = int((steps[len(steps) // 2 - 1] + steps[len(steps) // 2]) // 2)
    integration = sloshdyn.Integration(max_steps=budget)
    runs = [alone(FIG12.replace(rho=r, A=a), np.zeros(4), steady, integration)
            for r, a in zip(rho, A)]
    statuses = [r[3] for r in runs]
    # some finish, some exhaust the budget (SD_TOO_MANY_STEPS = 6), rho = 0 is refused (1)
    assert statuses.count(0) >= 2 and statuses.count(6) >= 2 and statuses[6] == 1
    motions = {int(r[0][simulation.SUMMARY_COLUMNS.index("motion")]) for r in free if r[3] == 0}
    assert len(motions) >= 2          # periodic and irregular among them
    for block in BLOCKS:
        summaries, y_end, orbit, _, point_status, _, status, message = STUDIES.steady_path(
            *FIG12.array(), rho, A, np.zeros((4, len(rho)), order="F"), 0,
            integration.array(), steady.array(), block)
        assert list(point_status) == statuses
        for i, (summary, end, _, st, text) in enumerate(runs):
            if st == 0:
                assert same_bits(summaries[:, i], summary) and same_bits(y_end[:, i], end)
        # the first failure (in the order of the points) gives the status and the message,
        # which names the point and says what its run alone says
        first = next(i for i, st in enumerate(statuses) if st != 0)
        assert status == statuses[first]
        text = message.decode()
        assert text.startswith(f"point {first + 1} ")
        assert runs[first][4].decode().strip()[:60] in text


def test_a_bad_block_size_is_refused_naming_it():
    *_, status, message = STUDIES.attractor_points(
        *FIG12.array(), np.zeros((4, 2), order="F"), sloshdyn.Integration().array(),
        QUICK.array(), 0)
    assert status != 0 and b"block = 0" in message


def test_basin_task_equals_its_block_1_path(monkeypatch):
    y0 = np.asfortranarray(np.random.default_rng(2).uniform(-0.4, 0.4, (4, 3, 3)))
    y0[:, 1, 1] = np.nan
    args = (*FIG12.array(), y0, sloshdyn.Integration().array(), QUICK.array())
    monkeypatch.setattr(basins, "ENSEMBLE_BLOCK", 1)
    one = basins._basin_task(*args)
    monkeypatch.setattr(basins, "ENSEMBLE_BLOCK", 16)
    many = basins._basin_task(*args)
    assert_tasks_equal(one, many)


def test_response_task_equals_its_block_1_path(monkeypatch):
    rho, A = np.meshgrid([0.505, 0.513, 0.52], [0.0005, 0.00075], indexing="ij")
    args = (*FIG12.array(), rho, A, sloshdyn.Integration().array(), QUICK.array(), ())
    monkeypatch.setattr(response, "ENSEMBLE_BLOCK", 1)
    one = response._response_task(*args)
    monkeypatch.setattr(response, "ENSEMBLE_BLOCK", 16)
    many = response._response_task(*args)
    assert_tasks_equal(one, many)


def test_independent_sweep_in_blocks_equals_block_1_and_steady_state_alone():
    """Every block size (0: the core's default) and thread count of the core's sweep, and the
    Python sweep (which passes 0), give each point's steady state alone."""
    values = np.linspace(0.50, 0.53, 7)
    args = (*FIG12.array(), 1, values, np.zeros(4), sloshdyn.Integration().array(),
            QUICK.array())
    single = [sloshdyn.steady_state(FIG12.replace(rho=float(r)), steady=QUICK) for r in values]
    sweeps = [sloshdyn.frequency_sweep(FIG12, values, steady=QUICK, start_from="y0",
                                       threads=2).points]
    for block, threads in ((1, 1), (3, 1), (16, 2), (0, 1), (0, 2)):
        summaries, n_done, status, message = SINGLE.independent_sweep(*args, threads, block)
        assert status == 0 and n_done == len(values), message
        sweeps.append([simulation._summary(summaries[:, k], single[k].method)
                       for k in range(len(values))])
    for points in sweeps:
        for point, alone_point in zip(points, single, strict=True):
            for name in simulation.SUMMARY_COLUMNS:
                assert same_bits(getattr(point, name), getattr(alone_point, name)), name


def test_a_refused_sweep_value_inside_a_block_leaves_the_others_their_steady_states():
    """A value set_excitation_parameter refuses (rho < 0) among the sweep's points: it gets the
    status and message naming it, the points about it in the same block are their steady
    states alone."""
    values = np.array([0.50, -0.1, 0.52])
    summaries, n_done, status, message = SINGLE.independent_sweep(
        *FIG12.array(), 1, values, np.zeros(4), sloshdyn.Integration().array(), QUICK.array(),
        1, 0)
    assert status == 1 and n_done == 2 and b"rho = -0.1 is out of range" in message
    for k in (0, 2):
        alone_point = sloshdyn.steady_state(FIG12.replace(rho=float(values[k])), steady=QUICK)
        point = simulation._summary(summaries[:, k], alone_point.method)
        for name in simulation.SUMMARY_COLUMNS:
            assert same_bits(getattr(point, name), getattr(alone_point, name)), name


def test_a_negative_sweep_block_is_refused_naming_it():
    *_, status, message = SINGLE.independent_sweep(
        *FIG12.array(), 1, np.array([0.5, 0.51]), np.zeros(4), sloshdyn.Integration().array(),
        QUICK.array(), 1, -2)
    assert status != 0 and b"block = -2" in message and b"or 0 for the default" in message


def assert_tasks_equal(one, many):
    assert one.keys() == many.keys()
    for key in one:
        if key == SECONDS:
            continue
        a, b = np.asarray(one[key]), np.asarray(many[key])
        if a.dtype.kind == "f":
            assert same_bits(a, b), key
        else:
            assert np.array_equal(a, b), key
