"""The documentation site's sources (docs/, built by `bash .ci/dev docs`), checked without
building it: every public name of sloshdyn is in the API reference, every gallery and tutorial
script runs in the build and is listed, the Markdown pages link only inside the repository, and
the site's tools are pinned."""

import ast
import pkgutil
import re

import pytest

import sloshdyn

from conftest import ROOT

DOCS = ROOT / "docs"


def autosummary_entries():
    """The names listed in the autosummary tables of docs/api/*.rst, qualified by the
    currentmodule in force (each generates a page from its docstring)."""
    entries = set()
    for path in sorted((DOCS / "api").glob("*.rst")):
        module, in_table = "", False
        for line in path.read_text().splitlines():
            directive = re.match(r"\.\. (\w+)::\s*(\S*)", line)
            if directive:
                in_table = directive[1] == "autosummary"
                if directive[1] == "currentmodule":
                    module = directive[2]
                continue
            if in_table and line.strip() and not line.startswith(" "):
                in_table = False
            if in_table and line.strip() and not line.strip().startswith(":"):
                entries.add(f"{module}.{line.strip()}" if module else line.strip())
    return entries


def lazy_modules():
    """The submodules that `sloshdyn.<name>` loads on first use (sloshdyn.__getattr__):
    public, though not in __all__ (plotting, figures, reference, cli)."""
    found = []
    for info in pkgutil.iter_modules(sloshdyn.__path__):
        if info.name.startswith("_"):
            continue
        try:
            sloshdyn.__getattr__(info.name)
        except AttributeError:
            continue
        found.append(info.name)
    return found


def gallery_conf():
    """sphinx_gallery_conf of docs/conf.py, read as a literal (conf.py imports Sphinx, which
    the test environment need not have)."""
    tree = ast.parse((DOCS / "conf.py").read_text())
    for node in tree.body:
        if isinstance(node, ast.Assign) and [t.id for t in node.targets] == ["sphinx_gallery_conf"]:
            return ast.literal_eval(node.value)
    raise AssertionError("docs/conf.py sets no sphinx_gallery_conf")


def test_every_public_name_is_in_the_api_reference():
    entries = autosummary_entries()
    public = [f"sloshdyn.{name}" for name in sloshdyn.__all__]
    assert len(public) == len(set(public)) > 50
    missing = [name for name in public if name not in entries]
    assert not missing, f"not in docs/api/index.rst: {missing}"
    modules = lazy_modules()
    assert {"plotting", "cli"} <= set(modules)
    assert not [m for m in modules if f"sloshdyn.{m}" not in entries]
    # a module's page documents its members (the module template's automodule :members:)
    template = (DOCS / "_templates" / "autosummary" / "module.rst").read_text()
    assert re.search(r"\.\. automodule:: \{\{ fullname \}\}\n\s+:members:", template)


def test_the_api_reference_lists_only_names_that_exist():
    for entry in autosummary_entries():
        obj = sloshdyn
        for part in entry.split(".")[1:]:
            obj = getattr(obj, part)           # AttributeError names a stale entry
        assert obj is not None, entry


def test_every_gallery_script_runs_in_the_build_and_is_listed():
    conf = gallery_conf()
    assert len(conf["examples_dirs"]) == len(conf["gallery_dirs"])
    index = (DOCS / "index.rst").read_text()
    scripts = []
    for source, target in zip(conf["examples_dirs"], conf["gallery_dirs"]):
        folder = DOCS / source
        assert (folder / "GALLERY_HEADER.rst").is_file(), f"{source} has no GALLERY_HEADER.rst"
        assert f"{target}/index" in index, f"{target}/index is not in the toctree of index.rst"
        for script in sorted(folder.glob("*.py")):
            scripts.append(script)
            # sphinx-gallery runs a script whose path matches filename_pattern
            assert re.search(conf["filename_pattern"], str(script)), f"{script.name} would not run"
            assert not re.search(conf["ignore_pattern"], str(script)), f"{script.name} is ignored"
            doc = ast.get_docstring(ast.parse(script.read_text()))
            assert doc, f"{script.name} has no docstring (the gallery's title and text)"
            title, underline = doc.strip().splitlines()[:2]
            assert set(underline) == {"="} and len(underline) == len(title), script.name
    assert conf["abort_on_example_error"] is True      # a failing script fails the build
    names = {s.stem for s in scripts}
    assert {"plot_01_tank_engineer", "plot_02_researcher", "plot_03_tank_modes_roofs_two_components",
            "plot_04_researcher_branches_swirl", "plot_two_components",
            "plot_rectangular_modes"} <= names
    assert len(names) >= 11


MARKDOWN = sorted(str(p.relative_to(DOCS)) for p in DOCS.rglob("*.md")
                  if not p.relative_to(DOCS).parts[0].startswith(("auto_", "_build")))


@pytest.mark.parametrize("page", MARKDOWN)
def test_markdown_pages_link_only_inside_the_repository(page):
    assert "python.md" in MARKDOWN and "tutorials/getting_started.md" in MARKDOWN
    text = (DOCS / page).read_text()
    text = re.sub(r"```.*?```", "", text, flags=re.S)           # code blocks hold no links
    for target in re.findall(r"\]\(([^)\s]+)\)", text):
        if re.match(r"[a-z]+:", target) or target.startswith("#"):
            continue
        path = ((DOCS / page).parent / target.split("#")[0]).resolve()
        assert path.is_relative_to(ROOT), f"{page} links outside the repository: {target}"
        assert path.exists(), f"{page} links to a missing file: {target}"


def test_the_site_builds_by_one_command_with_pinned_tools():
    pins = [line.split("#")[0].strip() for line in (DOCS / "requirements.txt").read_text().splitlines()]
    pins = [p for p in pins if p]
    assert pins and all(re.fullmatch(r"[A-Za-z0-9_.-]+==[0-9][A-Za-z0-9.]*", p) for p in pins)
    assert {p.split("==")[0].lower() for p in pins} >= {"sphinx", "numpydoc", "sphinx-gallery",
                                                         "myst-parser"}
    dev = (ROOT / ".ci" / "dev").read_text()
    assert "docs/requirements.txt" in dev and "-W --keep-going" in dev
    assert "bash .ci/dev docs" in (ROOT / ".ci" / "run").read_text()
    assert "bash .ci/dev docs" in (ROOT / "README.md").read_text()
