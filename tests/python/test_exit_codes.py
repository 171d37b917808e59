"""One exit-code table for both front doors (docs/failure.md): sloshdyn-py exits as
the executable does for the same failure, never with a traceback for a sloshdyn error; `check`
tells a bad file (exit 3, naming the file and the line) from a quantity out of tolerance
(exit 1) and refuses an empty table."""

import json
import shutil
import subprocess
import sys

import pytest

from sloshdyn import _core
from sloshdyn._errors import EXIT_MEANINGS
from sloshdyn.reference import PACKAGE_REFERENCE

MODEL = "&model s1 = 1.5, mu1 = 0.5, kappa = 1.8049, theta0 = 0.785, gamma = 0.001 /\n"


def sloshdyn_py(*args, cwd):
    return subprocess.run([sys.executable, "-m", "sloshdyn", *args], cwd=cwd,
                          capture_output=True, text=True, timeout=300)


def test_every_exit_code_of_the_core_has_a_meaning():
    """The codes the core gives any status (its exit_code, which both doors apply) are the
    documented ones: a new code needs its row in EXIT_MEANINGS and docs/failure.md."""
    for reading in (False, True):
        for status in range(0, 16):
            assert int(_core.sloshdyn_bridge_input.exit_code(status, reading)) in EXIT_MEANINGS


FAILURES = {
    # name: (input text, the exit code the table gives it)
    "bad value": (MODEL.replace("s1 = 1.5", "s1 = -1") + "&output directory = 'out' /\n", 3),
    "unknown analysis": (MODEL + "&analysis kind = 'linearx' /\n&output directory = 'out' /\n",
                         3),
    "integration failure": (MODEL + "&excitation A = 0.001, rho = 0.5 /\n&analysis kind = "
                            "'simulate' /\n&simulation t_end = 100 /\n&integration max_steps = 5"
                            " /\n&output directory = 'out' /\n", 4),
    "not a namelist": ("\x00\x01 binary \xff garbage", 3),
}


@pytest.mark.parametrize("case", FAILURES)
def test_both_doors_exit_alike_without_a_traceback(exe, tmp_path, case):
    text, code = FAILURES[case]
    (tmp_path / "input.nml").write_text(text, errors="surrogateescape")
    executable = subprocess.run([exe, "input.nml"], cwd=tmp_path, capture_output=True,
                                text=True, timeout=120)
    python = sloshdyn_py("run", "input.nml", cwd=tmp_path)
    assert executable.returncode == python.returncode == code, (executable.stderr,
                                                                 python.stderr)
    assert python.stderr.startswith("sloshdyn-py: error:") and "Traceback" not in python.stderr
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("what", ["missing.nml", "."])
def test_an_input_that_is_no_file_is_an_input_error(exe, tmp_path, what):
    executable = subprocess.run([exe, what], cwd=tmp_path, capture_output=True, text=True,
                                timeout=60)
    python = sloshdyn_py("run", what, cwd=tmp_path)
    assert executable.returncode == python.returncode == 3
    assert "Traceback" not in python.stderr and what in python.stderr


def _check(tmp_path, values_text, reference=None):
    (tmp_path / "run").mkdir(exist_ok=True)
    (tmp_path / "run" / "values.json").write_text(values_text)
    args = ["check", str(tmp_path / "run")]
    if reference is not None:
        args += ["--reference", str(reference)]
    return sloshdyn_py(*args, cwd=tmp_path)


@pytest.mark.parametrize("content,line", [(b'{"omega1": 0.5,\n "omega2": }\n', 2),
                                          (b"[1, 2]", None), (b"{}", None),
                                          (b'{"omega1": 0.5,\n "omega2": "fast"\n}', 2),
                                          (b"\xff\xfe{", None), (b"", 1)])
def test_check_a_corrupted_values_json_is_a_bad_file(tmp_path, content, line):
    (tmp_path / "run").mkdir()
    (tmp_path / "run" / "values.json").write_bytes(content)
    result = sloshdyn_py("check", str(tmp_path / "run"), cwd=tmp_path)
    assert result.returncode == 3, result.stderr
    assert "bad file" in result.stderr and "values.json" in result.stderr
    assert "Traceback" not in result.stderr
    if line:
        assert f"line {line}" in result.stderr


def _corrupt_reference(tmp_path, edit):
    reference = tmp_path / "ref"
    shutil.copytree(PACKAGE_REFERENCE, reference)
    path = reference / "paper_values.csv"
    lines = path.read_text().splitlines(keepends=True)
    path.write_text("".join(edit(lines)))
    return reference


CORRUPTIONS = {
    # name: (edit of the lines of paper_values.csv, line named, words of the message)
    "reference not a number": (lambda ls: ls[:2] + [ls[2].replace("1.53308", "1.533O8")]
                               + ls[3:], 3, ["reference", "1.533O8"]),
    "unknown tolerance kind": (lambda ls: ls[:2] + [ls[2].replace(",abs,", ",absolute,")]
                               + ls[3:], 3, ["absolute"]),
    "missing field": (lambda ls: ls[:2] + ['omega1,"sec 4.2",0.50936\n'] + ls[3:], 3,
                      ["number of fields"]),
    "negative tolerance": (lambda ls: ls[:2] + [ls[2].replace("5e-6", "-5e-6")] + ls[3:], 3,
                           ["tolerance"]),
    "repeated quantity": (lambda ls: ls + [ls[1]], None, ["twice"]),
    "empty table": (lambda ls: ls[:1], None, ["no rows"]),
    "no header either": (lambda ls: [], None, ["no rows"]),
}


@pytest.mark.parametrize("case", CORRUPTIONS)
def test_check_a_corrupted_reference_table_is_a_bad_file(tmp_path, case):
    edit, line, words = CORRUPTIONS[case]
    result = _check(tmp_path, json.dumps({"omega1": 0.50936}),
                    _corrupt_reference(tmp_path, edit))
    assert result.returncode == 3, (result.stdout, result.stderr)
    assert "bad file" in result.stderr and "paper_values.csv" in result.stderr
    assert "Traceback" not in result.stderr
    if line:
        assert f"line {line}" in result.stderr
    for word in words:
        assert word in result.stderr


def test_check_a_missing_reference_table_is_a_bad_file(tmp_path):
    reference = tmp_path / "ref"
    shutil.copytree(PACKAGE_REFERENCE, reference)
    (reference / "computed_values.csv").unlink()
    result = _check(tmp_path, json.dumps({"omega1": 0.50936}), reference)
    assert result.returncode == 3 and "bad file" in result.stderr
    assert "computed_values.csv" in result.stderr and "missing" in result.stderr


def test_check_out_of_tolerance_is_exit_1_not_a_bad_file(tmp_path):
    """A well-formed run whose values miss the reference: exit 1, the quantities named."""
    result = _check(tmp_path, json.dumps({"omega1": 0.6}))
    assert result.returncode == 1 and "bad file" not in result.stderr
    assert "omega1" in result.stdout.splitlines()[-1]


def test_the_failure_page_table_is_the_exit_code_table_and_its_tests_exist():
    """docs/failure.md: its table is EXIT_MEANINGS, and every test it names exists."""
    import re
    from conftest import ROOT
    section = (ROOT / "docs" / "failure.md").read_text()
    rows = dict(re.findall(r"^\| (\d+) \| (.*?) \|$", section, re.M))
    assert {int(code): text.replace("`", "") for code, text in rows.items()} == EXIT_MEANINGS
    module = None
    for name in re.findall(r"`(?:(test_\w+\.py)::|::)(test_\w+)`", section):
        module = name[0] or module
        source = (ROOT / "tests" / "python" / module).read_text()
        assert f"def {name[1]}(" in source, name
