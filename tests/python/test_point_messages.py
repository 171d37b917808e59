"""Every failed point of a study task takes its message from the one call that computed it: the
core returns each point's message (steady_path's and attractor_points' point_message,
seismic_peaks' messages), so no failed point is integrated a second time to learn it. Each
message must be what the point's run alone says (the single-run bridge: steady_state,
seismic_response), whatever the task and the place in it, for points that fail for different
reasons in one block: a step budget exhausted half-way, a value refused by the checks."""

from collections import Counter

import numpy as np
import pytest

import sloshdyn
from sloshdyn._errors import message_text
from sloshdyn.studies import fragility

import test_fragility_ensemble as seismic_runs
from test_steady_blocks import FIG12, SINGLE, basins, response

STEADY = sloshdyn.Steady(max_transient_periods=300, window_periods=16)
TOO_MANY_STEPS, BAD_INPUT = 6, 1     # sloshdyn_status codes


class Counting:
    """A bridge module whose functions count their calls; `forbidden` ones fail the test."""

    def __init__(self, module, forbidden=()):
        self.module, self.forbidden, self.calls = module, forbidden, Counter()

    def __getattr__(self, name):
        function = getattr(self.module, name)
        if not callable(function):
            return function

        def counted(*args):
            assert name not in self.forbidden, f"{name} called during the study task"
            self.calls[name] += 1
            return function(*args)
        return counted


def alone(params, y0, integration):
    """status and message of one steady state run alone (the single-run bridge)."""
    *_, status, message = SINGLE.steady_state(*params.array(), np.array(y0, dtype=float),
                                              integration.array(), STEADY.array(), 16)
    return int(status), message_text(message)


def budget_between(runs):
    """A step budget between the median runs' steps: about half the runs exhaust it."""
    steps = sorted(runs)
    return int((steps[len(steps) // 2 - 1] + steps[len(steps) // 2]) // 2)


def free_steps(params, y0):
    *_, counts, status, _ = SINGLE.steady_state(*params.array(), np.array(y0, dtype=float),
                                                sloshdyn.Integration().array(), STEADY.array(),
                                                16)
    return counts[1] + counts[2] if status == 0 else None


def assert_messages_alone(status, messages, singles):
    """Each point's status and message are its run's alone; at least two causes of failure,
    and two or more points of each."""
    causes = Counter()
    for i, (st, text) in enumerate(singles):
        assert status[i] == st, i
        assert messages[i] == (text if st != 0 else ""), i
        causes[st] += st != 0
    assert causes[TOO_MANY_STEPS] >= 2 and causes[BAD_INPUT] >= 1


def test_basin_task_points_have_their_messages_alone_without_a_second_run(monkeypatch):
    """Initial states about rest with a step budget half of them exhaust, one out of range
    (|x1| > 1e3, refused by the checks) and one NaN (refused by the integrator's set-up)."""
    y0 = np.random.default_rng(3).uniform(-0.5, 0.5, (4, 4, 2))
    y0[:, 1, 0] = [2e3, 0, 0, 0]
    y0[:, 2, 1] = np.nan
    flat = y0.reshape(4, -1)
    steps = [free_steps(FIG12, flat[:, i]) for i in range(flat.shape[1])]
    integration = sloshdyn.Integration(max_steps=budget_between([s for s in steps if s]))
    singles = [alone(FIG12, flat[:, i], integration) for i in range(flat.shape[1])]
    bridge = Counting(basins._bridge)
    monkeypatch.setattr(basins, "_bridge", bridge)
    out = basins._basin_task(*FIG12.array(), y0, integration.array(), STEADY.array())
    assert bridge.calls == {"attractor_points": 1}        # no point run a second time
    assert_messages_alone(out["status"].ravel(), out["message"].ravel(), singles)


def test_response_task_points_have_their_messages_alone_without_a_second_run(monkeypatch):
    """A grid with rho = 0 (refused) and a step budget half the points exhaust; with the sweep
    up in frequency, which starts at rho = 0 in the first column: its points after that
    say they were not computed, naming the failure."""
    rho, A = np.meshgrid([0.0, 0.50, 0.513, 0.52], [0.00075, 0.001], indexing="ij")
    points = list(zip(rho.ravel(), A.ravel()))
    steps = [free_steps(FIG12.replace(rho=r, A=a), np.zeros(4)) for r, a in points]
    integration = sloshdyn.Integration(max_steps=budget_between([s for s in steps if s]))
    singles = [alone(FIG12.replace(rho=r, A=a), np.zeros(4), integration) for r, a in points]
    bridge = Counting(response._bridge)
    monkeypatch.setattr(response, "_bridge", bridge)
    out = response._response_task(*FIG12.array(), rho, A, integration.array(), STEADY.array(),
                                  ("up",))
    # one call for the grid, one per swept column
    assert bridge.calls == {"steady_path": 1 + rho.shape[1]}
    assert_messages_alone(out["status"].ravel(), out["message"].ravel(), singles)
    up, refused = out["message_up"][:, 0], singles[0][1]
    assert up[0] == refused and all(out["status_up"][:, 0] == BAD_INPUT)
    assert all(m == "not computed: the sweep carrying the state stopped at the failure of the "
               f"point before ({refused})" for m in up[1:])


def test_fragility_block_runs_have_their_messages_alone_without_a_second_run(monkeypatch):
    """One record's runs at five intensities in one block, a step budget the stronger shaking
    exceeds (tests/python/test_fragility_ensemble.py) and one run whose record has a NaN
    sample (refused): every failed run's message is its seismic_response's alone."""
    t, record = seismic_runs.tank(), seismic_runs.records()[0]
    integration = sloshdyn.Integration(rtol=1e-10, max_steps=3390).array()
    times = sloshdyn.seismic_defaults(t, record)
    chosen = np.array([times.t_end, times.n_out])
    runs = []
    for j, sa in enumerate(seismic_runs.INTENSITIES):
        scaled, samples = record.scaled(sa=sa, period=t.sloshing_period, damping=0.005,
                                        units="g")._arrays()
        runs.append((j, scaled, samples.copy()))
    runs[1][2][10] = np.nan
    singles = []
    for _, scaled, samples in runs:
        *_, status, message = fragility._bridge.seismic_response(
            t.array(), scaled, samples, times.t_end, times.n_out, integration)
        singles.append((int(status), message_text(message)))
    shape = (1, len(runs))
    out = {name: np.full(shape, np.nan) for name in fragility._FRAGILITY_LOADS}
    out.update(scale_factor=np.full(shape, np.nan), roof_impact=np.zeros(shape, np.int8),
               roof_impacts=np.full(shape, -1, np.int32), status=np.zeros(shape, np.int16),
               message=np.full(shape, "", dtype=object))
    bridge = Counting(fragility._bridge, forbidden=("seismic_response",))
    monkeypatch.setattr(fragility, "_bridge", bridge)
    ground, samples = record._arrays()
    fragility._run_block(t.array(), ground, samples, runs, chosen, integration, out, 0)
    assert bridge.calls == {"seismic_peaks": 1}
    assert_messages_alone(out["status"][0], out["message"][0], singles)
    assert out["message"][0, 1] == "the record sample 11 = NaN is out of range: samples must " \
                                   "be finite"


@pytest.mark.parametrize("carried", [False, True])
def test_a_call_refused_as_a_whole_gives_every_point_its_message(carried):
    """A bad model (rpar's s1 = -1) refuses the call before any point runs: every point has the
    status and message (not the carried wording: no point failed before another)."""
    rpar, ipar = FIG12.array()
    rpar = np.array(rpar, dtype=float)
    rpar[0] = -1.0
    *_, point_status, point_message, status, message = response._bridge.steady_path(
        rpar, ipar, np.full(3, 0.52), np.full(3, 0.00075), np.zeros((4, 3), order="F"),
        int(carried), sloshdyn.Integration().array(), STEADY.array(), 1)
    assert status != 0 and all(point_status == status)
    assert [message_text(m) for m in point_message] == [message_text(message)] * 3
    assert "s1 = -1" in message_text(message)
