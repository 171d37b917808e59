"""Regenerate computed_values.csv: each value computed by sloshdyn at tight tolerances and
confirmed here by an independent method before it is written (the method is recorded beside
it). Run from the repository root after a build:  python data/reference/make_reference.py"""

import csv
import math
import pathlib
import sys

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar

import sloshdyn
from sloshdyn import figures, reference

HERE = pathlib.Path(__file__).parent
sys.path.insert(0, str(HERE.parents[1] / "tests" / "python"))
from test_model import eq10_numpy  # noqa: E402  (eq 10 typed in numpy, independent of the core)
from test_response import scipy_return_time  # noqa: E402  (eq 53 typed in numpy, scipy)

#: the slow flow is first order in eps, with eps^2 the detuning (omega2 - 3 omega1)/omega1 of
#: sec 4.2 (eps^2 sigma1 = 0.005): its amplitudes and rates err by O(eps) relative
MODES = sloshdyn.linear_modes(figures.FIG12)
W1, W2 = MODES.omega1, MODES.omega2
EPS = math.sqrt(abs(W2 - 3 * W1) / W1)
ASYMPTOTIC = (f"asymptotic error: the slow flow is first order in eps, eps = sqrt((omega2 - 3 omega1)"
              f"/omega1) = {EPS:.4f}, so the full equations agree to O(eps) relative")


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
        reason = ("algebraic: Newton on eq (53) to 1e-12, no integrator involved, so any "
                  "build agrees to 1e-9")
        rows.append((f"slowflow_rho_{rho}_a1", a1, 1e-9, "rel", method, reason))
        rows.append((f"slowflow_rho_{rho}_a2", a2, 1e-9, "rel", method, reason))

    rows += steady_rows()

    for sigma_t, mu_t in ((0.305, 0.5), (1.0, 0.5), (3.0, 0.1)):
        alpha, beta = (1 + sigma_t) / (2 * mu_t), sigma_t / mu_t
        closed = math.sqrt((alpha + math.sqrt(alpha**2 - beta)) / (alpha - math.sqrt(alpha**2 - beta)))
        name = f"ratio_sigma_{sigma_t}_mu_{mu_t}"
        assert abs(values[name] - closed) <= 1e-12 * closed
        rows.append((name, values[name], 1e-12, "rel", "omega2/omega1; confirmed by eq (28) in "
                     "closed form (numpy), 1e-12", "closed form: rounding only"))

    rows += beat_rows() + fig15_rows()

    with open(HERE / "computed_values.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["quantity", "method", "reference", "tolerance", "kind", "reason"])
        for name, value, tol, kind, method, reason in rows:
            writer.writerow([name, method, repr(float(value)), tol, kind, reason])
    print(f"wrote {len(rows)} values to {HERE / 'computed_values.csv'}")


def steady_rows():
    """Fig 15 steady state: the same transient and window integrated by scipy DOP853 on eq (10),
    its maxima located on scipy's dense output (the best of 128 samples per period refined by
    scipy's bounded minimize_scalar between its neighbours), as the core locates them."""
    p = figures.FIG12.replace(rho=0.513)
    # integration only, as the reference's provider (shooting would jump to the orbit itself)
    st = sloshdyn.steady_state(p, steady=sloshdyn.Steady(shooting=False))
    period = 2 * math.pi / p.rho
    t_window = st.transient_periods * period
    samples = np.arange(0, 200 * 128 + 1) * period / 128 + t_window
    ref = solve_ivp(lambda t, y: eq10_numpy(p, t, y), (0, samples[-1]), np.zeros(4),
                    method="DOP853", rtol=1e-11, atol=1e-14, t_eval=samples, dense_output=True)
    modes = sloshdyn.linear_modes(p)

    def exact_max(quantity):
        values = np.abs(quantity(ref.y))
        k = int(np.argmax(values))
        lo, hi = samples[max(k - 1, 0)], samples[min(k + 1, len(samples) - 1)]
        best = minimize_scalar(lambda t: -abs(quantity(ref.sol(t)[:, None])[0]), bounds=(lo, hi),
                               method="bounded", options={"xatol": 1e-12 * period})
        return max(values[k], -best.fun)

    max_x1 = exact_max(lambda y: y[0])
    max_u1 = exact_max(lambda y: (modes.modal_inverse @ y[[0, 2]])[0])
    assert abs(max_x1 - st.max_x1) <= 1e-6 * max_x1 and abs(max_u1 - st.max_u1) <= 1e-6 * max_u1
    method = (f"steady state at rho = 0.513, A = 0.00075 from rest; confirmed by scipy DOP853 "
              f"(rtol 1e-11) on eq (10) over the same {st.transient_periods:.0f} + 200 periods, "
              f"maxima located on its dense output: {max_x1:.9g}, {max_u1:.9g} (1e-6)")
    reason = "the independent integration (scipy DOP853 at rtol 1e-11) agrees to 1e-6"
    return [("steady_fig15_max_x1", st.max_x1, 1e-6, "rel", method, reason),
            ("steady_fig15_max_u1", st.max_u1, 1e-6, "rel", method, reason)]


def beat_rows():
    """The Fig 14 beat two ways (issue 15), each confirmed by scipy on equations typed in numpy,
    and their ratio against the asymptotic error."""
    p = figures.FIG12
    period = 2 * math.pi / p.rho
    st, _, beat, slow_beat = figures.fig14_beats(quick=True)
    # full equations: scipy DOP853 on eq (10) over the same transient and window
    samples = (st.transient_periods + np.arange(3000)) * period
    ref = solve_ivp(lambda t, y: eq10_numpy(p, t, y), (0, samples[-1]), np.zeros(4),
                    method="DOP853", rtol=1e-11, atol=1e-14, t_eval=samples)
    scipy_beat = sloshdyn.beat_period(ref.y[:2])
    assert abs(scipy_beat - beat) <= 1e-5 * beat, (scipy_beat, beat)
    # slow flow: scipy DOP853 on eq (53) from the cycle's point returns to its section
    scipy_slow = scipy_return_time(p, sloshdyn.slow_flow_cycle(p))[0] / period
    assert abs(scipy_slow - slow_beat) <= 1e-7 * slow_beat, (scipy_slow, slow_beat)
    return [("beat_fig14_simulation", beat, 1e-4, "rel",
             f"Fig 14 beat [forcing periods] from the full equations: whole turns of the Poincare "
             f"points about their closed curve over 3000 periods after 5000; confirmed by scipy "
             f"DOP853 (rtol 1e-11) on eq (10): {scipy_beat:.8g}",
             "the independent integration agrees to 1e-5 and doubling the transient moves the "
             "beat by 1e-7; 1e-4 holds for any integrator at rtol <= 1e-9"),
            ("beat_fig14_slow_flow", slow_beat, 1e-6, "rel",
             f"period of the slow flow's limit cycle [forcing periods] at the Fig 14 point, by "
             f"Newton shooting with the period unknown; confirmed by scipy DOP853 (rtol 1e-11) "
             f"on eq (53) typed in numpy, return to the section: {scipy_slow:.10g}",
             "the independent return time agrees to 1e-7; shooting converges to 1e-10, so 1e-6 "
             "holds for any integrator at rtol <= 1e-9"),
            ("beat_fig14_ratio", 1.0, EPS, "rel",
             "ratio of the two beats (full equations over slow flow); expected 1", ASYMPTOTIC)]


def fig15_rows():
    """Fig 15 (rho = 0.513, A = 0.00075): the full equations' amplitude against the slow flow,
    and the Lyapunov exponent against the exact one of the periodic orbit (Floquet)."""
    p = figures.FIG12.replace(rho=0.513)
    st = sloshdyn.steady_state(p)
    orbit = sloshdyn.periodic_orbit(p, st.y_end)
    floquet = math.log(np.max(np.abs(orbit.multipliers))) / (2 * math.pi / p.rho)
    benettin_error = 1 / (2000 * 2 * math.pi / p.rho)
    return [("fig15_max_x1_over_slow_flow", 1.0, EPS, "rel",
             "max|x1| of the Fig 15 steady state over the slow flow's (its stable steady state "
             "of least |B1| at rho = 0.513, through eq 34, 42, 45); expected 1", ASYMPTOTIC),
            ("lyapunov_fig15", floquet, round(benettin_error, 6), "abs",
             "largest Lyapunov exponent of the Fig 15 periodic response (Benettin, 2000 periods); "
             "reference: ln max|mu| / T from the Floquet multipliers of the orbit by shooting",
             f"a finite-time estimate over N = 2000 forcing periods errs by O(1/(N T)) = "
             f"{benettin_error:.1e}")]


if __name__ == "__main__":
    main()
