"""Runs fuzzing cases of the Python API in child processes, so that a process death (LAPACK's
XERBLA, a segfault, an abort) or a hang is caught and blamed on its case.

A case is (label, function name, args, kwargs); the names "P", "TANK", "GROUND" among the args
stand for valid Parameters (Fig 12), a valid Tank and valid harmonic ground motion, built in
the child (and "RECORD" a recorded ground motion, "STORE" a new store path, "NO_CLUSTER" a
Dask client that stops a study whose inputs passed every check); a dict {"__class__": NAME,
**fields} stands for the settings object sloshdyn.NAME(**fields), built in the child so that
its own checks are fuzzed too. The parent pickles a batch of cases to the child's standard input; the child prints
"CASE i" before and "DONE i <outcome>" after each one. A child that dies or stops answering is
restarted after the case it was running, which is reported as 'death' or 'hang'.

Outcomes: 'finite' (a result whose numbers are all finite), 'sloshdyn <class>: message',
'nonfinite' (a result holding NaN or infinity), 'generic <type>: message' (any other exception),
'death <code>: stderr tail', 'hang'."""

from __future__ import annotations

import dataclasses
import json
import math
import os
import pickle
import subprocess
import sys
import time

#: seconds a case may take before it counts as a hang (the bound the suite states)
CASE_SECONDS = 20.0
#: seconds a child may take to import sloshdyn before its first case (generous: a loaded machine)
START_SECONDS = 300.0


class _NoCluster:
    """A Dask client that refuses the first thing asked of it: a study whose inputs pass every
    check stops there (InputError), before any store or computation."""

    def __getattr__(self, name):
        import sloshdyn
        raise sloshdyn.InputError(f"fuzzing: the study's inputs passed (client.{name})")


SENTINELS = ("P", "TANK", "GROUND", "RECORD", "STORE", "NO_CLUSTER")


def _valid(name):
    import tempfile

    import sloshdyn
    from sloshdyn.figures import FIG12
    if name == "P":
        return FIG12
    if name == "RECORD":
        return sloshdyn.GroundMotion(dt=0.01, acceleration=[0.0, 0.5, -0.5, 0.2, 0.0],
                                      units="m/s^2")
    if name == "STORE":
        return os.path.join(tempfile.mkdtemp(prefix="sloshdyn-fuzz-"), "study.zarr")
    if name == "NO_CLUSTER":
        return _NoCluster()
    if name == "TANK":
        return sloshdyn.Tank(radius=5, liquid_depth=6, freeboard=1, liquid_density=1000,
                             tank_mass=5e4, support_frequency=2)
    if name == "GROUND":
        return sloshdyn.GroundMotion.harmonic(0.05, 0.3)
    raise KeyError(name)


def _resolve(value):
    if isinstance(value, str) and value in SENTINELS:
        return _valid(value)
    if isinstance(value, dict) and "__class__" in value:
        import sloshdyn
        fields = {k: v for k, v in value.items() if k != "__class__"}
        return getattr(sloshdyn, value["__class__"])(**fields)
    if isinstance(value, list):
        return [_resolve(v) for v in value]
    return value


def _numbers(result):
    """Every number of a result (arrays, dataclasses, dicts, sequences)."""
    import numpy as np
    if isinstance(result, (bool, np.bool_, str, bytes)) or result is None:
        return
    if isinstance(result, (int, float, complex, np.number)):
        yield complex(result)
    elif isinstance(result, np.ndarray):
        if result.dtype.kind in "iufc":
            yield from (complex(x) for x in result.ravel())
    elif dataclasses.is_dataclass(result):
        for f in dataclasses.fields(result):
            if f.name not in MAY_BE_NAN.get(type(result).__name__, ()):
                yield from _numbers(getattr(result, f.name))
    elif isinstance(result, dict):
        for value in result.values():
            yield from _numbers(value)
    elif isinstance(result, (list, tuple)):
        for value in result:
            yield from _numbers(value)


#: result fields that are NaN by definition (documented), not by failure
MAY_BE_NAN = {"Simulation": ("u",), "SteadyState": ("max_u1", "max_u2", "poincare"),
              "DesignCodes": ("table",),   # NaN where a design code gives no value
              "Curve": ("l1",)}            # the Lyapunov coefficient exists on Hopf curves


def _finite(result):
    return all(math.isfinite(z.real) and math.isfinite(z.imag) for z in _numbers(result))


def _call(function, args, kwargs):
    import sloshdyn
    if function in ("os._exit", "time.sleep"):   # the harness's own test: a death, a hang
        return getattr(os if function == "os._exit" else time, function.split(".")[1])(*args)
    if "." in function:            # Class.method on a valid object: "TANK.design_codes"
        owner, method = function.split(".")
        return getattr(_valid(owner), method)(*[_resolve(a) for a in args],
                                              **{k: _resolve(v) for k, v in kwargs.items()})
    return getattr(sloshdyn, function)(*[_resolve(a) for a in args],
                                       **{k: _resolve(v) for k, v in kwargs.items()})


def child():
    """The child: run each case of the pickled batch on standard input, report on stdout."""
    import warnings
    warnings.simplefilter("ignore")
    import sloshdyn
    cases = pickle.load(sys.stdin.buffer)
    out = sys.stdout
    for i, (label, function, args, kwargs) in enumerate(cases):
        print(f"CASE {i}", file=out, flush=True)
        try:
            result = _call(function, args, kwargs)
            outcome = "finite" if _finite(result) else "nonfinite"
        except sloshdyn.SloshdynError as exc:
            outcome = f"sloshdyn {type(exc).__name__}: {exc}"
        except Exception as exc:  # the invariant's violation, reported to the parent
            outcome = f"generic {type(exc).__name__}: {exc}"
        print(f"DONE {i} {json.dumps(outcome)}", file=out, flush=True)


def run_cases(cases, case_seconds=CASE_SECONDS):
    """{label: outcome} of every case, each run in a child process (batched)."""
    outcomes = {}
    todo = list(cases)
    env = {**os.environ, "MPLBACKEND": "Agg", "OMP_NUM_THREADS": "1"}
    while todo:
        proc = subprocess.Popen([sys.executable, "-c",
                                 "import fuzz_runner; fuzz_runner.child()"],
                                stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, env=env,
                                cwd=os.path.dirname(os.path.abspath(__file__)))
        proc.stdin.write(pickle.dumps(todo))
        proc.stdin.close()
        os.set_blocking(proc.stdout.fileno(), False)
        running, buffer = None, b""
        deadline = time.monotonic() + START_SECONDS + case_seconds   # the import, then each case
        finished = 0
        while True:
            chunk = proc.stdout.read()
            if chunk:
                buffer += chunk
                *lines, buffer = buffer.split(b"\n")
                for line in lines:
                    word, index, *rest = line.decode().split(" ", 2)
                    if word == "CASE":
                        running = int(index)
                        deadline = time.monotonic() + case_seconds
                    else:
                        outcomes[todo[int(index)][0]] = json.loads(rest[0])
                        finished = int(index) + 1
                        running = None
            if proc.poll() is not None and not chunk:
                break
            if time.monotonic() > deadline:
                proc.kill()
                proc.wait()
                break
            time.sleep(0.01)
        stderr = proc.stderr.read().decode(errors="replace")
        if running is None and finished == len(todo):
            todo = []
            continue
        if running is None:            # died or hung before the first case (the import)
            raise RuntimeError(f"fuzz child failed to start: {stderr[-2000:]}")
        label = todo[running][0]
        if proc.returncode == -9 and time.monotonic() > deadline:
            outcomes[label] = "hang"
        else:
            outcomes[label] = f"death {proc.returncode}: {stderr.strip()[-300:]}"
        todo = todo[running + 1:]
    return outcomes


if __name__ == "__main__":
    child()
