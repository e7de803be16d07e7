"""Sphinx configuration: Markdown pages (myst-parser), the API from the docstrings
(autodoc + numpydoc), the pydata theme.  Build: sphinx-build -W -b html docs docs/_build/html"""
import os
import sys

sys.path.insert(0, os.path.abspath(".."))
from shell_adhesion import __version__  # noqa: E402

project = "shell-adhesion"
author = "the shell-adhesion authors"
copyright = "2026, the shell-adhesion authors"
release = version = __version__

extensions = ["myst_parser", "sphinx.ext.autodoc", "numpydoc", "sphinx.ext.mathjax"]
source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
exclude_patterns = ["_build"]
myst_heading_anchors = 3
autodoc_typehints = "none"
autodoc_member_order = "bysource"
numpydoc_show_class_members = False
numpydoc_validation_checks = set()
html_theme = "pydata_sphinx_theme"
html_title = f"shell-adhesion {version}"
html_theme_options = {"navigation_with_keys": False, "show_toc_level": 2}
