"""Problems and peer integrators of the sloshdyn benchmark (benchmarks/run.py).

Every peer integrates the same equations of motion, eq (10)/(15) with X = A sin(rho tau):
the formula of tests/python/test_model.py::eq10_numpy, with the 2x2 inertia system solved in
closed form (Cramer's rule) instead of by np.linalg.solve, so the Python peers get a
reasonably fast right-hand side (about 2.5 us per call here instead of about 10 us).
The numba version is the same formula as a C callback (@cfunc) for numbalsoda.
"""

from __future__ import annotations

import inspect
import math
import os
import shutil
import subprocess
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

import sloshdyn

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent


# --------------------------------------------------------------------------- problems

def fig14_parameters(**changes):
    """The Fig 14 case of the paper (also the parameters of Fig 12: A = 0.00075)."""
    p = sloshdyn.Parameters(s1=1.5, mu1=0.5, kappa=1.804897259, theta0=math.pi / 4, gamma=0.001,
                            beta=10.0, delta=0.1, n=6, p=2, A=0.00075, rho=0.509615)
    return p.replace(**changes) if changes else p


@dataclass(frozen=True)
class Problem:
    key: str            #: 'a', 'b'
    title: str
    params: sloshdyn.Parameters
    periods: int
    y0: tuple

    @property
    def t_end(self):
        return self.periods * 2 * math.pi / self.params.rho


def problems(periods_a=2000, periods_b=500):
    return [
        Problem("a", f"(a) Fig 14 case, A = 0.00075, rho = 0.509615, {periods_a} periods from "
                     "y0 = (0.01, 0, 0.01, 0)",
                fig14_parameters(), periods_a, (0.01, 0.0, 0.01, 0.0)),
        Problem("b", f"(b) impacts, A = 2.0, rho = 0.513, {periods_b} periods from rest",
                fig14_parameters(A=2.0, rho=0.513), periods_b, (0.0, 0.0, 0.0, 0.0)),
    ]


def synthetic_records(n, seed=2026, quick=False):
    """n ground-motion records for the fragility benchmark, made here and seeded: durations
    20-100 s (2-4 s with quick), steps 0.005-0.02 s, white noise through a Kanai-Tajimi filter
    (ground frequency 1-4 Hz, damping 0.6; scipy's bilinear discretisation) under a
    quadratic build-up, plateau and exponential decay, peak 0.1 g."""
    from scipy import signal
    rng = np.random.default_rng(seed)
    records = []
    for _ in range(n):
        duration = rng.uniform(2, 4) if quick else rng.uniform(20, 100)
        dt = rng.uniform(0.005, 0.02)
        t = np.arange(int(duration / dt) + 1) * dt
        wg, zg = 2 * math.pi * rng.uniform(1, 4), 0.6
        b, a = signal.bilinear([2 * zg * wg, wg * wg], [1, 2 * zg * wg, wg * wg], fs=1 / dt)
        acc = signal.lfilter(b, a, rng.standard_normal(t.size))
        rise, decay = 0.15 * duration, 0.5 * duration
        acc *= np.where(t < rise, (t / rise) ** 2, np.where(
            t < decay, 1.0, np.exp(-3 * (t - decay) / (duration - decay))))
        records.append(sloshdyn.GroundMotion(dt=dt, acceleration=0.1 * acc / np.abs(acc).max(),
                                             units="g"))
    return records


def fragility_tank():
    """A 10 m tank (R = 5 m, h = 6 m) on 2 Hz supports with 1 m freeboard (the example tank
    of data/examples/tank_seismic.nml)."""
    return sloshdyn.Tank(radius=5.0, liquid_depth=6.0, freeboard=1.0, liquid_density=1000,
                         tank_mass=5.0e4, support_frequency=2.0, support_damping=0.02)


# --------------------------------------------------------------------------- right-hand sides

def python_rhs(p: sloshdyn.Parameters):
    """f(tau, y) of eq (15) in plain Python (eq10_numpy of the tests, inertia solved in closed
    form). Returns a numpy array, as solve_ivp and ode expect."""
    s1, mu1, kappa, t0 = p.s1, p.mu1, p.kappa, p.theta0
    beta, gamma, delta, rho = p.beta, p.gamma, p.delta, p.rho
    a_rho2 = p.A * rho * rho
    n_imp, n_dis = 2 * p.n - 1, 2 * p.p
    sin, cos, array = math.sin, math.cos, np.array

    def rhs(tau, y):
        x1, v1, x2, v2 = y
        xdd = -a_rho2 * sin(rho * tau)
        q1 = t0 * x1
        q2 = t0 * x2
        c12 = cos(q1 + q2)
        s12 = sin(q1 + q2)
        f1 = (t0 / s1 * s12 * v2 * v2 - sin(q1) / t0 - beta / t0 * x1 ** n_imp
              - delta * x1 ** n_dis * v1 - cos(q1) * xdd / (t0 * s1))
        f2 = (mu1 * s1 * t0 * s12 * v1 * v1 - kappa * x2 + s1 / t0 * sin(q2) - gamma * v2
              - xdd * cos(q2) / t0)
        m12 = c12 / s1
        m21 = mu1 * s1 * c12
        det = 1.0 - m12 * m21
        return array([v1, (f1 - m12 * f2) / det, v2, (f2 - m21 * f1) / det])

    return rhs


def check_python_rhs(p):
    """Largest difference between python_rhs and sloshdyn.equations_of_motion at a few states."""
    rhs = python_rhs(p)
    worst = 0.0
    for tau, y in [(2.3, (0.3, -0.7, 0.2, 0.4)), (7.1, (1.05, 0.5, -0.3, -0.9)),
                   (0.4, (-0.8, 1.3, 0.05, 0.2))]:
        ref = sloshdyn.equations_of_motion(p, tau, y).dydt
        worst = max(worst, float(np.max(np.abs(rhs(tau, np.array(y)) - ref)
                                        / np.maximum(1.0, np.abs(ref)))))
    return worst


# --------------------------------------------------------------------------- numba / numbalsoda

class Numba:
    """The numba cfunc right-hand side and numbalsoda's dop853, or the reason they are missing."""

    def __init__(self):
        self.available = False
        self.reason = ""
        try:
            import numba  # noqa: F401
            import numbalsoda  # noqa: F401
        except Exception as exc:   # ImportError, or a broken llvmlite
            self.reason = (f"numbalsoda/numba not importable ({type(exc).__name__}: {exc}); "
                           "pip install numbalsoda numba to include this peer")
            return
        import numba
        import numbalsoda
        from numba import carray, cfunc, njit, types
        self.versions = f"numba {numba.__version__}, numbalsoda {_dist_version('numbalsoda')}"
        t = time.perf_counter()

        @njit(cache=False, fastmath=False)
        def eom(tau, u, du, d):
            s1 = d[0]; mu1 = d[1]; kappa = d[2]; t0 = d[3]; beta = d[4]       # noqa: E702
            gamma = d[5]; delta = d[6]; a = d[7]; rho = d[8]                   # noqa: E702
            n_imp = int(d[9]); n_dis = int(d[10])                              # noqa: E702
            x1 = u[0]; v1 = u[1]; x2 = u[2]; v2 = u[3]                         # noqa: E702
            xdd = -a * rho * rho * math.sin(rho * tau)
            q1 = t0 * x1
            q2 = t0 * x2
            c12 = math.cos(q1 + q2)
            s12 = math.sin(q1 + q2)
            f1 = (t0 / s1 * s12 * v2 * v2 - math.sin(q1) / t0 - beta / t0 * x1 ** n_imp
                  - delta * x1 ** n_dis * v1 - math.cos(q1) * xdd / (t0 * s1))
            f2 = (mu1 * s1 * t0 * s12 * v1 * v1 - kappa * x2 + s1 / t0 * math.sin(q2)
                  - gamma * v2 - xdd * math.cos(q2) / t0)
            m12 = c12 / s1
            m21 = mu1 * s1 * c12
            det = 1.0 - m12 * m21
            du[0] = v1
            du[1] = (f1 - m12 * f2) / det
            du[2] = v2
            du[3] = (f2 - m21 * f1) / det

        sig = types.void(types.double, types.CPointer(types.double),
                         types.CPointer(types.double), types.CPointer(types.double))

        @cfunc(sig)
        def rhs(tau, u_, du_, d_):
            eom(tau, carray(u_, (4,)), carray(du_, (4,)), carray(d_, (12,)))

        @cfunc(sig)
        def rhs_counting(tau, u_, du_, d_):      # the same, counting its calls in d[11]
            d = carray(d_, (12,))
            eom(tau, carray(u_, (4,)), carray(du_, (4,)), d)
            d[11] += 1.0

        @njit
        def time_eom(n, tau0, u0, d):
            u = u0.copy()
            du = np.zeros(4)
            acc = 0.0
            tau = tau0
            for _ in range(n):
                tau += 0.01
                eom(tau, u, du, d)
                for k in range(4):
                    u[k] += 1e-9 * du[k]
                acc += du[1]
            return acc

        self.rhs, self.rhs_counting, self.time_eom = rhs, rhs_counting, time_eom
        self.dop853 = numbalsoda.dop853
        try:
            self.has_mxstep = "mxstep" in inspect.signature(
                getattr(numbalsoda.dop853, "py_func", numbalsoda.dop853)).parameters
        except (TypeError, ValueError):
            self.has_mxstep = False
        self.available = True
        # compile the cfuncs' callers once, outside any timing
        p = fig14_parameters()
        self.integrate(p, (0.01, 0, 0.01, 0), 10.0, 1e-6, 1e-9)
        self.integrate(p, (0.01, 0, 0.01, 0), 10.0, 1e-6, 1e-9, count=True)
        self.time_eom(10, 0.0, np.array([0.01, 0.0, 0.01, 0.0]), self.data(p))
        self.compile_seconds = time.perf_counter() - t

    @staticmethod
    def data(p):
        return np.array([p.s1, p.mu1, p.kappa, p.theta0, p.beta, p.gamma, p.delta, p.A, p.rho,
                         2 * p.n - 1, 2 * p.p, 0.0], dtype=np.float64)

    def check(self, p):
        """Largest relative difference between the cfunc and sloshdyn.equations_of_motion."""
        import ctypes
        proto = ctypes.CFUNCTYPE(None, ctypes.c_double, ctypes.POINTER(ctypes.c_double),
                                 ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double))
        f = proto(self.rhs.address)
        d = self.data(p)
        worst = 0.0
        for tau, y in [(2.3, (0.3, -0.7, 0.2, 0.4)), (7.1, (1.05, 0.5, -0.3, -0.9))]:
            u = np.array(y, dtype=np.float64)
            du = np.zeros(4)
            ptr = ctypes.POINTER(ctypes.c_double)
            f(tau, u.ctypes.data_as(ptr), du.ctypes.data_as(ptr), d.ctypes.data_as(ptr))
            ref = sloshdyn.equations_of_motion(p, tau, y).dydt
            worst = max(worst, float(np.max(np.abs(du - ref) / np.maximum(1.0, np.abs(ref)))))
        return worst

    def integrate(self, p, y0, t_end, rtol, atol, count=False):
        """numbalsoda dop853 from 0 to t_end, output at t_end only. Returns (y_end, n_rhs or
        None). One call with mxstep = 10^9 when numbalsoda has that argument (0.3.x); older
        versions stop after 10 000 steps per call, so the span is then chained in pieces of
        10 forcing periods (halved whenever a piece fails)."""
        d = self.data(p)
        fptr = (self.rhs_counting if count else self.rhs).address
        u0 = np.array(y0, dtype=np.float64)
        if self.has_mxstep:
            usol, ok = self.dop853(fptr, u0, np.array([0.0, t_end]), data=d, rtol=rtol,
                                   atol=atol, mxstep=10**9)
            if not ok:
                raise RuntimeError("numbalsoda dop853 failed")
            return usol[-1].copy(), (int(d[11]) if count else None)
        span = 10 * 2 * math.pi / p.rho
        t, u = 0.0, u0
        while t < t_end:
            t1 = min(t_end, t + span)
            usol, ok = self.dop853(fptr, u, np.array([t, t1]), data=d, rtol=rtol, atol=atol)
            if not ok:
                span /= 2
                if span < 1e-6:
                    raise RuntimeError("numbalsoda dop853 failed")
                continue
            t, u = t1, usol[-1].copy()
        return u, (int(d[11]) if count else None)


def _dist_version(name):
    try:
        from importlib.metadata import version
        return version(name)
    except Exception:
        return "?"


# --------------------------------------------------------------------------- peer runs

@dataclass
class Run:
    """One integration: final state and work counts (None where the solver does not say)."""

    y_end: np.ndarray
    n_rhs: int | None
    steps: int | None        #: attempted steps (accepted + rejected)
    rejected: int | None = None
    steps_exact: bool = True


def run_sloshdyn(problem, rtol, atol, method):
    """method 'auto' is the default path: simulate is called without method=."""
    chosen = {} if method == "auto" else {"method": method}
    sim = sloshdyn.simulate(problem.params, problem.t_end, problem.y0,
                            tau_out=[0.0, problem.t_end],
                            integration=sloshdyn.Integration(rtol=rtol, atol=atol, **chosen))
    return Run(sim.y[:, -1].copy(), sim.n_rhs, sim.n_accepted + sim.n_rejected, sim.n_rejected)


def run_solve_ivp(problem, rtol, atol, method, rhs):
    from scipy.integrate import solve_ivp
    sol = solve_ivp(rhs, (0.0, problem.t_end), np.array(problem.y0, dtype=np.float64),
                    method=method, rtol=rtol, atol=atol, t_eval=[problem.t_end])
    if sol.status != 0:
        raise RuntimeError(f"solve_ivp {method}: {sol.message}")
    stages = {"RK45": 6, "DOP853": 12}[method]
    # one evaluation at t0 and one in the initial-step selection; then `stages` per attempt
    return Run(sol.y[:, -1].copy(), int(sol.nfev), int(round((sol.nfev - 2) / stages)),
               None, steps_exact=False)


def run_ode_dopri5(problem, rtol, atol, rhs):
    from scipy.integrate import ode
    r = ode(rhs).set_integrator("dopri5", rtol=rtol, atol=atol, nsteps=2_000_000_000)
    r.set_initial_value(np.array(problem.y0, dtype=np.float64), 0.0)
    y = r.integrate(problem.t_end)
    if not r.successful():
        raise RuntimeError("ode dopri5 failed")
    iwork = getattr(r._integrator, "iwork", None)     # Hairer's IWORK(17..20)
    if iwork is not None and iwork[16] > 0:
        return Run(np.array(y), int(iwork[16]), int(iwork[17]), int(iwork[19]))
    return Run(np.array(y), None, None)


# --------------------------------------------------------------------------- Fortran rhs cost

def fortran_rhs_cost(p, n_calls=5_000_000):
    """Seconds per call of the core's equations_of_motion (sloshdyn_motion), timed by a small
    Fortran driver (benchmarks/rhs_cost.f90) compiled against the meson build directory's
    modules and static library. Returns (seconds, None) or (None, reason)."""
    build = Path(os.environ.get("SLOSHDYN_BUILD_DIR", ROOT / "build"))
    lib = build / "fortran" / "libsloshdyn.a"
    mods = build / "fortran" / "libsloshdyn.a.p"
    fc = shutil.which(os.environ.get("FC", "gfortran"))
    if fc is None:
        return None, "gfortran not found"
    if not lib.exists() or not (mods / "sloshdyn_motion.mod").exists():
        return None, f"no meson build in {build} (run bash .ci/dev test)"
    with tempfile.TemporaryDirectory() as tmp:
        exe = Path(tmp) / "rhs_cost"
        cmd = [fc, "-O3", f"-I{mods}", str(HERE / "rhs_cost.f90"), str(lib), "-o", str(exe)]
        # libsloshdyn.a may need OpenMP and LAPACK at link time; the rhs itself uses neither
        for extra in ([], ["-fopenmp"], ["-fopenmp", "-llapack", "-lblas"]):
            res = subprocess.run(cmd + extra, capture_output=True, text=True, cwd=tmp)
            if res.returncode == 0:
                break
        else:
            return None, "could not compile the driver: " + res.stderr.strip()[-300:]
        rpar, ipar = p.array()
        text = " ".join(repr(float(x)) for x in rpar) + " " + " ".join(str(int(i)) for i in ipar)
        best = None
        for _ in range(3):
            res = subprocess.run([str(exe)], input=f"{text} {n_calls}\n", capture_output=True,
                                 text=True)
            if res.returncode != 0:
                return None, "driver failed: " + (res.stdout + res.stderr).strip()[-300:]
            seconds = float(res.stdout.split()[0])
            best = seconds if best is None else min(best, seconds)
        return best, None
