"""The core functions run by .ci/wheel_check.sh, from the wheel and from the source build.

  python wheel_cases.py run OUT.npz     a simulation, the equilibria (LAPACK dgeev), a seismic
                                        run and linear modes, saved as arrays
  python wheel_cases.py compare A B     every array of A equals B's to 1e-12 (relative to the
                                        array's largest magnitude); exit 1 otherwise
  python wheel_cases.py csv A B         the same for two directories of CSV result files
"""

import csv
import math
import sys
from pathlib import Path

import numpy as np

TOL = 1e-12


def run(out, root):
    import sloshdyn
    p = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=math.pi / 4,
                            beta=1.0, gamma=0.001, A=0.00075, rho=0.509615)
    arrays = {}
    sim = sloshdyn.simulate(p, t_end=200.0, y0=[0.01, 0, 0, 0],
                           integration=sloshdyn.Integration(rtol=1e-10, atol=1e-13))
    arrays.update(sim_tau=sim.tau, sim_u=sim.u, sim_impact=sim.impact_force)
    eq = sloshdyn.equilibria(p)
    arrays["equilibria"] = np.array([[e.theta, e.phi] for e in eq.points])
    arrays["eigenvalues"] = np.array([e.eigenvalues for e in eq.points])
    arrays["routh"] = eq.routh_coefficients
    modes = sloshdyn.linear_modes(p)
    arrays["omega_dgeev"] = np.array([modes.omega1_dgeev, modes.omega2_dgeev])
    arrays["modal"] = modes.modal
    tank = sloshdyn.Tank(radius=5.0, liquid_depth=6.0, freeboard=1.0, liquid_density=1000,
                         tank_mass=5e4, support_frequency=2.0, support_damping=0.02)
    quake = sloshdyn.GroundMotion.from_file(root / "data/examples/records/synthetic_kt.AT2")
    r = sloshdyn.seismic_response(tank, quake)
    arrays.update(seismic_t=r.t, wave_height=r.wave_height, base_shear=r.base_shear,
                  overturning_moment=r.overturning_moment)
    np.savez(out, **arrays)
    print(f"{out}: {len(arrays)} arrays, {sum(a.size for a in arrays.values())} numbers, "
          f"{len(eq.points)} equilibria, peak wave height {r.peaks['wave_height']}")


def differ(name, a, b):
    """A message if arrays a and b differ by more than TOL (relative to their largest value)."""
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape:
        return f"{name}: shapes {a.shape} and {b.shape}"
    scale = max(1.0, float(np.max(np.abs(b), initial=0.0)))
    err = float(np.max(np.abs(a - b), initial=0.0)) / scale
    return f"{name}: differs by {err:.3g}" if not err <= TOL else None


def compare(a, b):
    with np.load(a) as x, np.load(b) as y:
        if sorted(x.files) != sorted(y.files):
            return [f"arrays {sorted(x.files)} and {sorted(y.files)}"]
        return [m for m in (differ(n, x[n], y[n]) for n in x.files) if m]


def csv_table(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def compare_csv(a, b):
    names = sorted(p.name for p in Path(a).glob("*.csv"))
    if not names or names != sorted(p.name for p in Path(b).glob("*.csv")):
        return [f"CSV files {names} in {a}, and in {b}: "
                f"{sorted(p.name for p in Path(b).glob('*.csv'))}"]
    problems = []
    for name in names:
        (ha, ra), (hb, rb) = csv_table(Path(a) / name), csv_table(Path(b) / name)
        if ha != hb or len(ra) != len(rb):
            problems.append(f"{name}: header or number of rows")
            continue
        for j, column in enumerate(ha):
            xa, xb = [r[j] for r in ra], [r[j] for r in rb]
            try:
                message = differ(f"{name}:{column}", np.array(xa, float), np.array(xb, float))
            except ValueError:        # a text column
                message = None if xa == xb else f"{name}:{column}: text differs"
            if message:
                problems.append(message)
    return problems


if __name__ == "__main__":
    what, *args = sys.argv[1:]
    if what == "run":
        run(args[0], Path(__file__).resolve().parent.parent)
    else:
        problems = compare(*args) if what == "compare" else compare_csv(*args)
        for line in problems:
            print(f"error: {line}", file=sys.stderr)
        print(f"{what}: {args[0]} and {args[1]} " + ("differ" if problems else f"agree to {TOL}"))
        sys.exit(1 if problems else 0)
