"""Fuzzing the record readers of both front doors (issue 22): files that are FIFOs, devices,
directories, huge (sparse, past the 1 GiB limit), with odd headers (tabs, either order, column
names, junk), binary bytes, names ending in blanks or in Unicode.

The invariant: GroundMotion.from_file and the executable's &ground_motion either read the file
-- then the samples and the step are those a plain Python parser finds in it (an independent
reading), dt >= 1e-6 s -- or refuse it with a sloshdyn error (InputError or FileError; exit 3)
whose message names the file and holds no control character; never a hang, a memory blow-up,
another exception or a traceback. Python cases run in a child process with a memory limit and
a timeout, so a hang or a read of /dev/zero fails the test instead of the machine."""

import json
import math
import os
import re
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

LONG = int(os.environ.get("SLOSHDYN_FUZZ_EXAMPLES", "0"))
FUZZ = settings(max_examples=3 if not LONG else LONG, deadline=None, derandomize=not LONG,
                phases=[Phase.explicit, Phase.generate], suppress_health_check=list(HealthCheck))
G = 9.80665                      # standard gravity: AT2 values are in g
CHILD_SECONDS = 120              # a guard: the whole batch takes a few seconds

# ---- strategies ------------------------------------------------------------------------------

values = st.lists(st.floats(-2.0, 2.0, allow_nan=False).map(lambda x: round(x, 6)),
                  min_size=2, max_size=12)
steps = st.sampled_from([0.005, 0.01, 0.02, 1e-12, 1e-300, 2e-6])
blanks = st.sampled_from([" ", "  ", "\t", " \t ", ""])


@st.composite
def at2_files(draw):
    """AT2 text: the 4th header line in either form and order, any blanks or tabs, sometimes
    a wrong NPTS or junk in it; values several per line."""
    a, dt = draw(values), draw(steps)
    b1, b2 = draw(blanks), draw(blanks)
    npts = len(a) + draw(st.sampled_from([0, 0, 0, 1, -1]))
    forms = [f"NPTS={b1}{npts},{b2}DT={b1}{dt!r} SEC", f"DT{b1}={b2}{dt!r},{b1}NPTS{b2}={npts}",
             f"npts ={b1}{npts} , dt = {dt!r}", f"{b1}{npts}{b2} {dt!r}   NPTS, DT",
             f"NPTS= {npts}, DT= \x1b[31m{dt!r}"]
    fourth = draw(st.sampled_from(forms))
    per_line = draw(st.integers(1, 5))
    lines = [" ".join(f"{x:.6E}" for x in a[k:k + per_line]) for k in range(0, len(a), per_line)]
    text = "PEER NGA\nquake\nACCELERATION IN UNITS OF G\n" + fourth + "\n" + "\n".join(lines)
    return "at2", text.encode(), a, dt


@st.composite
def column_files(draw):
    """Two columns: optional column-name line, comments, blank lines, any separator."""
    a, dt = draw(values), draw(steps)
    sep = draw(st.sampled_from([",", ";", " ", "\t", ", "]))
    lines = [f"{k * dt!r}{sep}{x!r}" for k, x in enumerate(a)]
    header = draw(st.sampled_from(["", "time_s,accel_g\n", "# a comment\n",
                                   "t [s]; a [g]\n", "time,acc\nsecond,g\n"]))
    text = header + "\n".join(lines) + draw(st.sampled_from(["", "\n", "\n\n"]))
    return "csv", text.encode(), a, dt


junk = st.binary(min_size=0, max_size=300).map(lambda b: ("junk", b, None, None))
contents = st.one_of(at2_files(), column_files(), junk)
specials = st.sampled_from(["fifo", "/dev/null", "/dev/zero", "/dev/urandom", "directory",
                            "huge", "link_to_zero", "missing", "trailing_blank"])


# ---- the independent reading -------------------------------------------------------------------

NUMBER = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?")


def fields(line):
    """The fields of a line: separated by blanks, tabs, commas or semicolons (the format)."""
    return [f for f in re.split(r"[ \t,;]+", line) if f]


def number(text):
    if not NUMBER.fullmatch(text):
        raise ValueError(text)
    return float(text)


def plain_reading(kind, data):
    """(dt, samples in m/s^2) of a file as a plain Python parser reads the documented format,
    or None where the format is broken (the reader must then refuse it)."""
    text = data.decode("ascii")
    lines = re.split(r"\r\n|\r|\n", text)
    if kind == "at2":
        if len(lines) < 4:
            return None
        head = lines[3].upper().replace("\t", " ")
        try:
            if "=" in head:
                pairs = dict(part.split("=") for part in head.replace(" SEC", "")
                             .replace(" ", "").split(","))
                npts, dt = int(pairs["NPTS"]), number(pairs["DT"])
            else:
                npts, dt = int(head.split()[0]), number(head.split()[1])
            samples = [number(x) for line in lines[4:] for x in fields(line)]
        except (ValueError, KeyError):
            return None
        if npts != len(samples):
            return None
        return dt, G * np.array(samples)
    rows = [line for line in lines if fields(line) and not line.strip(" \t").startswith("#")]
    try:
        number(fields(rows[0])[0])
    except ValueError:
        rows = rows[1:]                              # one line of column names
    try:
        pairs = np.array([[number(x) for x in fields(row)] for row in rows])
    except ValueError:
        return None
    if pairs.ndim != 2 or pairs.shape[1] != 2 or len(pairs) < 2:
        return None
    return (pairs[-1, 0] - pairs[0, 0]) / (len(pairs) - 1), G * pairs[:, 1]


def make(folder, k, case):
    """Write case k into folder; return its path (the special files are made as named)."""
    if isinstance(case, str):
        path = folder / f"special_{k}.AT2"
        if case == "fifo":
            os.mkfifo(path)
        elif case.startswith("/dev/"):
            return case
        elif case == "directory":
            path.mkdir()
        elif case == "huge":                       # sparse: no disk space used
            with open(path, "wb") as f:
                f.truncate((1 << 30) + 1)
        elif case == "link_to_zero":
            os.symlink("/dev/zero", path)
        elif case == "trailing_blank":
            path.write_bytes(b"x\ny\nz\nNPTS= 2, DT= 0.01\n0.1 0.2\n")
            return str(path) + " "
        return str(path)
    kind, data, _, _ = case
    name = "séisme_" if k % 3 == 0 else "quake_"
    path = folder / f"{name}{k}.{'AT2' if kind == 'at2' else 'csv'}"  # junk: read as columns
    path.write_bytes(data)
    return str(path)


def expectation(case):
    """None: the file must be refused; "any": junk, read or refused; else the plain reading."""
    if isinstance(case, str):
        return None
    if case[0] == "junk":
        return "any"
    return plain_reading(case[0], case[1])


CHILD = """
import json, sys
import sloshdyn
out = []
for path in json.loads(sys.stdin.read()):
    try:
        g = sloshdyn.GroundMotion.from_file(path)
        out.append(["ok", g.dt, list(map(float, g.acceleration))])
    except sloshdyn.SloshdynError as exc:
        out.append([type(exc).__name__, str(exc), getattr(exc, "reading", False)])
print(json.dumps(out))
"""


def from_file_in_child(paths, cwd):
    def limit():
        import resource
        resource.setrlimit(resource.RLIMIT_AS, (3 << 30, 3 << 30))
    child = subprocess.run([sys.executable, "-c", CHILD], input=json.dumps(paths), cwd=cwd,
                           capture_output=True, text=True, timeout=CHILD_SECONDS,
                           preexec_fn=limit)
    assert child.returncode == 0, child.stderr[-3000:]
    return json.loads(child.stdout)


def check_refusal(message, path):
    assert all(32 <= ord(c) < 127 or ord(c) > 159 for c in message), message
    assert os.path.basename(path.rstrip()) in message, message


@FUZZ
@given(cases=st.lists(st.one_of(contents, specials), min_size=12, max_size=24))
def test_from_file_reads_what_a_plain_parser_reads_or_refuses_clearly(tmp_path_factory, cases):
    folder = tmp_path_factory.mktemp("records")
    paths = [make(folder, k, case) for k, case in enumerate(cases)]
    results = from_file_in_child(paths, folder)
    for case, path, (outcome, *rest) in zip(cases, paths, results):
        expected = expectation(case)
        if outcome == "ok":
            dt, samples = rest
            assert expected is not None, (case, path)
            assert dt >= 1e-6 and len(samples) >= 2 and all(map(math.isfinite, samples))
            if expected != "any":
                assert dt == pytest.approx(expected[0], rel=1e-9)
                assert samples == pytest.approx(list(expected[1]), rel=1e-12, abs=1e-300)
        else:
            message, reading = rest
            assert outcome in ("InputError", "FileError") and reading, (case, outcome)
            check_refusal(message, path)
            if expected not in (None, "any"):        # a readable file refused: by a rule
                assert expected[0] < 1e-6 and "dt" in message, (case, message)


@FUZZ
@given(cases=st.lists(st.one_of(contents, specials), min_size=4, max_size=8))
def test_the_executable_reads_or_refuses_with_exit_3(exe, tmp_path_factory, cases):
    folder = tmp_path_factory.mktemp("runs")
    tank = ("&tank radius = 5.0, liquid_depth = 6.0, freeboard = 1.0, liquid_density = 1000, "
            "tank_mass = 5.0e4, support_frequency = 2.0, support_damping = 0.02 /\n")
    for k, case in enumerate(cases):
        path = make(folder, k, case)
        if path.endswith(" "):
            continue                      # a namelist string cannot end in a blank
        (folder / "input.nml").write_text(tank + f"&ground_motion record = '{path}' /\n"
                                          "&analysis kind = 'linear' /\n&output directory = "
                                          f"'out_{k}' /\n", encoding="utf-8")
        run = subprocess.run([exe, "input.nml"], cwd=folder, capture_output=True,
                             timeout=CHILD_SECONDS)
        stderr = run.stderr.decode("utf-8", "replace")
        expected = expectation(case)
        assert run.returncode in (0, 3), stderr
        if run.returncode == 0:
            assert expected == "any" or (expected is not None and expected[0] >= 1e-6), case
        else:
            check_refusal(stderr.strip(), path)
            assert not (folder / f"out_{k}").exists()
