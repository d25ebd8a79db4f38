"""The documentation site: it builds with warnings as errors and teaches what the package does today.

Without the ``docs`` extra (``pip install -e '.[docs]'``) the build test skips and says which
package is missing; the checks of the sources need nothing but the checkout:

* the gallery shows every picture of ``docs/images`` with the code that draws it;
* the grammar pages name every key the readers accept;
* the ``docs`` extra lists what the build and the tutorials import;
* every ```python block of the how-to and explanation pages runs;
* the example notebook is committed without outputs (and, with the ``notebook`` extra, runs);
* every function and class of ``symlink.__all__`` has numpydoc Parameters, Returns and Examples
  sections, its examples through the front door.

The built site (one build, shared by the checks that read it): tutorial pages hold executed
outputs with images, the API has one page per public module and a public page of exactly
``symlink.__all__``, the command-line reference lists
every subcommand that ``symlink --help`` lists, the most used API has numpydoc sections, and the
benchmark page shows the benchmark's own table and plot.
"""
from __future__ import annotations

import contextlib
import html
import importlib.util
import io
import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from readme_text import fenced_blocks

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
NOTEBOOK = DOCS / "example.ipynb"
TUTORIALS = sorted(path for path in (DOCS / "tutorials").glob("*.md") if path.stem != "index")

#: Modules the API reference leaves out: the command line (its own page, from its parsers),
#: ``python -m symlink`` and the TOML reader kept for Python 3.10.
NOT_IN_API = {"symlink.cli", "symlink.__main__", "symlink.minitoml"}
#: What the site's build needs, by the module it imports.
BUILD_NEEDS = ("sphinx", "furo", "myst_nb", "ipykernel")


def missing(*modules: str) -> list[str]:
    """The modules of ``modules`` that cannot be imported here."""
    return [name for name in modules if importlib.util.find_spec(name) is None]


def package_modules() -> list[str]:
    """Every public module and package of symlink, by dotted name, from the source tree."""
    names = []
    for path in sorted((ROOT / "symlink").rglob("*.py")):
        parts = path.relative_to(ROOT).with_suffix("").parts
        name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        if not any(name == hidden or name.startswith(hidden + ".") for hidden in NOT_IN_API):
            names.append(name)
    return names


def html_text(path: Path) -> str:
    """The text of a built page's article, tags removed."""
    page = path.read_text(encoding="utf-8")
    found = re.search(r"<article[^>]*>(.*?)</article>", page, re.S)
    return re.sub(r"\s+", " ", re.sub(r"<[^>]+>", " ", found.group(1) if found else page))


# ---- the sources -------------------------------------------------------------------------------------------

#: Where users read examples: each must run with ``import symlink`` (or ``from symlink import ...``) alone.
EXAMPLE_PAGES = [ROOT / "README.md", *sorted((DOCS / "tutorials").glob("*.md")), *sorted((DOCS / "howto").glob("*.md")),
                 *sorted((DOCS / "explanation").glob("*.md")), NOTEBOOK, DOCS / "pictures.py"]
#: The one exception: the notebook widget lives in the studio, a leaf that the front door never imports.
SUBMODULE_IMPORT = re.compile(r"^\s*(?:from\s+symlink\.(?!studio\.widget\s+import\s+LinkageWidget[ \t]*(?:#.*)?$)[\w.]+\s+import"
                              r"|import\s+symlink\.[\w.]+)", re.M)


def example_code(path: Path) -> str:
    """The code a user would copy from ``path``: fenced and cell blocks of a page, every cell of the notebook."""
    if path.suffix == ".ipynb":
        return "\n".join("".join(cell["source"]) for cell in json.loads(path.read_text(encoding="utf-8"))["cells"]
                         if cell["cell_type"] == "code")
    if path.suffix == ".py":
        return path.read_text(encoding="utf-8")
    text = path.read_text(encoding="utf-8")
    return "\n".join(block for language in ("python", "{code-cell} ipython3", "{code-cell}")
                     for block in fenced_blocks(text, language))


@pytest.mark.parametrize("path", EXAMPLE_PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_examples_use_the_front_door_only(path):
    found = [line.strip() for line in SUBMODULE_IMPORT.findall(example_code(path))]
    assert found == [], f"{path.relative_to(ROOT)} imports a submodule; use `import symlink`: {found}"


def test_the_front_door_check_sees_a_submodule_import(tmp_path):
    page = tmp_path / "page.md"
    page.write_text("```python\nfrom symlink.numeric.solver import Solver\n```\n", encoding="utf-8")
    assert SUBMODULE_IMPORT.findall(example_code(page))
    # the studio's notebook widget, and it alone, is imported from its module
    page.write_text("```python\nfrom symlink.studio.widget import LinkageWidget\n```\n", encoding="utf-8")
    assert SUBMODULE_IMPORT.findall(example_code(page)) == []
    page.write_text("```python\nfrom symlink.studio.widget import LinkageWidget, widget_esm\n```\n", encoding="utf-8")
    assert SUBMODULE_IMPORT.findall(example_code(page))
    page.write_text("```python\nfrom symlink.studio.drawing import solver\n```\n", encoding="utf-8")
    assert SUBMODULE_IMPORT.findall(example_code(page))


def test_every_front_door_name_loads():
    import symlink
    for name in symlink.__all__:
        assert getattr(symlink, name) is not None, name
    assert len(set(symlink.__all__)) == len(symlink.__all__)


# ---- numpydoc sections of the public API -------------------------------------------------------------------

def _section(docstring: str, title: str) -> bool:
    """Whether ``docstring`` has the numpydoc section ``title`` (its title, underlined by dashes)."""
    return re.search(rf"^\s*{title}\n\s*-{{3,}}\s*$", docstring, re.M) is not None


def public_callables() -> list[tuple[str, object]]:
    """(name, object) of every function and class of ``symlink.__all__`` (the data constants left out)."""
    import inspect

    import symlink
    found = []
    for name in symlink.__all__:
        value = getattr(symlink, name)
        if inspect.isclass(value) or inspect.isroutine(inspect.unwrap(value)) and callable(value):
            found.append((name, value))
    return found


def numpydoc_gaps(name: str, value: object) -> list[str]:
    """The numpydoc sections that the docstring of the public ``value`` lacks."""
    import inspect

    is_class = inspect.isclass(value)
    docstring = inspect.getdoc(value) or ""
    if is_class and value.__dict__.get("__init__") is not None and value.__dict__["__init__"].__doc__:
        docstring += "\n" + inspect.cleandoc(value.__dict__["__init__"].__doc__)
    try:
        takes = [p for p in inspect.signature(value).parameters if p not in ("self", "cls")]
    except (TypeError, ValueError):
        takes = []
    gaps = []
    if takes and not _section(docstring, "Parameters"):
        gaps.append("Parameters")
    if not is_class and not _section(docstring, "Returns"):
        gaps.append("Returns")
    if not _section(docstring, "Examples") or ">>>" not in docstring.split("Examples", 1)[-1]:
        gaps.append("Examples")
    return gaps


def test_every_public_function_and_class_has_numpydoc_sections():
    names = public_callables()
    assert len(names) > 100, "the front door lists its functions and classes"
    gaps = {name: numpydoc_gaps(name, value) for name, value in names}
    gaps = {name: missing for name, missing in gaps.items() if missing}
    assert gaps == {}, f"{len(gaps)} of {len(names)} public names lack numpydoc sections: {gaps}"


def test_public_examples_go_through_the_front_door():
    import inspect

    for name, value in public_callables():
        examples = (inspect.getdoc(value) or "").split("Examples", 1)[-1]
        assert not SUBMODULE_IMPORT.search(examples.replace(">>> ", "")), f"{name}: its example imports a submodule"


def test_the_numpydoc_check_sees_a_missing_section():
    def documented(x):
        """Twice x.

        Parameters
        ----------
        x : float
            A number.

        Returns
        -------
        float
            Twice it.

        Examples
        --------
        >>> documented(2)
        4
        """
        return 2 * x

    def bare(x):
        """Twice x."""
        return 2 * x

    assert numpydoc_gaps("documented", documented) == []
    assert numpydoc_gaps("bare", bare) == ["Parameters", "Returns", "Examples"]

#: Screenshots of the studio (docs/tutorials/draw_it.md): taken by tests/studio/test_browser.py with
#: SYMLINK_SCREENSHOTS=1, pictures of a web page rather than of the gallery's code.
STUDIO_SCREENSHOTS = "studio_"


def test_gallery_shows_every_picture_with_its_code():
    gallery = (DOCS / "gallery.md").read_text()
    shown = re.findall(r"^```\{figure\} images/(\S+)$", gallery, re.MULTILINE)
    pictures = {path.name for path in (DOCS / "images").iterdir() if path.suffix in {".png", ".gif", ".svg"}
                and not path.name.startswith(STUDIO_SCREENSHOTS)}
    assert pictures and set(shown) == pictures
    code = re.findall(r"^```\{literalinclude\} (\S+)\n:pyobject: (\w+)$", gallery, re.MULTILINE)
    assert len(code) == len(shown), "every figure of the gallery is followed by the code that draws it"
    for source, name in code:
        text = (DOCS / source).read_text()
        assert re.search(rf"^def {name}\(", text, re.MULTILINE), f"{source} has no function {name}"


def test_pictures_script_draws_every_gallery_picture_but_the_benchmarks():
    spec = importlib.util.spec_from_file_location("pictures", DOCS / "pictures.py")
    pictures = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(pictures)
    assert set(pictures.DRAWERS) == set(pictures.PICTURES)
    made_elsewhere = {"bench.png", "growth.png"}  # `symlink bench --plot`, `python -m benchmarks.growth --plot`
    on_disk = {path.name for path in (DOCS / "images").iterdir() if path.suffix in {".png", ".gif", ".svg"}
               and not path.name.startswith(STUDIO_SCREENSHOTS)}
    assert set(pictures.PICTURES) == on_disk - made_elsewhere


def test_grammar_pages_name_every_key():
    from symlink.io import linkage_file, scene

    page = (DOCS / "reference" / "linkage_file.md").read_text()
    keys = (*linkage_file.TOP_KEYS, *linkage_file.TABLES, *linkage_file.DYNAMICS_KEYS,
            *(key for needs, may in linkage_file.DYNAMICS_ENTRIES.values() for key in needs + may))
    assert [key for key in keys if f"`{key}`" not in page and f"[{key}]" not in page and f".{key}" not in page] == []
    page = (DOCS / "reference" / "scene_file.md").read_text()
    assert [key for key in (*scene.TOP_KEYS, *scene.INPUT_KEYS) if f"`{key}`" not in page and f"[{key}]" not in page] == []


def test_docs_extra_brings_what_the_build_and_the_tutorials_import():
    pyproject = (ROOT / "pyproject.toml").read_text()
    extra = re.search(r"^docs = \[(.*?)\]", pyproject, re.MULTILINE | re.S).group(1)
    listed = {re.split(r"[<>=!~\[; ]", item.strip().strip('"'))[0].lower() for item in extra.split(",") if item.strip()}
    assert {"sphinx", "furo", "myst-nb", "ipykernel"} <= listed
    # what the tutorials use beyond the core dependencies: tables (pandas), sweeps (dask, pyarrow), SciPy
    assert {"pandas", "scipy", "dask", "distributed", "pyarrow"} <= listed
    imported = set()
    for path in TUTORIALS:
        for cell in re.findall(r"```\{code-cell\} ipython3\n(.*?)```", path.read_text(), re.S):
            imported |= set(re.findall(r"^(?:from|import) (\w+)", cell, re.MULTILINE))
    third_party = imported - set(sys.stdlib_module_names) - {"symlink", "numpy", "sympy", "matplotlib"}
    distribution = {"IPython": "ipykernel"}
    assert {distribution.get(name, name).lower() for name in third_party} <= listed


PAGES_WITH_CODE = sorted((DOCS / "howto").glob("*.md")) + sorted((DOCS / "explanation").glob("*.md"))
PYTHON_BLOCKS = [(path, index, block) for path in PAGES_WITH_CODE
                 for index, block in enumerate(fenced_blocks(path.read_text(), "python"))]


@pytest.mark.parametrize("path, index, block", PYTHON_BLOCKS,
                         ids=[f"{path.parent.name}/{path.stem}[{index}]" for path, index, _ in PYTHON_BLOCKS])
def test_docs_python_block_runs(path, index, block, tmp_path, monkeypatch):
    needs = [name for name in re.findall(r"^(?:from|import) (\w+)", block, re.MULTILINE) if name in ("pint", "pandas")]
    if missing(*needs):
        pytest.skip(f"{path.name} block {index} needs {', '.join(missing(*needs))}")
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        exec(compile(block, f"{path.name} block {index}", "exec"), {"__name__": "__docs__"})  # our own docs
    # what a comment says a print shows is what it shows (where the comment quotes it whole)
    for line in block.splitlines():
        said = re.match(r"\s*print\(.*\)\s+# (\[.*\]|\{.*\}|\d[^:]*)$", line)
        if said and said.group(1).startswith(("[", "{")):
            assert said.group(1) in printed.getvalue(), f"{path.name}: {line.strip()}"


def test_notebook_is_committed_without_outputs():
    notebook = json.loads(NOTEBOOK.read_text())
    code = [cell for cell in notebook["cells"] if cell["cell_type"] == "code"]
    assert code, "the notebook has no code"
    for cell in code:
        assert cell["outputs"] == [] and cell["execution_count"] is None, "clear the notebook's outputs"


# ---- the built site ----------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    """The site built once with ``-W`` (warnings are errors), its HTML folder."""
    if missing(*BUILD_NEEDS):
        pytest.skip(f"the docs extra is not installed ({', '.join(missing(*BUILD_NEEDS))}): pip install -e '.[docs]'")
    folder = tmp_path_factory.mktemp("site")
    build = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html",
                            "-d", str(folder / "doctrees"), str(DOCS), str(folder / "html")],
                           capture_output=True, text=True, cwd=ROOT, timeout=900)
    assert build.returncode == 0, build.stderr[-5000:] + build.stdout[-2000:]
    return folder / "html"


def test_site_builds_with_warnings_as_errors(site):
    assert (site / "index.html").is_file() and (site / "gallery.html").is_file()


@pytest.mark.parametrize("tutorial", [path.stem for path in TUTORIALS])
def test_tutorial_page_holds_executed_outputs_with_images(site, tutorial):
    page = (site / "tutorials" / f"{tutorial}.html").read_text()
    outputs = re.findall(r'<div class="cell_output docutils container">(.*?)</div>\s*</div>', page, re.S)
    cells = len(re.findall(r'class="cell docutils container"', page))
    assert cells and outputs, f"{tutorial}: no executed outputs"
    assert re.search(r'<img [^>]*src="\.\./_images/[^"]+\.png"', page), f"{tutorial}: no figure output"
    assert "Traceback" not in html_text(site / "tutorials" / f"{tutorial}.html")


def test_api_has_one_page_per_public_module(site):
    api = site / "reference" / "api"
    pages = {path.stem for path in api.glob("symlink*.html")}
    assert pages == set(package_modules())
    for module in ("symlink.numeric.solver", "symlink.symbolic.linkage", "symlink.io.export"):
        page = (api / f"{module}.html").read_text()
        assert f'id="{module}.' in page, f"{module}: autodoc rendered no object"
    internals = (api / "internals.html").read_text()
    assert [module for module in package_modules() if f'href="{module}.html"' not in internals] == []


def test_public_page_documents_exactly_the_front_door(site):
    import symlink

    page = (site / "reference" / "api" / "public.html").read_text()
    documented = set(re.findall(r'<dt class="sig sig-object py" id="symlink\.(\w+)"', page))
    assert documented == set(symlink.__all__)
    order = [name for name in re.findall(r'<dt class="sig sig-object py" id="symlink\.(\w+)"', page) if name != "__version__"]
    layers = ["symlink.common", "symlink.symbolic", "symlink.mechanism", "symlink.codegen", "symlink.numeric",
              "symlink.dynamics", "symlink.io", "symlink.analysis", "symlink.synthesis", "symlink.workshop",
              "symlink.plot", "symlink.studio"]
    layer = {name: layers.index(".".join(module.split(".")[:2])) for name, (module, _) in symlink.PUBLIC.items()}
    expected = sorted(symlink.PUBLIC, key=lambda name: layer[name])  # stable: PUBLIC's order within a layer
    assert order == expected, "the public page lists the names by layer, each in PUBLIC's order"


def test_most_used_api_has_numpydoc_sections(site):
    solver = (site / "reference" / "api" / "symlink.numeric.solver.html").read_text()
    call = solver[solver.index('id="symlink.numeric.solver.Solver.__call__"'):]
    call = call[:call.index('id="symlink.numeric.solver.NumericSolver"')]  # up to the next class
    for section in ("Parameters", "Returns", "Raises"):
        assert re.search(rf">{section}<", call), f"Solver.__call__ has no rendered {section} section"
    for module, anchor in (("symlink.symbolic.linkage", "symlink.symbolic.linkage.Linkage"), ("symlink.numeric.results", "symlink.numeric.results.Results"),
                           ("symlink.mechanism.catalog", "symlink.mechanism.catalog.fourbar"), ("symlink.numeric.solver", "symlink.numeric.solver.Solver"),
                           ("public", "symlink.Linkage"), ("public", "symlink.fourbar"), ("public", "symlink.Solver")):
        page = (site / "reference" / "api" / f"{module}.html").read_text()
        body = page[page.index(f'id="{anchor}"'):]
        body = body[:body.find('<dt class="sig sig-object py"', 1)]  # its own docstring, not its members'
        assert re.search(r">(Parameters|Returns)<", body) and "Examples" in body, f"{anchor}: no numpydoc sections"


def test_cli_reference_lists_every_subcommand_of_symlink_help(site, capsys):
    from symlink.cli import main

    try:
        assert main(["--help"]) == 0
    except SystemExit as done:  # argparse's own way out of --help
        assert done.code in (0, None)
    listing = capsys.readouterr().out
    commands = re.findall(r"^ {4}(\w[\w-]*)", listing, re.MULTILINE)
    assert len(commands) >= 20, listing
    page = html_text(site / "reference" / "cli.html")
    for command in commands:
        assert f"symlink {command} " in page or f"symlink {command}¶" in page, f"symlink {command} is not in the CLI reference"
    assert "--crank-speed" in page and "--to" in page and "--units" in page  # options, not just commands


def test_benchmark_page_shows_the_benchmarks_table_and_plot(site):
    page = (site / "explanation" / "benchmark.html").read_text()
    assert "bench.png" in page
    text = html.unescape(html_text(site / "explanation" / "benchmark.html"))
    rows = [line for line in (DOCS / "benchmark" / "results.md").read_text().splitlines()
            if re.search(r"\bsymlink\b.*\d", line) and not line.startswith("#")]
    assert rows, "docs/benchmark/results.md holds no row of symlink's numbers"
    for row in rows[:5]:  # a table row (markdown or preformatted) reads the same on the page
        words = " ".join(re.sub(r"[|`*]", " ", row).split())
        assert words in text, f"the benchmark page does not show: {words}"


def test_code_blocks_scroll_instead_of_being_cut_off(site):
    css = (DOCS / "_static" / "wide.css").read_text()
    assert "overflow-x: auto" in css
    assert "wide.css" in (site / "index.html").read_text()


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
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])))
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
