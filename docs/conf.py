"""Sphinx configuration: Markdown pages (myst-parser), the API from the docstrings
(autodoc + numpydoc), the examples run into a gallery (sphinx-gallery: a broken example
breaks the build), the pydata theme.  Build: sphinx-build -W -b html docs docs/_build/html"""
import os
import sys

sys.path.insert(0, os.path.abspath(".."))
sys.path.insert(0, os.path.abspath("."))       # _gallery: the examples' arguments
from shell_adhesion import __version__  # noqa: E402

project = "shell-adhesion"
author = "the shell-adhesion authors"
copyright = "2026, the shell-adhesion authors"
release = version = __version__

extensions = ["myst_parser", "sphinx.ext.autodoc", "numpydoc", "sphinx.ext.mathjax",
              "sphinx_gallery.gen_gallery"]
sphinx_gallery_conf = {
    "examples_dirs": "../examples",
    "gallery_dirs": "gallery",              # generated (not tracked)
    "filename_pattern": r"/ex\d\d_",        # run every example
    "reset_argv": "_gallery.argv",          # each on the coarse mesh, writing nothing here
    "abort_on_example_error": True,
    "download_all_examples": False,
    "capture_repr": (),
    "show_memory": False,
    "within_subsection_order": "FileNameSortKey",
    "write_computation_times": False,
}
source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
exclude_patterns = ["_build", "gallery/*.ipynb", "gallery/*.py", "gallery/ex03_output"]
myst_heading_anchors = 3
autodoc_typehints = "none"
autodoc_member_order = "bysource"
numpydoc_show_class_members = False
numpydoc_validation_checks = set()
html_theme = "pydata_sphinx_theme"
html_title = f"shell-adhesion {version}"
html_theme_options = {"navigation_with_keys": False, "show_toc_level": 2}
