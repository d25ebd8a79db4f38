"""Sphinx configuration of the symlink documentation site.

Build it with warnings as errors (what CI does; ``tests/test_docs.py`` does the same)::

    pip install -e '.[docs]'
    python -m sphinx -W --keep-going -b html docs docs/_build/html

The layout follows Diataxis: tutorials (MyST-NB notebooks, executed at every build so they cannot
rot), how-to guides, reference (the API one page per module and the command line, both generated
by ``_ext/symlink_docs.py`` from the package itself; the file grammars) and explanation. The
theme is furo; the docstrings' numpydoc sections are rendered by napoleon.
"""
from __future__ import annotations

import os
import re
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(ROOT))  # document this checkout, installed or not
sys.path.insert(0, str(DOCS / "_ext"))
# The tutorials' kernels inherit the environment: they import this checkout too, draw off-screen, and
# keep the derived code in the build's own cache unless the reader chose one.
os.environ["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH", "")]))
os.environ["MPLBACKEND"] = "module://matplotlib_inline.backend_inline"

import symlink  # noqa: E402

project = "symlink"
author = "the symlink authors"
copyright = "the symlink authors, MIT licence"
release = version = symlink.__version__

extensions = [
    "myst_nb",                 # MyST markdown and executed notebooks (brings myst_parser)
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",     # numpydoc-style Parameters / Returns / Raises / Examples sections
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "symlink_docs",            # docs/_ext: the API pages and the command-line reference, generated
]
source_suffix = {".md": "myst-nb", ".ipynb": "myst-nb"}
root_doc = "index"
smartquotes = False  # "--trace" stays two hyphens, quotes stay as typed (command lines are copied from here)
exclude_patterns = ["_build", "Thumbs.db", ".DS_Store", "**.ipynb_checkpoints", "example.ipynb", "pictures.py",
                    "benchmark/*", "_ext"]

# MyST: ```{directive} fences, $...$ maths, and headings that can be linked to.
myst_enable_extensions = ["colon_fence", "dollarmath", "amsmath"]
myst_heading_anchors = 3

# MyST-NB: execute every notebook page whenever Sphinx reads it (every page on a fresh build, as in CI
# and tests/test_docs.py); an error in a cell fails the build. Not "cache": a cache keyed on the cells'
# code would keep outputs of an older symlink.
nb_execution_mode = "force"
nb_execution_timeout = 180
nb_execution_raise_on_error = True
nb_execution_show_tb = True
nb_merge_streams = True
nb_render_image_options = {"width": "100%"}

# autodoc and napoleon: numpy-style sections only (a "Note:" in running text stays text).
autodoc_default_options = {"member-order": "bysource", "special-members": "__call__"}  # Solver(...)(...) is the call
autodoc_typehints = "signature"
autodoc_typehints_format = "short"
autodoc_preserve_defaults = True  # show defaults as written (names, not repr of objects)
autodoc_inherit_docstrings = False  # e.g. Results is a dict: do not repeat dict's docstrings
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False
napoleon_use_ivar = True  # an Attributes section as a field list of the class, not as separate objects

html_theme = "furo"
html_title = f"symlink {release}"
html_static_path = ["_static"]
html_css_files = ["wide.css"]
html_theme_options = {
    "source_repository": "https://github.com/symlink-kinematics/symlink/",
    "source_branch": "main",
    "source_directory": "docs/",
}

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


def _napoleon_outside_attributes(app) -> None:
    """Let napoleon read the docstrings of functions, classes and modules only.

    On a property or attribute napoleon takes a first line ``text: more`` as ``type: description``,
    which would turn the package's one-line property docstrings ("Memory a call needs: ...") into a
    type; their text stays as written instead.
    """
    from sphinx.ext import napoleon

    for listener in list(app.events.listeners.get("autodoc-process-docstring", [])):
        if listener.handler is napoleon._process_docstring:
            app.disconnect(listener.id)

    def numpy_sections(app, what, name, obj, options, lines) -> None:
        if what not in ("attribute", "data", "property"):
            napoleon._process_docstring(app, what, name, obj, options, lines)

    app.connect("autodoc-process-docstring", numpy_sections)


def setup(app) -> None:
    app.connect("autodoc-process-docstring", _escape_distance_bars, priority=400)
    _napoleon_outside_attributes(app)
