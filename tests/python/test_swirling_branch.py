"""The swirling orbits born at a swirl edge, switched onto and continued (issue 41).

Independent source: brute-force simulation (the spatial model's integrator, no shooting or
continuation) from the planar orbit plus a small out-of-plane kick, run until it repeats itself
after a period to 1e-9; and, on the unstable part of the branch, the growth of a small
perturbation of the continued orbit.
"""

import functools

import numpy as np
import pytest

import sloshdyn
from sloshdyn import spatial
from sloshdyn.options import Continuation, Integration
from conftest import read_csv, run, write

PARAMS = sloshdyn.Parameters(s1=1.0, mu1=0.01, kappa=1e3, theta0=1.4, beta=0.0, gamma=0.0,
                             delta=0.0, A=1e-3, rho=1.02, zeta=5e-4, n=6, p=2)
RHO = 1.003          # inside the band, where the swirl settles
STEPS = Continuation(ds=0.01, ds_min=1e-9, ds_max=0.05, x_scale=1.0, max_points=400)


@functools.lru_cache(maxsize=1)
def _branch():
    band = spatial.swirl_band(PARAMS, (0.995, 1.02), from_end="high")
    return band, spatial.swirling_branch(band, 0, (RHO, 1.1), params=PARAMS, ds=0.01,
                                         continuation=STEPS)


def _mirror_free(table, j):
    return np.array([table["max_x1"][j], table["swirl_amplitude"][j],
                     abs(table["angular_momentum"][j])])


def test_the_branch_leaves_the_edge_unstable_folds_and_returns_stable():
    band, branch = _branch()
    table = branch.table
    assert branch.complete
    edge = band.edges["rho"][0]
    # a pitchfork: the first point is next to the edge with a small swirl
    assert abs(table["rho"][0] - edge) < 1e-3 and table["swirl_amplitude"][0] < 0.02
    assert [p.kind for p in branch.special_points] == ["fold"]
    fold = branch.special_points[0].rho
    assert 1.05 < fold < 1.1 and table["rho"].max() <= fold + 1e-9
    turn = int(np.argmax(table["rho"]))
    assert np.all(table["stable"][:turn - 1] == 0) and np.all(table["stable"][turn + 1:] == 1)
    assert table["rho"][-1] == RHO


def test_the_continued_orbit_is_the_settled_simulation():
    _, branch = _branch()
    params = PARAMS.replace(rho=RHO)
    planar = sloshdyn.periodic_orbit(params)
    y0 = np.concatenate([planar.y0, [1e-4, 0.0, 0.0, 0.0]])
    period, periods = 2 * np.pi / RHO, 7000
    tau = (periods - 1) * period + np.linspace(0, period, 4001)
    sim = spatial.simulate(params, periods * period, y0, tau_out=tau,
                           integration=Integration(rtol=1e-11))
    assert np.abs(sim.y[:, -1] - sim.y[:, 0]).max() < 1e-8          # settled: measured 8e-10
    momentum = np.mean([spatial.equations_of_motion(params, t, y).angular_momentum
                        for t, y in zip(tau[:-1], sim.y[:, :-1].T)])
    settled = np.array([np.abs(sim.y[0]).max(), np.abs(sim.y[4]).max(), abs(momentum)])
    # 4000 samples a period: maxima within (pi/4000)^2 of the true ones (measured 3e-8, 5e-8,
    # 1.5e-8 relative)
    assert _mirror_free(branch.table, -1) == pytest.approx(settled, rel=1e-6)
    assert branch.table["stable"][-1] == 1                       # it settles: stable


def test_a_perturbation_of_an_unstable_swirling_orbit_grows():
    _, branch = _branch()
    table = branch.table
    j = int(np.flatnonzero(table["stable"] == 0)[len(table["rho"]) // 8])
    params = PARAMS.replace(rho=table["rho"][j])
    y = np.array([table[f"y{i}"][j] for i in range(1, 9)])
    largest = max(abs(table[f"mu{i}"][j]) for i in range(1, 9))
    assert largest > 1.005
    period, periods = 2 * np.pi / params.rho, 300
    # on the orbit: the simulation repeats y after a period to the integrator's tolerance
    on = spatial.simulate(params, period, y, tau_out=[period], integration=Integration(rtol=1e-12))
    assert np.abs(on.y[:, -1] - y).max() < 1e-8
    off = spatial.simulate(params, periods * period, y + 1e-9, tau_out=[periods * period],
                           integration=Integration(rtol=1e-12))
    # at least largest^periods / 20 of growth (the kick's part along the unstable direction)
    assert np.abs(off.y[:, -1] - y).max() > 1e-9 * largest**periods / 20


def test_a_bad_edge_is_named():
    band, _ = _branch()
    with pytest.raises(sloshdyn.InputError, match="edge = 3"):
        spatial.swirling_branch(band, 3, params=PARAMS)


SWIRLING_NML = ("&model s1 = 1.0, mu1 = 0.01, kappa = 1000, theta0 = 1.4, beta = 0, gamma = 0, "
                "delta = 0, zeta = 5e-4, n = 6, p = 2, planar = .false. /\n"
                "&excitation A = 0.001, rho = 1.0 /\n&analysis kind = 'swirl' /\n"
                "&response parameter = 'rho', start = 1.0, stop = 1.02, switch_at = {edge} /\n"
                "&output directory = 'out' /\n")


def test_the_namelists_switch_at_is_the_python_swirling_branch(exe, tmp_path):
    path = write(tmp_path, SWIRLING_NML.format(edge=1))
    result = run(exe, path.name, tmp_path)
    assert result.returncode == 0, result.stderr
    rows = read_csv(tmp_path / "out" / "swirling_branch.csv")
    inp = sloshdyn.read_namelist(path)
    r = inp.response_range
    band = spatial.swirl_band(inp.params, (r["start"], r["stop"]), continuation=inp.response,
                              integration=inp.integration)
    branch = spatial.swirling_branch(band, 0, (r["start"], r["stop"]), params=inp.params,
                                     continuation=inp.response, integration=inp.integration)
    assert len(rows) == len(branch.table["lambda"]) > 3
    for name in ("lambda", "y5", "max_x1", "swirl_amplitude", "angular_momentum", "stable"):
        assert [row[name] for row in rows] == list(branch.table[name]), name
    # born at the edge with a small swirl that grows along the branch (a pitchfork)
    assert rows[0]["swirl_amplitude"] < rows[-1]["swirl_amplitude"]
    # an edge that is not there is named
    path = write(tmp_path, SWIRLING_NML.format(edge=5))
    result = run(exe, path.name, tmp_path)
    assert result.returncode == 3 and "switch_at = 5" in result.stderr, result.stderr
