"""Sphinx configuration of sloshdyn's documentation site: `bash .ci/dev docs` builds it into
build/docs/html with warnings as errors.

The Markdown pages of docs/ (namelist.md, python.md, studies.md, model.md, errata.md,
architecture.md, failure.md) are read as they are by myst-parser; the API reference is generated
from the docstrings (autodoc, autosummary, numpydoc); the scripts of docs/gallery_src/ (the
gallery) and docs/tutorials/ (the two tutorials) are run by sphinx-gallery at build time and
shown with their figures.
"""

from pathlib import Path

import sloshdyn

ROOT = Path(__file__).resolve().parent.parent   # the repository

project = "sloshdyn"
author = "the sloshdyn developers"
copyright = "the sloshdyn developers, MIT licence"
release = version = sloshdyn.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
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
