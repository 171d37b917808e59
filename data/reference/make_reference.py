"""Regenerate computed_values.csv: each value computed by sloshdyn at tight tolerances and
confirmed here by an independent method before it is written (the method is recorded beside
it). Run from the repository root after a build:  python data/reference/make_reference.py"""

import csv
import math
import pathlib
import sys

import numpy as np
from scipy.integrate import solve_ivp

import sloshdyn
from sloshdyn import figures, reference

HERE = pathlib.Path(__file__).parent
sys.path.insert(0, str(HERE.parents[1] / "tests" / "python"))
from test_model import eq10_numpy  # noqa: E402  (eq 10 typed in numpy, independent of the core)


def harmonics(p, y0, periods=200, per=64):
    period = 2 * math.pi / p.rho
    tau = np.arange(periods * per + 1) * period / per
    sim = sloshdyn.simulate(p, tau[-1], y0, tau_out=tau)
    t = tau[:-1]
    return (2 * abs(np.mean(sim.u[0][:-1] * np.exp(-1j * p.rho * t))),
            2 * abs(np.mean(sim.u[1][:-1] * np.exp(-3j * p.rho * t))))


def main():
    values = reference._computed(quick=False)
    rows = []
    for rho in (0.505, 0.508, 0.5105, 0.511):
        p = figures.FIG12.replace(rho=rho)
        st = sloshdyn.steady_state(p)
        h1, h2 = harmonics(p, st.y_end)
        a1, a2 = values[f"slowflow_rho_{rho}_a1"], values[f"slowflow_rho_{rho}_a2"]
        assert abs(h1 - a1) <= 0.02 * a1 and abs(h2 - a2) <= 0.10 * a2, (rho, a1, h1, a2, h2)
        method = (f"slow flow (3:1, Fig 12 parameters); confirmed by direct RK45 simulation: "
                  f"rho-harmonic of u1 {h1:.6g} (2 %), 3 rho-harmonic of u2 {h2:.6g} (10 %)")
        rows.append((f"slowflow_rho_{rho}_a1", a1, 1e-9, method))
        rows.append((f"slowflow_rho_{rho}_a2", a2, 1e-9, method))

    # Fig 15 steady state: the same transient and window integrated by scipy DOP853 on eq (10)
    p = figures.FIG12.replace(rho=0.513)
    st = sloshdyn.steady_state(p)
    period = 2 * math.pi / p.rho
    t_window = st.transient_periods * period
    samples = np.arange(1, 200 * 128 + 1) * period / 128 + t_window
    ref = solve_ivp(lambda t, y: eq10_numpy(p, t, y), (0, samples[-1]), np.zeros(4),
                    method="DOP853", rtol=1e-11, atol=1e-14, t_eval=samples)
    max_x1 = np.max(np.abs(ref.y[0]))
    modes = sloshdyn.linear_modes(p)
    max_u1 = np.max(np.abs((modes.modal_inverse @ ref.y[[0, 2]])[0]))
    assert abs(max_x1 - st.max_x1) <= 1e-6 * max_x1 and abs(max_u1 - st.max_u1) <= 1e-6 * max_u1
    method = (f"steady state at rho = 0.513, A = 0.00075 from rest; confirmed by scipy DOP853 "
              f"(rtol 1e-11) on eq (10) over the same {st.transient_periods:.0f} + 200 periods: "
              f"{max_x1:.9g}, {max_u1:.9g} (1e-6)")
    rows.append(("steady_fig15_max_x1", st.max_x1, 1e-7, method))
    rows.append(("steady_fig15_max_u1", st.max_u1, 1e-7, method))

    for sigma_t, mu_t in ((0.305, 0.5), (1.0, 0.5), (3.0, 0.1)):
        alpha, beta = (1 + sigma_t) / (2 * mu_t), sigma_t / mu_t
        closed = math.sqrt((alpha + math.sqrt(alpha**2 - beta)) / (alpha - math.sqrt(alpha**2 - beta)))
        name = f"ratio_sigma_{sigma_t}_mu_{mu_t}"
        assert abs(values[name] - closed) <= 1e-12 * closed
        rows.append((name, values[name], 1e-12, "omega2/omega1; confirmed by eq (28) in closed form (numpy), 1e-12"))

    with open(HERE / "computed_values.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["quantity", "method", "reference", "tolerance", "kind"])
        for name, value, tol, method in rows:
            writer.writerow([name, method, repr(float(value)), tol, "rel"])
    print(f"wrote {len(rows)} values to {HERE / 'computed_values.csv'}")


if __name__ == "__main__":
    main()
