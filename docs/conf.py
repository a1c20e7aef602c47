"""Sphinx configuration of the bearingfe documentation site (``bash scripts/build-docs.sh``).

Sphinx rather than MkDocs: the package's docstrings are numpydoc, which Sphinx's ``numpydoc`` extension
renders as written (parameters with units, returns, raises), and ``autodoc`` imports the package, so the
API pages are the docstrings of the code that runs. The pages themselves are Markdown (MyST), the same
files that read well on the repository host. The example gallery runs every example at build time
(``_ext/gallery.py``). Built with warnings as errors, so a broken cross-reference or link fails the build.
"""

from __future__ import annotations

import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(DOCS / "_ext"))

import bearingfe  # noqa: E402

project = "bearingfe"
author = "bearingfe developers"
copyright = "bearingfe developers"
release = version = bearingfe.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.mathjax",
    "numpydoc",
    "gallery",
]

source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
root_doc = "index"
exclude_patterns = ["_build", "benchmarks_parts", "Thumbs.db", ".DS_Store"]
myst_heading_anchors = 3
myst_enable_extensions = ["dollarmath"]
suppress_warnings = ["myst.header"]  # generated pages start at level-2 headings in places

autodoc_member_order = "bysource"
autodoc_typehints = "none"  # numpydoc's Parameters sections carry the types and units
numpydoc_show_class_members = False
numpydoc_validation_checks: set[str] = set()

html_theme = "alabaster"
html_title = f"bearingfe {release}"
html_static_path: list[str] = []
