"""Benchmark of sloshdyn against peer integrators, in one process run.

    python benchmarks/run.py [--quick] [--repeats N] [--out FILE] [--peer-cap SECONDS]

Times sloshdyn.simulate (methods 'rk45' and 'dop853', Fortran) against scipy's solve_ivp
('RK45', 'DOP853'; Python right-hand side), scipy's ode('dopri5') (Hairer's DOPRI5, Python
right-hand side) and numbalsoda's dop853 (numba cfunc right-hand side) on identical problems,
at equal tolerance and at equal accuracy (work-precision), then the cost per right-hand-side
evaluation, a frequency sweep on 1 and 2 threads with its memory, the Fig 12 continuation
and the cost of one Python call into the core. Prints tables of ratios (speed-up of sloshdyn
over each peer) and PASS/MISS against the project's targets; --out writes them as Markdown.
See benchmarks/README.md.
"""

from __future__ import annotations

import argparse
import datetime
import gc
import json
import math
import os
import platform
import resource
import statistics
import subprocess
import sys
import time
import timeit
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import sloshdyn  # noqa: E402

import peers  # noqa: E402

REF_RTOL = 1e-14          # the reference: sloshdyn dop853 at this rtol
CROSS_RTOL = 1e-13        # cross-check of the reference: solve_ivp DOP853 (problem a)
ATOL_FACTOR = 1e-3        # atol = rtol * ATOL_FACTOR for every solver
SATURATED = 1e-2          # relative final-time error above which accuracy is meaningless
MIN_REPEATS_FAST = 5      # runs shorter than FAST_RUN are repeated at least this often
FAST_RUN = 0.5

PYTHON_PEERS = ["solve_ivp RK45", "solve_ivp DOP853", "ode dopri5"]
FAMILY = {"solve_ivp RK45": "rk45", "ode dopri5": "rk45", "solve_ivp DOP853": "dop853",
          "numbalsoda dop853": "dop853"}
TARGETS = {"solve_ivp RK45": 100.0, "ode dopri5": 30.0, "numbalsoda dop853": 1.0}
#: sloshdyn's methods on the ladder; 'auto' is the default path (simulate without method=)
SLOSHDYN_METHODS = ("rk45", "dop853", "vern9", "auto")
#: targets of the default path (issue 16), at equal accuracy (equal tolerance when saturated)
DEFAULT_TARGETS = {"solve_ivp DOP853": 50.0, "numbalsoda dop853": 1.2}
FIG12_TARGET = 0.030      # seconds
CHART_TARGET = 0.5        # seconds, the default stability chart (issue 28)
FRAGILITY_TARGET = 15.0   # seconds, 44 records x 20 intensities on 2 cores (issue 28)
SCALING_TARGET = 1.85     # 2 workers against 1 at the engine's default task size (issue 28)


# --------------------------------------------------------------------------- output

def log(msg):
    print(f"  .. {msg}", file=sys.stderr, flush=True)


class Report:
    """Headings, paragraphs and tables, printed as text as they come and kept for Markdown."""

    def __init__(self, cpu):
        self.blocks = []
        self.cpu = cpu   # the processor model, printed under every table with the load

    def heading(self, text):
        self.blocks.append(("h", text))
        print(f"\n## {text}\n", flush=True)

    def para(self, text):
        self.blocks.append(("p", text))
        print(text, flush=True)

    def table(self, headers, rows):
        rows = [[str(c) for c in r] for r in rows]
        self.blocks.append(("t", headers, rows))
        widths = [max(len(h), *(len(r[i]) for r in rows)) if rows else len(h)
                  for i, h in enumerate(headers)]
        line = "  ".join(h.ljust(w) for h, w in zip(headers, widths))
        print(line)
        print("  ".join("-" * w for w in widths))
        for r in rows:
            print("  ".join(c.rjust(w) if _numeric(c) else c.ljust(w) for c, w in zip(r, widths)))
        print(flush=True)
        self.para(f"Machine: {self.cpu}; load average {os.getloadavg()[0]:.2f} after this table.")

    def markdown(self):
        out = []
        for b in self.blocks:
            if b[0] == "h":
                out.append(f"## {b[1]}\n")
            elif b[0] == "p":
                out.append(b[1] + "\n")
            else:
                _, headers, rows = b
                out.append("| " + " | ".join(headers) + " |")
                out.append("|" + "|".join("---:" if rows and _numeric(rows[0][i]) else "---"
                                          for i in range(len(headers))) + "|")
                for r in rows:
                    out.append("| " + " | ".join(c.replace("|", "\\|") for c in r) + " |")
                out.append("")
        return "\n".join(out) + "\n"


def _numeric(text):
    t = text.strip().replace("=tol ", "").lstrip("≥≤~<>").replace("x", "").replace("%", "").split(" ")[0]
    try:
        float(t)
        return True
    except ValueError:
        return False


def fmt_t(seconds):
    if seconds is None:
        return "—"
    if seconds >= 1:
        return f"{seconds:.2f} s"
    if seconds >= 1e-3:
        return f"{seconds * 1e3:.1f} ms"
    return f"{seconds * 1e6:.1f} us"


def fmt_x(ratio, flag=""):
    if ratio is None:
        return "—"
    return f"{flag}{ratio:.3g}x" if ratio < 100 else f"{flag}{ratio:.0f}x"


def fmt_e(err):
    return "—" if err is None else f"{err:.1e}"


def fmt_n(n):
    return "—" if n is None else f"{n:,}"


# --------------------------------------------------------------------------- timing

def timed(fn, repeats):
    """(median seconds, result of the last run, all times)."""
    times, result = [], None
    for _ in range(max(1, repeats)):
        gc.collect()
        t = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times), result, times


def timed_interleaved(fns, repeats):
    """Time several callables in turn, repeat by repeat, so slow drifts of the machine's load
    hit them alike. Runs shorter than FAST_RUN are repeated at least MIN_REPEATS_FAST times.
    Returns {name: (median seconds, result, times)}."""
    times = {k: [] for k in fns}
    results = {}
    rounds = max(1, repeats)
    i = 0
    while i < rounds:
        for name, fn in fns.items():
            gc.collect()
            t = time.perf_counter()
            results[name] = fn()
            times[name].append(time.perf_counter() - t)
        i += 1
        if i == rounds and rounds < MIN_REPEATS_FAST and max(max(v) for v in times.values()) < FAST_RUN:
            rounds = MIN_REPEATS_FAST
    return {k: (statistics.median(v), results[k], v) for k, v in times.items()}


def rel_error(y, ref):
    return float(np.max(np.abs(np.asarray(y) - ref)) / np.max(np.abs(ref)))


# --------------------------------------------------------------------------- work-precision

def pareto(points):
    """points: [(error, seconds)]; the front of least time for errors up to e, sorted by
    increasing error (so decreasing time)."""
    front = []
    for e, t in sorted((max(e, 1e-300), t) for e, t in points):
        if not front or t < front[-1][1]:
            front.append((e, t))
    return front


def time_at_error(points, target):
    """sloshdyn time needed for error <= target, log-log interpolated along its front.
    Returns (seconds, flag): flag '' inside the ladder; '≥' when the target is looser than
    sloshdyn's loosest run (sloshdyn needs less than the time returned, so the speed-up is at
    least the one shown); '≤' when tighter than its tightest run (speed-up at most)."""
    front = pareto(points)
    target = max(target, 1e-300)
    if target < front[0][0]:
        return front[0][1], "≤"
    if target >= front[-1][0]:
        return front[-1][1], "≥"
    for (e0, t0), (e1, t1) in zip(front, front[1:]):
        if e0 <= target <= e1:
            if e1 == e0:
                return t0, ""
            w = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + w * (math.log(t1) - math.log(t0))), ""
    return front[-1][1], "≥"


# --------------------------------------------------------------------------- sections

def cpu_model():
    """The processor model of /proc/cpuinfo ('?' where there is none)."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "?"


def machine_info():
    import scipy
    return {
        "cpu": cpu_model(), "nproc": os.cpu_count(),
        "date": datetime.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z"),
        "python": platform.python_version(), "numpy": np.__version__, "scipy": scipy.__version__,
        "sloshdyn": getattr(sloshdyn, "__version__", "?"),
        "OMP_NUM_THREADS": os.environ.get("OMP_NUM_THREADS", "unset"),
        "load": " ".join(f"{x:.2f}" for x in os.getloadavg()),
    }


class Bench:
    def __init__(self, args):
        self.args = args
        self.quick = args.quick
        self.report = Report(f"{cpu_model()}, {os.cpu_count()} cores")
        self.repeats = 1 if args.quick and args.repeats is None else (args.repeats or 3)
        if self.quick:
            self.tolerances = [1e-6, 1e-9]
            self.ladder = [1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10]
            self.problems = peers.problems(20, 20)
        else:
            self.tolerances = [1e-6, 1e-9, 1e-12]
            self.ladder = sorted({*(10 ** (-k / 2) for k in range(10, 27)), *self.tolerances},
                                 reverse=True)
            self.problems = peers.problems(2000, 500)
        self.peer_cap = args.peer_cap
        self.numba = None
        self.results = {}     # problem key -> dict
        self.verdicts = []    # (target, measured, verdict, note)

    # ------------------------------------------------------------------ setup
    def setup(self):
        r = self.report
        info = machine_info()
        self.info = info
        r.heading("Machine and versions")
        r.para(f"CPU: {info['cpu']}, {info['nproc']} cores (nproc); {info['date']}; load "
               f"average at start {info['load']}; OMP_NUM_THREADS={info['OMP_NUM_THREADS']}.")
        p = peers.fig14_parameters()
        err_py = max(peers.check_python_rhs(pr.params) for pr in self.problems)
        log("compiling the numba right-hand side (if numba/numbalsoda are installed)")
        self.numba = peers.Numba()
        versions = (f"Python {info['python']}, numpy {info['numpy']}, scipy {info['scipy']}, "
                    f"sloshdyn {info['sloshdyn']}")
        if self.numba.available:
            versions += f", {self.numba.versions}"
            err_nb = max(self.numba.check(pr.params) for pr in self.problems)
            nb_line = (f"numba cfunc rhs vs sloshdyn.equations_of_motion: largest difference "
                       f"{err_nb:.1e} (compile and warm-up {self.numba.compile_seconds:.1f} s, "
                       "not timed). numbalsoda dop853: "
                       + ("one call per integration with mxstep = 10^9." if self.numba.has_mxstep
                          else "chained calls of 10 forcing periods (no mxstep argument)."))
        else:
            nb_line = f"numbalsoda dop853 peer SKIPPED: {self.numba.reason}."
        r.para(versions + ".")
        r.para(f"Python rhs (eq10_numpy of the tests, 2x2 inertia solved in closed form) vs "
               f"sloshdyn.equations_of_motion: largest difference {err_py:.1e}. " + nb_line)
        r.para(f"Timing: wall clock (time.perf_counter), median of {self.repeats} run(s) "
               f"(runs under {FAST_RUN} s at least {MIN_REPEATS_FAST} times); every solver is "
               "warmed up once first. atol = rtol * 1e-3 for every solver; output at the final "
               "time only. Error = max_i |y_i - y_ref,i| / max_i |y_ref,i| at the final time.")
        # warm-ups
        pr = self.problems[0]
        short = peers.Problem("w", "warm-up", pr.params, 2, pr.y0)
        rhs = peers.python_rhs(pr.params)
        for m in SLOSHDYN_METHODS:
            peers.run_sloshdyn(short, 1e-6, 1e-9, m)
        peers.run_solve_ivp(short, 1e-6, 1e-9, "RK45", rhs)
        peers.run_solve_ivp(short, 1e-6, 1e-9, "DOP853", rhs)
        peers.run_ode_dopri5(short, 1e-6, 1e-9, rhs)

    # ------------------------------------------------------------------ problems
    def problem(self, pr):
        r = self.report
        res = {"problem": pr}
        self.results[pr.key] = res
        r.heading(f"Problem {pr.title}")
        r.para(f"tau from 0 to {pr.t_end:.1f} ({pr.periods} forcing periods 2 pi/rho); "
               f"parameters s1={pr.params.s1}, mu1={pr.params.mu1}, kappa={pr.params.kappa}, "
               f"theta0=pi/4, gamma={pr.params.gamma}, beta={pr.params.beta}, "
               f"delta={pr.params.delta}, n={pr.params.n}, p={pr.params.p}, A={pr.params.A}, "
               f"rho={pr.params.rho}.")
        # reference
        log(f"problem {pr.key}: reference (sloshdyn dop853, rtol {REF_RTOL:g})")
        ref = peers.run_sloshdyn(pr, REF_RTOL, REF_RTOL * ATOL_FACTOR, "dop853").y_end
        ref13 = peers.run_sloshdyn(pr, 1e-13, 1e-13 * ATOL_FACTOR, "dop853").y_end
        res["ref"] = ref
        floor = rel_error(ref13, ref)
        lines = [f"Reference: sloshdyn dop853 at rtol {REF_RTOL:g}, y_ref = "
                 f"({', '.join(f'{v:.10g}' for v in ref)}); sloshdyn dop853 at rtol 1e-13 "
                 f"differs by {floor:.1e}"]
        if pr.key == "a":
            log(f"problem a: cross-check of the reference (solve_ivp DOP853, rtol {CROSS_RTOL:g})")
            t0 = time.perf_counter()
            cross = peers.run_solve_ivp(pr, CROSS_RTOL, CROSS_RTOL * ATOL_FACTOR, "DOP853",
                                        peers.python_rhs(pr.params)).y_end
            d = rel_error(cross, ref)
            floor = max(floor, d)
            lines.append(f"; solve_ivp DOP853 at rtol {CROSS_RTOL:g} (independent code, "
                         f"{time.perf_counter() - t0:.0f} s) differs by {d:.1e}")
        res["floor"] = floor
        r.para("".join(lines) + f". Errors below about {floor:.0e} are not resolved by the "
               "reference.")
        # sloshdyn ladder, interleaved with numbalsoda at the main tolerances
        ladder = {m: [] for m in SLOSHDYN_METHODS}
        runs = {}     # (solver, rtol) -> dict(time, run, error, times)
        for rtol in self.ladder:
            atol = rtol * ATOL_FACTOR
            fns = {m: (lambda m=m: peers.run_sloshdyn(pr, rtol, atol, m))
                   for m in SLOSHDYN_METHODS}
            if self.numba.available and rtol in self.tolerances:
                fns["numbalsoda dop853"] = (lambda: self.numba.integrate(
                    pr.params, pr.y0, pr.t_end, rtol, atol)[0])
            log(f"problem {pr.key}: sloshdyn {'/'.join(SLOSHDYN_METHODS)}"
                + (" + numbalsoda" if len(fns) > len(SLOSHDYN_METHODS) else "")
                + f" at rtol {rtol:.1e}")
            out = timed_interleaved(fns, self.repeats)
            for m in SLOSHDYN_METHODS:
                t, run, ts = out[m]
                e = rel_error(run.y_end, ref)
                ladder[m].append((rtol, t, run, e))
                runs[(f"sloshdyn {m}", rtol)] = {"time": t, "run": run, "error": e, "times": ts}
            if "numbalsoda dop853" in out:
                t, y_end, ts = out["numbalsoda dop853"]
                _, n_rhs = self.numba.integrate(pr.params, pr.y0, pr.t_end, rtol, atol, count=True)
                runs[("numbalsoda dop853", rtol)] = {
                    "time": t, "run": peers.Run(y_end, n_rhs, None), "times": ts,
                    "error": rel_error(y_end, ref)}
        res["ladder"], res["runs"] = ladder, runs
        saturated = min(e for m in ladder for (_, _, _, e) in ladder[m]) > SATURATED
        res["saturated"] = saturated
        # Python peers
        rhs = peers.python_rhs(pr.params)
        per_eval = {}
        skipped = []
        for i, rtol in enumerate(self.tolerances):
            if self.quick and i > 0:
                skipped.append(f"Python peers at rtol {rtol:g}: --quick runs them only at the "
                               "loosest tolerance")
                continue
            atol = rtol * ATOL_FACTOR
            reps = self.repeats if i == 0 else 1
            for name in PYTHON_PEERS:
                fam = FAMILY[name]
                expected = runs[(f"sloshdyn {fam}", rtol)]["run"].n_rhs
                if name in per_eval and per_eval[name] * expected > self.peer_cap:
                    skipped.append(f"{name} at rtol {rtol:g}: estimated "
                                   f"{per_eval[name] * expected:.0f} s > --peer-cap "
                                   f"{self.peer_cap:.0f} s")
                    continue
                if name == "solve_ivp RK45":
                    fn = lambda: peers.run_solve_ivp(pr, rtol, atol, "RK45", rhs)  # noqa: E731
                elif name == "solve_ivp DOP853":
                    fn = lambda: peers.run_solve_ivp(pr, rtol, atol, "DOP853", rhs)  # noqa: E731
                else:
                    fn = lambda: peers.run_ode_dopri5(pr, rtol, atol, rhs)  # noqa: E731
                est = (f", about {per_eval[name] * expected:.0f} s" if name in per_eval else "")
                log(f"problem {pr.key}: {name} at rtol {rtol:g} x{reps}{est}")
                t, run, ts = timed(fn, reps)
                if run.n_rhs:
                    per_eval.setdefault(name, t / run.n_rhs)
                runs[(name, rtol)] = {"time": t, "run": run, "times": ts,
                                      "error": rel_error(run.y_end, ref)}
        res["skipped"] = skipped
        self.problem_tables(pr, res)

    def solvers(self):
        s = [f"sloshdyn {m}" for m in SLOSHDYN_METHODS] + PYTHON_PEERS
        if self.numba.available:
            s.append("numbalsoda dop853")
        return s

    def problem_tables(self, pr, res):
        r = self.report
        runs, ladder, floor = res["runs"], res["ladder"], res["floor"]
        # 1. equal tolerance
        r.para(f"**{pr.key}: equal tolerance.** Speed-up = peer time / sloshdyn time with the "
               "same method family (rk45 for RK45 and dopri5, dop853 for DOP853 and "
               "numbalsoda), same rtol.")
        rows = []
        for rtol in self.tolerances:
            for name in self.solvers():
                x = runs.get((name, rtol))
                if x is None:
                    continue
                run = x["run"]
                sd = runs[(f"sloshdyn {FAMILY.get(name, name.split()[-1])}", rtol)]
                speed = None if name.startswith("sloshdyn") else x["time"] / sd["time"]
                steps = run.steps
                rows.append([f"{rtol:.0e}", name, fmt_t(x["time"]) + ("" if len(x["times"]) > 1
                                                                      else " (1 run)"),
                             fmt_n(run.n_rhs),
                             (fmt_n(steps) if run.steps_exact else f"~{steps:,}") if steps else "—",
                             f"{x['time'] / run.n_rhs * 1e9:.0f}" if run.n_rhs else "—",
                             fmt_e(x["error"]) + ("*" if x["error"] < 10 * floor else ""),
                             fmt_x(speed)])
        r.table(["rtol", "solver", "time", "rhs evals", "steps", "ns/rhs", "error",
                 "sloshdyn speed-up"], rows)
        notes = ["steps = attempted steps (accepted + rejected); solve_ivp's are (nfev-2)/stages "
                 "(~); numbalsoda does not report steps (it runs the same algorithm as sloshdyn "
                 "dop853: where rounding differences stay small, as in problem a, its rhs count "
                 "matches sloshdyn's to within a few evaluations)."]
        if any(x["error"] < 10 * floor for x in runs.values()):
            notes.append(f"* within 10x of the reference's own uncertainty ({floor:.0e}).")
        for s in res["skipped"]:
            notes.append(f"Not run: {s}.")
        r.para(" ".join(notes))
        # 2. sloshdyn ladder
        r.para(f"**{pr.key}: sloshdyn work-precision ladder** (interpolated below).")
        rows = []
        for i, rtol in enumerate(self.ladder):
            row = [f"{rtol:.1e}"]
            for m in SLOSHDYN_METHODS:
                _, t, run, e = ladder[m][i]
                row += [fmt_t(t), fmt_n(run.n_rhs), fmt_e(e)]
            rows.append(row)
        r.table(["rtol"] + [f"{m} {what}" for m in SLOSHDYN_METHODS
                            for what in ("time", "rhs", "error")], rows)
        # 3. equal accuracy
        points = {m: [(e, t) for (_, t, _, e) in ladder[m]] for m in ladder}
        res["equal_accuracy"] = {}
        if res["saturated"]:
            emin = min(e for m in ladder for (_, _, _, e) in ladder[m])
            lyap = self.lyapunov(pr)
            r.para(f"**{pr.key}: equal accuracy is not meaningful here.** Every run's final-time "
                   f"error is at least {emin:.1e} (relative) even at rtol {self.ladder[-1]:.0e}: "
                   "the errors saturate at the size of the state. The impacting motion amplifies "
                   "any perturbation (rounding included) exponentially" + lyap + ", so the final "
                   "state after this many periods is not determined by the tolerance. The "
                   "targets for this problem are therefore judged at equal tolerance (same work "
                   "criterion for every solver).")
            return
        r.para(f"**{pr.key}: equal accuracy.** For each peer run, the sloshdyn time needed to "
               "reach the peer's final-time error, interpolated (log-log) on sloshdyn's ladder "
               "(Pareto front of time vs error). ≥: the peer is less accurate than sloshdyn's "
               "loosest run, the speed-up is at least this; ≤: more accurate than sloshdyn's "
               "tightest run, at most this. =tol: the peer's error is within 10x of the "
               f"reference's own uncertainty ({floor:.0e}), so accuracies cannot be told apart: "
               "the sloshdyn time at the same rtol is used instead.")
        rows = []
        for rtol in self.tolerances:
            for name in self.solvers()[len(SLOSHDYN_METHODS):]:
                x = runs.get((name, rtol))
                if x is None:
                    continue
                unresolved = x["error"] < 10 * floor
                cells = [f"{rtol:.0e}", name, fmt_e(x["error"]) + ("*" if unresolved else ""),
                         fmt_t(x["time"])]
                best = None
                ea = {}
                for m in SLOSHDYN_METHODS:
                    if unresolved:
                        t, flag = runs[(f"sloshdyn {m}", rtol)]["time"], "=tol "
                    else:
                        t, flag = time_at_error(points[m], x["error"])
                    sp = x["time"] / t
                    ea[m] = (sp, flag)
                    cells += [fmt_t(t), fmt_x(sp, flag)]
                    if best is None or sp > best[0]:
                        best = (sp, flag)
                res["equal_accuracy"][(name, rtol)] = ea
                rows.append(cells + [fmt_x(*best)])
        r.table(["rtol", "peer", "peer error", "peer time"]
                + [h for m in SLOSHDYN_METHODS for h in (f"sloshdyn {m} time", "speed-up")]
                + ["best"], rows)

    def lyapunov(self, pr):
        fn = getattr(sloshdyn, "lyapunov_exponent", None)
        if fn is None:
            return ""
        try:
            n = min(pr.periods, 400)
            lam = fn(pr.params, pr.y0, lyapunov=sloshdyn.Lyapunov(transient_periods=0,
                                                                  n_periods=n)).exponent
        except Exception as exc:   # noqa: BLE001 - diagnostic only
            return f" (sloshdyn.lyapunov_exponent failed: {exc})"
        if lam <= 0:
            return f" (largest Lyapunov exponent from sloshdyn.lyapunov_exponent: {lam:.3g})"
        return (f" (largest Lyapunov exponent {lam:.3g} per unit tau from "
                f"sloshdyn.lyapunov_exponent over {n} periods: over tau = {pr.t_end:.0f} a "
                f"perturbation grows by about 10^{lam * pr.t_end / math.log(10):.0f})")

    # ------------------------------------------------------------------ cost per rhs
    def rhs_cost(self):
        r = self.report
        r.heading("Cost per right-hand-side evaluation (problem a)")
        pa = self.problems[0]
        res = self.results["a"]
        p = pa.params
        y = np.array([0.01, 0.002, 0.01, -0.003])
        log("right-hand side alone: Fortran driver, Python closure, numba")
        c_f, why = peers.fortran_rhs_cost(p, 2_000_000 if self.quick else 10_000_000)
        rhs = peers.python_rhs(p)
        c_py = min(timeit.repeat(lambda: rhs(0.3, y), number=20000, repeat=5)) / 20000
        c_nb = None
        if self.numba.available:
            d = self.numba.data(p)
            n = 2_000_000 if self.quick else 10_000_000
            self.numba.time_eom(1000, 0.0, y, d)
            c_nb = min(timed(lambda: self.numba.time_eom(n, 0.0, y, d), 3)[2]) / n
        c_eom = min(timeit.repeat(lambda: sloshdyn.equations_of_motion(p, 0.3, y), number=5000,
                                  repeat=5)) / 5000
        self.c_eom = c_eom
        rows = [["Fortran equations_of_motion (core, no Python)",
                 f"{c_f * 1e9:.0f} ns" if c_f else f"n/a ({why})"],
                ["numba eom (same formula, njit loop)", f"{c_nb * 1e9:.0f} ns" if c_nb else
                 "n/a (numba missing)"],
                ["Python rhs closure (the Python peers' rhs)", f"{c_py * 1e9:.0f} ns"],
                ["sloshdyn.equations_of_motion from Python (rhs + Jacobian + call)",
                 f"{c_eom * 1e9:.0f} ns"]]
        r.para("The right-hand side alone, per call (best of repeats, the state drifting by "
               "1e-9 dy/dtau per call so nothing is reused):")
        r.table(["right-hand side", "per call"], rows)
        # per solver at each tolerance: total time / n_rhs, and the share outside the rhs
        alone = {**{f"sloshdyn {m}": c_f for m in SLOSHDYN_METHODS}, "numbalsoda dop853": c_nb,
                 **{n: c_py for n in PYTHON_PEERS}}
        rows = []
        for rtol in self.tolerances:
            base = {}
            for name in self.solvers():
                x = res["runs"].get((name, rtol))
                if x is None or not x["run"].n_rhs:
                    continue
                per = x["time"] / x["run"].n_rhs
                base.setdefault(name, per)
                fam = "sloshdyn " + FAMILY.get(name, name.split()[-1])
                sd = res["runs"][(fam, rtol)]
                sd_per = sd["time"] / sd["run"].n_rhs
                c = alone.get(name)
                outside = f"{max(0.0, 1 - x['run'].n_rhs * c / x['time']) * 100:.0f}%" if c else "—"
                rows.append([f"{rtol:.0e}", name, fmt_t(x["time"]), fmt_n(x["run"].n_rhs),
                             f"{per * 1e9:.0f}", outside,
                             "—" if name.startswith("sloshdyn") else fmt_x(per / sd_per)])
        r.para("Whole integration, problem (a): time / rhs evaluations, the share of the time "
               "spent outside the right-hand side (1 - n_rhs x cost of the rhs alone from the "
               "table above: the Fortran driver for sloshdyn, the numba loop for numbalsoda, the "
               "Python closure for the Python peers), and the per-evaluation cost ratio peer / "
               "sloshdyn (same method family).")
        r.table(["rtol", "solver", "time", "rhs evals", "ns/rhs", "outside rhs",
                 "ns/rhs ratio"], rows)
        r.para("Method: the core's rhs is timed by benchmarks/rhs_cost.f90, a Fortran loop "
               "calling sloshdyn_motion's equations_of_motion (compiled with -O3 against the "
               "meson build's modules and libsloshdyn.a, the code the integrator calls through "
               "its type-bound rhs). sloshdyn.equations_of_motion from Python cannot measure it: "
               "that call also builds the model from the flat parameter arrays, evaluates the "
               "Jacobian and crosses f2py, about "
               f"{c_eom / c_f:.0f}x the rhs itself." if c_f else
               "Method: the Fortran rhs could not be timed here (" + str(why) + "); the share "
               "outside the rhs is then not given for sloshdyn.")

    # ------------------------------------------------------------------ sweep
    def sweep(self):
        r = self.report
        p = peers.fig14_parameters()
        if self.quick:
            n, n_small, steady = 8, 4, sloshdyn.Steady(transient_periods=40, settle_tol=0,
                                                       window_periods=16)
        else:
            n, n_small, steady = 200, 50, sloshdyn.Steady(transient_periods=400, settle_tol=0,
                                                          window_periods=100)
        r.heading(f"Frequency sweep: {n} independent values of rho in [0.49, 0.53], threads = 1 vs 2")
        values = np.linspace(0.49, 0.53, n)
        reps = self.repeats
        log(f"sweep: {n} points x {reps}, threads 1 and 2")
        rss0 = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss

        cpu = {1: [], 2: []}   # process CPU time (all threads) per run

        def run(threads):
            c0 = sum(resource.getrusage(resource.RUSAGE_SELF)[:2])
            result = sloshdyn.frequency_sweep(p, values, steady=steady, start_from="y0",
                                              threads=threads)
            cpu[threads].append(sum(resource.getrusage(resource.RUSAGE_SELF)[:2]) - c0)
            return result
        t1, s1, ts1 = timed(lambda: run(1), reps)
        t2, s2, ts2 = timed(lambda: run(2), reps)
        c1, c2 = statistics.median(cpu[1]), statistics.median(cpu[2])
        rss1 = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
        identical = all(list(s1.column(c)) == list(s2.column(c))
                        for c in ("max_x1", "max_x2", "max_u1", "max_u2", "spread"))
        speed = t1 / t2
        r.para(f"sloshdyn.frequency_sweep(p_fig14, values, steady=Steady(transient_periods="
               f"{steady.transient_periods:g}, settle_tol=0, window_periods="
               f"{steady.window_periods}), start_from='y0', threads=...), default integration, "
               f"{steady.transient_periods + steady.window_periods:g} periods per point, every "
               f"point from rest (independent points; a sweep that carries the state runs on one "
               f"thread and refuses more); median of {reps} run(s). Speed-ups are reported only "
               f"between runs whose results are identical: the 1- and 2-thread results are "
               f"{'bit for bit identical' if identical else 'NOT identical'}.")
        r.table(["run", "time", "speed-up vs 1 thread", "CPU time (all threads)"], [
            ["threads=1", fmt_t(t1), "1x", fmt_t(c1)],
            ["threads=2 (OpenMP, points shared out one at a time)", fmt_t(t2),
             fmt_x(speed) if identical else "not comparable", fmt_t(c2)],
        ])
        r.para(f"CPU time of the same work on 2 threads / on 1 thread: {c2 / c1:.3f}. Shared "
               "cache lines, allocator locks or other contention between the threads would "
               "show here as extra CPU time, whatever the load of the machine; the wall-clock "
               "speed-up also needs two otherwise idle cores.")
        r.para(f"ru_maxrss of this process before/after the timed sweeps: {rss0 / 1024:.1f} / "
               f"{rss1 / 1024:.1f} MiB (a process-lifetime peak, hence the separate processes "
               "below).")
        self.verdicts.append(("2-thread sweep >= 1.85x faster than 1 thread, identical results",
                              f"{speed:.2f}x" if identical else "results differ",
                              identical and speed >= 1.85, f"{speed / 1.85:.2f} of target"))
        # memory in fresh processes
        rows = []
        source = "peak RSS"
        log("sweep memory: fresh processes")
        for threads in (1, 2):
            for npts in (n_small, n):
                cmd = [sys.executable, str(HERE / "memprobe.py"), str(npts), str(threads),
                       str(steady.transient_periods), str(steady.window_periods)]
                res = subprocess.run(cmd, capture_output=True, text=True, cwd=str(HERE))
                if res.returncode != 0:
                    rows.append([str(threads), str(npts), "failed: " + res.stderr.strip()[-200:],
                                 "", "", ""])
                    continue
                m = json.loads(res.stdout.strip().splitlines()[-1])
                source = m["source"]
                rows.append([str(threads), str(npts), f"{m['peak_before_kib'] / 1024:.1f} MiB",
                             f"{m['peak_after_kib'] / 1024:.1f} MiB",
                             f"{(m['peak_after_kib'] - m['peak_before_kib']) / 1024:.2f} MiB",
                             f"{m['tracemalloc_peak_bytes'] / 1024:.0f} KiB"])
        r.para(f"Peak memory, each sweep in a fresh process (benchmarks/memprobe.py): peak "
               f"resident set ({source}; ru_maxrss would carry this process's peak over to the "
               "child) after import and a 2-point warm-up, after the sweep, the growth, and the "
               "tracemalloc peak of Python-side allocations during the sweep.")
        r.table(["threads", "points", "peak before", "peak after", "growth",
                 "Python peak (tracemalloc)"], rows)

    # ------------------------------------------------------------------ Fig 12
    def fig12(self):
        r = self.report
        r.heading("Fig 12 continuation: frequency_response(p_fig12, (0.49, 0.53))")
        p = peers.fig14_parameters(A=0.00075)
        sloshdyn.frequency_response(p, (0.49, 0.53))
        reps = max(self.repeats, MIN_REPEATS_FAST)
        t, resp, ts = timed(lambda: sloshdyn.frequency_response(p, (0.49, 0.53)), reps)
        hopf = [round(s.rho, 5) for s in resp.special_points if s.kind == "hopf"]
        folds = [round(s.rho, 5) for s in resp.special_points if s.kind == "fold"]
        bridge_t = None
        try:   # the Fortran call alone, without building the Python result (private API)
            from sloshdyn import asymptotics as _as
            s = _as.Continuation()
            args = (*p.array(), 1, 1, 0.49, 0.53, s.array(), s.max_points, 200)
            bridge_t = timed(lambda: _as._bridge.frequency_response(*args), reps)[0]
        except Exception:   # noqa: BLE001 - diagnostic only
            pass
        r.table(["quantity", "value"], [
            ["time (median of %d)" % reps, fmt_t(t)],
            ["fastest / slowest run", f"{fmt_t(min(ts))} / {fmt_t(max(ts))}"],
            ["of which the Fortran call (bridge alone)", fmt_t(bridge_t)],
            ["points on the branches", str(len(resp.table["a1"]))],
            ["Hopf points (rho)", ", ".join(map(str, hopf)) or "none"],
            ["folds (rho)", ", ".join(map(str, folds)) or "none"],
            ["target", f"<= {FIG12_TARGET * 1e3:.0f} ms"],
        ])
        self.verdicts.append((f"Fig 12 branch <= {FIG12_TARGET * 1e3:.0f} ms", fmt_t(t),
                              t <= FIG12_TARGET, f"{t / FIG12_TARGET:.2f} of the budget"))

    # ------------------------------------------------------------------ stability chart
    def chart(self):
        """The default stability chart of issue 28: stability_chart(FIG12, (0.49, 0.53),
        (0.0, 0.002)) with threads = 1 and 2, interleaved."""
        r = self.report
        r.heading("Stability chart: stability_chart(p_fig12, (0.49, 0.53), (0.0, 0.002))")
        p = peers.fig14_parameters(A=0.00075)
        def on(threads):
            return lambda: sloshdyn.stability_chart(p, (0.49, 0.53), (0.0, 0.002), threads=threads)

        one, two = on(1), on(2)
        if not self.quick:   # --quick: the first runs are timed (the smoke test stays short)
            one()
            two()
        reps = self.repeats if self.quick else max(self.repeats, MIN_REPEATS_FAST)
        got = timed_interleaved({"1": one, "2": two}, reps)
        (t1, chart, ts1), (t2, _, ts2) = got["1"], got["2"]
        r.table(["run", f"time (median of {reps})", "fastest / slowest", "speed-up"], [
            ["threads=1", fmt_t(t1), f"{fmt_t(min(ts1))} / {fmt_t(max(ts1))}", "1x"],
            ["threads=2", fmt_t(t2), f"{fmt_t(min(ts2))} / {fmt_t(max(ts2))}", fmt_x(t1 / t2)],
        ])
        r.para(f"{len(chart.curves)} curves, {len(chart.grid['rho'])} grid cells; target < "
               f"{CHART_TARGET:g} s.")
        t = min(t1, t2)
        self.verdicts.append((f"default stability chart < {CHART_TARGET:g} s", fmt_t(t),
                              t < CHART_TARGET, f"{t / CHART_TARGET:.2f} of the budget"))

    # ------------------------------------------------------------------ fragility study
    def fragility(self):
        """The fragility study of issue 28: 44 synthetic records of 20-100 s (dt 0.005-0.02 s,
        seeded; peers.synthetic_records) x 20 intensities, a 10 m tank on 2 Hz supports with
        1 m freeboard, on 1 and 2 workers of the engine's default kind (threads) at its default
        task size. One run each (a full study takes about half a minute); --quick: 2 short
        records x 2 intensities, 1 worker."""
        import shutil
        import tempfile
        r = self.report
        n_records, n_intensities = (2, 2) if self.quick else (44, 20)
        r.heading(f"Fragility study: {n_records} records x {n_intensities} intensities "
                  "(sloshdyn.fragility_study)")
        records = peers.synthetic_records(n_records, quick=self.quick)
        tank = peers.fragility_tank()
        intensities = np.linspace(0.05, 0.5, n_intensities)     # Sa(T_sloshing, 0.5 %) [g]
        kind = sloshdyn.studies.WORKER_KIND
        warm = tempfile.mkdtemp()          # Dask, xarray and Zarr imported before the timing
        sloshdyn.fragility_study(tank, peers.synthetic_records(2, quick=True), intensities[:2],
                                 os.path.join(warm, "f.zarr"), workers=1, progress=False)
        shutil.rmtree(warm)
        rows, results = [], {}
        for workers in ((1,) if self.quick else (1, 2)):
            where = tempfile.mkdtemp()
            log(f"fragility study on {workers} worker(s)")
            children = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu = time.process_time()
            t = time.perf_counter()
            ds = sloshdyn.fragility_study(tank, records, intensities,
                                          os.path.join(where, "f.zarr"), workers=workers,
                                          progress=False)
            wall = time.perf_counter() - t
            cpu = time.process_time() - cpu
            after = resource.getrusage(resource.RUSAGE_CHILDREN)    # the closed workers'
            worker_cpu = (after.ru_utime + after.ru_stime
                          - children.ru_utime - children.ru_stime)
            shutil.rmtree(where)
            results[workers] = (wall, ds)
            rows.append([f"{workers} worker(s), {kind}",
                         fmt_t(wall),
                         f"{ds.attrs['compute_seconds']:.1f} s",
                         f"{cpu:.2f} s", f"{worker_cpu:.1f} s" if kind == "processes" else "-",
                         fmt_x(results[1][0] / wall)])
        r.table(["run", "wall time", "task compute time (summed)", "CPU of this process",
                 "CPU of the worker processes", "speed-up"], rows)
        samples = sum(g.acceleration.size for g in records)
        durations = [g.dt * (g.acceleration.size - 1) for g in records]
        wall1, ds1 = results[1]
        r.para(f"{n_records * n_intensities} runs; records {min(durations):.0f}-"
               f"{max(durations):.0f} s, {samples} samples in all; roof reached in "
               f"{int((ds1.roof_impact == 1).sum())} runs; lognormal fit: median "
               f"{float(ds1.fragility_median):.3g} g, dispersion "
               f"{float(ds1.fragility_dispersion):.3g}.")
        if 2 in results:
            wall2, ds2 = results[2]
            same = all(np.array_equal(ds1[k].values, ds2[k].values, equal_nan=True)
                       for k in ds1.data_vars if ds1[k].dtype.kind == "f")
            r.para(f"1 and 2 workers give identical results: {same}.")
            self.verdicts.append((f"fragility {n_records} x {n_intensities} < "
                                  f"{FRAGILITY_TARGET:g} s (2 workers)", fmt_t(wall2),
                                  wall2 < FRAGILITY_TARGET,
                                  f"{wall2 / FRAGILITY_TARGET:.2f} of the budget"))
            self.verdicts.append((f"fragility: 2 workers >= {SCALING_TARGET:g}x 1 worker",
                                  fmt_x(wall1 / wall2), wall1 / wall2 >= SCALING_TARGET,
                                  f"{wall1 / wall2 / SCALING_TARGET:.2f} of target"))

    # ------------------------------------------------------------------ call overhead
    def call_overhead(self):
        r = self.report
        r.heading("Overhead of one Python call into the core")
        p = peers.fig14_parameters()
        y = np.array([0.01, 0.0, 0.01, 0.0])
        number = 2000 if self.quick else 20000

        def per_call(fn):
            return statistics.median(timeit.repeat(fn, number=number, repeat=5)) / number

        rows = [["sloshdyn.equations_of_motion(p, 0.0, y)",
                 fmt_t(per_call(lambda: sloshdyn.equations_of_motion(p, 0.0, y)))],
                ["sloshdyn.linear_modes(p)",
                 fmt_t(per_call(lambda: sloshdyn.linear_modes(p)))],
                ["  of which p.array() (parameters to the flat bridge arrays)",
                 fmt_t(per_call(p.array))]]
        try:
            from sloshdyn import model as _model
            rpar, ipar = p.array()
            rows.append(["  bridge equations_of_motion alone (f2py call, no Python wrapper)",
                         fmt_t(per_call(lambda: _model._bridge.equations_of_motion(
                             rpar, ipar, 0.0, y)))])
        except Exception:   # noqa: BLE001 - diagnostic only
            pass
        r.para(f"Median over 5 batches of {number} calls, per call.")
        r.table(["call", "per call"], rows)

    # ------------------------------------------------------------------ targets
    def targets(self):
        r = self.report
        others, self.verdicts = self.verdicts, []
        for name, target in TARGETS.items():
            if name == "numbalsoda dop853" and not self.numba.available:
                self.verdicts.append((f"no slower than {name} (sloshdyn dop853)", "—", None,
                                      "peer skipped: " + self.numba.reason))
                continue
            for key, res in self.results.items():
                fam = FAMILY[name]
                basis = "equal tolerance, errors saturate" if res["saturated"] else "equal accuracy"
                entries = {}
                for m in SLOSHDYN_METHODS:
                    for rtol in self.tolerances:
                        x = res["runs"].get((name, rtol))
                        if x is None:
                            continue
                        if res["saturated"]:
                            sp = x["time"] / res["runs"][(f"sloshdyn {m}", rtol)]["time"]
                            entries.setdefault(m, []).append((rtol, sp, ""))
                        else:
                            sp, flag = res["equal_accuracy"][(name, rtol)][m]
                            entries.setdefault(m, []).append((rtol, sp, flag))
                if not entries:
                    continue
                # same method family (the strict comparison), then the faster sloshdyn method
                same = entries[fam]
                worst = min(sp for _, sp, _ in same)
                if any(flag.startswith("=tol") for m in entries for _, _, flag in entries[m]):
                    basis += " (=tol: errors at the reference floor, equal tolerance used)"
                where = ", ".join(f"{rtol:.0e}: {fmt_x(sp, flag)}" for rtol, sp, flag in same)
                if name == "numbalsoda dop853":
                    label = f"({key}) sloshdyn dop853 no slower than numbalsoda dop853, every rtol"
                else:
                    label = f"({key}) >= {target:.0f}x faster than {name}, sloshdyn {fam}"
                self.verdicts.append((label, fmt_x(worst), worst >= target,
                                      f"worst of {where}; {basis}; {worst / target:.2f} of target"))
                if name != "numbalsoda dop853":
                    per_rtol = {}
                    for m in entries:
                        for rtol, sp, flag in entries[m]:
                            if rtol not in per_rtol or sp > per_rtol[rtol][0]:
                                per_rtol[rtol] = (sp, flag)
                    best = min(sp for sp, _ in per_rtol.values())
                    where = ", ".join(f"{rtol:.0e}: {fmt_x(sp, flag)}"
                                      for rtol, (sp, flag) in per_rtol.items())
                    self.verdicts.append((f"({key}) >= {target:.0f}x faster than {name}, faster "
                                          "sloshdyn method", fmt_x(best), best >= target,
                                          f"worst of {where}; {basis}; "
                                          f"{best / target:.2f} of target"))
        self.default_path_targets()
        r.heading("Targets")
        if self.quick:
            r.para("--quick: the sizes are far too small for these verdicts to mean anything "
                   "(fixed per-call costs dominate 20-period runs); they only show that the "
                   "script runs. Use the full run.")
        order = self.verdicts + others
        r.table(["target", "measured", "verdict", "note"],
                [[t, m, "SKIP" if ok is None else ("PASS" if ok else "MISS"), note]
                 for t, m, ok, note in order])

    def default_path_targets(self):
        """The default path (method not given: 'auto') against the peers of DEFAULT_TARGETS at
        every main rtol, at equal accuracy (equal tolerance where errors saturate)."""
        for name, target in DEFAULT_TARGETS.items():
            if name == "numbalsoda dop853" and not self.numba.available:
                self.verdicts.append((f"default path >= {target}x {name}", "—", None,
                                      "peer skipped: " + self.numba.reason))
                continue
            for key, res in self.results.items():
                got = []
                for rtol in self.tolerances:
                    x = res["runs"].get((name, rtol))
                    if x is None:
                        continue
                    if res["saturated"]:
                        sp, flag = x["time"] / res["runs"][("sloshdyn auto", rtol)]["time"], ""
                    else:
                        sp, flag = res["equal_accuracy"][(name, rtol)]["auto"]
                    got.append((rtol, sp, flag))
                if not got:
                    continue
                worst = min(sp for _, sp, _ in got)
                basis = "equal tolerance, errors saturate" if res["saturated"] else "equal accuracy"
                where = ", ".join(f"{rtol:.0e}: {fmt_x(sp, flag)}" for rtol, sp, flag in got)
                self.verdicts.append((f"({key}) default path (method 'auto') >= {target:g}x "
                                      f"{name}", fmt_x(worst), worst >= target,
                                      f"worst of {where}; {basis}; {worst / target:.2f} of target"))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true",
                    help="tiny sizes (20 periods, 2 tolerances, 8 sweep points, 1 repeat): a "
                         "smoke test that finishes in well under a minute")
    ap.add_argument("--repeats", type=int, default=None,
                    help="timed runs per measurement, median reported (default 3; 1 with "
                         "--quick); the Python peers run once below the loosest tolerance")
    ap.add_argument("--out", type=Path, default=None, help="also write the tables as Markdown")
    ap.add_argument("--peer-cap", type=float, default=240.0,
                    help="skip a Python-peer run whose estimated time exceeds this (seconds; "
                         "default 240)")
    args = ap.parse_args(argv)
    start = time.perf_counter()
    b = Bench(args)
    print(f"# sloshdyn benchmark ({'quick' if args.quick else 'full'})")
    b.setup()
    for pr in b.problems:
        b.problem(pr)
    b.rhs_cost()
    b.sweep()
    b.fig12()
    b.chart()
    b.fragility()
    b.call_overhead()
    b.targets()
    total = time.perf_counter() - start
    b.report.para(f"Total run time: {total:.0f} s ({'--quick' if args.quick else 'full'}); load "
                  f"average at the end {' '.join(f'{x:.2f}' for x in os.getloadavg())}.")
    if args.out:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text(f"# sloshdyn benchmark ({'quick' if args.quick else 'full'})\n\n"
                            + b.report.markdown())
        print(f"Markdown written to {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
