"""Sphinx configuration of the exudyn_turnout documentation.

Build: ``python -m sphinx -b html docs docs/_build/html`` (``pip install -e ".[docs]"``;
CI adds ``-W --keep-going``). The API reference, the examples gallery and the command-line
reference are generated from the package at build time by ``_ext/et_docs.py`` into
``api/generated/`` and ``examples/generated/`` (not committed); nothing is run but
``--help``.
"""

import os
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
# The package documented is the one next to this folder, whatever else is installed.
sys.path.insert(0, str(DOCS.parent))
sys.path.insert(0, str(DOCS / "_ext"))
os.environ.setdefault("MPLBACKEND", "Agg")

import exudyn_turnout  # noqa: E402

project = "exudyn_turnout"
author = "the exudyn_turnout authors"
copyright = "the exudyn_turnout authors, BSD-3-Clause"
version = release = exudyn_turnout.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.viewcode",
    "et_docs",
]

exclude_patterns = ["_build", "_ext", "Thumbs.db", ".DS_Store"]
templates_path: list[str] = []

# numpydoc docstrings (CONTRIBUTING.md), read by napoleon: one dependency fewer than numpydoc.
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False
# Types as text, not links: a type such as "ndarray, shape (n,)" would link "n" to whichever
# attribute of the package is called n.
napoleon_use_param = False
napoleon_use_ivar = True

autodoc_member_order = "bysource"
autodoc_typehints = "signature"
autodoc_typehints_format = "short"
autodoc_preserve_defaults = False
python_maximum_signature_line_length = 88
python_display_short_literal_types = True

# Literal blocks of docstrings ("::") are mostly ASCII drawings, tables and commands, not
# Python: left as they are. The pages name the language of their code blocks.
highlight_language = "none"

# Unresolved references (a type named in a docstring, numpy's ndarray) are not errors.
nitpicky = False

html_theme = "alabaster"
html_title = f"exudyn_turnout {release}"
html_theme_options = {
    "description": "Co-running turnout track models on Exudyn (Shih, Ambur & Dixon 2023)",
    "fixed_sidebar": True,
    "sidebar_collapse": True,
    "page_width": "1180px",
    "sidebar_width": "250px",
}
html_sidebars = {"**": ["about.html", "navigation.html", "searchbox.html"]}
html_show_sourcelink = False
html_static_path = ["_static"]
