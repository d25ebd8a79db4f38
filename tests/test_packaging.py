"""The package's metadata keeps its promises: ``pip install -e '.[test]' && pytest -n auto`` has every package it imports.

The default test run imports the tests, the ``conftest.py`` files and, for
their doctests (``--doctest-modules`` over ``testpaths``), every module of
``symlink/`` and ``benchmarks/``; it runs the README's ``python`` blocks
(``tests/test_readme.py``).  Each third-party package those import must
come with a runtime dependency or the ``test`` extra (directly, or as what
one of them requires), so that the README's test command passes on a fresh
machine.  Read with :mod:`ast`, without running anything:

- every ``import``/``from ... import`` at any depth, and the imports of every
  doctest example, count;
- an import is optional, and may name any package, where it is guarded: in the
  body of a ``try`` that catches ``ImportError`` (the code falls back or says
  which extra to install), in a test marked ``skipif(..., reason=...)``, or
  under ``if TYPE_CHECKING:`` (never imported at run time);
- ``pytest.importorskip("x")`` of a package that the ``test`` extra does not
  bring must say why it skips and what installs it (``reason=``);
- calls that import a package behind their name count as that import
  (:data:`HIDDEN_IMPORTS`: ``to_pandas()`` and ``Results.to_frame()`` need pandas);
- in ``benchmarks/`` an import inside a function is a peer of ``symlink bench``
  (the ``bench`` extra), which the benchmark runs only where it is installed;
- a requirement with an environment marker counts as provided (``tomli`` on
  Python 3.10 is imported only where it is installed).

The import names are mapped to distributions by the installed metadata
(:func:`importlib.metadata.packages_distributions`), so this runs where the
packages are installed: the development environment, or any that ran the
tests at all.
"""
from __future__ import annotations

import ast
import doctest
import importlib.metadata
import re
import sys
import warnings
from functools import lru_cache
from pathlib import Path

import pytest
from packaging.markers import default_environment
from packaging.requirements import Requirement

from readme_text import fenced_blocks, readme

if sys.version_info >= (3, 11):
    import tomllib
else:  # Python 3.10
    import tomli as tomllib

ROOT = Path(__file__).resolve().parent.parent
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())
PROJECT = PYPROJECT["project"]["name"]

#: Method calls that import a package the call's name does not show: ``Table.to_pandas()`` (pyarrow) and
#: :meth:`symlink.numeric.results.Results.to_frame` need pandas.
HIDDEN_IMPORTS = {"to_pandas": "pandas", "to_frame": "pandas"}
#: Import names whose distribution is named otherwise, for packages not installed here (their import fails
#: anyway; the message then names the distribution to add).
KNOWN_DISTRIBUTIONS = {"PIL": "pillow", "yaml": "pyyaml", "sklearn": "scikit-learn", "IPython": "ipython",
                       "mpl_toolkits": "matplotlib", "dateutil": "python-dateutil", "pkg_resources": "setuptools"}
#: The project's own top-level modules and the test helpers imported from tests/ (pythonpath and rootdir).
OWN = {"symlink", "benchmarks", "tests", "conftest"}


def normalized(name: str) -> str:
    """A distribution name as PEP 503 compares them."""
    return re.sub(r"[-_.]+", "-", name).lower()


def parse(source: str, name: str = "<unknown>") -> ast.AST:
    """``source`` parsed, quietly: an escape sequence in a string (LaTeX in a doctest) is the file's own business."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", (SyntaxWarning, DeprecationWarning))
        return ast.parse(source, name)


def scanned_files() -> list[Path]:
    """What the default test run imports: the tests, the conftest files, and the doctest modules of testpaths."""
    files = {ROOT / "conftest.py"} if (ROOT / "conftest.py").exists() else set()
    for folder in PYPROJECT["tool"]["pytest"]["ini_options"]["testpaths"]:
        files.update((ROOT / folder).rglob("*.py"))
    return sorted(path for path in files if "_build" not in path.parts)


def local_modules() -> set[str]:
    """Module names the tests import from their own folders (helpers beside the tests: ``references``...)."""
    return {path.stem for path in (ROOT / "tests").rglob("*.py")} | {
        path.name for path in (ROOT / "tests").rglob("*") if path.is_dir()}


def _catches_import_error(handler: ast.ExceptHandler) -> bool:
    if handler.type is None:
        return True
    names = handler.type.elts if isinstance(handler.type, ast.Tuple) else [handler.type]
    return any(isinstance(n, ast.Name) and n.id in {"ImportError", "ModuleNotFoundError", "Exception"}
               for n in names)


def _skips_with_reason(function: ast.AST) -> bool:
    """Whether a test is decorated ``pytest.mark.skipif(..., reason=...)``."""
    for decorator in getattr(function, "decorator_list", []):
        if (isinstance(decorator, ast.Call) and isinstance(decorator.func, ast.Attribute)
                and decorator.func.attr == "skipif" and any(k.arg == "reason" for k in decorator.keywords)):
            return True
    return False


def imports(tree: ast.AST, functions_optional: bool = False) -> list[tuple[str, int, str]]:
    """``(top-level import name, line, how)`` for every import in ``tree``; ``how`` is ``"required"``,
    ``"guarded"`` or ``"importorskip"`` / ``"importorskip with reason"``; with ``functions_optional``
    every import inside a function is ``"guarded"``."""
    found: list[tuple[str, int, str]] = []

    def visit(node: ast.AST, guarded: bool) -> None:
        if isinstance(node, ast.Try):
            caught = any(_catches_import_error(h) for h in node.handlers)
            for child in node.body:
                visit(child, guarded or caught)
            for child in node.handlers + node.orelse + node.finalbody:
                visit(child, guarded)
            return
        if isinstance(node, ast.If) and ast.unparse(node.test) in ("TYPE_CHECKING", "typing.TYPE_CHECKING"):
            for child in node.body:  # for the type checker only: never imported at run time
                visit(child, True)
            for child in node.orelse:
                visit(child, guarded)
            return
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and (
                functions_optional or _skips_with_reason(node)):
            guarded = True
        how = "guarded" if guarded else "required"
        if isinstance(node, ast.Import):
            found.extend((alias.name.split(".")[0], node.lineno, how) for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            found.append((node.module.split(".")[0], node.lineno, how))
        elif isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute):
            if (node.func.attr == "importorskip" and node.args and isinstance(node.args[0], ast.Constant)
                    and isinstance(node.args[0].value, str)):
                reason = any(k.arg == "reason" for k in node.keywords)
                found.append((node.args[0].value.split(".")[0], node.lineno,
                              "importorskip with reason" if reason else "importorskip"))
            elif node.func.attr in HIDDEN_IMPORTS:
                found.append((HIDDEN_IMPORTS[node.func.attr], node.lineno, how))
        for child in ast.iter_child_nodes(node):
            visit(child, guarded)

    visit(tree, False)
    return found


def doctest_trees(tree: ast.AST, path: Path) -> list[tuple[ast.AST, int]]:
    """Each doctest of the module's docstrings as one parsed tree, with the line of its docstring."""
    parser, found = doctest.DocTestParser(), []
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            text = ast.get_docstring(node, clean=False)
            if text and ">>>" in text:
                source = "\n".join(example.source for example in parser.get_examples(text, str(path)))
                try:
                    found.append((parse(source, str(path)), getattr(node, "lineno", 1)))
                except SyntaxError:
                    pass  # the doctest run itself reports it
    return found


def all_imports() -> list[tuple[str, str, str]]:
    """``(import name, "file:line", how)`` of every third-party import of the default test run."""
    skip = set(sys.stdlib_module_names) | OWN | local_modules()
    found = []
    for path in scanned_files():
        tree = parse(path.read_text(encoding="utf-8"), str(path))
        relative = path.relative_to(ROOT).as_posix()
        for name, line, how in imports(tree, functions_optional=relative.startswith("benchmarks/")):
            found.append((name, f"{relative}:{line}", how))
        for example, line in doctest_trees(tree, path):
            for name, _, how in imports(example):
                found.append((name, f"{relative}:{line} (doctest)", how))
    for index, block in enumerate(fenced_blocks(readme(), "python")):
        found.extend((name, f"README.md python block {index}", how) for name, _, how in imports(parse(block)))
    return [entry for entry in found if entry[0] not in skip and not entry[0].startswith("_")]


@lru_cache(maxsize=None)
def provided() -> frozenset[str]:
    """The distributions a ``pip install -e '.[test]'`` brings: the dependencies, the ``test`` extra and,
    through the installed metadata, everything they require in turn."""
    environment = default_environment()
    wanted = [Requirement(text) for text in PYPROJECT["project"]["dependencies"]
              + PYPROJECT["project"]["optional-dependencies"]["test"]]
    seen: set[str] = {normalized(requirement.name) for requirement in wanted}  # with their markers, on any Python
    while wanted:
        requirement = wanted.pop()
        name = normalized(requirement.name)
        extras = requirement.extras
        if requirement.marker is not None and not requirement.marker.evaluate({**environment, "extra": ""}):
            continue
        seen.add(name)
        try:
            requires = importlib.metadata.requires(requirement.name) or []
        except importlib.metadata.PackageNotFoundError:
            continue  # not installed here: its own requirements are unknown (its import fails anyway)
        for text in requires:
            inner = Requirement(text)
            marker = inner.marker
            if marker is None or any(marker.evaluate({**environment, "extra": extra}) for extra in extras | {""}):
                if normalized(inner.name) not in seen:
                    wanted.append(Requirement(str(inner).split(";")[0]))
    return frozenset(seen)


@lru_cache(maxsize=None)
def distributions_of(import_name: str) -> tuple[str, ...]:
    """The distributions that install the top-level module ``import_name`` (normalized)."""
    installed = importlib.metadata.packages_distributions().get(import_name)
    if installed:
        return tuple(normalized(name) for name in installed)
    return (normalized(KNOWN_DISTRIBUTIONS.get(import_name, import_name)),)


def unprovided(entries) -> list[str]:
    """The entries (name, where, how) whose package ``pip install -e '.[test]'`` does not bring."""
    return [f"{where}: {name} ({'/'.join(distributions_of(name))}, {how})" for name, where, how in entries
            if not set(distributions_of(name)) & provided()]


def test_the_test_extra_brings_every_package_the_test_run_imports():
    needed = [entry for entry in all_imports() if entry[2] == "required"]
    assert needed, "no third-party import found: the scan is broken"
    assert unprovided(needed) == [], "add these to the `test` extra in pyproject.toml (or guard the import)"


def test_an_optional_import_outside_the_test_extra_skips_saying_what_installs_it():
    bare = [entry for entry in all_imports() if entry[2] == "importorskip"]
    assert unprovided(bare) == [], "give these pytest.importorskip calls a reason= naming the extra to install"


# --- the checker finds what it is for ---------------------------------------------

def scan(source: str) -> list[tuple[str, int, str]]:
    return imports(ast.parse(source))


def test_the_scan_tells_required_guarded_and_skipping_imports_apart():
    source = '''
import numpy.linalg
from scipy import optimize
if TYPE_CHECKING:
    import pandas
try:
    import pint
except ImportError:
    pint = None
@pytest.mark.skipif(True, reason="the docs extra is missing")
def test_docs():
    import sphinx
def test_frame(results):
    ipython = pytest.importorskip("IPython.core")
    widgets = pytest.importorskip("ipympl", reason="pip install -e '.[notebook]'")
    results.to_frame()
'''
    assert scan(source) == [("numpy", 2, "required"), ("scipy", 3, "required"), ("pandas", 5, "guarded"),
                            ("pint", 7, "guarded"), ("sphinx", 12, "guarded"), ("IPython", 14, "importorskip"),
                            ("ipympl", 15, "importorskip with reason"), ("pandas", 16, "required")]


def test_a_package_outside_the_dependencies_is_reported():
    # the README's command failed this way: pyarrow's to_pandas() needs pandas, which no extra of `test` had
    entries = [("pandas", "tests/test_sweep.py:1", "required"), ("numpy", "tests/x.py:1", "required"),
               ("mpmath", "tests/x.py:2", "required"), ("surely_no_such_package", "tests/x.py:3", "required")]
    reported = unprovided(entries)
    assert reported[-1] == "tests/x.py:3: surely_no_such_package (surely-no-such-package, required)"
    assert all("numpy" not in line and "mpmath" not in line for line in reported)  # a dependency, and sympy's


def test_the_transitive_closure_follows_installed_requirements():
    assert {"numpy", "sympy", "mpmath", "pytest", "pandas"} <= provided()  # mpmath: sympy's own requirement
    assert "sphinx" not in provided() and "numba" not in provided()  # the docs and bench extras


def test_doctest_examples_are_scanned(tmp_path):
    module = tmp_path / "m.py"
    module.write_text('"""A module.\n\n>>> import numba\n>>> results.to_frame()\n"""\n')
    tree = ast.parse(module.read_text())
    found = [entry for example, _ in doctest_trees(tree, module) for entry in imports(example)]
    assert [(name, how) for name, _, how in found] == [("numba", "required"), ("pandas", "required")]


def test_the_wheel_ships_every_catalog_linkage_file():
    """The package data patterns cover the linkage files (``pip wheel . --no-deps`` lists them in the wheel)."""
    import fnmatch
    patterns = PYPROJECT["tool"]["setuptools"]["package-data"]["symlink"]
    shipped = sorted((ROOT / "symlink" / "linkages").glob("*.toml"))
    assert shipped, "symlink/linkages/ holds no linkage file"
    for path in shipped:
        relative = path.relative_to(ROOT / "symlink").as_posix()
        assert any(fnmatch.fnmatch(relative, pattern) for pattern in patterns), f"{relative} is not package data"


def test_the_extras_all_and_dev_name_existing_extras():
    extras = PYPROJECT["project"]["optional-dependencies"]
    for name, wanted in (("all", {"notebook", "pandas", "units", "dynamics", "sweep", "synthesis", "fabrication",
                                  "studio"}),
                         ("dev", {"test", "docs", "bench", "typecheck"})):
        (requirement,) = [Requirement(text) for text in extras[name]]
        assert normalized(requirement.name) == normalized(PROJECT)
        assert requirement.extras == wanted and wanted <= set(extras)
