"""Issue 43, item 2: the fragility study hands the runs of one record to the core's ensemble
integrator in blocks (seismic_peaks, sloshdyn_seismic's seismic_responses). Its results must be
those of the single-trajectory path, bit for bit: every run is compared here with
sloshdyn.seismic_response of the record scaled to the intensity alone (GroundMotion.scaled,
one trajectory at a time), for blocks of 1 (the single path), 2 (blocks of different sizes)
and 20 (the whole record at once), with runs that reach the roof and runs that do not (so the
second phase, the confined mass's run, takes a part of the block), with the paper's impact
model integrated too, and with runs that fail."""

from pathlib import Path

import numpy as np
import pytest

import sloshdyn
from sloshdyn.studies import fragility

ROOT = Path(__file__).resolve().parents[2]
#: Sa(T_sloshing, 0.5 %) [g]: the free wave of the example record reaches the 1 m freeboard
#: near 0.24 g (tests/python/test_studies.py, records())
INTENSITIES = np.array([0.15, 0.2, 0.24, 0.26, 0.3])
LOADS = list(fragility._FRAGILITY_LOADS)     # columns of seismic_peaks


def tank(**extra):
    """The tank of data/examples/tank_seismic.nml."""
    return sloshdyn.Tank(radius=5.0, liquid_depth=6.0, freeboard=1.0, liquid_density=1000,
                         tank_mass=5.0e4, support_frequency=2.0, support_damping=0.02, **extra)


def records():
    base = sloshdyn.GroundMotion.from_file(ROOT / "data/examples/records/synthetic_kt.AT2")
    return [base, sloshdyn.GroundMotion(dt=0.7 * base.dt, acceleration=base.acceleration[::-1],
                                        units="m/s^2")]


def task(t, motions, integration):
    return fragility._fragility_task(t.array(), [m._arrays() for m in motions], INTENSITIES,
                                     sloshdyn.acceleration_factor("g"), t.sloshing_period,
                                     0.005, integration.array())


def single_path(t, motions, integration):
    """Every run alone: the record scaled to Sa by GroundMotion.scaled, then seismic_response
    (status and message of a failed run from the InputError/ConvergenceError it raises)."""
    runs = {}
    for i, m in enumerate(motions):
        for j, sa in enumerate(INTENSITIES):
            g = m.scaled(sa=sa, period=t.sloshing_period, damping=0.005, units="g")
            try:
                runs[i, j] = sloshdyn.seismic_response(t, g, integration=integration)
            except sloshdyn.SloshdynError as exc:
                runs[i, j] = exc
    return runs


def assert_same_runs(out, runs):
    for (i, j), run in runs.items():
        if isinstance(run, Exception):
            assert out["status"][i, j] != 0 and out["roof_impact"][i, j] == -1
            assert out["message"][i, j] and out["message"][i, j] in str(run)
            continue
        assert out["status"][i, j] == 0, out["message"][i, j]
        for name in LOADS:
            # bit for bit: NaN (no roof time) in the same places, every other value equal
            np.testing.assert_array_equal(out[name][i, j], run.peak_table[name],
                                          err_msg=f"{name} of run {i}, {j}")
        assert out["roof_impact"][i, j] == run.roof_reached
        assert out["roof_impacts"][i, j] == run.roof_impacts


@pytest.mark.parametrize("block", [1, 2, 20])
def test_fragility_runs_in_blocks_are_the_single_runs_bit_for_bit(block, monkeypatch):
    t, motions, integration = tank(), records(), sloshdyn.Integration()
    monkeypatch.setattr(fragility, "ENSEMBLE_BLOCK", block)
    out = task(t, motions, integration)
    hit = out["roof_impact"]
    # both phases: some runs of each record reach the roof, some do not
    assert np.all((hit == 1).any(axis=1)) and np.all((hit == 0).any(axis=1))
    assert_same_runs(out, single_path(t, motions, integration))


def test_fragility_blocks_are_capped_by_their_outputs(monkeypatch):
    """ENSEMBLE_OUTPUTS bounds a block's outputs (n_out x runs): with blocks of up to 10
    runs and outputs of 3 runs' worth, the 5 intensities of a record go in blocks of 3 and 2,
    with the single runs' results."""
    t, motions, integration = tank(), records()[:1], sloshdyn.Integration()
    n_out = sloshdyn.seismic_defaults(t, motions[0]).n_out
    monkeypatch.setattr(fragility, "ENSEMBLE_BLOCK", 10)
    monkeypatch.setattr(fragility, "ENSEMBLE_OUTPUTS", 3 * n_out + 1)
    sizes, run_block = [], fragility._run_block

    def recording(tank_array, ground, samples, runs, *rest):
        sizes.append(len(runs))
        return run_block(tank_array, ground, samples, runs, *rest)
    monkeypatch.setattr(fragility, "_run_block", recording)
    out = task(t, motions, integration)
    assert sizes == [3, 2]
    assert_same_runs(out, single_path(t, motions, integration))


def test_fragility_blocks_with_the_impact_model_are_the_single_runs():
    """roof_contact = 'impact': the paper's model is integrated as a third phase of the block;
    every peak of the block's runs (the impact force's and the beta-sensitivity flag too)
    equals the single run's."""
    t, motions, integration = tank(roof_contact="impact"), records()[:1], sloshdyn.Integration()
    runs = single_path(t, motions, integration)
    assert_same_runs(task(t, motions, integration), runs)
    scaled = [motions[0].scaled(sa=sa, period=t.sloshing_period, damping=0.005,
                                units="g")._arrays() for sa in INTENSITIES]
    times = sloshdyn.seismic_defaults(t, motions[0])
    peaks, status, _ = fragility._bridge.seismic_peaks(
        t.array(), np.asfortranarray(np.stack([g for g, _ in scaled], axis=1)),
        np.asfortranarray(np.stack([s for _, s in scaled], axis=1)), times.t_end, times.n_out,
        integration.array())
    assert np.all(status == 0)
    for j in range(len(INTENSITIES)):
        single = np.array(list(runs[0, j].peak_table.values()), dtype=float)
        np.testing.assert_array_equal(peaks[:, j], single)
    assert any(runs[0, j].beta_sensitive for j in range(len(INTENSITIES))) or \
        max(runs[0, j].peak_table["peak_impact_force"] for j in range(len(INTENSITIES))) > 0


def test_fragility_blocks_with_failing_runs_fail_as_the_single_runs():
    """A step budget that the stronger shaking exceeds (3356 steps at 0.15 g, 3424 at 0.3 g,
    rtol 1e-10; the steps are bounded by the record's samples): those runs fail in the block with the
    single run's message (each from the block), the others equal the single runs."""
    t, motions = tank(), records()[:1]
    integration = sloshdyn.Integration(rtol=1e-10, max_steps=3390)
    runs = single_path(t, motions, integration)
    failed = [isinstance(r, Exception) for r in runs.values()]
    assert 1 < sum(failed) < len(failed)         # some runs fail, some do not
    assert_same_runs(task(t, motions, integration), runs)


def test_a_record_none_of_whose_runs_can_be_scaled_leaves_no_block():
    """A record shorter than the spectral period cannot be scaled to Sa (scale_to_sa's
    check): every intensity fails with that message, as the single path's scaling does, and
    no block is run; the other record's runs equal the single runs."""
    t = tank()
    base = records()[0]
    short = sloshdyn.GroundMotion(dt=base.dt, acceleration=base.acceleration[:50],
                                  units="m/s^2")
    assert 50 * base.dt < t.sloshing_period
    with pytest.raises(sloshdyn.InputError) as alone:
        short.scaled(sa=0.2, period=t.sloshing_period, damping=0.005, units="g")
    out = task(t, [short, base], sloshdyn.Integration())
    assert np.all(out["status"][0] != 0) and np.all(out["roof_impact"][0] == -1)
    assert all("longer than the record" in m and m in str(alone.value)
               for m in out["message"][0])
    second = {k: v[1:] for k, v in out.items() if k != fragility.SECONDS}
    assert_same_runs(second, single_path(t, [base], sloshdyn.Integration()))


def test_fragility_runs_of_a_tank_of_three_modes_are_the_single_runs():
    """With modes 2..3 the peaks are read at the output times (the single run's table), so the
    block's runs keep every output (seismic_peaks' ends_only is for one mode alone): every
    peak equals the single run's, both phases (roof reached or not) among them."""
    t, motions, integration = tank(modes=3), records()[:1], sloshdyn.Integration()
    out = task(t, motions, integration)
    assert (out["roof_impact"] == 1).any() and (out["roof_impact"] == 0).any()
    assert_same_runs(out, single_path(t, motions, integration))
