"""The table of printers: every language's module, with the same call shape, imported on first use; hostile
names never reach any printer's output as code."""
import ast
import inspect
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

import symlink.codegen as codegen
from symlink.codegen import PRINTERS, printer
from symlink.codegen.javascript import js_string
from symlink.codegen.numpy import load_numpy_module
from symlink.symbolic.linkage import Linkage
from symlink.symbolic.loops import Loop
from symlink.io.scene import catalog_linkage
from symlink.symbolic.vectors import Vector, coordinates, lengths


def test_every_printer_has_the_same_call_shape():
    shapes = {language: inspect.signature(printer(language).export_files) for language in PRINTERS}
    assert len({str(shape) for shape in shapes.values()}) == 1, shapes
    assert list(next(iter(shapes.values())).parameters) == ["linkage", "stem", "functions", "title", "regenerate", "form"]


@pytest.mark.parametrize("language, names", [
    ("numpy", ["fb.py"]), ("c", ["fb.h", "fb.c"]), ("octave", ["fb_positions.m", "fb_speeds.m"]),
    ("javascript", ["fb.js"]), ("latex", ["fb.tex"]),
])
def test_every_printer_writes_its_files(language, names):
    functions = [("positions", ["rocker"], "Rocker angle."), ("speeds", ["rocker", "rocker_speed"], "Its speed.")]
    files = printer(language).export_files(catalog_linkage("fourbar"), "fb", functions, "Four-bar.", "make")
    assert list(files) == names and all(text.endswith("\n") for text in files.values())


def test_an_unknown_language_is_refused_with_the_choices():
    with pytest.raises(ValueError, match="unknown export format 'fortran'; choose one of numpy, c, octave, javascript, latex"):
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


# --- hostile names: refused where the linkage is defined, or harmless in every printer's output ---------

HOSTILE = ['x"""', "x'", "a\nb", "x*/", "/*x", "%x", "a%b", "a\\b", "x\\", "th\u0435ta", "\u03b8", "\uff41",
           "lambda", "end", "int", "function", "endfunction", "__import__", "", "1x", "a;b", "x\x00", "x\u2028y",
           "$x$", "{x}", "x#y", "\u00e9", "numpy", "check", "shape", "cse_1", "branch_x", "symlink_x", "w_1",
           "x y", "x-y", "x  y", " x", "x" * 200]
#: Plain names that reach generated code: seed 001's q, names that look like keywords, Greek letters for LaTeX.
PLAIN = ["q", "end1", "Inf_x", "alpha", "x__y", "If", "lambda_"]
PLACES = ["linkage", "loop", "vector", "coordinate", "length", "point", "role", "extra"]


def _linkage(place: str, name: str):
    """The four-bar with ``name`` at one ``place``; everything else plainly named."""
    named = {p: default for p, default in zip(PLACES, ["four bar", "ABCD", "AB", "theta", "a", "C", "rocker", "gap"])}
    named[place] = name
    theta = sp.Symbol(named["coordinate"], real=True)
    beta, phi = coordinates("beta phi")
    a = sp.Symbol(named["length"], positive=True)
    b, c, d = lengths("b c d")
    AB, BC = Vector(a, theta, named["vector"]), Vector(b, beta, "BC")
    loop = Loop(Vector(d, 0, "AD") + Vector(c, phi, "DC") - BC - AB, name=named["loop"])
    return Linkage(named["linkage"], [loop], inputs=[theta], unknowns=[beta, phi],
                   points={"B": AB.as_sum(), named["point"]: AB + BC}, roles={"crank": theta, named["role"]: phi},
                   extras={named["extra"]: beta - phi}), named


def _numpy_module_is_safe(linkage, named, files):
    tree = ast.parse(files["h.py"])
    kinds = [type(node).__name__ for node in tree.body]
    assert kinds[:4] == ["Expr", "Import", "Assign", "Assign"] and set(kinds[4:]) == {"FunctionDef"}, kinds
    namespace = load_numpy_module(files["h.py"])
    values = {named["coordinate"]: [0.0, 0.5], named["length"]: 20.0, "b": 66.0, "c": 56.0, "d": 80.0}
    result = namespace["positions"](**values)
    # The seed 003 four-bar at theta = 0, branch +1: phi = 110.74 deg (its table).
    assert round(float(np.degrees(result[named["role"]][0])), 2) == 110.74
    assert result["assembled"].all()


def _c_is_safe(files, folder):
    for file, text in files.items():
        (folder / file).write_text(text)
    compiler = shutil.which("gcc") or shutil.which("cc")
    if compiler:
        checked = subprocess.run([compiler, "-std=c99", "-Wall", "-Werror", "-fsyntax-only", str(folder / "h.c")],
                                 capture_output=True, text=True, check=False, cwd=folder)
        assert checked.returncode == 0, checked.stderr
    for text in files.values():  # a comment never ends early: every "*/" closes a comment that "/*" opened
        assert text.count("/*") == text.count("*/")


def _octave_is_safe(files):
    for file, text in files.items():
        lines = text.splitlines()
        assert lines[0].startswith("function [") and lines[-1] == "end", file
        assert all(line.isprintable() and "\t" not in line for line in lines), file
        help_block = lines[1:lines.index("%") + 1]
        assert help_block and all(line.startswith("%") for line in help_block), file


def _javascript_is_safe(linkage, files):
    """One expression statement (the UMD wrapper) registering the solver under the name as a JSON string;
    every comment closed; names only in strings or as plain identifiers (run under Node in test_javascript)."""
    text = files["h.js"]
    assert text.startswith("(function (root, factory) {\n") and text.endswith("\n});\n")
    assert f"{{[{js_string(linkage.name)}]: solver}}" in text
    assert text.count("/*") == text.count("*/") and "</" not in text and "<!" not in text
    assert all(line.isprintable() for line in text.splitlines())


def _latex_is_safe(files):
    text = files["h.tex"]
    assert text.isprintable() or all(line.isprintable() for line in text.splitlines())
    assert re.search(r"(?<!\\)%", text) is None  # no bare % comments out the rest of a line
    assert text.count("{") - text.count("\\{") == text.count("}") - text.count("\\}")


@pytest.mark.parametrize("place", PLACES)
@pytest.mark.parametrize("name", HOSTILE + PLAIN, ids=repr)
def test_a_name_is_refused_where_it_is_defined_or_harmless_in_every_printer(place, name, tmp_path):
    try:
        linkage, named = _linkage(place, name)
    except ValueError as error:
        assert repr(name) in str(error) or repr(name[:20])[:-1] in str(error), str(error)
        assert "\n" not in str(error)
        assert name not in PLAIN, f"the plain name {name!r} is refused as the {place}"
        return
    functions = [("positions", [named["role"], f"{named['point']}_x", named["extra"]], "Positions.")]
    files = {language: printer(language).export_files(linkage, "h", functions, f"{linkage.name} solver.", "make")
             for language in PRINTERS}
    _numpy_module_is_safe(linkage, named, files["numpy"])
    _c_is_safe(files["c"], tmp_path)
    _octave_is_safe(files["octave"])
    _javascript_is_safe(linkage, files["javascript"])
    _latex_is_safe(files["latex"])
