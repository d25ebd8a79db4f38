"""The table of printers: every language's module, with the same call shape, imported on first use."""
import ast
import inspect
import subprocess
import sys
from pathlib import Path

import pytest

import symlink.codegen as codegen
from symlink.codegen import PRINTERS, printer
from symlink.scene import catalog_linkage


def test_every_printer_has_the_same_call_shape():
    shapes = {language: inspect.signature(printer(language).export_files) for language in PRINTERS}
    assert len({str(shape) for shape in shapes.values()}) == 1, shapes
    assert list(next(iter(shapes.values())).parameters) == ["linkage", "stem", "functions", "title", "regenerate"]


@pytest.mark.parametrize("language, names", [
    ("numpy", ["fb.py"]), ("c", ["fb.h", "fb.c"]), ("octave", ["fb_positions.m", "fb_speeds.m"]), ("latex", ["fb.tex"]),
])
def test_every_printer_writes_its_files(language, names):
    functions = [("positions", ["rocker"], "Rocker angle."), ("speeds", ["rocker", "rocker_speed"], "Its speed.")]
    files = printer(language).export_files(catalog_linkage("fourbar"), "fb", functions, "Four-bar.", "make")
    assert list(files) == names and all(text.endswith("\n") for text in files.values())


def test_an_unknown_language_is_refused_with_the_choices():
    with pytest.raises(ValueError, match="unknown export format 'fortran'; choose one of numpy, c, octave, latex"):
        printer("fortran")


def test_the_package_imports_nothing_of_symlink():
    tree = ast.parse(inspect.getsource(codegen))
    imported = [n for n in ast.walk(tree) if isinstance(n, (ast.Import, ast.ImportFrom))]
    assert all(isinstance(n, ast.Import) or not n.level for n in imported)
    root = Path(codegen.__file__).resolve().parent.parent.parent
    fresh = subprocess.run([sys.executable, "-c", "import sys, symlink.codegen; "
                            "print(sorted(m for m in sys.modules if m.startswith('symlink.codegen.')))"],
                           capture_output=True, text=True, check=True, cwd=root)
    assert fresh.stdout.strip() == "[]"
