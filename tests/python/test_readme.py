"""The README's Python example runs as written, and its namelist reference lists exactly the
variables the reader accepts."""

import os
import re

import sloshdyn
from conftest import ROOT

README = (ROOT / "README.md").read_text()


def test_python_examples_run(tmp_path, monkeypatch):
    block = "\n".join(re.findall(r"```python\n(.*?)```", README, re.S))
    monkeypatch.chdir(ROOT)
    block = block.replace('"case.nml"', repr(os.fspath(tmp_path / "case.nml")))
    namespace = {}
    exec(compile(block, "README.md", "exec"), namespace)
    assert sloshdyn.read_namelist(tmp_path / "case.nml").params == namespace["p"]
    assert namespace["st"].motion == "periodic" and round(namespace["st"].max_u1, 4) == 0.0357


def test_namelist_reference_matches_the_reader():
    from sloshdyn.parameters import NAMELIST_SCHEMA
    for group, variables in NAMELIST_SCHEMA.items():
        section = re.search(rf"^`&{group}`.*?\n\n(\|.*?)\n\n", README, re.S | re.M)
        assert section, f"&{group} missing from README"
        documented = set(re.findall(r"`(\w+)`", section.group(1)))
        assert {name for name, _, _ in variables.values()} <= documented, group


def test_python_examples_run_in_a_fresh_interpreter(tmp_path):
    """No test-session imports help the README's code: run it alone."""
    import subprocess
    import sys
    block = "\n".join(re.findall(r"```python\n(.*?)```", README, re.S))
    block = block.replace('"case.nml"', repr(os.fspath(tmp_path / "case.nml")))
    result = subprocess.run([sys.executable, "-c", block], cwd=ROOT, capture_output=True, text=True,
                            timeout=300)
    assert result.returncode == 0, result.stderr
