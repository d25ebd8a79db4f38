"""The documentation: the site builds with warnings as errors, and the example notebook runs top to bottom.

Both need the optional extras (``pip install -e '.[docs,notebook]'``, what ``.ci/run`` installs);
without them those two tests skip and say which package is missing.  The checks of what the
pages list need nothing but the sources.
"""
from __future__ import annotations

import importlib.util
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
NOTEBOOK = DOCS / "example.ipynb"

#: Modules the API reference leaves out: the command line (documented by ``symlink --help``),
#: ``python -m symlink`` and the TOML reader kept for Python 3.10.
NOT_IN_API = {"symlink.cli", "symlink.__main__", "symlink.minitoml"}


def missing(*modules: str) -> list[str]:
    """The modules of ``modules`` that cannot be imported here."""
    return [name for name in modules if importlib.util.find_spec(name) is None]


def package_modules() -> list[str]:
    """Every module and package of symlink, by dotted name, from the source tree."""
    names = []
    for path in sorted((ROOT / "symlink").rglob("*.py")):
        parts = path.relative_to(ROOT).with_suffix("").parts
        names.append(".".join(parts[:-1] if parts[-1] == "__init__" else parts))
    return names


def test_api_reference_lists_every_public_module():
    documented = set(re.findall(r"^\.\. automodule:: (\S+)$", (DOCS / "api.md").read_text(), re.MULTILINE))
    public = {name for name in package_modules()
              if not any(name == hidden or name.startswith(hidden + ".") for hidden in NOT_IN_API)}
    assert public - documented == set(), "add these modules to docs/api.md"
    assert documented - public == set(), "docs/api.md documents modules that do not exist"


def test_gallery_shows_every_picture():
    shown = set(re.findall(r"^```\{figure\} images/(\S+)$", (DOCS / "gallery.md").read_text(), re.MULTILINE))
    pictures = {path.name for path in (DOCS / "images").iterdir() if path.suffix in {".png", ".gif", ".svg"}}
    assert pictures, "docs/images holds no pictures"
    assert shown == pictures


def test_notebook_is_committed_without_outputs():
    notebook = json.loads(NOTEBOOK.read_text())
    code = [cell for cell in notebook["cells"] if cell["cell_type"] == "code"]
    assert code, "the notebook has no code"
    for cell in code:
        assert cell["outputs"] == [] and cell["execution_count"] is None, "clear the notebook's outputs"


@pytest.mark.skipif(bool(missing("sphinx", "myst_parser")),
                    reason=f"the docs extra is not installed ({', '.join(missing('sphinx', 'myst_parser'))}): "
                           "pip install -e '.[docs]'")
def test_docs_build_without_warnings(tmp_path):
    build = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html",
                            "-d", str(tmp_path / "doctrees"), str(DOCS), str(tmp_path / "html")],
                           capture_output=True, text=True, cwd=ROOT, timeout=600)
    assert build.returncode == 0, build.stderr + build.stdout
    api = (tmp_path / "html" / "api.html").read_text()
    # autodoc rendered the docstrings as objects (not as text), e.g. the solver and the linkage
    for anchor in ('id="symlink.solver.Solver"', 'id="symlink.linkage.Linkage"', 'id="symlink.export.export"'):
        assert anchor in api
    readme = (tmp_path / "html" / "readme.html").read_text()
    assert "_images/jansen.png" in readme  # the README's pictures come along with it


@pytest.mark.skipif(bool(missing("nbclient", "nbformat", "ipykernel")),
                    reason=f"the notebook extra is not installed ({', '.join(missing('nbclient', 'nbformat', 'ipykernel'))}): "
                           "pip install -e '.[notebook]'")
def test_example_notebook_runs_top_to_bottom(tmp_path, monkeypatch):
    import nbformat
    from nbclient import NotebookClient

    # The kernel inherits the environment: Jupyter's inline figures (CI sets Agg) and a
    # temporary folder of the test's own for the files the notebook writes.
    monkeypatch.setenv("MPLBACKEND", "module://matplotlib_inline.backend_inline")
    monkeypatch.setenv("TMPDIR", str(tmp_path))
    notebook = nbformat.read(NOTEBOOK, as_version=4)
    NotebookClient(notebook, timeout=300, kernel_name="python3",
                   resources={"metadata": {"path": str(tmp_path)}}).execute()  # raises on any error

    outputs = [output for cell in notebook.cells if cell.cell_type == "code" for output in cell.outputs]
    kinds = {kind for output in outputs for kind in output.get("data", {})}
    assert {"text/latex", "image/png", "image/gif"} <= kinds  # equations, figure, animation
    latex = next(output.data["text/latex"] for output in outputs if "text/latex" in output.get("data", {}))
    assert r"\theta" in latex and r"\beta" in latex
    text = "".join(output.get("text", "") for output in outputs)
    assert "same rocker angles as the solver: True" in text
    written = {path.name for path in tmp_path.rglob("*") if path.is_file()}
    assert {"coupler_fourbar.gif", "coupler_fourbar.tex", "coupler_fourbar.py"} <= written
