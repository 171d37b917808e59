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


def reader_groups():
    """{group: {variable: default text}} as the Fortran reader writes its groups."""
    text = sloshdyn._core.sloshdyn_bridge_input.namelist_defaults().decode().strip()
    groups = {}
    for match in re.finditer(r"&(\w+)(.*?)/\s*$", text, re.M):
        items = re.findall(r"(\w+)=\s*(\"[^\"]*\"|[^,]*?)\s*,", match.group(2))
        groups[match.group(1).lower()] = {name.lower(): value.strip('" ') for name, value in items}
    return groups


def documented_groups():
    """{group: {variable: documented default}} from the README's namelist reference tables."""
    groups = {}
    for match in re.finditer(r"^`&(\w+)`.*?\n\n(\|.*?)\n\n", README, re.S | re.M):
        variables = {}
        for line in match.group(2).splitlines()[2:]:
            cells = [c.strip() for c in re.split(r"(?<!\\)\|", line)[1:-1]]
            names = re.findall(r"`(\w+)`", cells[0])
            defaults = [d.strip() for d in cells[2].split(",")] if len(names) > 1 else [cells[2]]
            for k, name in enumerate(names):
                variables[name.lower()] = defaults[k] if k < len(defaults) else ""
        groups[match.group(1)] = variables
    return groups


def same_default(documented, written):
    """A documented default against the reader's written value: numbers compare as numbers,
    quoted strings as strings; prose ('required', '—', 's1 + 1000') is not compared."""
    words = documented.replace("`", "").split()
    if not words:
        return True
    token = words[0]
    if token.startswith("'"):
        return token.strip("'") == written.strip()
    try:
        expected = float(token)
    except ValueError:
        return True
    return float(written.replace("*", " ").split()[-1]) == expected


def test_namelist_reference_matches_the_reader():
    """Every group and variable the reader has is documented, and nothing else; each documented
    default equals the reader's."""
    reader, documented = reader_groups(), documented_groups()
    assert set(documented) == set(reader)
    for group, variables in reader.items():
        assert set(documented[group]) == set(variables), group
        for name, written in variables.items():
            assert same_default(documented[group][name], written), (group, name, written)


def test_python_examples_run_in_a_fresh_interpreter(tmp_path):
    """No test-session imports help the README's code: run it alone."""
    import subprocess
    import sys
    block = "\n".join(re.findall(r"```python\n(.*?)```", README, re.S))
    block = block.replace('"case.nml"', repr(os.fspath(tmp_path / "case.nml")))
    result = subprocess.run([sys.executable, "-c", block], cwd=ROOT, capture_output=True, text=True,
                            timeout=300)
    assert result.returncode == 0, result.stderr
