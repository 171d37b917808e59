"""simulate_ensemble (issue 43) against its independent reference, simulate called once per
member (the single-trajectory path, its own driver): the same outputs, work counts and time
reached, bit for bit, for members that differ in rho (a sweep), amplitude (impacts: many
rejected steps), initial state and final time; and the checks of its inputs."""

import numpy as np
import pytest

import sloshdyn
from sloshdyn import Integration


def _members(fig12, k):
    params = [fig12.replace(rho=0.49 + 0.04 * i / max(k - 1, 1),
                            A=0.2 if i % 3 == 2 else 0.00075) for i in range(k)]
    y0 = np.array([[0.01 + 0.002 * (i % 5), 0.0, 0.01, 0.001 * (i % 2)] for i in range(k)])
    t_end = 40.0 + 7.0 * np.arange(k)
    return params, y0, t_end


def _same(a, b):
    return np.array_equal(a, b, equal_nan=True)


@pytest.mark.parametrize("method", ["rk45", "dop853", "vern9"])
@pytest.mark.parametrize("k", [1, 3, 8])
def test_ensemble_equals_single_runs_bit_for_bit(fig12, method, k):
    params, y0, t_end = _members(fig12, k)
    integration = Integration(rtol=1e-9, atol=1e-12, method=method)
    ens = sloshdyn.simulate_ensemble(params, t_end, y0, n_out=9, integration=integration)
    assert len(ens) == k and ens.y.shape == (k, 4, 9) and ens.method == method
    for i in range(k):
        alone = sloshdyn.simulate(params[i], t_end[i], y0[i], n_out=9, integration=integration)
        member = ens.member(i)
        assert _same(member.tau, alone.tau)
        for name in ("y", "u", "impact_force", "theta", "phi"):
            assert _same(getattr(member, name), getattr(alone, name)), (i, name)
        assert (member.n_rhs, member.n_accepted, member.n_rejected, member.tau_reached) == \
            (alone.n_rhs, alone.n_accepted, alone.n_rejected, alone.tau_reached)
    if k == 8:   # the members really differ: some reject steps, not all alike
        assert ens.n_rejected.max() > 0 and len(set(ens.n_accepted)) > 4


def test_shared_inputs_broadcast(fig12):
    """One Parameters, K initial states, one tau_out for all: each member as simulate."""
    y0 = np.array([[0.01, 0, 0, 0], [0.0, 0.02, 0.01, 0], [0.5, 0, 0, 0]])
    tau = np.linspace(0.0, 30.0, 13)
    ens = sloshdyn.simulate_ensemble(fig12, 30.0, y0, tau_out=tau)
    assert ens.y.shape == (3, 4, 13)
    for i in range(3):
        assert _same(ens.y[i], sloshdyn.simulate(fig12, 30.0, y0[i], tau_out=tau).y)


def test_mismatched_sizes_are_named(fig12):
    with pytest.raises(sloshdyn.InputError, match="t_end has 2 members"):
        sloshdyn.simulate_ensemble([fig12] * 3, [10.0, 20.0])
    with pytest.raises(sloshdyn.InputError, match="y0 has shape"):
        sloshdyn.simulate_ensemble(fig12, 10.0, np.zeros((2, 3)))


def test_a_failing_member_is_named_and_the_others_finish(fig12):
    """A step budget that the longest member exhausts: the error names it (0-based), and its
    partial history and the others' equal the single runs."""
    params, y0, t_end = _members(fig12, 3)
    t_end = np.array([20.0, 25.0, 4000.0])
    integration = Integration(rtol=1e-9, atol=1e-12, method="dop853", max_steps=2000)
    with pytest.raises(sloshdyn.IntegrationError, match="member 2") as info:
        sloshdyn.simulate_ensemble(params, t_end, y0, n_out=5, integration=integration)
    ens = info.value.partial
    assert list(ens.status != 0) == [False, False, True]
    for i in range(3):
        try:
            alone = sloshdyn.simulate(params[i], t_end[i], y0[i], n_out=5,
                                      integration=integration)
        except sloshdyn.IntegrationError as exc:
            alone = exc.partial
        assert _same(ens.y[i], alone.y) and ens.n_rhs[i] == alone.n_rhs


def test_a_member_failing_the_checks_is_named_and_the_others_equal_single_runs(fig12):
    """A start outside the state's range (time_history's check_initial_state): that member
    reports simulate's own error and is not integrated (a zero history, no work), and the
    members around it, integrated together, equal their single runs (read from the bridge:
    Python raises the InputError without the partial ensemble)."""
    from sloshdyn._core import sloshdyn_bridge_simulation as bridge
    params, y0, t_end = _members(fig12, 3)
    y0[1, 0] = 1.0e9
    with pytest.raises(sloshdyn.InputError) as alone:
        sloshdyn.simulate(params[1], t_end[1], y0[1], n_out=5)
    with pytest.raises(sloshdyn.InputError, match="member 1"):
        sloshdyn.simulate_ensemble(params, t_end, y0, n_out=5)
    tau_out = np.stack([np.linspace(0, e, 5) for e in t_end])
    arrays = [p.array() for p in params]
    history, counts, status, message = bridge.simulate_ensemble(
        np.stack([a[0] for a in arrays], axis=1), np.stack([a[1] for a in arrays], axis=1),
        np.zeros(3), np.asfortranarray(y0.T), np.asfortranarray(tau_out.T),
        Integration().array())
    assert list(status != 0) == [False, True, False]
    text = sloshdyn._errors.message_text(message)
    assert text.startswith("member 1: y0(1) = 1e9 is out of range")
    assert text[len("member 1: "):] in str(alone.value)
    assert np.all(history[:, :, 1] == 0) and np.all(counts[:, 1] == 0)
    for i in (0, 2):
        single = sloshdyn.simulate(params[i], t_end[i], y0[i], tau_out=tau_out[i])
        assert _same(history[0:4, :, i], single.y) and counts[0, i] == single.n_rhs
