"""The namelist scanner is linear in the length of a line (issue 22, item 8).

On the main before the fix one `&model` line padded with blanks to 300 kB took 16.6 s to read and
1 MB more than 60 s (issue 22); here, on a loaded 2-core machine, 250 kB took 48 s and 2 MB was
still being read when killed after 79 s. The body of a group grew by one character at a time (a
copy of the whole body each time, n^2/2 bytes copied), and each assignment was found by scanning
the body from its start again (n times the number of assignments). Now 250 kB takes 0.13 s,
1 MB 0.21 s and 2 MB about 0.3 s for the whole run, process start included.

No timing is asserted (the machine may be loaded): the 2 MB line must be read, to the right
values, by a child process limited to 20 s of CPU time (RLIMIT_CPU: the processor time the reader
itself uses, which another load on the machine does not inflate as it does elapsed time; a wall
timeout of 60 s only guards against a hang). 20 s is more than 20 times what the linear scanner
needs (the executable on the 2 MB line: 0.11 s of CPU, 0.5 s elapsed on a busy machine; the
child interpreter of the second test, import included, a few seconds) and far below what the quadratic one needs (about 16.6 s x (2 MB / 300 kB)^2 =
740 s by the issue's figures). So the test cannot pass with the quadratic scanner and does not
fail with the linear one on a slow machine. The second test reads a line with
20,000 assignments through Python (read_namelist, the same reader), which exercises the
assignment positions, found before the fix by a scan from the start of the body for each one.
"""

import resource
import subprocess
import sys

from conftest import write

MEGABYTE = 1 << 20
CPU_SECONDS = 20   # > 20x the linear scanner's time, < 1/30 of the quadratic one's
TIMEOUT = 60       # elapsed seconds: only against a hang


def limited(command, cwd):
    """Run command with at most CPU_SECONDS of processor time (SIGXCPU beyond)."""
    def limit():
        resource.setrlimit(resource.RLIMIT_CPU, (CPU_SECONDS, CPU_SECONDS))
    result = subprocess.run(command, cwd=cwd, capture_output=True, text=True, timeout=TIMEOUT,
                            preexec_fn=limit)
    assert result.returncode == 0, (result.returncode, result.stderr[-2000:])
    return result


def padded_model(size, assignments=1):
    """A one-line input of about `size` bytes: &model with its values spread over the line by
    blanks (`assignments` copies of `beta = 0.5,` among them), then a linear analysis."""
    values = ["s1 = 1.5,", "mu1 = 0.5,", "kappa = 1.804897259,", "theta0 = 0.7853981633974483,"]
    values += ["beta = 0.5,"] * assignments
    gap = " " * max((size - 100) // (len(values) - 1), 1)
    return "&model " + gap.join(values) + " / &analysis kind = 'linear' /\n"


def test_a_2_megabyte_line_reads_within_the_bound_executable(exe, tmp_path):
    """The padded file gives the same results as the file without padding."""
    for name, size in (("padded", 2 * MEGABYTE), ("plain", 0)):
        (tmp_path / name).mkdir()
        path = write(tmp_path / name, padded_model(size) + "&output directory = 'out' /\n")
        limited([exe, str(path)], tmp_path / name)
    assert (tmp_path / "padded" / "input.nml").stat().st_size > 2 * MEGABYTE - 200
    files = sorted(p.name for p in (tmp_path / "plain" / "out").iterdir())
    assert files and files == sorted(p.name for p in (tmp_path / "padded" / "out").iterdir())
    for name in files:
        assert (tmp_path / "plain" / "out" / name).read_bytes() == \
            (tmp_path / "padded" / "out" / name).read_bytes(), name


def test_a_2_megabyte_line_with_many_assignments_reads_within_the_bound_python(tmp_path):
    """20,000 assignments on one 2 MB line, read through the bridge in a child interpreter (so
    the timeout can stop it); the last assignment of beta wins, as in any namelist read."""
    text = padded_model(2 * MEGABYTE, assignments=20000).replace(
        "beta = 0.5, / &analysis", "beta = 0.25 / &analysis")
    path = write(tmp_path, text)
    code = ("import sloshdyn, sys; p = sloshdyn.read_namelist(sys.argv[1]).params; "
            "print(p.s1, p.beta)")
    result = limited([sys.executable, "-c", code, str(path)], tmp_path)
    assert result.stdout.split() == ["1.5", "0.25"]
