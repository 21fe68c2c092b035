"""Sphinx configuration of the documentation site (``make docs``).

Markdown pages (MyST), the furo theme, the three command lines rendered from their
parsers (sphinx-argparse), the API from the docstrings (autodoc). The reference pages
and the results are drawn from the code, the Makefile and ``reports/`` at every build by
the local extension ``docs/_ext/harness_docs.py``; nothing there is typed by hand twice.
Every warning is an error (``make docs`` runs ``sphinx-build -W``).
"""
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path[:0] = [str(ROOT), str(DOCS / "_ext")]

project = "ANCF hyperelastic verification harness"
author = "the harness's authors"
copyright = "the harness's authors"

extensions = [
    "myst_parser",
    "sphinxarg.ext",
    "sphinx.ext.autodoc",
    "sphinx.ext.mathjax",
    "harness_docs",
]
source_suffix = {".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "_generated", "**/.ipynb_checkpoints"]

myst_enable_extensions = ["deflist", "dollarmath", "colon_fence"]
myst_heading_anchors = 3

# the API pages build without the continuum's stack and without compiling anything:
# importing ancf defines its compiled functions but compiles none until one is called
autodoc_mock_imports = ["dolfinx", "petsc4py", "mpi4py", "ufl", "basix", "gmsh", "felupe", "tensortrax"]
autodoc_default_options = {"members": True, "show-inheritance": False}
autodoc_member_order = "bysource"
autodoc_typehints = "none"

html_theme = "furo"
html_title = "ANCF hyperelastic verification harness"
html_static_path = []
pygments_style = "default"
