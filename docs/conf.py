"""Sphinx configuration of sloshdyn's documentation site: `bash .ci/dev docs` builds it into
build/docs/html with warnings as errors.

The Markdown pages of docs/ (namelist.md, python.md, studies.md, model.md, errata.md,
architecture.md, failure.md) are read as they are by myst-parser; the API reference is generated
from the docstrings (autodoc, autosummary, numpydoc); the scripts of docs/gallery_src/ (the
gallery) and docs/tutorials/ (the two tutorials) are run by sphinx-gallery at build time and
shown with their figures.
"""

import os
import re
from pathlib import Path

from docutils import nodes
from sphinx import addnodes
from sphinx.transforms import SphinxTransform

import sloshdyn

ROOT = Path(__file__).resolve().parent.parent   # the repository

# the studies of the gallery run Dask in this process: its scheduler's INFO lines are no output
os.environ.setdefault("DASK_LOGGING__DISTRIBUTED", "warning")

project = "sloshdyn"
author = "the sloshdyn developers"
copyright = "the sloshdyn developers, MIT licence"
release = version = sloshdyn.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
    "myst_parser",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
templates_path = ["_templates"]
exclude_patterns = ["_build", "**/GALLERY_HEADER.rst", "sg_execution_times.rst"]

# Markdown: GitHub's heading anchors, so the pages' links (#the-command-line) work on the site
# as they do on the repository's web view
myst_heading_anchors = 4

# API reference
autosummary_generate = True
autodoc_typehints = "none"            # the numpydoc sections say the types
autodoc_member_order = "bysource"
numpydoc_show_class_members = False   # the class template lists the members
numpydoc_xref_param_type = False

# Gallery and tutorials, run at build time (each script in its own folder)
sphinx_gallery_conf = {
    "examples_dirs": ["gallery_src", "tutorials"],
    "gallery_dirs": ["auto_gallery", "auto_tutorials"],
    "filename_pattern": r"/plot_",    # every script whose name starts with plot_ runs
    "ignore_pattern": r"__init__\.py",
    "within_subsection_order": "FileNameSortKey",
    "download_all_examples": False,
    "remove_config_comments": True,
    "abort_on_example_error": True,
    "image_scrapers": ("matplotlib",),
    "matplotlib_animations": False,
    "reset_modules": ("matplotlib",),
    "show_memory": False,
    "write_computation_times": True,
}

html_theme = "furo"
html_title = f"sloshdyn {version}"
html_static_path = []


# ---- two adaptations of plain-text sources to reStructuredText and the site ------------------

_ABSOLUTE_VALUE = re.compile(r"(?<![\w\\|`])\|([^\s|`][^|`\n]*?)\|(?![\w|`])")


def absolute_values(app, what, name, obj, options, lines):
    """The docstrings write absolute values as |u1|, which reStructuredText reads as a
    substitution reference: escape the bars (outside ``literals``), so they print as written."""
    for k, line in enumerate(lines):
        parts = line.split("``")
        parts[::2] = [_ABSOLUTE_VALUE.sub(r"\\|\1\\|", part) for part in parts[::2]]
        lines[k] = "``".join(parts)


class RepositoryLinks(SphinxTransform):
    """The Markdown pages link to the repository's folders and to files outside docs/
    (../fortran/bridge, ../benchmarks/README.md), which are no pages of the site: a file becomes
    a download of that file, a folder its path in the repository as literal text."""

    default_priority = 5

    def apply(self, **kwargs):
        docs = Path(self.env.srcdir).resolve()
        here = (docs / self.env.docname).parent
        for node in list(self.document.findall(addnodes.pending_xref)):
            if node.get("reftype") != "myst":
                continue
            target = node["reftarget"].split("#")[0]
            if not target:
                continue
            if node.get("refdomain") == "doc":      # a .md outside docs/: named as a document
                if target in self.env.found_docs:
                    continue
                found = [p for p in (docs / (target + s) for s in source_suffix) if p.is_file()]
                path = found[0].resolve() if found else docs / target
            else:
                path = (here / target).resolve()
            if not path.is_relative_to(ROOT) or (path.is_relative_to(docs) and not path.is_dir()):
                continue
            if path.is_file():
                new = addnodes.download_reference(refdoc=node["refdoc"], reftype="myst",
                                                  refexplicit=True,
                                                  reftarget=os.path.relpath(path, here))
                new += node.children
            elif path.is_dir():
                new = nodes.literal(text=f"{path.relative_to(ROOT)}/")
            else:
                continue
            node.replace_self(new)


def setup(app):
    app.connect("autodoc-process-docstring", absolute_values)
    app.add_transform(RepositoryLinks)
