"""Sphinx configuration of the symlink documentation site.

Build it with warnings as errors (what CI does)::

    pip install -e '.[docs]'
    sphinx-build -W --keep-going -b html docs docs/_build/html

The pages are Markdown (MyST); the API reference comes from the docstrings through autodoc.
"""
from __future__ import annotations

import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))  # document this checkout, installed or not

import symlink  # noqa: E402

project = "symlink"
author = "the symlink authors"
copyright = "the symlink authors, MIT licence"
release = version = symlink.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.mathjax",
]
source_suffix = {".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "Thumbs.db", ".DS_Store", "**.ipynb_checkpoints", "*.ipynb", "pictures.py"]

# MyST: ```{directive} fences, $...$ maths, and headings that can be linked to.
myst_enable_extensions = ["colon_fence", "dollarmath"]
myst_heading_anchors = 3

# autodoc: the docstrings are reStructuredText with ``code`` literals (no numpydoc/Google
# sections, so no napoleon). Members in source order, as a reader meets them in the module.
autodoc_default_options = {
    "members": True,
    "member-order": "bysource",
}
autodoc_typehints = "signature"  # the docstrings do not list parameters: the hints stay in the signature
autodoc_typehints_format = "short"
autodoc_preserve_defaults = True  # show defaults as written (names, not repr of objects)

html_theme = "alabaster"
html_title = f"symlink {release}"
html_static_path: list[str] = []

# Two docstrings write a distance as |AC| or |BD| in running text, which reStructuredText reads
# as a substitution reference (an error). Escape such bars outside ``literals`` as the
# docstrings are read, so the package's text stays as written.
_LITERAL = re.compile(r"(``.*?``)")
_BARS = re.compile(r"(?<!\\)\|([A-Za-z][A-Za-z0-9]{0,3})\|")


def _escape_distance_bars(app, what, name, obj, options, lines: list[str]) -> None:
    for index, line in enumerate(lines):
        parts = _LITERAL.split(line)  # odd parts are ``literals``: leave them alone
        lines[index] = "".join(part if number % 2 else _BARS.sub(r"\\|\1\\|", part)
                               for number, part in enumerate(parts))


def setup(app) -> None:
    app.connect("autodoc-process-docstring", _escape_distance_bars)
