"""The documentation holds: the Python examples of the README and of docs/python.md run as
written, the executable's output they show is what it prints, the namelist reference
(docs/namelist.md) lists exactly the variables the reader accepts with its defaults, the README
keeps the two commands that CI runs, and every link inside the repository leads somewhere."""

import os
import re
import subprocess
import sys

import pytest

import sloshdyn
from conftest import ROOT, run

README = ROOT / "README.md"
PYTHON_GUIDE = ROOT / "docs" / "python.md"
NAMELIST_REFERENCE = ROOT / "docs" / "namelist.md"
#: the pages with code that runs: each page's ```python blocks together form one program
CODE_PAGES = (README, PYTHON_GUIDE)


def python_code(page, tmp_path):
    """The page's ```python blocks as one program, writing its files into tmp_path."""
    block = "\n".join(re.findall(r"```python\n(.*?)```", page.read_text(), re.S))
    assert block, f"{page.name} has no python example"
    for name in ("case.nml", "branch.csv"):
        block = block.replace(f'"{name}"', repr(os.fspath(tmp_path / name)))
    return block


def test_readme_example_runs_and_finds_the_papers_hopf_points(tmp_path, monkeypatch):
    """The README's example: the Hopf points of Fig 12 against the paper's 0.50925 and 0.50998
    (sec 4.2, Fig 13; printed to 5 decimals from misprinted coefficients, so 1e-4 as in
    data/reference/paper_values.csv), and eq (28)'s frequencies against dgeev of the same
    linearised equations."""
    monkeypatch.chdir(ROOT)
    namespace = {}
    exec(compile(python_code(README, tmp_path), "README.md", "exec"), namespace)
    assert namespace["hopf"] == pytest.approx([0.50925, 0.50998], abs=1e-4)
    modes = sloshdyn.linear_modes(namespace["p"])
    assert (modes.omega1, modes.omega2) == pytest.approx(
        (modes.omega1_dgeev, modes.omega2_dgeev), rel=1e-9)


def test_python_guide_examples_run(tmp_path, monkeypatch):
    monkeypatch.chdir(ROOT)
    namespace = {}
    exec(compile(python_code(PYTHON_GUIDE, tmp_path), "docs/python.md", "exec"), namespace)
    assert sloshdyn.read_namelist(tmp_path / "case.nml").params == namespace["p"]
    assert namespace["st"].motion == "periodic" and round(namespace["st"].max_u1, 4) == 0.0357


@pytest.mark.parametrize("page", CODE_PAGES, ids=lambda p: p.name)
def test_python_examples_run_in_a_fresh_interpreter(tmp_path, page):
    """No test-session imports help the documented code: run each page's code alone."""
    result = subprocess.run([sys.executable, "-c", python_code(page, tmp_path)], cwd=ROOT,
                            capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr


def shown_runs(page):
    """(input file, shown output lines) of each ```sh block `sloshdyn FILE` followed by a
    plain ``` block: the output the page says the executable prints."""
    pattern = r"```sh\nsloshdyn (\S+)\n```\n\n```\n(.*?)```"
    return [(path, output.splitlines()) for path, output in re.findall(pattern, page.read_text(), re.S)]


@pytest.mark.parametrize("page", (README, NAMELIST_REFERENCE), ids=lambda p: p.name)
def test_shown_executable_output_is_what_it_prints(exe, tmp_path, page):
    """Every line a page shows of the executable's summary is printed, in that order ('...'
    stands for lines left out)."""
    runs = shown_runs(page)
    assert runs, f"{page.name} shows no run of the executable"
    for path, shown in runs:
        result = run(exe, ROOT / path, tmp_path)
        assert result.returncode == 0, result.stderr
        printed = iter(result.stdout.splitlines())
        for line in shown:
            if line.strip() != "...":
                assert any(out.rstrip() == line.rstrip() for out in printed), (path, line)


def test_the_two_commands_are_the_readmes_and_ci_runs_the_test_one():
    """The README keeps the two commands, and .ci/run runs the README's test command (then
    the documentation site and the wheel check)."""
    commands = re.findall(r"^(bash \.ci/dev \w+)", README.read_text(), re.M)
    assert commands[:2] == ["bash .ci/dev main", "bash .ci/dev test"]
    ci = [line for line in (ROOT / ".ci" / "run").read_text().splitlines()
          if line.startswith("bash ")]
    assert ci == ["bash .ci/dev test", "bash .ci/dev docs", "bash .ci/dev wheel"]


def slug(heading):
    """The anchor GitHub gives a heading: lower case, punctuation out, spaces to hyphens."""
    return re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-")


def anchors(page):
    text = re.sub(r"```.*?```", "", page.read_text(), flags=re.S)
    return {slug(h) for h in re.findall(r"^#+ (.*)$", text, re.M)}


@pytest.mark.parametrize("page", [README] + sorted((ROOT / "docs").glob("*.md")),
                         ids=lambda p: p.name)
def test_links_inside_the_repository_lead_somewhere(page):
    """Every relative link of the README and of docs/ names a file of the repository (never one
    outside it), and an anchor names a heading of its page."""
    text = re.sub(r"```.*?```", "", page.read_text(), flags=re.S)
    for target in re.findall(r"\]\(([^)\s]+)\)", text):
        if re.match(r"[a-z]+:", target):
            continue
        path, _, anchor = target.partition("#")
        resolved = (page.parent / path).resolve() if path else page
        assert resolved.is_relative_to(ROOT), (page.name, target)
        assert resolved.exists(), (page.name, target)
        if anchor:
            assert anchor in anchors(resolved), (page.name, target)


def test_readme_indexes_every_docs_page():
    readme = README.read_text()
    for page in (ROOT / "docs").glob("*.md"):
        assert f"(docs/{page.name})" in readme, page.name


def reader_groups():
    """{group: {variable: default text}} as the Fortran reader writes its groups."""
    text = sloshdyn._core.sloshdyn_bridge_input.namelist_defaults().decode().strip()
    groups = {}
    for match in re.finditer(r"&(\w+)(.*?)/\s*$", text, re.M):
        items = re.findall(r"(\w+)=\s*(\"[^\"]*\"|[^,]*?)\s*,", match.group(2))
        groups[match.group(1).lower()] = {name.lower(): value.strip('" ') for name, value in items}
    return groups


def documented_groups():
    """{group: {variable: documented default}} from the namelist reference: each group's
    section (a heading `&group`) and the first table in it."""
    groups = {}
    sections = re.split(r"^### `&(\w+)`.*$", NAMELIST_REFERENCE.read_text(), flags=re.M)
    for group, body in zip(sections[1::2], sections[2::2]):
        table = re.search(r"^(\|.*\n)+", body, re.M).group(0)
        variables = {}
        for line in table.splitlines()[2:]:
            cells = [c.strip() for c in re.split(r"(?<!\\)\|", line)[1:-1]]
            names = re.findall(r"`(\w+)`", cells[0])
            defaults = [d.strip() for d in cells[2].split(",")] if len(names) > 1 else [cells[2]]
            for k, name in enumerate(names):
                variables[name.lower()] = defaults[k] if k < len(defaults) else ""
        groups[group] = variables
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
